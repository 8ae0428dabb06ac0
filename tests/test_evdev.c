/*
 * test_evdev.c - evdev records into events, and evemu files.
 *
 * The decoder is checked against the kernel's documented semantics
 * (Documentation/input/event-codes.rst: a frame is applied at SYN_REPORT,
 * EV_REL values are deltas, EV_KEY values 0/1/2, SYN_DROPPED drops to the
 * next SYN_REPORT) and libinput's rules (presses of keys already down and
 * releases of keys not down are ignored; the BTN_* blocks are buttons),
 * with answers worked by hand. The evemu reader is checked against
 * libevemu's own reader: tests/input/evdev/NAME.evemu were written by
 * libevemu (evemu_write, evemu_record) and NAME.ref is what libevemu's
 * reader makes of them (tests/input/evdev/README).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "alloc_count.h"
#include "test_util.h"

#include "devices/evdev_input.h"
#include "devices/rec_evemu.h"

#define DATA "tests/input/evdev/"

static struct input_queue q;
static struct evdev_input dec;
static FILE *devnull;

static int
setup(void **state)
{
	(void)state;
	input_queue_init(&q);
	evdev_input_init(&dec, 7, "test mouse");
	if (!devnull)
		devnull = fopen("/dev/null", "w");
	dec.log.out = devnull; /* the log lines are not under test */
	return 0;
}

/* one record's bytes at sec.usec */
static void
rec(uint8_t *dest, uint64_t sec, uint32_t usec, uint16_t type, uint16_t code, int32_t value)
{
	struct input_event r;
	memset(&r, 0, sizeof r);
	r.input_event_sec = (time_t)sec;
	r.input_event_usec = (suseconds_t)usec;
	r.type = type;
	r.code = code;
	r.value = value;
	memcpy(dest, &r, sizeof r);
}

/* feeds one record */
static int
feed1(uint64_t sec, uint32_t usec, uint16_t type, uint16_t code, int32_t value)
{
	uint8_t b[sizeof(struct input_event)];
	rec(b, sec, usec, type, code, value);
	return evdev_input_feed(&dec, b, sizeof b, &q);
}

static void
syn(uint64_t sec, uint32_t usec)
{
	assert_int_equal(feed1(sec, usec, EV_SYN, SYN_REPORT, 0), 0);
}

static struct input_event_rec
next(void)
{
	struct input_event_rec ev;
	if (!input_queue_pop(&q, &ev))
		fail_msg("the queue is empty, an event was expected");
	return ev;
}

static void
expect(enum input_kind kind, uint16_t code, int32_t value)
{
	struct input_event_rec ev = next();
	if (ev.kind != kind || ev.code != code || ev.value != value)
		fail_msg("got %s code %#x value %d, want %s code %#x value %d",
			 input_kind_to_str((enum input_kind)ev.kind), ev.code, ev.value,
			 input_kind_to_str(kind), code, value);
	assert_int_equal(ev.device, 7);
}

static void
expect_frame(uint64_t t_us)
{
	struct input_event_rec ev = next();
	assert_int_equal(ev.kind, INPUT_FRAME);
	assert_int_equal(ev.t_us, t_us);
}

static void
expect_empty(void)
{
	assert_int_equal(q.len, 0);
}

/* ---- frames --------------------------------------------------------------- */

static void
test_motion_summed_at_syn_report(void **state)
{
	(void)state;
	feed1(10, 5, EV_REL, REL_X, 3);
	feed1(10, 5, EV_REL, REL_Y, -2);
	feed1(10, 6, EV_REL, REL_X, 4);
	expect_empty(); /* nothing before the frame ends */
	syn(10, 7);
	struct input_event_rec ev = next();
	assert_int_equal(ev.kind, INPUT_MOTION);
	assert_near(ev.x, 7, 0);
	assert_near(ev.y, -2, 0);
	assert_int_equal(ev.t_us, 10000006); /* the newest REL record's kernel time */
	expect_frame(10000007);
	expect_empty();
	/* an empty frame is still a frame */
	syn(11, 0);
	expect_frame(11000000);
}

static void
test_buttons_and_keys(void **state)
{
	(void)state;
	feed1(1, 0, EV_MSC, MSC_SCAN, 0x90001); /* ignored */
	feed1(1, 0, EV_KEY, BTN_LEFT, 1);
	feed1(1, 0, EV_KEY, KEY_A, 1);
	feed1(1, 0, EV_KEY, BTN_TRIGGER_HAPPY1, 1);
	feed1(1, 0, EV_KEY, KEY_OK, 1);
	feed1(1, 0, EV_LED, LED_CAPSL, 1); /* ignored */
	syn(1, 0);
	expect(INPUT_BUTTON, BTN_LEFT, 1);
	expect(INPUT_KEY, KEY_A, 1);
	expect(INPUT_BUTTON, BTN_TRIGGER_HAPPY1, 1);
	expect(INPUT_KEY, KEY_OK, 1);
	expect_frame(1000000);
	expect_empty();
	assert_true(evdev_input_key_down(&dec, KEY_A));
	assert_true(evdev_input_key_down(&dec, BTN_LEFT));

	/* a repeat, then the release; a button's value 2 is no event */
	feed1(2, 0, EV_KEY, KEY_A, 2);
	feed1(2, 0, EV_KEY, BTN_LEFT, 2);
	syn(2, 0);
	expect(INPUT_KEY, KEY_A, 2);
	expect_frame(2000000);
	feed1(3, 0, EV_KEY, KEY_A, 0);
	feed1(3, 0, EV_KEY, BTN_LEFT, 0);
	syn(3, 0);
	expect(INPUT_KEY, KEY_A, 0);
	expect(INPUT_BUTTON, BTN_LEFT, 0);
	expect_frame(3000000);
	assert_int_equal(dec.unknown_events, 0);
}

