/*
 * test_behave.c - the dissertation's figures as scenarios (Figures 5.3 to
 * 5.10): the human's behaviours respond to the manipulation primitives as
 * Chapter 5 describes. Each scenario also renders its final posture into
 * build/test-output/behave-NAME.png for a person to look at.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "test_util.h"

#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "pose/behave.h"
#include "figure/human.h"
#include "figure/kin.h"
#include "draw/render.h"
#include "draw/sink.h"
#include "draw/view.h"

#define DEG (M_PI / 180)

struct rig {
	struct model *m;
	struct state *s;
	struct ik *ik;
	struct behave b;
	struct ik_options opt;
};

static void
rig_make(struct rig *r, const struct behave_params *p)
{
	char err[200];
	struct human_def hd = human_default_def(HUMAN_MALE);
	r->m = human_build(&hd, err, sizeof err);
	assert_non_null(r->m);
	r->s = state_make(r->m);
	kin_update(r->m, r->s);
	r->ik = ik_make(r->m, 32);
	assert_int_equal(behave_attach(&r->b, r->m, r->s, r->ik, p), 0);
	r->opt = ik_default_options();
	r->opt.budget_us = 0; /* frames run to convergence: the tests are about where things go */
}

static void
rig_free(struct rig *r)
{
	ik_free(r->ik);
	state_free(r->s);
	model_free(r->m);
}

static void
frames(struct rig *r, int n)
{
	for (int i = 0; i < n; i++)
		behave_frame(&r->b, r->m, r->s, r->ik, &r->opt, NULL);
}

/* the final posture as a picture, for people */
static void
snapshot(const struct rig *r, const char *name, const double eye[3])
{
	char err[256], path[256];
	mkdir("build", 0755);
	mkdir("build/test-output", 0755);
	struct render_def rd = render_default_def();
	rd.max_w = 480, rd.max_h = 360;
	struct render *ren = render_make(&rd, err, sizeof err);
	assert_non_null(ren);
	struct drawlist *dl = view_drawlist_make();
	struct camera cam;
	double target[3] = { r->s->com[0], 0.9, r->s->com[2] };
	view_camera_default(&cam);
	view_camera_aim(&cam, eye, target);
	view_begin(dl, &cam, 480, 360);
	view_add_figure(dl, r->m, r->s, 0);
	view_add_balance(dl, r->m, r->s, NULL);
	view_add_status(dl, name, NULL, -1);
	struct frame f;
	assert_int_equal(render_frame(ren, dl, 0, &f), 0);
	snprintf(path, sizeof path, "build/test-output/behave-%s.png", name);
	struct sink *png = sink_png_latest(path, err, sizeof err);
	assert_non_null(png);
	assert_int_equal(sink_write(png, &f, err, sizeof err), 0);
	sink_close(png);
	view_drawlist_free(dl);
	render_free(ren);
}

static const double FRONT[3] = { 1.6, 1.4, 2.6 };
static const double SIDE[3] = { 2.8, 1.0, 0.4 };

static double
dist3(const double a[3], const double b[3])
{
	double d[3] = { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
	return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

static double
dist2(const double a[2], const double b[2])
{
	return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]));
}

/* Figure 5.3: moving a foot keeps the weight distribution (x, z) */
static void
move_left_foot(int follow, double *dx, double *dz, double *moved_bp)
{
	struct behave_params p = behave_default_params();
	p.balance_follows_feet = follow;
	struct rig r;
	rig_make(&r, &p);
	frames(&r, 5);
	double x0 = r.b.bal.x, z0 = r.b.bal.z, bp0[2] = { r.b.bal.point[0], r.b.bal.point[1] };
	struct xform goal = r.s->site_xf[r.b.s_toe[0]];
	goal.p[2] += 0.20; /* 20 cm forward */
	goal.p[0] += 0.05; /* and 5 cm out */
	behave_move_foot(&r.b, r.m, r.s, r.ik, BEHAVE_LEFT, &goal);
	frames(&r, 40);
	/* the foot got there */
	for (int i = 0; i < 3; i++)
		assert_near(r.s->site_xf[r.b.s_toe[0]].p[i], goal.p[i], 2e-3);
	*dx = r.b.bal.x - x0;
	*dz = r.b.bal.z - z0;
	*moved_bp = dist2(r.b.bal.point, bp0);
	snapshot(&r, follow ? "fig5.3-foot-moved" : "fig5.3-balance-point-fixed", FRONT);
	rig_free(&r);
}

