/*
 * test_can.c - the CAN panel: maps made by tools/dbc2panel decode the same
 * frames to the same values cantools gives (tests/input/can/NAME.expect, made
 * by make_expect.py); the map syntax's forms against hand-worked bits; every
 * refusal with file:line and nothing changed; frames counted, not decoded
 * (wrong size, error, RTR, unknown ids, short frames); valuators stale once,
 * buttons on change only; no allocation per frame; candump logs read,
 * written byte for byte as candump and python-can write them, and read back.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <linux/can.h>
#include <linux/input-event-codes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "alloc_count.h"
#include "devices/can_input.h"
#include "devices/can_map.h"
#include "devices/rec_candump.h"

#define DIR "tests/input/can/"

static struct can_map map_a, map_b;
static struct input_queue queue;
static struct can_input input;

static char *
slurp(const char *path, size_t *n)
{
	FILE *f = fopen(path, "rb");
	assert_non_null(f);
	fseek(f, 0, SEEK_END);
	long len = ftell(f);
	fseek(f, 0, SEEK_SET);
	char *buf = malloc((size_t)len + 1);
	assert_non_null(buf);
	assert_int_equal(fread(buf, 1, (size_t)len, f), (size_t)len);
	buf[len] = 0;
	fclose(f);
	*n = (size_t)len;
	return buf;
}

static void
map_from(const char *text, struct can_map *dest)
{
	char err[256] = "";
	int r = can_map_parse(text, strlen(text), "t.map", dest, err, sizeof err);
	if (r)
		fail_msg("%s", err);
}

/* decoding one frame: the value of line `name`, or NAN when it did not decode */
static double
value_of(const struct can_map *m, uint32_t id, const uint8_t *data, int len, const char *name)
{
	int lines[CAN_MAP_MAX_LINES];
	double vals[CAN_MAP_MAX_LINES];
	int n = can_input_decode(m, id, data, len, lines, vals, CAN_MAP_MAX_LINES);
	for (int i = 0; i < n; i++)
		if (strcmp(m->line[lines[i]].name, name) == 0)
			return vals[i];
	return NAN;
}

static void
oracle(const char *base)
{
	char path[256], err[256] = "";
	snprintf(path, sizeof path, DIR "%s.map", base);
	if (can_map_read(path, &map_a, err, sizeof err))
		fail_msg("%s", err);
	struct rec_candump log;
	snprintf(path, sizeof path, DIR "%s.log", base);
	if (rec_candump_read(path, &log, err, sizeof err))
		fail_msg("%s", err);
	snprintf(path, sizeof path, DIR "%s.expect", base);
	FILE *f = fopen(path, "r");
	assert_non_null(f);
	char line[512];
	size_t frame = 0;
	int lines[CAN_MAP_MAX_LINES], pos = 0, n = -1, checked = 0;
	double vals[CAN_MAP_MAX_LINES];
	for (;;) {
		/* the next expected value, or the end */
		int ef = -1, el = -1;
		char name[128];
		double ev = 0;
		while (fgets(line, sizeof line, f)) {
			if (line[0] == '#')
				continue;
			assert_int_equal(sscanf(line, "%d %d %127s %lf", &ef, &el, name, &ev), 4);
			break;
		}
		if (feof(f))
			ef = (int)log.n;
		/* our values of the frames up to that one: no more than cantools gives */
		while (frame < (size_t)ef || (frame == (size_t)ef && n < 0)) {
			if (n >= 0) {
				if (pos != n)
					fail_msg("%s frame %zu: line %s decoded, cantools has "
						 "no value",
						 base, frame, map_a.line[lines[pos]].name);
				frame++;
				n = -1;
				continue;
			}
			if (frame >= log.n)
				break;
			const struct rec_candump_frame *fr = &log.frames[frame];
			n = can_input_decode(&map_a, fr->can_id, fr->data, fr->len, lines, vals,
					     CAN_MAP_MAX_LINES);
			pos = 0;
		}
		if (feof(f) || frame >= log.n)
			break;
		if (pos >= n)
			fail_msg("%s frame %d: cantools gives %s = %.17g, we give nothing", base,
				 ef, name, ev);
		assert_int_equal(lines[pos], el);
		assert_string_equal(map_a.line[el].name, name);
		double tol = 1e-9 * fmax(1.0, fabs(ev));
		if (fabs(vals[pos] - ev) > tol)
			fail_msg("%s frame %d %s: cantools %.17g, ours %.17g", base, ef, name, ev,
				 vals[pos]);
		pos++;
		checked++;
	}
	assert_int_equal(frame, log.n);
	fclose(f);
	rec_candump_free(&log);
	assert_true(checked > 100);
}

static void
test_decoding_agrees_with_cantools_panel(void **unused)
{
	(void)unused;
	oracle("panel");
}

static void
test_decoding_agrees_with_cantools_mux(void **unused)
{
	(void)unused;
	oracle("mux");
}

static void
test_decoding_agrees_with_cantools_defects(void **unused)
{
	(void)unused;
	oracle("defects");
}

