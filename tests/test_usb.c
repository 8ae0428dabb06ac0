/*
 * test_usb.c - the USB backend's transfer seam (devices/usb_intr.h) driven
 * with recorded reports and transfer endings, no USB device needed: what
 * the reports mean is checked against hid-tools' decoding (the .expect
 * files tests/input/hid/make_expect.py writes) and the codes against
 * linux/input-event-codes.h; the boot report layout against HID 1.11
 * Appendix B. Also the spec's syntax, the backend's answer when the device
 * is not there, the Resolution Multiplier lengths the backend writes, and
 * the device set opening its specs again after a backend noted an arrival.
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
#include "devices/input_devs.h"
#include "devices/queue.h"
#include "devices/rec_hid.h"
#include "devices/usb_dev.h"
#include "devices/usb_intr.h"

#include "alloc_count.h"

#define DATA "tests/input/hid/"
#define DEV 3

static struct input_queue queue;
static struct usb_intr intr;
static struct hid_desc desc;

/* ---- helpers ------------------------------------------------------------- */

static size_t
hex_bytes(const char *s, uint8_t *dest, size_t max)
{
	size_t n = 0;
	for (;;) {
		while (*s == ' ' || *s == '\t')
			s++;
		char *end;
		unsigned long v = strtoul(s, &end, 16);
		if (end == s || n == max)
			return n;
		dest[n++] = (uint8_t)v;
		s = end;
	}
}

static void
load_desc(const char *name, struct hid_desc *d)
{
	char path[256], line[512], err[256];
	uint8_t b[HID_DESC_MAX_BYTES];
	size_t n = 0;
	snprintf(path, sizeof path, DATA "%s.rdesc", name);
	FILE *f = fopen(path, "r");
	if (!f)
		fail_msg("cannot open %s", path);
	while (fgets(line, sizeof line, f)) {
		char *hash = strchr(line, '#');
		if (hash)
			*hash = '\0';
		n += hex_bytes(line, b + n, sizeof b - n);
	}
	fclose(f);
	if (hid_desc_parse(b, n, d, err, sizeof err) < 0)
		fail_msg("%s: %s", path, err);
}

static enum usb_intr_next
complete(enum usb_intr_status st, const uint8_t *b, size_t n)
{
	return usb_intr_complete(&intr, st, b, n, 1000, &queue);
}

static void
expect_event(enum input_kind kind, unsigned code, int value)
{
	expect_event_in(&queue, DEV, kind, code, value);
}

static void
expect_motion(double x, double y)
{
	struct input_event_rec e;
	assert_int_equal(input_queue_pop(&queue, &e), 1);
	if (e.kind != INPUT_MOTION)
		fail_msg("got %s; want motion %g %g", input_kind_to_str((enum input_kind)e.kind), x,
			 y);
	assert_true(e.x == x && e.y == y);
}

static void
expect_empty(void)
{
	struct input_event_rec e;
	if (input_queue_pop(&queue, &e))
		fail_msg("unexpected %s code %u value %d",
			 input_kind_to_str((enum input_kind)e.kind), e.code, e.value);
}

static void
setup_mouse_report_protocol(void)
{
	input_queue_init(&queue);
	load_desc("qemu_mouse", &desc);
	usb_intr_init(&intr, &desc, 0, INPUT_CLASS_MOUSE, DEV, "test mouse");
}

static void
setup_boot(enum hid_boot kind)
{
	input_queue_init(&queue);
	assert_int_equal(hid_desc_boot(kind, &desc), 0);
	usb_intr_init(&intr, &desc, kind == HID_BOOT_MOUSE ? 3 : 8,
		      kind == HID_BOOT_MOUSE ? INPUT_CLASS_MOUSE : INPUT_CLASS_KEYBOARD, DEV,
		      "test boot");
}

/* ---- recorded reports ----------------------------------------------------- */

/*
 * Every report of qemu_mouse.expect as a completed transfer: the events
 * must say what hid-tools decoded (button n held: BTN_LEFT + n - 1 by the
 * kernel's mouse mapping; X and Y: one motion; Wheel: detents).
 */
