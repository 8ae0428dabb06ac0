/*
 * test_queue.c - the device-to-loop queue: order kept, motion merged only
 * past the soft limit and only with its own device and kind, the sums of
 * merged motion exact, transitions never merged and given the reserve,
 * losses counted, nothing allocated.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <linux/input-event-codes.h>
#include <stdlib.h>
#include <string.h>

#include "alloc_count.h"
#include "devices/queue.h"

static struct input_event_rec
ev(enum input_kind kind, uint16_t device, uint16_t code, int32_t value, double x, double y)
{
	struct input_event_rec e;
	memset(&e, 0, sizeof e);
	e.kind = (uint8_t)kind;
	e.device = device;
	e.code = code;
	e.value = value;
	e.x = x;
	e.y = y;
	return e;
}

static struct input_queue *
fresh(void)
{
	static struct input_queue q;
	input_queue_init(&q);
	return &q;
}

static void
test_order_is_kept_below_the_soft_limit(void **unused)
{
	(void)unused;
	struct input_queue *q = fresh();
	for (int i = 0; i < INPUT_QUEUE_SOFT; i++) {
		struct input_event_rec e = ev(i % 2 ? INPUT_FRAME : INPUT_MOTION, 1, 0, 0, i, -i);
		e.t_us = (uint64_t)i;
		assert_int_equal(input_queue_push(q, &e), 0);
	}
	struct input_event_rec out;
	for (int i = 0; i < INPUT_QUEUE_SOFT; i++) {
		assert_int_equal(input_queue_pop(q, &out), 1);
		assert_int_equal(out.t_us, (uint64_t)i);
		assert_true(out.x == i && out.y == -i);
	}
	assert_int_equal(input_queue_pop(q, &out), 0);
	assert_int_equal(q->coalesced, 0);
	assert_int_equal(q->dropped, 0);
}

/* fills the queue to the soft limit with key presses and releases of device 9 */
static void
fill_to_soft(struct input_queue *q)
{
	for (int i = 0; i < INPUT_QUEUE_SOFT; i++) {
		struct input_event_rec e = ev(INPUT_KEY, 9, KEY_A, i % 2, 0, 0);
		assert_int_equal(input_queue_push(q, &e), 0);
	}
}

static void
test_motion_merges_past_the_soft_limit_with_exact_sums(void **unused)
{
	(void)unused;
	struct input_queue *q = fresh();
	fill_to_soft(q);
	struct input_event_rec m = ev(INPUT_MOTION, 1, 0, 0, 0.5, -2);
	assert_int_equal(input_queue_push(q, &m), 0); /* nothing of device 1 to merge into */
	struct input_event_rec f = ev(INPUT_FRAME, 1, 0, 0, 0, 0);
	assert_int_equal(input_queue_push(q, &f), 0);
	double sx = 0.5, sy = -2;
	for (int i = 1; i <= 1000; i++) {
		m = ev(INPUT_MOTION, 1, 0, 0, i * 0.25, -i);
		m.t_us = (uint64_t)i;
		sx += i * 0.25;
		sy += -i;
		assert_int_equal(input_queue_push(q, &m), 1); /* past the frame end, into the motion */
		assert_int_equal(input_queue_push(q, &f), 1); /* a second frame end in a row: skipped */
	}
	assert_int_equal(q->len, INPUT_QUEUE_SOFT + 2);
	assert_int_equal(q->coalesced, 2000);
	struct input_event_rec out;
	for (int i = 0; i < INPUT_QUEUE_SOFT; i++)
		input_queue_pop(q, &out);
	assert_int_equal(input_queue_pop(q, &out), 1);
	assert_int_equal(out.kind, INPUT_MOTION);
	assert_true(out.x == sx && out.y == sy); /* quarters and integers: exact in double */
	assert_int_equal(out.t_us, 1000);        /* the newest time */
	assert_int_equal(input_queue_pop(q, &out), 1);
	assert_int_equal(out.kind, INPUT_FRAME);
}

static void
test_motion_does_not_merge_across_a_button_or_another_device(void **unused)
{
	(void)unused;
	struct input_queue *q = fresh();
	fill_to_soft(q);
	struct input_event_rec m = ev(INPUT_MOTION, 1, 0, 0, 1, 1);
	struct input_event_rec press = ev(INPUT_BUTTON, 1, BTN_LEFT, 1, 0, 0);
	struct input_event_rec other = ev(INPUT_MOTION, 2, 0, 0, 5, 5);
	assert_int_equal(input_queue_push(q, &m), 0);
	assert_int_equal(input_queue_push(q, &press), 0);
	assert_int_equal(input_queue_push(q, &m), 0);     /* the drag starts after the press */
	assert_int_equal(input_queue_push(q, &other), 0); /* device 2 has nothing queued */
	assert_int_equal(input_queue_push(q, &m), 1);     /* device 1's newest is its motion */
	struct input_event_rec wheel = ev(INPUT_WHEEL, 1, INPUT_WHEEL_V, 1, 120, 0);
	struct input_event_rec hwheel = ev(INPUT_WHEEL, 1, INPUT_WHEEL_H, 1, 120, 0);
	assert_int_equal(input_queue_push(q, &wheel), 0); /* a wheel is not motion */
	assert_int_equal(input_queue_push(q, &hwheel), 0); /* nor the other wheel */
	assert_int_equal(input_queue_push(q, &wheel), 0); /* the newest is the horizontal one */
	assert_int_equal(q->coalesced, 1);
}

