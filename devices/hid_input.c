/* hid_input.c - HID input reports to events (see hid_input.h) */
#include "devices/hid_input.h"

#include <linux/input-event-codes.h>
#include <string.h>

#include "devices/hid_keymap.h"

_Static_assert(HID_INPUT_CODES == KEY_MAX + 1, "one held slot per key code");

#define USAGE_GD_SYSTEM_CONTROL 0x00010080u

/* what one report adds up to, flushed at its end */
struct frame {
	int64_t dx, dy;
	int motion, pointer;
	int64_t wheel[2], wheel_hi[2]; /* detents, 1/120 detent */
	int wheel_seen[2], hires[2];
};

static int32_t
saturate(int64_t v)
{
	return v > INT32_MAX ? INT32_MAX : v < INT32_MIN ? INT32_MIN : (int32_t)v;
}

enum hid_input_role
hid_input_map(const struct hid_desc_field *f, uint32_t usage, uint16_t *code)
{
	uint32_t page = usage >> 16, id = usage & 0xffff;
	int rel = (f->flags & HID_FIELD_RELATIVE) != 0;
	*code = 0;
	if (f->flags & HID_FIELD_CONSTANT)
		return HID_ROLE_NONE;
	switch (page) {
	case HID_PAGE_KEYBOARD: {
		uint16_t k = hid_keymap_key(id);
		if (k == 0)
			return HID_ROLE_NONE;
		*code = k;
		return HID_ROLE_KEY;
	}
	case HID_PAGE_BUTTON: {
		/* button n is code n - 1 above a base the collections choose */
		uint32_t c = (id - 1) & 0xffff;
		switch (f->application) {
		case HID_USAGE_GD_MOUSE:
		case HID_USAGE_GD_POINTER:
			c += BTN_MOUSE;
			break;
		case HID_USAGE_GD_JOYSTICK:
			c += c <= 0xf ? BTN_JOYSTICK : BTN_TRIGGER_HAPPY - 0x10;
			break;
		case HID_USAGE_GD_GAMEPAD:
			c += c <= 0xf ? BTN_GAMEPAD : BTN_TRIGGER_HAPPY - 0x10;
			break;
		default:
			switch (f->physical) {
			case HID_USAGE_GD_MOUSE:
			case HID_USAGE_GD_POINTER:
				c += BTN_MOUSE;
				break;
			case HID_USAGE_GD_JOYSTICK:
				c += BTN_JOYSTICK;
				break;
			case HID_USAGE_GD_GAMEPAD:
				c += BTN_GAMEPAD;
				break;
			default:
				c += BTN_MISC;
			}
		}
		if (c > KEY_MAX)
			return HID_ROLE_NONE;
		*code = (uint16_t)c;
		return HID_ROLE_BUTTON;
	}
	case 0x0001:
		if (f->application == USAGE_GD_SYSTEM_CONTROL)
			return HID_ROLE_NONE;
		switch (usage) {
		case HID_USAGE_GD_X:
			return rel ? HID_ROLE_REL_X : HID_ROLE_ABS_X;
		case HID_USAGE_GD_Y:
			return rel ? HID_ROLE_REL_Y : HID_ROLE_ABS_Y;
		case HID_USAGE_GD_WHEEL:
			return rel ? HID_ROLE_WHEEL : HID_ROLE_NONE;
		}
		return HID_ROLE_NONE;
	case 0x000c:
		/* AC Pan is a relative wheel whatever the field says */
		return usage == HID_USAGE_CONSUMER_AC_PAN ? HID_ROLE_HWHEEL : HID_ROLE_NONE;
	}
	return HID_ROLE_NONE;
}

void
hid_input_init(struct hid_input *h, const struct hid_desc *d, uint16_t device, const char *who)
{
	memset(h, 0, sizeof *h);
	h->d = d;
	h->device = device;
	devlog_init(&h->log, who);
	/* a variable field's values map the same way in every report */
	for (unsigned k = 0; k < d->nfields; k++) {
		const struct hid_desc_field *f = &d->fields[k];
		if (f->value_first == HID_DESC_NONE || !(f->flags & HID_FIELD_VARIABLE))
			continue;
		for (unsigned i = 0; i < f->count; i++) {
			unsigned s = f->value_first + i;
			uint32_t usage = hid_desc_usage(d, f, i);
			h->role[s] = (uint8_t)hid_input_map(f, usage, &h->code[s]);
		}
	}
}

