/*
 * test_hidraw.c - the hidraw backend (devices/hidraw_dev.c) through its
 * seam: a socketpair(AF_UNIX, SOCK_SEQPACKET) stands in for the reader
 * thread, and the tests write into it what the thread sends, one datagram
 * a report (the time, then the report's bytes). The reports are the ones
 * hid-tools recorded (tests/input/hid/hidtools_*.hid); what the backend
 * makes of them must be what the decoder makes of the same bytes, with
 * the recording's times. Also: a descriptor the parser refuses, a device
 * gone mid-press (its button released, INPUT_REMOVED), a flood read in
 * capped batches, the Resolution Multiplier writes, the recorder's tap and
 * the spec's forms. The real hidapi path runs under umockdev
 * (tests/tools/test_hidraw_dev.py) and against the kernel's uhid in the
 * guest (tests/guest/test_guest_hidraw.py).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <poll.h>
#include <linux/input-event-codes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "devices/hid_desc.h"
#include "devices/hid_input.h"
#include "devices/hidraw_dev.h"
#include "devices/input_backends.h"
#include "devices/input_devs.h"
#include "devices/queue.h"
#include "devices/rec_hid.h"

#define DATA "tests/input/hid/"

static struct input_queue queue, want_queue;
static struct hidraw_dev dev, dev2;
static struct rec_hid rec;
static int peer = -1, peer2 = -1;
static FILE *quiet;

/* ---- helpers ------------------------------------------------------------- */

/* one end adopted into d (as device index idx, descriptor desc[0..n)), the other returned */
static int
adopt(struct hidraw_dev *d, const uint8_t *desc, size_t n, uint16_t idx)
{
	int sv[2];
	assert_int_equal(socketpair(AF_UNIX, SOCK_SEQPACKET, 0, sv), 0);
	char err[256];
	if (hidraw_dev_adopt(d, sv[0], desc, n, idx, "test", err, sizeof err) < 0)
		fail_msg("adopt: %s", err);
	d->in.log.out = quiet;
	return sv[1];
}

/* what the reader thread sends for one report */
static void
send_report(int fd, uint64_t t_us, const uint8_t *report, size_t n)
{
	uint8_t buf[HIDRAW_DEV_HEAD + HIDRAW_DEV_REPORT_MAX];
	assert_true(n <= HIDRAW_DEV_REPORT_MAX);
	memcpy(buf, &t_us, sizeof t_us);
	memcpy(buf + HIDRAW_DEV_HEAD, report, n);
	assert_int_equal(send(fd, buf, HIDRAW_DEV_HEAD + n, 0), (ssize_t)(HIDRAW_DEV_HEAD + n));
}

/* pops every event of q into dest (at most max); the count */
static size_t
drain(struct input_queue *q, struct input_event_rec *dest, size_t max)
{
	size_t n = 0;
	struct input_event_rec e;
	while (input_queue_pop(q, &e)) {
		assert_true(n < max);
		dest[n++] = e;
	}
	return n;
}

static void
assert_same_events(const struct input_event_rec *got, size_t ngot,
		   const struct input_event_rec *want, size_t nwant)
{
	assert_int_equal(ngot, nwant);
	for (size_t i = 0; i < ngot; i++) {
		if (got[i].t_us != want[i].t_us || got[i].device != want[i].device ||
		    got[i].kind != want[i].kind || got[i].code != want[i].code ||
		    got[i].value != want[i].value || got[i].x != want[i].x ||
		    got[i].y != want[i].y || got[i].flags != want[i].flags)
			fail_msg("event %zu: got %s code %u value %d x %g at %llu, want %s code %u "
				 "value %d x %g at %llu",
				 i, input_kind_to_str((enum input_kind)got[i].kind), got[i].code,
				 got[i].value, got[i].x, (unsigned long long)got[i].t_us,
				 input_kind_to_str((enum input_kind)want[i].kind), want[i].code,
				 want[i].value, want[i].x, (unsigned long long)want[i].t_us);
	}
}

static int
setup(void **state)
{
	(void)state;
	input_queue_init(&queue);
	input_queue_init(&want_queue);
	memset(&dev, 0, sizeof dev);
	memset(&dev2, 0, sizeof dev2);
	dev.fd = dev2.fd = -1;
	peer = peer2 = -1;
	quiet = tmpfile();
	return 0;
}

