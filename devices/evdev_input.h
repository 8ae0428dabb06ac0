/*
 * evdev_input.h - the kernel's evdev records (struct input_event, read
 * from /dev/input/eventN or taken from a recording) decoded into the one
 * event stream (devices/event.h).
 *
 * The kernel sends a device's state changes as a frame of records ended by
 * EV_SYN/SYN_REPORT (Documentation/input/event-codes.rst). As libinput's
 * fallback dispatch does, the decoder gathers a frame and applies it at
 * SYN_REPORT: relative motion summed into one INPUT_MOTION, wheels into
 * one INPUT_WHEEL per axis, absolute X/Y into one INPUT_POINTER, then the
 * buttons and keys in the order they came, then one INPUT_FRAME. Every
 * event carries the record's own (kernel) timestamp.
 *
 * SYN_DROPPED means the kernel's buffer for this client overflowed: the
 * pending frame and every record up to and including the next SYN_REPORT
 * are dropped, and resync_wanted is set. The backend then reads the key
 * state (EVIOCGKEY) and calls evdev_input_resync, which emits the
 * difference from what the decoder believed. Fixed size, nothing
 * allocates.
 */
#ifndef POSTURE_DEVICES_EVDEV_INPUT_H
#define POSTURE_DEVICES_EVDEV_INPUT_H

#include <stddef.h>
#include <stdint.h>

#include <linux/input.h>

#include "devices/devlog.h"
#include "devices/queue.h"

/* the size of one record in the bytes a device sends: 24 on LP64 */
#define EVDEV_INPUT_RECORD_SIZE sizeof(struct input_event)

/* the key-state bitmap, in the layout of EVIOCGKEY: bit c of byte c / 8 */
#define EVDEV_INPUT_KEYBITS (KEY_MAX / 8 + 1)

/*
 * Key and button changes a frame may hold. A real frame holds a few; a
 * frame with more loses the rest (counted) and asks for a resync, so the
 * key state is put right from the kernel's.
 */
#define EVDEV_INPUT_FRAME_KEYS 64

struct evdev_input_key {
	uint64_t t_us;
	uint16_t code;
	int32_t value;
};

struct evdev_input_axis {
	int32_t min, max; /* the caller's absinfo range */
	int32_t value;    /* the last value the device sent */
	uint8_t ranged;   /* evdev_input_set_abs was called */
};

struct evdev_input {
	uint16_t device;
	struct devlog log;

	/* the frame being gathered (applied at SYN_REPORT) */
	int64_t dx, dy;
	int64_t wheel[2], wheel_hires[2]; /* by enum input_wheel_axis */
	uint8_t have_motion, have_abs;
	uint8_t have_wheel[2], have_hires[2];
	uint64_t t_motion_us, t_abs_us, t_wheel_us[2];
	struct evdev_input_key keys[EVDEV_INPUT_FRAME_KEYS];
	unsigned nkeys;
	uint64_t t_last_us; /* the newest record's time, for logs */

	/*
	 * 1/120 detents not yet reported as a whole detent, for a wheel that
	 * sends only REL_*_HI_RES: each frame reports the whole detents of the
	 * sum (truncated toward zero) and keeps the rest; a turn the other way
	 * starts again from zero.
	 */
	int64_t hires_rest[2];

	struct evdev_input_axis abs[2]; /* ABS_X, ABS_Y */

	/* keys and buttons the decoder has reported down */
	uint8_t down[EVDEV_INPUT_KEYBITS];

	/* after SYN_DROPPED: dropping records up to the next SYN_REPORT */
	uint8_t dropping;
	/* the key state is in doubt: read EVIOCGKEY and call evdev_input_resync */
	uint8_t resync_wanted;

	/* counters */
	uint64_t records;         /* whole records decoded */
	uint64_t short_records;   /* byte tails shorter than a record, refused */
	uint64_t dropped_frames;  /* SYN_DROPPED seen */
	uint64_t unknown_events;  /* records of no meaning here (bad values, unknown codes) */
	uint64_t abs_unranged;    /* ABS_X/ABS_Y records without a range, ignored */
	uint64_t key_overflows;   /* key changes beyond EVDEV_INPUT_FRAME_KEYS in a frame */
};

/* sets e up for one device; who names it in log lines ("mouse (event3)") */
void
evdev_input_init(struct evdev_input *e, uint16_t device, const char *who);

/*
 * Gives ABS_X or ABS_Y its range (the device's absinfo minimum and
 * maximum): the pointer is then reported as (value - min) / (max - min),
 * 0..1. Returns 0, or -1 (nothing changed) for another code or an empty
 * range (max <= min).
 */
int
evdev_input_set_abs(struct evdev_input *e, uint16_t code, int32_t min, int32_t max);

/*
 * Decodes n bytes of whole struct input_event records, pushing the events
 * of every frame that ends (SYN_REPORT) into q. A tail shorter than a
 * record is refused: it is counted (short_records), logged, and nothing of
 * it is kept or queued. Returns 0, or -1 when a tail was refused.
 */
int
evdev_input_feed(struct evdev_input *e, const uint8_t *bytes, size_t n, struct input_queue *q);

/*
 * Puts the key state right after SYN_DROPPED: keybits is the kernel's key
 * state in the layout of EVIOCGKEY (EVDEV_INPUT_KEYBITS bytes). Emits a
 * release for each key or button believed down that the kernel says is
 * up, a press for each down that was not known, then one INPUT_FRAME, all
 * at t_us; clears resync_wanted. Returns the number of transitions
 * emitted.
 */
int
evdev_input_resync(struct evdev_input *e, const uint8_t *keybits, uint64_t t_us,
		   struct input_queue *q);

/*
 * Releases every key and button believed down (the device is gone), then
 * one INPUT_FRAME when anything was released, at t_us; the pending frame
 * is dropped. Returns the number of releases emitted.
 */
int
evdev_input_release_all(struct evdev_input *e, uint64_t t_us, struct input_queue *q);

/* 1 when code (an EV_KEY code) is a button (BTN_* ranges), 0 for a key */
int
evdev_input_is_button(uint16_t code);

/* 1 when the decoder believes key or button code is down */
int
evdev_input_key_down(const struct evdev_input *e, uint16_t code);

#endif
