/*
 * test_input_devs.c - the device set over a table of backends (a fake
 * backend whose devices are socketpairs, so what "arrives" and "goes" is
 * under the test's control), the spec language and its errors, hot-plug
 * rescans, the shared-fd path libusb takes, the kiosk grab; and the small
 * pure parts beside it: MOUSE_DPI as systemd's hwdb writes it, flat motion
 * scaling with its remainders, the grab's escape chord.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <linux/input-event-codes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "devices/escape_chord.h"
#include "devices/input_devs.h"
#include "devices/motion_scale.h"
#include "devices/mouse_dpi.h"
#include "test_util.h"

/* ---- a fake backend: "fake:NAME" opens NAME when NAME is in the present list ---- */

struct fake_dev {
	int fd, peer;   /* the device reads fd; the test writes peer */
	int grabbed;
	int held;       /* a button held, released when gone */
	uint16_t device;
};

static const char *fake_present[8];
static int fake_shared_work_calls, fake_refuse_grab;
static const struct input_backend fake_backend, fake_shared_backend;

static int
fake_fd(const void *dev)
{
	return ((const struct fake_dev *)dev)->fd;
}

static int
fake_no_fd(const void *dev)
{
	(void)dev;
	return -1;
}

static void
fake_release(struct fake_dev *d, uint64_t now_us, struct input_queue *q)
{
	if (!d->held || !q)
		return;
	struct input_event_rec e = { .t_us = now_us, .device = d->device, .kind = INPUT_BUTTON,
				     .code = BTN_LEFT, .value = 0 };
	input_queue_push(q, &e);
	d->held = 0;
}

/* one byte a read: 'p' presses, anything else moves by it; the peer closed: gone */
static int
fake_read(void *dev, uint64_t now_us, struct input_queue *q)
{
	struct fake_dev *d = dev;
	unsigned char b;
	ssize_t n = recv(d->fd, &b, 1, MSG_DONTWAIT);
	if (n == 0) {
		fake_release(d, now_us, q);
		struct input_event_rec e = { .t_us = now_us, .device = d->device,
					     .kind = INPUT_REMOVED };
		input_queue_push(q, &e);
		return -1;
	}
	if (n < 0)
		return 0;
	struct input_event_rec e = { .t_us = now_us, .device = d->device };
	if (b == 'p') {
		e.kind = INPUT_BUTTON;
		e.code = BTN_LEFT;
		e.value = 1;
		d->held = 1;
	} else {
		e.kind = INPUT_MOTION;
		e.x = b;
	}
	input_queue_push(q, &e);
	return 1;
}

static void
fake_close(void *dev, uint64_t now_us, struct input_queue *q)
{
	struct fake_dev *d = dev;
	fake_release(d, now_us, q);
	close(d->fd);
	if (d->peer >= 0)
		close(d->peer);
	free(d);
}

static int
fake_set_grab(void *dev, int on)
{
	if (fake_refuse_grab)
		return -1;
	((struct fake_dev *)dev)->grabbed = on;
	return 0;
}

static int
fake_open_with(struct input_devs *s, const struct input_backend *be, const char *arg, char *err,
	       size_t errlen)
{
	if (arg && strchr(arg, '!')) {
		snprintf(err, errlen, "fake:%s: no '!' in a name", arg);
		return -1;
	}
	int opened = 0, found = 0;
	for (int k = 0; k < 8 && fake_present[k]; k++) {
		const char *name = fake_present[k];
		if (arg && strcmp(arg, name))
			continue;
		found = 1;
		if (input_devs_find(s, be, name) >= 0)
			continue;
		int i = input_devs_free_place(s, name);
		if (i < 0)
			continue;
		int sv[2];
		assert_int_equal(socketpair(AF_UNIX, SOCK_SEQPACKET, 0, sv), 0);
		struct fake_dev *d = calloc(1, sizeof *d);
		d->fd = sv[0];
		d->peer = sv[1];
		d->device = (uint16_t)i;
		d->grabbed = s->grab;
		struct input_dev_info info = { .iface = -1, .cls = INPUT_CLASS_MOUSE,
					       .grabbed = (uint8_t)s->grab, .dpi = 800 };
		snprintf(info.path, sizeof info.path, "%s", name);
		snprintf(info.name, sizeof info.name, "Fake %s", name);
		input_devs_put(s, i, be, d, &info);
		opened++;
	}
	if (arg && !found)
		input_devs_skip(s, arg, "not present");
	return opened;
}