/* bits worked by hand: the research file's panel frame and Motorola fields */
static void
test_field_forms_decode_hand_worked_bits(void **unused)
{
	(void)unused;
	map_from("axis 181 0-1 d1 factor=0.1\n"
		 "axis 181 16|16@1+ d2 factor=0.5 offset=-50\n"
		 "axis 181 5-6le- d3\n"
		 "axis 181 0-1be raw_be\n"
		 "axis 181 7|12@0+ moto12\n"
		 "axis 181 3|13@1- odd13\n"
		 "axis 181 4+ b4\n"
		 "axis 181 4- s4\n"
		 "button 181 5.3 bit53\n"
		 "axis 181 63|1@1+ top\n"
		 "axis 181 0|64@1+ all_le\n"
		 "axis 181 7|64@0- all_be\n",
		 &map_a);
	const uint8_t d[8] = { 0xE8, 0x03, 0xF4, 0x01, 0x80, 0x08, 0xF8, 0x81 };
	assert_true(value_of(&map_a, 0x181, d, 8, "d1") == 1000 * 0.1);      /* 0x03E8 */
	assert_true(value_of(&map_a, 0x181, d, 8, "d2") == 500 * 0.5 - 50);  /* 0x01F4 */
	assert_true(value_of(&map_a, 0x181, d, 8, "d3") == (int16_t)0xF808); /* -2040 */
	assert_true(value_of(&map_a, 0x181, d, 8, "raw_be") == 0xE803);
	/* Motorola, MSB at byte 0 bit 7, 12 bits: 0xE80 */
	assert_true(value_of(&map_a, 0x181, d, 8, "moto12") == 0xE80);
	/* Intel from bit 3, 13 bits: (0x03E8 >> 3) = 0x7D, bit 12 clear */
	assert_true(value_of(&map_a, 0x181, d, 8, "odd13") == 0x7D);
	assert_true(value_of(&map_a, 0x181, d, 8, "b4") == 128);
	assert_true(value_of(&map_a, 0x181, d, 8, "s4") == -128);
	assert_true(value_of(&map_a, 0x181, d, 8, "bit53") == 1); /* 0x08 bit 3 */
	assert_true(value_of(&map_a, 0x181, d, 8, "top") == 1);   /* 0x81 bit 7 */
	assert_true(value_of(&map_a, 0x181, d, 8, "all_le") == (double)0x81F8088001F403E8ull);
	assert_true(value_of(&map_a, 0x181, d, 8, "all_be") ==
		    (double)(int64_t)0xE803F4018008F881ull);
	/* the shorthand forms are the DBC forms */
	assert_int_equal(map_a.line[0].start, 0);
	assert_int_equal(map_a.line[0].length, 16);
	assert_int_equal(map_a.line[3].order, CAN_MAP_MOTOROLA);
	assert_int_equal(map_a.line[3].start, 7);
	assert_int_equal(map_a.line[8].start, 43);
	assert_int_equal(map_a.line[8].length, 1);
	/* a frame of another id, an extended twin of the id: nothing */
	int li[4];
	double va[4];
	assert_int_equal(can_input_decode(&map_a, 0x182, d, 8, li, va, 4), 0);
	assert_int_equal(can_input_decode(&map_a, 0x181 | CAN_EFF_FLAG, d, 8, li, va, 4), 0);
}

static void
test_mux_and_clamp_and_truncation(void **unused)
{
	(void)unused;
	map_from("mux 00000200 0|4@1+ sel\n"
		 "axis 00000200 8|8@1- a factor=2 clamp=-10,100 mux=sel:1,3\n"
		 "axis 00000200 16|16@1+ b mux=sel:2\n"
		 "mux 00000200 4|4@1+ sub mux=sel:2\n"
		 "axis 00000200 32|8@1+ c mux=sub:5\n"
		 "axis 00000200 56|8@1+ tail\n",
		 &map_a);
	uint32_t id = 0x200 | CAN_EFF_FLAG;
	uint8_t d[8] = { 0x01, 0x40, 0x34, 0x12, 0x07, 0, 0, 0x99 };
	assert_true(value_of(&map_a, id, d, 8, "a") == 100); /* 0x40 * 2 = 128, clamped */
	assert_true(isnan(value_of(&map_a, id, d, 8, "b")));
	assert_true(isnan(value_of(&map_a, id, d, 8, "sub")));
	d[1] = 0xF0; /* -16 * 2 = -32, clamped */
	assert_true(value_of(&map_a, id, d, 8, "a") == -10);
	d[0] = 0x52; /* sel 2, sub 5 */
	assert_true(isnan(value_of(&map_a, id, d, 8, "a")));
	assert_true(value_of(&map_a, id, d, 8, "b") == 0x1234);
	assert_true(value_of(&map_a, id, d, 8, "sub") == 5);
	assert_true(value_of(&map_a, id, d, 8, "c") == 7);
	assert_true(value_of(&map_a, id, d, 8, "tail") == 0x99);
	/* a 4-byte frame holds sel, sub, b and c whole; tail is missing */
	assert_true(isnan(value_of(&map_a, id, d, 4, "c")));
	assert_true(value_of(&map_a, id, d, 4, "b") == 0x1234);
	assert_true(isnan(value_of(&map_a, id, d, 4, "tail")));
	/* through feed: counted */
	can_input_init(&input, &map_a, 3, "panel (test)");
	input.log.out = fopen("/dev/null", "w");
	input_queue_init(&queue);
	uint8_t fr[16] = { 0 };
	memcpy(fr, &id, 4);
	fr[4] = 4;
	memcpy(fr + 8, d, 8);
	assert_int_equal(can_input_feed(&input, fr, 16, 10, &queue), 0);
	assert_int_equal(input.short_frames, 1);
	assert_int_equal(input.missing_fields, 2); /* c (its sub is 5) and tail */
	fr[4] = 0;
	assert_int_equal(can_input_feed(&input, fr, 16, 20, &queue), -1);
	assert_int_equal(input.missing_fields, 4); /* sel (its branches not tried) and tail */
	fclose(input.log.out);
}

