/*
 * test_hid.c - raw HID: the report descriptor parser, the report decoder
 * and hid-recorder files. Field values are checked against hid-tools (the
 * .expect files tests/input/hid/make_expect.py writes), key codes against
 * linux/input-event-codes.h, parsing rules against drivers/hid/hid-core.c
 * and hid-input.c, and the recording format against files hid-tools wrote.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "expect_event.h"

#include <linux/input-event-codes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "devices/hid_desc.h"
#include "devices/hid_input.h"
#include "devices/hid_keymap.h"
#include "devices/queue.h"
#include "devices/rec_hid.h"

#include "alloc_count.h"

#define DATA "tests/input/hid/"

static struct input_queue queue;
static struct hid_desc desc;
static struct hid_input hin;

/* ---- helpers ------------------------------------------------------------- */

static char *
slurp(const char *path, size_t *n)
{
	FILE *f = fopen(path, "rb");
	if (!f)
		fail_msg("cannot open %s", path);
	fseek(f, 0, SEEK_END);
	long len = ftell(f);
	fseek(f, 0, SEEK_SET);
	char *buf = malloc((size_t)len + 1);
	assert_non_null(buf);
	assert_int_equal(fread(buf, 1, (size_t)len, f), (size_t)len);
	buf[len] = '\0';
	fclose(f);
	*n = (size_t)len;
	return buf;
}

/* hex bytes separated by blanks; '#' to the end of a line is a comment */
static size_t
hex_to_bytes(const char *s, uint8_t *dest, size_t max)
{
	size_t n = 0;
	while (*s) {
		if (*s == '#') {
			while (*s && *s != '\n')
				s++;
			continue;
		}
		if (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r') {
			s++;
			continue;
		}
		char *end;
		unsigned long v = strtoul(s, &end, 16);
		assert_true(end > s && v <= 0xff);
		assert_true(n < max);
		dest[n++] = (uint8_t)v;
		s = end;
	}
	return n;
}

static size_t
load_rdesc(const char *name, uint8_t *dest)
{
	char path[256];
	size_t len;
	snprintf(path, sizeof path, DATA "%s.rdesc", name);
	char *text = slurp(path, &len);
	size_t n = hex_to_bytes(text, dest, HID_DESC_MAX_BYTES);
	free(text);
	return n;
}

static void
parse_ok(const uint8_t *b, size_t n, struct hid_desc *d)
{
	char err[256];
	int ret = hid_desc_parse(b, n, d, err, sizeof err);
	if (ret != 0)
		fail_msg("parse failed: %s", err);
}

static void
parse_named(const char *name, struct hid_desc *d)
{
	uint8_t b[HID_DESC_MAX_BYTES];
	size_t n = load_rdesc(name, b);
	parse_ok(b, n, d);
}

/* the error message for bytes that must be refused; d must come back empty */
static void
refuse(const uint8_t *b, size_t n, const char *want_at, const char *want_text)
{
	char err[256];
	struct hid_desc *d = &desc;
	assert_int_equal(hid_desc_parse(b, n, d, err, sizeof err), -1);
	if (strncmp(err, want_at, strlen(want_at)) != 0 || !strstr(err, want_text))
		fail_msg("got \"%s\", want \"%s...%s\"", err, want_at, want_text);
	assert_int_equal(d->nreports, 0);
	assert_int_equal(d->nfields, 0);
	assert_null(hid_desc_report_by_id(d, 0));
}

static void
start(const struct hid_desc *d)
{
	input_queue_init(&queue);
	hid_input_init(&hin, d, 7, "test device");
	hin.log.out = tmpfile();
}

static void
stop(void)
{
	if (hin.log.out)
		fclose(hin.log.out);
	hin.log.out = NULL;
}

static int
feed(const uint8_t *r, size_t n)
{
	return hid_input_feed(&hin, r, n, 1000, &queue);
}

/* the next event must be this one */
static void
expect_event(enum input_kind kind, unsigned code, int value)
{
	expect_event_in(&queue, 7, kind, code, value);
}

static struct input_event_rec
next_event(void)
{
	struct input_event_rec e;
	assert_int_equal(input_queue_pop(&queue, &e), 1);
	return e;
}

static void
expect_empty(void)
{
	struct input_event_rec e;
	if (input_queue_pop(&queue, &e))
		fail_msg("unexpected %s code %u value %d",
			 input_kind_to_str((enum input_kind)e.kind), e.code, e.value);
}

/* ---- field values against hid-tools --------------------------------------- */

/* our decoding of one report in the .expect file's line format */
static int
our_lines(const struct hid_desc *d, const uint8_t *r, size_t n, int usages_known,
	  char lines[][2048], int max)
{
	unsigned id = d->numbered ? r[0] : 0;
	const struct hid_desc_report *rep = hid_desc_report_by_id(d, id);
	assert_non_null(rep);
	assert_int_equal(rep->bytes, n);
	const uint8_t *data = r + (d->numbered ? 1 : 0);
	unsigned base = d->numbered ? 8 : 0;
	int k = 0;
	for (unsigned i = 0; i < rep->field_count; i++) {
		const struct hid_desc_field *f = &d->fields[rep->field_first + i];
		if (f->flags & HID_FIELD_CONSTANT)
			continue;
		assert_true(f->usages > 0);
		if (f->flags & HID_FIELD_VARIABLE) {
			for (unsigned j = 0; j < f->count; j++) {
				int32_t v = hid_input_value(f, data, j);
				if (v == 0)
					continue;
				assert_true(k < max);
				if (usages_known)
					snprintf(lines[k++], 2048, "V: %u %u 0x%08x %d",
						 base + f->bit_offset + j * f->size, f->size,
						 hid_desc_usage(d, f, j), v);
				else
					snprintf(lines[k++], 2048, "V: %u %u ? %d",
						 base + f->bit_offset + j * f->size, f->size, v);
			}
			continue;
		}
		assert_true(k < max);
		int len = snprintf(lines[k], 2048, "A: %u %u %u", base + f->bit_offset, f->size,
				   f->count);
		for (unsigned j = 0; j < f->count; j++) {
			int32_t v = hid_input_value(f, data, j);
			int64_t idx = (int64_t)v - f->logical_min;
			uint32_t nusages = f->usages > f->count ? f->usages : f->count;
			if (!usages_known)
				len += snprintf(lines[k] + len, 2048 - (size_t)len, " %d=?", v);
			else if (v >= f->logical_min && v <= f->logical_max && idx < nusages)
				len += snprintf(lines[k] + len, 2048 - (size_t)len, " %d=0x%08x", v,
						hid_desc_usage(d, f, (uint32_t)idx));
			else
				len += snprintf(lines[k] + len, 2048 - (size_t)len, " %d=-", v);
		}
		k++;
	}
	return k;
}

