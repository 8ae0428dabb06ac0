/*
 * test_interact.c - the modes around the manipulation operator: the object
 * follows G rigidly, the pointer stays in the view and moves by the pixels
 * given, absolute positions of another view are not ours, ESC ends the
 * mode and leaves G, no mode means no effect.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <linux/input-event-codes.h>
#include <math.h>
#include <string.h>

#include "interact/interact.h"
#include "test_util.h"

static struct camera
front_camera(void)
{
	struct camera cam;
	double eye[3] = { 0, 1, 3 }, target[3] = { 0, 1, 0 };
	view_camera_default(&cam);
	view_camera_aim(&cam, eye, target);
	return cam;
}

static struct input_event_rec
ev(enum input_kind kind, uint16_t code, int value)
{
	struct input_event_rec e = { .kind = (uint8_t)kind, .code = code, .value = value };
	return e;
}

static struct input_event_rec
pointer_at(uint16_t view, double x, double y)
{
	struct input_event_rec e = { .kind = INPUT_POINTER, .flags = INPUT_F_VIEW, .code = view,
				     .x = x, .y = y };
	return e;
}

static void
test_the_object_follows_g_rigidly(void **unused)
{
	(void)unused;
	struct interact ia;
	interact_init(&ia);
	struct camera cam = front_camera();
	struct xform g0, obj;
	xform_identity(&g0);
	g0.p[1] = 1;
	xform_identity(&obj); /* the object 30 cm to G's right, turned 90 degrees about y */
	obj.p[0] = 0.3;
	obj.p[1] = 1;
	obj.r[0] = 0, obj.r[2] = 1, obj.r[6] = -1, obj.r[8] = 0;
	interact_start(&ia, INTERACT_FIGURE, 0, 2, &g0, &obj, &cam, 320, 240);
	struct input_event_rec e = pointer_at(2, 100, 120);
	interact_input(&ia, &e, 0, 0, &cam, 320, 240);
	e = ev(INPUT_BUTTON, BTN_LEFT, 1);
	int r = interact_input(&ia, &e, 0, 0, &cam, 320, 240);
	assert_true(r & INTERACT_ICONS);
	assert_false(r & INTERACT_MOVED); /* a press never moves G */
	e = pointer_at(2, 250, 60);
	r = interact_input(&ia, &e, 0, 0, &cam, 320, 240);
	assert_true(r & INTERACT_MOVED);
	struct xform t;
	interact_target(&ia, &t);
	double moved = ia.m.g.p[0] - g0.p[0];
	assert_true(moved > 0.1); /* right on the screen is +x from this camera */
	assert_near(t.p[0], obj.p[0] + moved, 1e-12);
	assert_near(t.p[1], obj.p[1], 1e-12);
	assert_near(t.p[2], obj.p[2], 1e-12);
	for (int k = 0; k < 9; k++)
		assert_near(t.r[k], obj.r[k], 1e-12);
}

static void
test_the_pointer_stays_in_the_view_and_only_its_view_moves_it(void **unused)
{
	(void)unused;
	struct interact ia;
	interact_init(&ia);
	struct camera cam = front_camera();
	struct xform g0;
	xform_identity(&g0);
	interact_start(&ia, INTERACT_FIGURE, 0, 1, &g0, &g0, &cam, 320, 240);
	assert_near(ia.px, 160, 0);
	assert_near(ia.py, 120, 0);
	struct input_event_rec e = ev(INPUT_MOTION, 0, 0);
	interact_input(&ia, &e, 1000, -7, &cam, 320, 240);
	assert_near(ia.px, 320, 0);
	assert_near(ia.py, 113, 0);
	e = pointer_at(0, 5, 5); /* view 0: another view's pointer */
	interact_input(&ia, &e, 0, 0, &cam, 320, 240);
	assert_near(ia.px, 320, 0);
	e = (struct input_event_rec){ .kind = INPUT_POINTER, .x = 0.25, .y = 0.5 }; /* 0..1 */
	interact_input(&ia, &e, 0, 0, &cam, 320, 240);
	assert_near(ia.px, 80, 1e-12);
	assert_near(ia.py, 120, 1e-12);
	/* the view shrinks: the pointer comes with it */
	e = ev(INPUT_MOTION, 0, 0);
	interact_input(&ia, &e, 0, 0, &cam, 40, 30);
	assert_near(ia.px, 40, 0);
	assert_near(ia.py, 30, 0);
}

static void
test_esc_ends_the_mode_and_no_mode_does_nothing(void **unused)
{
	(void)unused;
	struct interact ia;
	interact_init(&ia);
	struct camera cam = front_camera();
	struct input_event_rec e = ev(INPUT_BUTTON, BTN_LEFT, 1);
	assert_int_equal(interact_input(&ia, &e, 0, 0, &cam, 320, 240), 0);
	struct xform g0;
	xform_identity(&g0);
	interact_start(&ia, INTERACT_FIGURE, 3, 0, &g0, &g0, &cam, 320, 240);
	assert_string_equal(interact_mode_to_str(ia.mode), "figure");
	e = ev(INPUT_KEY, KEY_ESC, 0); /* a release is not the press */
	assert_int_equal(interact_input(&ia, &e, 0, 0, &cam, 320, 240) & INTERACT_ENDED, 0);
	e = ev(INPUT_KEY, KEY_ESC, 1);
	assert_int_equal(interact_input(&ia, &e, 0, 0, &cam, 320, 240), INTERACT_ENDED);
	assert_int_equal(ia.mode, INTERACT_NONE);
	assert_string_equal(interact_mode_to_str(ia.mode), "none");
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_the_object_follows_g_rigidly),
		cmocka_unit_test(test_the_pointer_stays_in_the_view_and_only_its_view_moves_it),
		cmocka_unit_test(test_esc_ends_the_mode_and_no_mode_does_nothing),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
