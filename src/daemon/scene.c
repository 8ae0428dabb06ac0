/* scene.c - the views' pictures: drawn, written to files and the framebuffer, sent as events */
#include "daemon/scene.h"

#include "interact/menu_draw.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/assess_live.h"
#include "daemon/loads_json.h"
#include "daemon/loads_live.h"
#include "daemon/family.h"
#include "daemon/tint.h"
#include "draw/pack.h"
#include "draw/sink.h"
#include "draw/tiles.h"
#include "pose/eyeview.h"
#include "pose/load_balance.h"
#include "interact/menu_draw.h"

void
scene_init(struct scene *sc, const char *frames_dir)
{
	memset(sc, 0, sizeof *sc);
	sc->frames_dir = frames_dir;
	sc->dirty = 1;
}

/* the renderer and draw list, made when first needed; 0, or -1 with err */
static int
scene_ready(struct scene *sc, char *err, size_t errlen)
{
	if (sc->r)
		return 0;
	if (sc->failed) {
		snprintf(err, errlen, "the renderer could not start");
		return -1;
	}
	struct render_def rd = render_default_def();
	rd.max_w = VIEW_MAX_W;
	rd.max_h = VIEW_MAX_H;
	sc->r = render_make(&rd, err, errlen);
	sc->dl = sc->r ? view_drawlist_make() : NULL;
	sc->hemi = sc->r ? malloc(sizeof *sc->hemi) : NULL;
	for (int k = 0; k < 2; k++)
		sc->idmap[k] = sc->r ? malloc(sizeof *sc->idmap[k]) : NULL;
	if (!sc->r || !sc->dl || !sc->hemi || !sc->idmap[0] || !sc->idmap[1]) {
		if (sc->r)
			snprintf(err, errlen, "out of memory");
		view_drawlist_free(sc->dl);
		free(sc->hemi);
		for (int k = 0; k < 2; k++) {
			free(sc->idmap[k]);
			sc->idmap[k] = NULL;
		}
		sc->dl = NULL;
		sc->hemi = NULL;
		fprintf(stderr, "postured: no pictures: %s\n", err);
		render_free(sc->r);
		sc->r = NULL;
		sc->failed = 1;
		return -1;
	}
	return 0;
}

/*
 * The manipulation icons of §3.6 in the mode's view: G as a labelled
 * frame, and what the chord chose (the arrow of an axis, the arrows of a
 * plane, the wheel with its spoke), drawn as soon as the chord changes;
 * the pointer on top.
 */
static void
scene_add_manip(struct drawlist *dl, const struct interact *ia)
{
	if (ia->mode == INTERACT_JOINT) { /* the selected DOF's wheel with its limits (§3.8.1) */
		if (ia->jm.dof >= 0) {
			int dof = ia->model->jnt_dof0[ia->joint] + ia->jm.dof;
			if (view_add_joint_wheel(dl, ia->model, ia->state, dof, 0.2) < 0) {
				struct joint_dof_view dv;
				interact_dof_view(ia->model, ia->state, dof, &dv);
				view_add_translation_arrow(dl, dv.pivot, dv.axis, 0.4);
			}
		}
		view_add_pointer(dl, ia->px, ia->py);
		return;
	}
	struct manip_icon ic;
	manip_icon(&ia->m, &ic);
	view_add_frame_icon(dl, &ia->m.g, 0.25, 1);
	switch (ic.state) {
	case MANIP_LINEAR:
		view_add_translation_arrow(dl, ic.origin, ic.axis, 0.6);
		break;
	case MANIP_PLANAR:
		view_add_translation_arrow(dl, ic.origin, ic.u, 0.6);
		view_add_translation_arrow(dl, ic.origin, ic.v, 0.6);
		break;
	case MANIP_ROTATE: {
		struct view_wheel w = { .radius = 0.3 };
		memcpy(w.center, ic.origin, sizeof w.center);
		memcpy(w.axis, ic.axis, sizeof w.axis);
		memcpy(w.spoke, ic.has_spokes ? ic.spoke : ic.u, sizeof w.spoke);
		view_add_rotation_wheel(dl, &w);
		break;
	}
	default:
		break;
	}
	view_add_pointer(dl, ia->px, ia->py);
}

/* figure i's meshes into the renderer when it is new to it */
static void
figure_meshes(struct scene *sc, const struct env_figure *f, int i)
{
	if (sc->mesh_gen[i] == f->gen)
		return;
	char err[256];
	int base = render_add_model(sc->r, f->model, err, sizeof err);
	if (base < 0)
		fprintf(stderr, "postured: figure %s drawn without its meshes: %s\n", f->name, err);
	sc->mesh_base[i] = base < 0 ? 0 : base;
	sc->mesh_gen[i] = f->gen;
}

