/*
 * render-scene - renders a scene of the standard human to a PNG file, and
 * measures the renderer (render + readback) with --bench.
 *
 * Scenes: "standing" (the human's rest posture), "seated" (in the vehicle
 * seat: pelvis on the H-point, heels on the heel points, hands on the
 * steering wheel, solved by the IK of ik.h). --icons adds every icon: the
 * manipulation transform's frame on the right hand, the translation arrow,
 * the right elbow's rotation wheel with its limits, the rotation fans to a
 * turned hand goal, the goal icons of the IK constraints, the balance
 * icons, the status and message lines and the pointer.
 */
#include <errno.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "figure.h"
#include "human.h"
#include "ik.h"
#include "kin.h"
#include "render.h"
#include "view.h"

static const char usage[] =
	"usage: render-scene [OPTIONS]\n"
	"  --scene standing|seated   what to show (default standing)\n"
	"  --icons                   every icon, the status and message lines, the pointer\n"
	"  --size WxH                image size (default 640x480)\n"
	"  --samples 0|4             multisampling (default 0)\n"
	"  --no-shadows              no shadows on the floor\n"
	"  --eye X,Y,Z --target X,Y,Z  the camera (default: the scene's)\n"
	"  --seat FILE               the vehicle seat figure (default src/figures/vehicle_seat.fig)\n"
	"  --out FILE.png            write the picture (default scene.png)\n"
	"  --bench N                 render N frames after 20 of warm-up and print timings\n";

#define DEG (M_PI / 180)

struct scene {
	struct model *human, *seat;
	struct state *hs, *ss;
	struct ik *ik;
	int seated;
};

static int
dof_of(const struct model *m, const char *joint, int k)
{
	int j = model_find_joint(m, joint);
	return j < 0 ? -1 : m->jnt_dof0[j] + k;
}

/* a global point goal for site on the human */
static int
point_goal(struct scene *sc, const char *site, const double p[3], const char *start, int dir_y)
{
	struct ik_constraint_def d = ik_constraint_default_def();
	d.effector_site = model_find_site(sc->human, site);
	d.start_joint = model_find_joint(sc->human, start);
	memcpy(d.goal_xf.p, p, sizeof d.goal_xf.p);
	if (dir_y) {
		/* the sole stays level: the foot's y along the world's */
		d.ori = IK_DIRECTION;
		d.effector_axis[0] = d.effector_axis[2] = 0;
		d.effector_axis[1] = 1;
		d.pos_weight = 0.8;
	}
	return ik_add(sc->ik, sc->human, &d);
}

/* the driver: pelvis on the H-point leaning back, heels on the heel points, hands on the wheel */
static int
seat_human(struct scene *sc, char *err, size_t errlen)
{
	struct model *h = sc->human, *st = sc->seat;
	struct state *s = sc->hs;
	int hp = model_find_site(st, "cushion.h_point");
	int heel_r = model_find_site(st, "body.heel_point"), heel_l = model_find_site(st, "body.left_heel");
	int grip_l = model_find_site(st, "wheel.left_grip"), grip_r = model_find_site(st, "wheel.right_grip");
	if (hp < 0 || heel_r < 0 || heel_l < 0 || grip_l < 0 || grip_r < 0) {
		snprintf(err, errlen, "the seat lacks an H-point, heel points or grips");
		return -1;
	}
	/* the root (mid hip joints) on the H-point, the pelvis tilted back 20 deg */
	double lean = -20 * DEG, q[4] = { sin(lean / 2), 0, 0, cos(lean / 2) };
	s->root_site = model_find_site(h, HUMAN_SITE_ROOT);
	mathx_quat_to_mat(q, s->root_xf.r);
	memcpy(s->root_xf.p, sc->ss->site_xf[hp].p, sizeof s->root_xf.p);
	state_set_root(h, s, s->root_site);
	memcpy(s->root_xf.p, sc->ss->site_xf[hp].p, sizeof s->root_xf.p);
	mathx_quat_to_mat(q, s->root_xf.r);

	/* a start near the answer: hips and knees bent, the upper body upright again */
	s->q[dof_of(h, "hip_l", HUMAN_DOF_FLEX)] = s->q[dof_of(h, "hip_r", HUMAN_DOF_FLEX)] = 90 * DEG;
	s->q[dof_of(h, "knee_l", 0)] = s->q[dof_of(h, "knee_r", 0)] = 80 * DEG;
	s->q[dof_of(h, "spine_17", HUMAN_DOF_FLEX)] = 12 * DEG;
	s->q[dof_of(h, "spine_12", HUMAN_DOF_FLEX)] = 4 * DEG;
	for (int side = 0; side < 2; side++) {
		const char *sh = side ? "shoulder_r" : "shoulder_l", *el = side ? "elbow_r" : "elbow_l";
		s->q[dof_of(h, sh, HUMAN_DOF_FLEX)] = 60 * DEG;
		s->q[dof_of(h, el, 0)] = 60 * DEG;
	}
	kin_update(h, s);

	/* IK: heels to the heel points (soles level), palms to the grips */
	double p[3];
	sc->ik = ik_make(h, 8);
	if (!sc->ik)
		return -1;
	memcpy(p, sc->ss->site_xf[heel_l].p, sizeof p);
	point_goal(sc, "foot_l.heel", p, "hip_l", 1);
	memcpy(p, sc->ss->site_xf[heel_r].p, sizeof p);
	point_goal(sc, "foot_r.heel", p, "hip_r", 1);
	memcpy(p, sc->ss->site_xf[grip_l].p, sizeof p);
	point_goal(sc, "hand_l.palm", p, "clavicle_l", 0);
	memcpy(p, sc->ss->site_xf[grip_r].p, sizeof p);
	point_goal(sc, "hand_r.palm", p, "clavicle_r", 0);
	struct ik_options o = ik_default_options();
	o.step_pos = 0;
	o.step_ori = 0;
	o.budget_us = 0;
	o.max_iter = 500;
	ik_solve(sc->ik, h, s, &o, NULL);
	kin_update(h, s);
	return 0;
}

