/*
 * test_reach.c - "can she reach it?" on a copy of the state (pose/reach.h):
 * a target in front of the shoulder is reached; one far beyond the arm is
 * not, by the distance the arm's geometry says (the chain's pivots, by the
 * triangle inequality), with the stretched elbow named among the limits;
 * the body reaches lower than the arm alone; and the posture the figure
 * shows is untouched.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "figure/human.h"
#include "figure/kin.h"
#include "pose/reach.h"

struct rig {
	struct model *m;
	struct state *s;
	struct reach *r;
};

static void
rig_make(struct rig *g)
{
	char err[200];
	struct human_def hd = human_default_def(HUMAN_MALE);
	g->m = human_build(&hd, err, sizeof err);
	assert_non_null(g->m);
	g->s = state_make(g->m);
	kin_update(g->m, g->s);
	g->r = reach_make(g->m);
	assert_non_null(g->r);
}

static void
rig_free(struct rig *g)
{
	reach_free(g->r);
	state_free(g->s);
	model_free(g->m);
}

static double
dist(const double *a, const double *b)
{
	return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
		    (a[2] - b[2]) * (a[2] - b[2]));
}

static const double *
site_p(const struct rig *g, const struct state *s, const char *name)
{
	int i = model_find_site(g->m, name);
	assert_true(i >= 0);
	return s->site_xf[i].p;
}

/* the world point joint name turns about (its first dof's pivot) */
static const double *
pivot(const struct rig *g, const char *name)
{
	int j = model_find_joint(g->m, name);
	assert_true(j >= 0);
	return &g->s->dof_pivot_w[3 * g->m->jnt_dof0[j]];
}

static void
request(struct reach_request *q, const double *t, enum reach_mode mode)
{
	memset(q, 0, sizeof *q);
	q->side = BEHAVE_RIGHT;
	memcpy(q->target, t, sizeof q->target);
	q->mode = mode;
	q->balance = 1;
}

static void
test_in_front_of_the_shoulder_is_reached(void **state)
{
	(void)state;
	struct rig g;
	rig_make(&g);
	const double *sh = site_p(&g, g.s, "clavicle_r.shoulder_r");
	const double *palm = site_p(&g, g.s, "hand_r.palm");
	/* halfway from the hanging palm to straight ahead of the shoulder, 35 cm out */
	double fwd[3] = { 0, 0, 1 }, t[3];
	for (int i = 0; i < 3; i++)
		t[i] = 0.5 * (palm[i] + sh[i] + 0.35 * fwd[i]);
	uint64_t before = state_hash(g.m, g.s);
	for (enum reach_mode md = REACH_ARM; md <= REACH_BODY; md++) {
		struct reach_request q;
		struct reach_result res;
		request(&q, t, md);
		assert_int_equal(reach_solve(g.r, g.m, g.s, NULL, NULL, 0, &q, &res), 0);
		assert_true(res.reached);
		assert_true(res.distance <= REACH_TOL_POS);
		/* the posture it reports has the palm there */
		assert_true(dist(site_p(&g, reach_posture(g.r), "hand_r.palm"), t) <= REACH_TOL_POS);
		assert_true(res.margin > 0); /* standing, balanced */
	}
	assert_true(state_hash(g.m, g.s) == before); /* the copy was solved, not the figure */
	rig_free(&g);
}

static void
test_beyond_the_arm_falls_short_by_the_geometry(void **state)
{
	(void)state;
	struct rig g;
	rig_make(&g);
	/* the most the palm can be from the clavicle's pivot: the chain's links end to end */
	const double *c = pivot(&g, "clavicle_r"), *s = pivot(&g, "shoulder_r"),
		     *e = pivot(&g, "elbow_r"), *w = pivot(&g, "wrist_r");
	const double *palm = site_p(&g, g.s, "hand_r.palm");
	double longest = dist(c, s) + dist(s, e) + dist(e, w) + dist(w, palm);
	double t[3] = { c[0] - 1.5, c[1], c[2] }; /* straight out to the right */
	double bound = dist(t, c) - longest;
	struct reach_request q;
	struct reach_result res;
	request(&q, t, REACH_ARM);
	uint64_t before = state_hash(g.m, g.s);
	assert_int_equal(reach_solve(g.r, g.m, g.s, NULL, NULL, 0, &q, &res), 0);
	assert_false(res.reached);
	assert_true(res.distance >= bound - 1e-6);   /* no arm gets nearer */
	assert_true(res.distance <= bound + 0.005); /* out to the side it stretches straight */
	int elbow = model_find_joint(g.m, "elbow_r"), named = 0;
	for (int i = 0; i < res.nlimiting; i++)
		named |= res.limiting[i] == elbow;
	assert_true(named); /* straight: the elbow on its extension limit */
	assert_true(state_hash(g.m, g.s) == before);
	rig_free(&g);
}

static void
test_the_body_reaches_the_floor_the_arm_does_not(void **state)
{
	(void)state;
	struct rig g;
	rig_make(&g);
	const double *sh = site_p(&g, g.s, "clavicle_r.shoulder_r");
	/* 40 cm ahead of the shoulder, 25 cm above the floor */
	double t[3] = { sh[0], 0.25, sh[2] + 0.4 };
	struct reach_request q;
	struct reach_result arm, body;
	request(&q, t, REACH_ARM);
	assert_int_equal(reach_solve(g.r, g.m, g.s, NULL, NULL, 0, &q, &arm), 0);
	request(&q, t, REACH_BODY);
	assert_int_equal(reach_solve(g.r, g.m, g.s, NULL, NULL, 0, &q, &body), 0);
	assert_false(arm.reached);
	assert_true(body.reached);
	assert_true(body.margin >= -1e-3); /* balance held: the centre of mass over the feet */
	/* the feet stayed where they stood */
	assert_true(dist(site_p(&g, reach_posture(g.r), "toes_r.toe"), site_p(&g, g.s, "toes_r.toe")) < 1e-3);
	assert_true(dist(site_p(&g, reach_posture(g.r), "foot_l.heel"), site_p(&g, g.s, "foot_l.heel")) < 1e-3);
	rig_free(&g);
}

static void
test_bad_requests_are_refused(void **state)
{
	(void)state;
	struct rig g;
	rig_make(&g);
	struct reach_request q;
	struct reach_result res;
	double t[3] = { 0, 1, NAN };
	request(&q, t, REACH_ARM);
	assert_int_equal(reach_solve(g.r, g.m, g.s, NULL, NULL, 0, &q, &res), -1);
	t[2] = 0.3;
	request(&q, t, REACH_ARM);
	q.side = 7;
	assert_int_equal(reach_solve(g.r, g.m, g.s, NULL, NULL, 0, &q, &res), -1);
	rig_free(&g);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_in_front_of_the_shoulder_is_reached),
		cmocka_unit_test(test_beyond_the_arm_falls_short_by_the_geometry),
		cmocka_unit_test(test_the_body_reaches_the_floor_the_arm_does_not),
		cmocka_unit_test(test_bad_requests_are_refused),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