static void
check_against_hidtools(const char *name, int usages_known)
{
	char path[256];
	size_t len;
	static char ours[256][2048];
	parse_named(name, &desc);
	snprintf(path, sizeof path, DATA "%s.expect", name);
	char *text = slurp(path, &len);

	/* walk the file: L: lengths, then E: reports each followed by its values */
	uint8_t report[HID_DESC_MAX_REPORT_BITS / 8 + 1];
	size_t rn = 0;
	int nours = 0, at = 0, reports = 0, lengths = 0;
	char *save = NULL;
	for (char *line = strtok_r(text, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
		if (line[0] == '#')
			continue;
		if (!strncmp(line, "L: ", 3)) {
			unsigned id, bytes;
			assert_int_equal(sscanf(line + 3, "%u %u", &id, &bytes), 2);
			const struct hid_desc_report *rep = hid_desc_report_by_id(&desc, id);
			assert_non_null(rep);
			assert_int_equal(rep->bytes, bytes);
			lengths++;
			continue;
		}
		if (!strncmp(line, "E: ", 3)) {
			if (reports && at != nours)
				fail_msg("%s report %d: we have %d values, hid-tools %d", name,
					 reports, nours, at);
			rn = hex_to_bytes(line + 3, report, sizeof report);
			nours = our_lines(&desc, report, rn, usages_known, ours, 256);
			at = 0;
			reports++;
			continue;
		}
		if (at >= nours)
			fail_msg("%s report %d: hid-tools has \"%s\", we have no more", name,
				 reports, line);
		if (strcmp(line, ours[at]) != 0)
			fail_msg("%s report %d: hid-tools \"%s\", we \"%s\"", name, reports, line,
				 ours[at]);
		at++;
	}
	assert_int_equal(at, nours);
	assert_int_equal(lengths, (int)desc.nreports);
	assert_true(reports > 10);
	free(text);
}

static void
test_values_match_hidtools(void **state)
{
	(void)state;
	static const char *names[] = {
		"boot_mouse",  "boot_keyboard", "qemu_mouse", "qemu_tablet", "qemu_keyboard",
		"nkro_keyboard", "mouse12",    "report_ids", "hires_wheel",
	};
	for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
		check_against_hidtools(names[i], 1);
	/* hid-tools has this one's usages wrong: values and positions only */
	check_against_hidtools("two_ranges", 0);
}

/*
 * hid-core.c hid_parser_local: each Usage Maximum adds usage_minimum ..
 * maximum to the usages already declared, so a second pair appends. The
 * field's bit 0 is then 0xE0 (left control) and bit 8 usage 0x00.
 * hid-tools 0.12 keeps only the second pair, so this is checked by hand.
 */
static void
test_two_usage_ranges_accumulate(void **state)
{
	(void)state;
	parse_named("two_ranges", &desc);
	assert_int_equal(desc.nfields, 1);
	const struct hid_desc_field *f = &desc.fields[0];
	assert_int_equal(f->count, 112);
	assert_int_equal(f->usages, 8 + 0x68);
	assert_int_equal(hid_desc_usage(&desc, f, 0), 0x000700e0);
	assert_int_equal(hid_desc_usage(&desc, f, 7), 0x000700e7);
	assert_int_equal(hid_desc_usage(&desc, f, 8), 0x00070000);
	assert_int_equal(hid_desc_usage(&desc, f, 8 + 0x04), 0x00070004);
	assert_int_equal(hid_desc_usage(&desc, f, 111), 0x00070067);

	/* bit 0: left control; bit 8 + 4: usage 0x04, A */
	start(&desc);
	uint8_t r[14] = { 0x01, 0x10 };
	assert_int_equal(feed(r, sizeof r), 0);
	expect_event(INPUT_KEY, KEY_LEFTCTRL, 1);
	expect_event(INPUT_KEY, KEY_A, 1);
	expect_event(INPUT_FRAME, 0, 0);
	expect_empty();
	stop();
}

/* ---- the descriptor's grammar ---------------------------------------------- */

static void
test_logical_maximum_signedness(void **state)
{
	(void)state;
	/* QEMU's keyboard: "15 00 25 ff" is 0..255 */
	parse_named("qemu_keyboard", &desc);
	const struct hid_desc_report *rep = hid_desc_report_by_id(&desc, 0);
	assert_non_null(rep);
	assert_int_equal(rep->bytes, 8);
	const struct hid_desc_field *keys = &desc.fields[rep->field_first + 2];
	assert_false(keys->flags & HID_FIELD_VARIABLE);
	assert_int_equal(keys->logical_min, 0);
	assert_int_equal(keys->logical_max, 255);

	/* "15 81 25 7f" is -127..127; "15 ff 25 ff" is -1..-1 (signed, as the minimum is) */
	parse_named("boot_mouse", &desc);
	assert_int_equal(desc.fields[2].logical_min, -127);
	assert_int_equal(desc.fields[2].logical_max, 127);
	static const uint8_t neg[] = { 0x05, 0x01, 0x09, 0x30, 0x15, 0xff, 0x25, 0xff,
				       0x75, 0x08, 0x95, 0x01, 0x81, 0x02 };
	parse_ok(neg, sizeof neg, &desc);
	assert_int_equal(desc.fields[0].logical_min, -1);
	assert_int_equal(desc.fields[0].logical_max, -1);
}

static void
test_boot_descriptors(void **state)
{
	(void)state;
	uint8_t b[HID_DESC_MAX_BYTES];
	size_t n, bn;

	/* the built-in ones are Appendix B's bytes, and parse to its formats */
	n = load_rdesc("boot_mouse", b);
	const uint8_t *bb = hid_desc_boot_bytes(HID_BOOT_MOUSE, &bn);
	assert_int_equal(bn, n);
	assert_memory_equal(bb, b, n);
	assert_int_equal(hid_desc_boot(HID_BOOT_MOUSE, &desc), 0);
	assert_int_equal(desc.nreports, 1);
	assert_int_equal(desc.numbered, 0);
	assert_int_equal(desc.reports[0].bytes, 3);

	n = load_rdesc("boot_keyboard", b);
	bb = hid_desc_boot_bytes(HID_BOOT_KEYBOARD, &bn);
	assert_int_equal(bn, n);
	assert_memory_equal(bb, b, n);
	assert_int_equal(hid_desc_boot(HID_BOOT_KEYBOARD, &desc), 0);
	assert_int_equal(desc.reports[0].bytes, 8);
	/* modifiers, reserved, keys */
	assert_int_equal(desc.reports[0].field_count, 3);
	assert_int_equal(desc.fields[2].bit_offset, 16);
	assert_int_equal(desc.fields[2].count, 6);
	assert_int_equal(desc.fields[2].logical_max, 101);
}

static void
test_report_ids_and_offsets(void **state)
{
	(void)state;
	parse_named("report_ids", &desc);
	assert_true(desc.numbered);
	assert_int_equal(desc.nreports, 2);
	const struct hid_desc_report *m = hid_desc_report_by_id(&desc, 1);
	const struct hid_desc_report *k = hid_desc_report_by_id(&desc, 2);
	assert_non_null(m);
	assert_non_null(k);
	assert_null(hid_desc_report_by_id(&desc, 0));
	assert_null(hid_desc_report_by_id(&desc, 3));
	/* id byte + 8 buttons + 16 + 16 + 8 + 8 bits */
	assert_int_equal(m->bytes, 1 + 7);
	assert_int_equal(k->bytes, 1 + 8);

	/* mouse12: 12-bit X and Y at bits 8 and 20 */
	parse_named("mouse12", &desc);
	const struct hid_desc_field *xy = &desc.fields[2];
	assert_int_equal(xy->bit_offset, 8);
	assert_int_equal(xy->size, 12);
	assert_int_equal(hid_desc_usage(&desc, xy, 0), HID_USAGE_GD_X);
	assert_int_equal(hid_desc_usage(&desc, xy, 1), HID_USAGE_GD_Y);
	/* Y = -2048 is 0x800 at bits 20..31: bytes 2 and 3 */
	uint8_t r[5] = { 0, 0x01, 0x00, 0x80, 0 };
	assert_int_equal(hid_input_value(xy, r, 0), 1);
	assert_int_equal(hid_input_value(xy, r, 1), -2048);
}

static void
test_usage_page_rules(void **state)
{
	(void)state;
	/*
	 * HID 1.11 6.2.2.8 and hid_concatenate_last_usage_page: at the main
	 * item, 1-2 byte usages take the last Usage Page: X declared under
	 * Generic Desktop becomes Button 0x30 after "Usage Page (Button)".
	 * A 4-byte (extended) usage keeps its own page.
	 */
	static const uint8_t late_page[] = { 0x05, 0x01, 0x09, 0x30, 0x05, 0x09, 0x15, 0x00,
					     0x25, 0x01, 0x75, 0x01, 0x95, 0x01, 0x81, 0x02,
					     0x75, 0x07, 0x81, 0x01 };
	parse_ok(late_page, sizeof late_page, &desc);
	assert_int_equal(hid_desc_usage(&desc, &desc.fields[0], 0), 0x00090030);

	static const uint8_t extended[] = { 0x05, 0x01, 0x0b, 0x38, 0x02, 0x0c, 0x00,
					    0x09, 0x38, 0x15, 0x81, 0x25, 0x7f, 0x75, 0x08,
					    0x95, 0x02, 0x81, 0x06 };
	parse_ok(extended, sizeof extended, &desc);
	assert_int_equal(hid_desc_usage(&desc, &desc.fields[0], 0), HID_USAGE_CONSUMER_AC_PAN);
	assert_int_equal(hid_desc_usage(&desc, &desc.fields[0], 1), HID_USAGE_GD_WHEEL);
	/* past the usages declared, the last repeats */
	static const uint8_t repeat[] = { 0x05, 0x01, 0x09, 0x30, 0x15, 0x81, 0x25, 0x7f,
					  0x75, 0x08, 0x95, 0x03, 0x81, 0x06 };
	parse_ok(repeat, sizeof repeat, &desc);
	assert_int_equal(hid_desc_usage(&desc, &desc.fields[0], 2), HID_USAGE_GD_X);

	/* Push saves the globals, Pop restores them: the second field is 8 bits again */
	static const uint8_t push_pop[] = { 0x05, 0x01, 0x09, 0x30, 0x15, 0x81, 0x25, 0x7f,
					    0x75, 0x08, 0x95, 0x01, 0xa4, 0x75, 0x10, 0x95,
					    0x01, 0x09, 0x31, 0x81, 0x06, 0xb4, 0x09, 0x38,
					    0x81, 0x06 };
	parse_ok(push_pop, sizeof push_pop, &desc);
	assert_int_equal(desc.fields[0].size, 16);
	assert_int_equal(desc.fields[1].size, 8);
	assert_int_equal(desc.fields[1].bit_offset, 16);

	/* a long item is skipped: 0xfe, 2 data bytes, tag, data */
	uint8_t b[HID_DESC_MAX_BYTES] = { 0xfe, 0x02, 0x10, 0xaa, 0xbb };
	size_t bn;
	const uint8_t *mouse = hid_desc_boot_bytes(HID_BOOT_MOUSE, &bn);
	memcpy(b + 5, mouse, bn);
	parse_ok(b, bn + 5, &desc);
	assert_int_equal(desc.reports[0].bytes, 3);
}

static void
test_resolution_multiplier(void **state)
{
	(void)state;
	/*
	 * hid_setup_resolution_multiplier after hid-input set the feature to
	 * its logical maximum: (1 - 0) / (1 - 0) * (pmax - pmin) + pmin = pmax,
	 * applied to the input fields in the multiplier's Logical collection
	 */
	parse_named("hires_wheel", &desc);
	assert_int_equal(desc.nmultipliers, 2);
	assert_int_equal(desc.multipliers[0].effective, 8);
	assert_int_equal(desc.multipliers[1].effective, 4);
	assert_int_equal(desc.multipliers[1].bit_offset, 8);
	int seen = 0;
	for (unsigned i = 0; i < desc.nfields; i++) {
		const struct hid_desc_field *f = &desc.fields[i];
		uint32_t u = hid_desc_usage(&desc, f, 0);
		if (u == HID_USAGE_GD_WHEEL) {
			assert_int_equal(f->resolution_multiplier, 8);
			seen++;
		} else if (u == HID_USAGE_CONSUMER_AC_PAN) {
			assert_int_equal(f->resolution_multiplier, 4);
			seen++;
		} else {
			assert_int_equal(f->resolution_multiplier, 1);
		}
	}
	assert_int_equal(seen, 2);
}

static void
test_describe(void **state)
{
	(void)state;
	char *buf = NULL;
	size_t n = 0;
	parse_named("qemu_mouse", &desc);
	FILE *out = open_memstream(&buf, &n);
	hid_desc_describe(&desc, out);
	fclose(out);
	assert_non_null(strstr(buf, "report 0: 4 bytes"));
	assert_non_null(strstr(buf, "0x0001:0x0030 (X)"));
	assert_non_null(strstr(buf, "0x0001:0x0038 (Wheel)"));
	assert_non_null(strstr(buf, "0x0009:0x0001 (Button 1) .. 0x0009:0x0003 (Button 3)"));
	assert_non_null(strstr(buf, "bit 8: 3 x 8 bits, variable relative, logical -127..127"));
	assert_non_null(strstr(buf, "bit 3: 1 x 5 bits, constant"));
	free(buf);
}

/* ---- refusals, each naming its byte ------------------------------------------ */

static void
test_bad_descriptors_refused(void **state)
{
	(void)state;
	refuse(NULL, 0, "byte 0:", "empty");
	static const uint8_t trunc1[] = { 0x05, 0x01, 0x09 };
	refuse(trunc1, sizeof trunc1, "byte 2:", "truncated");
	static const uint8_t trunc4[] = { 0x05, 0x01, 0x27, 0xff, 0xff };
	refuse(trunc4, sizeof trunc4, "byte 2:", "truncated");
	static const uint8_t long_trunc[] = { 0x05, 0x01, 0xfe, 0x05, 0x00, 0x01 };
	refuse(long_trunc, sizeof long_trunc, "byte 2:", "long item truncated");
	static const uint8_t long_head[] = { 0x05, 0x01, 0xfe, 0x05 };
	refuse(long_head, sizeof long_head, "byte 2:", "truncated");
	static const uint8_t pop[] = { 0x05, 0x01, 0xb4 };
	refuse(pop, sizeof pop, "byte 2:", "Pop without Push");
	static const uint8_t push[] = { 0xa4, 0xa4, 0xa4, 0xa4, 0xa4 };
	refuse(push, sizeof push, "byte 4:", "Push nested deeper");
	static const uint8_t end[] = { 0x05, 0x01, 0xc0 };
	refuse(end, sizeof end, "byte 2:", "End Collection without Collection");
	static const uint8_t open[] = { 0x05, 0x01, 0x09, 0x02, 0xa1, 0x01, 0xa1, 0x00, 0xc0 };
	refuse(open, sizeof open, "byte 9:", "1 Collection not closed");
	static const uint8_t size0[] = { 0x05, 0x01, 0x09, 0x30, 0x75, 0x00, 0x95, 0x01,
					 0x81, 0x02 };
	refuse(size0, sizeof size0, "byte 8:", "0-bit values");
	static const uint8_t size33[] = { 0x05, 0x01, 0x09, 0x30, 0x75, 0x21, 0x95, 0x01,
					  0x81, 0x02 };
	refuse(size33, sizeof size33, "byte 8:", "33-bit values");
	static const uint8_t size257[] = { 0x75, 0x00, 0x76, 0x01, 0x01 };
	refuse(size257, sizeof size257, "byte 2:", "Report Size 257");
	static const uint8_t count[] = { 0x75, 0x01, 0x96, 0x01, 0x30 };
	refuse(count, sizeof count, "byte 2:", "Report Count 12289");
	/* 32 bits x 129 = 4128 bits */
	static const uint8_t too_long[] = { 0x05, 0x01, 0x09, 0x30, 0x75, 0x20, 0x95, 0x81,
					    0x81, 0x02 };
	refuse(too_long, sizeof too_long, "byte 8:", "longer than 4096 bits");
	static const uint8_t id0[] = { 0x85, 0x00 };
	refuse(id0, sizeof id0, "byte 0:", "Report ID 0");
	static const uint8_t range[] = { 0x15, 0x05, 0x25, 0x01, 0x75, 0x08, 0x95, 0x01,
					 0x09, 0x30, 0x81, 0x02 };
	refuse(range, sizeof range, "byte 10:", "Logical Maximum 1 below Logical Minimum 5");
	static const uint8_t minmax[] = { 0x05, 0x09, 0x19, 0x05, 0x29, 0x01 };
	refuse(minmax, sizeof minmax, "byte 4:", "Usage Minimum 0x5 above Usage Maximum 0x1");
	static const uint8_t global[] = { 0x05, 0x01, 0xc4 };
	refuse(global, sizeof global, "byte 2:", "unknown global item tag 0xc");
	static const uint8_t big_array[] = { 0x05, 0x07, 0x19, 0x00, 0x29, 0xff, 0x15, 0x00, 0x26,
					     0xff, 0x00, 0x75, 0x08, 0x95, 0x41, 0x81, 0x00 };
	refuse(big_array, sizeof big_array, "byte 15:", "array field of 65 values");
	static const uint8_t delim[] = { 0xa9, 0x01, 0xa9, 0x01 };
	refuse(delim, sizeof delim, "byte 2:", "nested Delimiter");

	/* more fields than the fixed array: 129 one-bit padding fields */
	uint8_t b[HID_DESC_MAX_BYTES];
	size_t n = 0;
	b[n++] = 0x75;
	b[n++] = 0x01;
	b[n++] = 0x95;
	b[n++] = 0x01;
	for (int i = 0; i < HID_DESC_MAX_FIELDS + 1; i++) {
		b[n++] = 0x81;
		b[n++] = 0x01;
	}
	char at[32];
	snprintf(at, sizeof at, "byte %d:", 4 + 2 * HID_DESC_MAX_FIELDS);
	refuse(b, n, at, "more than 128 input fields");

	/* more usage items than runs: 513 Usage items before one Input */
	n = 0;
	b[n++] = 0x05;
	b[n++] = 0x07;
	for (int i = 0; i < HID_DESC_MAX_RUNS + 1; i++) {
		b[n++] = 0x09;
		b[n++] = (uint8_t)(i * 2);
	}
	snprintf(at, sizeof at, "byte %d:", 2 + 2 * HID_DESC_MAX_RUNS);
	refuse(b, n, at, "more than 512 usage items");

	/* too long for the parser */
	memset(b, 0xb4, sizeof b);
	refuse(b, HID_DESC_MAX_BYTES + 1, "byte 4096:", "longer than 4096");
}

/* ---- events: the kernel's hid-input mapping ---------------------------------- */

static void
test_key_codes_against_kernel_table(void **state)
{
	(void)state;
	/* HID Usage Tables 10: a-z are 0x04-0x1d, 1-9 and 0 are 0x1e-0x27 */
	static const uint16_t letters[26] = {
		KEY_A, KEY_B, KEY_C, KEY_D, KEY_E, KEY_F, KEY_G, KEY_H, KEY_I,
		KEY_J, KEY_K, KEY_L, KEY_M, KEY_N, KEY_O, KEY_P, KEY_Q, KEY_R,
		KEY_S, KEY_T, KEY_U, KEY_V, KEY_W, KEY_X, KEY_Y, KEY_Z,
	};
	for (unsigned i = 0; i < 26; i++)
		assert_int_equal(hid_keymap_key(0x04 + i), letters[i]);
	static const uint16_t digits[10] = { KEY_1, KEY_2, KEY_3, KEY_4, KEY_5,
					     KEY_6, KEY_7, KEY_8, KEY_9, KEY_0 };
	for (unsigned i = 0; i < 10; i++)
		assert_int_equal(hid_keymap_key(0x1e + i), digits[i]);
	static const uint16_t fkeys[12] = { KEY_F1, KEY_F2, KEY_F3, KEY_F4,  KEY_F5,  KEY_F6,
					    KEY_F7, KEY_F8, KEY_F9, KEY_F10, KEY_F11, KEY_F12 };
	for (unsigned i = 0; i < 12; i++)
		assert_int_equal(hid_keymap_key(0x3a + i), fkeys[i]);
	/* 0xE0-0xE7: left control, shift, alt, meta, then the right ones */
	static const uint16_t mods[8] = {
		KEY_LEFTCTRL,  KEY_LEFTSHIFT,  KEY_LEFTALT,  KEY_LEFTMETA,
		KEY_RIGHTCTRL, KEY_RIGHTSHIFT, KEY_RIGHTALT, KEY_RIGHTMETA,
	};
	for (unsigned i = 0; i < 8; i++)
		assert_int_equal(hid_keymap_key(0xe0 + i), mods[i]);
	assert_int_equal(hid_keymap_key(0x28), KEY_ENTER);
	assert_int_equal(hid_keymap_key(0x29), KEY_ESC);
	assert_int_equal(hid_keymap_key(0x2a), KEY_BACKSPACE);
	assert_int_equal(hid_keymap_key(0x2b), KEY_TAB);
	assert_int_equal(hid_keymap_key(0x2c), KEY_SPACE);
	assert_int_equal(hid_keymap_key(0x4f), KEY_RIGHT);
	assert_int_equal(hid_keymap_key(0x50), KEY_LEFT);
	assert_int_equal(hid_keymap_key(0x51), KEY_DOWN);
	assert_int_equal(hid_keymap_key(0x52), KEY_UP);
	assert_int_equal(hid_keymap_key(0x4c), KEY_DELETE);
	assert_int_equal(hid_keymap_key(0x64), KEY_102ND);
	assert_int_equal(hid_keymap_key(0x9c), KEY_DELETE);
	assert_int_equal(hid_keymap_key(0xb6), KEY_KPLEFTPAREN);
	/* usages 0-3 are no key; 0xa5 and 0x100 and up are KEY_UNKNOWN */
	for (unsigned i = 0; i < 4; i++)
		assert_int_equal(hid_keymap_key(i), 0);
	assert_int_equal(hid_keymap_key(0xa5), KEY_UNKNOWN);
	assert_int_equal(hid_keymap_key(0x100), KEY_UNKNOWN);
}

static void
test_buttons_and_motion(void **state)
{
	(void)state;
	/* boot mouse: buttons 1-3 are BTN_LEFT, BTN_RIGHT, BTN_MIDDLE */
	assert_int_equal(hid_desc_boot(HID_BOOT_MOUSE, &desc), 0);
	start(&desc);
	uint8_t r[3] = { 0x01, 0x05, 0xfb };
	assert_int_equal(feed(r, 3), 0);
	expect_event(INPUT_BUTTON, BTN_LEFT, 1);
	struct input_event_rec e = next_event();
	assert_int_equal(e.kind, INPUT_MOTION);
	assert_true(e.x == 5 && e.y == -5);
	assert_int_equal(e.t_us, 1000);
	expect_event(INPUT_FRAME, 0, 0);
	expect_empty();
	uint8_t r2[3] = { 0x06, 0, 0 };
	assert_int_equal(feed(r2, 3), 0);
	expect_event(INPUT_BUTTON, BTN_LEFT, 0);
	expect_event(INPUT_BUTTON, BTN_RIGHT, 1);
	expect_event(INPUT_BUTTON, BTN_MIDDLE, 1);
	expect_event(INPUT_FRAME, 0, 0);
	/* the same state again: only the frame end */
	assert_int_equal(feed(r2, 3), 0);
	expect_event(INPUT_FRAME, 0, 0);
	expect_empty();
	/* -128 is outside -127..127: clamped, as hidinput_hid_event does */
	uint8_t r3[3] = { 0x06, 0x80, 0x00 };
	assert_int_equal(feed(r3, 3), 0);
	e = next_event();
	assert_int_equal(e.kind, INPUT_MOTION);
	assert_true(e.x == -127 && e.y == 0);
	expect_event(INPUT_FRAME, 0, 0);
	stop();

	/* mouse12: buttons 4 and 5 are BTN_SIDE, BTN_EXTRA; 12-bit axes */
	parse_named("mouse12", &desc);
	start(&desc);
	uint8_t m[5] = { 0x18, 0x00, 0xf8, 0x7f, 0x00 }; /* X = 0x800 = -2048, Y = 0x7ff */
	assert_int_equal(feed(m, 5), 0);
	expect_event(INPUT_BUTTON, BTN_SIDE, 1);
	expect_event(INPUT_BUTTON, BTN_EXTRA, 1);
	e = next_event();
	assert_int_equal(e.kind, INPUT_MOTION);
	if (e.x != -2048 || e.y != 2047)
		fail_msg("motion %g %g", e.x, e.y);
	expect_event(INPUT_FRAME, 0, 0);
	stop();

	/* report_ids: 16-bit axes, buttons 1-8 from BTN_LEFT up */
	parse_named("report_ids", &desc);
	start(&desc);
	uint8_t q[8] = { 0x01, 0x80, 0x00, 0x80, 0xff, 0x7f, 0x00, 0x00 };
	assert_int_equal(feed(q, 8), 0);
	expect_event(INPUT_BUTTON, BTN_TASK, 1);
	e = next_event();
	assert_int_equal(e.kind, INPUT_MOTION);
	if (e.x != -32768 || e.y != 32767)
		fail_msg("motion %g %g", e.x, e.y);
	expect_event(INPUT_FRAME, 0, 0);
	stop();
}

static void
test_absolute_pointer(void **state)
{
	(void)state;
	parse_named("qemu_tablet", &desc);
	start(&desc);
	uint8_t r[6] = { 0x00, 0xff, 0x7f, 0x00, 0x40, 0x00 }; /* X = 0x7fff, Y = 0x4000 */
	assert_int_equal(feed(r, 6), 0);
	struct input_event_rec e = next_event();
	assert_int_equal(e.kind, INPUT_POINTER);
	assert_int_equal(e.code, INPUT_POINTER_VIEW_NONE);
	assert_true(e.x == 1.0);
	assert_true(e.y == 16384.0 / 32767.0);
	expect_event(INPUT_FRAME, 0, 0);
	/* unchanged: no pointer event */
	assert_int_equal(feed(r, 6), 0);
	expect_event(INPUT_FRAME, 0, 0);
	/* Y alone moves: both coordinates come */
	r[4] = 0;
	assert_int_equal(feed(r, 6), 0);
	e = next_event();
	assert_int_equal(e.kind, INPUT_POINTER);
	assert_true(e.x == 1.0 && e.y == 0.0);
	expect_event(INPUT_FRAME, 0, 0);
	stop();
}

static void
test_wheels(void **state)
{
	(void)state;
	/* no multiplier: one detent is 120 */
	parse_named("qemu_mouse", &desc);
	start(&desc);
	uint8_t r[4] = { 0, 0, 0, 0xfe };
	assert_int_equal(feed(r, 4), 0);
	struct input_event_rec e = next_event();
	assert_int_equal(e.kind, INPUT_WHEEL);
	assert_int_equal(e.code, INPUT_WHEEL_V);
	assert_int_equal(e.value, -2);
	assert_true(e.x == -240);
	assert_int_equal(e.flags & INPUT_F_HIRES, 0);
	expect_event(INPUT_FRAME, 0, 0);
	stop();

	/* AC Pan without a multiplier: the horizontal wheel */
	parse_named("report_ids", &desc);
	start(&desc);
	uint8_t p[8] = { 0x01, 0, 0, 0, 0, 0, 0x00, 0x01 };
	assert_int_equal(feed(p, 8), 0);
	e = next_event();
	assert_int_equal(e.kind, INPUT_WHEEL);
	assert_int_equal(e.code, INPUT_WHEEL_H);
	assert_int_equal(e.value, 1);
	assert_true(e.x == 120);
	stop();

	/*
	 * hires_wheel: multiplier 8 on the wheel, 4 on AC Pan;
	 * hidinput_handle_scroll: hi = v * 120 / m, detents from the remainder
	 */
	parse_named("hires_wheel", &desc);
	start(&desc);
	uint8_t h[7] = { 0, 0, 0, 0, 0, 3, 0 };
	assert_int_equal(feed(h, 7), 0);
	e = next_event();
	assert_int_equal(e.kind, INPUT_WHEEL);
	assert_int_equal(e.code, INPUT_WHEEL_V);
	assert_true(e.x == 45 && e.value == 0 && (e.flags & INPUT_F_HIRES));
	expect_event(INPUT_FRAME, 0, 0);
	h[5] = 5; /* 45 + 75 = 120: one detent */
	assert_int_equal(feed(h, 7), 0);
	e = next_event();
	assert_true(e.x == 75 && e.value == 1);
	expect_event(INPUT_FRAME, 0, 0);
	h[5] = 0;
	h[6] = 0xff; /* AC Pan -1 in quarters: -30 each, a detent every fourth */
	for (int i = 0; i < 4; i++) {
		assert_int_equal(feed(h, 7), 0);
		e = next_event();
		assert_int_equal(e.code, INPUT_WHEEL_H);
		assert_true(e.x == -30);
		assert_int_equal(e.value, i == 3 ? -1 : 0);
		expect_event(INPUT_FRAME, 0, 0);
	}
	stop();
}

static void
test_array_keys_by_difference(void **state)
{
	(void)state;
	assert_int_equal(hid_desc_boot(HID_BOOT_KEYBOARD, &desc), 0);
	start(&desc);
	uint8_t a[8] = { 0, 0, 0x04 };          /* A */
	uint8_t ab[8] = { 0, 0, 0x04, 0x05 };   /* A, B */
	uint8_t b[8] = { 0, 0, 0x05 };          /* B (A released, B moved up a slot) */
	uint8_t none[8] = { 0 };
	uint8_t rollover[8] = { 0x02, 0, 1, 1, 1, 1, 1, 1 }; /* shift + ErrorRollOver */
	assert_int_equal(feed(a, 8), 0);
	expect_event(INPUT_KEY, KEY_A, 1);
	expect_event(INPUT_FRAME, 0, 0);
	assert_int_equal(feed(ab, 8), 0);
	expect_event(INPUT_KEY, KEY_B, 1);
	expect_event(INPUT_FRAME, 0, 0);
	assert_int_equal(feed(b, 8), 0);
	expect_event(INPUT_KEY, KEY_A, 0);
	expect_event(INPUT_FRAME, 0, 0);
	assert_int_equal(feed(none, 8), 0);
	expect_event(INPUT_KEY, KEY_B, 0);
	expect_event(INPUT_FRAME, 0, 0);
	expect_empty();

	/*
	 * ErrorRollOver (hid_input_fetch_field): the key array is ignored and
	 * keeps its keys; the modifier bitmap still counts
	 */
	assert_int_equal(feed(a, 8), 0);
	expect_event(INPUT_KEY, KEY_A, 1);
	expect_event(INPUT_FRAME, 0, 0);
	assert_int_equal(feed(rollover, 8), 0);
	expect_event(INPUT_KEY, KEY_LEFTSHIFT, 1);
	expect_event(INPUT_FRAME, 0, 0);
	expect_empty();
	assert_int_equal(feed(none, 8), 0);
	expect_event(INPUT_KEY, KEY_LEFTSHIFT, 0);
	expect_event(INPUT_KEY, KEY_A, 0);
	expect_event(INPUT_FRAME, 0, 0);
	expect_empty();
	stop();

	/* NKRO bitmap: each bit its key; usage 0x04 is bit 64 + 4 */
	parse_named("nkro_keyboard", &desc);
	start(&desc);
	uint8_t n[25] = { 0 };
	n[8] = 0x10;
	n[8 + 0x28 / 8] |= 1 << (0x28 % 8); /* Enter */
	assert_int_equal(feed(n, 25), 0);
	expect_event(INPUT_KEY, KEY_A, 1);
	expect_event(INPUT_KEY, KEY_ENTER, 1);
	expect_event(INPUT_FRAME, 0, 0);
	n[8] = 0;
	assert_int_equal(feed(n, 25), 0);
	expect_event(INPUT_KEY, KEY_A, 0);
	expect_event(INPUT_FRAME, 0, 0);
	expect_empty();
	stop();

	/*
	 * a key in two fields (2 array slots, then a bitmap of usages 0-15) is
	 * one key to the input core: pressed once, released by the first
	 * field that lets go, and not again by the other
	 */
	static const uint8_t both[] = { 0x05, 0x01, 0x09, 0x06, 0xa1, 0x01, 0x05, 0x07, 0x15, 0x00,
					0x26, 0xff, 0x00, 0x19, 0x00, 0x2a, 0xff, 0x00, 0x75, 0x08,
					0x95, 0x02, 0x81, 0x00, 0x19, 0x00, 0x29, 0x0f, 0x25, 0x01,
					0x75, 0x01, 0x95, 0x10, 0x81, 0x02, 0xc0 };
	parse_ok(both, sizeof both, &desc);
	start(&desc);
	uint8_t twice[4] = { 0x04, 0x00, 0x10, 0x00 };
	assert_int_equal(feed(twice, 4), 0);
	expect_event(INPUT_KEY, KEY_A, 1);
	expect_event(INPUT_FRAME, 0, 0);
	twice[0] = 0;
	assert_int_equal(feed(twice, 4), 0);
	expect_event(INPUT_KEY, KEY_A, 0);
	expect_event(INPUT_FRAME, 0, 0);
	twice[2] = 0;
	assert_int_equal(feed(twice, 4), 0);
	expect_event(INPUT_FRAME, 0, 0);
	expect_empty();
	stop();
}

static void
test_bad_reports_dropped(void **state)
{
	(void)state;
	parse_named("report_ids", &desc);
	start(&desc);
	uint8_t r[16] = { 0x01, 0x01 };
	/* short, long, unknown id, empty: counted, nothing queued */
	assert_int_equal(feed(r, 7), -1);
	assert_int_equal(feed(r, 9), -1);
	r[0] = 3;
	assert_int_equal(feed(r, 8), -1);
	r[0] = 0;
	assert_int_equal(feed(r, 8), -1);
	assert_int_equal(feed(r, 0), -1);
	assert_int_equal(hin.short_reports, 1);
	assert_int_equal(hin.long_reports, 1);
	assert_int_equal(hin.unknown_reports, 3);
	assert_int_equal(hin.reports, 0);
	assert_int_equal(queue.len, 0);
	/* nothing else changed: button 1 still presses on the next good report */
	r[0] = 0x01;
	assert_int_equal(feed(r, 8), 0);
	expect_event(INPUT_BUTTON, BTN_LEFT, 1);
	expect_event(INPUT_FRAME, 0, 0);

	/* the log blames the device */
	char line[256] = "";
	rewind(hin.log.out);
	assert_non_null(fgets(line, sizeof line, hin.log.out));
	assert_non_null(strstr(line, "test device: device fault: report 1 short: 7 bytes, "
				     "expected 8"));
	assert_non_null(fgets(line, sizeof line, hin.log.out));
	assert_non_null(strstr(line, "report 1 long: 9 bytes"));
	assert_non_null(fgets(line, sizeof line, hin.log.out));
	assert_non_null(strstr(line, "report 3 not in the descriptor"));
	stop();

	/* unnumbered reports: the length alone */
	assert_int_equal(hid_desc_boot(HID_BOOT_MOUSE, &desc), 0);
	start(&desc);
	assert_int_equal(feed(r, 2), -1);
	assert_int_equal(feed(r, 4), -1);
	assert_int_equal(hin.short_reports, 1);
	assert_int_equal(hin.long_reports, 1);
	assert_int_equal(queue.len, 0);
	stop();
}

static void
test_release_all(void **state)
{
	(void)state;
	parse_named("report_ids", &desc);
	start(&desc);
	uint8_t m[8] = { 0x01, 0x01 };
	uint8_t k[9] = { 0x02, 0x01, 0x00, 0x04 };
	assert_int_equal(feed(m, 8), 0);
	assert_int_equal(feed(k, 9), 0);
	input_queue_init(&queue);
	hid_input_release_all(&hin, 2000, &queue);
	/* in code order: KEY_LEFTCTRL (29), KEY_A (30), then BTN_LEFT */
	expect_event(INPUT_KEY, KEY_LEFTCTRL, 0);
	expect_event(INPUT_KEY, KEY_A, 0);
	expect_event(INPUT_BUTTON, BTN_LEFT, 0);
	expect_event(INPUT_FRAME, 0, 0);
	expect_empty();
	/* nothing held: nothing to say */
	hid_input_release_all(&hin, 3000, &queue);
	expect_empty();
	/* afresh: the same report presses again */
	assert_int_equal(feed(k, 9), 0);
	expect_event(INPUT_KEY, KEY_LEFTCTRL, 1);
	expect_event(INPUT_KEY, KEY_A, 1);
	stop();
}

static void
test_no_allocation_per_report(void **state)
{
	(void)state;
	static struct hid_desc kbd;
	static struct hid_input kin;
	assert_int_equal(hid_desc_boot(HID_BOOT_MOUSE, &desc), 0);
	assert_int_equal(hid_desc_boot(HID_BOOT_KEYBOARD, &kbd), 0);
	start(&desc);
	hid_input_init(&kin, &kbd, 8, "kbd");
	uint8_t m[3] = { 0x01, 0x03, 0xfd };
	uint8_t k[8] = { 0x02, 0, 0x04, 0x05 };
#if COUNT_ALLOCS
	long before = allocs;
#endif
	for (int i = 0; i < 10000; i++) {
		m[0] = (uint8_t)(i & 7);
		k[2] = (uint8_t)(4 + i % 20);
		hid_input_feed(&hin, m, 3, (uint64_t)i, &queue);
		hid_input_feed(&kin, k, 8, (uint64_t)i, &queue);
		struct input_event_rec e;
		while (input_queue_pop(&queue, &e))
			;
	}
#if COUNT_ALLOCS
	assert_int_equal(allocs - before, 0);
#endif
	assert_int_equal(hin.reports, 10000);
	assert_int_equal(kin.reports, 10000);
	stop();
}

/* ---- recordings --------------------------------------------------------------- */

static void
assert_same_recording(const struct rec_hid *a, const struct rec_hid *b)
{
	assert_int_equal(a->ndevices, b->ndevices);
	for (unsigned i = 0; i < a->ndevices; i++) {
		const struct rec_hid_device *x = &a->devices[i], *y = &b->devices[i];
		assert_string_equal(x->name, y->name);
		assert_string_equal(x->phys, y->phys);
		assert_int_equal(x->bus, y->bus);
		assert_int_equal(x->vid, y->vid);
		assert_int_equal(x->pid, y->pid);
		assert_int_equal(x->desc_len, y->desc_len);
		assert_memory_equal(x->desc, y->desc, x->desc_len);
	}
	assert_int_equal(a->nevents, b->nevents);
	for (size_t i = 0; i < a->nevents; i++) {
		assert_int_equal(a->events[i].t_us, b->events[i].t_us);
		assert_int_equal(a->events[i].device, b->events[i].device);
		assert_int_equal(a->events[i].len, b->events[i].len);
		assert_memory_equal(a->events[i].bytes, b->events[i].bytes, a->events[i].len);
	}
}

static void
round_trip(const struct rec_hid *r)
{
	char *buf = NULL;
	size_t n = 0;
	char err[256];
	struct rec_hid again;
	FILE *out = open_memstream(&buf, &n);
	assert_int_equal(rec_hid_write(out, r), 0);
	fclose(out);
	if (rec_hid_parse(buf, n, "written", &again, err, sizeof err) != 0)
		fail_msg("%s\n%s", err, buf);
	assert_same_recording(r, &again);
	rec_hid_free(&again);
	free(buf);
}

static void
test_recording_written_by_hidtools(void **state)
{
	(void)state;
	static struct rec_hid r;
	char err[256];
	uint8_t mouse[HID_DESC_MAX_BYTES], kbd[HID_DESC_MAX_BYTES];
	size_t mn = load_rdesc("qemu_mouse", mouse), kn = load_rdesc("qemu_keyboard", kbd);

	/* what make_expect.py asked hid-tools' HidrawDevice.dump() to write */
	if (rec_hid_read(DATA "hidtools_mouse.hid", &r, err, sizeof err) != 0)
		fail_msg("%s", err);
	assert_int_equal(r.ndevices, 1);
	assert_string_equal(r.devices[0].name, "QEMU QEMU USB Mouse");
	assert_string_equal(r.devices[0].phys, "");
	assert_int_equal(r.devices[0].bus, 3);
	assert_int_equal(r.devices[0].vid, 0x0627);
	assert_int_equal(r.devices[0].pid, 0x0001);
	assert_int_equal(r.devices[0].desc_len, mn);
	assert_memory_equal(r.devices[0].desc, mouse, mn);
	assert_int_equal(r.nevents, 3);
	static const uint8_t e0[4] = { 0x00, 0x01, 0xff, 0x00 }, e2[4] = { 0, 0, 0, 1 };
	assert_int_equal(r.events[0].t_us, 0);
	assert_memory_equal(r.events[0].bytes, e0, 4);
	assert_int_equal(r.events[1].t_us, 120004);
	assert_int_equal(r.events[2].t_us, 1000005);
	assert_memory_equal(r.events[2].bytes, e2, 4);
	round_trip(&r);

	/* and the recording decodes: X 1, Y -1, then the left button, then the wheel */
	parse_ok(r.devices[0].desc, r.devices[0].desc_len, &desc);
	start(&desc);
	for (size_t i = 0; i < r.nevents; i++)
		assert_int_equal(hid_input_feed(&hin, r.events[i].bytes, r.events[i].len,
						r.events[i].t_us, &queue),
				 0);
	struct input_event_rec e = next_event();
	assert_int_equal(e.kind, INPUT_MOTION);
	assert_true(e.x == 1 && e.y == -1);
	expect_event(INPUT_FRAME, 0, 0);
	expect_event(INPUT_BUTTON, BTN_LEFT, 1);
	e = next_event();
	assert_int_equal(e.t_us, 120004);
	stop();
	rec_hid_free(&r);

	/* two devices, with hid-recorder's D: lines */
	if (rec_hid_read(DATA "hidtools_two.hid", &r, err, sizeof err) != 0)
		fail_msg("%s", err);
	assert_int_equal(r.ndevices, 2);
	assert_string_equal(r.devices[1].name, "QEMU QEMU USB Keyboard");
	assert_int_equal(r.devices[1].desc_len, kn);
	assert_memory_equal(r.devices[1].desc, kbd, kn);
	assert_int_equal(r.nevents, 4);
	static const unsigned dev[4] = { 0, 1, 0, 1 };
	static const uint64_t t[4] = { 0, 50000, 120004, 200000 };
	for (int i = 0; i < 4; i++) {
		assert_int_equal(r.events[i].device, dev[i]);
		assert_int_equal(r.events[i].t_us, t[i]);
		assert_int_equal(r.events[i].len, dev[i] ? 8 : 4);
	}
	round_trip(&r);
	rec_hid_free(&r);
}

static void
test_recording_rebased_and_lenient(void **state)
{
	(void)state;
	static struct rec_hid r;
	char err[256];
	/* comments, blank and unknown lines, CRLF, zero-padded seconds, P: */
	static const char text[] = "# a comment\r\n"
				   "\n"
				   "R: 3 05 01 c0\r\n"
				   "N: a  name with  spaces  \n"
				   "P: usb-1/input0\n"
				   "I: 5 46d c52b\n"
				   "X: something we do not know\n"
				   "E: 000012.500000 2 aa bb\n"
				   "  E: 12.750001 1 0c\n"
				   "E: 13.500000 1 0d\n";
	assert_int_equal(rec_hid_parse(text, sizeof text - 1, "t.hid", &r, err, sizeof err), 0);
	assert_string_equal(r.devices[0].name, "a  name with  spaces");
	assert_string_equal(r.devices[0].phys, "usb-1/input0");
	assert_int_equal(r.devices[0].bus, 5);
	assert_int_equal(r.devices[0].vid, 0x046d);
	assert_int_equal(r.devices[0].pid, 0xc52b);
	assert_int_equal(r.nevents, 3);
	assert_int_equal(r.events[0].t_us, 0);
	assert_int_equal(r.events[1].t_us, 250001);
	assert_int_equal(r.events[2].t_us, 1000000);
	round_trip(&r);
	rec_hid_free(&r);
}

static void
refuse_recording(const char *text, const char *want)
{
	static struct rec_hid r;
	char err[256];
	assert_int_equal(rec_hid_parse(text, strlen(text), "bad.hid", &r, err, sizeof err), -1);
	if (strncmp(err, want, strlen(want)) != 0)
		fail_msg("got \"%s\", want \"%s...\"", err, want);
	assert_int_equal(r.nevents, 0);
	assert_int_equal(r.ndevices, 0);
	assert_null(r.events);
}

static void
test_bad_recordings_refused(void **state)
{
	(void)state;
	refuse_recording("R: 2 05 01\nE: 0.12 1 00\n", "bad.hid:2: E: the time needs exactly six");
	refuse_recording("R: 2 05 01\nE: 0.1200000 1 00\n", "bad.hid:2: E: the time needs");
	refuse_recording("R: 3 05 01\n", "bad.hid:1: R: length 3 but 2 bytes follow");
	refuse_recording("R: 1 05 01\n", "bad.hid:1: R: length 1 but 2 bytes follow");
	refuse_recording("R: 2 05 01\nE: 0.000000 2 00\n", "bad.hid:2: E: length 2 but 1");
	refuse_recording("R: 2 05 01\nE: 0.000000 1 0g\n", "bad.hid:2: E: byte 1 is not");
	refuse_recording("R: 2 05 01\nE: 0.000000 1 100\n", "bad.hid:2: E: byte 1 is not");
	refuse_recording("R: 2 05 01\nD: 1\nE: 0.000000 1 00\n",
			 "bad.hid:3: E: a report of device 1 before its R: line");
	refuse_recording("R: 2 05 01\nE: 1.000000 1 00\nE: 0.999999 1 00\n",
			 "bad.hid:3: E: time 0.999999 before");
	refuse_recording("R: 2 05 01\nD: 8\n", "bad.hid:2: D: device 8 outside 0-7");
	refuse_recording("R: 2 05 01\nI: 3 10000 1\n", "bad.hid:2: I: vendor 0x10000 over");
	refuse_recording("R: 2 05 01\nR: 2 05 01\n", "bad.hid:2: R: a second descriptor");
	refuse_recording("N: no descriptor\n", "bad.hid:1: device 0 has no R: line");
	refuse_recording("R: 2 05 01\nD: 1\nN: second\n", "bad.hid:2: device 1 has no R: line");
	refuse_recording("", "bad.hid:1: no R: line");
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_values_match_hidtools),
		cmocka_unit_test(test_two_usage_ranges_accumulate),
		cmocka_unit_test(test_logical_maximum_signedness),
		cmocka_unit_test(test_boot_descriptors),
		cmocka_unit_test(test_report_ids_and_offsets),
		cmocka_unit_test(test_usage_page_rules),
		cmocka_unit_test(test_resolution_multiplier),
		cmocka_unit_test(test_describe),
		cmocka_unit_test(test_bad_descriptors_refused),
		cmocka_unit_test(test_key_codes_against_kernel_table),
		cmocka_unit_test(test_buttons_and_motion),
		cmocka_unit_test(test_absolute_pointer),
		cmocka_unit_test(test_wheels),
		cmocka_unit_test(test_array_keys_by_difference),
		cmocka_unit_test(test_bad_reports_dropped),
		cmocka_unit_test(test_release_all),
		cmocka_unit_test(test_no_allocation_per_report),
		cmocka_unit_test(test_recording_written_by_hidtools),
		cmocka_unit_test(test_recording_rebased_and_lenient),
		cmocka_unit_test(test_bad_recordings_refused),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