const struct hemi_map *
scene_hemicube(struct scene *sc, struct daemon *d, const double origin[3], const double dir[3],
	       int skip, const unsigned char *skip_seg, char *err, size_t errlen)
{
	struct env *e = &d->env;
	struct camera cam;
	if (scene_ready(sc, err, errlen) < 0)
		return NULL;
	if (hemi_camera(&cam, origin, dir) < 0) {
		snprintf(err, errlen, "no direction");
		return NULL;
	}
	view_begin(sc->dl, &cam, HEMI_N, HEMI_N);
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		struct env_figure *f = &e->fig[i];
		/* a ghost hides nothing: it is drawn see-through */
		if (!f->gen || (i == skip && !skip_seg) || daemon_is_ghost(d, i))
			continue;
		figure_meshes(sc, f, i);
		view_add_figure_ids_except(sc->dl, f->model, f->state, sc->mesh_base[i], i,
					   i == skip ? skip_seg : NULL);
	}
	if (render_hemicube(sc->r, sc->dl, sc->hemi) < 0) {
		snprintf(err, errlen, "render_hemicube failed");
		return NULL;
	}
	return sc->hemi;
}

const struct hemi_map *
scene_id_map(struct scene *sc, struct daemon *d, const struct camera *cam, int slot, int only,
	     int skip, const unsigned char *skip_seg, char *err, size_t errlen)
{
	struct env *e = &d->env;
	if (scene_ready(sc, err, errlen) < 0)
		return NULL;
	view_begin(sc->dl, cam, HEMI_N, HEMI_N);
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		struct env_figure *f = &e->fig[i];
		if (!f->gen || (only >= 0 && i != only) || daemon_is_ghost(d, i))
			continue;
		figure_meshes(sc, f, i);
		view_add_figure_ids_except(sc->dl, f->model, f->state, sc->mesh_base[i], i,
					   i == skip ? skip_seg : NULL);
	}
	if (sc->dl->dropped) {
		snprintf(err, errlen, "the scene has more than %d geometry parts", VIEW_MAX_INST);
		return NULL;
	}
	if (render_hemicube(sc->r, sc->dl, sc->idmap[slot & 1]) < 0) {
		snprintf(err, errlen, "render_hemicube failed");
		return NULL;
	}
	return sc->idmap[slot & 1];
}

/*
 * What a prompt would pick under the pointer: its segment's bounding box
 * as the picking sees it, drawn through everything (x-ray) so it shows
 * where the pointer is even behind another part.
 */
static void
add_hover(struct scene *sc, struct daemon *d)
{
	int fig = d->hover_fig, seg = d->hover_seg;
	if (fig < 0 || fig >= ENV_MAX_FIGURES || !d->env.fig[fig].gen)
		return;
	const struct pick_model *pm = daemon_pick_model(d, fig);
	if (!pm || seg < 0 || seg >= pm->nseg)
		return;
	static const uint8_t yellow[4] = { 255, 220, 40, 255 };
	const double *lo = &pm->seg_lo[3 * seg], *hi = &pm->seg_hi[3 * seg];
	const struct xform *x = &d->env.fig[fig].state->seg_xf[seg];
	double c[8][3];
	for (int k = 0; k < 8; k++) {
		double p[3] = { k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2] };
		xform_apply(x, p, c[k]);
	}
	view_batch_begin(sc->dl, VIEW_LINES, VIEW_WORLD, 2, 1);
	for (int k = 0; k < 8; k++)
		for (int b = 1; b < 8; b <<= 1)
			if (!(k & b)) /* each edge once: from the corner with the bit clear */
				view_line(sc->dl, c[k], c[k | b], yellow);
}


/*
 * The kiosk's edit line in place of the status while something is typed:
 * "> " and the line (or "value: " and a value typed in a mode), the part
 * of it that fits the view's width. Returns the caret's column, or -1
 * when nothing is typed (dest untouched).
 */
static int
edit_line(struct daemon *d, int width, char *dest, size_t len)
{
	if (!d->kiosk)
		return -1;
	const struct editline *el = kiosk_line(d->kiosk);
	int value = kiosk_typing_value(d->kiosk);
	const struct prompt_arg *asking = d->prompt ? prompt_asking(d->prompt) : NULL;
	if (!editline_text(el)[0] && !value && !asking)
		return -1;
	/* a prompt shows the line so far and its question before what is typed */
	char ask[VIEW_TEXT_LEN];
	if (asking) { /* a long line shows its end: the words just given */
		const char *line = prompt_line(d->prompt);
		size_t l = strlen(line);
		snprintf(ask, sizeof ask, "%s%.60s  %.60s ", l > 60 ? "..." : "", l > 60 ? line + l - 57 : line,
			 asking->question);
	}
	const char *prompt = asking ? ask : value ? "value: " : "> ";
	int plen = (int)strlen(prompt);
	int cols = (width - 12) / VIEW_CHAR_PX - plen;
	if (cols > (int)len - plen - 1)
		cols = (int)len - plen - 1;
	struct editline_window w;
	kiosk_visible(d->kiosk, cols, &w);
	size_t n = strlen(prompt);
	if (n >= len)
		n = len - 1;
	memcpy(dest, prompt, n);
	/*
	 * The font has ASCII's glyphs: any other character is one '?', so that
	 * a column is a character and the caret stays under its own (the
	 * window counts characters, not bytes).
	 */
	for (size_t i = 0; i < w.len && n + 1 < len; i++) {
		unsigned char ch = (unsigned char)w.text[i];
		if (ch < 0x80)
			dest[n++] = (char)ch;
		else if ((ch & 0xc0) != 0x80) /* a lead byte: the character's one column */
			dest[n++] = '?';
	}
	dest[n] = '\0';
	return plen + w.cursor_col;
}