/* hid_field_extract: n bits (1-32) at bit offset, little-endian */
static uint32_t
extract(const uint8_t *data, unsigned offset, unsigned n)
{
	unsigned idx = offset >> 3, shift = offset & 7;
	unsigned nbytes = (shift + n + 7) >> 3;
	uint64_t v = 0;
	for (unsigned i = 0; i < nbytes; i++)
		v |= (uint64_t)data[idx + i] << (8 * i);
	v >>= shift;
	return n < 32 ? (uint32_t)v & ((1u << n) - 1) : (uint32_t)v;
}

/* snto32: an n-bit two's complement value widened */
static int32_t
sign_extend(uint32_t value, unsigned n)
{
	if (value == 0 || n == 0 || n >= 32)
		return (int32_t)value;
	if (value & (1u << (n - 1)))
		value |= ~0u << n;
	return (int32_t)value;
}

int32_t
hid_input_value(const struct hid_desc_field *f, const uint8_t *data, unsigned i)
{
	uint32_t v = extract(data, f->bit_offset + i * f->size, f->size);
	return f->logical_min < 0 ? sign_extend(v, f->size) : (int32_t)v;
}

static void
push(struct hid_input *h, struct input_queue *q, uint64_t t, enum input_kind kind, uint16_t code,
     int32_t value, double x, double y, uint8_t flags)
{
	struct input_event_rec e = {
		.t_us = t,
		.device = h->device,
		.kind = (uint8_t)kind,
		.flags = flags,
		.code = code,
		.value = value,
		.x = x,
		.y = y,
	};
	input_queue_push(q, &e);
}

/* a button or key to state `down`, if it is not there already */
static void
set_key(struct hid_input *h, struct input_queue *q, uint64_t t, enum hid_input_role role,
	uint16_t code, int down)
{
	enum input_kind kind = role == HID_ROLE_BUTTON ? INPUT_BUTTON : INPUT_KEY;
	if (!!h->held[code] == !!down)
		return;
	h->held[code] = down ? (uint8_t)(kind + 1) : 0;
	push(h, q, t, kind, code, down ? 1 : 0, 0, 0, 0);
}

/* hidinput_handle_scroll: value in 1/multiplier detents */
static void
scroll(struct hid_input *h, const struct hid_desc_field *f, unsigned slot, int axis, int32_t v,
       struct frame *fr)
{
	if (v == 0)
		return;
	int64_t m = f->resolution_multiplier ? f->resolution_multiplier : 1;
	int64_t hi = (int64_t)v * 120 / m;
	int64_t acc = h->value[slot] + hi;
	int64_t lo = acc / 120;
	h->value[slot] = (int32_t)(acc - lo * 120);
	fr->wheel[axis] += lo;
	fr->wheel_hi[axis] += hi;
	fr->wheel_seen[axis] = 1;
	fr->hires[axis] |= m != 1;
}

static double
normalise(const struct hid_desc_field *f, int32_t v)
{
	return ((double)v - f->logical_min) / ((double)f->logical_max - f->logical_min);
}

/* hidinput_hid_event for one value of a variable field */
static void
variable(struct hid_input *h, const struct hid_desc_field *f, unsigned slot, int32_t raw,
	 uint64_t t, struct input_queue *q, struct frame *fr)
{
	enum hid_input_role role = (enum hid_input_role)h->role[slot];
	int32_t v = raw;
	int rel = (f->flags & HID_FIELD_RELATIVE) != 0;
	if (role == HID_ROLE_NONE)
		return;

	/* out of range: dropped with a null state, clamped without */
	if (f->logical_min < f->logical_max) {
		if ((f->flags & HID_FIELD_NULL_STATE) &&
		    (v < f->logical_min || v > f->logical_max))
			return;
		if (v < f->logical_min)
			v = f->logical_min;
		if (v > f->logical_max)
			v = f->logical_max;
	}

	/* wheels keep their remainder in the slot */
	if (role == HID_ROLE_WHEEL || role == HID_ROLE_HWHEEL) {
		scroll(h, f, slot, role == HID_ROLE_WHEEL ? INPUT_WHEEL_V : INPUT_WHEEL_H, v, fr);
		return;
	}

	/* absolute data that did not change says nothing */
	if (!rel && !(f->flags & HID_FIELD_BUFFERED_BYTES)) {
		int same = v == h->value[slot];
		h->value[slot] = raw;
		if (same)
			return;
	}

	switch (role) {
	case HID_ROLE_KEY:
	case HID_ROLE_BUTTON:
		if (!rel)
			set_key(h, q, t, role, h->code[slot], v != 0);
		break;
	case HID_ROLE_REL_X:
		fr->dx += v;
		fr->motion |= v != 0;
		break;
	case HID_ROLE_REL_Y:
		fr->dy += v;
		fr->motion |= v != 0;
		break;
	case HID_ROLE_ABS_X:
		if (f->logical_min < f->logical_max) {
			h->x = normalise(f, v);
			fr->pointer = 1;
		}
		break;
	case HID_ROLE_ABS_Y:
		if (f->logical_min < f->logical_max) {
			h->y = normalise(f, v);
			fr->pointer = 1;
		}
		break;
	case HID_ROLE_NONE:
	case HID_ROLE_WHEEL:
	case HID_ROLE_HWHEEL:
		break;
	}
}

