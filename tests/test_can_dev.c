/*
 * test_can_dev.c - the SocketCAN backend (devices/can_dev.h) on its read
 * path, with a SOCK_SEQPACKET socketpair standing in for the CAN_RAW socket
 * (can_dev_adopt): each datagram one struct can_frame as <linux/can.h>
 * lays it out. A real candump log's frames decode to the events cantools'
 * values give (tests/input/can/panel.expect, made by make_expect.py);
 * error frames are counted and said in words (bus-off silences the panel);
 * datagrams that are not 16 bytes are refused with a line and change
 * nothing; the interface going down (ENETDOWN, injected through the recvmsg
 * seam) releases the buttons and keeps the device, which reads on; the
 * interface gone (ENODEV, or the stand-in's peer closed) removes it; a
 * kernel without CAN, or a missing interface, is a skip with its reason;
 * a bad map is a configuration error.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/input-event-codes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "alloc_count.h"
#include "devices/can_dev.h"
#include "devices/can_map.h"
#include "devices/input_backends.h"
#include "devices/input_devs.h"
#include "devices/rec_candump.h"

#define DIR "tests/input/can/"

static struct can_map map;
static struct input_queue queue;
static struct can_dev dev;
static int peer = -1;
static char *logbuf;
static size_t loglen;
static FILE *log_out;

/* a socketpair as the device, the panel map, the log lines into logbuf */
static int
setup(void **state)
{
	(void)state;
	char err[256] = "";
	if (can_map_read(DIR "panel.map", &map, err, sizeof err))
		fail_msg("%s", err);
	int sv[2];
	assert_int_equal(socketpair(AF_UNIX, SOCK_SEQPACKET, 0, sv), 0);
	if (can_dev_adopt(&dev, sv[0], &map, 3, "test0", err, sizeof err))
		fail_msg("%s", err);
	peer = sv[1];
	input_queue_init(&queue);
	log_out = open_memstream(&logbuf, &loglen);
	dev.in.log.out = log_out;
	dev.link_log.out = log_out;
	return 0;
}

static int
teardown(void **state)
{
	(void)state;
	can_dev_close(&dev, 0, NULL);
	if (peer >= 0)
		close(peer);
	peer = -1;
	fclose(log_out);
	free(logbuf);
	logbuf = NULL;
	return 0;
}

/* the log lines written so far */
static const char *
log_text(void)
{
	fflush(log_out);
	return logbuf ? logbuf : "";
}

static size_t
count_of(const char *text, const char *what)
{
	size_t n = 0;
	for (const char *p = text; (p = strstr(p, what)); p += strlen(what))
		n++;
	return n;
}

/* one frame as the kernel lays it out, written as one datagram */
static void
send_frame(uint32_t can_id, const uint8_t *data, uint8_t len)
{
	struct can_frame f;
	memset(&f, 0, sizeof f);
	f.can_id = can_id;
	f.len = len;
	if (data)
		memcpy(f.data, data, len);
	assert_int_equal(write(peer, &f, sizeof f), (ssize_t)sizeof f);
}

static void
send_bytes(size_t n)
{
	uint8_t b[80];
	memset(b, 0x5a, sizeof b);
	assert_int_equal(write(peer, b, n), (ssize_t)n);
}

/* every queued event, popped */
static int
drain(struct input_event_rec *dest, int max)
{
	int n = 0;
	struct input_event_rec e;
	while (input_queue_pop(&queue, &e))
		if (n < max)
			dest[n++] = e;
	return n;
}

/* ---- a real log, against cantools' values ---- */

struct expected {
	int frame, line;
	double value;
};

/* panel.expect: what cantools decodes from each frame of panel.log */
static int
read_expect(struct expected *dest, int max)
{
	FILE *f = fopen(DIR "panel.expect", "r");
	assert_non_null(f);
	char line[512], name[128];
	int n = 0;
	while (fgets(line, sizeof line, f)) {
		if (line[0] == '#')
			continue;
		assert_true(n < max);
		assert_int_equal(sscanf(line, "%d %d %127s %lf", &dest[n].frame, &dest[n].line,
					name, &dest[n].value),
				 4);
		n++;
	}
	fclose(f);
	return n;
}