static void
test_expect_file_mouse(void **state)
{
	(void)state;
	setup_mouse_report_protocol();
	FILE *f = fopen(DATA "qemu_mouse.expect", "r");
	assert_non_null(f);
	char line[512];
	uint8_t report[64];
	size_t n = 0;
	int reports = 0, held[3] = { 0, 0, 0 };
	int want_btn[3], x = 0, y = 0, wheel = 0, pending = 0;

	for (;;) {
		char *got = fgets(line, sizeof line, f);
		int is_e = got && !strncmp(line, "E: ", 3);
		if (pending && (!got || is_e)) {
			assert_int_equal(complete(USB_INTR_COMPLETED, report, n), USB_INTR_RESUBMIT);
			/* buttons first, as they change, in field order; then motion, wheel, the end */
			for (int b = 0; b < 3; b++)
				if (want_btn[b] != held[b]) {
					expect_event(INPUT_BUTTON, BTN_LEFT + b, want_btn[b]);
					held[b] = want_btn[b];
				}
			if (x || y)
				expect_motion(x, y);
			if (wheel)
				expect_event(INPUT_WHEEL, INPUT_WHEEL_V, wheel);
			expect_event(INPUT_FRAME, 0, 0);
			expect_empty();
			reports++;
			pending = 0;
		}
		if (!got)
			break;
		if (is_e) {
			n = hex_bytes(line + 3, report, sizeof report);
			memset(want_btn, 0, sizeof want_btn);
			x = y = wheel = 0;
			pending = 1;
		} else if (!strncmp(line, "V: ", 3)) {
			unsigned bit, size, usage;
			int value;
			assert_int_equal(sscanf(line + 3, "%u %u %x %d", &bit, &size, &usage, &value),
					 4);
			if (usage >= 0x00090001 && usage <= 0x00090003)
				want_btn[usage - 0x00090001] = value != 0;
			else if (usage == 0x00010030)
				x = value;
			else if (usage == 0x00010031)
				y = value;
			else if (usage == 0x00010038)
				wheel = value;
			else
				fail_msg("unexpected usage %x", usage);
		}
	}
	fclose(f);
	assert_true(reports >= 20);
	assert_int_equal(intr.transfers, (uint64_t)reports);
	assert_int_equal(intr.gone, 0);
}

/* a hid-recorder file (hid-tools wrote it) through the seam, as its bytes say (HID 1.11 B.2 + wheel) */
static void
test_hid_recording(void **state)
{
	(void)state;
	struct rec_hid r;
	char err[256];
	if (rec_hid_read(DATA "hidtools_mouse.hid", &r, err, sizeof err) != 0)
		fail_msg("%s", err);
	char perr[256];
	input_queue_init(&queue);
	assert_int_equal(hid_desc_parse(r.devices[0].desc, r.devices[0].desc_len, &desc, perr,
					sizeof perr),
			 0);
	usb_intr_init(&intr, &desc, 0, INPUT_CLASS_MOUSE, DEV, "recorded mouse");
	assert_int_equal(r.nevents, 3);
	for (size_t k = 0; k < r.nevents; k++)
		assert_int_equal(complete(USB_INTR_COMPLETED, r.events[k].bytes, r.events[k].len),
				 USB_INTR_RESUBMIT);
	/* 00 01 ff 00: X +1, Y -1 */
	expect_motion(1, -1);
	expect_event(INPUT_FRAME, 0, 0);
	/* 01 00 00 00: button 1 */
	expect_event(INPUT_BUTTON, BTN_LEFT, 1);
	expect_event(INPUT_FRAME, 0, 0);
	/* 00 00 00 01: button 1 up, wheel +1 */
	expect_event(INPUT_BUTTON, BTN_LEFT, 0);
	expect_event(INPUT_WHEEL, INPUT_WHEEL_V, 1);
	expect_event(INPUT_FRAME, 0, 0);
	expect_empty();
	rec_hid_free(&r);
}

/* ---- transfer endings ----------------------------------------------------- */