static int
teardown(void **state)
{
	(void)state;
	hidraw_dev_close(&dev, 0, NULL);
	hidraw_dev_close(&dev2, 0, NULL);
	if (peer >= 0)
		close(peer);
	if (peer2 >= 0)
		close(peer2);
	rec_hid_free(&rec);
	fclose(quiet);
	return 0;
}

static const uint8_t qemu_mouse_desc[] = {
	0x05, 0x01, 0x09, 0x02, 0xa1, 0x01, 0x09, 0x01, 0xa1, 0x00, 0x05, 0x09, 0x19,
	0x01, 0x29, 0x03, 0x15, 0x00, 0x25, 0x01, 0x95, 0x03, 0x75, 0x01, 0x81, 0x02,
	0x95, 0x01, 0x75, 0x05, 0x81, 0x01, 0x05, 0x01, 0x09, 0x30, 0x09, 0x31, 0x09,
	0x38, 0x15, 0x81, 0x25, 0x7f, 0x75, 0x08, 0x95, 0x03, 0x81, 0x06, 0xc0, 0xc0,
};

/* ---- recorded reports through the seam ------------------------------------ */

/* every device of a hid-recorder file through the backend and through the decoder alone */
static void
replay(const char *path)
{
	static struct input_event_rec got[4096], want[4096];
	char err[512];
	if (rec_hid_read(path, &rec, err, sizeof err) < 0)
		fail_msg("%s", err);
	assert_true(rec.ndevices >= 1 && rec.ndevices <= 2);
	struct hidraw_dev *devs[2] = { &dev, &dev2 };
	int *peers[2] = { &peer, &peer2 };
	static struct hid_desc descs[2];
	static struct hid_input refs[2];
	for (unsigned i = 0; i < rec.ndevices; i++) {
		*peers[i] = adopt(devs[i], rec.devices[i].desc, rec.devices[i].desc_len,
				  (uint16_t)i);
		assert_int_equal(hid_desc_parse(rec.devices[i].desc, rec.devices[i].desc_len,
						&descs[i], err, sizeof err),
				 0);
		hid_input_init(&refs[i], &descs[i], (uint16_t)i, "reference");
	}
	/* the mouse and the keyboard of the QEMU recordings are told apart by the descriptor */
	assert_int_equal(dev.info.cls, INPUT_CLASS_MOUSE);
	if (rec.ndevices == 2)
		assert_int_equal(dev2.info.cls, INPUT_CLASS_KEYBOARD);

	size_t ngot = 0, nwant = 0;
	for (size_t k = 0; k < rec.nevents; k++) {
		const struct rec_hid_event *e = &rec.events[k];
		send_report(*peers[e->device], e->t_us + 5000000, e->bytes, e->len);
		/* the loop: the device's fd was readable, one read takes the report */
		assert_int_equal(hidraw_dev_read(devs[e->device], 1, &queue), 1);
		assert_int_equal(hidraw_dev_read(devs[e->device], 2, &queue), 0);
		ngot += drain(&queue, got + ngot, 4096 - ngot);
		hid_input_feed(&refs[e->device], e->bytes, e->len, e->t_us + 5000000, &want_queue);
		nwant += drain(&want_queue, want + nwant, 4096 - nwant);
	}
	assert_true(ngot > rec.nevents); /* something besides frame ends */
	assert_same_events(got, ngot, want, nwant);
	assert_int_equal(dev.reports + dev2.reports, rec.nevents);
	assert_int_equal(dev.bad + dev2.bad, 0);
}

static void
test_replay_mouse_recording(void **state)
{
	(void)state;
	replay(DATA "hidtools_mouse.hid");
}

static void
test_replay_two_devices(void **state)
{
	(void)state;
	replay(DATA "hidtools_two.hid");
}