static void
test_log_frames_give_cantools_values(void **state)
{
	(void)state;
	static struct expected want[2048];
	int nwant = read_expect(want, 2048);
	char err[256];
	struct rec_candump log;
	if (rec_candump_read(DIR "panel.log", &log, err, sizeof err))
		fail_msg("%s", err);
	/* staleness is another test's: here every frame's values, whatever the gaps */
	for (int i = 0; i < map.n; i++)
		map.line[i].stale_ms = 0;

	/* the event rule applied to cantools' values: a valuator when it changes, a button on edges */
	double last[CAN_MAP_MAX_LINES];
	uint8_t seen[CAN_MAP_MAX_LINES] = { 0 }, down[CAN_MAP_MAX_LINES] = { 0 };
	int k = 0, checked = 0;
	for (size_t fi = 0; fi < log.n; fi++) {
		const struct rec_candump_frame *fr = &log.frames[fi];
		send_frame(fr->can_id, fr->data, fr->len);
		assert_int_equal(can_dev_read(&dev, fr->t_us, &queue), 1);
		struct input_event_rec got[64];
		int ngot = drain(got, 64), g = 0;
		for (; k < nwant && want[k].frame == (int)fi; k++) {
			const struct can_map_line *l = &map.line[want[k].line];
			double v = want[k].value;
			if (l->kind == CAN_MAP_BUTTON) {
				if ((v != 0) == down[want[k].line])
					continue;
				down[want[k].line] = v != 0;
				assert_true(g < ngot);
				assert_int_equal(got[g].kind, INPUT_BUTTON);
				assert_int_equal(got[g].code, l->code);
				assert_int_equal(got[g].value, v != 0);
			} else {
				if (seen[want[k].line] && last[want[k].line] == v)
					continue;
				seen[want[k].line] = 1;
				last[want[k].line] = v;
				assert_true(g < ngot);
				assert_int_equal(got[g].kind, INPUT_VALUATOR);
				assert_int_equal(got[g].code, want[k].line);
				if (fabs(got[g].x - v) > 1e-9 * fmax(1.0, fabs(v)))
					fail_msg("frame %zu %s: %.17g, cantools %.17g", fi, l->name,
						 got[g].x, v);
			}
			assert_int_equal(got[g].device, 3);
			assert_int_equal(got[g].t_us, fr->t_us);
			g++;
			checked++;
		}
		if (g) {
			assert_int_equal(ngot, g + 1);
			assert_int_equal(got[g].kind, INPUT_FRAME);
		} else {
			assert_int_equal(ngot, 0);
		}
	}
	assert_int_equal(k, nwant);
	assert_true(checked > 300);
	assert_int_equal(dev.frames, log.n);
	assert_int_equal(dev.bad_size, 0);
	rec_candump_free(&log);
}

/* a flood is read 64 frames a call; the rest waits */
static void
test_reads_capped(void **state)
{
	(void)state;
	uint8_t data[8] = { 0 };
	for (int i = 0; i < 100; i++) {
		data[0] = (uint8_t)i;
		send_frame(0x181, data, 8);
	}
	assert_int_equal(can_dev_read(&dev, 1000, &queue), CAN_DEV_READ_MAX);
	assert_int_equal(dev.capped, 1);
	assert_int_equal(can_dev_read(&dev, 2000, &queue), 100 - CAN_DEV_READ_MAX);
	assert_int_equal(can_dev_read(&dev, 3000, &queue), 0);
	assert_int_equal(dev.frames, 100);
	assert_int_equal(dev.reads, 2);
}

/* ---- bad input: error frames, wrong sizes ---- */

static void
test_error_frames_counted_and_said(void **state)
{
	(void)state;
	/* linux/can/error.h: class in the id, the controller's detail in data[1] */
	uint8_t crtl[8] = { 0, CAN_ERR_CRTL_RX_PASSIVE, 0, 0, 0, 0, 0, 0 };
	send_frame(CAN_ERR_FLAG | CAN_ERR_CRTL, crtl, CAN_ERR_DLC);
	uint8_t prot[8] = { 0, 0, CAN_ERR_PROT_FORM, CAN_ERR_PROT_LOC_SOF, 0, 0, 0, 0 };
	send_frame(CAN_ERR_FLAG | CAN_ERR_PROT | CAN_ERR_BUSERROR, prot, CAN_ERR_DLC);
	assert_int_equal(can_dev_read(&dev, 1000, &queue), 2);
	struct input_event_rec got[8];
	assert_int_equal(drain(got, 8), 0);
	assert_int_equal(dev.error_frames, 2);
	assert_int_equal(dev.bus_off, 0);
	const char *t = log_text();
	assert_non_null(strstr(t, "panel (test0): device fault: error frame: controller problem, "
				  "receive error passive"));
	assert_non_null(strstr(t, "error frame: protocol violation, bus error, protocol type 0x02 "
				  "at 0x03"));
	assert_int_equal(dev.in.frames, 0); /* not decoded */
}