static void
test_key_rules(void **state)
{
	(void)state;
	/* a repeat of a key not down is its press */
	feed1(1, 0, EV_KEY, KEY_B, 2);
	syn(1, 0);
	expect(INPUT_KEY, KEY_B, 1);
	expect_frame(1000000);
	/* libinput: a press of a key down, a release of a key up: ignored */
	feed1(2, 0, EV_KEY, KEY_B, 1);
	feed1(2, 0, EV_KEY, KEY_C, 0);
	syn(2, 0);
	expect_frame(2000000);
	/* a value that is none of 0, 1, 2 and a code past KEY_MAX: counted, ignored */
	feed1(3, 0, EV_KEY, KEY_D, 5);
	feed1(3, 0, EV_KEY, KEY_MAX + 1, 1);
	syn(3, 0);
	expect_frame(3000000);
	assert_int_equal(dec.unknown_events, 2);
	expect_empty();
}

static void
test_button_ranges(void **state)
{
	(void)state;
	/* the BTN_* blocks of input-event-codes.h, as libinput's evdev_get_key_type reads them */
	static const struct {
		uint16_t code;
		int button;
	} cases[] = {
		{ KEY_ESC, 0 },		{ KEY_MICMUTE, 0 },	   { BTN_MISC, 1 },
		{ BTN_LEFT, 1 },	{ BTN_TASK, 1 },	   { BTN_JOYSTICK, 1 },
		{ BTN_SOUTH, 1 },	{ BTN_TOUCH, 1 },	   { BTN_GEAR_UP, 1 },
		{ KEY_OK, 0 },		{ KEY_LIGHTS_TOGGLE, 0 },  { BTN_DPAD_UP, 1 },
		{ BTN_DPAD_RIGHT, 1 },	{ KEY_ALS_TOGGLE, 0 },	   { KEY_MACRO1, 0 },
		{ BTN_TRIGGER_HAPPY, 1 }, { BTN_TRIGGER_HAPPY40, 1 },
		{ BTN_TRIGGER_HAPPY40 + 1, 0 },
		{ KEY_MAX, 0 },
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
		if (evdev_input_is_button(cases[i].code) != cases[i].button)
			fail_msg("code %#x: button %d, want %d", cases[i].code,
				 evdev_input_is_button(cases[i].code), cases[i].button);
}

static void
expect_wheel(uint16_t axis, int32_t detents, double v120, int hires)
{
	struct input_event_rec ev = next();
	assert_int_equal(ev.kind, INPUT_WHEEL);
	assert_int_equal(ev.code, axis);
	if (ev.value != detents)
		fail_msg("wheel detents %d, want %d", ev.value, detents);
	assert_near(ev.x, v120, 0);
	assert_int_equal(ev.flags & INPUT_F_HIRES, hires ? INPUT_F_HIRES : 0);
}

static void
test_wheel_detents(void **state)
{
	(void)state;
	/* a wheel without hi-res: detents, and the same in 1/120 */
	feed1(1, 0, EV_REL, REL_WHEEL, -2);
	feed1(1, 0, EV_REL, REL_HWHEEL, 1);
	syn(1, 0);
	expect_wheel(INPUT_WHEEL_V, -2, -240, 0);
	expect_wheel(INPUT_WHEEL_H, 1, 120, 0);
	expect_frame(1000000);
	/* the kernel's hi-res wheel: both in one frame, one event carrying both */
	feed1(2, 0, EV_REL, REL_WHEEL, 1);
	feed1(2, 0, EV_REL, REL_WHEEL_HI_RES, 120);
	syn(2, 0);
	expect_wheel(INPUT_WHEEL_V, 1, 120, 1);
	expect_frame(2000000);
	expect_empty();
}

static void
test_wheel_hires_remainder(void **state)
{
	(void)state;
	/* only hi-res, 1/8 detent a frame: a whole detent on the eighth */
	for (int i = 1; i <= 8; i++) {
		feed1(1, (uint32_t)i, EV_REL, REL_WHEEL_HI_RES, 15);
		syn(1, (uint32_t)i);
		expect_wheel(INPUT_WHEEL_V, i == 8 ? 1 : 0, 15, 1);
		expect_frame(1000000 + (uint64_t)i);
	}
	/* 250/120: two detents, 10 kept; then 110 more make the third */
	feed1(2, 0, EV_REL, REL_WHEEL_HI_RES, 250);
	syn(2, 0);
	expect_wheel(INPUT_WHEEL_V, 2, 250, 1);
	expect_frame(2000000);
	feed1(2, 1, EV_REL, REL_WHEEL_HI_RES, 110);
	syn(2, 1);
	expect_wheel(INPUT_WHEEL_V, 1, 110, 1);
	expect_frame(2000001);
	/* 105 kept, then a turn the other way starts from zero: -15 is no detent */
	for (int i = 0; i < 7; i++) {
		feed1(3, 0, EV_REL, REL_WHEEL_HI_RES, 15);
		syn(3, 0);
		expect_wheel(INPUT_WHEEL_V, 0, 15, 1);
		expect_frame(3000000);
	}
	feed1(3, 1, EV_REL, REL_WHEEL_HI_RES, -15);
	syn(3, 1);
	expect_wheel(INPUT_WHEEL_V, 0, -15, 1);
	expect_frame(3000001);
	feed1(3, 2, EV_REL, REL_WHEEL_HI_RES, -105);
	syn(3, 2);
	expect_wheel(INPUT_WHEEL_V, -1, -105, 1);
	expect_frame(3000002);
	/* a horizontal hi-res wheel has its own rest */
	feed1(4, 0, EV_REL, REL_HWHEEL_HI_RES, -130);
	syn(4, 0);
	expect_wheel(INPUT_WHEEL_H, -1, -130, 1);
	expect_frame(4000000);
	expect_empty();
}

static void
test_absolute_pointer(void **state)
{
	(void)state;
	/* without a range: ignored and counted */
	feed1(1, 0, EV_ABS, ABS_X, 100);
	syn(1, 0);
	expect_frame(1000000);
	assert_int_equal(dec.abs_unranged, 1);

	assert_int_equal(evdev_input_set_abs(&dec, ABS_X, 0, 1000), 0);
	assert_int_equal(evdev_input_set_abs(&dec, ABS_Y, -100, 100), 0);
	assert_int_equal(evdev_input_set_abs(&dec, ABS_Z, 0, 10), -1);
	assert_int_equal(evdev_input_set_abs(&dec, ABS_X, 5, 5), -1);
	feed1(2, 0, EV_ABS, ABS_X, 250);
	feed1(2, 0, EV_ABS, ABS_Y, 0);
	feed1(2, 0, EV_ABS, ABS_PRESSURE, 30); /* no range: counted */
	syn(2, 0);
	struct input_event_rec ev = next();
	assert_int_equal(ev.kind, INPUT_POINTER);
	assert_near(ev.x, 0.25, 1e-15);
	assert_near(ev.y, 0.5, 1e-15);
	assert_int_equal(ev.flags & INPUT_F_VIEW, 0);
	expect_frame(2000000);
	assert_int_equal(dec.abs_unranged, 2);
	/* one axis changes, the other keeps its value */
	feed1(3, 0, EV_ABS, ABS_Y, 100);
	syn(3, 0);
	ev = next();
	assert_near(ev.x, 0.25, 1e-15);
	assert_near(ev.y, 1, 1e-15);
	expect_frame(3000000);
}

static void
test_times_from_records(void **state)
{
	(void)state;
	feed1(1234, 567890, EV_KEY, KEY_Z, 1);
	syn(1234, 567891);
	struct input_event_rec ev = next();
	assert_int_equal(ev.t_us, 1234567890ull);
	expect_frame(1234567891ull);
}

/* ---- SYN_DROPPED, resync, removal ------------------------------------------ */

static void
test_syn_dropped(void **state)
{
	(void)state;
	feed1(1, 0, EV_REL, REL_X, 5);
	feed1(1, 0, EV_KEY, BTN_LEFT, 1);
	feed1(1, 0, EV_SYN, SYN_DROPPED, 0);
	assert_true(dec.resync_wanted);
	feed1(1, 1, EV_REL, REL_X, 7);
	feed1(1, 1, EV_KEY, KEY_A, 1);
	syn(1, 1); /* the end of what is dropped */
	expect_empty();
	feed1(1, 2, EV_REL, REL_X, 2);
	syn(1, 2);
	struct input_event_rec ev = next();
	assert_int_equal(ev.kind, INPUT_MOTION);
	assert_near(ev.x, 2, 0);
	expect_frame(1000002);
	expect_empty();
	assert_int_equal(dec.dropped_frames, 1);
	assert_false(evdev_input_key_down(&dec, BTN_LEFT));
	assert_false(evdev_input_key_down(&dec, KEY_A));
}

static void
test_resync(void **state)
{
	(void)state;
	feed1(1, 0, EV_KEY, KEY_A, 1);
	feed1(1, 0, EV_KEY, BTN_LEFT, 1);
	syn(1, 0);
	while (q.len)
		next();
	feed1(2, 0, EV_SYN, SYN_DROPPED, 0);
	/* the kernel says: KEY_A up, KEY_B down, BTN_LEFT still down */
	uint8_t bits[EVDEV_INPUT_KEYBITS];
	memset(bits, 0, sizeof bits);
	bits[KEY_B / 8] |= 1 << (KEY_B % 8);
	bits[BTN_LEFT / 8] |= 1 << (BTN_LEFT % 8);
	assert_int_equal(evdev_input_resync(&dec, bits, 5000, &q), 2);
	expect(INPUT_KEY, KEY_A, 0);
	expect(INPUT_KEY, KEY_B, 1);
	expect_frame(5000);
	expect_empty();
	assert_false(dec.resync_wanted);
	assert_true(evdev_input_key_down(&dec, KEY_B));
	assert_true(evdev_input_key_down(&dec, BTN_LEFT));
	assert_false(evdev_input_key_down(&dec, KEY_A));
}

static void
test_release_all(void **state)
{
	(void)state;
	feed1(1, 0, EV_KEY, KEY_LEFTCTRL, 1);
	feed1(1, 0, EV_KEY, BTN_RIGHT, 1);
	syn(1, 0);
	while (q.len)
		next();
	feed1(1, 1, EV_KEY, BTN_MIDDLE, 1); /* pending, never reported: not released */
	assert_int_equal(evdev_input_release_all(&dec, 9000, &q), 2);
	expect(INPUT_KEY, KEY_LEFTCTRL, 0);
	expect(INPUT_BUTTON, BTN_RIGHT, 0);
	expect_frame(9000);
	expect_empty();
	assert_int_equal(evdev_input_release_all(&dec, 9001, &q), 0);
	expect_empty();
	syn(1, 2); /* the pending press was dropped with the device */
	expect_frame(1000002);
	expect_empty();
}

/* ---- short records ---------------------------------------------------------- */

static void
test_short_records(void **state)
{
	(void)state;
	size_t size = sizeof(struct input_event);
	uint8_t b[2 * sizeof(struct input_event)];
	/* 23 bytes: refused, nothing queued or kept */
	rec(b, 1, 0, EV_KEY, BTN_LEFT, 1);
	assert_int_equal(evdev_input_feed(&dec, b, size - 1, &q), -1);
	assert_int_equal(dec.short_records, 1);
	syn(1, 1);
	expect_frame(1000001);
	expect_empty();
	assert_false(evdev_input_key_down(&dec, BTN_LEFT));
	/* 47 bytes: the whole record is decoded, the 23 after it refused */
	feed1(2, 0, EV_REL, REL_X, 3);
	rec(b, 2, 1, EV_SYN, SYN_REPORT, 0);
	rec(b + size, 2, 2, EV_KEY, BTN_LEFT, 1);
	assert_int_equal(evdev_input_feed(&dec, b, 2 * size - 1, &q), -1);
	assert_int_equal(dec.short_records, 2);
	struct input_event_rec ev = next();
	assert_int_equal(ev.kind, INPUT_MOTION);
	assert_near(ev.x, 3, 0);
	expect_frame(2000001);
	syn(2, 3);
	expect_frame(2000003);
	expect_empty();
	assert_int_equal(sizeof(struct input_event), 24); /* LP64 */
}

/* ---- evemu files ------------------------------------------------------------- */

static void
read_ok(const char *path, struct rec_evemu *dest)
{
	char err[512];
	if (rec_evemu_read(path, dest, err, sizeof err))
		fail_msg("%s", err);
}

/* r against what libevemu's reader made of the same file (NAME.ref) */
static void
check_against_ref(const struct rec_evemu *r, const char *refpath)
{
	FILE *f = fopen(refpath, "r");
	assert_non_null(f);
	char line[512];
	uint8_t bits[EV_CNT][REC_EVEMU_MASK_BYTES];
	uint8_t props[REC_EVEMU_PROP_BYTES];
	memset(bits, 0, sizeof bits);
	memset(props, 0, sizeof props);
	size_t nev = 0;
	while (fgets(line, sizeof line, f)) {
		line[strcspn(line, "\n")] = 0;
		unsigned a, b, c, d;
		int v[5];
		unsigned long sec, usec;
		if (line[0] == 'N') {
			assert_string_equal(r->name, line + 2);
		} else if (sscanf(line, "I %u %u %u %u", &a, &b, &c, &d) == 4) {
			assert_int_equal(r->bustype, a);
			assert_int_equal(r->vendor, b);
			assert_int_equal(r->product, c);
			assert_int_equal(r->version, d);
		} else if (sscanf(line, "P %u", &a) == 1) {
			props[a / 8] |= (uint8_t)(1u << (a % 8));
		} else if (sscanf(line, "B %u %u", &a, &b) == 2) {
			bits[a][b / 8] |= (uint8_t)(1u << (b % 8));
		} else if (sscanf(line, "A %u %d %d %d %d %d", &a, &v[0], &v[1], &v[2], &v[3],
				  &v[4]) == 6) {
			assert_true(r->abs_given[a]);
			assert_int_equal(r->abs[a].min, v[0]);
			assert_int_equal(r->abs[a].max, v[1]);
			assert_int_equal(r->abs[a].fuzz, v[2]);
			assert_int_equal(r->abs[a].flat, v[3]);
			assert_int_equal(r->abs[a].res, v[4]);
		} else if (sscanf(line, "E %lu %lu %u %u %d", &sec, &usec, &a, &b, &v[0]) == 5) {
			assert_true(nev < r->nev);
			const struct rec_evemu_event *ev = &r->ev[nev++];
			assert_int_equal(ev->sec, sec);
			assert_int_equal(ev->usec, usec);
			assert_int_equal(ev->type, a);
			assert_int_equal(ev->code, b);
			assert_int_equal(ev->value, v[0]);
		} else {
			fail_msg("%s: bad line %s", refpath, line);
		}
	}
	fclose(f);
	assert_int_equal(nev, r->nev);
	assert_memory_equal(props, r->props, sizeof props);
	/* EV_SYN aside: libevdev reports every SYN code of a device */
	for (unsigned t = 1; t < EV_CNT; t++)
		assert_memory_equal(bits[t], r->bits[t], sizeof bits[t]);
	/* times rebased to the first event */
	for (size_t i = 0; i < r->nev; i++)
		assert_int_equal(r->ev[i].t_us, (r->ev[i].sec * 1000000 + r->ev[i].usec) -
							(r->ev[0].sec * 1000000 + r->ev[0].usec));
}

static const char *const evemu_files[] = { "mouse", "keyboard", "tablet", "tablet-v1.0" };

static void
test_evemu_reads_libevemu_files(void **state)
{
	(void)state;
	for (size_t i = 0; i < sizeof evemu_files / sizeof evemu_files[0]; i++) {
		char path[256], ref[256];
		snprintf(path, sizeof path, DATA "%s.evemu", evemu_files[i]);
		snprintf(ref, sizeof ref, DATA "%s.ref", evemu_files[i]);
		struct rec_evemu r;
		read_ok(path, &r);
		check_against_ref(&r, ref);
		rec_evemu_free(&r);
	}
}

static void
assert_same_recording(const struct rec_evemu *a, const struct rec_evemu *b)
{
	assert_int_equal(a->described, b->described);
	assert_string_equal(a->name, b->name);
	assert_int_equal(a->bustype, b->bustype);
	assert_int_equal(a->vendor, b->vendor);
	assert_int_equal(a->product, b->product);
	assert_int_equal(a->version, b->version);
	assert_memory_equal(a->props, b->props, sizeof a->props);
	assert_memory_equal(a->bits, b->bits, sizeof a->bits);
	assert_memory_equal(a->abs, b->abs, sizeof a->abs);
	assert_memory_equal(a->abs_given, b->abs_given, sizeof a->abs_given);
	assert_memory_equal(a->led, b->led, sizeof a->led);
	assert_memory_equal(a->sw, b->sw, sizeof a->sw);
	assert_int_equal(a->nev, b->nev);
	for (size_t i = 0; i < a->nev; i++) {
		assert_int_equal(a->ev[i].t_us, b->ev[i].t_us);
		assert_int_equal(a->ev[i].sec, b->ev[i].sec);
		assert_int_equal(a->ev[i].usec, b->ev[i].usec);
		assert_int_equal(a->ev[i].type, b->ev[i].type);
		assert_int_equal(a->ev[i].code, b->ev[i].code);
		assert_int_equal(a->ev[i].value, b->ev[i].value);
	}
}

/* r written into a fresh buffer (free it) */
static char *
write_to_memory(const struct rec_evemu *r, size_t *len)
{
	char *buf = NULL;
	FILE *m = open_memstream(&buf, len);
	assert_non_null(m);
	assert_int_equal(rec_evemu_write(m, r), 0);
	fclose(m);
	return buf;
}

static void
test_evemu_round_trip(void **state)
{
	(void)state;
	for (size_t i = 0; i < sizeof evemu_files / sizeof evemu_files[0]; i++) {
		char path[256], err[512];
		snprintf(path, sizeof path, DATA "%s.evemu", evemu_files[i]);
		struct rec_evemu a, b;
		read_ok(path, &a);
		size_t len;
		char *text = write_to_memory(&a, &len);
		if (rec_evemu_parse(text, len, "written", &b, err, sizeof err))
			fail_msg("%s", err);
		assert_same_recording(&a, &b);
		/* and the second writing is the first, byte for byte */
		size_t len2;
		char *text2 = write_to_memory(&b, &len2);
		assert_int_equal(len, len2);
		assert_memory_equal(text, text2, len);
		free(text);
		free(text2);
		rec_evemu_free(&a);
		rec_evemu_free(&b);
	}
	/* a file with LED and switch states and no A: lines keeps them */
	static const char text[] = "# EVEMU 1.3\nN: states\nI: 0019 0000 0000 0000\n"
				   "B: 05 01 00 00 00 00 00 00 00\nB: 11 02 00 00 00 00 00 00 00\n"
				   "L: 01 1\nS: 00 1\n";
	struct rec_evemu a, b;
	char err[256];
	assert_int_equal(rec_evemu_parse(text, sizeof text - 1, "states", &a, err, sizeof err), 0);
	assert_int_equal(a.led[LED_CAPSL], 1);
	assert_int_equal(a.sw[SW_LID], 1);
	size_t len;
	char *out = write_to_memory(&a, &len);
	assert_int_equal(rec_evemu_parse(out, len, "written", &b, err, sizeof err), 0);
	assert_same_recording(&a, &b);
	free(out);
	rec_evemu_free(&a);
	rec_evemu_free(&b);
}

/* a recording through the device's path: records, evdev_input_feed, events */
static void
replay(const char *name)
{
	struct rec_evemu r;
	char path[256];
	snprintf(path, sizeof path, DATA "%s.evemu", name);
	read_ok(path, &r);
	rec_evemu_apply_abs(&r, &dec);
	size_t need = rec_evemu_to_records(&r, NULL, 0);
	assert_int_equal(need, r.nev * sizeof(struct input_event));
	uint8_t *bytes = malloc(need);
	assert_int_equal(rec_evemu_to_records(&r, bytes, need), need);
	assert_int_equal(evdev_input_feed(&dec, bytes, need, &q), 0);
	free(bytes);
	rec_evemu_free(&r);
}

static void
expect_motion(double x, double y, uint64_t t_us)
{
	struct input_event_rec ev = next();
	assert_int_equal(ev.kind, INPUT_MOTION);
	assert_near(ev.x, x, 0);
	assert_near(ev.y, y, 0);
	assert_int_equal(ev.t_us, t_us);
}

static void
test_evemu_mouse_replay(void **state)
{
	(void)state;
	/* mouse.ev, rebased: the first event at 0 */
	replay("mouse");
	expect_motion(3, -2, 0);
	expect_frame(0);
	expect_motion(5, 7, 8000);
	expect_frame(8000);
	expect(INPUT_BUTTON, BTN_LEFT, 1);
	expect_frame(16123);
	expect_wheel(INPUT_WHEEL_V, 0, 60, 1);
	expect_frame(100000);
	expect_wheel(INPUT_WHEEL_V, 1, 60, 1);
	expect_frame(108000);
	expect_wheel(INPUT_WHEEL_H, -1, -120, 1);
	expect_frame(200000);
	expect(INPUT_BUTTON, BTN_LEFT, 0);
	expect(INPUT_BUTTON, BTN_RIGHT, 1);
	expect(INPUT_BUTTON, BTN_MIDDLE, 1);
	expect_frame(300000);
	expect_motion(-10, 0, 600001);
	expect(INPUT_BUTTON, BTN_RIGHT, 0);
	expect(INPUT_BUTTON, BTN_MIDDLE, 0);
	expect(INPUT_BUTTON, BTN_SIDE, 1);
	expect_frame(600001);
	expect(INPUT_BUTTON, BTN_SIDE, 0);
	expect(INPUT_BUTTON, BTN_EXTRA, 1);
	expect_frame(850000);
	expect(INPUT_BUTTON, BTN_EXTRA, 0);
	expect_frame(900000);
	expect_empty();
	assert_int_equal(dec.unknown_events, 0);
}

static void
test_evemu_keyboard_replay(void **state)
{
	(void)state;
	replay("keyboard");
	expect(INPUT_KEY, KEY_A, 1);
	expect_frame(0);
	expect(INPUT_KEY, KEY_A, 2);
	expect_frame(250000);
	expect(INPUT_KEY, KEY_A, 2);
	expect_frame(283000);
	expect(INPUT_KEY, KEY_A, 0);
	expect_frame(300000);
	expect(INPUT_KEY, KEY_LEFTSHIFT, 1);
	expect(INPUT_KEY, KEY_B, 1);
	expect_frame(1000000);
	expect(INPUT_KEY, KEY_B, 0);
	expect(INPUT_KEY, KEY_LEFTSHIFT, 0);
	expect_frame(1100000);
	expect(INPUT_KEY, KEY_CAPSLOCK, 1);
	expect_frame(1200000);
	expect_frame(1200100); /* the LED's frame */
	expect(INPUT_KEY, KEY_CAPSLOCK, 0);
	expect_frame(1300000);
	expect_empty();
}

static void
expect_pointer(double x, double y)
{
	struct input_event_rec ev = next();
	assert_int_equal(ev.kind, INPUT_POINTER);
	assert_near(ev.x, x, 1e-12);
	assert_near(ev.y, y, 1e-12);
}

static void
test_evemu_tablet_replay(void **state)
{
	(void)state;
	/* A: 00 0 32767, A: 01 -100 16283 */
	replay("tablet");
	expect_pointer(16384.0 / 32767, 8192.0 / 16383);
	expect_frame(0);
	expect_pointer(1, 8192.0 / 16383);
	expect_frame(16000);
	expect_pointer(1, 0);
	expect(INPUT_BUTTON, BTN_LEFT, 1);
	expect_frame(32000);
	expect_pointer(0, 0);
	expect(INPUT_BUTTON, BTN_LEFT, 0);
	expect_frame(48000);
	expect_empty();
	assert_int_equal(dec.abs_unranged, 0);
}

static void
test_evemu_to_records_fits(void **state)
{
	(void)state;
	struct rec_evemu r;
	read_ok(DATA "mouse.evemu", &r);
	size_t size = sizeof(struct input_event);
	uint8_t buf[3 * sizeof(struct input_event) + 5];
	memset(buf, 0xee, sizeof buf);
	/* two and a half records of room: two written, the rest untouched */
	assert_int_equal(rec_evemu_to_records(&r, buf, 2 * size + size / 2), r.nev * size);
	struct input_event e;
	memcpy(&e, buf + size, size);
	assert_int_equal(e.type, EV_REL);
	assert_int_equal(e.code, REL_Y);
	assert_int_equal(e.value, -2);
	assert_int_equal(buf[2 * size], 0xee);
	rec_evemu_free(&r);
}

static void
test_evemu_bad_files(void **state)
{
	(void)state;
	static const char head[] = "# EVEMU 1.3\nN: m\nI: 0003 0001 0002 0003\n";
	static const struct {
		const char *text;
		const char *err; /* the start of the message */
	} cases[] = {
		{ "", "bad.evemu:0: neither a device description nor events" },
		{ "# just a comment\n", "bad.evemu:1: neither" },
		{ "# EVEMU 2.0\nN: m\n", "bad.evemu:1: format 2.0" },
		{ "# EVEMU x\n", "bad.evemu:1: bad format line" },
		{ "E: 0.5 0002 0000 1\n", "bad.evemu:1: the event's fraction of a second must" },
		{ "E: 0.0000001 0002 0000 1\n", "bad.evemu:1: the event's fraction" },
		{ "E: 0.000001 0002 0000 1 x\n", "bad.evemu:1: unexpected text after the event's" },
		{ "E: 0.000001 0002 0000 2147483648\n", "bad.evemu:1: expected \"E:" },
		{ "E: 0.000001 0020 0000 1\n", "bad.evemu:1: no event type 0x20" },
		{ "E: 0.000001 0002 10000 1\n", "bad.evemu:1: expected \"E:" },
		{ "E: 1.000000 0002 0000 1\nE: 0.999999 0000 0000 0\n",
		  "bad.evemu:2: the event is earlier" },
		{ "N: m\nI: 0003 0001\n", "bad.evemu:2: expected \"I:" },
		{ "N: m\n", "bad.evemu:1: an N: line without an I: line" },
		{ "N: m\nN: n\n", "bad.evemu:2: a second N: line" },
		{ "I: 0003 0001 0002 0003\n", "bad.evemu:1: I: before the N: line" },
		{ "B: 02 03 00 00 00 00 00 00 00\n", "bad.evemu:1: a B: line before the N:" },
		{ "N: m\nI: 1 2 3 4\nB: 02 03 00 00 00 00 00 00\n", "bad.evemu:3: expected 8 hex" },
		{ "N: m\nI: 1 2 3 4\nB: 20 03 00 00 00 00 00 00 00\n", "bad.evemu:3: no event" },
		{ "N: m\nI: 1 2 3 4\nB: 02 003 00 00 00 00 00 00 00\n", "bad.evemu:3: expected 8" },
		{ "N: m\nI: 1 2 3 4\nP: 01 00 00 00 00 00 00 00\nP: 01 00 00 00 00 00 00 00\n",
		  "bad.evemu:4: bits past the 8 bytes of the P: bitmask" },
		{ "N: m\nI: 1 2 3 4\nA: 00 0 10 0\n", "bad.evemu:3: expected 4 numbers" },
		{ "N: m\nI: 1 2 3 4\nA: 00 0 10 0 0 0\n", "bad.evemu:3: more than 4 numbers" },
		{ "N: m\nI: 1 2 3 4\nA: 40 0 10 0 0\n", "bad.evemu:3: no ABS code 0x40" },
		{ "N: m\nI: 1 2 3 4\nL: 10 1\n", "bad.evemu:3: no LED code 0x10" },
		{ "N: m\nI: 1 2 3 4\nS: 01\n", "bad.evemu:3: expected \"S:" },
		{ "N: m\nI: 1 2 3 4\nE: 0.000001 0000 0000 0\nB: 00 0b 00 00 00 00 00 00 00\n",
		  "bad.evemu:4: a B: line after the events" },
	};
	char err[512];
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		struct rec_evemu r;
		memset(&r, 0x5a, sizeof r);
		int rc = rec_evemu_parse(cases[i].text, strlen(cases[i].text), "bad.evemu", &r, err,
					 sizeof err);
		if (rc != -1 || strncmp(err, cases[i].err, strlen(cases[i].err)))
			fail_msg("case %zu: rc %d, error \"%s\", want \"%s...\"", i, rc, err,
				 cases[i].err);
		assert_null(r.ev); /* nothing half-read */
		assert_int_equal(r.nev, 0);
		rec_evemu_free(&r);
	}
	/* an A: line of 1.3 lacking the resolution, after the header */
	char text[256];
	snprintf(text, sizeof text, "%sA: 00 0 10 0 0\n", head);
	struct rec_evemu r;
	assert_int_equal(rec_evemu_parse(text, strlen(text), "bad.evemu", &r, err, sizeof err), -1);
	assert_string_equal(err, "bad.evemu:4: expected 5 numbers after the A: line's code "
				 "(format 1.3)");
	/* a NUL byte */
	static const char nul[] = "N: m\nI: 1 2 3 4\nE: 0.000001 0000\0 0000 0\n";
	assert_int_equal(rec_evemu_parse(nul, sizeof nul - 1, "bad.evemu", &r, err, sizeof err),
			 -1);
	assert_string_equal(err, "bad.evemu:3: a NUL byte in the line");
	/* a missing file names the path */
	assert_int_equal(rec_evemu_read(DATA "no-such.evemu", &r, err, sizeof err), -1);
	assert_string_equal(err, DATA "no-such.evemu: No such file or directory");
}