static int
in_layout(const struct env *e, int v)
{
	for (int i = 0; i < e->nlayout; i++)
		if (e->layout[i] == v)
			return 1;
	return 0;
}

/*
 * The message and status lines, width pixels wide, for view v: the edit
 * line in the kiosk's view (a prompt, a value), else the view's figures;
 * the operator's refusal, while there is one, over the daemon's message.
 */
static void
add_lines(struct scene *sc, struct daemon *d, int v, int width)
{
	const struct env_view *vw = &d->env.view[v];
	const struct interact *ia = d->interact;
	int manipulating = ia && ia->mode != INTERACT_NONE && ia->view == v;
	char status[VIEW_TEXT_LEN], who[80] = ""; /* who: room left for the frame's numbers */
	int kiosk = v == daemon_kiosk_view(d), caret = kiosk ? edit_line(d, width, status, sizeof status)
							  : -1;
	/* the kiosk's figure, and where its size comes from, after the view's name */
	int fig = daemon_kiosk_figure(d);
	/* a human's RULA and REBA grand scores now (the font is ASCII's), its low back's
	 * compression and the weakest joint's percent capable */
	char scores[40] = "", loads[48] = "";
	if (fig >= 0) {
		memcpy(who, "   ", 3);
		family_describe(&d->env, fig, who + 3, sizeof who - 3);
		const struct assess_live_fig *a = assess_live_of(d, fig);
		if (a)
			snprintf(scores, sizeof scores, "   RULA %d, REBA %d", a->res[ASSESS_RULA].score,
				 a->res[ASSESS_REBA].score);
		if (d->env.fig[fig].is_human)
			loads_json_status(loads_live_of(d, fig), loads, sizeof loads);
	}
	/* a line longer than the status's room loses its end: the timings, then the frame */
	int n = 0;
	if (caret < 0 && sc->replaying) /* the live timings are not the replay's: pictures stay alike */
		n = snprintf(status, sizeof status, "%s%s%s%s   frame %llu   replay", vw->name, who,
			     scores, loads, (unsigned long long)d->stats.frame);
	else if (caret < 0)
		n = snprintf(status, sizeof status,
			     "%s%s%s%s   frame %llu   %.0f fps   solver %.0f us   drawing %.1f ms",
			     vw->name, who, scores, loads, (unsigned long long)d->stats.frame, d->stats.fps,
			     d->stats.ik_us, d->stats.draw_us / 1000);
	if (n < 0)
		status[0] = '\0';
	if (kiosk)
		snprintf(d->status_line, sizeof d->status_line, "%s", status);
	view_add_status(sc->dl, status, manipulating && ia->message[0] ? ia->message : d->message,
			caret);
}

/* a size for a label: whole units from 100 up, else three significant digits */
static void
size_text(char *dest, size_t len, double x, const char *unit)
{
	snprintf(dest, len, x >= 100 ? "%.0f %s" : "%.3g %s", x, unit);
}

/* the loads on figure fig as arrows at their sites, each labelled with its size */
static void
add_loads(struct drawlist *dl, const struct env *e, int fig)
{
	const struct state *s = e->fig[fig].state;
	for (int k = 0; k < ENV_MAX_LOADS; k++) {
		const struct env_load *l = &e->load[k];
		if (!l->gen || l->fig != fig)
			continue;
		char label[64], a[28], b[28];
		double fn = sqrt(mathx_dot(l->force, l->force)), tn = sqrt(mathx_dot(l->torque, l->torque));
		if (l->mass > 0) {
			size_text(label, sizeof label, l->mass, "kg");
		} else {
			size_text(a, sizeof a, fn, "N");
			size_text(b, sizeof b, tn, "N m");
			snprintf(label, sizeof label, "%s%s%s", fn > 0 ? a : "", fn > 0 && tn > 0 ? ", " : "",
				 tn > 0 ? b : "");
		}
		view_add_load(dl, s->site_xf[l->site].p, l->force, l->torque, label);
	}
}