static void
test_bus_off_releases_and_frames_resume(void **state)
{
	(void)state;
	/* Dials.Foot (bit 32) pressed, Dial1 = 0x0102 raw */
	uint8_t data[8] = { 0x02, 0x01, 0, 0, 0x01, 0, 0, 0 };
	send_frame(0x181, data, 8);
	assert_int_equal(can_dev_read(&dev, 1000, &queue), 1);
	struct input_event_rec got[32];
	int n = drain(got, 32);
	int foot = can_map_find(&map, "Dials.Foot");
	assert_true(foot >= 0);
	int pressed = 0;
	for (int i = 0; i < n; i++)
		pressed += got[i].kind == INPUT_BUTTON && got[i].code == map.line[foot].code &&
			   got[i].value == 1;
	assert_int_equal(pressed, 1);

	send_frame(CAN_ERR_FLAG | CAN_ERR_BUSOFF, NULL, CAN_ERR_DLC);
	assert_int_equal(can_dev_read(&dev, 2000, &queue), 1);
	n = drain(got, 32);
	/* the button released, the four dials of 0x181 stale, one frame end */
	int released = 0, stale = 0;
	for (int i = 0; i < n; i++) {
		released += got[i].kind == INPUT_BUTTON && got[i].value == 0 &&
			    got[i].code == map.line[foot].code;
		stale += got[i].kind == INPUT_VALUATOR && (got[i].flags & INPUT_F_STALE);
	}
	assert_int_equal(released, 1);
	assert_int_equal(stale, 4);
	assert_int_equal(got[n - 1].kind, INPUT_FRAME);
	assert_int_equal(dev.bus_off, 1);
	assert_non_null(strstr(log_text(), "the bus is off (error frame: bus-off): 1 button(s) "
					    "released"));

	/* a frame again: everything it holds reported afresh, the button pressed again */
	send_frame(0x181, data, 8);
	assert_int_equal(can_dev_read(&dev, 3000, &queue), 1);
	n = drain(got, 32);
	int valuators = 0;
	pressed = 0;
	for (int i = 0; i < n; i++) {
		valuators += got[i].kind == INPUT_VALUATOR && !(got[i].flags & INPUT_F_STALE);
		pressed += got[i].kind == INPUT_BUTTON && got[i].value == 1;
	}
	assert_int_equal(valuators, 4);
	assert_int_equal(pressed, 1);
	assert_non_null(strstr(log_text(), "frames again on test0"));
}

static void
test_wrong_sizes_refused(void **state)
{
	(void)state;
	static const size_t sizes[] = { 1, 8, 15, 17, 24, 72 };
	for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++)
		send_bytes(sizes[i]);
	assert_int_equal(can_dev_read(&dev, 1000, &queue), 0);
	struct input_event_rec got[8];
	assert_int_equal(drain(got, 8), 0);
	assert_int_equal(dev.bad_size, 6);
	assert_int_equal(dev.frames, 0);
	const char *t = log_text();
	assert_non_null(strstr(t, "device fault: read of 1 bytes, not a 16-byte can_frame: refused"));
	assert_non_null(strstr(t, "read of 15 bytes"));
	/* rate-limited: five lines in the window, the rest counted */
	assert_int_equal(count_of(t, "not a 16-byte can_frame"), DEVLOG_BURST);
	/* the device reads on */
	uint8_t data[8] = { 0 };
	send_frame(0x181, data, 8);
	assert_int_equal(can_dev_read(&dev, 2000, &queue), 1);
	assert_true(drain(got, 8) > 0);
}

/* ---- the interface down and up, and gone ---- */

static int fake_errno;   /* the next recvmsg fails with this, once (0: the real one) */
static int fake_repeat;  /* ... this many times */

static ssize_t
fake_recvmsg(int fd, struct msghdr *msg, int flags)
{
	if (fake_errno && fake_repeat > 0) {
		fake_repeat--;
		errno = fake_errno;
		return -1;
	}
	return recvmsg(fd, msg, flags);
}