static void
frame_make(uint8_t *dest, uint32_t id, int len, const uint8_t *data)
{
	memset(dest, 0, 16);
	memcpy(dest, &id, 4);
	dest[4] = (uint8_t)len;
	if (data)
		memcpy(dest + 8, data, (size_t)(len > 8 ? 8 : len));
}

static int
pop_all(struct input_event_rec *dest, int max)
{
	int n = 0;
	while (n < max && input_queue_pop(&queue, &dest[n]))
		n++;
	return n;
}

static void
test_frames_counted_not_decoded(void **unused)
{
	(void)unused;
	map_from("axis 181 0 a\n", &map_a);
	can_input_init(&input, &map_a, 1, "panel (test)");
	input.log.out = fopen("/dev/null", "w");
	input_queue_init(&queue);
	uint8_t fr[17], d[8] = { 5 };
	frame_make(fr, 0x181, 1, d);
	assert_int_equal(can_input_feed(&input, fr, 15, 1, &queue), -1);
	assert_int_equal(can_input_feed(&input, fr, 17, 1, &queue), -1);
	assert_int_equal(input.bad_size, 2);
	frame_make(fr, 0x181 | CAN_ERR_FLAG, 8, d);
	assert_int_equal(can_input_feed(&input, fr, 16, 2, &queue), -1);
	assert_int_equal(input.error_frames, 1);
	frame_make(fr, 0x181 | CAN_RTR_FLAG, 1, NULL);
	assert_int_equal(can_input_feed(&input, fr, 16, 3, &queue), -1);
	assert_int_equal(input.rtr_frames, 1);
	frame_make(fr, 0x182, 1, d);
	assert_int_equal(can_input_feed(&input, fr, 16, 4, &queue), -1);
	frame_make(fr, 0x181 | CAN_EFF_FLAG, 1, d);
	assert_int_equal(can_input_feed(&input, fr, 16, 4, &queue), -1);
	assert_int_equal(input.unknown_ids, 2);
	frame_make(fr, 0x181, 9, d);
	assert_int_equal(can_input_feed(&input, fr, 16, 5, &queue), -1);
	assert_int_equal(input.bad_len, 1);
	struct input_event_rec ev[8];
	assert_int_equal(pop_all(ev, 8), 0);
	/* and a good one decodes */
	frame_make(fr, 0x181, 1, d);
	assert_int_equal(can_input_feed(&input, fr, 16, 6, &queue), 0);
	assert_int_equal(pop_all(ev, 8), 2);
	assert_int_equal(ev[0].kind, INPUT_VALUATOR);
	assert_true(ev[0].x == 5);
	assert_int_equal(ev[1].kind, INPUT_FRAME);
	fclose(input.log.out);
}