static void
test_transitions_are_never_merged_and_get_the_reserve(void **unused)
{
	(void)unused;
	struct input_queue *q = fresh();
	fill_to_soft(q);
	/* motion that cannot merge takes places until only the reserve is left */
	int keys_in = 0;
	while (q->len < INPUT_QUEUE_CAP - INPUT_QUEUE_RESERVE) {
		struct input_event_rec m = ev(INPUT_MOTION, 1, 0, 0, 1, 0);
		struct input_event_rec k = ev(INPUT_KEY, 1, KEY_B, keys_in % 2, 0, 0);
		assert_int_equal(input_queue_push(q, &m), 0); /* after a key: nothing to merge into */
		if (q->len < INPUT_QUEUE_CAP - INPUT_QUEUE_RESERVE) {
			assert_int_equal(input_queue_push(q, &k), 0);
			keys_in++;
		}
	}
	assert_int_equal(q->len, INPUT_QUEUE_CAP - INPUT_QUEUE_RESERVE);
	uint64_t lost = q->dropped;
	struct input_event_rec m = ev(INPUT_MOTION, 3, 0, 0, 1, 0);
	assert_int_equal(input_queue_push(q, &m), -1); /* no place left for motion */
	assert_int_equal(q->dropped, lost + 1);
	/* every key, button and device change still fits, up to the last place */
	for (int i = 0; i < INPUT_QUEUE_RESERVE; i++) {
		struct input_event_rec k = ev(i % 3 ? INPUT_BUTTON : INPUT_ADDED, 4, BTN_RIGHT, 1, 0, 0);
		assert_int_equal(input_queue_push(q, &k), 0);
	}
	assert_int_equal(q->len, INPUT_QUEUE_CAP);
	struct input_event_rec k = ev(INPUT_KEY, 4, KEY_C, 1, 0, 0);
	assert_int_equal(input_queue_push(q, &k), -1); /* full: lost and counted */
	assert_int_equal(q->dropped, lost + 2);
	/* nothing merged into a transition */
	struct input_event_rec out;
	int keys = 0;
	while (input_queue_pop(q, &out))
		keys += out.kind == INPUT_KEY && out.device == 1;
	assert_int_equal(keys, keys_in);
}

static void
test_pointer_and_valuator_keep_the_newest_value(void **unused)
{
	(void)unused;
	struct input_queue *q = fresh();
	fill_to_soft(q);
	struct input_event_rec v = ev(INPUT_VALUATOR, 5, 2, 0, 10, 0);
	assert_int_equal(input_queue_push(q, &v), 0);
	v.x = 12;
	v.flags = INPUT_F_STALE;
	assert_int_equal(input_queue_push(q, &v), 1);
	struct input_event_rec w = ev(INPUT_VALUATOR, 5, 3, 0, 7, 0);
	assert_int_equal(input_queue_push(q, &w), 0); /* another axis of the panel */
	struct input_event_rec out;
	for (int i = 0; i < INPUT_QUEUE_SOFT; i++)
		input_queue_pop(q, &out);
	assert_int_equal(input_queue_pop(q, &out), 1);
	assert_true(out.code == 2 && out.x == 12 && out.flags == INPUT_F_STALE);
}

static void
test_nothing_allocates(void **unused)
{
	(void)unused;
	struct input_queue *q = fresh();
#if COUNT_ALLOCS
	long before = allocs;
#endif
	for (int i = 0; i < 3 * INPUT_QUEUE_CAP; i++) {
		struct input_event_rec e = ev(i % 5 ? INPUT_MOTION : INPUT_BUTTON, 1, BTN_LEFT, 1, 1, 1);
		input_queue_push(q, &e);
		if (i % 7 == 0) {
			struct input_event_rec out;
			input_queue_pop(q, &out);
		}
	}
#if COUNT_ALLOCS
	assert_int_equal(allocs - before, 0);
#endif
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_order_is_kept_below_the_soft_limit),
		cmocka_unit_test(test_motion_merges_past_the_soft_limit_with_exact_sums),
		cmocka_unit_test(test_motion_does_not_merge_across_a_button_or_another_device),
		cmocka_unit_test(test_transitions_are_never_merged_and_get_the_reserve),
		cmocka_unit_test(test_pointer_and_valuator_keep_the_newest_value),
		cmocka_unit_test(test_nothing_allocates),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
