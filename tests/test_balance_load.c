/*
 * test_balance_load.c - balance feels the load: the centre of mass the
 * behaviours keep over the support includes the weights the figure carries
 * (point_mass.h), checked against the combined centre of mass worked out
 * here from the segments' centres of mass and the weight's site, and the
 * lever rule for how far the body must lean back under a weight held out.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "test_util.h"
#include "test_human.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pose/behave.h"
#include "figure/kin.h"

#define BOX_KG 15.0

struct rig {
	struct model *m;
	struct state *s;
	struct ik *ik;
	struct behave b;
	struct ik_options opt;
};

static void
rig_make(struct rig *r)
{
	r->m = test_human();
	r->s = state_make(r->m);
	kin_update(r->m, r->s);
	r->ik = ik_make(r->m, 32);
	assert_int_equal(behave_attach(&r->b, r->m, r->s, r->ik, NULL), 0);
	r->opt = ik_default_options();
	r->opt.budget_us = 0; /* to convergence: the test is about where things go */
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

/* a weight at a site of the figure, as a point mass on the site's segment */
static struct point_mass
weight_at(const struct model *m, const char *site, double kg)
{
	int k = test_site(m, site);
	struct point_mass pm = { m->site_seg[k], { 0, 0, 0 }, kg };
	memcpy(pm.local, m->site_loc[k].p, sizeof pm.local);
	return pm;
}

/*
 * The centre of mass of the segments (kin's segment centres of mass and the
 * model's masses) and of a weight at a site, summed here: sum m c / sum m.
 * kg 0: the body alone.
 */
static void
combined_com(const struct model *m, const struct state *s, int site, double kg, double dest[3])
{
	double sum[3] = { 0, 0, 0 }, total = 0;
	for (int g = 0; g < m->nseg; g++) {
		for (int r = 0; r < 3; r++)
			sum[r] += m->seg_mass[g] * s->seg_com_w[3 * g + r];
		total += m->seg_mass[g];
	}
	for (int r = 0; r < 3; r++)
		sum[r] += kg * s->site_xf[site].p[r];
	total += kg;
	for (int r = 0; r < 3; r++)
		dest[r] = sum[r] / total;
}

static double
body_mass(const struct model *m)
{
	double total = 0;
	for (int g = 0; g < m->nseg; g++)
		total += m->seg_mass[g];
	return total;
}

static void
test_balance_point_is_the_combined_centre_of_mass(void **unused)
{
	(void)unused;
	struct rig r;
	rig_make(&r);
	frames(&r, 3);
	int palm = test_site(r.m, "hand_r.palm");
	double want[3];
	/* without a load: the body's own */
	behave_measure(&r.b, r.m, r.s);
	combined_com(r.m, r.s, palm, 0, want);
	assert_near(r.b.bal.point[0], want[0], 1e-9);
	assert_near(r.b.bal.point[1], want[2], 1e-9);
	/* 15 kg in the right hand: the body's and the box's together */
	struct point_mass box = weight_at(r.m, "hand_r.palm", BOX_KG);
	assert_int_equal(behave_set_masses(&r.b, r.m, r.s, &box, 1), 0);
	behave_measure(&r.b, r.m, r.s);
	combined_com(r.m, r.s, palm, BOX_KG, want);
	for (int i = 0; i < 3; i++)
		assert_near(r.b.bal.com[i], want[i], 1e-9);
	assert_near(r.b.bal.point[0], want[0], 1e-9);
	assert_near(r.b.bal.point[1], want[2], 1e-9);
	/* the hand's 15 kg moved it: the test is not one of a load too light to tell */
	double body[3];
	combined_com(r.m, r.s, palm, 0, body);
	assert_true(hypot(want[0] - body[0], want[2] - body[2]) > 0.01);
	/* what the solver holds is the same point */
	double held[3];
	ik_set_point_masses(r.ik, r.m, &box, 1);
	ik_com(r.ik, r.s, held);
	for (int i = 0; i < 3; i++)
		assert_near(held[i], want[i], 1e-9);
	rig_free(&r);
}

