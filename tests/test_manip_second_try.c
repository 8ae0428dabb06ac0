/*
 * test_manip_second_try.c - §3.7's second try ("the automatic viewing
 * adjustment invokes itself if the user selects the same axis again after
 * getting the warning message") for chords that take more than one key:
 * two buttons for a plane, CONTROL and a button for a wheel. Keys go down
 * and up one at a time, so a chord passes through others on the way in
 * and on the way out; those are not choices, and neither they nor a
 * pointer's jitter while the chord forms may make the second try differ
 * from the first. The view adjustment that a repeat triggers (the
 * daemon's part) is run here too, and its result checked from the
 * geometry: the line of sight at least 20 degrees off the plane.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <linux/input-event-codes.h>
#include <math.h>
#include <string.h>

#include "draw/view.h"
#include "figure/mathx.h"
#include "interact/manip.h"
#include "interact/view_adjust.h"
#include "test_util.h"

#define DEG (M_PI / 180.0)

/* where the first report of the planar case stood: eye (3, 1.6, 4), G about a hip's height */
static const double EYE[3] = { 3, 1.6, 4 };
static const double G_AT[3] = { 0, 0.9275, 0 };

static struct camera
cam_at(const double eye[3], const double target[3])
{
	struct camera c;
	view_camera_default(&c);
	assert_int_equal(view_camera_aim(&c, eye, target), 0);
	return c;
}

static void
send(struct manip *m, uint8_t kind, uint16_t code, int32_t value)
{
	struct input_event_rec e;
	memset(&e, 0, sizeof e);
	e.kind = kind;
	e.code = code;
	e.value = value;
	manip_event(m, &e);
}

static void
button(struct manip *m, uint16_t code, int down)
{
	send(m, INPUT_BUTTON, code, down);
}

static void
key(struct manip *m, uint16_t code, int down)
{
	send(m, INPUT_KEY, code, down);
}

/* the mouse line from c's eye through x; returns 1 when G moved */
static int
mouse_through(struct manip *m, const struct camera *c, const double x[3])
{
	struct ray r;
	double n = 0;
	for (int i = 0; i < 3; i++) {
		r.o[i] = c->xf.p[i];
		r.d[i] = x[i] - c->xf.p[i];
		n += r.d[i] * r.d[i];
	}
	for (int i = 0; i < 3; i++)
		r.d[i] /= sqrt(n);
	return manip_ray(m, &r);
}

/* G at g (unturned), seen from eye, default settings */
static void
start(struct manip *m, const double g[3], const double eye[3], struct camera *c)
{
	struct xform x;
	xform_identity(&x);
	memcpy(x.p, g, sizeof x.p);
	*c = cam_at(eye, g);
	const struct manip_def def = manip_default_def();
	manip_init(m, &def, &x, c);
}

/* the angle between the line of sight from c's eye to p and the plane with unit normal n */
static double
sight_to_plane(const struct camera *c, const double p[3], const double n[3])
{
	double d[3] = { p[0] - c->xf.p[0], p[1] - c->xf.p[1], p[2] - c->xf.p[2] };
	return asin(fabs(mathx_dot(d, n)) / sqrt(mathx_dot(d, d)));
}

/* the refusal is the xz plane's (normal y), a first one (repeat 0) or a second (1) */
static void
assert_xz_refused(const struct manip *m, int repeat)
{
	const struct manip_refusal *r = manip_refusal(m);
	assert_int_equal(m->state, MANIP_REFUSED);
	assert_int_equal(r->active, 1);
	assert_int_equal(r->sel.mode, MANIP_MODE_PLANAR);
	assert_int_equal(r->sel.axis, 1);
	assert_string_equal(r->message, "can't translate in that plane from this view");
	assert_int_equal(r->repeat, repeat);
}

/*
 * The reported case: from (3, 1.6, 4) the line of sight to G is 7.7
 * degrees off the horizontal, so the xz plane is refused while x (54
 * degrees from the line of sight) and z (38) are not. Left then right,
 * a drag, both up; the same again is the second try, whichever button
 * comes up first and with a mouse line between the presses.
 */