static void
test_stale_once_and_buttons_on_change(void **unused)
{
	(void)unused;
	map_from("axis 181 0 dial stale=100\n"
		 "button 181 1.0 b1\n"
		 "button 181 1.1 b2 code=BTN_0 stale=50\n"
		 "axis 181 2 forever stale=0\n",
		 &map_a);
	assert_int_equal(map_a.line[1].code, BTN_TRIGGER_HAPPY1);
	assert_int_equal(map_a.line[2].code, BTN_0);
	can_input_init(&input, &map_a, 7, "panel (test)");
	input_queue_init(&queue);
	struct input_event_rec ev[16];
	uint8_t fr[16], d[8] = { 10, 0x02, 1 };
	frame_make(fr, 0x181, 3, d);
	assert_int_equal(can_input_feed(&input, fr, 16, 1000, &queue), 0);
	/* dial, b2 pressed, forever, frame; b1 was released and stays so: no event */
	int n = pop_all(ev, 16);
	assert_int_equal(n, 4);
	assert_int_equal(ev[0].kind, INPUT_VALUATOR);
	assert_int_equal(ev[0].code, 0);
	assert_int_equal(ev[0].device, 7);
	assert_int_equal(ev[0].t_us, 1000);
	assert_int_equal(ev[1].kind, INPUT_BUTTON);
	assert_int_equal(ev[1].code, BTN_0);
	assert_int_equal(ev[1].value, 1);
	assert_int_equal(ev[2].code, 3);
	assert_int_equal(ev[3].kind, INPUT_FRAME);
	/* the same frame again: nothing changed, no events */
	assert_int_equal(can_input_feed(&input, fr, 16, 2000, &queue), 0);
	assert_int_equal(pop_all(ev, 16), 0);
	/* b1 down, b2 up */
	fr[8 + 1] = 0x01;
	assert_int_equal(can_input_feed(&input, fr, 16, 3000, &queue), 0);
	n = pop_all(ev, 16);
	assert_int_equal(n, 3);
	assert_int_equal(ev[0].code, BTN_TRIGGER_HAPPY1);
	assert_int_equal(ev[0].value, 1);
	assert_int_equal(ev[1].code, BTN_0);
	assert_int_equal(ev[1].value, 0);
	/* within the timeout: nothing */
	can_input_tick(&input, 3000 + 50000, &queue);
	assert_int_equal(pop_all(ev, 16), 0);
	/* past b1's default (1000 ms) no; past the dial's 100 ms: stale once */
	can_input_tick(&input, 3000 + 100001, &queue);
	n = pop_all(ev, 16);
	assert_int_equal(n, 2);
	assert_int_equal(ev[0].kind, INPUT_VALUATOR);
	assert_int_equal(ev[0].flags, INPUT_F_STALE);
	assert_true(ev[0].x == 10);
	assert_int_equal(ev[0].t_us, 103001);
	assert_int_equal(ev[1].kind, INPUT_FRAME);
	can_input_tick(&input, 3000 + 200000, &queue);
	assert_int_equal(pop_all(ev, 16), 0);
	/* b1 held past its timeout: released once */
	can_input_tick(&input, 3000 + 1000001, &queue);
	n = pop_all(ev, 16);
	assert_int_equal(n, 2);
	assert_int_equal(ev[0].kind, INPUT_BUTTON);
	assert_int_equal(ev[0].value, 0);
	can_input_tick(&input, 9000000, &queue);
	assert_int_equal(pop_all(ev, 16), 0);
	/* a frame brings the stale dial back, same value and all */
	assert_int_equal(can_input_feed(&input, fr, 16, 9100000, &queue), 0);
	n = pop_all(ev, 16);
	assert_int_equal(n, 3); /* dial (fresh), b1 pressed again, frame */
	assert_int_equal(ev[0].flags, 0);
	assert_int_equal(ev[1].code, BTN_TRIGGER_HAPPY1);
	assert_int_equal(ev[1].value, 1);
}

static void
test_no_allocation_per_frame(void **unused)
{
	(void)unused;
	char err[256];
	if (can_map_read(DIR "panel.map", &map_a, err, sizeof err))
		fail_msg("%s", err);
	can_input_init(&input, &map_a, 1, "panel (test)");
	input.log.out = fopen("/dev/null", "w");
	setvbuf(input.log.out, NULL, _IONBF, 0); /* as stderr: no buffer to allocate */
	input_queue_init(&queue);
	uint8_t fr[16];
	struct input_event_rec ev;
#if COUNT_ALLOCS
	long a0 = allocs;
#endif
	for (int i = 0; i < 20000; i++) {
		uint8_t d[8] = { (uint8_t)i, (uint8_t)(i >> 8), (uint8_t)(i * 7), 3, 4, 5, 6, 7 };
		frame_make(fr, i % 2 ? 0x181 : 0x18FF0A42 | CAN_EFF_FLAG, 8 - i % 3, d);
		can_input_feed(&input, fr, 16, (uint64_t)i * 1000, &queue);
		can_input_tick(&input, (uint64_t)i * 1000, &queue);
		while (input_queue_pop(&queue, &ev))
			;
	}
#if COUNT_ALLOCS
	assert_int_equal(allocs, a0);
#endif
	assert_true(input.frames > 10000);
	fclose(input.log.out);
}

/* a bad map: refused with name:line: and the message, the destination untouched */
static void
refused_n(const char *text, size_t n, int line, const char *words)
{
	char err[256] = "", want[64];
	memset(&map_b, 0xA5, sizeof map_b);
	int r = can_map_parse(text, n, "bad.map", &map_b, err, sizeof err);
	if (r != -1)
		fail_msg("accepted: %s", text);
	snprintf(want, sizeof want, "bad.map:%d: ", line);
	if (strncmp(err, want, strlen(want)) != 0 || !strstr(err, words))
		fail_msg("for '%s': got '%s', want '%s...%s'", text, err, want, words);
	const unsigned char *p = (const unsigned char *)&map_b;
	for (size_t i = 0; i < sizeof map_b; i++)
		if (p[i] != 0xA5)
			fail_msg("'%s' changed the destination at byte %zu", text, i);
}

static void
refused(const char *text, int line, const char *words)
{
	refused_n(text, strlen(text), line, words);
}

