/*
 * test_load_set.c - the loads a figure feels (load_set.h) against the rule
 * written out by hand: the lever rule between two palms on the floor plane,
 * clamped to the palms; equal halves for palms one above the other (closer
 * than 1 cm on the floor plane); the shares together exactly the weight at
 * the object's centre of mass (load_set_weights); an object held only with
 * hold hand carried by no one.
 *
 * The palms and the object's centre of mass are put where each case wants
 * them by writing the frames load_set reads (the palms' site frames, the
 * object's centre of mass); the segments' frames stay the posture's.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "test_util.h"

#include <stdlib.h>

#include "figure/human.h"
#include "figure/kin.h"
#include "pose/attach.h"
#include "pose/env.h"
#include "pose/load_set.h"

static struct env e;
static int jack, crate;

static int
setup(void **unused)
{
	(void)unused;
	char err[300];
	env_init(&e);
	struct human_def hd = human_default_def(HUMAN_MALE);
	jack = env_add_figure(&e, human_build(&hd, err, sizeof err), "jack", 1, &hd, NULL);
	crate = env_add_figure(&e, human_build(&hd, err, sizeof err), "crate", 1, &hd, NULL);
	assert_true(jack >= 0 && crate >= 0);
	struct env_figure *f = &e.fig[jack];
	f->behave = calloc(1, sizeof *f->behave);
	assert_non_null(f->behave);
	assert_int_equal(behave_attach(f->behave, f->model, f->state, f->ik, NULL), 0);
	return 0;
}

static int
teardown(void **unused)
{
	(void)unused;
	env_clear(&e);
	return 0;
}

/* the palms at pl and pr, the crate's centre of mass at c */
static void
place(const double pl[3], const double pr[3], const double c[3])
{
	struct env_figure *f = &e.fig[jack];
	memcpy(f->state->site_xf[f->behave->s_palm[0]].p, pl, 3 * sizeof *pl);
	memcpy(f->state->site_xf[f->behave->s_palm[1]].p, pr, 3 * sizeof *pr);
	memcpy(e.fig[crate].state->com, c, 3 * sizeof *c);
}

/* the loads on jack: the left and right hands' weight shares (the set's order: left, right) */
static void
shares(double *left, double *right, struct ext_load set[LOAD_SET_MAX], int *n)
{
	struct load_origin from[LOAD_SET_MAX];
	*n = load_set_of(&e, jack, set, from, LOAD_SET_MAX);
	assert_int_equal(*n, 2);
	assert_int_equal(from[0].side, 0);
	assert_int_equal(from[1].side, 1);
	assert_int_equal(from[0].carried, crate);
	*left = from[0].share;
	*right = from[1].share;
}

/* the shares together: the crate's weight at its centre of mass, force and point */
static void
whole_weight_at_com(const struct ext_load *set, int n)
{
	const struct env_figure *f = &e.fig[jack];
	double mass = e.fig[crate].model->total_mass, com[3], fy = 0;
	assert_near(load_set_weights(f->model, f->state, set, n, com), mass, 1e-12);
	for (int i = 0; i < 3; i++)
		assert_near(com[i], e.fig[crate].state->com[i], 1e-12);
	for (int k = 0; k < n; k++)
		fy += set[k].force[1];
	assert_near(fy, -mass * LOAD_GRAVITY, 1e-9);
}

