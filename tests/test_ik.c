/* test_ik.c - inverse kinematics: objectives, gradients, bounds, limits of time, balance */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "test_util.h"
#include "test_human.h"

#include <nlopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/human.h"
#include "pose/ik.h"
#include "figure/kin.h"
#include "pose/stance.h"

#define DEG (M_PI / 180)

static const double QID[4] = { 0, 0, 0, 1 };

#include "alloc_count.h"

/* ---- small figures with analytic answers --------------------------------- */

/* base --R(z)--> link1 (l1) --R(z)--> link2 (l2): a planar arm in x-y */
static struct model *
planar_arm(double l1, double l2, double lo, double hi)
{
	struct model_builder *b = model_builder_create("arm");
	struct segment_def sd = segment_default_def();
	const char *names[3] = { "base", "l1", "l2" };
	int seg[3];
	for (int i = 0; i < 3; i++) {
		sd.name = names[i];
		sd.mass = 1;
		seg[i] = model_builder_segment(b, &sd);
	}
	double o[3] = { 0, 0, 0 }, x1[3] = { l1, 0, 0 }, x2[3] = { l2, 0, 0 };
	int root = model_builder_site(b, seg[0], "origin", o, QID);
	int a = model_builder_site(b, seg[1], "proximal", o, QID);
	int a2 = model_builder_site(b, seg[1], "distal", x1, QID);
	int c = model_builder_site(b, seg[2], "proximal", o, QID);
	model_builder_site(b, seg[2], "tip", x2, QID);
	struct joint_def jd = joint_default_def();
	jd.ndof = 1;
	jd.dof[0] = (struct dof_def){ DOF_ROTATION, 2, 1, lo, hi, 0 };
	jd.name = "shoulder";
	jd.site_from = root;
	jd.site_to = a;
	model_builder_joint(b, &jd);
	jd.name = "elbow";
	jd.site_from = a2;
	jd.site_to = c;
	jd.dof[0].init = 0.3; /* start bent: the elbow-down solution */
	model_builder_joint(b, &jd);
	model_builder_root(b, root, o, QID);
	struct model *m = model_builder_finish(b);
	assert_non_null(m);
	model_builder_free(b);
	return m;
}

/* a ball joint (R(z) R(y) R(x)) carrying a pointer 0.5 m along +z */
static struct model *
ball(void)
{
	struct model_builder *b = model_builder_create("ball");
	struct segment_def sd = segment_default_def();
	sd.name = "base";
	int s0 = model_builder_segment(b, &sd);
	sd.name = "pointer";
	int s1 = model_builder_segment(b, &sd);
	double o[3] = { 0, 0, 0 }, tip[3] = { 0, 0, 0.5 };
	int root = model_builder_site(b, s0, "origin", o, QID);
	int c = model_builder_site(b, s1, "origin", o, QID);
	model_builder_site(b, s1, "tip", tip, QID);
	struct joint_def jd = joint_default_def();
	jd.name = "ball";
	jd.site_from = root;
	jd.site_to = c;
	jd.ndof = 3;
	for (int i = 0; i < 3; i++)
		jd.dof[i] = (struct dof_def){ DOF_ROTATION, 2 - i, 1, -M_PI, M_PI, 0 };
	model_builder_joint(b, &jd);
	model_builder_root(b, root, o, QID);
	struct model *m = model_builder_finish(b);
	assert_non_null(m);
	model_builder_free(b);
	return m;
}

static struct ik_options
exact_options(void)
{
	struct ik_options o = ik_default_options();
	o.step_pos = o.step_ori = 0;
	o.tol_pos = 1e-9;
	o.tol_ori = 1e-9;
	o.max_iter = 500;
	return o;
}

static void
test_point_planar_arm_law_of_cosines(void **unused)
{
	(void)unused;
	struct model *m = planar_arm(1.0, 0.7, -M_PI, M_PI);
	struct state *s = state_make(m);
	kin_update(m, s);
	struct ik *ik = ik_make(m, 2);
	struct ik_constraint_def c = ik_constraint_default_def();
	c.effector_site = model_find_site(m, "l2.tip");
	c.goal_xf.p[0] = 0.9;
	c.goal_xf.p[1] = 0.8;
	assert_int_equal(ik_add(ik, m, &c), 0);
	struct ik_options o = exact_options();
	struct ik_result r = ik_solve(ik, m, s, &o, NULL);
	assert_true(r.met);
	/* analytic: cos(elbow) = (x^2 + y^2 - l1^2 - l2^2) / (2 l1 l2), elbow-down branch */
	double x = 0.9, y = 0.8, l1 = 1.0, l2 = 0.7;
	double q2 = acos((x * x + y * y - l1 * l1 - l2 * l2) / (2 * l1 * l2));
	double q1 = atan2(y, x) - atan2(l2 * sin(q2), l1 + l2 * cos(q2));
	assert_near(s->q[1], q2, 1e-7);
	assert_near(s->q[0], q1, 1e-7);
	assert_near(r.f_end, 0, 1e-15);
	assert_true(r.f_start > 0.1);
	ik_free(ik);
	state_free(s);
	model_free(m);
}