static void
test_bad_maps_refused_with_file_and_line(void **unused)
{
	(void)unused;
	refused("# nothing\n\n", 2, "no axis");
	refused("axis 181 0 a\nknob 181 1 b\n", 2, "unknown line kind");
	refused("axis 181 0\n", 1, "KIND ID FIELD NAME");
	refused("axis 0x181 0 a\n", 1, "3 hex digits");
	refused("axis 1810 0 a\n", 1, "3 hex digits");
	refused("axis 800 0 a\n", 1, "out of range");
	refused("axis 20000000 0 a\n", 1, "out of range");
	refused("axis 18g 0 a\n", 1, "3 hex digits");
	refused("axis 181 8 a\n", 1, "a field is");
	refused("axis 181 3-2 a\n", 1, "A <= B");
	refused("axis 181 2.8 a\n", 1, "BYTE.BIT");
	refused("axis 181 0|0@1+ a\n", 1, "1..64");
	refused("axis 181 0|65@1+ a\n", 1, "1..64");
	refused("axis 181 64|1@1+ a\n", 1, "START|LENGTH");
	refused("axis 181 0|8@2+ a\n", 1, "@1 (Intel)");
	refused("axis 181 0|8@1 a\n", 1, "+ (unsigned)");
	refused("axis 181 60|8@1+ a\n", 1, "past the 8 bytes");
	refused("axis 181 7|8@0+ a\naxis 181 56|16@0+ b\n", 2, "past the 8 bytes");
	refused("axis 181 0x a\n", 1, "unexpected characters");
	refused("axis 181 0 a b\n", 1, "not an option");
	refused("axis 181 0 a speed=3\n", 1, "unknown option");
	refused("axis 181 0 a factor=2 factor=3\n", 1, "given twice");
	refused("axis 181 0 a factor=x\n", 1, "finite number");
	refused("axis 181 0 a offset=inf\n", 1, "finite number");
	refused("axis 181 0 a factor=1e999\n", 1, "finite number");
	refused("axis 181 0 a clamp=5\n", 1, "MIN,MAX");
	refused("axis 181 0 a clamp=5,1\n", 1, "MIN <= MAX");
	refused("button 181 0.0 a clamp=0,1\n", 1, "for axis lines");
	refused("axis 181 0 a stale=-1\n", 1, "milliseconds");
	refused("axis 181 0 a stale=3600001\n", 1, "milliseconds");
	refused("axis 181 0 a code=BTN_0\n", 1, "for button lines");
	refused("button 181 0.0 a code=KEY_A\n", 1, "BTN_");
	refused("button 181 0.0 a code=0x300\n", 1, "BTN_");
	refused("axis 181 0 a dlc=9\n", 1, "1..8");
	refused("axis 181 0 a\naxis 181 1 a\n", 2, "already used");
	refused("axis 181 0 a b=c\n", 1, "unknown option");
	refused("axis 181 0 a mux=s:1\nmux 181 1 s\n", 1, "no earlier line");
	refused("axis 181 0 s\naxis 181 1 a mux=s:1\n", 2, "not a mux line");
	refused("mux 182 0 s\naxis 181 1 a mux=s:1\n", 2, "another id");
	refused("mux 181 0 s\naxis 181 1 a mux=s\n", 2, "NAME:VALUE");
	refused("mux 181 0 s\naxis 181 1 a mux=s:1,x\n", 2, "integers");
	refused("mux 181 0 s\naxis 181 1 a mux=s:1,2,3,4,5,6,7,8,9\n", 2, "at most 8");
	refused_n("axis 181 0 a\0b\n", 13, 1, "NUL");
	refused("axis 181 0 a/b\n", 1, "a name is");
	refused("axis 181 0 a1234567890123456789012345678901234567890123456789012345678901234\n", 1,
		"a name is");
	/* too many lines */
	static char big[300 * 32];
	size_t k = 0;
	for (int i = 0; i < 257; i++)
		k += (size_t)snprintf(big + k, sizeof big - k, "axis 181 0 n%d\n", i);
	refused(big, 257, "too many lines");
	/* the file reader names the path */
	char err[256];
	assert_int_equal(can_map_read("/nonexistent/x.map", &map_b, err, sizeof err), -1);
	assert_non_null(strstr(err, "/nonexistent/x.map:"));
}

/* n button lines on 8 ids, a comment line first and an axis line last; the last button
 * with code (when not NULL) */
static size_t
buttons_text(char *dest, size_t size, int n, const char *code)
{
	size_t k = (size_t)snprintf(dest, size, "# buttons\n");
	for (int i = 0; i < n; i++)
		k += (size_t)snprintf(dest + k, size - k, "button %03X %d.%d b%d%s%s\n", 0x100 + i / 8,
				      0, i % 8, i, i == n - 1 && code ? " code=" : "",
				      i == n - 1 && code ? code : "");
	k += (size_t)snprintf(dest + k, size - k, "axis 1FF 0 tail\n");
	return k;
}