/* the manikins' sight as cones from their eyes, where the eyes are now (set view sight=) */
static void
add_sight(struct drawlist *dl, const struct daemon *d, const struct env_view *vw)
{
	const struct env *e = &d->env;
	if (!vw->sight[0])
		return;
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		double eye[3], dir[3], deg[ENV_VIEW_CONES];
		if (!eyeview_draws_sight(e, vw, i) || daemon_is_ghost(d, i) ||
		    eyeview_camera(e, i, ENV_EYES_BOTH, eye, dir) < 0)
			continue;
		int n = eyeview_figure_cones(e, i, deg);
		view_add_sight_cones(dl, eye, dir, deg, n, vw->sight_len);
	}
}

static const struct envelope_mesh no_mesh; /* an emptied slot's */

/* envelope mesh m into the renderer under *id (an id plus 1; 0: a new one); 0, or -1 */
static int
envelope_upload(struct scene *sc, int *id, const struct envelope_mesh *m, const char *name)
{
	char err[256];
	/* the frame packs every instance into one buffer (pack.h): a surface taking more than
	 * half of it would push the figures out, so it is not drawn */
	if (m->nvert > PACK_MAX_VERT / 2 || 3L * m->ntri > PACK_MAX_IDX / 2) {
		fprintf(stderr, "postured: envelope %s not drawn: %d vertices, %d triangles, more "
			"than a frame holds (a coarser resolution draws)\n", name, m->nvert, m->ntri);
		m = &no_mesh;
	}
	int got = render_set_mesh(sc->r, *id - 1, m->vert, m->normal, m->nvert, m->tri, m->ntri, err,
				  sizeof err);
	if (got < 0) {
		fprintf(stderr, "postured: envelope %s not drawn: %s\n", name, err);
		return -1;
	}
	*id = got + 1;
	return 0;
}

/*
 * The kept envelopes, see-through (alpha < 1: drawn after the opaque
 * figures, their front faces alone), the comfort zone inside in its own
 * colour. A surface is handed to the renderer once, when it is new; a
 * slot emptied empties its meshes, which keep their ids for the next.
 */
static void
add_envelopes(struct scene *sc, const struct daemon *d)
{
	static const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
	const struct envelopes *s = d->envelopes;
	for (int k = 0; k < ENVELOPES_MAX; k++) {
		const struct envelope_entry *x = s && s->slot[k].used ? &s->slot[k] : NULL;
		int *id = sc->envelope_mesh[k];
		if (!x) {
			if (sc->envelope_serial[k])
				for (int i = 0; i < 2; i++)
					if (id[i])
						envelope_upload(sc, &id[i], &no_mesh, "");
			sc->envelope_serial[k] = 0;
			continue;
		}
		if (sc->envelope_serial[k] != x->serial) {
			int bad = envelope_upload(sc, &id[0], &x->e.reach, x->name);
			if (!bad && (x->e.comfort.ntri || id[1]))
				bad = envelope_upload(sc, &id[1], &x->e.comfort, x->name);
			sc->envelope_serial[k] = x->serial; /* a failure is said once, not each frame */
			for (int i = 0; bad && i < 2; i++) /* nothing drawn of it, ids kept */
				if (id[i])
					envelope_upload(sc, &id[i], &no_mesh, x->name);
		}
		if (x->hidden || !id[0])
			continue;
		if (x->e.comfort.ntri && id[1])
			view_add_instance(sc->dl, id[1] - 1, identity, ENVELOPE_COMFORT_RGBA, 0);
		view_add_instance(sc->dl, id[0] - 1, identity, ENVELOPE_REACH_RGBA, 0);
	}
	sc->envelopes_seen = s ? s->serial : 0;
}