static void
test_two_hands_share_by_the_lever_rule_on_the_floor_plane(void **unused)
{
	(void)unused;
	char err[200];
	assert_int_equal(attach_grab(&e, jack, 1, crate, err, sizeof err), 0);
	assert_int_equal(attach_local(&e, jack, ATTACH_HAND, 0, crate, 0, err, sizeof err), 0);
	struct ext_load set[LOAD_SET_MAX];
	int n;
	double l, r;
	/* palms 0.4 m apart along x, the centre of mass 0.1 m from the left one and 0.3 m
	 * forward and 0.2 m lower: 3/4 left, 1/4 right (heights and the forward offset play
	 * no part) */
	place((const double[3]){ 0.2, 1.0, 0.3 }, (const double[3]){ -0.2, 1.0, 0.3 },
	      (const double[3]){ 0.1, 0.8, 0.6 });
	shares(&l, &r, set, &n);
	assert_near(l, 0.75, 1e-15);
	assert_near(r, 0.25, 1e-15);
	whole_weight_at_com(set, n);
	/* along a slanted line, at different heights: t = (c - p1).d / |d|^2 */
	place((const double[3]){ 0.1, 1.1, 0.2 }, (const double[3]){ -0.2, 0.9, 0.6 },
	      (const double[3]){ 0.0, 0.5, 0.5 });
	shares(&l, &r, set, &n);
	double t = ((0.0 - 0.1) * -0.3 + (0.5 - 0.2) * 0.4) / (0.3 * 0.3 + 0.4 * 0.4);
	assert_near(r, t, 1e-15);
	assert_near(l, 1 - t, 1e-15);
	whole_weight_at_com(set, n);
	/* beyond the right palm: all on it, none pushed down by the left */
	place((const double[3]){ 0.2, 1.0, 0.3 }, (const double[3]){ -0.2, 1.0, 0.3 },
	      (const double[3]){ -0.5, 1.0, 0.3 });
	shares(&l, &r, set, &n);
	assert_true(l == 0 && r == 1);
	whole_weight_at_com(set, n);
	/* ... and beyond the left one: all on the left */
	place((const double[3]){ 0.2, 1.0, 0.3 }, (const double[3]){ -0.2, 1.0, 0.3 },
	      (const double[3]){ 0.45, 1.0, 0.1 });
	shares(&l, &r, set, &n);
	assert_true(l == 1 && r == 0);
	whole_weight_at_com(set, n);
}

static void
test_palms_one_above_the_other_share_equally(void **unused)
{
	(void)unused;
	struct ext_load set[LOAD_SET_MAX];
	int n;
	double l, r;
	/* 9 mm apart on the floor plane, 30 cm apart in height: halves */
	place((const double[3]){ 0.0, 1.2, 0.3 }, (const double[3]){ 0.009, 0.9, 0.3 },
	      (const double[3]){ 0.2, 1.0, 0.5 });
	shares(&l, &r, set, &n);
	assert_true(l == 0.5 && r == 0.5);
	whole_weight_at_com(set, n);
	/* 11 mm apart: the lever rule again, clamped (the centre of mass beyond the right) */
	place((const double[3]){ 0.0, 1.2, 0.3 }, (const double[3]){ 0.011, 0.9, 0.3 },
	      (const double[3]){ 0.2, 1.0, 0.5 });
	shares(&l, &r, set, &n);
	assert_true(l == 0 && r == 1);
	whole_weight_at_com(set, n);
}

static void
test_an_object_held_by_hold_hand_alone_is_carried_by_no_one(void **unused)
{
	(void)unused;
	struct ext_load set[LOAD_SET_MAX];
	double mid[3];
	int hf[LOAD_SET_HANDS], hs[LOAD_SET_HANDS];
	double sh[LOAD_SET_HANDS];
	assert_int_equal(attach_release(&e, jack, ATTACH_HAND, 1), 1); /* the grab let go */
	assert_int_equal(load_set_of(&e, jack, set, NULL, LOAD_SET_MAX), 0);
	assert_int_equal(load_set_hands(&e, crate, hf, hs, sh, mid), 0);
	/* the crate's own load stays its own, and a too small array is refused */
	struct env_load w = { .fig = crate, .site = model_find_site(e.fig[crate].model, "head.origin"),
			      .mass = 2, .force = { 0, -2 * LOAD_GRAVITY, 0 } };
	assert_true(env_add_load(&e, NULL, &w) >= 0);
	assert_int_equal(load_set_of(&e, crate, set, NULL, LOAD_SET_MAX), 1);
	assert_int_equal(load_set_of(&e, crate, set, NULL, 0), -1);
	/* a weight whose force is not its mass's is no load */
	w.force[1] = -2 * 9.81;
	assert_int_equal(env_add_load(&e, NULL, &w), ENV_BAD);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_two_hands_share_by_the_lever_rule_on_the_floor_plane),
		cmocka_unit_test(test_palms_one_above_the_other_share_equally),
		cmocka_unit_test(test_an_object_held_by_hold_hand_alone_is_carried_by_no_one),
	};
	return cmocka_run_group_tests(tests, setup, teardown);
}