static void
test_default_button_codes_are_the_kernel_s_forty(void **unused)
{
	(void)unused;
	static char text[64 * 48];
	/* BTN_TRIGGER_HAPPY1..40 in order: the kernel's codes for buttons of this kind */
	buttons_text(text, sizeof text, 40, NULL);
	map_from(text, &map_a);
	assert_int_equal(map_a.n, 41);
	for (int i = 0; i < 40; i++)
		assert_int_equal(map_a.line[i].code, BTN_TRIGGER_HAPPY1 + i);
	assert_int_equal(map_a.line[39].code, BTN_TRIGGER_HAPPY40);
	assert_int_equal(BTN_TRIGGER_HAPPY40, 0x2e7);
	/* a 41st without code= has none left: refused on its own line (the comment is line 1) */
	buttons_text(text, sizeof text, 41, NULL);
	refused(text, 42, "more than 40 buttons without code=");
	/* with a code of its own it loads */
	buttons_text(text, sizeof text, 41, "BTN_0");
	map_from(text, &map_a);
	assert_int_equal(map_a.n, 42);
	assert_int_equal(map_a.line[40].code, BTN_0);
	assert_int_equal(map_a.line[39].code, BTN_TRIGGER_HAPPY40);
}

static void
map_equal(const struct can_map *a, const struct can_map *b)
{
	assert_int_equal(a->n, b->n);
	assert_memory_equal(a->line, b->line, (size_t)a->n * sizeof a->line[0]);
	assert_int_equal(a->n_ids, b->n_ids);
	assert_memory_equal(a->ids, b->ids, (size_t)a->n_ids * sizeof a->ids[0]);
	assert_memory_equal(a->id_len, b->id_len, (size_t)a->n_ids);
	assert_memory_equal(a->by_id, b->by_id, (size_t)a->n * sizeof a->by_id[0]);
}

static void
round_trip(const struct can_map *m)
{
	char *text = NULL, err[256];
	size_t n = 0;
	FILE *f = open_memstream(&text, &n);
	assert_int_equal(can_map_write(f, m), 0);
	fclose(f);
	if (can_map_parse(text, n, "written", &map_b, err, sizeof err))
		fail_msg("%s\n%s", err, text);
	map_equal(m, &map_b);
	free(text);
}

static void
test_map_written_and_read_back_is_the_same(void **unused)
{
	(void)unused;
	const char *files[] = { DIR "panel.map", DIR "mux.map", DIR "defects.map" };
	char err[256];
	for (int i = 0; i < 3; i++) {
		if (can_map_read(files[i], &map_a, err, sizeof err))
			fail_msg("%s", err);
		round_trip(&map_a);
	}
	map_from("mux 1FFFFFFF 0-1be- s factor=0.1 offset=-3.3333333333333335 stale=0\n"
		 "axis 1FFFFFFF 2-3 a clamp=-1e-300,0.30000000000000004 "
		 "mux=s:-1,0,9223372036854775807 dlc=8\n"
		 "button 000 7.7 b code=0x2ff\n"
		 "button 000 7.6 c code=BTN_TRIGGER_HAPPY40\n"
		 "button 000 0.0 d\n"
		 "axis 7FF 7- e   # a comment\n",
		 &map_a);
	round_trip(&map_a);
	assert_int_equal(map_a.line[4].code, BTN_TRIGGER_HAPPY1 + 2);
	/* filters: one per id, exact */
	struct can_filter flt[4];
	assert_int_equal(can_map_filters(&map_a, flt, 4), 3);
	assert_int_equal(flt[0].can_id, 0x000);
	assert_int_equal(flt[0].can_mask, CAN_SFF_MASK | CAN_EFF_FLAG);
	assert_int_equal(flt[1].can_id, 0x7FF);
	assert_int_equal(flt[2].can_id, 0x1FFFFFFF | CAN_EFF_FLAG);
	assert_int_equal(flt[2].can_mask, CAN_EFF_MASK | CAN_EFF_FLAG);
	assert_int_equal(can_map_filters(&map_a, flt, 1), 3);
}

/* ---- candump logs ---- */

static char *
written(const struct rec_candump *r, size_t *n)
{
	char *text = NULL;
	FILE *f = open_memstream(&text, n);
	assert_int_equal(rec_candump_write(f, r), 0);
	fclose(f);
	return text;
}

static void
logs_equal(const struct rec_candump *a, const struct rec_candump *b)
{
	assert_int_equal(a->n, b->n);
	assert_int_equal(a->nanoseconds, b->nanoseconds);
	for (size_t i = 0; i < a->n; i++) {
		const struct rec_candump_frame *x = &a->frames[i], *y = &b->frames[i];
		assert_int_equal(x->t_abs_us, y->t_abs_us);
		assert_int_equal(x->t_us, y->t_us);
		assert_int_equal(x->t_ns, y->t_ns);
		assert_string_equal(x->iface, y->iface);
		assert_int_equal(x->can_id, y->can_id);
		assert_int_equal(x->len, y->len);
		assert_int_equal(x->len8_dlc, y->len8_dlc);
		assert_memory_equal(x->data, y->data, 8);
		assert_int_equal(x->dir, y->dir);
	}
}