/* out of reach: the closest reachable configuration is the straight arm pointing at the goal */
static void
test_unreachable_goal_ends_closest_and_within_limits(void **unused)
{
	(void)unused;
	/* elbow limited to [-1, 1]: a straight arm (0) is allowed */
	struct model *m = planar_arm(1.0, 0.7, -1.0, 1.0);
	struct state *s = state_make(m);
	kin_update(m, s);
	struct ik *ik = ik_make(m, 1);
	struct ik_constraint_def c = ik_constraint_default_def();
	c.effector_site = model_find_site(m, "l2.tip");
	c.goal_xf.p[0] = 2.0; /* 3 m away at 30 degrees, reach 1.7 m */
	c.goal_xf.p[1] = 2.0 * tan(30 * DEG) + 0.0;
	c.goal_xf.p[0] = 3 * cos(30 * DEG);
	c.goal_xf.p[1] = 3 * sin(30 * DEG);
	ik_add(ik, m, &c);
	struct ik_options o = exact_options();
	o.tol_pos = 1e-6;
	ik_solve(ik, m, s, &o, NULL);
	assert_near(s->q[1], 0, 1e-5);
	assert_near(s->q[0], 30 * DEG, 1e-5);
	/* a goal that needs the shoulder beyond its limit stops at the limit */
	c.goal_xf.p[0] = -1.0;
	c.goal_xf.p[1] = -0.1; /* behind: needs about -174 degrees, allowed -57 */
	ik_set_goal(ik, 0, &c.goal_xf);
	ik_free(ik);
	model_free(m);
	m = planar_arm(1.0, 0.7, -1.0, 1.0);
	ik = ik_make(m, 1);
	state_free(s);
	s = state_make(m);
	kin_update(m, s);
	ik_add(ik, m, &c);
	struct ik_result r = ik_solve(ik, m, s, &o, NULL);
	for (int d = 0; d < m->ndof; d++) {
		assert_true(s->q[d] >= m->dof_lo[d]);
		assert_true(s->q[d] <= m->dof_hi[d]);
	}
	assert_true(r.active_limits >= 1);
	assert_false(r.met);
	ik_free(ik);
	state_free(s);
	model_free(m);
}

static void
test_line_and_plane(void **unused)
{
	(void)unused;
	struct model *m = planar_arm(1.0, 0.7, -M_PI, M_PI);
	struct state *s = state_make(m);
	kin_update(m, s);
	struct ik *ik = ik_make(m, 1);
	struct ik_constraint_def c = ik_constraint_default_def();
	c.effector_site = model_find_site(m, "l2.tip");
	/* the line x = 0.5 (through (0.5, 0, 0) along y) */
	c.pos = IK_LINE;
	c.goal_xf.p[0] = 0.5;
	c.goal_axis[0] = 0;
	c.goal_axis[1] = 1;
	c.goal_axis[2] = 0;
	ik_add(ik, m, &c);
	struct ik_options o = exact_options();
	ik_solve(ik, m, s, &o, NULL);
	int tip = model_find_site(m, "l2.tip");
	assert_near(s->site_xf[tip].p[0], 0.5, 1e-9);
	/* the plane y = 1.2, its normal rotated into place by the goal frame */
	c.pos = IK_PLANE;
	xform_identity(&c.goal_xf);
	c.goal_xf.p[1] = 1.2;
	c.goal_axis[0] = 1; /* normal along goal x, which the goal turns to world y */
	c.goal_axis[1] = 0;
	double q[4], zaxis[3] = { 0, 0, 1 };
	mathx_quat_axis_angle(zaxis, M_PI / 2, q);
	mathx_quat_to_mat(q, c.goal_xf.r);
	assert_int_equal(ik_set(ik, m, 0, &c), 0);
	ik_solve(ik, m, s, &o, NULL);
	assert_near(s->site_xf[tip].p[1], 1.2, 1e-9);
	ik_free(ik);
	state_free(s);
	model_free(m);
}