int
scene_draw(struct scene *sc, struct daemon *d, int v, const struct frame **dest, char *err,
	   size_t errlen)
{
	struct env *e = &d->env;
	eyeview_follow(e, &e->view[v]); /* an eye view where the eyes are now */
	const struct env_view *vw = &e->view[v];
	if (scene_ready(sc, err, errlen) < 0)
		return -1;
	uint64_t t0 = sc->wall_us ? sc->wall_us() : 0, c0 = sc->cpu_us ? sc->cpu_us() : 0;
	struct camera cam;
	view_camera_of_view(vw, &cam);
	view_begin(sc->dl, &cam, vw->width, vw->height);
	const struct interact *ia = d->interact;
	int manipulating = ia && ia->mode != INTERACT_NONE && ia->view == v;
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		struct env_figure *f = &e->fig[i];
		if (!f->gen)
			continue;
		figure_meshes(sc, f, i);
		if (daemon_is_ghost(d, i)) { /* a family overlaid: the others as ghosts, no icons */
			view_add_figure_ghost(sc->dl, f->model, f->state, sc->mesh_base[i],
					      FAMILY_GHOST_ALPHA);
			continue;
		}
		/* a tinted view: a human's parts in their part scores' colours (tint.h) */
		const float *tinted = vw->tint ? tint_figure(&sc->tint, d, i, vw->tint) : NULL;
		if (tinted)
			view_add_figure_rgba(sc->dl, f->model, f->state, sc->mesh_base[i], tinted);
		else
			view_add_figure(sc->dl, f->model, f->state, sc->mesh_base[i]);
		if (!vw->loads_hidden) /* what was put on the body, where it acts */
			add_loads(sc->dl, e, i);
		int dragged = manipulating && ia->mode == INTERACT_DRAG && ia->fig == i;
		if (!vw->icons && !dragged)
			continue;
		if (f->is_human && vw->icons) {
			double com[3]; /* with the weights it carries */
			load_balance_com(e, i, com);
			view_add_balance(sc->dl, f->model, f->state, com);
		}
		env_sync_solver(e, i);
		view_add_goals(sc->dl, f->ik, f->model, f->state);
	}
	add_envelopes(sc, d);
	if (vw->eyes[0]) /* the cones about the line of sight (eyeview.h) */
		view_add_cone_marks(sc->dl, vw->cones_deg, vw->ncones);
	add_sight(sc->dl, d, vw);
	if (manipulating)
		scene_add_manip(sc->dl, ia);
	add_hover(sc, d);
	tint_legend(sc->dl, vw->tint);
	/* the pop-up menu over everything, in the view it opened in */
	if (d->menu && d->menu_view == v && menu_is_open(d->menu)) {
		menu_layout(d->menu, &sc->menu_layout);
		menu_draw(sc->dl, &sc->menu_layout);
	}
	/* outside a mode the kiosk's pointer is drawn where it is (a mode draws its own) */
	if (!(ia && ia->mode != INTERACT_NONE) && d->pointer_view == v)
		view_add_pointer(sc->dl, d->pointer_x, d->pointer_y);
	/* a view on a layout's screen leaves its lines to the screen's band */
	if (!in_layout(e, v))
		add_lines(sc, d, v, vw->width);
	if (render_frame(sc->r, sc->dl, d->stats.frame, &sc->frame) < 0) {
		snprintf(err, errlen, "render_frame failed");
		return -1;
	}
	sc->frame.input_us = sc->input_us;
	sc->frame.seq = d->stats.frame;
	*dest = &sc->frame;
	if (sc->wall_us)
		sc->drawn_us += sc->wall_us() - t0;
	if (sc->cpu_us)
		sc->drawn_cpu_us += sc->cpu_us() - c0;
	return 0;
}

int
scene_draw_picture(struct scene *sc, struct daemon *d, const struct env_view *vw, int only,
		   const struct frame **dest, char *err, size_t errlen)
{
	struct env *e = &d->env;
	if (scene_ready(sc, err, errlen) < 0)
		return -1;
	struct camera cam;
	view_camera_of_view(vw, &cam);
	view_begin(sc->dl, &cam, vw->width, vw->height);
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		struct env_figure *f = &e->fig[i];
		/* one human among the objects: the others (a family's members, ghosts) left out */
		if (!f->gen || (only >= 0 && i != only && f->is_human) || daemon_is_ghost(d, i))
			continue;
		figure_meshes(sc, f, i);
		const float *tinted = vw->tint ? tint_figure(&sc->tint, d, i, vw->tint) : NULL;
		if (tinted)
			view_add_figure_rgba(sc->dl, f->model, f->state, sc->mesh_base[i], tinted);
		else
			view_add_figure(sc->dl, f->model, f->state, sc->mesh_base[i]);
	}
	tint_legend(sc->dl, vw->tint);
	if (render_frame(sc->r, sc->dl, d->stats.frame, &sc->frame) < 0) {
		snprintf(err, errlen, "render_frame failed");
		return -1;
	}
	sc->frame.input_us = 0;
	sc->frame.seq = d->stats.frame;
	*dest = &sc->frame;
	return 0;
}

/* the picture of a view as a frame event: its PNG (made on the files' thread) in base64 */
static void
frame_event(struct events *E, const char *view, const struct frame *f, const uint8_t *png,
	    size_t len)
{
	struct jbuf *j = events_begin(E, "frame", NULL);
	jbuf_key(j, "view", 0);
	jbuf_str(j, view);
	jbuf_key(j, "width", 0);
	jbuf_int(j, f->width);
	jbuf_key(j, "height", 0);
	jbuf_int(j, f->height);
	jbuf_key(j, "png", 0);
	jbuf_base64(j, png, len);
	jbuf_raw(j, "}");
	events_send(E, SUB_FRAME);
}

/* frame events' slots in the files' writer: after the views' files */
/* the files' writer's slot for the screen's picture, after a file and an event slot per view */
#define SCENE_SCREEN_SLOT (2 * ENV_MAX_VIEWS)
_Static_assert(SCENE_SCREEN_SLOT < FRAME_WRITER_SLOTS, "a file and an event slot per view, the screen");

/*
 * the writer *w, made when first needed at niceness nice; NULL when no
 * thread could be had (said once)
 */
