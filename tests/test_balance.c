/* test_balance.c - support polygon, balance parameters (Figure 5.2), margin, rooting rules */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "test_util.h"
#include "test_human.h"

#include <stdio.h>
#include <string.h>

#include "pose/balance.h"
#include "figure/human.h"
#include "figure/kin.h"

/* two feet as rectangles 0.1 wide and 0.26 long, 0.2 apart, facing +z; left at +x */
static void
two_feet(struct balance *b)
{
	double pts[8][2] = { { 0.05, -0.08 }, { 0.15, -0.08 }, { 0.15, 0.18 }, { 0.05, 0.18 },
			     { -0.05, -0.08 }, { -0.15, -0.08 }, { -0.15, 0.18 }, { -0.05, 0.18 } };
	memset(b, 0, sizeof *b);
	b->npoly = balance_hull(pts, 8, b->poly);
	b->ref_l[0] = 0.1, b->ref_l[1] = 0.04;
	b->ref_r[0] = -0.1, b->ref_r[1] = 0.04;
	b->forward[0] = 0, b->forward[1] = 1;
}

static void
test_hull_of_two_feet_is_their_outer_rectangle(void **unused)
{
	(void)unused;
	struct balance b;
	two_feet(&b);
	assert_int_equal(b.npoly, 4);
	/* counter-clockwise seen from above: positive area in (x, z) */
	double area = 0;
	for (int i = 0; i < b.npoly; i++) {
		const double *p = b.poly[i], *q = b.poly[(i + 1) % b.npoly];
		area += p[0] * q[1] - q[0] * p[1];
	}
	assert_near(area / 2, 0.3 * 0.26, 1e-12);
}

static void
test_parameters_and_their_inverse(void **unused)
{
	(void)unused;
	struct balance b;
	two_feet(&b);
	/* on the line, a quarter of the way from the left foot: x = 0.25, z = 0 */
	double p[2];
	balance_point_of(&b, 0.25, 0, p);
	assert_near(p[0], 0.05, 1e-12);
	assert_near(p[1], 0.04, 1e-12);
	/* halfway to the front edge (z 0.04 -> 0.18) and to the back edge (0.04 -> -0.08) */
	balance_point_of(&b, 0.5, 0.5, p);
	assert_near(p[1], 0.11, 1e-12);
	balance_point_of(&b, 0.5, -0.5, p);
	assert_near(p[1], -0.02, 1e-12);
	/* the margin: inside, the distance to the nearest edge; outside, negative */
	double centre[2] = { 0, 0.05 }, out[2] = { 0, 0.28 };
	assert_near(balance_margin(&b, centre), 0.13, 1e-12);
	assert_near(balance_margin(&b, out), -0.10, 1e-12);
}

/* out past a foot's side: x beyond 0..1, z finite, normalised as at that foot's end */
static void
test_parameters_past_a_foot(void **unused)
{
	(void)unused;
	struct balance b;
	two_feet(&b);
	double out[2] = { 0.30, 0.11 }, x, z, p[2];
	balance_params_of(&b, out, &x, &z);
	assert_near(x, -1.0, 1e-12);   /* a whole line's length past the left foot */
	assert_near(z, 0.5, 1e-12);    /* half the left foot's reach to the front (0.04 -> 0.18) */
	balance_point_of(&b, x, z, p); /* and back */
	assert_near(p[0], out[0], 1e-12);
	assert_near(p[1], out[1], 1e-12);
}


static void
test_standing_human_is_balanced_between_its_feet(void **unused)
{
	(void)unused;
	struct model *m = test_human();
	struct state *s = state_make(m);
	kin_update(m, s);
	struct balance b;
	assert_int_equal(balance_measure(m, s, BALANCE_CONTACT, &b), 0);
	assert_true(b.npoly >= 4);
	assert_near(b.x, 0.5, 1e-9);
	assert_near(b.z, 0, 1e-9);
	assert_near(b.weight_l, 0.5, 1e-9);
	assert_near(b.forward[1], 1, 1e-12);
	assert_true(b.margin > 0.05); /* well inside */
	/* the inverse of the parameters gives back the balance point */
	double p[2];
	balance_point_of(&b, b.x, b.z, p);
	assert_near(p[0], b.point[0], 1e-12);
	assert_near(p[1], b.point[1], 1e-12);
	state_free(s);
	model_free(m);
}