/* the reports' meaning, not only the decoder's agreement: the mouse recording by hand */
static void
test_mouse_recording_means(void **state)
{
	(void)state;
	char err[512];
	if (rec_hid_read(DATA "hidtools_mouse.hid", &rec, err, sizeof err) < 0)
		fail_msg("%s", err);
	peer = adopt(&dev, rec.devices[0].desc, rec.devices[0].desc_len, 3);
	for (size_t k = 0; k < rec.nevents; k++)
		send_report(peer, rec.events[k].t_us, rec.events[k].bytes, rec.events[k].len);
	assert_int_equal(hidraw_dev_read(&dev, 0, &queue), 3);
	struct input_event_rec e[16];
	size_t n = drain(&queue, e, 16);
	/* motion 1,-1 | BTN_LEFT down | BTN_LEFT up and the wheel one detent */
	assert_int_equal(n, 7);
	assert_int_equal(e[0].kind, INPUT_MOTION);
	assert_true(e[0].x == 1 && e[0].y == -1);
	assert_int_equal(e[0].t_us, 0);
	assert_int_equal(e[0].device, 3);
	assert_int_equal(e[1].kind, INPUT_FRAME);
	assert_int_equal(e[2].kind, INPUT_BUTTON);
	assert_int_equal(e[2].code, BTN_LEFT);
	assert_int_equal(e[2].value, 1);
	assert_int_equal(e[2].t_us, 120004);
	assert_int_equal(e[3].kind, INPUT_FRAME);
	assert_true(e[4].kind == INPUT_BUTTON && e[4].code == BTN_LEFT && e[4].value == 0);
	assert_int_equal(e[5].kind, INPUT_WHEEL);
	assert_int_equal(e[5].code, INPUT_WHEEL_V);
	assert_int_equal(e[5].value, 1);
	assert_int_equal(e[5].t_us, 1000005);
	assert_int_equal(e[6].kind, INPUT_FRAME);
}

/* ---- the device going away -------------------------------------------------- */

static void
test_gone_mid_press_releases(void **state)
{
	(void)state;
	peer = adopt(&dev, qemu_mouse_desc, sizeof qemu_mouse_desc, 2);
	const uint8_t press[] = { 0x03, 0x00, 0x00, 0x00 }; /* left and right held */
	send_report(peer, 1000, press, sizeof press);
	assert_int_equal(hidraw_dev_read(&dev, 1500, &queue), 1);
	struct input_event_rec e[16];
	assert_int_equal(drain(&queue, e, 16), 3);

	/* the thread's end closes: the end of the stream, the device gone */
	close(peer);
	peer = -1;
	assert_int_equal(hidraw_dev_read(&dev, 9000, &queue), -1);
	size_t n = drain(&queue, e, 16);
	assert_int_equal(n, 4);
	for (int i = 0; i < 2; i++) {
		assert_int_equal(e[i].kind, INPUT_BUTTON);
		assert_int_equal(e[i].value, 0);
		assert_int_equal(e[i].t_us, 9000);
		assert_int_equal(e[i].device, 2);
	}
	assert_true((e[0].code == BTN_LEFT && e[1].code == BTN_RIGHT) ||
		    (e[0].code == BTN_RIGHT && e[1].code == BTN_LEFT));
	assert_int_equal(e[2].kind, INPUT_FRAME);
	assert_int_equal(e[3].kind, INPUT_REMOVED);
	assert_int_equal(e[3].code, INPUT_CLASS_MOUSE);

	/* the line that says so blames the stream's end and counts the releases */
	char line[256] = "";
	rewind(quiet);
	assert_non_null(fgets(line, sizeof line, quiet));
	assert_non_null(strstr(line, "gone (end of the stream); 2 key(s) and button(s) released"));

	/* closing it afterwards releases nothing twice */
	hidraw_dev_close(&dev, 9500, &queue);
	assert_int_equal(drain(&queue, e, 16), 0);
	assert_int_equal(hidraw_dev_fd(&dev), -1);
}

/* the daemon's path: the set reads the place, the device is gone, the place is free */
static int seam_peer = -1;

static int
seam_open_spec(struct input_devs *s, const char *arg, char *err, size_t errlen)
{
	(void)arg;
	int i = input_devs_free_place(s, "seam");
	assert_true(i >= 0);
	struct hidraw_dev *d = malloc(sizeof *d);
	assert_non_null(d);
	int sv[2];
	assert_int_equal(socketpair(AF_UNIX, SOCK_SEQPACKET, 0, sv), 0);
	if (hidraw_dev_adopt(d, sv[0], qemu_mouse_desc, sizeof qemu_mouse_desc, (uint16_t)i,
			     "seam", err, errlen) < 0)
		fail_msg("%s", err);
	d->in.log.out = quiet;
	seam_peer = sv[1];
	struct input_dev_info info = { .cls = d->info.cls, .iface = -1 };
	snprintf(info.path, sizeof info.path, "seam");
	input_devs_put(s, i, s->backends[0], d, &info);
	return 1;
}