/* candump.log is written by hand in candump's format: (%010lu.%06lu) %*s %s */
static void
test_candump_read_and_written_as_candump_writes(void **unused)
{
	(void)unused;
	struct rec_candump r, r2;
	char err[256];
	if (rec_candump_read(DIR "candump.log", &r, err, sizeof err))
		fail_msg("%s", err);
	assert_int_equal(r.n, 9);
	assert_int_equal(r.frames[0].t_abs_us, 1700000000000000ull);
	assert_int_equal(r.frames[0].t_us, 0);
	assert_int_equal(r.frames[1].t_us, 10123);
	assert_string_equal(r.frames[1].iface, "vcan10");
	assert_int_equal(r.frames[0].can_id, 0x181);
	assert_int_equal(r.frames[0].len, 8);
	assert_int_equal(r.frames[0].data[1], 0x03);
	assert_int_equal(r.frames[1].can_id, 0x18FF0A42 | CAN_EFF_FLAG);
	assert_int_equal(r.frames[2].can_id, 0x123 | CAN_RTR_FLAG);
	assert_int_equal(r.frames[2].len, 0);
	assert_int_equal(r.frames[3].len, 5);
	assert_int_equal(r.frames[4].can_id, 0x7FF);
	assert_int_equal(r.frames[4].len, 0);
	assert_int_equal(r.frames[5].can_id, 0x80 | CAN_ERR_FLAG);
	assert_int_equal(r.frames[5].len, 8);
	assert_int_equal(r.frames[6].can_id, 1 | CAN_EFF_FLAG);
	assert_int_equal(r.frames[7].dir, 'R');
	assert_int_equal(r.frames[8].dir, 'T');
	assert_int_equal(r.frames[8].t_us, 3000000);
	/* written: the same bytes */
	size_t n, m;
	char *text = written(&r, &n);
	char *file = slurp(DIR "candump.log", &m);
	assert_int_equal(n, m);
	assert_memory_equal(text, file, n);
	/* and read back: the same frames */
	if (rec_candump_parse(text, n, "written", &r2, err, sizeof err))
		fail_msg("%s", err);
	logs_equal(&r, &r2);
	free(text);
	free(file);
	rec_candump_free(&r);
	rec_candump_free(&r2);
}

/* pycan.log is what python-can's CanutilsLogWriter wrote (tests/tools/test_can_oracle.py) */
static void
test_candump_python_can_log_read_and_written_byte_for_byte(void **unused)
{
	(void)unused;
	struct rec_candump r;
	char err[256];
	if (rec_candump_read(DIR "pycan.log", &r, err, sizeof err))
		fail_msg("%s", err);
	/* the messages the test gave python-can */
	assert_int_equal(r.n, 6);
	assert_int_equal(r.frames[0].can_id, 0x181);
	assert_int_equal(r.frames[0].len, 4);
	assert_int_equal(r.frames[0].data[3], 0x01);
	assert_int_equal(r.frames[0].dir, 'R');
	assert_int_equal(r.frames[1].can_id, 0x18FF0A42 | CAN_EFF_FLAG);
	assert_int_equal(r.frames[1].t_us, 10123);
	assert_int_equal(r.frames[2].can_id, 0x123 | CAN_RTR_FLAG);
	assert_int_equal(r.frames[3].dir, 'T');
	assert_int_equal(r.frames[3].len, 0);
	assert_int_equal(r.frames[4].can_id, CAN_ERR_FLAG | 0x80);
	assert_int_equal(r.frames[4].dir, 0);
	assert_int_equal(r.frames[5].can_id, 0x1FFFFFFF | CAN_EFF_FLAG);
	assert_int_equal(r.frames[5].t_abs_us, 1700000002999999ull);
	size_t n, m;
	char *text = written(&r, &n);
	char *file = slurp(DIR "pycan.log", &m);
	assert_int_equal(n, m);
	assert_memory_equal(text, file, n);
	free(text);
	free(file);
	rec_candump_free(&r);
}

static void
test_candump_tolerances_and_nanoseconds(void **unused)
{
	(void)unused;
	struct rec_candump r, r2;
	char err[256];
	if (rec_candump_read(DIR "candump-ns.log", &r, err, sizeof err))
		fail_msg("%s", err);
	assert_int_equal(r.n, 4);
	assert_int_equal(r.skipped, 3);
	assert_true(r.nanoseconds);
	assert_int_equal(r.frames[0].t_ns, 1);
	assert_int_equal(r.frames[0].len, 4);
	assert_int_equal(r.frames[0].data[0], 0xE8);
	assert_int_equal(r.frames[0].dir, 'R');
	assert_int_equal(r.frames[1].t_ns, 500);
	assert_int_equal(r.frames[1].len8_dlc, 9);
	assert_int_equal(r.frames[2].can_id, 0x123 | CAN_RTR_FLAG);
	assert_int_equal(r.frames[2].len, 8);
	assert_int_equal(r.frames[2].len8_dlc, 15);
	assert_int_equal(r.frames[2].t_us, 1);
	assert_int_equal(r.frames[3].t_us, 100000);
	size_t n;
	char *text = written(&r, &n);
	const char *want = "(1700000000.000000001) can0 181#E803F401 R\n"
			   "(1700000000.000000500) can0 123#1122334455667788_9\n"
			   "(1700000000.000001000) can0 123#R8_F\n"
			   "(1700000000.100000000) can0 12345678#\n";
	assert_string_equal(text, want);
	if (rec_candump_parse(text, n, "written", &r2, err, sizeof err))
		fail_msg("%s", err);
	logs_equal(&r, &r2);
	/* the kernel's frame */
	uint8_t fr[16];
	rec_candump_to_can_frame(&r.frames[1], fr);
	uint32_t id;
	memcpy(&id, fr, 4);
	assert_int_equal(id, 0x123);
	assert_int_equal(fr[4], 8);
	assert_int_equal(fr[7], 9);
	assert_int_equal(fr[15], 0x88);
	free(text);
	rec_candump_free(&r);
	rec_candump_free(&r2);
}