/* leaning the spine moves the centre of mass over planted feet */
static void
test_leaning_moves_the_parameters_the_right_way(void **unused)
{
	(void)unused;
	struct model *m = test_human();
	struct state *s = state_make(m);
	kin_update(m, s);
	struct balance b0, b;
	balance_measure(m, s, BALANCE_CONTACT, &b0);
	for (int k = 0; k < HUMAN_NSPINE; k++) {
		char name[32];
		snprintf(name, sizeof name, "spine_%d", k);
		int j = model_find_joint(m, name);
		s->q[m->jnt_dof0[j] + HUMAN_DOF_FLEX] = 0.05; /* forward */
	}
	kin_update(m, s);
	balance_measure(m, s, BALANCE_CONTACT, &b);
	assert_true(b.z > 0.1);
	assert_near(b.x, 0.5, 1e-9); /* straight forward: no side shift */
	for (int k = 0; k < HUMAN_NSPINE; k++) {
		char name[32];
		snprintf(name, sizeof name, "spine_%d", k);
		int j = model_find_joint(m, name);
		s->q[m->jnt_dof0[j] + HUMAN_DOF_FLEX] = 0;
		s->q[m->jnt_dof0[j] + HUMAN_DOF_ABD] = 0.03; /* bend to the left (+x) */
	}
	kin_update(m, s);
	balance_measure(m, s, BALANCE_CONTACT, &b);
	assert_true(b.x < 0.45);
	assert_true(b.weight_l > 0.55);
	/* the parameters are those of the point: the inverse agrees */
	double p[2];
	balance_point_of(&b, b.x, b.z, p);
	assert_near(p[0], b.point[0], 1e-12);
	assert_near(p[1], b.point[1], 1e-12);
	state_free(s);
	model_free(m);
}

static void
test_rooting_rules(void **unused)
{
	(void)unused;
	struct balance b;
	memset(&b, 0, sizeof b);
	double leg = 0.9;
	b.weight_l = 0.65;
	assert_int_equal(balance_choose_root(&b, 0.8, leg, BALANCE_ROOT_RIGHT_FOOT),
			 BALANCE_ROOT_LEFT_FOOT);
	b.weight_l = 0.35;
	assert_int_equal(balance_choose_root(&b, 0.8, leg, BALANCE_ROOT_LEFT_FOOT),
			 BALANCE_ROOT_RIGHT_FOOT);
	/* between 40 and 60 %: no flip-flopping */
	b.weight_l = 0.55;
	assert_int_equal(balance_choose_root(&b, 0.8, leg, BALANCE_ROOT_RIGHT_FOOT),
			 BALANCE_ROOT_RIGHT_FOOT);
	assert_int_equal(balance_choose_root(&b, 0.8, leg, BALANCE_ROOT_LEFT_FOOT),
			 BALANCE_ROOT_LEFT_FOOT);
	/* below 70 % of the leg: the lower torso, whatever the weight */
	b.weight_l = 0.9;
	assert_int_equal(balance_choose_root(&b, 0.7 * leg - 1e-6, leg, BALANCE_ROOT_LEFT_FOOT),
			 BALANCE_ROOT_LOWER_TORSO);
	assert_int_equal(balance_choose_root(&b, 0.7 * leg + 1e-6, leg, BALANCE_ROOT_LOWER_TORSO),
			 BALANCE_ROOT_LEFT_FOOT);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_hull_of_two_feet_is_their_outer_rectangle),
		cmocka_unit_test(test_parameters_and_their_inverse),
		cmocka_unit_test(test_parameters_past_a_foot),
		cmocka_unit_test(test_standing_human_is_balanced_between_its_feet),
		cmocka_unit_test(test_leaning_moves_the_parameters_the_right_way),
		cmocka_unit_test(test_rooting_rules),
	};
	return cmocka_run_group_tests_name("balance", tests, NULL, NULL);
}