/*
 * A behaviour's packed numbers as a session or the journal gives them back:
 * each integer field a whole number in its range, or the numbers were not
 * ours and nothing changes (found by the session fuzzer: a count of 4e40
 * steps cast to int, undefined; a hand on site -5 was taken)
 */
static void
test_unpack_refuses_numbers_that_are_not_its_own(void **unused)
{
	(void)unused;
	struct rig r;
	rig_make(&r, NULL);
	double v[256], w[256], back[256];
	int n = behave_pack(&r.b, v, 256);
	assert_true(n > 54 && n <= 256);
	assert_int_equal(behave_unpack(&r.b, r.m, v, n), 0);
	/* index in the packed list (behave_store.c's order), a value that is not its own */
	static const struct {
		int at;
		double bad;
	} cases[] = {
		{ 0, 2 },      { 0, 4.4e40 },  { 1, -1 },   { 2, 5 },  { 3, -5 },  { 3, 0.5 }, { 3, 1e6 },
		{ 8, 2 },      { 9, 3 },       { 10, -1 },  { 19, 7 }, { 26, -1 }, { 29, 0.25 },
		{ 49, 3 },     { 50, -1 },     { 50, 4.4e40 }, { 51, 2 }, { 51, 1 }, { 52, 2 },
		{ 53, 21 },    { 54, 3e9 },
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		memcpy(w, v, sizeof v);
		w[cases[i].at] = cases[i].bad;
		if (cases[i].at == 53)
			w[54] = 20; /* a step's frame past its frames */
		/* at 51, 1: a step under way of 0 frames (the rig's step has none) */
		if (behave_unpack(&r.b, r.m, w, n) != -1)
			fail_msg("number %d as %g was taken", cases[i].at, cases[i].bad);
		assert_int_equal(behave_pack(&r.b, back, 256), n);
		assert_memory_equal(back, v, sizeof(double) * (size_t)n); /* nothing changed */
	}
	rig_free(&r);
}

static void
test_fig_5_3_balance_point_follows_feet(void **unused)
{
	(void)unused;
	double dx, dz, moved;
	move_left_foot(1, &dx, &dz, &moved);
	printf("follows: x %+.4f z %+.4f, point moved %.1f mm\n", dx, dz, 1e3 * moved);
	assert_true(fabs(dx) < 0.02 && fabs(dz) < 0.02);
	assert_true(moved > 0.03); /* it did move, with the feet */
	move_left_foot(0, &dx, &dz, &moved);
	printf("fixed: x %+.4f z %+.4f, point moved %.1f mm\n", dx, dz, 1e3 * moved);
	assert_true(moved < 5e-3); /* without the behaviour it stays put in space */
}

/* Figure 5.4: shifting the centre of mass with the feet held */
static void
test_fig_5_4_shift_com_feet_held(void **unused)
{
	(void)unused;
	struct rig r;
	rig_make(&r, NULL);
	frames(&r, 3);
	double feet0[2][3];
	for (int k = 0; k < 2; k++)
		memcpy(feet0[k], r.s->site_xf[r.b.s_toe[k]].p, sizeof feet0[k]);
	behave_move_com(&r.b, r.m, r.s, r.ik, 0.07, 0, 0); /* 7 cm to the left */
	frames(&r, 30);
	for (int k = 0; k < 2; k++)
		for (int i = 0; i < 3; i++)
			assert_near(r.s->site_xf[r.b.s_toe[k]].p[i], feet0[k][i], 1e-3);
	double com[2] = { r.s->com[0], r.s->com[2] };
	printf("centre of mass %.2f mm from the new balance point; x %.3f\n",
	       1e3 * dist2(com, r.b.bal_point), r.b.bal.x);
	assert_true(dist2(com, r.b.bal_point) < 5e-3);
	assert_true(r.b.bal.x < 0.3); /* the weight went to the left foot */
	assert_int_equal(r.b.root, BALANCE_ROOT_LEFT_FOOT);
	snapshot(&r, "fig5.4-com-shifted", FRONT);
	rig_free(&r);
}