static int
scene_make(struct scene *sc, const char *name, const char *seat_path, char *err, size_t errlen)
{
	memset(sc, 0, sizeof *sc);
	struct human_def hd = human_default_def(HUMAN_MALE);
	sc->human = human_build(&hd, err, errlen);
	if (!sc->human || !(sc->hs = state_make(sc->human)))
		return -1;
	kin_update(sc->human, sc->hs);
	if (!strcmp(name, "standing"))
		return 0;
	if (strcmp(name, "seated")) {
		snprintf(err, errlen, "unknown scene %s", name);
		return -1;
	}
	sc->seated = 1;
	sc->seat = figure_read_file(seat_path, err, errlen);
	if (!sc->seat || !(sc->ss = state_make(sc->seat)))
		return -1;
	kin_update(sc->seat, sc->ss);
	return seat_human(sc, err, errlen);
}

static void
scene_free(struct scene *sc)
{
	ik_free(sc->ik);
	state_free(sc->hs);
	state_free(sc->ss);
	model_free(sc->human);
	model_free(sc->seat);
}

/* every icon of the dissertation on the scene */
static void
add_icons(struct drawlist *dl, const struct scene *sc)
{
	const struct model *h = sc->human;
	const struct state *s = sc->hs;
	int palm = model_find_site(h, "hand_r.palm");
	const struct xform *hand = &s->site_xf[palm];
	view_add_frame_icon(dl, hand, 0.22, 1);
	double up[3] = { 0, 1, 0 };
	view_add_translation_arrow(dl, hand->p, up, 0.5);
	view_add_joint_wheel(dl, h, s, dof_of(h, "elbow_r", 0), 0.17);
	/* a goal turned 35 deg about the hand's own x and 20 about the world's y */
	struct xform goal = *hand, rot;
	double qa[4] = { sin(35 * DEG / 2), 0, 0, cos(35 * DEG / 2) };
	double qb[4] = { 0, sin(20 * DEG / 2), 0, cos(20 * DEG / 2) };
	double qab[4];
	mathx_quat_mul(qb, qa, qab);
	xform_identity(&rot);
	mathx_quat_to_mat(qab, rot.r);
	xform_mul(&rot, hand, &goal);
	memcpy(goal.p, hand->p, sizeof goal.p);
	view_add_orientation_fans(dl, hand, &goal, 0.15);
	if (sc->ik)
		view_add_goals(dl, sc->ik, h, s);
	view_add_balance(dl, h, s);
	view_add_status(dl, "move end effector: hand_r.palm  x 0.213  y 1.024  z 0.305",
			"left: x   middle: y   right: z   CONTROL rotates, SHIFT local axes", 1);
	view_add_pointer(dl, dl->width * 0.62, dl->height * 0.38);
}

/* the scene's camera: a front three-quarter view, or the driver from the front left */
static void
scene_camera(const struct scene *sc, struct camera *cam)
{
	double eye[3] = { -1.45, 1.35, 2.3 }, target[3] = { -0.05, 0.86, 0 };
	double seye[3] = { -2.1, 1.6, 1.9 }, starget[3] = { 0, 0.6, 0.3 };
	view_camera_default(cam);
	view_camera_aim(cam, sc->seated ? seye : eye, sc->seated ? starget : target);
}

static void
build(struct drawlist *dl, const struct scene *sc, const struct camera *cam, int w, int h,
      const int base[2], int icons)
{
	view_begin(dl, cam, w, h);
	view_add_figure(dl, sc->human, sc->hs, base[0]);
	if (sc->seat)
		view_add_figure(dl, sc->seat, sc->ss, base[1]);
	if (icons)
		add_icons(dl, sc);
}