/* NO_DEVICE mid-press: nothing more submitted; read releases the button and removes */
static void
test_no_device_mid_press(void **state)
{
	(void)state;
	setup_mouse_report_protocol();
	static const uint8_t press[4] = { 0x05, 0x00, 0x00, 0x00 }; /* buttons 1 and 3 */
	assert_int_equal(complete(USB_INTR_COMPLETED, press, 4), USB_INTR_RESUBMIT);
	expect_event(INPUT_BUTTON, BTN_LEFT, 1);
	expect_event(INPUT_BUTTON, BTN_MIDDLE, 1);
	expect_event(INPUT_FRAME, 0, 0);
	assert_int_equal(usb_intr_reap(&intr, 2000, &queue), 0);
	expect_empty();

	assert_int_equal(complete(USB_INTR_NO_DEVICE, NULL, 0), USB_INTR_STOP);
	assert_int_equal(intr.gone, 1);
	expect_empty(); /* the callback only notes it */
	assert_int_equal(usb_intr_reap(&intr, 2000, &queue), -1);
	expect_event(INPUT_BUTTON, BTN_LEFT, 0);
	expect_event(INPUT_BUTTON, BTN_MIDDLE, 0);
	expect_event(INPUT_FRAME, 0, 0);
	struct input_event_rec e;
	assert_int_equal(input_queue_pop(&queue, &e), 1);
	assert_int_equal(e.kind, INPUT_REMOVED);
	assert_int_equal(e.code, INPUT_CLASS_MOUSE);
	assert_int_equal(e.device, DEV);
	assert_int_equal(e.t_us, 2000);
	expect_empty();
	/* said once; a late transfer changes nothing */
	assert_int_equal(usb_intr_reap(&intr, 3000, &queue), -1);
	assert_int_equal(complete(USB_INTR_COMPLETED, press, 4), USB_INTR_STOP);
	expect_empty();
}

/* the boot keyboard: keys from Appendix B's layout; gone mid-press releases them */
static void
test_boot_keyboard_gone(void **state)
{
	(void)state;
	setup_boot(HID_BOOT_KEYBOARD);
	/* modifiers (bit 1: left shift), reserved, key 0x04 (a) */
	static const uint8_t shift_a[8] = { 0x02, 0, 0x04, 0, 0, 0, 0, 0 };
	assert_int_equal(complete(USB_INTR_COMPLETED, shift_a, 8), USB_INTR_RESUBMIT);
	expect_event(INPUT_KEY, KEY_LEFTSHIFT, 1);
	expect_event(INPUT_KEY, KEY_A, 1);
	expect_event(INPUT_FRAME, 0, 0);
	expect_empty();
	/* a submit refused because the device went: the same as NO_DEVICE */
	usb_intr_lost(&intr, "No such device", 1, 1500);
	assert_int_equal(usb_intr_reap(&intr, 1500, &queue), -1);
	struct input_event_rec e;
	int released = 0; /* in any order */
	for (int k = 0; k < 2; k++) {
		assert_int_equal(input_queue_pop(&queue, &e), 1);
		assert_int_equal(e.kind, INPUT_KEY);
		assert_int_equal(e.value, 0);
		released |= e.code == KEY_LEFTSHIFT ? 1 : e.code == KEY_A ? 2 : 4;
	}
	assert_int_equal(released, 3);
	expect_event(INPUT_FRAME, 0, 0);
	assert_int_equal(input_queue_pop(&queue, &e), 1);
	assert_int_equal(e.kind, INPUT_REMOVED);
	assert_int_equal(e.code, INPUT_CLASS_KEYBOARD);
	expect_empty();
}

/* boot protocol: bytes after the boot report are the vendor's, cut off; a short one is dropped */
static void
test_boot_mouse_cut_and_short(void **state)
{
	(void)state;
	setup_boot(HID_BOOT_MOUSE);
	static const uint8_t four[4] = { 0x01, 0x05, 0xfb, 0x01 }; /* wheel byte: vendor data here */
	assert_int_equal(complete(USB_INTR_COMPLETED, four, 4), USB_INTR_RESUBMIT);
	expect_event(INPUT_BUTTON, BTN_LEFT, 1);
	expect_motion(5, -5);
	expect_event(INPUT_FRAME, 0, 0);
	expect_empty();
	assert_int_equal(intr.cut, 1);
	static const uint8_t two[2] = { 0x00, 0x01 };
	assert_int_equal(complete(USB_INTR_COMPLETED, two, 2), USB_INTR_RESUBMIT);
	expect_empty();
	assert_int_equal(intr.in.short_reports, 1);
	assert_int_equal(intr.in.held[BTN_LEFT] != 0, 1); /* nothing else changed */
}

