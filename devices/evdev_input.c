/* evdev_input.c - struct input_event records into events (see evdev_input.h) */
#include "devices/evdev_input.h"

#include <string.h>

void
evdev_input_init(struct evdev_input *e, uint16_t device, const char *who)
{
	memset(e, 0, sizeof *e);
	e->device = device;
	devlog_init(&e->log, who);
}

int
evdev_input_set_abs(struct evdev_input *e, uint16_t code, int32_t min, int32_t max)
{
	if (code != ABS_X && code != ABS_Y)
		return -1;
	if (max <= min)
		return -1;
	struct evdev_input_axis *a = &e->abs[code];
	if (!a->ranged)
		a->value = min;
	a->min = min;
	a->max = max;
	a->ranged = 1;
	return 0;
}

int
evdev_input_is_button(uint16_t code)
{
	/* the BTN_* blocks of input-event-codes.h; everything else is a key */
	return (code >= BTN_MISC && code <= BTN_GEAR_UP) ||
	       (code >= BTN_DPAD_UP && code <= BTN_DPAD_RIGHT) ||
	       (code >= BTN_TRIGGER_HAPPY && code <= BTN_TRIGGER_HAPPY40);
}

int
evdev_input_key_down(const struct evdev_input *e, uint16_t code)
{
	if (code > KEY_MAX)
		return 0;
	return (e->down[code / 8] >> (code % 8)) & 1;
}

static enum input_kind
kind_of(uint16_t code)
{
	return evdev_input_is_button(code) ? INPUT_BUTTON : INPUT_KEY;
}

static void
set_down(struct evdev_input *e, uint16_t code, int down)
{
	if (down)
		e->down[code / 8] |= (uint8_t)(1u << (code % 8));
	else
		e->down[code / 8] &= (uint8_t)~(1u << (code % 8));
}

static void
clear_pending(struct evdev_input *e)
{
	e->dx = e->dy = 0;
	e->have_motion = 0;
	e->have_abs = 0;
	for (int a = 0; a < 2; a++) {
		e->wheel[a] = e->wheel_hires[a] = 0;
		e->have_wheel[a] = e->have_hires[a] = 0;
	}
	e->nkeys = 0;
}

static void
push(struct evdev_input *e, struct input_queue *q, enum input_kind kind, uint16_t code,
     int32_t value, uint64_t t_us)
{
	struct input_event_rec ev = {
		.t_us = t_us,
		.device = e->device,
		.kind = (uint8_t)kind,
		.code = code,
		.value = value,
	};
	input_queue_push(q, &ev);
}

static int32_t
clamp32(int64_t v)
{
	if (v > INT32_MAX)
		return INT32_MAX;
	if (v < INT32_MIN)
		return INT32_MIN;
	return (int32_t)v;
}

/* the axis's value in 0..1 by its range; 0 for an axis without one */
static double
normalise(const struct evdev_input_axis *a)
{
	if (!a->ranged)
		return 0;
	double v = ((double)a->value - a->min) / ((double)a->max - a->min);
	return v < 0 ? 0 : v > 1 ? 1 : v;
}

/* one wheel axis's event for the frame: detents, and 1/120 where the device sends them */
static void
apply_wheel(struct evdev_input *e, int a, struct input_queue *q)
{
	struct input_event_rec ev = {
		.t_us = e->t_wheel_us[a],
		.device = e->device,
		.kind = INPUT_WHEEL,
		.code = (uint16_t)a,
	};
	if (e->have_hires[a]) {
		int64_t hi = e->wheel_hires[a];
		ev.flags = INPUT_F_HIRES;
		ev.x = (double)hi;
		if (e->have_wheel[a]) {
			/* the device counted its own detents */
			ev.value = clamp32(e->wheel[a]);
			e->hires_rest[a] = 0;
		} else {
			/* whole detents of the rest, kept apart from a turn the other way */
			int64_t *rest = &e->hires_rest[a];
			if ((hi > 0 && *rest < 0) || (hi < 0 && *rest > 0))
				*rest = 0;
			*rest += hi;
			int64_t whole = *rest / 120;
			*rest -= whole * 120;
			ev.value = clamp32(whole);
		}
	} else {
		ev.value = clamp32(e->wheel[a]);
		ev.x = (double)e->wheel[a] * 120;
		e->hires_rest[a] = 0;
	}
	input_queue_push(q, &ev);
}