static int
parse_vec(const char *s, double dest[3])
{
	return sscanf(s, "%lf,%lf,%lf", &dest[0], &dest[1], &dest[2]) == 3 ? 0 : -1;
}

static double
now_s(void)
{
	struct timespec t;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return t.tv_sec + t.tv_nsec * 1e-9;
}

static int
cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

static int
write_png(const char *path, const struct frame *f)
{
	png_image img;
	memset(&img, 0, sizeof img);
	img.version = PNG_IMAGE_VERSION;
	img.width = (png_uint_32)f->width;
	img.height = (png_uint_32)f->height;
	img.format = PNG_FORMAT_RGBA;
	return png_image_write_to_file(&img, path, 0, f->rgba, f->stride, NULL) ? 0 : -1;
}

int
main(int argc, char **argv)
{
	const char *scene = "standing", *out = "scene.png", *seat = "src/figures/vehicle_seat.fig";
	int w = 640, h = 480, icons = 0, bench = 0, have_eye = 0, have_target = 0;
	double eye[3], target[3];
	struct render_def rd = render_default_def();
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
		if (!strcmp(a, "--icons")) {
			icons = 1;
		} else if (!strcmp(a, "--no-shadows")) {
			rd.shadows = 0;
		} else if (v && !strcmp(a, "--scene")) {
			scene = argv[++i];
		} else if (v && !strcmp(a, "--size") && sscanf(v, "%dx%d", &w, &h) == 2) {
			i++;
		} else if (v && !strcmp(a, "--samples")) {
			rd.samples = atoi(argv[++i]);
		} else if (v && !strcmp(a, "--eye") && !parse_vec(v, eye)) {
			have_eye = 1, i++;
		} else if (v && !strcmp(a, "--target") && !parse_vec(v, target)) {
			have_target = 1, i++;
		} else if (v && !strcmp(a, "--seat")) {
			seat = argv[++i];
		} else if (v && !strcmp(a, "--out")) {
			out = argv[++i];
		} else if (v && !strcmp(a, "--bench")) {
			bench = atoi(argv[++i]);
		} else {
			fputs(usage, stderr);
			return 2;
		}
	}
	char err[256];
	struct scene sc;
	if (scene_make(&sc, scene, seat, err, sizeof err)) {
		fprintf(stderr, "render-scene: %s\n", err);
		return 1;
	}
	rd.max_w = w;
	rd.max_h = h;
	struct render *r = render_make(&rd, err, sizeof err);
	struct drawlist *dl = view_drawlist_make();
	int base[2] = { 0, 0 };
	if (!r || !dl || (base[0] = render_add_model(r, sc.human, err, sizeof err)) < 0 ||
	    (sc.seat && (base[1] = render_add_model(r, sc.seat, err, sizeof err)) < 0)) {
		fprintf(stderr, "render-scene: %s\n", dl ? err : "out of memory");
		return 1;
	}
	struct camera cam;
	scene_camera(&sc, &cam);
	if (have_eye || have_target) {
		double e[3], t[3];
		memcpy(e, cam.xf.p, sizeof e);
		view_camera_vrp(&cam, t);
		view_camera_aim(&cam, have_eye ? eye : e, have_target ? target : t);
	}
	struct frame f;
	if (bench > 0) {
		/* render + readback per frame, the draw list rebuilt each time as the loop will */
		double *t = malloc(sizeof(double) * (size_t)bench);
		for (int i = 0; i < 20 + bench; i++) {
			double t0 = now_s();
			build(dl, &sc, &cam, w, h, base, icons);
			render_frame(r, dl, 0, &f);
			if (i >= 20)
				t[i - 20] = now_s() - t0;
		}
		qsort(t, (size_t)bench, sizeof *t, cmp_double);
		struct render_stats st = render_last_stats(r);
		printf("render-scene: %s%s %dx%d samples %d shadows %d: median %.3f ms "
		       "(%.1f fps), instances %d, triangles %d, icon vertices %d\n",
		       scene, icons ? "+icons" : "", w, h, rd.samples, rd.shadows, 1e3 * t[bench / 2],
		       1 / t[bench / 2], st.instances, st.triangles, st.vertices);
		printf("BENCH render.%dx%d.posture fps=%.1f\n", w, h, 1 / t[bench / 2]);
		free(t);
	} else {
		build(dl, &sc, &cam, w, h, base, icons);
		render_frame(r, dl, 0, &f);
		if (dl->dropped)
			fprintf(stderr, "render-scene: %d items did not fit the draw list\n", dl->dropped);
		if (write_png(out, &f)) {
			fprintf(stderr, "render-scene: cannot write %s\n", out);
			return 1;
		}
	}
	view_drawlist_free(dl);
	render_free(r);
	scene_free(&sc);
	return 0;
}