static void
log_refused(const char *text, int line, const char *words)
{
	struct rec_candump r;
	char err[256] = "", want[64];
	int res = rec_candump_parse(text, strlen(text), "bad.log", &r, err, sizeof err);
	if (res != -1)
		fail_msg("accepted: %s", text);
	assert_null(r.frames);
	assert_int_equal(r.n, 0);
	snprintf(want, sizeof want, "bad.log:%d: ", line);
	if (strncmp(err, want, strlen(want)) != 0 || !strstr(err, words))
		fail_msg("for '%s': got '%s', want '%s...%s'", text, err, want, words);
}

static void
test_bad_logs_refused_with_file_and_line(void **unused)
{
	(void)unused;
	const char *ok = "(1700000000.000000) can0 123#11\n";
	char buf[256];
	log_refused("(1700000000.00000) can0 123#11\n", 1, "6 digits");
	log_refused("(1700000000.0000000) can0 123#11\n", 1, "6 digits");
	log_refused("(1700000000.0000000000) can0 123#11\n", 1, "6 digits");
	log_refused("(1700000000) can0 123#11\n", 1, "SECONDS.FRACTION");
	log_refused("(1700000000.000000 can0 123#11\n", 1, "SECONDS.FRACTION");
	log_refused("(a.000000) can0 123#11\n", 1, "SECONDS.FRACTION");
	log_refused("(1234567890123.000000) can0 123#11\n", 1, "12 digits");
	log_refused("(1700000000.000000) can0\n", 1, "IFACE FRAME");
	log_refused("(1700000000.000000) can0 12311\n", 1, "no '#'");
	log_refused("(1700000000.000000) can0 1234#11\n", 1, "3 hex digits");
	log_refused("(1700000000.000000) can0 12G#11\n", 1, "not hex");
	log_refused("(1700000000.000000) can0 800#11\n", 1, "at most 7FF");
	log_refused("(1700000000.000000) can0 80000001#11\n", 1, "at most 1FFFFFFF");
	log_refused("(1700000000.000000) can0 123##1112233\n", 1, "CAN FD");
	log_refused("(1700000000.000000) can0 123#R9\n", 1, "one digit 0..8");
	log_refused("(1700000000.000000) can0 20000080#R\n", 1, "error frame");
	log_refused("(1700000000.000000) can0 123#112\n", 1, "pairs of hex");
	log_refused("(1700000000.000000) can0 123#11ZZ\n", 1, "pairs of hex");
	log_refused("(1700000000.000000) can0 123#112233445566778899\n", 1, "more than 8");
	log_refused("(1700000000.000000) can0 123#11_9\n", 1, "raw DLC");
	log_refused("(1700000000.000000) can0 123#1122334455667788_8\n", 1, "raw DLC");
	log_refused("(1700000000.000000) can0 123#R1_9\n", 1, "raw DLC");
	log_refused("(1700000000.000000) can0123456789012345678901234567890123 123#11\n", 1,
		    "longer than 31");
	snprintf(buf, sizeof buf, "%s\n# c\n(1699999999.999999) can0 123#11\n", ok);
	log_refused(buf, 4, "earlier than the line before");
	char err[256];
	struct rec_candump r;
	assert_int_equal(rec_candump_read("/nonexistent/x.log", &r, err, sizeof err), -1);
	assert_non_null(strstr(err, "/nonexistent/x.log:"));
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_decoding_agrees_with_cantools_panel),
		cmocka_unit_test(test_decoding_agrees_with_cantools_mux),
		cmocka_unit_test(test_decoding_agrees_with_cantools_defects),
		cmocka_unit_test(test_field_forms_decode_hand_worked_bits),
		cmocka_unit_test(test_mux_and_clamp_and_truncation),
		cmocka_unit_test(test_frames_counted_not_decoded),
		cmocka_unit_test(test_stale_once_and_buttons_on_change),
		cmocka_unit_test(test_no_allocation_per_frame),
		cmocka_unit_test(test_bad_maps_refused_with_file_and_line),
		cmocka_unit_test(test_default_button_codes_are_the_kernel_s_forty),
		cmocka_unit_test(test_map_written_and_read_back_is_the_same),
		cmocka_unit_test(test_candump_read_and_written_as_candump_writes),
		cmocka_unit_test(test_candump_python_can_log_read_and_written_byte_for_byte),
		cmocka_unit_test(test_candump_tolerances_and_nanoseconds),
		cmocka_unit_test(test_bad_logs_refused_with_file_and_line),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