static void
test_plane_built_through_an_axis_that_is_not_refused(void **unused)
{
	(void)unused;
	struct camera c;
	struct manip m;
	start(&m, G_AT, EYE, &c);
	const double y[3] = { 0, 1, 0 };
	assert_true(sight_to_plane(&c, G_AT, y) < 20 * DEG);
	struct xform g0 = m.g;

	mouse_through(&m, &c, G_AT);
	button(&m, BTN_LEFT, 1);
	assert_int_equal(m.state, MANIP_LINEAR); /* x on the way: accepted */
	button(&m, BTN_RIGHT, 1);
	assert_xz_refused(&m, 0);
	assert_int_equal(mouse_through(&m, &c, (double[3]){ 0.3, 0.9, 0.2 }), 0);
	button(&m, BTN_LEFT, 0); /* left up first: z (accepted) on the way out */
	assert_int_equal(m.state, MANIP_LINEAR);
	button(&m, BTN_RIGHT, 0);
	assert_memory_equal(&m.g, &g0, sizeof g0);

	/* the second try, right up first this time; the pointer moves between the presses */
	button(&m, BTN_LEFT, 1);
	mouse_through(&m, &c, (double[3]){ 0.01, 0.93, 0 });
	mouse_through(&m, &c, (double[3]){ 0.02, 0.93, 0 }); /* G creeps along x */
	button(&m, BTN_RIGHT, 1);
	assert_xz_refused(&m, 1);
	button(&m, BTN_RIGHT, 0);
	button(&m, BTN_LEFT, 0);

	/* a third, built right then left, is a second try still: nothing moved in the plane */
	button(&m, BTN_RIGHT, 1);
	button(&m, BTN_LEFT, 1);
	assert_xz_refused(&m, 1);
	button(&m, BTN_LEFT, 0);

	/* but a drag along z on the button still held moves G: an action, so a first try again */
	assert_int_equal(m.state, MANIP_LINEAR);
	mouse_through(&m, &c, m.g.p);
	assert_int_equal(mouse_through(&m, &c, (double[3]){ m.g.p[0], m.g.p[1], 0.3 }), 1);
	button(&m, BTN_RIGHT, 0);
	button(&m, BTN_LEFT, 1);
	button(&m, BTN_RIGHT, 1);
	assert_xz_refused(&m, 0);
	button(&m, BTN_RIGHT, 0);
	button(&m, BTN_LEFT, 0);
}

/*
 * Looking along z: z itself is refused, and so is the xz plane (seen
 * edge-on). Building the plane from the right button passes through the
 * refused z each time; z's refusal on the way is not the choice, so it
 * neither becomes the remembered one nor makes the plane a first try.
 */
static void
test_a_refused_axis_on_the_way_does_not_take_the_plane_s_place(void **unused)
{
	(void)unused;
	struct camera c;
	struct manip m;
	const double o[3] = { 0, 0, 0 };
	start(&m, o, (double[3]){ 0, 0.2, 5 }, &c);
	for (int k = 0; k < 2; k++) {
		button(&m, BTN_RIGHT, 1);
		assert_int_equal(m.state, MANIP_REFUSED);
		assert_int_equal(manip_refusal(&m)->sel.mode, MANIP_MODE_LINEAR);
		assert_int_equal(manip_refusal(&m)->repeat, 0); /* z was never the choice */
		button(&m, BTN_LEFT, 1);
		assert_xz_refused(&m, k);
		mouse_through(&m, &c, (double[3]){ 0.2, 0.1, 0 });
		button(&m, BTN_RIGHT, 0);
		button(&m, BTN_LEFT, 0);
	}
}

/*
 * A wheel let go of CONTROL first passes through the plain axis (x,
 * accepted, seen from along z): the second try is still the wheel's. And
 * a one-button axis pressed, moved and released in between is an action:
 * the plane's next refusal is a first one again.
 */