/* a short transfer in report protocol: dropped, counted, resubmitted; a zero-length one too */
static void
test_short_transfer(void **state)
{
	(void)state;
	setup_mouse_report_protocol();
	static const uint8_t three[3] = { 0x01, 0x05, 0x05 };
	assert_int_equal(complete(USB_INTR_COMPLETED, three, 3), USB_INTR_RESUBMIT);
	expect_empty();
	assert_int_equal(intr.in.short_reports, 1);
	assert_int_equal(complete(USB_INTR_COMPLETED, three, 0), USB_INTR_RESUBMIT);
	expect_empty();
	static const uint8_t five[5] = { 0x01, 0, 0, 0, 0 };
	assert_int_equal(complete(USB_INTR_COMPLETED, five, 5), USB_INTR_RESUBMIT);
	expect_empty();
	assert_int_equal(intr.in.long_reports, 1);
	assert_int_equal(usb_intr_reap(&intr, 1000, &queue), 0);
}

/* STALL: clear the halt; a report resets the count; a run of them gives the device up */
static void
test_stall(void **state)
{
	(void)state;
	setup_mouse_report_protocol();
	static const uint8_t press[4] = { 0x02, 0, 0, 0 };
	assert_int_equal(complete(USB_INTR_STALL, NULL, 0), USB_INTR_CLEAR_HALT);
	expect_empty();
	assert_int_equal(complete(USB_INTR_COMPLETED, press, 4), USB_INTR_RESUBMIT);
	expect_event(INPUT_BUTTON, BTN_RIGHT, 1);
	expect_event(INPUT_FRAME, 0, 0);
	for (int k = 1; k < USB_INTR_FAULTS_MAX; k++)
		assert_int_equal(complete(USB_INTR_STALL, NULL, 0), USB_INTR_CLEAR_HALT);
	assert_int_equal(usb_intr_reap(&intr, 1000, &queue), 0);
	assert_int_equal(complete(USB_INTR_STALL, NULL, 0), USB_INTR_STOP);
	assert_int_equal(intr.stalls, USB_INTR_FAULTS_MAX + 1);
	assert_int_equal(usb_intr_reap(&intr, 1000, &queue), -1);
	expect_event(INPUT_BUTTON, BTN_RIGHT, 0);
	expect_event(INPUT_FRAME, 0, 0);
	struct input_event_rec e;
	assert_int_equal(input_queue_pop(&queue, &e), 1);
	assert_int_equal(e.kind, INPUT_REMOVED);
	expect_empty();
}

/* errors, overflows and timeouts: resubmitted, nothing decoded; cancelled: stopped, not gone */
static void
test_other_endings(void **state)
{
	(void)state;
	setup_mouse_report_protocol();
	static const uint8_t junk[4] = { 0x07, 0x10, 0x10, 0x10 };
	assert_int_equal(complete(USB_INTR_ERROR, junk, 4), USB_INTR_RESUBMIT);
	assert_int_equal(complete(USB_INTR_OVERFLOW, junk, 4), USB_INTR_RESUBMIT);
	assert_int_equal(complete(USB_INTR_TIMED_OUT, junk, 0), USB_INTR_RESUBMIT);
	expect_empty();
	assert_int_equal(intr.errors, 1);
	assert_int_equal(intr.overflows, 1);
	assert_int_equal(intr.timeouts, 1);
	assert_int_equal(complete(USB_INTR_CANCELLED, NULL, 0), USB_INTR_STOP);
	assert_int_equal(intr.gone, 0);
	assert_int_equal(usb_intr_reap(&intr, 1000, &queue), 0);
	expect_empty();
}

/* a report per transfer allocates nothing */
static void
test_no_allocation_per_transfer(void **state)
{
	(void)state;
	setup_mouse_report_protocol();
#if COUNT_ALLOCS
	long before = allocs;
	static const uint8_t r[4] = { 0x01, 0x02, 0x03, 0x01 };
	for (int k = 0; k < 1000; k++) {
		complete(k % 7 ? USB_INTR_COMPLETED : USB_INTR_STALL, r, 4);
		struct input_event_rec e;
		while (input_queue_pop(&queue, &e))
			;
	}
	assert_int_equal(allocs, before);
#else
	skip();
#endif
}