static struct frame_writer *
scene_writer(struct scene *sc, struct frame_writer **w, int nice)
{
	char err[256];
	if (!*w && !sc->writer_failed && !(*w = frame_writer_make(nice, err, sizeof err))) {
		fprintf(stderr, "postured: pictures not written: %s\n", err);
		sc->writer_failed = 1;
	}
	return *w;
}

/* view v's picture to the screen's writer; the sink becomes the writer's on first use */
static void
scene_to_screen(struct scene *sc, const struct env_view *vw, const struct frame *f)
{
	char err[256];
	if (sc->screen_held)
		return;
	if (!sc->screen) {
		if (!scene_writer(sc, &sc->screen, 0))
			return;
		if (frame_writer_attach(sc->screen, 0, sc->fb, vw->width, vw->height, err,
					sizeof err) < 0) {
			fprintf(stderr, "postured: framebuffer: %s\n", err);
			sc->fb = NULL; /* closed by the writer */
			return;
		}
	}
	if (frame_writer_submit(sc->screen, 0, f, err, sizeof err) < 0)
		fprintf(stderr, "postured: framebuffer: %s\n", err);
}

/* view v's picture to the files' writer, its file (re)opened when new or renamed */
static void
scene_to_file(struct scene *sc, int v, const struct env_view *vw, const struct frame *f)
{
	char err[256];
	if (!scene_writer(sc, &sc->files, SCENE_FILES_NICE))
		return;
	if (strcmp(sc->png_name[v], vw->name)) {
		char path[4200];
		snprintf(path, sizeof path, "%s/%s.png", sc->frames_dir, vw->name);
		struct sink *s = sink_png_latest(path, err, sizeof err);
		sc->png_name[v][0] = '\0';
		if (!s || frame_writer_attach(sc->files, v, s, vw->width, vw->height, err,
					      sizeof err) < 0) {
			fprintf(stderr, "postured: frame file: %s\n", err);
			return;
		}
		snprintf(sc->png_name[v], sizeof sc->png_name[v], "%s", vw->name);
	}
	if (frame_writer_submit(sc->files, v, f, err, sizeof err) < 0)
		fprintf(stderr, "postured: frame file: %s\n", err);
}

/* view v's picture to be encoded on the files' thread, for a frame event once it is */
static void
scene_to_events(struct scene *sc, int v, const struct env_view *vw, const struct frame *f)
{
	char err[256];
	if (!scene_writer(sc, &sc->files, SCENE_FILES_NICE))
		return;
	if (!sc->relay[v]) {
		struct sink *s = sink_relay_open(err, sizeof err);
		if (!s || frame_writer_attach(sc->files, ENV_MAX_VIEWS + v, s, vw->width,
					      vw->height, err, sizeof err) < 0) {
			fprintf(stderr, "postured: frame events: %s\n", err);
			return;
		}
		sc->relay[v] = s; /* the writer's; it lives as long as the writer */
	}
	if (frame_writer_submit(sc->files, ENV_MAX_VIEWS + v, f, err, sizeof err) < 0)
		fprintf(stderr, "postured: frame events: %s\n", err);
	else
		sc->relay_pending[v] = 1;
}

/*
 * The screen's picture for a layout: made (and its gaps painted) when the
 * screen's size is new, not each frame.
 */
static int
screen_ready(struct scene *sc, int w, int h)
{
	if (sc->screen_rgba && sc->screen_w == w && sc->screen_h == h)
		return 0;
	uint8_t *p = malloc((size_t)w * (size_t)h * 4);
	if (!p)
		return -1;
	for (size_t i = 0; i < (size_t)w * (size_t)h; i++) { /* the gaps: the bands' dark blue */
		p[4 * i] = 20;
		p[4 * i + 1] = 24;
		p[4 * i + 2] = 32;
		p[4 * i + 3] = 255;
	}
	free(sc->screen_rgba);
	sc->screen_rgba = p;
	sc->screen_w = w;
	sc->screen_h = h;
	return 0;
}

/* view f's picture into its tile of the screen, row by row (cut to the tile) */
static void
screen_put(struct scene *sc, const struct tile *t, const struct frame *f)
{
	int w = f->width < t->w ? f->width : t->w, h = f->height < t->h ? f->height : t->h;
	for (int y = 0; y < h; y++)
		memcpy(sc->screen_rgba + 4 * ((size_t)(t->y + y) * (size_t)sc->screen_w + (size_t)t->x),
		       f->rgba + (size_t)y * (size_t)f->stride, 4 * (size_t)w);
}

/*
 * The screen's band: the kiosk's view's lines drawn across the whole
 * screen on an opaque ground, and put at the screen's bottom.
 */
