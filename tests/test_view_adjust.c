/*
 * test_view_adjust.c - §3.7's automatic viewing adjustment on random
 * cameras and axes: afterwards the line of sight to the object's origin is
 * clear of a translation axis by the limit (or a wheel's axis is off
 * edge-on), the turn is the least that does it, the camera never twists
 * and ends focused on the origin, and the in-betweens take one second of
 * the given clock, plus or minus a frame, at 10, 30, 60 and 120 fps.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>

#include "interact/view_adjust.h"
#include "test_util.h"

#define DEG (M_PI / 180)

static double
rnd(double lo, double hi)
{
	return lo + (hi - lo) * (double)rand() / RAND_MAX;
}

static void
unit(double v[3])
{
	double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
	for (int k = 0; k < 3; k++)
		v[k] /= n;
}

/* a camera at distance dist from origin, in direction (heading h, elevation e), aimed at aim */
static struct camera
camera_at(const double origin[3], double h, double e, double dist, const double aim[3])
{
	struct camera c;
	view_camera_default(&c);
	double eye[3] = { origin[0] + dist * cos(e) * sin(h), origin[1] + dist * sin(e),
			  origin[2] + dist * cos(e) * cos(h) };
	view_camera_aim(&c, eye, aim);
	return c;
}

/* an axis at angle a from unit u: u turned by a towards a random perpendicular */
static void
axis_at_angle(const double u[3], double a, double dest[3])
{
	double r[3] = { rnd(-1, 1), rnd(-1, 1), rnd(-1, 1) }, c = 0, p[3];
	for (int k = 0; k < 3; k++)
		c += r[k] * u[k];
	for (int k = 0; k < 3; k++)
		p[k] = r[k] - c * u[k];
	unit(p);
	for (int k = 0; k < 3; k++)
		dest[k] = cos(a) * u[k] + sin(a) * p[k];
	if (rand() % 2) /* the axis' sign does not matter */
		for (int k = 0; k < 3; k++)
			dest[k] = -dest[k];
}

/* runs the adjustment at fps from t0; returns the time it took, camera in *end */
static double
run(struct view_adjust *va, double fps, uint64_t t0, double min_turn, struct camera *end)
{
	uint64_t dt = (uint64_t)(1e6 / fps), t = t0;
	int more = 1;
	while (more) {
		t += dt;
		more = view_adjust_step(va, t, 1000000, min_turn, end);
		assert_true(fabs(end->xf.r[3]) < 1e-12); /* x horizontal: never a twist */
	}
	return (double)(t - t0) / 1e6;
}

static void
check_adjusted(enum view_adjust_kind kind)
{
	srand(kind == VIEW_ADJUST_ALONG ? 7 : 8);
	static const double fps[] = { 10, 30, 60, 120 };
	for (int trial = 0; trial < 400; trial++) {
		double origin[3] = { rnd(-1, 1), rnd(0, 1.5), rnd(-1, 1) };
		double h = rnd(-M_PI, M_PI), e = rnd(-60, 60) * DEG, dist = rnd(1, 6);
		double aim[3] = { origin[0] + rnd(-0.3, 0.3), origin[1] + rnd(-0.3, 0.3),
				  origin[2] + rnd(-0.3, 0.3) };
		struct camera cam = camera_at(origin, h, e, dist, aim);
		double u[3] = { cos(e) * sin(h), sin(e), cos(e) * cos(h) }; /* origin to eye */
		double bad = kind == VIEW_ADJUST_ALONG ? rnd(0, 19.5) : rnd(70.5, 90);
		double axis[3];
		axis_at_angle(u, bad * DEG, axis);
		struct view_adjust va;
		assert_int_equal(view_adjust_begin(&va, &cam, origin, axis, kind, 20 * DEG, 1000), 1);
		struct camera end;
		double took = run(&va, fps[trial % 4], 1000, 0, &end);
		double dt = 1 / fps[trial % 4];
		assert_true(fabs(took - 1) <= dt + 1e-9);
		double after = view_adjust_sight_angle(&end, origin, axis) / DEG;
		if (kind == VIEW_ADJUST_ALONG)
			assert_true(after >= 20);
		else
			assert_true(after <= 70);
		/* the least turn: the eye moved round the origin by want - bad, no more */
		double v[3] = { end.xf.p[0] - origin[0], end.xf.p[1] - origin[1],
				end.xf.p[2] - origin[2] };
		assert_near(sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]), dist, 1e-9);
		unit(v);
		double moved = acos(fmin(1, u[0] * v[0] + u[1] * v[1] + u[2] * v[2])) / DEG;
		double want = kind == VIEW_ADJUST_ALONG ? 21 - bad : bad - 69;
		if (fabs(asin(v[1])) < 88.9 * DEG) /* unless the poles cut it */
			assert_near(moved, want, 1e-6);
		/* focused on the origin */
		double r[3];
		view_camera_vrp(&end, r);
		for (int k = 0; k < 3; k++)
			assert_near(r[k], origin[k], 1e-9);
	}
}