static void
test_evemu_lenient_where_evemu_is(void **state)
{
	(void)state;
	/* comments, blank and unknown lines, CRLF, a name with '#', comments after data */
	static const char text[] = "# EVEMU 1.2\r\n\r\n# a comment\nN:   Name # with hash  \r\n"
				   "I: 3 46d c077 111\nX: an unknown line\n"
				   "B: 02 03 00 00 00 00 00 00 00   # REL_X REL_Y\n"
				   "  \t\nE: 7.000010 0002 0000 -0003\t# EV_REL / REL_X -3\n"
				   "E: 7.000010 0000 0000 0000\nT: ignored\nE: 7.000020 2 1 +4\n";
	struct rec_evemu r;
	char err[256];
	if (rec_evemu_parse(text, sizeof text - 1, "ok.evemu", &r, err, sizeof err))
		fail_msg("%s", err);
	assert_int_equal(r.major, 1);
	assert_int_equal(r.minor, 2);
	assert_string_equal(r.name, "Name # with hash  ");
	assert_int_equal(r.vendor, 0x46d);
	assert_int_equal(r.nev, 3);
	assert_int_equal(r.ev[0].value, -3);
	assert_int_equal(r.ev[2].code, REL_Y);
	assert_int_equal(r.ev[2].value, 4);
	assert_int_equal(r.ev[2].t_us, 10);
	assert_int_equal(r.ev[2].sec, 7);
	assert_int_equal(r.ev[2].usec, 20);
	rec_evemu_free(&r);
	/* no header: format 1.0, five numbers on an A: line */
	static const char old[] = "N: old\nI: 1 2 3 4\nA: 00 -5 5 0 0\n";
	assert_int_equal(rec_evemu_parse(old, sizeof old - 1, "old", &r, err, sizeof err), 0);
	assert_int_equal(r.minor, 0);
	assert_int_equal(r.abs[ABS_X].min, -5);
	rec_evemu_free(&r);
}