static int
fake_open_spec(struct input_devs *s, const char *arg, char *err, size_t errlen)
{
	return fake_open_with(s, &fake_backend, arg, err, errlen);
}

static int
fake_shared_open_spec(struct input_devs *s, const char *arg, char *err, size_t errlen)
{
	return fake_open_with(s, &fake_shared_backend, arg, err, errlen);
}

static int fake_shared_fd = -1;

static int
fake_shared_fds(struct pollfd *fds, int max)
{
	if (max < 1 || fake_shared_fd < 0)
		return 0;
	fds[0] = (struct pollfd){ .fd = fake_shared_fd, .events = POLLIN };
	return 1;
}

static void
fake_shared_work(uint64_t now_us, struct input_queue *q)
{
	(void)now_us;
	(void)q;
	fake_shared_work_calls++;
}

static const struct input_backend fake_backend = {
	.name = "fake",
	.usage = "fake:NAME",
	.open_spec = fake_open_spec,
	.fd = fake_fd,
	.read = fake_read,
	.close = fake_close,
	.set_grab = fake_set_grab,
};

static const struct input_backend fake_shared_backend = {
	.name = "shared",
	.usage = "shared:NAME",
	.open_spec = fake_shared_open_spec,
	.fd = fake_no_fd,
	.read = fake_read,
	.close = fake_close,
	.shared_fds = fake_shared_fds,
	.shared_work = fake_shared_work,
};

static const struct input_backend *const fake_table[] = { &fake_backend, &fake_shared_backend };

static struct input_queue q;
static struct input_devs set;

static int
setup(void **unused)
{
	(void)unused;
	memset(fake_present, 0, sizeof fake_present);
	fake_shared_work_calls = fake_refuse_grab = 0;
	fake_shared_fd = -1;
	input_queue_init(&q);
	input_devs_init(&set, fake_table, 2, 0, &q);
	return 0;
}

static int
teardown(void **unused)
{
	(void)unused;
	input_devs_close_all(&set, 0, NULL);
	return 0;
}

static struct fake_dev *
dev_at(int i)
{
	assert_non_null(set.place[i].be);
	return set.place[i].dev;
}

/* ---- the set ---- */

static void
test_auto_opens_the_first_backends_devices_and_announces_them(void **unused)
{
	(void)unused;
	fake_present[0] = "m1";
	fake_present[1] = "m2";
	char err[256];
	assert_int_equal(input_devs_open(&set, "auto", 42, err, sizeof err), 2);
	assert_int_equal(input_devs_count(&set), 2);
	struct input_event_rec e;
	for (int k = 0; k < 2; k++) {
		assert_int_equal(input_queue_pop(&q, &e), 1);
		assert_int_equal(e.kind, INPUT_ADDED);
		assert_int_equal(e.device, k);
		assert_int_equal(e.code, INPUT_CLASS_MOUSE);
		assert_int_equal(e.t_us, 42);
	}
	assert_int_equal(input_devs_next_new(&set), 0);
	assert_int_equal(input_devs_next_new(&set), 1);
	assert_int_equal(input_devs_next_new(&set), -1);
	assert_string_equal(set.place[1].info.name, "Fake m2");
}

static void
test_a_spec_nobody_takes_is_refused_naming_every_form(void **unused)
{
	(void)unused;
	char err[256] = "";
	assert_int_equal(input_devs_open(&set, "bluetooth:aa", 0, err, sizeof err), -1);
	assert_string_equal(err, "input 'bluetooth:aa': expected auto, none, fake:NAME, shared:NAME");
	assert_int_equal(input_devs_open(&set, "fake:", 0, err, sizeof err), -1);
	assert_int_equal(input_devs_open(&set, "fake:a!b", 0, err, sizeof err), -1);
	assert_string_equal(err, "fake:a!b: no '!' in a name");
	assert_int_equal(set.nspec, 0); /* refused specs are not remembered */
	assert_int_equal(input_devs_open(&set, "none", 0, err, sizeof err), 0);
	assert_int_equal(input_devs_count(&set), 0);
}