static void
test_gone_through_the_device_set(void **state)
{
	(void)state;
	/* hidraw's table with the seam's open: fd, read and close are the backend's own */
	static struct input_backend be;
	be = input_backend_hidraw;
	be.open_spec = seam_open_spec;
	const struct input_backend *const backends[] = { &be };
	static struct input_devs s;
	char err[256];
	input_devs_init(&s, backends, 1, 0, &queue);
	assert_int_equal(input_devs_open(&s, "hidraw:seam", 50, err, sizeof err), 1);
	struct input_event_rec e[16];
	assert_int_equal(drain(&queue, e, 16), 1);
	assert_true(e[0].kind == INPUT_ADDED && e[0].code == INPUT_CLASS_MOUSE);

	/* a press, read when the loop's poll says the fd is readable */
	const uint8_t press[] = { 0x01, 0x00, 0x00, 0x00 };
	send_report(seam_peer, 60, press, sizeof press);
	struct pollfd fds[INPUT_DEVS_POLL_MAX];
	int tags[INPUT_DEVS_POLL_MAX];
	assert_int_equal(input_devs_pollfds(&s, fds, tags, INPUT_DEVS_POLL_MAX), 1);
	assert_int_equal(poll(fds, 1, 1000), 1);
	assert_int_equal(input_devs_ready(&s, tags[0], 70, &queue), 0);
	assert_int_equal(drain(&queue, e, 16), 2);
	assert_true(e[0].kind == INPUT_BUTTON && e[0].code == BTN_LEFT && e[0].value == 1);

	/* gone mid-press: released, removed, the place free */
	close(seam_peer);
	assert_int_equal(poll(fds, 1, 1000), 1);
	assert_int_equal(input_devs_ready(&s, tags[0], 80, &queue), -1);
	assert_int_equal(drain(&queue, e, 16), 3);
	assert_true(e[0].kind == INPUT_BUTTON && e[0].code == BTN_LEFT && e[0].value == 0);
	assert_int_equal(e[1].kind, INPUT_FRAME);
	assert_int_equal(e[2].kind, INPUT_REMOVED);
	assert_int_equal(input_devs_count(&s), 0);
	assert_int_equal(input_devs_pollfds(&s, fds, tags, INPUT_DEVS_POLL_MAX), 0);
}

/* ---- a descriptor the parser refuses ------------------------------------------ */

static void
test_refused_descriptor_leaves_it_closed(void **state)
{
	(void)state;
	int sv[2];
	assert_int_equal(socketpair(AF_UNIX, SOCK_SEQPACKET, 0, sv), 0);
	/* an End Collection with no Collection open */
	const uint8_t bad[] = { 0x05, 0x01, 0x09, 0x02, 0xc0 };
	char err[256];
	FILE *old = stderr;
	stderr = quiet; /* the log line the refusal writes */
	int rc = hidraw_dev_adopt(&dev, sv[0], bad, sizeof bad, 0, "bad", err, sizeof err);
	stderr = old;
	assert_int_equal(rc, -1);
	assert_non_null(strstr(err, "report descriptor refused: byte 4"));
	assert_int_equal(hidraw_dev_fd(&dev), -1);
	char line[256] = "";
	rewind(quiet);
	assert_non_null(fgets(line, sizeof line, quiet));
	assert_non_null(strstr(line, "device fault: report descriptor refused"));
	/* the fd is still the caller's */
	assert_int_equal(send(sv[1], "x", 1, 0), 1);
	close(sv[0]);
	close(sv[1]);
}

/* ---- bad datagrams and floods ---------------------------------------------------- */

static void
test_bad_datagrams_are_counted(void **state)
{
	(void)state;
	peer = adopt(&dev, qemu_mouse_desc, sizeof qemu_mouse_desc, 0);
	assert_int_equal(send(peer, "abc", 3, 0), 3);           /* shorter than the header */
	const uint8_t shortrep[] = { 0x01, 0x02 };              /* the decoder's: too short */
	send_report(peer, 10, shortrep, sizeof shortrep);
	const uint8_t ok[] = { 0x00, 0x05, 0x00, 0x00 };
	send_report(peer, 20, ok, sizeof ok);
	assert_int_equal(hidraw_dev_read(&dev, 30, &queue), 3);
	assert_int_equal(dev.bad, 1);
	assert_int_equal(dev.reports, 2);
	assert_int_equal(dev.in.short_reports, 1);
	struct input_event_rec e[8];
	assert_int_equal(drain(&queue, e, 8), 2);
	assert_int_equal(e[0].kind, INPUT_MOTION);
	assert_true(e[0].x == 5 && e[0].t_us == 20);
}