/* Figure 5.5: lowering the centre of mass squats, hips square, and roots the lower torso */
static void
test_fig_5_5_squat_reroots_at_the_lower_torso(void **unused)
{
	(void)unused;
	struct rig r;
	rig_make(&r, NULL);
	frames(&r, 3);
	double h0 = r.s->com[1];
	behave_move_com(&r.b, r.m, r.s, r.ik, 0, 0, -0.40);
	frames(&r, 60);
	printf("centre of mass %.3f -> %.3f m (leg %.3f), root %d\n", h0, r.s->com[1],
	       r.b.leg_length, r.b.root);
	assert_true(r.s->com[1] < h0 - 0.25);
	assert_int_equal(r.b.root, BALANCE_ROOT_LOWER_TORSO);
	assert_true(r.s->com[1] < 0.7 * r.b.leg_length + 0.05);
	/* hips square: the pelvis's left-right axis stays level and square to the feet */
	const double *pr = r.s->site_xf[r.b.s_pelvis].r;
	assert_true(fabs(pr[3]) < sin(3 * DEG)); /* x axis has no vertical part */
	snapshot(&r, "fig5.5-squat", FRONT);
	rig_free(&r);
}

/*
 * Tiptoe (Table D.1, §5.5.2): with "allow heel to rise", raising the centre
 * of mass 5 cm lifts the heels and brings the weight over the balls of the
 * feet: the toes stay, and the centre of mass ends above the toes' contact
 * (between each foot's toe joint and toe tip, the part still on the
 * floor), not over the mid-foot it started from; no step. With the default
 * "keep heel on floor" the heels stay down and the centre of mass cannot
 * rise more than a centimetre (the legs are straight already).
 */
static void
test_tiptoe_needs_heels_allowed_to_rise(void **unused)
{
	(void)unused;
	for (int rise = 0; rise < 2; rise++) {
		struct behave_params p = behave_default_params();
		p.heel[0] = p.heel[1] = rise ? HEEL_ALLOW_RISE : HEEL_KEEP_ON_FLOOR;
		struct rig r;
		rig_make(&r, &p);
		frames(&r, 3);
		double h0 = r.s->com[1], toe0[2][3], heel0[2];
		for (int k = 0; k < 2; k++) {
			memcpy(toe0[k], r.s->site_xf[r.b.s_toe[k]].p, sizeof toe0[k]);
			heel0[k] = r.s->site_xf[r.b.s_heel[k]].p[1];
			assert_true(fabs(heel0[k]) < 1e-3); /* at rest the heels are down either way */
		}
		behave_move_com(&r.b, r.m, r.s, r.ik, 0, 0, 0.05);
		frames(&r, 30);
		double *com = r.s->com;
		printf("heels %s: centre of mass up %.1f mm, heels at %.1f / %.1f mm, z %.3f\n",
		       rise ? "rise" : "floor", 1e3 * (com[1] - h0),
		       1e3 * r.s->site_xf[r.b.s_heel[0]].p[1], 1e3 * r.s->site_xf[r.b.s_heel[1]].p[1],
		       com[2]);
		printf("toes moved %.2f / %.2f mm\n", 1e3 * dist3(r.s->site_xf[r.b.s_toe[0]].p, toe0[0]),
		       1e3 * dist3(r.s->site_xf[r.b.s_toe[1]].p, toe0[1]));
		/* with the heels down the goal is out of reach and the free foot's
		 * toes give a few mm to it (the elevation shares the balance
		 * constraint's weight): only the root foot is held to 1 mm there */
		for (int k = 0; k < 2; k++)
			if (rise || k == (int)r.b.root)
				assert_true(dist3(r.s->site_xf[r.b.s_toe[k]].p, toe0[k]) < 1e-3);
		assert_int_equal(r.b.steps_taken, 0);
		assert_false(r.b.step.active);
		if (!rise) {
			assert_true(com[1] - h0 < 0.01);
			for (int k = 0; k < 2; k++)
				assert_true(fabs(r.s->site_xf[r.b.s_heel[k]].p[1]) < 3e-3);
			rig_free(&r);
			continue;
		}
		assert_true(fabs(com[1] - h0 - 0.05) < 3e-3);
		for (int k = 0; k < 2; k++) {
			assert_true(r.s->site_xf[r.b.s_heel[k]].p[1] > 0.03);
			const double *toe = r.s->site_xf[r.b.s_toe[k]].p;
			const double *tip = r.s->site_xf[r.b.s_tip[k]].p;
			assert_true(com[2] > fmin(toe[2], tip[2]) && com[2] < fmax(toe[2], tip[2]));
		}
		snapshot(&r, "tiptoe", SIDE);
		rig_free(&r);
	}
}

