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

#include <stddef.h>

#include "devices/event.h"

#define INPUT_QUEUE_CAP 4096
#define INPUT_QUEUE_SOFT 3072    /* merging starts here */
#define INPUT_QUEUE_RESERVE 512  /* the last places, for transitions only */

/*
 * What a decoder (evdev_input, hid_input, can_input) was given: a recorder
 * taps the queue to write down every call into a decoder that feeds it, so
 * that a replay makes the same calls into its own decoders (daemon/tape.h).
 */
enum input_tap_kind {
	INPUT_TAP_BYTES,   /* feed: a read's bytes (evdev records, a HID report, a CAN frame) */
	INPUT_TAP_RESYNC,  /* evdev_input_resync: bytes are the key bitmask read back */
	INPUT_TAP_RELEASE, /* release_all; arg: can_input's stale_valuators */
	INPUT_TAP_TICK,    /* can_input_tick: a valuator's stale timer */
};

struct input_queue_tap {
	/* a decoder of device is called (bytes: n of them, or NULL) */
	void (*call)(void *user, uint16_t device, enum input_tap_kind kind, int arg,
		     const uint8_t *bytes, size_t n, uint64_t t_us);
	/* an event pushed by no decoder (a device arriving or leaving) and not from the socket */
	void (*pushed)(void *user, const struct input_event_rec *e);
	void *user;
};

struct input_queue {
	struct input_event_rec ev[INPUT_QUEUE_CAP];
	unsigned head, len;
	uint64_t coalesced; /* events merged into a queued one */
	uint64_t dropped;   /* events lost to a full queue */
	const struct input_queue_tap *tap; /* NULL: not recorded */
	int in_decoder;     /* a decoder call is under way: its pushes are its own */
};

void input_queue_init(struct input_queue *q);

/* returns 0 when queued, 1 when merged or skipped, -1 when lost (queue full) */
int input_queue_push(struct input_queue *q, const struct input_event_rec *e);

/* queues INPUT_REMOVED for a device of class cls (what every backend says last) */
int input_queue_removed(struct input_queue *q, uint64_t t_us, uint16_t device, enum input_class cls);

/*
 * A decoder's entry points bracket their work with these (q may be NULL):
 * the call is given to the tap, and what it pushes is not reported again.
 */
void input_queue_decoder_enter(struct input_queue *q, uint16_t device, enum input_tap_kind kind,
			       int arg, const uint8_t *bytes, size_t n, uint64_t t_us);
void input_queue_decoder_leave(struct input_queue *q);
/* the oldest event into dest: 1, or 0 when empty */
int input_queue_pop(struct input_queue *q, struct input_event_rec *dest);

#endif