static void
test_frame_direction_and_aim_on_a_ball_joint(void **unused)
{
	(void)unused;
	struct model *m = ball();
	struct state *s = state_make(m);
	kin_update(m, s);
	struct ik *ik = ik_make(m, 1);
	struct ik_constraint_def c = ik_constraint_default_def();
	int tip = model_find_site(m, "pointer.tip"), org = model_find_site(m, "pointer.origin");
	struct ik_options o = exact_options();

	/* frame: any orientation is reachable; the result must equal it */
	double axis[3] = { 0.3, -0.5, 0.81 }, q[4];
	double n = sqrt(mathx_dot(axis, axis));
	for (int i = 0; i < 3; i++)
		axis[i] /= n;
	mathx_quat_axis_angle(axis, 1.1, q);
	c.effector_site = org;
	c.pos = IK_POS_NONE;
	c.ori = IK_FRAME;
	c.pos_weight = 0;
	mathx_quat_to_mat(q, c.goal_xf.r);
	ik_add(ik, m, &c);
	struct ik_result r = ik_solve(ik, m, s, &o, NULL);
	assert_true(r.met);
	for (int i = 0; i < 9; i++)
		assert_near(s->site_xf[org].r[i], c.goal_xf.r[i], 1e-8);

	/* direction: the pointer's z axis along world (1, 1, 0)/sqrt2 */
	state_reset(m, s);
	kin_update(m, s);
	c.ori = IK_DIRECTION;
	xform_identity(&c.goal_xf);
	c.goal_axis[0] = c.goal_axis[1] = sqrt(0.5);
	c.goal_axis[2] = 0;
	c.effector_axis[0] = c.effector_axis[1] = 0;
	c.effector_axis[2] = 1;
	ik_set(ik, m, 0, &c);
	ik_solve(ik, m, s, &o, NULL);
	assert_near(s->site_xf[tip].p[0], 0.5 * sqrt(0.5), 1e-8);
	assert_near(s->site_xf[tip].p[1], 0.5 * sqrt(0.5), 1e-8);

	/* aim: the pointer's z axis at the point (2, -1, 2) */
	state_reset(m, s);
	kin_update(m, s);
	c.ori = IK_AIM;
	c.goal_xf.p[0] = 2;
	c.goal_xf.p[1] = -1;
	c.goal_xf.p[2] = 2;
	ik_set(ik, m, 0, &c);
	ik_solve(ik, m, s, &o, NULL);
	for (int i = 0; i < 3; i++) /* the tip lies on the ray, at 0.5 of 3 m */
		assert_near(s->site_xf[tip].p[i], c.goal_xf.p[i] / 6, 1e-8);
	ik_free(ik);
	state_free(s);
	model_free(m);
}

/* ---- the human ---------------------------------------------------------- */



static int
joint(const struct model *m, const char *name)
{
	int j = model_find_joint(m, name);
	assert_true(j >= 0);
	return j;
}

static void
random_posture(const struct model *m, struct state *s, unsigned seed, double scale)
{
	srand(seed);
	for (int d = 0; d < m->ndof; d++) {
		double mid = 0, span = (m->dof_hi[d] - m->dof_lo[d]) * scale;
		double v = mid + span * ((double)rand() / RAND_MAX - 0.5);
		s->q[d] = v < m->dof_lo[d] ? m->dof_lo[d] : v > m->dof_hi[d] ? m->dof_hi[d] : v;
	}
	kin_update(m, s);
}

