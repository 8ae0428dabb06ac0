/*
 * cmd_vision.c - analyze visibility FIG TARGET: where a target lies in a
 * manikin's sight (interact/visibility.h) and how much of it its eyes see.
 *
 * The eye is the cyclopean eye and the line of sight the mean one, as an
 * eye view's (pose/eyeview.h). A segment's share seen comes from two id
 * maps rendered from the eye, aimed at the segment's bounding sphere: the
 * segment alone, then every figure; a point's (or a site's) from the ray
 * from the eye to it (pick.h), the first thing it hits naming the
 * occluder. The manikin's head and eyeballs, which the eye sits in, hide
 * nothing.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/daemon.h"
#include "daemon/words.h"
#include "interact/obstruct.h"
#include "interact/visibility.h"
#include "pose/eyeview.h"

#define VIS_MAX_SEGMENTS 1024  /* segments of a figure the maps can leave out */
#define VIS_RAY_SKIPS 32       /* parts a point's ray may pass through (the eye's own) */
#define VIS_SURFACE 1e-6       /* m: a hit this near the point is the point's own surface */

/* what TARGET names: a point (a site's too), or a segment of a figure */
struct target {
	int fig, seg;  /* the figure and segment named; seg -1 for a point */
	int site_seg;  /* a site's segment (seen when the ray reaches it), else -1 */
	double p[3];   /* the point; for a segment its bounding sphere's centre */
	double radius; /* a segment's bounding sphere */
};

/* X,Y,Z | FIG.SEG | FIG.SEG.SITE: 0, or -1 with the error set */
static int
read_target(struct cmd_ctx *c, const char *w, struct target *t)
{
	*t = (struct target){ .fig = -1, .seg = -1, .site_seg = -1 };
	if (strchr(w, ','))
		return words_list(w, UNIT_LENGTH, 3, t->p) < 0
			       ? cmd_fail(c, "bad-number", "a point: X,Y,Z (three lengths)")
			       : 0;
	const char *dot = strchr(w, '.');
	char fig[MODEL_NAME_MAX];
	if (!dot || dot == w || (size_t)(dot - w) >= sizeof fig || !dot[1])
		return cmd_fail(c, "bad-argument", "TARGET: X,Y,Z, FIG.SEG or FIG.SEG.SITE, not '%.60s'",
				w);
	memcpy(fig, w, (size_t)(dot - w));
	fig[dot - w] = '\0';
	if ((t->fig = cmd_figure(c, fig)) < 0)
		return -1;
	const struct env_figure *f = &c->d->env.fig[t->fig];
	const char *rest = dot + 1;
	if (strchr(rest, '.')) { /* a site */
		int s = model_find_site(f->model, rest);
		if (s < 0)
			return cmd_fail(c, "not-found", "%s has no site '%.60s'", f->name, rest);
		memcpy(t->p, f->state->site_xf[s].p, sizeof t->p);
		t->site_seg = f->model->site_seg[s];
		return 0;
	}
	if ((t->seg = model_find_segment(f->model, rest)) < 0)
		return cmd_fail(c, "not-found", "%s has no segment '%.60s'", f->name, rest);
	const struct pick_model *pm = daemon_pick_model(c->d, t->fig);
	if (!pm)
		return cmd_fail(c, "internal", "out of memory");
	const double *lo = &pm->seg_lo[3 * t->seg], *hi = &pm->seg_hi[3 * t->seg];
	if (pm->seg_npart[t->seg] == 0 || !(lo[0] <= hi[0]))
		return cmd_fail(c, "bad-argument", "%s.%s has no geometry to see", f->name, rest);
	/* the bounding box's centre and half diagonal, in the world */
	double mid[3], h2 = 0;
	for (int k = 0; k < 3; k++) {
		mid[k] = 0.5 * (lo[k] + hi[k]);
		h2 += 0.25 * (hi[k] - lo[k]) * (hi[k] - lo[k]);
	}
	xform_apply(&f->state->seg_xf[t->seg], mid, t->p);
	t->radius = sqrt(h2);
	return 0;
}

