/*
 * test_joint_manip.c - a joint's DOFs with the mouse (§3.8): the chord
 * selects the DOF (left, middle, right the first three, CONTROL the next),
 * a press moves nothing, a rotational DOF turns by the analytic spoke
 * angle, a translational one slides by the change of the nearest point,
 * the limits clamp, and a crank past half a turn keeps turning.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <linux/input-event-codes.h>
#include <math.h>

#include "interact/joint_manip.h"
#include "test_util.h"

static struct input_event_rec
ev(enum input_kind kind, uint16_t code, int value)
{
	struct input_event_rec e = { .kind = (uint8_t)kind, .code = code, .value = value };
	return e;
}

/* a ray straight down onto the plane z = 0 at angle a, radius rad, about the z axis */
static struct ray
down_at(double a, double rad)
{
	struct ray r = { { rad * cos(a), rad * sin(a), 5 }, { 0, 0, -1 } };
	return r;
}

static void
test_the_chord_selects_the_dof(void **unused)
{
	(void)unused;
	struct joint_manip j;
	joint_manip_init(&j, 5);
	struct input_event_rec e = ev(INPUT_BUTTON, BTN_MIDDLE, 1);
	assert_int_equal(joint_manip_event(&j, &e), 1);
	assert_int_equal(j.dof, 1);
	e = ev(INPUT_KEY, KEY_RIGHTCTRL, 1);
	assert_int_equal(joint_manip_event(&j, &e), 1);
	assert_int_equal(j.dof, 4);
	e = ev(INPUT_BUTTON, BTN_MIDDLE, 0);
	joint_manip_event(&j, &e);
	e = ev(INPUT_BUTTON, BTN_RIGHT, 1); /* CONTROL + right: DOF 5, which this joint lacks */
	joint_manip_event(&j, &e);
	assert_int_equal(j.dof, -1);
	e = ev(INPUT_KEY, KEY_RIGHTCTRL, 0);
	joint_manip_event(&j, &e);
	assert_int_equal(j.dof, 2);
	e = ev(INPUT_BUTTON, BTN_LEFT, 1); /* two buttons: nothing */
	joint_manip_event(&j, &e);
	assert_int_equal(j.dof, -1);
	e = ev(INPUT_KEY, KEY_A, 1);
	assert_int_equal(joint_manip_event(&j, &e), 0);
}

static void
test_a_rotation_turns_by_the_spoke_angle_within_limits(void **unused)
{
	(void)unused;
	struct joint_manip j;
	joint_manip_init(&j, 3);
	struct joint_dof_view dv = { .rotation = 1, .axis = { 0, 0, 1 }, .pivot = { 0, 0, 0 },
				     .lo = -1.0, .hi = 2.0, .value = 0.3 };
	struct input_event_rec e = ev(INPUT_BUTTON, BTN_LEFT, 1);
	joint_manip_event(&j, &e);
	double v = 99;
	struct ray r = down_at(0.7, 0.5);
	assert_int_equal(joint_manip_ray(&j, &dv, &r, &v), 0); /* the press anchors: no move */
	assert_true(v == 99);
	r = down_at(1.1, 0.8); /* radius changes nothing: the angle does */
	assert_int_equal(joint_manip_ray(&j, &dv, &r, &v), 1);
	assert_near(v, 0.3 + 0.4, 1e-12);
	/* crank on, past the upper limit: clamped there */
	for (double a = 1.1; a < 4.5; a += 0.3) {
		r = down_at(a, 0.5);
		joint_manip_ray(&j, &dv, &r, &v);
	}
	assert_near(v, 2.0, 0);
	/* and back the other way, past half a turn, to below the lower limit */
	for (double a = 4.5; a > -3.0; a -= 0.3) {
		r = down_at(a, 0.5);
		joint_manip_ray(&j, &dv, &r, &v);
	}
	assert_near(v, -1.0, 0);
	/* back up in small steps to 0.05 past the anchor: the summed turn since the anchor is
	 * kept, unclamped, so the value comes back off the limit where the spoke says */
	double a = -3.0 + 0.3;
	while (a < 0.75) {
		a = fmin(a + 0.3, 0.75);
		r = down_at(a, 0.5);
		joint_manip_ray(&j, &dv, &r, &v);
	}
	assert_near(v, 0.3 + 0.05, 1e-9);
}

static void
test_a_translation_slides_by_the_nearest_point(void **unused)
{
	(void)unused;
	struct joint_manip j;
	joint_manip_init(&j, 1);
	struct joint_dof_view dv = { .rotation = 0, .axis = { 1, 0, 0 }, .pivot = { 0, 1, 0 },
				     .lo = -0.1, .hi = 0.25, .value = 0.02 };
	struct input_event_rec e = ev(INPUT_BUTTON, BTN_LEFT, 1);
	joint_manip_event(&j, &e);
	double v;
	struct ray r = { { 0.5, 1, 5 }, { 0, 0, -1 } };
	assert_int_equal(joint_manip_ray(&j, &dv, &r, &v), 0);
	r.o[0] = 0.6;
	assert_int_equal(joint_manip_ray(&j, &dv, &r, &v), 1);
	assert_near(v, 0.12, 1e-12);
	r.o[0] = 5;
	joint_manip_ray(&j, &dv, &r, &v);
	assert_near(v, 0.25, 0);
	/* a ray along the axis has no nearest point: nothing changes */
	struct ray along = { { -3, 1, 0 }, { 1, 0, 0 } };
	assert_int_equal(joint_manip_ray(&j, &dv, &along, &v), 0);
}

static void
test_a_typed_value_counts_from_where_the_dof_was_selected(void **unused)
{
	(void)unused;
	struct joint_manip j;
	joint_manip_init(&j, 1);
	struct joint_dof_view dv = { .rotation = 1, .axis = { 0, 0, 1 }, .lo = -1, .hi = 1,
				     .value = 0.2 };
	double v;
	assert_int_equal(joint_manip_type(&j, &dv, 0.1, &v), 0); /* nothing selected */
	struct input_event_rec e = ev(INPUT_BUTTON, BTN_LEFT, 1);
	joint_manip_event(&j, &e);
	assert_int_equal(joint_manip_type(&j, &dv, 0.3, &v), 1);
	assert_near(v, 0.5, 1e-15);
	/* after motion, still from the value at selection (the anchor), and clamped */
	struct ray r = down_at(0.0, 1);
	joint_manip_ray(&j, &dv, &r, &v);
	r = down_at(0.2, 1);
	joint_manip_ray(&j, &dv, &r, &v);
	assert_int_equal(joint_manip_type(&j, &dv, 5, &v), 1);
	assert_near(v, 1, 0);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_the_chord_selects_the_dof),
		cmocka_unit_test(test_a_rotation_turns_by_the_spoke_angle_within_limits),
		cmocka_unit_test(test_a_translation_slides_by_the_nearest_point),
		cmocka_unit_test(test_a_typed_value_counts_from_where_the_dof_was_selected),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
