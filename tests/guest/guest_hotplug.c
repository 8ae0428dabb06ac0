/*
 * guest_hotplug.c - run inside the test guest (tests/guest): devices
 * arriving and leaving while the device set runs, against the real kernel.
 * A uinput mouse is made after the set opened `auto`; the kernel's uevent
 * reaches the hot-plug monitor (source "kernel": the guest has no udevd),
 * the rescan opens the new node and nothing else, a press comes through,
 * and destroying the device mid-press releases the button and frees its
 * place. One line a check: "ok ..." or "FAIL ...: why"; the exit status
 * is the number of failures.
 */
#include <errno.h>
#include <fcntl.h>
#include <linux/uinput.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

#include "devices/hotplug.h"
#include "devices/input_backends.h"
#include "devices/input_devs.h"
#include "tests/guest/guest_check.h"

/* one record through uinput, a failure said */
static void
emit(int fd, int type, int code, int value)
{
	if (uinput_emit(fd, (unsigned)type, (unsigned)code, value) < 0)
		printf("uinput write: %s\n", strerror(errno));
}

static int
make_mouse(void)
{
	int fd = open("/dev/uinput", O_WRONLY | O_NONBLOCK | O_CLOEXEC);
	if (fd < 0)
		return -1;
	ioctl(fd, UI_SET_EVBIT, EV_KEY);
	ioctl(fd, UI_SET_KEYBIT, BTN_LEFT);
	ioctl(fd, UI_SET_KEYBIT, BTN_RIGHT);
	ioctl(fd, UI_SET_EVBIT, EV_REL);
	ioctl(fd, UI_SET_RELBIT, REL_X);
	ioctl(fd, UI_SET_RELBIT, REL_Y);
	struct uinput_setup us = { .id = { .bustype = BUS_USB, .vendor = 0x1234, .product = 0x5679 } };
	snprintf(us.name, sizeof us.name, "posture hotplug mouse");
	if (ioctl(fd, UI_DEV_SETUP, &us) < 0 || ioctl(fd, UI_DEV_CREATE) < 0) {
		close(fd);
		return -1;
	}
	return fd;
}

/* polls the monitor and the devices for up to ms, handling what comes; returns arrivals */
static int
pump(struct hotplug *h, struct input_devs *s, struct input_queue *q, int ms)
{
	int arrivals = 0;
	uint64_t end = now_us() + (uint64_t)ms * 1000u;
	while (now_us() < end) {
		struct pollfd fds[1 + INPUT_DEVS_POLL_MAX];
		int tags[INPUT_DEVS_POLL_MAX];
		fds[0] = (struct pollfd){ .fd = hotplug_fd(h), .events = POLLIN };
		int n = input_devs_pollfds(s, fds + 1, tags, INPUT_DEVS_POLL_MAX);
		if (poll(fds, (nfds_t)n + 1, 50) <= 0)
			continue;
		if (fds[0].revents) {
			int a = hotplug_read(h);
			if (a > 0) {
				arrivals += a;
				input_devs_rescan(s, now_us());
			}
		}
		for (int k = 0; k < n; k++)
			if (fds[k + 1].revents)
				input_devs_ready(s, tags[k], now_us(), q);
	}
	return arrivals;
}

/* the first queued event of kind (and code, unless -1), or 0 */
static int
find_event(struct input_queue *q, int kind, int code, struct input_event_rec *dest)
{
	struct input_event_rec e;
	while (input_queue_pop(q, &e))
		if (e.kind == kind && (code < 0 || e.code == code)) {
			*dest = e;
			return 1;
		}
	return 0;
}

int
main(void)
{
	static struct input_devs s;
	static struct input_queue q;
	struct hotplug h;
	char err[256];
	input_queue_init(&q);
	input_devs_init(&s, input_backends, input_backends_count, 0, &q);

	int rc = hotplug_open(&h, "kernel", err, sizeof err);
	check(rc == 0, "hotplug monitor on the kernel's uevents", "%s", err);
	if (rc < 0)
		return 1;
	check(hotplug_open(&(struct hotplug){ 0 }, "bluetooth", err, sizeof err) < 0 &&
		      strstr(err, "udev or kernel"),
	      "a source that is neither udev nor kernel is refused", "%s", err);

	int opened = input_devs_open(&s, "auto", now_us(), err, sizeof err);
	int before = input_devs_count(&s);
	check(opened >= 0, "auto before the mouse arrives", "%s", err);
	printf("# %d device(s) before: the guest's own keyboard and mouse, if any\n", before);
	struct input_event_rec e;
	while (input_queue_pop(&q, &e)) /* their arrivals */
		;

	int ufd = make_mouse();
	check(ufd >= 0, "uinput mouse made", "%s", strerror(errno));
	if (ufd < 0)
		return guest_failures;
	int arrivals = pump(&h, &s, &q, 1500);
	check(arrivals >= 1, "its arrival seen by the monitor", "%d arrivals", arrivals);
	int place = -1;
	for (int i = 0; i < INPUT_DEVS_MAX; i++)
		if (s.place[i].be && !strcmp(s.place[i].info.name, "posture hotplug mouse"))
			place = i;
	check(place >= 0 && input_devs_count(&s) == before + 1,
	      "the rescan opened the new mouse and nothing else", "place %d, %d devices", place,
	      input_devs_count(&s));
	if (place < 0)
		return guest_failures;
	check(s.place[place].info.cls == INPUT_CLASS_MOUSE && s.place[place].info.vendor == 0x1234 &&
		      s.place[place].info.product == 0x5679,
	      "it is a mouse with its id", "class %d id %04x:%04x", s.place[place].info.cls,
	      s.place[place].info.vendor, s.place[place].info.product);
	check(find_event(&q, INPUT_ADDED, -1, &e) && e.device == place, "INPUT_ADDED queued for it",
	      "none");

	emit(ufd, EV_KEY, BTN_LEFT, 1);
	emit(ufd, EV_REL, REL_X, 7);
	emit(ufd, EV_SYN, SYN_REPORT, 0);
	pump(&h, &s, &q, 300);
	check(find_event(&q, INPUT_BUTTON, BTN_LEFT, &e) && e.value == 1 && e.device == place,
	      "the press comes through", "none");

	/* unplugged mid-drag */
	ioctl(ufd, UI_DEV_DESTROY);
	close(ufd);
	arrivals = pump(&h, &s, &q, 800);
	check(arrivals == 0, "a removal is not an arrival", "%d arrivals", arrivals);
	check(find_event(&q, INPUT_BUTTON, BTN_LEFT, &e) && e.value == 0 && e.device == place,
	      "the held button released as an event", "none");
	check(find_event(&q, INPUT_REMOVED, -1, &e) && e.device == place, "INPUT_REMOVED queued",
	      "none");
	check(!s.place[place].be && input_devs_count(&s) == before, "its place is free again",
	      "%d devices", input_devs_count(&s));

	input_devs_close_all(&s, now_us(), NULL);
	hotplug_close(&h);
	printf("hotplug: %d failure(s)\n", guest_failures);
	return guest_status();
}