/* hid_array_value_is_valid: the value names one of the field's usages */
static int
array_valid(const struct hid_desc_field *f, int32_t v)
{
	uint32_t nusages = f->usages > f->count ? f->usages : f->count;
	return v >= f->logical_min && v <= f->logical_max &&
	       (uint32_t)((int64_t)v - f->logical_min) < nusages;
}

static int
has(const int32_t *values, unsigned n, int32_t v)
{
	for (unsigned i = 0; i < n; i++)
		if (values[i] == v)
			return 1;
	return 0;
}

/* a usage of an array field going down or up */
static void
array_key(struct hid_input *h, const struct hid_desc_field *f, int32_t v, int down, uint64_t t,
	  struct input_queue *q)
{
	uint16_t code;
	uint32_t usage = hid_desc_usage(h->d, f, (uint32_t)((int64_t)v - f->logical_min));
	enum hid_input_role role = hid_input_map(f, usage, &code);
	if (role == HID_ROLE_KEY || role == HID_ROLE_BUTTON)
		set_key(h, q, t, role, code, down);
}

/* hid_input_array_field: press what appeared, release what went */
static void
array(struct hid_input *h, const struct hid_desc_field *f, const uint8_t *data, uint64_t t,
      struct input_queue *q)
{
	int32_t *prev = &h->value[f->value_first];
	int32_t cur[HID_DESC_MAX_ARRAY];
	unsigned n = f->count;

	/* ErrorRollOver: the whole field is ignored, its keys stay as they were */
	for (unsigned i = 0; i < n; i++) {
		cur[i] = hid_input_value(f, data, i);
		if (array_valid(f, cur[i]) &&
		    hid_desc_usage(h->d, f, (uint32_t)((int64_t)cur[i] - f->logical_min)) ==
			    HID_USAGE_KEYBOARD_ERROR_ROLLOVER)
			return;
	}

	for (unsigned i = 0; i < n; i++) {
		if (array_valid(f, prev[i]) && !has(cur, n, prev[i]))
			array_key(h, f, prev[i], 0, t, q);
		if (array_valid(f, cur[i]) && !has(prev, n, cur[i]))
			array_key(h, f, cur[i], 1, t, q);
	}
	memcpy(prev, cur, n * sizeof cur[0]);
}

/*
 * a bitmap (1-bit absolute values from 0): only the bits that changed can
 * say anything, so the others are skipped a byte at a time
 */
static void
bitmap(struct hid_input *h, const struct hid_desc_field *f, const uint8_t *data, uint64_t t,
       struct input_queue *q, struct frame *fr)
{
	for (unsigned i = 0; i < f->count; i += 8) {
		unsigned k = f->count - i < 8 ? f->count - i : 8;
		uint32_t bits = extract(data, f->bit_offset + i, k);
		uint8_t *seen = &h->bits[f->value_first + i];
		if (bits == *seen) /* most bytes of a keyboard's bitmap, most of the time */
			continue;
		const int32_t *prev = &h->value[f->value_first + i];
		for (unsigned j = 0; j < k; j++) {
			int32_t v = (int32_t)(bits >> j & 1);
			if (v != prev[j])
				variable(h, f, f->value_first + i + j, v, t, q, fr);
		}
		*seen = (uint8_t)bits;
	}
}

/* a dropped report: counted and blamed on the device */
static int
drop(struct hid_input *h, uint64_t *counter, uint64_t t, const char *what, unsigned id, size_t n,
     unsigned expected)
{
	(*counter)++;
	if (expected)
		devlog(&h->log, t, DEVLOG_DEVICE, "report %u %s: %zu bytes, expected %u (dropped)",
		       id, what, n, expected);
	else
		devlog(&h->log, t, DEVLOG_DEVICE, "report %u %s (%zu bytes, dropped)", id, what, n);
	return -1;
}

