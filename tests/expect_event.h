/*
 * expect_event.h - the next event a decoder or backend queued must be this
 * one: kind, code, value and device, with a message naming both when not.
 * Include after <cmocka.h>.
 */
#ifndef POSTURE_TEST_EXPECT_EVENT_H
#define POSTURE_TEST_EXPECT_EVENT_H

#include "devices/queue.h"

static inline void
expect_event_in(struct input_queue *q, uint16_t device, enum input_kind kind, unsigned code,
		int value)
{
	struct input_event_rec e;
	if (!input_queue_pop(q, &e))
		fail_msg("no event; want %s code %u value %d", input_kind_to_str(kind), code,
			 value);
	if (e.kind != kind || e.code != code || e.value != value)
		fail_msg("got %s code %u value %d; want %s code %u value %d",
			 input_kind_to_str((enum input_kind)e.kind), e.code, e.value,
			 input_kind_to_str(kind), code, value);
	assert_int_equal(e.device, device);
}

#endif
