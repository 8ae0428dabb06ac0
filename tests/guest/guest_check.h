/*
 * guest_check.h - what the kernel tier's guest programs (tests/guest/guest_*.c)
 * share: their one-line checks, the monotonic clock, a read with a timeout,
 * writing events through uinput, finding an input device's event node under
 * sysfs, and one turn of the daemon's loop over a device set.
 *
 * Checks print one line each, "ok <what>" or "FAIL <what>: <why>" (the pytest
 * wrappers match on those texts); guest_failures counts the FAIL lines and
 * guest_checks both kinds. A program ends with its own summary line and
 * returns guest_status(). Include after the project's headers.
 */
#ifndef POSTURE_GUEST_CHECK_H
#define POSTURE_GUEST_CHECK_H

#include <poll.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <dirent.h>
#include <time.h>
#include <unistd.h>

#include <linux/input.h>

#include "devices/input_devs.h"
#include "devices/queue.h"

static int guest_failures; /* FAIL lines so far */
static int guest_checks;   /* ok and FAIL lines so far */

static inline void ok(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static inline void fail(const char *what, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));
static inline void check(int cond, const char *what, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* one check's line, counted: head, "what: " when there is a what, then the text */
static inline void
check_line(const char *head, const char *what, const char *fmt, va_list ap)
{
	fputs(head, stdout);
	if (what)
		printf("%s: ", what);
	vprintf(fmt, ap);
	putchar('\n');
	fflush(stdout);
	guest_checks++;
}

/* "ok " and the text */
static inline void
ok(const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	check_line("ok ", NULL, fmt, ap);
	va_end(ap);
}

/* "FAIL what: " and the reason, counted as a failure */
static inline void
vfail(const char *what, const char *fmt, va_list ap)
{
	check_line("FAIL ", what, fmt, ap);
	guest_failures++;
}

static inline void
fail(const char *what, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vfail(what, fmt, ap);
	va_end(ap);
}

/* "ok what" when cond holds, else "FAIL what: " and the reason */
static inline void
check(int cond, const char *what, const char *fmt, ...)
{
	if (cond) {
		ok("%s", what);
		return;
	}
	va_list ap;
	va_start(ap, fmt);
	vfail(what, fmt, ap);
	va_end(ap);
}

/* the exit status: the number of failures, at most 100 */
static inline int
guest_status(void)
{
	return guest_failures > 100 ? 100 : guest_failures;
}

/* ---- time ---- */

static inline uint64_t
now_us(void)
{
	struct timespec t;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return (uint64_t)t.tv_sec * 1000000u + (uint64_t)t.tv_nsec / 1000u;
}

static inline void
sleep_ms(long ms)
{
	struct timespec t = { ms / 1000, (ms % 1000) * 1000000L };
	nanosleep(&t, NULL);
}

/* ---- evdev nodes and uinput ---- */

/* one record from an evdev node, waiting up to ms: 1, 0 when none came, or -1 */
static inline int
read_event(int fd, struct input_event *e, int ms)
{
	struct pollfd p = { .fd = fd, .events = POLLIN };
	if (poll(&p, 1, ms) <= 0)
		return 0;
	return read(fd, e, sizeof *e) == (ssize_t)sizeof *e ? 1 : -1;
}

/* the "eventN" child of a sysfs input device's folder, as /dev/input/eventN into node: 0, or -1 */
static inline int
event_node(const char *dir, char *node, size_t n)
{
	DIR *d = opendir(dir);
	if (!d)
		return -1;
	struct dirent *e;
	int found = -1;
	while ((e = readdir(d)) != NULL)
		if (!strncmp(e->d_name, "event", 5)) {
			snprintf(node, n, "/dev/input/%.32s", e->d_name);
			found = 0;
			break;
		}
	closedir(d);
	return found;
}

/* n records in one write to a uinput fd (one frame, as a driver sends it): 0, or -1 */
static inline int
uinput_write(int fd, const struct input_event *ev, size_t n)
{
	ssize_t w = write(fd, ev, n * sizeof *ev);
	return w == (ssize_t)(n * sizeof *ev) ? 0 : -1;
}

/* one record through uinput: 0, or -1 */
static inline int
uinput_emit(int fd, unsigned type, unsigned code, int value)
{
	struct input_event ev;
	memset(&ev, 0, sizeof ev);
	ev.type = (uint16_t)type;
	ev.code = (uint16_t)code;
	ev.value = value;
	return uinput_write(fd, &ev, 1);
}

/* ---- the device set ---- */

/*
 * One turn of the daemon's loop over s: its fds polled for up to ms (with
 * none, poll just waits), each ready one read into q. How many devices went
 * away, or -1 when nothing was ready in time.
 */
static inline int
poll_devs(struct input_devs *s, struct input_queue *q, int ms)
{
	struct pollfd fds[INPUT_DEVS_POLL_MAX];
	int tags[INPUT_DEVS_POLL_MAX];
	int n = input_devs_pollfds(s, fds, tags, INPUT_DEVS_POLL_MAX);
	if (poll(fds, (nfds_t)n, ms) <= 0)
		return -1;
	int gone = 0;
	for (int k = 0; k < n; k++)
		if (fds[k].revents && input_devs_ready(s, tags[k], now_us(), q) < 0)
			gone++;
	return gone;
}

#endif