/* the eyes' range about the head from the eye joints (yaw = eye_l's abduction) */
static int
eye_limits(const struct model *m, struct vis_limits *lim, int *head_seg)
{
	int jl = model_find_joint(m, "eye_l"), jr = model_find_joint(m, "eye_r");
	if (jl < 0 || jr < 0 || m->jnt_ndof[jl] != 2 || m->jnt_ndof[jr] != 2)
		return -1;
	*lim = (struct vis_limits){ -M_PI, M_PI, -M_PI / 2, M_PI / 2 };
	for (int e = 0; e < 2; e++) {
		int d0 = m->jnt_dof0[e ? jr : jl];
		for (int k = 0; k < 2; k++) {
			/* yaw: about y, towards +x for the left eye, mirrored for the right;
			 * pitch: about -x, up */
			double f = k == 0 ? m->dof_sign[d0] * (e ? -1 : 1) : -m->dof_sign[d0 + 1];
			double lo = m->dof_lo[d0 + k], hi = m->dof_hi[d0 + k];
			double a = f > 0 ? lo : -hi, b = f > 0 ? hi : -lo;
			double *l = k == 0 ? &lim->yaw_lo : &lim->pitch_lo, *h = l + 1;
			*l = fmax(*l, a);
			*h = fmin(*h, b);
		}
	}
	*head_seg = m->site_seg[m->jnt_site_from[jl]];
	return 0;
}

/* the manikin's parts the eye sits in: its eyeballs and the head they hang from */
static int
own_parts(const struct model *m, const struct state *s, const struct target *t, int is_fig,
	  unsigned char *skip)
{
	int sl = model_find_segment(m, "eyeball_l"), sr = model_find_segment(m, "eyeball_r");
	unsigned char r[VIS_MAX_SEGMENTS];
	if (sl < 0 || sr < 0 || obstruct_own_parts(m, s, sl, skip, VIS_MAX_SEGMENTS) < 0 ||
	    obstruct_own_parts(m, s, sr, r, VIS_MAX_SEGMENTS) < 0)
		return -1;
	for (int k = 0; k < m->nseg; k++)
		skip[k] = (skip[k] || r[k]) && !(is_fig && k == t->seg);
	return 0;
}

static void
occluder_name(const struct env *e, uint32_t id, char *dest, size_t len)
{
	int fig = VIEW_ID_FIG(id), seg = VIEW_ID_SEG(id);
	if (fig < 0 || fig >= ENV_MAX_FIGURES || !e->fig[fig].gen || seg < 0 ||
	    seg >= e->fig[fig].model->nseg)
		snprintf(dest, len, "?");
	else
		snprintf(dest, len, "%s.%s", e->fig[fig].name, e->fig[fig].model->seg_name[seg]);
}

/* a point's ray from the eye: seen (1) or hidden (0, *occ the first thing hit); -1 no memory */
static int
point_seen(struct cmd_ctx *c, int fig, const unsigned char *own, const struct target *t,
	   const double eye[3], uint32_t *occ)
{
	double w[3] = { t->p[0] - eye[0], t->p[1] - eye[1], t->p[2] - eye[2] };
	double n = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]), tmin = 0;
	struct ray r = { { eye[0], eye[1], eye[2] }, { w[0] / n, w[1] / n, w[2] / n } };
	for (int k = 0; k < VIS_RAY_SKIPS; k++) {
		struct pick_hit h;
		int hf, hit = daemon_pick(c->d, &r, tmin, -1, &h, &hf);
		if (hit < 0)
			return -1;
		if (!hit || h.distance >= n - VIS_SURFACE)
			return 1;
		if ((hf == fig && own[h.segment]) || (hf == t->fig && h.segment == t->site_seg)) {
			tmin = h.distance + VIS_SURFACE; /* through the eye's own parts, the site's */
			continue;
		}
		*occ = view_id(hf, h.segment);
		return 0;
	}
	return 1;
}

static json_t *
turn_json(double yaw, double pitch)
{
	return json_pack("{sfsf}", "yaw", yaw, "pitch", pitch);
}