/* Figure 5.6: dragging the centre of mass forward past the feet takes a step */
static void
test_fig_5_6_step_when_losing_balance(void **unused)
{
	(void)unused;
	struct rig r;
	rig_make(&r, NULL);
	frames(&r, 3);
	behave_move_com(&r.b, r.m, r.s, r.ik, 0, 0.35, 0);
	frames(&r, 60);
	printf("steps %d, margin %.3f m\n", r.b.steps_taken, r.b.bal.margin);
	assert_true(r.b.steps_taken >= 1);
	assert_false(r.b.step.active);
	assert_true(r.b.bal.margin > 0); /* the balance point lies inside the new polygon */
	double side[3] = { 2.8, 1.3, 0.6 };
	snapshot(&r, "fig5.6-step", side);
	rig_free(&r);
}

/* §D.3.1: past a foot's outer edge only the support foot can step, out to the side */
static void
test_step_to_the_side(void **unused)
{
	(void)unused;
	struct rig r;
	rig_make(&r, NULL);
	frames(&r, 3);
	double left0[3], right0[3];
	memcpy(left0, r.s->site_xf[r.b.s_toe[0]].p, sizeof left0);
	memcpy(right0, r.s->site_xf[r.b.s_toe[1]].p, sizeof right0);
	behave_move_com(&r.b, r.m, r.s, r.ik, 0.20, 0, 0); /* 20 cm to the left: past the left foot */
	frames(&r, 80);
	double moved = r.s->site_xf[r.b.s_toe[0]].p[0] - left0[0];
	printf("steps %d, left foot out %.1f cm, margin %.3f m, x %.2f\n", r.b.steps_taken,
	       100 * moved, r.b.bal.margin, r.b.bal.x);
	assert_true(r.b.steps_taken >= 1);
	assert_false(r.b.step.active);
	assert_true(moved > 0.15); /* the left (support) foot stepped out to the left */
	for (int i = 0; i < 3; i++) /* the right foot stayed where it was */
		assert_near(r.s->site_xf[r.b.s_toe[1]].p[i], right0[i], 2e-3);
	assert_true(r.b.bal.margin > 0);
	/* the balance point ends midway between the feet, as the step aimed */
	assert_true(r.b.bal.x > 0.3 && r.b.bal.x < 0.7);
	snapshot(&r, "step-to-the-side", FRONT);
	rig_free(&r);
}

/* the heading of a foot about the vertical, heel to toe tip */
static double
heading(const struct rig *r, int side)
{
	const double *h = r->s->site_xf[r->b.s_heel[side]].p, *t = r->s->site_xf[r->b.s_tip[side]].p;
	return atan2(t[0] - h[0], t[2] - h[2]);
}

/* §D.2.2: a foot moved forward turns with the balance line, toward the stationary foot */
static void
foot_forward(int follow, double *turned, double *line_turned)
{
	struct behave_params p = behave_default_params();
	p.foot_follows_line = follow;
	struct rig r;
	rig_make(&r, &p);
	frames(&r, 3);
	double h0 = heading(&r, 0);
	/* the balance line from the right foot to the left, before and (the foot moved) after */
	double w[2] = { r.b.bal.ref_l[0] - r.b.bal.ref_r[0], r.b.bal.ref_l[1] - r.b.bal.ref_r[1] };
	const double d = 0.10;
	struct xform goal = r.s->site_xf[r.b.s_toe[0]];
	goal.p[2] += d;
	behave_move_foot(&r.b, r.m, r.s, r.ik, BEHAVE_LEFT, &goal);
	frames(&r, 40);
	*turned = atan2(sin(heading(&r, 0) - h0), cos(heading(&r, 0) - h0));
	*line_turned = atan2(w[0], w[1] + d) - atan2(w[0], w[1]);
	for (int i = 0; i < 3; i += 2) /* the toes got there */
		assert_near(r.s->site_xf[r.b.s_toe[0]].p[i], goal.p[i], 3e-3);
	if (follow)
		snapshot(&r, "foot-follows-balance-line", FRONT);
	rig_free(&r);
}

static void
test_foot_orientation_follows_balance_line(void **unused)
{
	(void)unused;
	double turned, line;
	foot_forward(1, &turned, &line);
	printf("follows: foot turned %.1f deg, the line %.1f deg\n", turned / DEG, line / DEG);
	assert_true(line < -10 * DEG); /* the line does turn, toward the right foot */
	assert_near(turned, line, 1.5 * DEG);
	foot_forward(0, &turned, &line);
	printf("global: foot turned %.1f deg\n", turned / DEG);
	assert_near(turned, 0, 1 * DEG);
}