static void
test_a_device_that_goes_releases_what_it_held_and_frees_its_place(void **unused)
{
	(void)unused;
	fake_present[0] = "m1";
	char err[256];
	assert_int_equal(input_devs_open(&set, "fake:m1", 0, err, sizeof err), 1);
	struct input_event_rec e;
	while (input_queue_pop(&q, &e))
		;
	struct fake_dev *d = dev_at(0);
	assert_int_equal(write(d->peer, "p", 1), 1);
	struct pollfd fds[INPUT_DEVS_POLL_MAX];
	int tags[INPUT_DEVS_POLL_MAX];
	assert_int_equal(input_devs_pollfds(&set, fds, tags, INPUT_DEVS_POLL_MAX), 1);
	assert_int_equal(tags[0], 0);
	assert_int_equal(fds[0].fd, d->fd);
	assert_int_equal(input_devs_ready(&set, tags[0], 5, &q), 0);
	assert_int_equal(input_queue_pop(&q, &e), 1);
	assert_true(e.kind == INPUT_BUTTON && e.value == 1);
	/* unplugged mid-drag */
	close(d->peer);
	d->peer = -1;
	assert_int_equal(input_devs_ready(&set, 0, 9, &q), -1);
	assert_int_equal(input_queue_pop(&q, &e), 1);
	assert_true(e.kind == INPUT_BUTTON && e.code == BTN_LEFT && e.value == 0);
	assert_int_equal(input_queue_pop(&q, &e), 1);
	assert_int_equal(e.kind, INPUT_REMOVED);
	assert_int_equal(input_queue_pop(&q, &e), 0); /* released once, not again at close */
	assert_null(set.place[0].be);
	assert_int_equal(input_devs_pollfds(&set, fds, tags, INPUT_DEVS_POLL_MAX), 0);
}

static void
test_a_rescan_opens_what_arrived_and_keeps_what_is_open(void **unused)
{
	(void)unused;
	char err[256];
	assert_int_equal(input_devs_open(&set, "fake:m2", 0, err, sizeof err), 0);
	assert_int_equal(set.nskip, 1);
	assert_string_equal(set.skip[0].what, "m2");
	assert_string_equal(set.skip[0].why, "not present");
	fake_present[0] = "m1";
	assert_int_equal(input_devs_open(&set, "auto", 0, err, sizeof err), 1);
	struct fake_dev *first = dev_at(0);
	/* m2 arrives */
	fake_present[1] = "m2";
	assert_int_equal(input_devs_rescan(&set, 7), 1);
	assert_ptr_equal(dev_at(0), first);     /* kept, not reopened */
	assert_string_equal(set.place[1].info.path, "m2");
	assert_int_equal(set.nskip, 0);         /* the skip is gone with its reason */
	assert_int_equal(input_devs_rescan(&set, 8), 0); /* nothing new: nothing opened */
	assert_int_equal(input_devs_count(&set), 2);
}

static void
test_skips_are_one_line_per_thing_and_the_set_has_a_size(void **unused)
{
	(void)unused;
	char err[256];
	const char *names[] = { "a", "b", "c", "d", "e", "f", "g", "h" };
	for (int k = 0; k < 8; k++)
		fake_present[k] = names[k];
	for (int r = 0; r < 3; r++) /* the same skip three times is one line */
		input_devs_open(&set, "fake:zz", 0, err, sizeof err);
	assert_int_equal(set.nskip, 1);
	/* 16 places: two specs of 8 devices each fill it, on different backends */
	assert_int_equal(input_devs_open(&set, "auto", 0, err, sizeof err), 8);
	assert_int_equal(input_devs_open(&set, "shared:a", 0, err, sizeof err), 1);
	for (int k = 1; k < 8; k++) {
		char spec[16];
		snprintf(spec, sizeof spec, "shared:%s", names[k]);
		assert_int_equal(input_devs_open(&set, spec, 0, err, sizeof err), 1);
	}
	assert_int_equal(input_devs_count(&set), INPUT_DEVS_MAX);
	fake_present[0] = "zz";
	assert_int_equal(input_devs_open(&set, "fake:zz", 0, err, sizeof err), 0);
	assert_string_equal(set.skip[0].why, "too many devices open");
}