static void
test_enetdown_keeps_the_device(void **state)
{
	(void)state;
	dev.recvmsg_fn = fake_recvmsg;
	uint8_t data[8] = { 0x10, 0, 0, 0, 0x03, 0, 0, 0 }; /* Foot and Hand pressed */
	send_frame(0x181, data, 8);
	assert_int_equal(can_dev_read(&dev, 1000, &queue), 1);
	struct input_event_rec got[32];
	drain(got, 32);

	/* down: the kernel says ENETDOWN once per down */
	fake_errno = ENETDOWN;
	fake_repeat = 1;
	assert_int_equal(can_dev_read(&dev, 2000, &queue), 0);
	int n = drain(got, 32), released = 0;
	for (int i = 0; i < n; i++)
		released += got[i].kind == INPUT_BUTTON && got[i].value == 0;
	assert_int_equal(released, 2);
	assert_int_equal(dev.downs, 1);
	assert_int_equal(count_of(log_text(), "went down"), 1);
	assert_non_null(strstr(log_text(),
			       "interface test0 went down: 2 button(s) released"));
	/* up and down again with no frame between: said again, nothing left to release */
	fake_repeat = 1;
	assert_int_equal(can_dev_read(&dev, 2500, &queue), 0);
	assert_int_equal(drain(got, 32), 0);
	assert_int_equal(dev.downs, 2);
	assert_non_null(strstr(log_text(), "interface test0 went down: 0 button(s) released"));
	assert_int_equal(can_dev_fd(&dev) >= 0, 1);

	/* up: frames read on the same socket */
	send_frame(0x181, data, 8);
	assert_int_equal(can_dev_read(&dev, 3000, &queue), 1);
	n = drain(got, 32);
	int pressed = 0;
	for (int i = 0; i < n; i++)
		pressed += got[i].kind == INPUT_BUTTON && got[i].value == 1;
	assert_int_equal(pressed, 2);
	assert_int_equal(count_of(log_text(), "frames again"), 1);
	fake_errno = 0;
}

static void
test_enodev_removes(void **state)
{
	(void)state;
	dev.recvmsg_fn = fake_recvmsg;
	uint8_t data[8] = { 0, 0, 0, 0, 0x01, 0, 0, 0 };
	send_frame(0x181, data, 8);
	assert_int_equal(can_dev_read(&dev, 1000, &queue), 1);
	struct input_event_rec got[32];
	drain(got, 32);
	fake_errno = ENODEV;
	fake_repeat = 1;
	assert_int_equal(can_dev_read(&dev, 2000, &queue), -1);
	int n = drain(got, 32);
	assert_true(n >= 2);
	assert_int_equal(got[0].kind, INPUT_BUTTON);
	assert_int_equal(got[0].value, 0);
	assert_int_equal(got[n - 1].kind, INPUT_REMOVED);
	assert_int_equal(got[n - 1].code, INPUT_CLASS_PANEL);
	assert_int_equal(got[n - 1].device, 3);
	assert_non_null(strstr(log_text(), "panel (test0): device fault: interface test0 gone (No "
					    "such device); 1 button(s) released"));
	fake_errno = 0;
}

static void
test_peer_closed_removes(void **state)
{
	(void)state;
	close(peer);
	peer = -1;
	assert_int_equal(can_dev_read(&dev, 1000, &queue), -1);
	struct input_event_rec got[8];
	int n = drain(got, 8);
	assert_int_equal(n, 1);
	assert_int_equal(got[0].kind, INPUT_REMOVED);
	assert_non_null(strstr(log_text(), "gone (end of the stream)"));
}

/* a silent bus: dials stale after their stale= time, at the next read */
static void
test_stale_on_a_silent_bus(void **state)
{
	(void)state;
	uint8_t data[8] = { 0 };
	send_frame(0x181, data, 8);
	assert_int_equal(can_dev_read(&dev, 1000000, &queue), 1);
	struct input_event_rec got[32];
	drain(got, 32);
	/* panel.map: stale=150 on 0x181's lines */
	assert_int_equal(can_dev_read(&dev, 1000000 + 150000, &queue), 0);
	assert_int_equal(drain(got, 32), 0);
	assert_int_equal(can_dev_read(&dev, 1000000 + 150001, &queue), 0);
	int n = drain(got, 32), stale = 0;
	for (int i = 0; i < n; i++)
		stale += got[i].kind == INPUT_VALUATOR && (got[i].flags & INPUT_F_STALE);
	assert_int_equal(stale, 4);
}

static void
test_read_allocates_nothing(void **state)
{
	(void)state;
#if COUNT_ALLOCS
	uint8_t data[8] = { 1, 2, 3, 4, 5, 6, 7, 8 };
	for (int i = 0; i < 10; i++)
		send_frame(0x181, data, 8);
	send_frame(CAN_ERR_FLAG | CAN_ERR_BUSOFF, NULL, CAN_ERR_DLC);
	send_bytes(9);
	long before = allocs;
	can_dev_read(&dev, 1000, &queue);
	can_dev_read(&dev, 5000000, &queue);
	assert_int_equal(allocs, before);
#endif
}

/* ---- the error frame in words, by the kernel's header ---- */