static void
test_flood_is_read_in_capped_batches(void **state)
{
	(void)state;
	peer = adopt(&dev, qemu_mouse_desc, sizeof qemu_mouse_desc, 0);
	const int n = 150;
	for (int i = 0; i < n; i++) {
		const uint8_t r[] = { 0x00, 0x01, 0x00, 0x00 };
		send_report(peer, (uint64_t)i, r, sizeof r);
	}
	int total = 0, calls = 0, got;
	double sum = 0;
	while ((got = hidraw_dev_read(&dev, 0, &queue)) > 0) {
		assert_true(got <= HIDRAW_DEV_READ_MAX);
		total += got;
		calls++;
		struct input_event_rec e;
		while (input_queue_pop(&queue, &e))
			if (e.kind == INPUT_MOTION)
				sum += e.x;
	}
	assert_int_equal(got, 0);
	assert_int_equal(total, n);
	assert_int_equal(calls, 3);   /* 64 + 64 + 22 */
	assert_int_equal(dev.capped, 2);
	assert_int_equal(dev.reads, 3);
	assert_true(sum == n);
}

/* ---- the Resolution Multipliers ---------------------------------------------------- */

struct fake_feature {
	int gets, sets;
	int refuse_set;
	uint8_t get_answer[8];
	size_t get_len;
	uint8_t set[8];
	size_t set_len;
};

static int
fake_feature(void *ctx, int set, uint8_t *buf, size_t n)
{
	struct fake_feature *f = ctx;
	/* the kernel's hidraw refuses buffers over HID_MAX_BUFFER_SIZE (4096 on 6.1) */
	assert_true(n <= 4096);
	if (!set) {
		f->gets++;
		assert_int_equal(buf[0], 0); /* the report id asked for */
		if (!f->get_len)
			return -1;
		assert_true(n >= f->get_len);
		memcpy(buf, f->get_answer, f->get_len);
		return (int)f->get_len;
	}
	f->sets++;
	assert_true(n <= sizeof f->set);
	memcpy(f->set, buf, n);
	f->set_len = n;
	return f->refuse_set ? -1 : (int)n;
}

static size_t
load_rdesc(const char *name, uint8_t *dest)
{
	char path[256];
	snprintf(path, sizeof path, DATA "%s.rdesc", name);
	FILE *f = fopen(path, "r");
	assert_non_null(f);
	char line[512];
	size_t n = 0;
	while (fgets(line, sizeof line, f)) {
		char *hash = strchr(line, '#');
		if (hash)
			*hash = '\0';
		for (char *p = strtok(line, " \t\r\n"); p; p = strtok(NULL, " \t\r\n"))
			dest[n++] = (uint8_t)strtoul(p, NULL, 16);
	}
	fclose(f);
	return n;
}

/* buttons (5 bits + 3), X and Y (16 bits each), wheel, AC Pan: hires_wheel.rdesc's report */
static void
wheel_report(int fd, int8_t wheel, int8_t pan)
{
	const uint8_t r[] = { 0, 0, 0, 0, 0, (uint8_t)wheel, (uint8_t)pan };
	send_report(fd, 100, r, sizeof r);
}

