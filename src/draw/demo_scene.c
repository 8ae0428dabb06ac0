/* demo_scene.c - the standing and the seated (driver) scenes */
#include "draw/demo_scene.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "figure/figure.h"
#include "figure/human.h"
#include "figure/kin.h"
#include "draw/view.h"

#define DEG (M_PI / 180)

static int
dof_of(const struct model *m, const char *joint, int k)
{
	int j = model_find_joint(m, joint);
	return j < 0 ? -1 : m->jnt_dof0[j] + k;
}

/* a global point goal for site on the human */
static int
point_goal(struct demo_scene *sc, const char *site, const double p[3], const char *start, int dir_y)
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
seat_human(struct demo_scene *sc, char *err, size_t errlen)
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
	struct xform at;
	mathx_quat_to_mat(q, at.r);
	memcpy(at.p, sc->ss->site_xf[hp].p, sizeof at.p);
	state_root_at(h, s, model_find_site(h, HUMAN_SITE_ROOT), &at);

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

int
demo_scene_make(struct demo_scene *sc, const char *name, const char *seat_path, char *err, size_t errlen)
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

void
demo_scene_free(struct demo_scene *sc)
{
	ik_free(sc->ik);
	state_free(sc->hs);
	state_free(sc->ss);
	model_free(sc->human);
	model_free(sc->seat);
}


/* every icon; without the frame icon when frame is 0 */
void
demo_scene_icons(struct drawlist *dl, const struct demo_scene *sc, int frame)
{
	const struct model *h = sc->human;
	const struct state *s = sc->hs;
	int palm = model_find_site(h, "hand_r.palm");
	const struct xform *hand = &s->site_xf[palm];
	if (frame)
		view_add_frame_icon(dl, hand, 0.22, 1);
	double up[3] = { 0, 1, 0 };
	view_add_translation_arrow(dl, hand->p, up, 0.5);
	view_add_joint_wheel(dl, h, s, h->jnt_dof0[model_find_joint(h, "elbow_r")], 0.17);
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
	view_add_balance(dl, h, s, NULL);
	static const char status[] = "move end effector: hand_r.palm  x 0.213  y 1.024  z 0.305";
	view_add_status(dl, status, "left: x   middle: y   right: z   CONTROL rotates, SHIFT local axes",
			(int)sizeof status - 1);
	view_add_pointer(dl, dl->width * 0.62, dl->height * 0.38);
}

void
demo_scene_camera(const struct demo_scene *sc, struct camera *cam)
{
	double eye[3] = { -1.45, 1.35, 2.3 }, target[3] = { -0.05, 0.86, 0 };
	double seye[3] = { -2.1, 1.6, 1.9 }, starget[3] = { 0, 0.6, 0.3 };
	view_camera_default(cam);
	view_camera_aim(cam, sc->seated ? seye : eye, sc->seated ? starget : target);
}

void
demo_scene_draw(struct drawlist *dl, const struct demo_scene *sc, const struct camera *cam, int w,
		int h, const int base[2], int icons)
{
	view_begin(dl, cam, w, h);
	view_add_figure(dl, sc->human, sc->hs, base[0]);
	if (sc->seat)
		view_add_figure(dl, sc->seat, sc->ss, base[1]);
	if (icons)
		demo_scene_icons(dl, sc, icons == 1);
}