static int
screen_band(struct scene *sc, struct daemon *d)
{
	int v = daemon_kiosk_view(d);
	if (v < 0)
		return -1;
	struct camera cam;
	view_camera_of_view(&d->env.view[v], &cam);
	view_begin(sc->dl, &cam, sc->screen_w, SCENE_BAND);
	static const uint8_t ground[4] = { 20, 24, 32, 255 };
	view_add_rect(sc->dl, 0, 0, sc->screen_w, SCENE_BAND, ground);
	add_lines(sc, d, v, sc->screen_w);
	if (render_frame(sc->r, sc->dl, d->stats.frame, &sc->frame) < 0)
		return -1;
	struct tile band = { 0, sc->screen_h - SCENE_BAND, sc->screen_w, SCENE_BAND };
	screen_put(sc, &band, &sc->frame);
	return 0;
}

/* view v's picture into the screen when the layout tiles it there */
static void
tile_view(struct scene *sc, const struct daemon *d, const struct tiles *T, int v,
	  const struct frame *f)
{
	for (int i = 0; i < d->env.nlayout; i++)
		if (d->env.layout[i] == v)
			screen_put(sc, &T->t[i], f);
}

/* the screen's picture to FRAMES/screen.png, through the files' writer */
static void
screen_to_file(struct scene *sc, const struct frame *f)
{
	char err[256];
	if (!scene_writer(sc, &sc->files, SCENE_FILES_NICE))
		return;
	if (!sc->screen_file) {
		char path[4200];
		snprintf(path, sizeof path, "%s/screen.png", sc->frames_dir);
		struct sink *s = sink_png_latest(path, err, sizeof err);
		if (!s || frame_writer_attach(sc->files, SCENE_SCREEN_SLOT, s, f->width, f->height, err,
					      sizeof err) < 0) {
			fprintf(stderr, "postured: screen file: %s\n", err);
			return;
		}
		sc->screen_file = 1;
	}
	if (frame_writer_submit(sc->files, SCENE_SCREEN_SLOT, f, err, sizeof err) < 0)
		fprintf(stderr, "postured: screen file: %s\n", err);
}

/* the screen, its views tiled in it as they were drawn, to the framebuffer and the files */
static void
publish_screen(struct scene *sc, struct daemon *d, int files)
{
	screen_band(sc, d);
	struct frame screen;
	frame_init(&screen, sc->screen_w, sc->screen_h, sc->screen_rgba);
	screen.input_us = sc->input_us;
	struct env_view whole = { .width = sc->screen_w, .height = sc->screen_h };
	if (sc->fb)
		scene_to_screen(sc, &whole, &screen);
	if (files)
		screen_to_file(sc, &screen);
}

int
scene_draw_screen(struct scene *sc, struct daemon *d, const struct frame **dest, char *err,
		  size_t errlen)
{
	const struct env *e = &d->env;
	if (!e->nlayout) {
		for (int v = 0; v < ENV_MAX_VIEWS; v++)
			if (e->view[v].used)
				return scene_draw(sc, d, v, dest, err, errlen);
		snprintf(err, errlen, "no view to show");
		return -1;
	}
	struct tiles T;
	if (tiles_make(&T, d->screen_w, d->screen_h, SCENE_BAND, e->nlayout) < 0 ||
	    screen_ready(sc, d->screen_w, d->screen_h) < 0) {
		snprintf(err, errlen, "the layout does not fit the screen");
		return -1;
	}
	for (int i = 0; i < e->nlayout; i++) {
		const struct frame *f;
		if (scene_draw(sc, d, e->layout[i], &f, err, errlen) < 0)
			return -1;
		screen_put(sc, &T.t[i], f);
	}
	if (screen_band(sc, d) < 0) {
		snprintf(err, errlen, "the screen's band could not be drawn");
		return -1;
	}
	frame_init(&sc->screen_frame, sc->screen_w, sc->screen_h, sc->screen_rgba);
	*dest = &sc->screen_frame;
	return 0;
}

int
scene_publish(struct scene *sc, struct daemon *d, struct events *E, uint64_t now)
{
	struct env *e = &d->env;
	int files = sc->frames_dir && now - sc->last_png_us >= SCENE_PERIOD_US;
	int events = events_wanted(E, SUB_FRAME) && now - sc->last_event_us >= SCENE_PERIOD_US;
	if (d->envelopes && d->envelopes->serial != sc->envelopes_seen)
		sc->dirty = 1; /* an envelope made, hidden, shown or gone */
	if (!sc->dirty || (!files && !events && !sc->fb) || sc->failed)
		return 0;
	int first = 1;
	struct tiles T;
	int tiled = (sc->fb || files) && e->nlayout &&
		    tiles_make(&T, d->screen_w, d->screen_h, SCENE_BAND, e->nlayout) == 0 &&
		    screen_ready(sc, d->screen_w, d->screen_h) == 0;
	for (int v = 0; v < ENV_MAX_VIEWS; v++) {
		const struct env_view *vw = &e->view[v];
		const struct frame *f;
		char err[256];
		if (!vw->used || scene_draw(sc, d, v, &f, err, sizeof err) < 0)
			continue;
		if (tiled)
			tile_view(sc, d, &T, v, f);
		else if (first && sc->fb)
			scene_to_screen(sc, vw, f);
		first = 0;
		if (files)
			scene_to_file(sc, v, vw, f);
		if (events)
			scene_to_events(sc, v, vw, f);
	}
	if (tiled)
		publish_screen(sc, d, files);
	sc->input_us = 0; /* shown: the next pictures' latency counts from newer input */
	if (files)
		sc->last_png_us = now;
	if (events)
		sc->last_event_us = now;
	sc->dirty = 0;
	return 1;
}