static void
test_multipliers_written_and_hires(void **state)
{
	(void)state;
	uint8_t desc[HID_DESC_MAX_BYTES];
	size_t n = load_rdesc("hires_wheel", desc);
	peer = adopt(&dev, desc, n, 0);
	assert_int_equal(dev.desc.nmultipliers, 2);

	/* the device answers GET with other bits set: they are kept */
	struct fake_feature f = { .get_answer = { 0x00, 0xfc, 0xfc }, .get_len = 3 };
	assert_int_equal(hidraw_dev_set_multipliers(&dev, fake_feature, &f), 2);
	/* both multipliers live in feature report 0: one GET, one SET, as the kernel sends */
	assert_int_equal(f.gets, 1);
	assert_int_equal(f.sets, 1);
	assert_int_equal(f.set_len, 3);
	assert_int_equal(f.set[0], 0x00);
	assert_int_equal(f.set[1], 0xfd); /* logical maximum 1 in bits 0-1 */
	assert_int_equal(f.set[2], 0xfd);
	assert_int_equal(dev.multipliers_set, 2);

	/* one wheel count is 1/8 detent (the wheel's multiplier 8), a pan count 1/4 */
	wheel_report(peer, 1, 0);
	wheel_report(peer, 0, 1);
	assert_int_equal(hidraw_dev_read(&dev, 0, &queue), 2);
	struct input_event_rec e[8];
	assert_int_equal(drain(&queue, e, 8), 4);
	assert_int_equal(e[0].kind, INPUT_WHEEL);
	assert_int_equal(e[0].code, INPUT_WHEEL_V);
	assert_true(e[0].x == 15 && e[0].value == 0 && (e[0].flags & INPUT_F_HIRES));
	assert_int_equal(e[2].code, INPUT_WHEEL_H);
	assert_true(e[2].x == 30 && e[2].value == 0);
}

static void
test_multipliers_refused_mean_whole_detents(void **state)
{
	(void)state;
	uint8_t desc[HID_DESC_MAX_BYTES];
	size_t n = load_rdesc("hires_wheel", desc);
	peer = adopt(&dev, desc, n, 0);
	/* GET fails (zeros, the multiplier's length), SET refused */
	struct fake_feature f = { .refuse_set = 1 };
	assert_int_equal(hidraw_dev_set_multipliers(&dev, fake_feature, &f), 0);
	assert_int_equal(f.set_len, 3);
	assert_int_equal(f.set[1], 0x01);
	assert_int_equal(f.set[2], 0x01);
	assert_int_equal(dev.multipliers_refused, 2);
	char line[256] = "";
	rewind(quiet);
	assert_non_null(fgets(line, sizeof line, quiet));
	assert_non_null(strstr(line, "Resolution Multiplier (feature report 0) was not written"));

	wheel_report(peer, 1, -1);
	assert_int_equal(hidraw_dev_read(&dev, 0, &queue), 1);
	struct input_event_rec e[8];
	assert_int_equal(drain(&queue, e, 8), 3);
	assert_true(e[0].kind == INPUT_WHEEL && e[0].value == 1 && e[0].x == 120);
	assert_true(e[1].kind == INPUT_WHEEL && e[1].value == -1 && e[1].x == -120);
}

static void
test_no_multipliers_no_requests(void **state)
{
	(void)state;
	peer = adopt(&dev, qemu_mouse_desc, sizeof qemu_mouse_desc, 0);
	struct fake_feature f = { 0 };
	assert_int_equal(hidraw_dev_set_multipliers(&dev, fake_feature, &f), 0);
	assert_int_equal(f.gets + f.sets, 0);
}

/* ---- the recorder's tap and the description ------------------------------------------ */

struct tapped {
	int n;
	uint64_t t[4];
	size_t len[4];
	uint8_t first[4];
};

static void
tap(void *ctx, uint64_t t_us, const uint8_t *report, size_t n)
{
	struct tapped *t = ctx;
	assert_true(t->n < 4);
	t->t[t->n] = t_us;
	t->len[t->n] = n;
	t->first[t->n] = report[0];
	t->n++;
}

static void
test_tap_sees_each_report(void **state)
{
	(void)state;
	peer = adopt(&dev, qemu_mouse_desc, sizeof qemu_mouse_desc, 0);
	struct tapped t = { 0 };
	dev.tap = tap;
	dev.tap_ctx = &t;
	const uint8_t a[] = { 0x01, 0, 0, 0 }, b[] = { 0x00, 0, 0, 1 };
	send_report(peer, 111, a, sizeof a);
	send_report(peer, 222, b, sizeof b);
	assert_int_equal(hidraw_dev_read(&dev, 0, &queue), 2);
	assert_int_equal(t.n, 2);
	assert_true(t.t[0] == 111 && t.t[1] == 222);
	assert_true(t.len[0] == 4 && t.first[0] == 0x01 && t.first[1] == 0x00);

	struct rec_hid_device rd;
	hidraw_dev_describe(&dev, &rd);
	assert_int_equal(rd.desc_len, sizeof qemu_mouse_desc);
	assert_memory_equal(rd.desc, qemu_mouse_desc, sizeof qemu_mouse_desc);
	assert_string_equal(rd.name, "test");
}