static void
test_shared_fds_do_the_backends_work_then_read_its_devices(void **unused)
{
	(void)unused;
	int sv[2];
	assert_int_equal(socketpair(AF_UNIX, SOCK_SEQPACKET, 0, sv), 0);
	fake_shared_fd = sv[0];
	fake_present[0] = "u1";
	char err[256];
	assert_int_equal(input_devs_open(&set, "shared:u1", 0, err, sizeof err), 1);
	struct input_event_rec e;
	while (input_queue_pop(&q, &e))
		;
	struct pollfd fds[INPUT_DEVS_POLL_MAX];
	int tags[INPUT_DEVS_POLL_MAX];
	/* the device has no fd of its own: only the backend's shared one is polled */
	assert_int_equal(input_devs_pollfds(&set, fds, tags, INPUT_DEVS_POLL_MAX), 1);
	assert_int_equal(fds[0].fd, sv[0]);
	assert_int_equal(tags[0], INPUT_DEVS_MAX + 1);
	assert_int_equal(write(dev_at(0)->peer, "\x05", 1), 1);
	assert_int_equal(input_devs_ready(&set, tags[0], 3, &q), 0);
	assert_int_equal(fake_shared_work_calls, 1);
	assert_int_equal(input_queue_pop(&q, &e), 1);
	assert_true(e.kind == INPUT_MOTION && e.x == 5);
	/* a device the work found gone is reaped the same way */
	close(dev_at(0)->peer);
	dev_at(0)->peer = -1;
	assert_int_equal(input_devs_ready(&set, tags[0], 4, &q), -1);
	assert_int_equal(input_devs_count(&set), 0);
	close(sv[0]);
	close(sv[1]);
}

static void
test_the_grab_is_taken_on_open_and_given_up_on_every_device(void **unused)
{
	(void)unused;
	fake_present[0] = "k1";
	fake_present[1] = "k2";
	input_devs_init(&set, fake_table, 2, 1, &q);
	char err[256];
	assert_int_equal(input_devs_open(&set, "auto", 0, err, sizeof err), 2);
	assert_true(dev_at(0)->grabbed && set.place[1].info.grabbed);
	assert_int_equal(input_devs_set_grab(&set, 0), 0);
	assert_true(!dev_at(0)->grabbed && !dev_at(1)->grabbed && !set.place[0].info.grabbed);
	fake_refuse_grab = 1;
	assert_int_equal(input_devs_set_grab(&set, 1), -1);
	assert_false(set.place[0].info.grabbed);
}

/* ---- MOUSE_DPI: the forms of systemd's hwdb.d/70-mouse.hwdb ---- */

static void
test_mouse_dpi_takes_the_hwdb_forms(void **unused)
{
	(void)unused;
	/* one setting, with and without its report rate */
	assert_near(mouse_dpi_parse("1000@125"), 1000, 0);
	assert_near(mouse_dpi_parse("800"), 800, 0);
	/* several settings: the default one is marked '*' */
	assert_near(mouse_dpi_parse("400@125 *800@125 1600@125"), 800, 0);
	assert_near(mouse_dpi_parse("*1200@500 2400@500"), 1200, 0);
	assert_near(mouse_dpi_parse("  *3200  "), 3200, 0);
	/* refused: no default among several, two defaults, garbage, out of range */
	assert_true(mouse_dpi_parse("400 800") == 0);
	assert_true(mouse_dpi_parse("*400 *800") == 0);
	assert_true(mouse_dpi_parse("") == 0);
	assert_true(mouse_dpi_parse("fast") == 0);
	assert_true(mouse_dpi_parse("800@") == 0);
	assert_true(mouse_dpi_parse("800dpi") == 0);
	assert_true(mouse_dpi_parse("0@125") == 0);
	assert_true(mouse_dpi_parse("1000000") == 0);
	/* no udev entry (not a device node): the default */
	assert_near(mouse_dpi_of_node("/nonexistent/event0"), INPUT_DEV_DPI_DEFAULT, 0);
}

/* ---- flat motion with remainders ---- */