/* ---- the spec, the backend without a device, the multipliers -------------- */

static void
test_spec(void **state)
{
	(void)state;
	uint16_t v, p;
	int i;
	char err[200];
	assert_int_equal(usb_dev_parse_spec("1d6b:0104", &v, &p, &i, err, sizeof err), 0);
	assert_int_equal(v, 0x1d6b);
	assert_int_equal(p, 0x0104);
	assert_int_equal(i, -1);
	assert_int_equal(usb_dev_parse_spec("46D:C077:1", &v, &p, &i, err, sizeof err), 0);
	assert_int_equal(v, 0x046d);
	assert_int_equal(p, 0xc077);
	assert_int_equal(i, 1);
	static const char *const bad[] = { "", "1d6b", "1d6b:", "1d6b:0104:", "1d6b:0104:100",
					   "1d6b0:0104", "xyz:0104", "1d6b:0104:1:2", ":0104" };
	for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
		err[0] = '\0';
		if (usb_dev_parse_spec(bad[k], &v, &p, &i, err, sizeof err) != -1)
			fail_msg("'%s' taken", bad[k]);
		assert_non_null(strstr(err, "usb:VID:PID[:IFACE]"));
	}
}

/* no such device here (this machine has no USB): skipped with its reason, nothing open */
static void
test_open_absent_device(void **state)
{
	(void)state;
	static struct input_devs set;
	static const struct input_backend *const backends[] = { &input_backend_usb };
	char err[256];
	input_queue_init(&queue);
	input_devs_init(&set, backends, 1, 0, &queue);
	assert_int_equal(input_devs_open(&set, "usb:1d6b:0104", 0, err, sizeof err), 0);
	assert_int_equal(input_devs_count(&set), 0);
	assert_int_equal(set.nskip, 1);
	assert_string_equal(set.skip[0].what, "usb:1d6b:0104");
	if (!strstr(set.skip[0].why, "no USB device 1d6b:0104") &&
	    !strstr(set.skip[0].why, "libusb cannot start"))
		fail_msg("why: %s", set.skip[0].why);
	assert_int_equal(input_devs_open(&set, "usb:1d6b", 0, err, sizeof err), -1);
	assert_non_null(strstr(err, "usb:VID:PID[:IFACE]"));
	/* the shared fds are the context's own (its event and timer fds), polled for reading */
	struct pollfd fds[INPUT_DEVS_POLL_MAX];
	int tags[INPUT_DEVS_POLL_MAX];
	int n = input_devs_pollfds(&set, fds, tags, INPUT_DEVS_POLL_MAX);
	for (int k = 0; k < n; k++) {
		assert_int_equal(tags[k], INPUT_DEVS_MAX + 0);
		assert_true(fds[k].events & POLLIN);
	}
	/* work with nothing pending: no events, nothing opened */
	if (n)
		assert_int_equal(input_devs_ready(&set, tags[0], 5, &queue), 0);
	expect_empty();
	assert_int_equal(usb_dev_exit(), 0);
}

/*
 * hires_wheel.rdesc: two Resolution Multipliers (2 bits, then 6 bits of
 * padding each) in one feature report without an id: 16 bits to write.
 * A device refusing them: the wheels go back to whole detents.
 */