static void
test_a_wheel_let_go_of_control_first_and_an_action_in_between(void **unused)
{
	(void)unused;
	struct camera c;
	struct manip m;
	const double o[3] = { 0, 0, 0 };
	start(&m, o, (double[3]){ 0, 0.2, 5 }, &c);
	for (int k = 0; k < 2; k++) {
		key(&m, KEY_LEFTCTRL, 1);
		button(&m, BTN_LEFT, 1); /* about x: the wheel seen edge-on */
		assert_int_equal(m.state, MANIP_REFUSED);
		assert_int_equal(manip_refusal(&m)->sel.mode, MANIP_MODE_ROTATE);
		assert_int_equal(manip_refusal(&m)->repeat, k);
		key(&m, KEY_LEFTCTRL, 0);
		assert_int_equal(m.state, MANIP_LINEAR);
		button(&m, BTN_LEFT, 0);
	}

	/* the plane refused; then a drag along x moves G; then the plane again: a first try */
	button(&m, BTN_LEFT, 1);
	button(&m, BTN_RIGHT, 1);
	assert_xz_refused(&m, 0);
	button(&m, BTN_RIGHT, 0);
	button(&m, BTN_LEFT, 0);
	button(&m, BTN_LEFT, 1);
	mouse_through(&m, &c, (double[3]){ 0, 0, 0 });
	assert_int_equal(mouse_through(&m, &c, (double[3]){ 0.3, 0, 0 }), 1);
	button(&m, BTN_LEFT, 0);
	button(&m, BTN_LEFT, 1);
	button(&m, BTN_RIGHT, 1);
	assert_xz_refused(&m, 0);
	button(&m, BTN_LEFT, 0);
	button(&m, BTN_RIGHT, 0);
}

/*
 * The whole second try as the daemon runs it: the repeat plans the
 * adjustment from the refusal's normal, the camera goes through its
 * in-betweens under the held chord, and the end view sees the plane at
 * least 20 degrees off edge-on (by the least turn: under 22); the held
 * chord then drags G in the plane, under the pointer.
 */
static void
test_the_second_planar_try_turns_the_view_and_then_drags(void **unused)
{
	(void)unused;
	struct camera c;
	struct manip m;
	start(&m, G_AT, EYE, &c);
	for (int k = 0; k < 2; k++) {
		button(&m, BTN_LEFT, 1);
		button(&m, BTN_RIGHT, 1);
		assert_xz_refused(&m, k);
		if (k == 0) {
			button(&m, BTN_LEFT, 0);
			button(&m, BTN_RIGHT, 0);
		}
	}
	const struct manip_refusal *r = manip_refusal(&m);
	struct view_adjust va;
	assert_int_equal(view_adjust_begin(&va, &c, m.g.p, r->axis, VIEW_ADJUST_ACROSS, m.limit, 0),
			 1);
	struct camera now = c;
	uint64_t t = 0;
	int more = 1;
	while (more) {
		t += 16667; /* 60 frames a second */
		more = view_adjust_step(&va, t, VIEW_ADJUST_US, VIEW_ADJUST_MIN_TURN, &now);
		manip_camera(&m, &now);
	}
	const double y[3] = { 0, 1, 0 };
	double seen = sight_to_plane(&now, G_AT, y);
	assert_true(seen >= 20 * DEG && seen < 22 * DEG);
	assert_int_equal(m.state, MANIP_PLANAR);
	assert_int_equal(manip_refusal(&m)->active, 0);

	/* the drag: G goes from its origin to where the pointer's line meets the plane y = G.y */
	mouse_through(&m, &now, G_AT);
	const double to[3] = { 0.4, G_AT[1], -0.3 };
	assert_int_equal(mouse_through(&m, &now, to), 1);
	for (int i = 0; i < 3; i++)
		assert_near(m.g.p[i], to[i], 1e-9);
	button(&m, BTN_RIGHT, 0);
	button(&m, BTN_LEFT, 0);

	/* that drag was an action: back in the old view, the plane is a first try again */
	manip_camera(&m, &c);
	button(&m, BTN_LEFT, 1);
	button(&m, BTN_RIGHT, 1);
	assert_xz_refused(&m, 0);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_plane_built_through_an_axis_that_is_not_refused),
		cmocka_unit_test(test_a_refused_axis_on_the_way_does_not_take_the_plane_s_place),
		cmocka_unit_test(test_a_wheel_let_go_of_control_first_and_an_action_in_between),
		cmocka_unit_test(test_the_second_planar_try_turns_the_view_and_then_drags),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