/* one key or button change, filtered by what was reported: nothing twice */
static void
apply_key(struct evdev_input *e, const struct evdev_input_key *k, struct input_queue *q)
{
	int button = evdev_input_is_button(k->code);
	enum input_kind kind = kind_of(k->code);
	int down = evdev_input_key_down(e, k->code);
	switch (k->value) {
	case 0:
		if (!down)
			return;
		set_down(e, k->code, 0);
		push(e, q, kind, k->code, 0, k->t_us);
		return;
	case 1:
		if (down)
			return;
		set_down(e, k->code, 1);
		push(e, q, kind, k->code, 1, k->t_us);
		return;
	case 2:
		/* a repeat of a key not down is its press; buttons do not repeat */
		if (!down) {
			set_down(e, k->code, 1);
			push(e, q, kind, k->code, 1, k->t_us);
		} else if (!button) {
			push(e, q, kind, k->code, 2, k->t_us);
		}
		return;
	}
}

/* SYN_REPORT: the frame's events, in the order motion, pointer, wheels, keys, frame */
static void
apply_frame(struct evdev_input *e, uint64_t t_us, struct input_queue *q)
{
	if (e->have_motion) {
		struct input_event_rec ev = {
			.t_us = e->t_motion_us,
			.device = e->device,
			.kind = INPUT_MOTION,
			.x = (double)e->dx,
			.y = (double)e->dy,
		};
		input_queue_push(q, &ev);
	}
	if (e->have_abs) {
		struct input_event_rec ev = {
			.t_us = e->t_abs_us,
			.device = e->device,
			.kind = INPUT_POINTER,
			.code = INPUT_POINTER_VIEW_NONE,
			.x = normalise(&e->abs[ABS_X]),
			.y = normalise(&e->abs[ABS_Y]),
		};
		input_queue_push(q, &ev);
	}
	for (int a = 0; a < 2; a++)
		if (e->have_wheel[a] || e->have_hires[a])
			apply_wheel(e, a, q);
	for (unsigned i = 0; i < e->nkeys; i++)
		apply_key(e, &e->keys[i], q);
	push(e, q, INPUT_FRAME, 0, 0, t_us);
	clear_pending(e);
}

static void
unknown(struct evdev_input *e, const struct input_event *r, uint64_t t_us)
{
	e->unknown_events++;
	devlog(&e->log, t_us, DEVLOG_DEVICE, "ignored event type %#x code %#x value %d",
	       (unsigned)r->type, (unsigned)r->code, (int)r->value);
}

static void
gather_key(struct evdev_input *e, const struct input_event *r, uint64_t t_us)
{
	if (r->code > KEY_MAX || r->value < 0 || r->value > 2) {
		unknown(e, r, t_us);
		return;
	}
	if (e->nkeys == EVDEV_INPUT_FRAME_KEYS) {
		e->key_overflows++;
		e->resync_wanted = 1;
		devlog(&e->log, t_us, DEVLOG_DEVICE,
		       "more than %d key changes in one frame, key state resync wanted",
		       EVDEV_INPUT_FRAME_KEYS);
		return;
	}
	struct evdev_input_key *k = &e->keys[e->nkeys++];
	k->t_us = t_us;
	k->code = r->code;
	k->value = r->value;
}

static void
gather_rel(struct evdev_input *e, const struct input_event *r, uint64_t t_us)
{
	int a;
	switch (r->code) {
	case REL_X:
		e->dx += r->value;
		break;
	case REL_Y:
		e->dy += r->value;
		break;
	case REL_WHEEL:
	case REL_HWHEEL:
		a = r->code == REL_WHEEL ? INPUT_WHEEL_V : INPUT_WHEEL_H;
		e->wheel[a] += r->value;
		e->have_wheel[a] = 1;
		e->t_wheel_us[a] = t_us;
		return;
	case REL_WHEEL_HI_RES:
	case REL_HWHEEL_HI_RES:
		a = r->code == REL_WHEEL_HI_RES ? INPUT_WHEEL_V : INPUT_WHEEL_H;
		e->wheel_hires[a] += r->value;
		e->have_hires[a] = 1;
		e->t_wheel_us[a] = t_us;
		return;
	default:
		unknown(e, r, t_us);
		return;
	}
	e->have_motion = 1;
	e->t_motion_us = t_us;
}

static void
gather_abs(struct evdev_input *e, const struct input_event *r, uint64_t t_us)
{
	if ((r->code != ABS_X && r->code != ABS_Y) || !e->abs[r->code].ranged) {
		e->abs_unranged++;
		return;
	}
	e->abs[r->code].value = r->value;
	e->have_abs = 1;
	e->t_abs_us = t_us;
}