/* analytic gradients against central differences, every objective, goals fixed and live */
static void
test_gradients_match_finite_differences_on_the_human(void **unused)
{
	(void)unused;
	struct model *m = test_human();
	struct state *s = state_make(m);
	kin_update(m, s);
	struct ik *ik = ik_make(m, 16);
	random_posture(m, s, 3, 0.6);
	kin_set_root(m, s, test_site(m, "foot_l.balance"));
	struct ik_constraint_def c = ik_constraint_default_def();
	double axis[3] = { 0.48, 0.6, 0.64 };
	/* position objectives with a fixed goal */
	c.effector_site = test_site(m, "hand_r.palm");
	c.goal_xf.p[0] = -0.4;
	c.goal_xf.p[1] = 1.2;
	c.goal_xf.p[2] = 0.3;
	double q[4];
	mathx_quat_axis_angle(axis, 0.7, q);
	mathx_quat_to_mat(q, c.goal_xf.r);
	enum ik_pos pos[] = { IK_POINT, IK_LINE, IK_PLANE };
	enum ik_ori ori[] = { IK_FRAME, IK_DIRECTION, IK_AIM };
	memcpy(c.goal_axis, axis, sizeof axis);
	c.effector_axis[0] = 0.6;
	c.effector_axis[1] = 0;
	c.effector_axis[2] = 0.8;
	for (int i = 0; i < 3; i++) {
		c.pos = pos[i];
		c.ori = ori[i];
		c.pos_weight = 0.4;
		c.weight = 1 + i;
		c.start_joint = -1;
		assert_true(ik_add(ik, m, &c) >= 0);
	}
	/* the same objectives with a live goal on the figure: hand to the left knee */
	c.goal_site = test_site(m, "shank_l.knee");
	xform_identity(&c.goal_xf);
	c.goal_xf.p[2] = 0.1;
	mathx_quat_to_mat(q, c.goal_xf.r);
	for (int i = 0; i < 3; i++) {
		c.effector_site = test_site(m, i == 2 ? "head.between_eyes" : "hand_l.palm");
		c.pos = pos[i];
		c.ori = ori[(i + 1) % 3];
		c.pos_weight = 0.6;
		assert_true(ik_add(ik, m, &c) >= 0);
	}
	/* the centre of mass on a vertical line, and limit springs on both knees */
	c = ik_constraint_default_def();
	c.effector_site = test_site(m, HUMAN_SITE_LOWER_TORSO);
	c.com_effector = 1;
	c.pos = IK_LINE;
	c.goal_xf.p[2] = 0.05;
	assert_true(ik_add(ik, m, &c) >= 0);
	for (int side = 0; side < 2; side++) {
		int j = joint(m, side ? "knee_r" : "knee_l");
		assert_int_equal(ik_set_spring(ik, m, m->jnt_dof0[j], -1, 40 * DEG, 3.0), 0);
		s->q[m->jnt_dof0[j]] = 12 * DEG; /* inside the spring's reach */
	}
	kin_update(m, s);
	/* a solve of zero iterations sets up the centre-of-mass offset */
	struct ik_options o = ik_default_options();
	o.max_iter = 0;
	o.balance_rounds = 1;
	o.step_pos = o.step_ori = 0;
	ik_solve(ik, m, s, &o, NULL);
	int n = ik_prepare(ik, m, s, 0);
	assert_true(n > 40);
	double *x = calloc((size_t)n, sizeof *x), *g = calloc((size_t)n, sizeof *g);
	for (int i = 0; i < n; i++)
		x[i] = s->q[ik_var_dof(ik, i)];
	double f = ik_energy(ik, m, s, x, g);
	assert_true(f > 0.1);
	double err2 = 0, ref2 = 0;
	for (int i = 0; i < n; i++) {
		const double h = 1e-6;
		double xi = x[i];
		x[i] = xi + h;
		double fp = ik_energy(ik, m, s, x, NULL);
		x[i] = xi - h;
		double fm = ik_energy(ik, m, s, x, NULL);
		x[i] = xi;
		double fd = (fp - fm) / (2 * h);
		err2 += (g[i] - fd) * (g[i] - fd);
		ref2 += fd * fd;
	}
	assert_true(ref2 > 1);
	double rel = sqrt(err2 / ref2);
	printf("gradient relative error %.3g over %d variables\n", rel, n);
	assert_true(rel < 1e-6);
	free(x);
	free(g);
	ik_free(ik);
	state_free(s);
	model_free(m);
}

/* every joint value within limits after solves, reachable or not */
static void
test_limits_hold_for_reachable_and_unreachable_goals(void **unused)
{
	(void)unused;
	struct model *m = test_human();
	struct state *s = state_make(m);
	kin_update(m, s);
	struct ik *ik = ik_make(m, 2);
	struct ik_constraint_def c = ik_constraint_default_def();
	c.effector_site = test_site(m, "hand_r.palm");
	c.ori = IK_FRAME;
	c.pos_weight = 0.5;
	c.start_joint = joint(m, "clavicle_r");
	ik_add(ik, m, &c);
	struct ik_options o = ik_default_options();
	o.step_pos = o.step_ori = 0;
	srand(5);
	for (int t = 0; t < 60; t++) {
		struct xform g;
		xform_identity(&g);
		double reach = t % 2 ? 0.4 : 3.0; /* odd: near, even: far out of reach */
		for (int i = 0; i < 3; i++)
			g.p[i] = s->site_xf[c.effector_site].p[i] + reach * ((double)rand() / RAND_MAX - 0.5);
		double axis[3] = { rand() % 3 - 1.0, 1, rand() % 2 }, q[4];
		double n = sqrt(mathx_dot(axis, axis));
		for (int i = 0; i < 3; i++)
			axis[i] /= n;
		mathx_quat_axis_angle(axis, (double)rand() / RAND_MAX * M_PI, q);
		mathx_quat_to_mat(q, g.r);
		ik_set_goal(ik, 0, &g);
		ik_solve(ik, m, s, &o, NULL);
		for (int d = 0; d < m->ndof; d++) {
			assert_true(s->q[d] >= m->dof_lo[d]);
			assert_true(s->q[d] <= m->dof_hi[d]);
		}
	}
	ik_free(ik);
	state_free(s);
	model_free(m);
}