int
scene_waiting(const struct scene *sc, const struct events *E)
{
	for (int v = 0; v < ENV_MAX_VIEWS; v++)
		if (sc->relay_pending[v]) /* a frame event being encoded: the loop stays awake */
			return 1;
	return sc->dirty && !sc->failed && (sc->frames_dir || sc->fb || events_wanted(E, SUB_FRAME));
}

/* one writer's failures since the last look, logged under what it writes */
static void
scene_writer_errors(struct frame_writer *w, const char *what)
{
	char err[256];
	uint64_t n = w ? frame_writer_error(w, err, sizeof err) : 0;
	if (n == 1)
		fprintf(stderr, "postured: %s: %s\n", what, err);
	else if (n > 1)
		fprintf(stderr, "postured: %s: %llu writes failed, the last: %s\n", what,
			(unsigned long long)n, err);
}

int
scene_latencies(struct scene *sc, uint64_t *dest, int max)
{
	return sc->screen ? frame_writer_latencies(sc->screen, dest, max) : 0;
}

int
scene_flip_times(struct scene *sc, struct kms_times_summary *dest)
{
	struct sink *s = sc->screen ? frame_writer_sink(sc->screen, 0) : sc->fb;
	if (!s || strcmp(s->ops->name, "kms"))
		return -1;
	sink_kms_times(s, dest);
	return 0;
}

void
scene_sync(struct scene *sc, struct daemon *d, struct events *E)
{
	/* the frame events whose PNGs the files' thread has made */
	for (int v = 0; v < ENV_MAX_VIEWS; v++) {
		const uint8_t *png;
		size_t len;
		struct frame info;
		if (!sc->relay[v] || !sink_relay_take(sc->relay[v], &png, &len, &info))
			continue;
		sc->relay_pending[v] = 0;
		if (len && d->env.view[v].used) /* len 0: its encoding failed (logged below) */
			frame_event(E, d->env.view[v].name, &info, png, len);
	}
	scene_writer_errors(sc->files, "frame file");
	scene_writer_errors(sc->screen, "framebuffer");
	struct frame_writer_stats a = { 0 }, b = { 0 };
	if (sc->files)
		frame_writer_stats(sc->files, &a);
	if (sc->screen)
		frame_writer_stats(sc->screen, &b);
	d->stats.frames_written = a.written + b.written;
	d->stats.frames_dropped = a.dropped + b.dropped;
}

void
scene_hold_screen(struct scene *sc, int held)
{
	struct sink *s = sc->screen ? frame_writer_sink(sc->screen, 0) : sc->fb;
	sc->screen_held = held;
	if (held && sc->screen)
		frame_writer_flush(sc->screen); /* the last frame written before master goes */
	if (s && !strcmp(s->ops->name, "kms") && sink_kms_master(s, !held) < 0)
		fprintf(stderr, "postured: screen: DRM master %s: %s\n", held ? "not dropped" : "not taken",
			strerror(errno));
	if (!held)
		sc->dirty = 1;
}

int
scene_reprobe_screen(struct scene *sc, int *w, int *h)
{
	struct sink *s = sc->screen ? frame_writer_sink(sc->screen, 0) : sc->fb;
	char err[300], desc[160];
	if (!s || strcmp(s->ops->name, "kms"))
		return 0;
	if (sc->screen)
		frame_writer_flush(sc->screen); /* the writer idle while the sink changes */
	int rc = sink_kms_reprobe(s, err, sizeof err);
	if (rc < 0) {
		fprintf(stderr, "postured: screen: %s\n", err);
		return -1;
	}
	sink_kms_info(s, w, h, desc, sizeof desc);
	if (rc > 0)
		fprintf(stderr, "postured: screen: now %s\n", desc);
	sc->dirty = 1;
	return rc;
}

void
scene_free(struct scene *sc)
{
	/* the newest pictures written before the threads end */
	frame_writer_free(sc->files);
	if (sc->screen)
		frame_writer_free(sc->screen); /* fb with it */
	else
		sink_close(sc->fb);
	view_drawlist_free(sc->dl);
	free(sc->screen_rgba);
	free(sc->hemi);
	free(sc->idmap[0]);
	free(sc->idmap[1]);
	render_free(sc->r);
}