static void
test_motion_scale_normalises_by_dpi_and_loses_no_motion(void **unused)
{
	(void)unused;
	struct motion_scale a, b;
	motion_scale_init(&a, 400, 1);  /* 2.5 px a count */
	motion_scale_init(&b, 1600, 1); /* 0.625 px a count */
	long px, py, sa = 0, sb = 0;
	/* the same hand movement, one inch: 400 counts on one, 1600 on the other */
	for (int i = 0; i < 400; i++) {
		motion_scale_apply(&a, 1, 0, &px, &py);
		sa += px;
	}
	for (int i = 0; i < 1600; i++) {
		motion_scale_apply(&b, 1, 0, &px, &py);
		sb += px;
	}
	assert_int_equal(sa, 1000);
	assert_int_equal(sb, 1000);
	/* slow motion: 0.625 px a count is never rounded away */
	struct motion_scale c;
	motion_scale_init(&c, 1600, 1);
	long seen = 0;
	for (int i = 1; i <= 8; i++) {
		motion_scale_apply(&c, 1, -1, &px, &py);
		seen += px;
		assert_true(fabs((double)seen - 0.625 * i) < 1);
		assert_int_equal(px, -py);
	}
	assert_int_equal(seen, 5);
	/* a gain of 2 doubles it; no dpi means 1000 */
	motion_scale_init(&c, 0, 2);
	motion_scale_apply(&c, 3, -4, &px, &py);
	assert_int_equal(px, 6);
	assert_int_equal(py, -8);
}

/* ---- the escape chord ---- */

static struct input_event_rec
key(uint16_t code, int value)
{
	struct input_event_rec e = { .kind = INPUT_KEY, .code = code, .value = value };
	return e;
}

static void
test_ctrl_alt_backspace_and_nothing_else_is_the_escape(void **unused)
{
	(void)unused;
	struct escape_chord c = { 0 };
	struct input_event_rec e = key(KEY_BACKSPACE, 1);
	assert_int_equal(escape_chord_feed(&c, &e), 0); /* alone */
	e = key(KEY_LEFTCTRL, 1);
	escape_chord_feed(&c, &e);
	e = key(KEY_BACKSPACE, 1);
	assert_int_equal(escape_chord_feed(&c, &e), 0); /* Ctrl only */
	e = key(KEY_RIGHTALT, 1);
	escape_chord_feed(&c, &e);
	e = key(KEY_BACKSPACE, 2);
	assert_int_equal(escape_chord_feed(&c, &e), 0); /* a repeat is not a press */
	e = key(KEY_BACKSPACE, 1);
	assert_int_equal(escape_chord_feed(&c, &e), 1);
	e = key(KEY_RIGHTALT, 0);
	escape_chord_feed(&c, &e);
	e = key(KEY_BACKSPACE, 1);
	assert_int_equal(escape_chord_feed(&c, &e), 0); /* Alt let go */
	e = key(KEY_LEFTALT, 1);
	escape_chord_feed(&c, &e);
	e = key(KEY_LEFTCTRL, 0);
	escape_chord_feed(&c, &e);
	e = key(KEY_BACKSPACE, 1);
	assert_int_equal(escape_chord_feed(&c, &e), 0); /* Ctrl let go */
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(test_auto_opens_the_first_backends_devices_and_announces_them, setup, teardown),
		cmocka_unit_test_setup_teardown(test_a_spec_nobody_takes_is_refused_naming_every_form, setup, teardown),
		cmocka_unit_test_setup_teardown(test_a_device_that_goes_releases_what_it_held_and_frees_its_place, setup, teardown),
		cmocka_unit_test_setup_teardown(test_a_rescan_opens_what_arrived_and_keeps_what_is_open, setup, teardown),
		cmocka_unit_test_setup_teardown(test_skips_are_one_line_per_thing_and_the_set_has_a_size, setup, teardown),
		cmocka_unit_test_setup_teardown(test_shared_fds_do_the_backends_work_then_read_its_devices, setup, teardown),
		cmocka_unit_test_setup_teardown(test_the_grab_is_taken_on_open_and_given_up_on_every_device, setup, teardown),
		cmocka_unit_test(test_mouse_dpi_takes_the_hwdb_forms),
		cmocka_unit_test(test_motion_scale_normalises_by_dpi_and_loses_no_motion),
		cmocka_unit_test(test_ctrl_alt_backspace_and_nothing_else_is_the_escape),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