static void
test_error_describe(void **state)
{
	(void)state;
	struct can_frame f;
	memset(&f, 0, sizeof f);
	char text[200];
	f.can_id = CAN_ERR_FLAG | CAN_ERR_BUSOFF;
	assert_int_equal(can_dev_error_describe((const uint8_t *)&f, text, sizeof text), 1);
	assert_string_equal(text, "bus-off");
	f.can_id = CAN_ERR_FLAG | CAN_ERR_RESTARTED;
	assert_int_equal(can_dev_error_describe((const uint8_t *)&f, text, sizeof text), 0);
	assert_string_equal(text, "controller restarted");
	f.can_id = CAN_ERR_FLAG | CAN_ERR_CRTL;
	f.data[1] = CAN_ERR_CRTL_RX_OVERFLOW | CAN_ERR_CRTL_TX_WARNING;
	can_dev_error_describe((const uint8_t *)&f, text, sizeof text);
	assert_string_equal(text, "controller problem, receive buffer overflow, transmit error "
				  "warning");
	f.can_id = CAN_ERR_FLAG;
	can_dev_error_describe((const uint8_t *)&f, text, sizeof text);
	assert_string_equal(text, "no class given (id 0x20000000)");
	/* a small buffer is cut, never overrun */
	char small[8];
	f.can_id = CAN_ERR_FLAG | CAN_ERR_BUSOFF | CAN_ERR_ACK;
	can_dev_error_describe((const uint8_t *)&f, small, sizeof small);
	assert_true(strlen(small) < sizeof small);
}

/* ---- the backend through the device set ---- */

static void
test_spec_errors_and_skips(void **state)
{
	(void)state;
	static struct input_devs s;
	char err[512] = "";
	input_devs_init(&s, input_backends, input_backends_count, 0, NULL);

	/* a malformed spec and a bad map are configuration errors: -1, the reason */
	assert_int_equal(input_devs_open(&s, "can:can0", 0, err, sizeof err), -1);
	assert_non_null(strstr(err, "expected can:IFACE:MAPFILE"));
	assert_int_equal(input_devs_open(&s, "can:can0:" DIR "panel.log", 0, err, sizeof err), -1);
	assert_non_null(strstr(err, DIR "panel.log:1: "));
	assert_int_equal(input_devs_open(&s, "can:can0:" DIR "nothing.map", 0, err, sizeof err),
			 -1);
	assert_non_null(strstr(err, DIR "nothing.map"));
	assert_int_equal(
		input_devs_open(&s, "can:abcdefghijklmnop:" DIR "panel.map", 0, err, sizeof err),
		-1);
	assert_non_null(strstr(err, "at most 15 characters"));
	assert_int_equal(s.nskip, 0);

	/* no CAN in the kernel (this build machine), or no such interface: a skip, 0 */
	int fd = socket(PF_CAN, SOCK_RAW, CAN_RAW);
	int no_can = fd < 0 && errno == EAFNOSUPPORT;
	if (fd >= 0)
		close(fd);
	assert_int_equal(input_devs_open(&s, "can:posture9:" DIR "panel.map", 0, err, sizeof err),
			 0);
	assert_int_equal(input_devs_count(&s), 0);
	assert_int_equal(s.nskip, 1);
	assert_string_equal(s.skip[0].what, "posture9");
	if (no_can)
		assert_string_equal(s.skip[0].why, "no CAN in this kernel (socket(PF_CAN): "
						   "Address family not supported by protocol)");
	else
		assert_string_equal(s.skip[0].why, "no such CAN interface");
	/* a rescan tries again, and says so again */
	assert_int_equal(input_devs_rescan(&s, 0), 0);
	assert_int_equal(s.nskip, 1);
	input_devs_close_all(&s, 0, NULL);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(test_log_frames_give_cantools_values, setup, teardown),
		cmocka_unit_test_setup_teardown(test_reads_capped, setup, teardown),
		cmocka_unit_test_setup_teardown(test_error_frames_counted_and_said, setup, teardown),
		cmocka_unit_test_setup_teardown(test_bus_off_releases_and_frames_resume, setup,
						teardown),
		cmocka_unit_test_setup_teardown(test_wrong_sizes_refused, setup, teardown),
		cmocka_unit_test_setup_teardown(test_enetdown_keeps_the_device, setup, teardown),
		cmocka_unit_test_setup_teardown(test_enodev_removes, setup, teardown),
		cmocka_unit_test_setup_teardown(test_peer_closed_removes, setup, teardown),
		cmocka_unit_test_setup_teardown(test_stale_on_a_silent_bus, setup, teardown),
		cmocka_unit_test_setup_teardown(test_read_allocates_nothing, setup, teardown),
		cmocka_unit_test(test_error_describe),
		cmocka_unit_test(test_spec_errors_and_skips),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