/* ---- an overconstrained set against NLopt -------------------------------- */

struct nlopt_ctx {
	struct ik *ik;
	const struct model *m;
	struct state *s;
};

static double
nlopt_energy(unsigned n, const double *x, double *grad, void *data)
{
	(void)n;
	struct nlopt_ctx *c = data;
	return ik_energy(c->ik, c->m, c->s, x, grad);
}

/*
 * Palm and fingertip at goals that disagree, and a frame on the palm: no
 * posture meets all three, so the solve settles at the weighted minimum
 * (§4.4). NLopt, from the same start, on the same energy and bounds, must
 * find the same minimum. Goals lie near the start so that both settle in
 * the same basin (the energy has several local minima far apart).
 */
static void
test_overconstrained_minimum_matches_nlopt(void **unused)
{
	(void)unused;
	struct model *m = test_human();
	struct state *s = state_make(m);
	kin_update(m, s);
	srand(11);
	for (int trial = 0; trial < 6; trial++) {
		struct ik *ik = ik_make(m, 4);
		state_reset(m, s);
		kin_update(m, s);
		random_posture(m, s, 100 + trial, 0.3);
		int palm = test_site(m, "hand_r.palm"), tip = test_site(m, "hand_r.fingertip");
		struct ik_constraint_def c = ik_constraint_default_def();
		c.start_joint = joint(m, "clavicle_r");
		c.effector_site = palm;
		c.goal_xf = s->site_xf[palm];
		for (int i = 0; i < 3; i++)
			c.goal_xf.p[i] += 0.15 * ((double)rand() / RAND_MAX - 0.5);
		ik_add(ik, m, &c);
		c.effector_site = tip;
		c.goal_xf = s->site_xf[tip];
		for (int i = 0; i < 3; i++)
			c.goal_xf.p[i] += 0.15 * ((double)rand() / RAND_MAX - 0.5);
		c.weight = 2;
		ik_add(ik, m, &c);
		c.effector_site = palm;
		c.pos = IK_POS_NONE;
		c.ori = IK_FRAME;
		c.pos_weight = 0;
		c.weight = 0.3;
		double axis[3] = { 0, 0.6, 0.8 }, q[4];
		mathx_quat_axis_angle(axis, 0.4, q);
		struct xform turn = { { 0 }, { 0 } };
		mathx_quat_to_mat(q, turn.r);
		xform_mul(&s->site_xf[palm], &turn, &c.goal_xf);
		ik_add(ik, m, &c);

		int n = ik_prepare(ik, m, s, 0);
		assert_int_equal(n, 9);
		double x[9], x0[9], lo[9], hi[9], f_nlopt = 0;
		for (int i = 0; i < n; i++) {
			int d = ik_var_dof(ik, i);
			x0[i] = x[i] = s->q[d];
			lo[i] = m->dof_lo[d];
			hi[i] = m->dof_hi[d];
		}
		struct nlopt_ctx ctx = { ik, m, s };
		nlopt_opt opt = nlopt_create(NLOPT_LD_MMA, (unsigned)n);
		nlopt_set_lower_bounds(opt, lo);
		nlopt_set_upper_bounds(opt, hi);
		nlopt_set_min_objective(opt, nlopt_energy, &ctx);
		nlopt_set_ftol_rel(opt, 1e-14);
		nlopt_set_xtol_rel(opt, 1e-12);
		nlopt_set_maxeval(opt, 50000);
		assert_true(nlopt_optimize(opt, x, &f_nlopt) > 0);
		nlopt_destroy(opt);

		/* ours, from the same start, run to a stationary point */
		for (int i = 0; i < n; i++)
			s->q[ik_var_dof(ik, i)] = x0[i];
		kin_update(m, s);
		struct ik_options o = ik_default_options();
		o.step_pos = o.step_ori = 0;
		o.max_iter = 2000;
		o.tol_pos = o.tol_ori = 0;
		o.settle_rel = 0;
		struct ik_result r = ik_solve(ik, m, s, &o, NULL);
		/* and with the default settling: it stops sooner, close above the floor */
		for (int i = 0; i < n; i++)
			s->q[ik_var_dof(ik, i)] = x0[i];
		kin_update(m, s);
		o.settle_rel = ik_default_options().settle_rel;
		struct ik_result settled = ik_solve(ik, m, s, &o, NULL);
		printf("overconstrained %d: ours %.12f (%d iterations; settled %.12f in %d), "
		       "NLopt MMA %.12f\n",
		       trial, r.f_end, r.iterations, settled.f_end, settled.iterations, f_nlopt);
		assert_true(f_nlopt > 1e-4); /* really overconstrained */
		assert_true(fabs(r.f_end - f_nlopt) <= 1e-6);
		assert_true(settled.f_end <= f_nlopt * (1 + o.settle_rel));
		assert_true(settled.iterations <= r.iterations);
		ik_free(ik);
	}
	state_free(s);
	model_free(m);
}