/* ---- the spec ---------------------------------------------------------------------- */

static void
test_spec_forms(void **state)
{
	(void)state;
	uint16_t vid, pid;
	int iface;
	const char *path;
	char err[256];
	assert_int_equal(hidraw_dev_parse_spec("046d:C077", &vid, &pid, &iface, &path, err,
					       sizeof err),
			 0);
	assert_true(vid == 0x046d && pid == 0xc077 && iface == -1 && !path);
	assert_int_equal(hidraw_dev_parse_spec("0627:0001:2", &vid, &pid, &iface, &path, err,
					       sizeof err),
			 0);
	assert_true(vid == 0x0627 && pid == 0x0001 && iface == 2);
	assert_int_equal(hidraw_dev_parse_spec("/dev/hidraw3", &vid, &pid, &iface, &path, err,
					       sizeof err),
			 0);
	assert_string_equal(path, "/dev/hidraw3");
	static const char *const bad[] = { "", "046d", "046d:", "12345:1", "046d:c077:",
					   "046d:c077:1:2", "046d:xyz", "g:1", "046d:c077:1x",
					   "046d:c077:a" };
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		if (hidraw_dev_parse_spec(bad[i], &vid, &pid, &iface, &path, err, sizeof err) != -1)
			fail_msg("'%s' was taken", bad[i]);
		assert_non_null(strstr(err, "hidraw"));
	}
}

/* through the device set: a malformed spec is an error; no match is a skip with a reason */
static void
test_the_set_opens_hidraw_specs(void **state)
{
	(void)state;
	static struct input_devs s;
	char err[256];
	input_devs_init(&s, input_backends, input_backends_count, 0, NULL);
	assert_int_equal(input_devs_open(&s, "hidraw:046d", 0, err, sizeof err), -1);
	assert_non_null(strstr(err, "VID:PID[:IFACE]"));
	/* no such device here (hidapi enumerates for real; this machine has no ffff:fffe) */
	assert_int_equal(input_devs_open(&s, "hidraw:ffff:fffe", 0, err, sizeof err), 0);
	assert_int_equal(input_devs_count(&s), 0);
	assert_int_equal(s.nskip, 1);
	assert_string_equal(s.skip[0].what, "hidraw:ffff:fffe");
	assert_true(strlen(s.skip[0].why) > 0);
	/* a path that is no hidraw node: skipped, saying why */
	assert_int_equal(input_devs_open(&s, "hidraw:/nonexistent/hidraw9", 0, err, sizeof err),
			 0);
	assert_int_equal(s.nskip, 2);
	assert_non_null(strstr(s.skip[1].why, "No such file or directory"));
	/* the forms the set lists on an unknown backend name the new one */
	assert_int_equal(input_devs_open(&s, "bluetooth:1", 0, err, sizeof err), -1);
	assert_non_null(strstr(err, "hidraw:VID:PID[:IFACE]"));
	input_devs_close_all(&s, 0, NULL);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(test_replay_mouse_recording, setup, teardown),
		cmocka_unit_test_setup_teardown(test_replay_two_devices, setup, teardown),
		cmocka_unit_test_setup_teardown(test_mouse_recording_means, setup, teardown),
		cmocka_unit_test_setup_teardown(test_gone_mid_press_releases, setup, teardown),
		cmocka_unit_test_setup_teardown(test_gone_through_the_device_set, setup, teardown),
		cmocka_unit_test_setup_teardown(test_refused_descriptor_leaves_it_closed, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_bad_datagrams_are_counted, setup, teardown),
		cmocka_unit_test_setup_teardown(test_flood_is_read_in_capped_batches, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_multipliers_written_and_hires, setup, teardown),
		cmocka_unit_test_setup_teardown(test_multipliers_refused_mean_whole_detents, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_no_multipliers_no_requests, setup, teardown),
		cmocka_unit_test_setup_teardown(test_tap_sees_each_report, setup, teardown),
		cmocka_unit_test_setup_teardown(test_spec_forms, setup, teardown),
		cmocka_unit_test_setup_teardown(test_the_set_opens_hidraw_specs, setup, teardown),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