static void
decode(struct evdev_input *e, const struct input_event *r, struct input_queue *q)
{
	uint64_t t_us = (uint64_t)r->input_event_sec * 1000000u + (uint64_t)r->input_event_usec;
	e->t_last_us = t_us;
	e->records++;
	if (r->type == EV_SYN) {
		switch (r->code) {
		case SYN_REPORT:
			if (e->dropping) {
				e->dropping = 0;
				clear_pending(e);
			} else {
				apply_frame(e, t_us, q);
			}
			return;
		case SYN_DROPPED:
			e->dropped_frames++;
			e->dropping = 1;
			e->resync_wanted = 1;
			clear_pending(e);
			devlog(&e->log, t_us, DEVLOG_KERNEL,
			       "events lost (SYN_DROPPED), key state resync wanted");
			return;
		case SYN_CONFIG:
		case SYN_MT_REPORT:
			return;
		default:
			unknown(e, r, t_us);
			return;
		}
	}
	if (e->dropping)
		return;
	switch (r->type) {
	case EV_KEY:
		gather_key(e, r, t_us);
		return;
	case EV_REL:
		gather_rel(e, r, t_us);
		return;
	case EV_ABS:
		gather_abs(e, r, t_us);
		return;
	case EV_MSC:
	case EV_LED:
	case EV_SND:
		return;
	default:
		unknown(e, r, t_us);
		return;
	}
}

static int
evdev_input_feed_work(struct evdev_input *e, const uint8_t *bytes, size_t n, struct input_queue *q)
{
	size_t whole = n - n % sizeof(struct input_event);
	for (size_t off = 0; off < whole; off += sizeof(struct input_event)) {
		struct input_event r;
		memcpy(&r, bytes + off, sizeof r);
		decode(e, &r, q);
	}
	if (whole == n)
		return 0;
	/* a record cut short: the kernel never sends one, so refuse it whole */
	e->short_records++;
	devlog(&e->log, e->t_last_us, DEVLOG_KERNEL,
	       "%zu bytes at offset %zu are not a whole record of %zu bytes, refused", n - whole,
	       whole, sizeof(struct input_event));
	return -1;
}

/* what the tap of q records (queue.h), then the work */
int
evdev_input_feed(struct evdev_input *e, const uint8_t *bytes, size_t n, struct input_queue *q)
{
	input_queue_decoder_enter(q, e->device, INPUT_TAP_BYTES, 0, bytes, n, 0);
	int rc = evdev_input_feed_work(e, bytes, n, q);
	input_queue_decoder_leave(q);
	return rc;
}

static int
evdev_input_resync_work(struct evdev_input *e, const uint8_t *keybits, uint64_t t_us,
		   struct input_queue *q)
{
	int n = 0;
	/* releases first, so no key is reported down twice over */
	for (unsigned c = 0; c <= KEY_MAX; c++) {
		int kernel = (keybits[c / 8] >> (c % 8)) & 1;
		if (evdev_input_key_down(e, (uint16_t)c) && !kernel) {
			set_down(e, (uint16_t)c, 0);
			push(e, q, kind_of((uint16_t)c), (uint16_t)c, 0, t_us);
			n++;
		}
	}
	for (unsigned c = 0; c <= KEY_MAX; c++) {
		int kernel = (keybits[c / 8] >> (c % 8)) & 1;
		if (!evdev_input_key_down(e, (uint16_t)c) && kernel) {
			set_down(e, (uint16_t)c, 1);
			push(e, q, kind_of((uint16_t)c), (uint16_t)c, 1, t_us);
			n++;
		}
	}
	push(e, q, INPUT_FRAME, 0, 0, t_us);
	e->resync_wanted = 0;
	return n;
}

/* what the tap of q records (queue.h), then the work */
int
evdev_input_resync(struct evdev_input *e, const uint8_t *keybits, uint64_t t_us, struct input_queue *q)
{
	input_queue_decoder_enter(q, e->device, INPUT_TAP_RESYNC, 0, keybits, KEY_MAX / 8 + 1, t_us);
	int rc = evdev_input_resync_work(e, keybits, t_us, q);
	input_queue_decoder_leave(q);
	return rc;
}

static int
evdev_input_release_all_work(struct evdev_input *e, uint64_t t_us, struct input_queue *q)
{
	int n = 0;
	clear_pending(e);
	e->dropping = 0;
	for (unsigned c = 0; c <= KEY_MAX; c++) {
		if (!evdev_input_key_down(e, (uint16_t)c))
			continue;
		set_down(e, (uint16_t)c, 0);
		push(e, q, kind_of((uint16_t)c), (uint16_t)c, 0, t_us);
		n++;
	}
	if (n)
		push(e, q, INPUT_FRAME, 0, 0, t_us);
	return n;
}

/* what the tap of q records (queue.h), then the work */
int
evdev_input_release_all(struct evdev_input *e, uint64_t t_us, struct input_queue *q)
{
	input_queue_decoder_enter(q, e->device, INPUT_TAP_RELEASE, 0, NULL, 0, t_us);
	int rc = evdev_input_release_all_work(e, t_us, q);
	input_queue_decoder_leave(q);
	return rc;
}