static void
test_evemu_writer_format(void **state)
{
	(void)state;
	/* the E: lines as libevemu's evemu_write_event writes them (mouse.evemu's own) */
	struct rec_evemu r;
	read_ok(DATA "mouse.evemu", &r);
	size_t len;
	char *text = write_to_memory(&r, &len);
	FILE *f = fopen(DATA "mouse.evemu", "r");
	assert_non_null(f);
	char line[512];
	size_t n = 0;
	while (fgets(line, sizeof line, f)) {
		if (strncmp(line, "E:", 2))
			continue;
		if (!strstr(text, line))
			fail_msg("libevemu's line not written the same: %s", line);
		n++;
	}
	fclose(f);
	assert_int_equal(n, r.nev);
	assert_string_equal(rec_evemu_code_name(EV_KEY, BTN_LEFT), "BTN_LEFT");
	assert_string_equal(rec_evemu_code_name(EV_REL, REL_WHEEL_HI_RES), "REL_WHEEL_HI_RES");
	assert_string_equal(rec_evemu_type_name(EV_LED), "EV_LED");
	assert_null(rec_evemu_code_name(EV_REL, 0x0e));
	assert_null(rec_evemu_type_name(EV_MAX + 1));
	free(text);
	rec_evemu_free(&r);
}