static void
test_masses_the_figure_cannot_carry_are_refused(void **unused)
{
	(void)unused;
	struct rig r;
	rig_make(&r);
	struct point_mass ok = weight_at(r.m, "hand_r.palm", BOX_KG);
	assert_int_equal(behave_set_masses(&r.b, r.m, r.s, &ok, 1), 0);
	struct point_mass bad[4] = { ok, ok, ok, ok };
	bad[0].seg = r.m->nseg;
	bad[1].mass = 0;
	bad[2].mass = -1;
	bad[3].local[1] = NAN;
	for (int i = 0; i < 4; i++) {
		assert_int_equal(behave_set_masses(&r.b, r.m, r.s, &bad[i], 1), -1);
		assert_int_equal(ik_set_point_masses(r.ik, r.m, &bad[i], 1), -1);
	}
	struct point_mass many[POINT_MASS_MAX + 1];
	for (int i = 0; i <= POINT_MASS_MAX; i++)
		many[i] = ok;
	assert_int_equal(behave_set_masses(&r.b, r.m, r.s, many, POINT_MASS_MAX + 1), -1);
	/* nothing changed: the one good weight is still carried */
	assert_int_equal(r.b.nmass, 1);
	assert_near(r.b.mass[0].mass, BOX_KG, 0);
	rig_free(&r);
}

/* the weights among loads: a pure force has no mass and moves no centre of mass */
static void
test_only_weights_become_point_masses(void **unused)
{
	(void)unused;
	struct ext_load l[4] = {
		{ 3, { 0.1, 0, 0 }, { 0, -BOX_KG * LOAD_GRAVITY, 0 }, { 0, 0, 0 }, BOX_KG },
		{ 4, { 0, 0.2, 0 }, { 50, 0, 0 }, { 0, 0, 0 }, 0 },
		{ 5, { 0, 0, 0.3 }, { 0, -9.80665, 0 }, { 0, 0, 0 }, 1 },
		/* a second weight on segment 3: one mass of 20 kg at their centre */
		{ 3, { 0.1, 0.4, 0 }, { 0, -5 * LOAD_GRAVITY, 0 }, { 0, 0, 0 }, 5 },
	};
	struct point_mass pm[2];
	assert_int_equal(point_mass_of_loads(l, 4, pm, 2), 2);
	assert_int_equal(pm[0].seg, 3);
	assert_near(pm[0].mass, 20, 0);
	assert_near(pm[0].local[0], 0.1, 1e-15);
	assert_near(pm[0].local[1], 5 * 0.4 / 20, 1e-15);
	assert_int_equal(pm[1].seg, 5);
	assert_near(pm[1].local[2], 0.3, 0);
	assert_near(pm[1].mass, 1, 0);
	assert_int_equal(point_mass_of_loads(l, 4, pm, 1), -1);
}

/* the right hand out in front at chest height, with or without the box in it */
static void
hold_out(struct rig *r, int loaded, struct xform *goal)
{
	rig_make(r);
	frames(r, 3);
	*goal = r->s->site_xf[r->b.s_palm[1]];
	goal->p[1] += 0.40;
	goal->p[2] += 0.40;
	behave_move_hand(&r->b, r->m, r->s, r->ik, BEHAVE_RIGHT, goal, 0);
	if (loaded) {
		struct point_mass box = weight_at(r->m, "hand_r.palm", BOX_KG);
		assert_int_equal(behave_set_masses(&r->b, r->m, r->s, &box, 1), 0);
	}
	frames(r, 60);
	double pe, oe;
	ik_constraint_error(r->ik, r->m, r->s, r->b.c_hand[1], &pe, &oe);
	assert_true(pe < 1e-3);
}

static double
along(const double a[2], const double b[2], const double f[2])
{
	return (a[0] - b[0]) * f[0] + (a[1] - b[1]) * f[1];
}