static void
test_a_translation_axis_ends_clear_of_the_line_of_sight(void **unused)
{
	(void)unused;
	check_adjusted(VIEW_ADJUST_ALONG);
}

static void
test_a_wheel_ends_off_edge_on(void **unused)
{
	(void)unused;
	check_adjusted(VIEW_ADJUST_ACROSS);
}

static void
test_a_clear_view_is_left_alone_and_a_least_turn_ends_sooner(void **unused)
{
	(void)unused;
	double origin[3] = { 0, 1, 0 }, aim[3] = { 0, 1, 0 };
	struct camera cam = camera_at(origin, 0, 0, 3, aim); /* looking along -z */
	double x[3] = { 1, 0, 0 }, z[3] = { 0, 0, 1 };
	struct view_adjust va;
	assert_int_equal(view_adjust_begin(&va, &cam, origin, x, VIEW_ADJUST_ALONG, 20 * DEG, 0), 0);
	assert_int_equal(view_adjust_begin(&va, &cam, origin, z, VIEW_ADJUST_ACROSS, 20 * DEG, 0), 0);
	/* z along the line of sight: refused, turned away by 21 degrees */
	assert_int_equal(view_adjust_begin(&va, &cam, origin, z, VIEW_ADJUST_ALONG, 20 * DEG, 0), 1);
	struct camera end;
	double took = run(&va, 60, 0, 2 * DEG, &end); /* 21 degrees at 2 a frame at least */
	assert_true(took <= 11.0 / 60 + 1e-9);
	assert_true(view_adjust_sight_angle(&end, origin, z) >= 20 * DEG);
	/* the eye on the origin: nothing to turn about */
	struct camera at = cam;
	at.xf.p[0] = 0, at.xf.p[1] = 1, at.xf.p[2] = 0;
	assert_int_equal(view_adjust_begin(&va, &at, origin, z, VIEW_ADJUST_ALONG, 20 * DEG, 0), -1);
}

static void
test_visible_is_inside_the_picture_and_a_focus_turns_to_the_origin(void **unused)
{
	(void)unused;
	double origin[3] = { 0, 1, 0 }, aim[3] = { 0, 1, 0 };
	struct camera cam = camera_at(origin, 0, 0, 3, aim); /* at (0, 1, 3) looking along -z */
	double fov = cam.fovy / 2, t = tan(fov);
	double ahead[3] = { 0, 1, 0 }, behind[3] = { 0, 1, 4 };
	assert_int_equal(view_adjust_visible(&cam, 400, 200, ahead), 1);
	assert_int_equal(view_adjust_visible(&cam, 400, 200, behind), 0);
	/* 3 m ahead the picture is 3 tan(fovy/2) high and twice that wide (400 x 200) */
	double top_in[3] = { 0, 1 + 0.99 * 3 * t, 0 }, top_out[3] = { 0, 1 + 1.01 * 3 * t, 0 };
	double right_in[3] = { 0.99 * 6 * t, 1, 0 }, right_out[3] = { 1.01 * 6 * t, 1, 0 };
	assert_int_equal(view_adjust_visible(&cam, 400, 200, top_in), 1);
	assert_int_equal(view_adjust_visible(&cam, 400, 200, top_out), 0);
	assert_int_equal(view_adjust_visible(&cam, 400, 200, right_in), 1);
	assert_int_equal(view_adjust_visible(&cam, 400, 200, right_out), 0);
	/* focus: the eye stays, the reference point ends on the target, in a second */
	double off[3] = { 5, 1, 0 };
	struct view_adjust va;
	assert_int_equal(view_adjust_focus(&va, &cam, off, 0), 1);
	struct camera end;
	double took = run(&va, 30, 0, 0, &end);
	assert_true(fabs(took - 1) <= 1.0 / 30 + 1e-9);
	double r[3];
	view_camera_vrp(&end, r);
	for (int k = 0; k < 3; k++) {
		assert_near(end.xf.p[k], cam.xf.p[k], 1e-12);
		assert_near(r[k], off[k], 1e-9);
	}
	assert_int_equal(view_adjust_visible(&end, 400, 200, off), 1);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_a_translation_axis_ends_clear_of_the_line_of_sight),
		cmocka_unit_test(test_a_wheel_ends_off_edge_on),
		cmocka_unit_test(test_a_clear_view_is_left_alone_and_a_least_turn_ends_sooner),
		cmocka_unit_test(test_visible_is_inside_the_picture_and_a_focus_turns_to_the_origin),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