/* stability as data: the alert rises once when the margin drops below the threshold */
static void
test_stability_alert_edges(void **unused)
{
	(void)unused;
	struct rig r;
	rig_make(&r, NULL);
	frames(&r, 3);
	assert_false(r.b.stability_low); /* standing square: far inside */
	assert_false(r.b.stability_changed);
	double m0 = r.b.bal.margin;
	assert_true(m0 > r.b.p.stability_threshold);
	struct behave_params p = r.b.p;
	p.step_when_losing_balance = 0;
	behave_set_params(&r.b, r.m, r.s, r.ik, &p);
	/* lean forward to 95 % of the way to the front edge (Figure 5.2's z): low, said once */
	double front[2];
	balance_point_of(&r.b.bal, r.b.bal.x, 0.95, front);
	double lean[2] = { front[0] - r.b.bal.point[0], front[1] - r.b.bal.point[1] };
	behave_move_com(&r.b, r.m, r.s, r.ik, lean[0], lean[1], 0);
	int rises = 0, falls = 0;
	for (int i = 0; i < 30; i++) {
		frames(&r, 1);
		rises += r.b.stability_changed && r.b.stability_low;
		falls += r.b.stability_changed && !r.b.stability_low;
	}
	printf("margin %.4f -> %.4f m\n", m0, r.b.bal.margin);
	assert_near(r.b.bal.z, 0.95, 0.01);
	assert_true(r.b.bal.margin > 0 && r.b.bal.margin < r.b.p.stability_threshold);
	assert_int_equal(rises, 1);
	assert_int_equal(falls, 0);
	assert_true(r.b.stability_low);
	/* and back: ok, said once */
	behave_move_com(&r.b, r.m, r.s, r.ik, -lean[0] / 2, -lean[1] / 2, 0);
	for (int i = 0; i < 30; i++) {
		frames(&r, 1);
		rises += r.b.stability_changed && r.b.stability_low;
		falls += r.b.stability_changed && !r.b.stability_low;
	}
	assert_int_equal(rises, 1);
	assert_int_equal(falls, 1);
	assert_false(r.b.stability_low);
	rig_free(&r);
}

/* the palm's facing direction (the site's -sigma x axis, human.c) */
static void
palm_normal(const struct rig *r, int side, double n[3])
{
	const double *R = r->s->site_xf[r->b.s_palm[side]].r, sigma = side ? -1 : 1;
	for (int i = 0; i < 3; i++)
		n[i] = -sigma * R[3 * i];
}

/* moves the hand to shoulder + d (chest axes are the world's here) and reports the palm */
static double
palm_facing(struct rig *r, int side, const double d[3], const double want[3], enum hand_region *region)
{
	const double *sh = r->s->site_xf[r->b.s_shoulder[side]].p;
	struct xform g = r->s->site_xf[r->b.s_palm[side]];
	for (int i = 0; i < 3; i++)
		g.p[i] = sh[i] + d[i];
	*region = behave_hand_region(&r->b, r->s, side, g.p);
	behave_predict_hand(&r->b, r->s, side, &g);
	behave_move_hand(&r->b, r->m, r->s, r->ik, side, &g, 0);
	frames(r, 40);
	/* the rule's direction as near as a palm on the line of the arm can face it */
	double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), f[3], w[3], n[3];
	for (int i = 0; i < 3; i++)
		f[i] = d[i] / dl;
	double along = want[0] * f[0] + want[1] * f[1] + want[2] * f[2];
	for (int i = 0; i < 3; i++)
		w[i] = want[i] - along * f[i];
	double wl = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
	palm_normal(r, side, n);
	return acos(fmin(1, (n[0] * w[0] + n[1] * w[1] + n[2] * w[2]) / wl)) / DEG;
}