/* ---- monotone progress, iteration and time limits ----------------------- */

struct fake_clock {
	uint64_t t, step;
	int reads;
};

static uint64_t
fake_now(void *ctx)
{
	struct fake_clock *c = ctx;
	c->reads++;
	return c->t += c->step;
}

static struct ik *
arm_problem(const struct model *m, double dx)
{
	struct ik *ik = ik_make(m, 2);
	struct ik_constraint_def c = ik_constraint_default_def();
	c.effector_site = model_find_site(m, "hand_r.palm");
	c.ori = IK_FRAME;
	c.pos_weight = 0.5;
	c.start_joint = model_find_joint(m, "clavicle_r");
	c.goal_xf.p[0] = -0.3 + dx;
	c.goal_xf.p[1] = 1.3;
	c.goal_xf.p[2] = 0.4;
	double axis[3] = { 1, 0, 0 }, q[4];
	mathx_quat_axis_angle(axis, -1.2, q);
	mathx_quat_to_mat(q, c.goal_xf.r);
	ik_add(ik, m, &c);
	return ik;
}

static void
test_energy_never_increases(void **unused)
{
	(void)unused;
	struct model *m = test_human();
	struct state *s = state_make(m);
	kin_update(m, s);
	double trace[512];
	for (int t = 0; t < 5; t++) {
		struct ik *ik = arm_problem(m, 0.1 * t);
		struct ik_options o = ik_default_options();
		o.step_pos = o.step_ori = 0;
		o.trace = trace;
		o.trace_cap = 512;
		state_reset(m, s);
		kin_update(m, s);
		struct ik_result r = ik_solve(ik, m, s, &o, NULL);
		assert_true(r.trace_len > 5);
		for (int i = 1; i < r.trace_len; i++)
			assert_true(trace[i] <= trace[i - 1]);
		assert_true(trace[r.trace_len - 1] < trace[0]);
		ik_free(ik);
	}
	state_free(s);
	model_free(m);
}

static void
test_time_limit_cuts_after_one_iteration_and_replays_identically(void **unused)
{
	(void)unused;
	struct model *m = test_human();
	struct state *s = state_make(m), *s2 = state_make(m);
	kin_update(m, s);
	kin_update(m, s2);
	struct ik *ik = arm_problem(m, 0);
	struct ik_options o = ik_default_options();
	o.step_pos = o.step_ori = 0;
	o.budget_us = 100;
	/* a virtual clock advancing 10 us per read: the deadline falls after 9 iterations */
	struct fake_clock fc = { 0, 10, 0 };
	struct ik_clock clk = { fake_now, &fc };
	struct ik_result r = ik_solve(ik, m, s, &o, &clk);
	assert_int_equal(r.status, IK_TIME_LIMIT);
	assert_int_equal(r.iterations, 9);
	assert_int_equal(fc.reads, r.iterations + 2); /* start, each iteration, the one that stops */
	/* the same virtual time gives the same posture, bit for bit */
	struct fake_clock fc2 = { 0, 10, 0 };
	struct ik_clock clk2 = { fake_now, &fc2 };
	ik_solve(ik, m, s2, &o, &clk2);
	assert_true(state_hash(m, s) == state_hash(m, s2));
	/* and it is the best posture so far: better than the start */
	assert_true(r.f_end < r.f_start);
	ik_free(ik);
	state_free(s);
	state_free(s2);
	model_free(m);
}