int
cmd_analyze_visibility(struct cmd_ctx *c)
{
	struct daemon *d = c->d;
	struct env *e = &d->env;
	int fig = cmd_figure(c, c->argv[0]), head;
	if (fig < 0)
		return -1;
	const struct env_figure *f = &e->fig[fig];
	struct vis_limits lim;
	double eye[3], dir[3];
	if (eye_limits(f->model, &lim, &head) < 0 || eyeview_camera(e, fig, ENV_EYES_BOTH, eye, dir) < 0)
		return cmd_fail(c, "bad-argument", "%s has no eyes (joints eye_l, eye_r; sites "
				"eyeball_l.gaze, eyeball_r.gaze)", f->name);
	if (f->model->nseg > VIS_MAX_SEGMENTS)
		return cmd_fail(c, "limit", "%s has more than %d segments", f->name, VIS_MAX_SEGMENTS);
	struct target t;
	if (read_target(c, c->argv[1], &t) < 0)
		return -1;
	if (t.seg >= 0 && e->fig[t.fig].model->nseg > VIS_MAX_SEGMENTS)
		return cmd_fail(c, "limit", "%s has more than %d segments", e->fig[t.fig].name,
				VIS_MAX_SEGMENTS);
	struct vis_fixation fx;
	if (vis_fixate(eye, dir, f->state->seg_xf[head].r, &lim, t.p, &fx) < 0)
		return cmd_fail(c, "bad-argument", "the target is at the eye");
	unsigned char own[VIS_MAX_SEGMENTS];
	if (own_parts(f->model, f->state, &t, t.fig == fig, own) < 0)
		return cmd_fail(c, "bad-argument", "%s has no eyeballs", f->name);

	struct vis_coverage cov = { .fraction = 1 };
	struct camera cam;
	if (t.seg < 0) {
		uint32_t occ = 0;
		int seen = point_seen(c, fig, own, &t, eye, &occ);
		if (seen < 0)
			return cmd_fail(c, "internal", "out of memory");
		if (!seen)
			cov = (struct vis_coverage){ .fraction = 0, .nocc = 1,
						     .occ = { { .id = occ, .fraction = 1 } } };
	} else {
		if (vis_map_camera(&cam, eye, t.p, t.radius) < 0)
			return cmd_fail(c, "bad-argument", "%s's eye is within %s's bounds (%.3g m "
					"about its centre): too near to see it whole", f->name,
					c->argv[1], t.radius);
		if (!d->id_map)
			return cmd_fail(c, "internal", "this daemon cannot render");
		unsigned char only[VIS_MAX_SEGMENTS];
		const struct model *tm = e->fig[t.fig].model;
		for (int k = 0; k < tm->nseg; k++)
			only[k] = k != t.seg;
		char err[256];
		const struct hemi_map *alone = d->id_map(d, &cam, 0, t.fig, t.fig, only, err, sizeof err);
		const struct hemi_map *all = alone ? d->id_map(d, &cam, 1, -1, fig, own, err, sizeof err)
						   : NULL;
		if (!all)
			return cmd_fail(c, "internal", "%s", err);
		vis_coverage(alone, all, view_id(t.fig, t.seg), &cov);
		if (!cov.pixels)
			return cmd_fail(c, "bad-argument", "%s shows no surface towards the eye", c->argv[1]);
	}

	double cones[ENV_VIEW_CONES];
	int ncones = eyeview_figure_cones(e, fig, cones), cone = vis_cone(fx.angle, cones, ncones);
	json_t *r = c->result, *occ = json_array();
	for (int k = 0; k < cov.nocc; k++) {
		char name[2 * MODEL_NAME_MAX + 2];
		occluder_name(e, cov.occ[k].id, name, sizeof name);
		json_array_append_new(occ, json_pack("{sssf}", "name", name, "fraction",
						     cov.occ[k].fraction));
	}
	json_object_set_new(r, "figure", json_string(f->name));
	json_object_set_new(r, "target", json_string(c->argv[1]));
	json_object_set_new(r, "fraction", json_real(cov.fraction));
	json_object_set_new(r, "angle", json_real(fx.angle));
	json_object_set_new(r, "cone", cone >= 0 ? json_real(cones[cone]) : json_null());
	json_object_set_new(r, "eye_rotation", turn_json(fx.eye_yaw, fx.eye_pitch));
	json_object_set_new(r, "head_rotation", turn_json(fx.head_yaw, fx.head_pitch));
	json_object_set_new(r, "occluders", occ);
	json_object_set_new(r, "hidden_by_others", json_real(cov.others));
	json_object_set_new(r, "eye", cmd_vec(eye, 3));
	json_object_set_new(r, "point", cmd_vec(t.p, 3));
	if (t.seg >= 0) { /* the map it was counted on, for its resolution */
		double aim[3];
		view_camera_vrp(&cam, aim);
		json_object_set_new(r, "map", json_pack("{sisfsosisisf}", "size", HEMI_N, "fov",
							cam.fovy * 180 / M_PI, "aim", cmd_vec(aim, 3),
							"pixels", cov.pixels, "edge_pixels",
							cov.edge_pixels, "resolution", cov.edge_share));
	}
	return 0;
}