static void
test_a_box_held_out_in_front_moves_the_hips_back(void **unused)
{
	(void)unused;
	struct rig a, b;
	struct xform ga, gb;
	hold_out(&a, 0, &ga);
	hold_out(&b, 1, &gb);
	int palm = test_site(b.m, "hand_r.palm");
	/* the same feet and held balance parameters: the same balance point */
	assert_near(a.b.bal_point[0], b.b.bal_point[0], 1e-6);
	assert_near(a.b.bal_point[1], b.b.bal_point[1], 1e-6);
	const double *bp = b.b.bal_point, *fwd = b.b.bal.forward;
	/* loaded: the combined centre of mass settles over the balance point */
	double with[3];
	combined_com(b.m, b.s, palm, BOX_KG, with);
	double off[2] = { with[0] - bp[0], with[2] - bp[1] };
	printf("combined off the balance point %.6f m\n", hypot(off[0], off[1]));
	assert_true(hypot(off[0], off[1]) < 2e-4);
	/* the lever rule: for M c + m p = (M + m) bp the body's own centre of mass
	 * goes (m / M)(p - bp) back from the balance point */
	double M = body_mass(b.m), ca[3], cb[3];
	combined_com(a.m, a.s, palm, 0, ca);
	combined_com(b.m, b.s, palm, 0, cb);
	double p[2] = { b.s->site_xf[palm].p[0], b.s->site_xf[palm].p[2] };
	double lever = -(BOX_KG / M) * along(p, bp, fwd);
	double ca2[2] = { ca[0], ca[2] }, cb2[2] = { cb[0], cb[2] };
	double body_shift = along(cb2, ca2, fwd);
	/* the pelvis with it */
	int pel = b.b.s_pelvis;
	double pa[2] = { a.s->site_xf[pel].p[0], a.s->site_xf[pel].p[2] };
	double pb[2] = { b.s->site_xf[pel].p[0], b.s->site_xf[pel].p[2] };
	double pelvis_shift = along(pb, pa, fwd);
	printf("box %.3f m ahead; body com shift %.4f m (lever rule %.4f); pelvis shift %.4f m\n",
	       along(p, bp, fwd), body_shift, lever, pelvis_shift);
	assert_true(along(p, bp, fwd) > 0.2); /* the box is well out in front */
	assert_near(body_shift, lever, 5e-4);
	assert_true(pelvis_shift < 0);
	assert_true(pelvis_shift < 0.5 * lever && pelvis_shift > 2 * lever);
	rig_free(&a);
	rig_free(&b);
}

/*
 * A held elevation holds the body where it stands when a weight is taken
 * up: the centre of mass balanced jumps with the weight, the height held
 * with it, and the body does not rise to bring it back. A state unpacked
 * (a session, undo) was packed with its weights: taking them up again
 * moves nothing.
 */
static void
test_a_held_elevation_keeps_the_body_where_it_stands(void **unused)
{
	(void)unused;
	struct rig r;
	rig_make(&r);
	frames(&r, 3);
	behave_move_com(&r.b, r.m, r.s, r.ik, 0, 0, -0.05);
	frames(&r, 40);
	double before = r.s->com[1], elevation = r.b.elevation;
	/* the box in the hanging hand, well below the centre of mass */
	struct point_mass box = weight_at(r.m, "hand_r.palm", BOX_KG);
	assert_true(r.s->site_xf[test_site(r.m, "hand_r.palm")].p[1] < before - 0.15);
	assert_int_equal(behave_set_masses(&r.b, r.m, r.s, &box, 1), 0);
	frames(&r, 40);
	printf("body com height %.4f -> %.4f m\n", before, r.s->com[1]);
	assert_near(r.s->com[1], before, 1e-3);
	/* packed and unpacked into a behaviour that carried nothing: the same weights
	 * taken up again leave the held height as packed */
	double v[256];
	int n = behave_pack(&r.b, v, 256);
	assert_true(n <= 256);
	struct behave *fresh = calloc(1, sizeof *fresh);
	assert_non_null(fresh);
	assert_int_equal(behave_unpack(fresh, r.m, v, n), 0);
	assert_int_equal(behave_set_masses(fresh, r.m, r.s, &box, 1), 0);
	assert_near(fresh->elevation, r.b.elevation, 0);
	assert_true(fabs(r.b.elevation - elevation) > 0.01); /* the jump the box made */
	free(fresh);
	rig_free(&r);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_balance_point_is_the_combined_centre_of_mass),
		cmocka_unit_test(test_masses_the_figure_cannot_carry_are_refused),
		cmocka_unit_test(test_only_weights_become_point_masses),
		cmocka_unit_test(test_a_box_held_out_in_front_moves_the_hips_back),
		cmocka_unit_test(test_a_held_elevation_keeps_the_body_where_it_stands),
	};
	return cmocka_run_group_tests_name("balance_load", tests, NULL, NULL);
}