static int
hid_input_feed_work(struct hid_input *h, const uint8_t *report, size_t n, uint64_t t_us,
	       struct input_queue *q)
{
	const struct hid_desc *d = h->d;
	struct frame fr;

	/* which report: the first byte when the descriptor numbers them */
	if (n == 0)
		return drop(h, &h->unknown_reports, t_us, "empty", 0, n, 0);
	unsigned id = d->numbered ? report[0] : 0;
	const struct hid_desc_report *rep = hid_desc_report_by_id(d, id);
	if (!rep)
		return drop(h, &h->unknown_reports, t_us, "not in the descriptor", id, n, 0);
	if (n < rep->bytes)
		return drop(h, &h->short_reports, t_us, "short", id, n, rep->bytes);
	if (n > rep->bytes)
		return drop(h, &h->long_reports, t_us, "long", id, n, rep->bytes);
	const uint8_t *data = report + (d->numbered ? 1 : 0);
	h->reports++;

	/* fields in descriptor order; keys and buttons go out as they change */
	memset(&fr, 0, sizeof fr);
	for (unsigned k = 0; k < rep->field_count; k++) {
		const struct hid_desc_field *f = &d->fields[rep->field_first + k];
		if (f->value_first == HID_DESC_NONE)
			continue;
		if (!(f->flags & HID_FIELD_VARIABLE)) {
			array(h, f, data, t_us, q);
			continue;
		}
		if (f->size == 1 && f->logical_min == 0 && f->logical_max >= 1 &&
		    !(f->flags & (HID_FIELD_RELATIVE | HID_FIELD_BUFFERED_BYTES))) {
			bitmap(h, f, data, t_us, q, &fr);
			continue;
		}
		for (unsigned i = 0; i < f->count; i++) {
			int32_t v = hid_input_value(f, data, i);
			variable(h, f, f->value_first + i, v, t_us, q, &fr);
		}
	}

	/* then the axes the report moved, and the frame end */
	if (fr.motion)
		push(h, q, t_us, INPUT_MOTION, 0, 0, (double)fr.dx, (double)fr.dy, 0);
	if (fr.pointer)
		push(h, q, t_us, INPUT_POINTER, INPUT_POINTER_VIEW_NONE, 0, h->x, h->y, 0);
	for (int a = 0; a < 2; a++)
		if (fr.wheel_seen[a])
			push(h, q, t_us, INPUT_WHEEL, (uint16_t)a, saturate(fr.wheel[a]),
			     (double)fr.wheel_hi[a], 0, fr.hires[a] ? INPUT_F_HIRES : 0);
	push(h, q, t_us, INPUT_FRAME, 0, 0, 0, 0, 0);
	return 0;
}

/* what the tap of q records (queue.h), then the work */
int
hid_input_feed(struct hid_input *h, const uint8_t *report, size_t n, uint64_t t_us, struct input_queue *q)
{
	input_queue_decoder_enter(q, h->device, INPUT_TAP_BYTES, 0, report, n, t_us);
	int rc = hid_input_feed_work(h, report, n, t_us, q);
	input_queue_decoder_leave(q);
	return rc;
}

static void
hid_input_release_all_work(struct hid_input *h, uint64_t t_us, struct input_queue *q)
{
	int any = 0;
	for (unsigned c = 0; c < HID_INPUT_CODES; c++) {
		if (!h->held[c])
			continue;
		enum input_kind kind = (enum input_kind)(h->held[c] - 1);
		h->held[c] = 0;
		push(h, q, t_us, kind, (uint16_t)c, 0, 0, 0, 0);
		any = 1;
	}
	/* a fresh start: the next report presses what it holds */
	memset(h->value, 0, sizeof h->value);
	memset(h->bits, 0, sizeof h->bits);
	if (any)
		push(h, q, t_us, INPUT_FRAME, 0, 0, 0, 0, 0);
}

/* what the tap of q records (queue.h), then the work */
void
hid_input_release_all(struct hid_input *h, uint64_t t_us, struct input_queue *q)
{
	input_queue_decoder_enter(q, h->device, INPUT_TAP_RELEASE, 0, NULL, 0, t_us);
	hid_input_release_all_work(h, t_us, q);
	input_queue_decoder_leave(q);
}