/* ---- no allocation per event --------------------------------------------------- */

static void
test_feed_allocates_nothing(void **state)
{
	(void)state;
	struct rec_evemu r;
	read_ok(DATA "keyboard.evemu", &r);
	size_t need = rec_evemu_to_records(&r, NULL, 0);
	uint8_t *bytes = malloc(need);
	rec_evemu_to_records(&r, bytes, need);
	rec_evemu_free(&r);
#if COUNT_ALLOCS
	long before = allocs;
#endif
	for (int i = 0; i < 200; i++) {
		evdev_input_feed(&dec, bytes, need, &q);
		evdev_input_feed(&dec, bytes, 5, &q); /* the error path too */
		struct input_event_rec ev;
		while (input_queue_pop(&q, &ev))
			;
	}
	free(bytes);
#if COUNT_ALLOCS
	assert_int_equal(allocs, before);
#else
	skip();
#endif
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup(test_motion_summed_at_syn_report, setup),
		cmocka_unit_test_setup(test_buttons_and_keys, setup),
		cmocka_unit_test_setup(test_key_rules, setup),
		cmocka_unit_test_setup(test_button_ranges, setup),
		cmocka_unit_test_setup(test_wheel_detents, setup),
		cmocka_unit_test_setup(test_wheel_hires_remainder, setup),
		cmocka_unit_test_setup(test_absolute_pointer, setup),
		cmocka_unit_test_setup(test_times_from_records, setup),
		cmocka_unit_test_setup(test_syn_dropped, setup),
		cmocka_unit_test_setup(test_resync, setup),
		cmocka_unit_test_setup(test_release_all, setup),
		cmocka_unit_test_setup(test_short_records, setup),
		cmocka_unit_test_setup(test_evemu_reads_libevemu_files, setup),
		cmocka_unit_test_setup(test_evemu_round_trip, setup),
		cmocka_unit_test_setup(test_evemu_mouse_replay, setup),
		cmocka_unit_test_setup(test_evemu_keyboard_replay, setup),
		cmocka_unit_test_setup(test_evemu_tablet_replay, setup),
		cmocka_unit_test_setup(test_evemu_to_records_fits, setup),
		cmocka_unit_test_setup(test_evemu_bad_files, setup),
		cmocka_unit_test_setup(test_evemu_lenient_where_evemu_is, setup),
		cmocka_unit_test_setup(test_evemu_writer_format, setup),
		cmocka_unit_test_setup(test_feed_allocates_nothing, setup),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