/* §D.2.4: Labanotation's palm rules as a moved hand changes region */
static void
test_hands_maintain_consistent_orientation(void **unused)
{
	(void)unused;
	struct behave_params p = behave_default_params();
	p.hands_laban = 1;
	struct rig r;
	rig_make(&r, &p);
	frames(&r, 3);
	const int L = BEHAVE_LEFT;
	const double in[3] = { -1, 0, 0 }, forward[3] = { 0, 0, 1 }, backward[3] = { 0, 0, -1 };
	enum hand_region reg;
	/* raised forward to shoulder height: palms face each other (in, for the left hand) */
	double a = palm_facing(&r, L, (double[3]){ 0, -0.05, 0.50 }, in, &reg);
	printf("forward: palm %.1f deg from facing in\n", a);
	assert_int_equal(reg, REGION_FORWARD_UP);
	assert_true(a < 10);
	/* out to the side: palms face forward */
	a = palm_facing(&r, L, (double[3]){ 0.50, -0.05, 0.05 }, forward, &reg);
	printf("side: palm %.1f deg from facing forward\n", a);
	assert_int_equal(reg, REGION_SIDE);
	assert_true(a < 10);
	/* a small move within the region keeps the orientation as it is */
	double before[3], after[3];
	palm_normal(&r, L, before);
	palm_facing(&r, L, (double[3]){ 0.48, 0.02, 0.10 }, forward, &reg);
	palm_normal(&r, L, after);
	assert_int_equal(reg, REGION_SIDE);
	assert_true(before[0] * after[0] + before[1] * after[1] + before[2] * after[2] > cos(2 * DEG));
	/* across the body: palms face backward */
	a = palm_facing(&r, L, (double[3]){ -0.32, -0.15, 0.30 }, backward, &reg);
	printf("across: palm %.1f deg from facing backward\n", a);
	assert_int_equal(reg, REGION_ACROSS);
	assert_true(a < 10);
	/* hanging by the side again: palms face in */
	a = palm_facing(&r, L, (double[3]){ 0.02, -0.60, 0.02 }, in, &reg);
	printf("hanging: palm %.1f deg from facing in\n", a);
	assert_int_equal(reg, REGION_HANG);
	assert_true(a < 10);
	snapshot(&r, "hands-laban", FRONT);
	rig_free(&r);
}

/* §D.1.1: seated, the heel holds the foot (position and orientation); balance rests */
static void
test_seated_heels_hold_the_feet(void **unused)
{
	(void)unused;
	struct rig r;
	rig_make(&r, NULL);
	frames(&r, 3);
	struct behave_params p = r.b.p;
	p.seated = 1;
	behave_set_params(&r.b, r.m, r.s, r.ik, &p);
	assert_int_equal(r.b.root, BALANCE_ROOT_LOWER_TORSO);
	assert_int_equal(behave_foot_site(&r.b, 1), r.b.s_heel[1]);
	struct xform pelvis0 = r.s->site_xf[r.b.s_lower];
	/* the right heel 10 cm forward, 5 cm up, turned 15 degrees out */
	struct xform goal = r.s->site_xf[r.b.s_heel[1]];
	double turn[9];
	mathx_rot_y(-15 * DEG, turn);
	mathx_mat3_mul(turn, goal.r, goal.r);
	goal.p[2] += 0.10;
	goal.p[1] += 0.05;
	behave_move_foot(&r.b, r.m, r.s, r.ik, BEHAVE_RIGHT, &goal);
	frames(&r, 40);
	const struct xform *heel = &r.s->site_xf[r.b.s_heel[1]];
	for (int i = 0; i < 3; i++)
		assert_near(heel->p[i], goal.p[i], 1e-3);
	double tr = 0; /* the angle between the heel's frame and the goal's */
	for (int i = 0; i < 3; i++)
		for (int k = 0; k < 3; k++)
			tr += heel->r[3 * k + i] * goal.r[3 * k + i];
	printf("seated: heel %.2f mm, %.2f deg from its goal\n",
	       1e3 * sqrt(pow(heel->p[0] - goal.p[0], 2) + pow(heel->p[1] - goal.p[1], 2) +
			  pow(heel->p[2] - goal.p[2], 2)),
	       acos(fmin(1, (tr - 1) / 2)) / DEG);
	assert_true(acos(fmin(1, (tr - 1) / 2)) < 1 * DEG);
	/* the root stayed; the other foot stayed */
	for (int i = 0; i < 3; i++)
		assert_near(r.s->site_xf[r.b.s_lower].p[i], pelvis0.p[i], 1e-9);
	assert_false(ik_get(r.ik, r.b.c_balance)->enabled);
	assert_false(ik_get(r.ik, r.b.c_toe[1])->enabled);
	assert_int_equal(r.b.steps_taken, 0);
	snapshot(&r, "seated-heel-moved", FRONT);
	rig_free(&r);
}