static void
test_step_factor_walks_the_effector_to_the_goal(void **unused)
{
	(void)unused;
	struct model *m = test_human();
	struct state *s = state_make(m);
	kin_update(m, s);
	struct ik *ik = ik_make(m, 1);
	int palm = test_site(m, "hand_r.palm");
	struct ik_constraint_def c = ik_constraint_default_def();
	c.effector_site = palm;
	c.start_joint = joint(m, "clavicle_r");
	double start[3];
	memcpy(start, s->site_xf[palm].p, sizeof start);
	c.goal_xf.p[0] = start[0] - 0.2;
	c.goal_xf.p[1] = start[1] + 0.6;
	c.goal_xf.p[2] = start[2] + 0.3; /* 0.7 m away */
	ik_add(ik, m, &c);
	struct ik_options o = ik_default_options(); /* 25 cm, 5 degrees */
	int solves = 0;
	double prev = 1e9;
	for (; solves < 10; solves++) {
		struct ik_result r = ik_solve(ik, m, s, &o, NULL);
		double pe, oe;
		ik_constraint_error(ik, m, s, 0, &pe, &oe);
		if (!r.stepped)
			break;
		/* each stepped solve moves the effector at most one step */
		double moved = 0;
		for (int i = 0; i < 3; i++)
			moved += (s->site_xf[palm].p[i] - start[i]) * (s->site_xf[palm].p[i] - start[i]);
		assert_true(sqrt(moved) <= 0.25 + 1e-3);
		assert_true(pe < prev);
		prev = pe;
		memcpy(start, s->site_xf[palm].p, sizeof start);
	}
	double pe, oe;
	ik_constraint_error(ik, m, s, 0, &pe, &oe);
	assert_int_equal(solves, 2); /* 0.7 m: two shortened solves, then the goal itself */
	assert_true(pe < 1e-3);
	ik_free(ik);
	state_free(s);
	model_free(m);
}

/* ---- balance: both feet held, the hand moved ---------------------------- */

static void
test_balance_with_feet_held_and_the_hand_moved(void **unused)
{
	(void)unused;
	struct model *m = test_human();
	struct state *s = state_make(m);
	kin_update(m, s);
	struct ik *ik = ik_make(m, 8);
	struct stance st;
	assert_int_equal(stance_standing(ik, m, s, &st), 0);
	int hand = stance_hand(ik, m, s, &st, 1);
	assert_true(hand >= 0);
	int bal_r = test_site(m, "foot_r.balance");
	double foot_before[3];
	memcpy(foot_before, s->site_xf[bal_r].p, sizeof foot_before);
	/* the hand, solved after the body: 35 cm forward and 20 cm up */
	struct xform g = ik_get(ik, hand)->goal_xf;
	g.p[1] += 0.2;
	g.p[2] += 0.35;
	ik_set_goal(ik, hand, &g);
	struct ik_options o = ik_default_options();
	o.step_pos = o.step_ori = 0;
	struct ik_result r = ik_solve(ik, m, s, &o, NULL);
	double pe, oe;
	ik_constraint_error(ik, m, s, hand, &pe, &oe);
	assert_true(pe < 1e-3 && oe < 1 * DEG);
	/* both feet where they were */
	for (int i = 0; i < 3; i++)
		assert_near(s->site_xf[bal_r].p[i], foot_before[i], 1e-3);
	ik_constraint_error(ik, m, s, st.foot_r, &pe, &oe);
	assert_true(pe < 1e-3 && oe < 1 * DEG);
	/* the centre of mass over the balance point */
	double dx = s->com[0] - st.balance_point[0], dz = s->com[2] - st.balance_point[2];
	printf("balance: %d rounds, centre of mass %.2f mm from the balance line\n",
	       r.balance_rounds, 1e3 * sqrt(dx * dx + dz * dz));
	assert_true(sqrt(dx * dx + dz * dz) < 5e-3);
	assert_true(r.balance_rounds >= 2); /* the hand moved the mass: at least one more round */
	/* without balance, the same reach leaves the mass off the line */
	state_reset(m, s);
	kin_update(m, s);
	ik_enable(ik, st.balance, 0);
	ik_solve(ik, m, s, &o, NULL);
	dx = s->com[0] - st.balance_point[0];
	dz = s->com[2] - st.balance_point[2];
	assert_true(sqrt(dx * dx + dz * dz) > 5e-3);
	ik_free(ik);
	state_free(s);
	model_free(m);
}

/* a limit spring (§D.1.6) pushes a straight elbow out of its 10 degrees */
static void
test_limit_spring_keeps_the_elbow_off_full_extension(void **unused)
{
	(void)unused;
	struct model *m = test_human();
	struct state *s = state_make(m);
	kin_update(m, s);
	struct ik *ik = ik_make(m, 1);
	int palm = test_site(m, "hand_r.palm"), elbow = m->jnt_dof0[joint(m, "elbow_r")];
	struct ik_constraint_def c = ik_constraint_default_def();
	c.effector_site = palm;
	c.start_joint = joint(m, "clavicle_r");
	c.goal_xf = s->site_xf[palm]; /* hold the hanging hand where it is */
	c.weight = 10;
	ik_add(ik, m, &c);
	struct ik_options o = ik_default_options();
	o.step_pos = o.step_ori = 0;
	o.tol_pos = o.tol_ori = 0;
	ik_solve(ik, m, s, &o, NULL);
	assert_near(s->q[elbow], 0, 1e-6); /* nothing asks it to bend */
	assert_int_equal(ik_set_spring(ik, m, elbow, -1, 10 * DEG, 1e-3), 0);
	struct ik_result r = ik_solve(ik, m, s, &o, NULL);
	printf("spring: elbow %.2f deg, energy %.3g -> %.3g\n", s->q[elbow] / DEG, r.f_start, r.f_end);
	assert_true(s->q[elbow] > 3 * DEG);
	assert_true(r.f_end < r.f_start);
	ik_set_spring(ik, m, elbow, -1, 10 * DEG, 0); /* weight 0 removes it */
	state_reset(m, s);
	kin_update(m, s);
	ik_solve(ik, m, s, &o, NULL);
	assert_near(s->q[elbow], 0, 1e-6);
	ik_free(ik);
	state_free(s);
	model_free(m);
}