static void
test_multiplier_feature_length(void **state)
{
	(void)state;
	load_desc("hires_wheel", &desc);
	assert_int_equal(desc.nmultipliers, 2);
	for (unsigned m = 0; m < 2; m++) {
		assert_int_equal(desc.multipliers[m].report_id, 0);
		assert_int_equal(desc.multipliers[m].report_bits, 16);
	}
	assert_int_equal(desc.multipliers[0].bit_offset, 0);
	assert_int_equal(desc.multipliers[1].bit_offset, 8);
	int hires = 0;
	for (unsigned f = 0; f < desc.nfields; f++)
		hires += desc.fields[f].resolution_multiplier != 1;
	assert_int_equal(hires, 2);
	desc.multipliers[0].effective = desc.multipliers[1].effective = 1;
	hid_desc_apply_multipliers(&desc);
	for (unsigned f = 0; f < desc.nfields; f++)
		assert_int_equal(desc.fields[f].resolution_multiplier, 1);

	/* so a wheel report of +1 is one whole detent */
	input_queue_init(&queue);
	usb_intr_init(&intr, &desc, 0, INPUT_CLASS_MOUSE, DEV, "hires refused");
	/* buttons(5)+pad(3), X(16), Y(16), wheel(8), AC Pan(8) */
	static const uint8_t r[7] = { 0, 0, 0, 0, 0, 0x01, 0 };
	assert_int_equal(complete(USB_INTR_COMPLETED, r, 7), USB_INTR_RESUBMIT);
	expect_event(INPUT_WHEEL, INPUT_WHEEL_V, 1);
	expect_event(INPUT_FRAME, 0, 0);
	expect_empty();
}

/* ---- the set's side of a hot-plug: a backend notes an arrival in its work ---- */

static int fake_opens, fake_arrival_due, fake_noted;

static int
fake_open_spec(struct input_devs *s, const char *arg, char *err, size_t errlen)
{
	(void)s;
	(void)arg;
	(void)err;
	(void)errlen;
	fake_opens++;
	return 0;
}

static int
fake_shared_fds(struct pollfd *fds, int max)
{
	if (max < 1)
		return 0;
	fds[0] = (struct pollfd){ .fd = 0, .events = POLLIN };
	return 1;
}

/* as libusb's hot-plug callback inside the event handling: only a note */
static void
fake_shared_work(uint64_t now_us, struct input_queue *q)
{
	(void)now_us;
	(void)q;
	fake_noted |= fake_arrival_due;
	fake_arrival_due = 0;
}

static int
fake_arrived(void)
{
	int a = fake_noted;
	fake_noted = 0;
	return a;
}

static const struct input_backend fake_backend = {
	.name = "fake",
	.usage = "fake:X",
	.open_spec = fake_open_spec,
	.shared_fds = fake_shared_fds,
	.shared_work = fake_shared_work,
	.arrived = fake_arrived,
};

static void
test_set_rescans_after_arrival(void **state)
{
	(void)state;
	static struct input_devs set;
	static const struct input_backend *const backends[] = { &fake_backend };
	char err[200];
	input_queue_init(&queue);
	input_devs_init(&set, backends, 1, 0, &queue);
	fake_opens = fake_arrival_due = fake_noted = 0;
	assert_int_equal(input_devs_open(&set, "fake:a", 0, err, sizeof err), 0);
	assert_int_equal(fake_opens, 1);
	struct pollfd fds[INPUT_DEVS_POLL_MAX];
	int tags[INPUT_DEVS_POLL_MAX];
	assert_int_equal(input_devs_pollfds(&set, fds, tags, INPUT_DEVS_POLL_MAX), 1);
	/* work without an arrival: the specs stay as they are */
	assert_int_equal(input_devs_ready(&set, tags[0], 10, &queue), 0);
	assert_int_equal(fake_opens, 1);
	/* an arrival noted in the work: the spec is opened again, once */
	fake_arrival_due = 1;
	assert_int_equal(input_devs_ready(&set, tags[0], 20, &queue), 0);
	assert_int_equal(fake_opens, 2);
	assert_int_equal(input_devs_ready(&set, tags[0], 30, &queue), 0);
	assert_int_equal(fake_opens, 2);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_expect_file_mouse),
		cmocka_unit_test(test_hid_recording),
		cmocka_unit_test(test_no_device_mid_press),
		cmocka_unit_test(test_boot_keyboard_gone),
		cmocka_unit_test(test_boot_mouse_cut_and_short),
		cmocka_unit_test(test_short_transfer),
		cmocka_unit_test(test_stall),
		cmocka_unit_test(test_other_endings),
		cmocka_unit_test(test_no_allocation_per_transfer),
		cmocka_unit_test(test_spec),
		cmocka_unit_test(test_open_absent_device),
		cmocka_unit_test(test_multiplier_feature_length),
		cmocka_unit_test(test_set_rescans_after_arrival),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