/* Figure 5.7: bending forward 45 degrees shifts the hips back, balanced, feet planted */
static void
test_fig_5_7_bend_torso_keeps_balance(void **unused)
{
	(void)unused;
	struct rig r;
	rig_make(&r, NULL);
	frames(&r, 3);
	double feet0[2][3], hips0 = r.s->site_xf[r.b.s_pelvis].p[2];
	for (int k = 0; k < 2; k++)
		memcpy(feet0[k], r.s->site_xf[r.b.s_toe[k]].p, sizeof feet0[k]);
	double total[3] = { 45 * DEG, 0, 0 };
	struct spine_flavor waist = spine_bend_from_waist();
	assert_int_equal(behave_bend_torso(&r.b, r.m, r.s, r.ik, total, &waist), 0);
	frames(&r, 40);
	double hips = r.s->site_xf[r.b.s_pelvis].p[2];
	double com[2] = { r.s->com[0], r.s->com[2] };
	printf("hips moved %.1f cm back; centre of mass %.2f mm from the balance point\n",
	       100 * (hips0 - hips), 1e3 * dist2(com, r.b.bal_point));
	assert_true(hips < hips0 - 0.03);
	assert_true(dist2(com, r.b.bal_point) < 5e-3);
	for (int k = 0; k < 2; k++)
		for (int i = 0; i < 3; i++)
			assert_near(r.s->site_xf[r.b.s_toe[k]].p[i], feet0[k][i], 1e-3);
	double side[3] = { 2.8, 1.3, 0.6 };
	snapshot(&r, "fig5.7-bend", side);
	rig_free(&r);
}

/* hands on hips survive a torso bend (§D.1.5) */
static void
test_hands_on_hips_survive_a_bend(void **unused)
{
	(void)unused;
	struct behave_params p = behave_default_params();
	p.hand[0] = p.hand[1] = HAND_ON_HIPS;
	struct rig r;
	rig_make(&r, &p);
	frames(&r, 30);
	double total[3] = { 30 * DEG, 10 * DEG, 0 };
	struct spine_flavor waist = spine_bend_from_waist();
	behave_bend_torso(&r.b, r.m, r.s, r.ik, total, &waist);
	frames(&r, 40);
	for (int k = 0; k < 2; k++) {
		double pe, oe;
		ik_constraint_error(r.ik, r.m, r.s, r.b.c_hand[k], &pe, &oe);
		assert_true(pe < 2e-3);
	}
	snapshot(&r, "hands-on-hips-bent", FRONT);
	rig_free(&r);
}

/* Figure 5.8: curling the pelvis with "keep vertical" leaves the chest vertical */
static void
test_fig_5_8_rotate_pelvis_keeps_chest_vertical(void **unused)
{
	(void)unused;
	struct rig r;
	rig_make(&r, NULL);
	frames(&r, 3);
	double q[4], r9[9], axis[3] = { 1, 0, 0 };
	mathx_quat_axis_angle(axis, 20 * DEG, q); /* curl the hips under */
	mathx_quat_to_mat(q, r9);
	behave_rotate_pelvis(&r.b, r.m, r.s, r.ik, r9);
	frames(&r, 30);
	const double *cr = r.s->site_xf[r.b.s_chest].r, *pr = r.s->site_xf[r.b.s_pelvis].r;
	double chest_tilt = acos(fmin(1, cr[4])) / DEG, pelvis_tilt = acos(fmin(1, pr[4])) / DEG;
	printf("pelvis tilted %.1f deg, chest %.2f deg from vertical\n", pelvis_tilt, chest_tilt);
	assert_true(pelvis_tilt > 12);
	assert_true(chest_tilt < 2);
	double side[3] = { 2.8, 1.3, 0.6 };
	snapshot(&r, "fig5.8-pelvis-curled", side);
	rig_free(&r);
}

static void
test_fig_5_8_twisting_the_pelvis_takes_a_step(void **unused)
{
	(void)unused;
	struct rig r;
	rig_make(&r, NULL);
	frames(&r, 3);
	double q[4], r9[9], axis[3] = { 0, 1, 0 };
	mathx_quat_axis_angle(axis, 70 * DEG, q);
	mathx_quat_to_mat(q, r9);
	behave_rotate_pelvis(&r.b, r.m, r.s, r.ik, r9);
	r.b.p.pelvis_follows_feet = 1;
	frames(&r, 80);
	printf("steps after a 70 deg twist: %d\n", r.b.steps_taken);
	assert_true(r.b.steps_taken >= 1);
	snapshot(&r, "fig5.8-twist-step", FRONT);
	rig_free(&r);
}