/* ---- no allocation, cheap goal changes ---------------------------------- */

static void
test_solving_allocates_nothing(void **unused)
{
	(void)unused;
	struct model *m = test_human();
	struct state *s = state_make(m);
	kin_update(m, s);
	struct ik *ik = arm_problem(m, 0);
	struct ik_options o = ik_default_options();
	o.restarts = 3;
#if COUNT_ALLOCS
	long before = allocs;
	struct state *probe = state_make(m); /* the hook sees allocations */
	kin_update(m, probe);
	assert_true(allocs > before);
	state_free(probe);
	before = allocs;
#endif
	for (int i = 0; i < 20; i++) {
		struct xform g = ik_get(ik, 0)->goal_xf;
		g.p[0] += 0.01;
		ik_set_goal(ik, 0, &g);
		ik_enable(ik, 0, i < 7 || i > 8);
		struct ik_result r = ik_solve(ik, m, s, &o, NULL);
		/* moving a goal rebuilds no chain; switching a constraint does */
		assert_int_equal(r.chains_rebuilt, i == 0 || i == 7 || i == 9 ? 1 : 0);
	}
#if COUNT_ALLOCS
	assert_int_equal(allocs - before, 0);
#endif
	ik_free(ik);
	state_free(s);
	model_free(m);
}

static void
test_bad_definitions_are_rejected(void **unused)
{
	(void)unused;
	struct model *m = test_human();
	struct ik *ik = ik_make(m, 1);
	struct ik_constraint_def c = ik_constraint_default_def();
	assert_int_equal(ik_add(ik, m, &c), -1); /* no effector */
	c.effector_site = 0;
	c.goal_xf.p[1] = NAN;
	assert_int_equal(ik_add(ik, m, &c), -1);
	c.goal_xf.p[1] = 0;
	c.pos = IK_LINE;
	c.goal_axis[1] = 0; /* zero axis */
	assert_int_equal(ik_add(ik, m, &c), -1);
	c.goal_axis[1] = 1;
	c.pos_weight = 1.5;
	assert_int_equal(ik_add(ik, m, &c), -1);
	c.pos_weight = 1;
	c.start_joint = m->njnt;
	assert_int_equal(ik_add(ik, m, &c), -1);
	c.start_joint = -1;
	assert_int_equal(ik_add(ik, m, &c), 0);
	assert_int_equal(ik_add(ik, m, &c), -1); /* full */
	struct xform bad;
	xform_identity(&bad);
	bad.r[4] = INFINITY;
	assert_int_equal(ik_set_goal(ik, 0, &bad), -1);
	assert_int_equal(ik_set_goal(ik, 1, &bad), -1);
	assert_int_equal(ik_set_spring(ik, m, 0, 2, 0.1, 1), -1);
	ik_free(ik);
	model_free(m);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_point_planar_arm_law_of_cosines),
		cmocka_unit_test(test_unreachable_goal_ends_closest_and_within_limits),
		cmocka_unit_test(test_line_and_plane),
		cmocka_unit_test(test_frame_direction_and_aim_on_a_ball_joint),
		cmocka_unit_test(test_gradients_match_finite_differences_on_the_human),
		cmocka_unit_test(test_limits_hold_for_reachable_and_unreachable_goals),
		cmocka_unit_test(test_overconstrained_minimum_matches_nlopt),
		cmocka_unit_test(test_energy_never_increases),
		cmocka_unit_test(test_time_limit_cuts_after_one_iteration_and_replays_identically),
		cmocka_unit_test(test_step_factor_walks_the_effector_to_the_goal),
		cmocka_unit_test(test_balance_with_feet_held_and_the_hand_moved),
		cmocka_unit_test(test_limit_spring_keeps_the_elbow_off_full_extension),
		cmocka_unit_test(test_solving_allocates_nothing),
		cmocka_unit_test(test_bad_definitions_are_rejected),
	};
	return cmocka_run_group_tests_name("ik", tests, NULL, NULL);
}
