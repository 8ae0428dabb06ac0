/*
 * queue.h - the fixed-capacity queue from the devices to the loop. Below
 * INPUT_QUEUE_SOFT events everything is queued as it comes. Above it
 * (the loop has fallen behind), a motion, wheel, absolute pointer or
 * valuator event is merged into the newest queued event of the same
 * device, kind and code when only frame ends stand between them, and
 * counted; a frame end right after another of the same device is skipped.
 * What cannot merge (motion right after a button) is still queued until
 * only INPUT_QUEUE_RESERVE places are left. Those are kept for buttons,
 * keys and devices coming and going, which are never merged: only a queue
 * full to INPUT_QUEUE_CAP loses one (counted). Nothing allocates.
 */
#ifndef POSTURE_DEVICES_QUEUE_H
#define POSTURE_DEVICES_QUEUE_H

#include "devices/event.h"

#define INPUT_QUEUE_CAP 4096
#define INPUT_QUEUE_SOFT 3072    /* merging starts here */
#define INPUT_QUEUE_RESERVE 512  /* the last places, for transitions only */

struct input_queue {
	struct input_event_rec ev[INPUT_QUEUE_CAP];
	unsigned head, len;
	uint64_t coalesced; /* events merged into a queued one */
	uint64_t dropped;   /* events lost to a full queue */
};

void input_queue_init(struct input_queue *q);

/* returns 0 when queued, 1 when merged or skipped, -1 when lost (queue full) */
int input_queue_push(struct input_queue *q, const struct input_event_rec *e);

/* queues INPUT_REMOVED for a device of class cls (what every backend says last) */
int input_queue_removed(struct input_queue *q, uint64_t t_us, uint16_t device, enum input_class cls);

/* the oldest event into dest: 1, or 0 when empty */
int input_queue_pop(struct input_queue *q, struct input_event_rec *dest);

#endif