/* Figures 5.9 and 5.10: the hand reaches, head and eyes keep fixating, the body holds */
static void
test_fig_5_9_5_10_hand_head_eyes(void **unused)
{
	(void)unused;
	struct rig r;
	rig_make(&r, NULL);
	frames(&r, 3);
	double look[3] = { 0.5, 1.2, 2.0 };
	behave_move_head(&r.b, r.ik, look);
	behave_move_eyes(&r.b, r.ik, look);
	double feet0[2][3];
	for (int k = 0; k < 2; k++)
		memcpy(feet0[k], r.s->site_xf[r.b.s_toe[k]].p, sizeof feet0[k]);
	struct xform g = r.s->site_xf[r.b.s_palm[0]];
	g.p[1] += 0.35;
	g.p[2] += 0.30;
	behave_move_hand(&r.b, r.m, r.s, r.ik, BEHAVE_LEFT, &g, 0);
	frames(&r, 40);
	double pe, oe;
	ik_constraint_error(r.ik, r.m, r.s, r.b.c_hand[0], &pe, &oe);
	assert_true(pe < 1e-3);
	for (int k = 0; k < 2; k++)
		for (int i = 0; i < 3; i++)
			assert_near(r.s->site_xf[r.b.s_toe[k]].p[i], feet0[k][i], 1e-3);
	/* the head and both eyes aim at the point */
	int aims[3] = { r.b.c_head, r.b.c_eye[0], r.b.c_eye[1] };
	for (int i = 0; i < 3; i++) {
		ik_constraint_error(r.ik, r.m, r.s, aims[i], &pe, &oe);
		assert_true(oe < 1 * DEG);
	}
	/* move the body: the fixation holds */
	behave_move_com(&r.b, r.m, r.s, r.ik, 0.05, 0.03, 0);
	frames(&r, 30);
	for (int i = 0; i < 3; i++) {
		ik_constraint_error(r.ik, r.m, r.s, aims[i], &pe, &oe);
		assert_true(oe < 1 * DEG);
	}
	snapshot(&r, "fig5.9-reach-and-look", FRONT);
	rig_free(&r);
}

static void
test_hands_on_hips(void **unused)
{
	(void)unused;
	struct behave_params p = behave_default_params();
	p.hand[0] = p.hand[1] = HAND_ON_HIPS;
	struct rig r;
	rig_make(&r, &p);
	frames(&r, 40);
	for (int k = 0; k < 2; k++) {
		double pe, oe;
		ik_constraint_error(r.ik, r.m, r.s, r.b.c_hand[k], &pe, &oe);
		assert_true(pe < 2e-3);
	}
	snapshot(&r, "hands-on-hips", FRONT);
	rig_free(&r);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_unpack_refuses_numbers_that_are_not_its_own),
		cmocka_unit_test(test_fig_5_3_balance_point_follows_feet),
		cmocka_unit_test(test_fig_5_4_shift_com_feet_held),
		cmocka_unit_test(test_fig_5_5_squat_reroots_at_the_lower_torso),
		cmocka_unit_test(test_tiptoe_needs_heels_allowed_to_rise),
		cmocka_unit_test(test_fig_5_6_step_when_losing_balance),
		cmocka_unit_test(test_step_to_the_side),
		cmocka_unit_test(test_foot_orientation_follows_balance_line),
		cmocka_unit_test(test_stability_alert_edges),
		cmocka_unit_test(test_hands_maintain_consistent_orientation),
		cmocka_unit_test(test_seated_heels_hold_the_feet),
		cmocka_unit_test(test_fig_5_7_bend_torso_keeps_balance),
		cmocka_unit_test(test_hands_on_hips_survive_a_bend),
		cmocka_unit_test(test_fig_5_8_rotate_pelvis_keeps_chest_vertical),
		cmocka_unit_test(test_fig_5_8_twisting_the_pelvis_takes_a_step),
		cmocka_unit_test(test_fig_5_9_5_10_hand_head_eyes),
		cmocka_unit_test(test_hands_on_hips),
	};
	return cmocka_run_group_tests_name("behave", tests, NULL, NULL);
}
