/*
 * devlog.h - log lines that say who is at fault, rate-limited per source:
 * a device sending garbage at 1 kHz gives a few lines, then a count.
 * Time is a parameter (the caller's clock); nothing allocates.
 */
#ifndef POSTURE_DEVICES_DEVLOG_H
#define POSTURE_DEVICES_DEVLOG_H

#include <stdint.h>
#include <stdio.h>

#define DEVLOG_BURST 5            /* lines a source may write in one window */
#define DEVLOG_WINDOW_US 10000000 /* 10 s */

enum devlog_blame { DEVLOG_DEVICE, DEVLOG_KERNEL, DEVLOG_CLIENT, DEVLOG_FILE, DEVLOG_US };

struct devlog {
	char who[48];        /* "mouse (hidraw3)", "panel (can0)", ... */
	uint64_t window_t0;  /* start of the current window */
	unsigned lines;      /* written in the window */
	unsigned suppressed; /* not written since the last line that was */
	FILE *out;           /* NULL: stderr */
};

void devlog_init(struct devlog *l, const char *who);

/*
 * Writes "posture: <who>: <blame>: <message>" unless the source has used
 * its lines for this window; returns 1 when written, 0 when suppressed.
 */
int devlog(struct devlog *l, uint64_t now_us, enum devlog_blame blame, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));

/*
 * The same, written whatever the window holds: a source's last line (its
 * device gone), which comes once and says what became of it.
 */
int devlog_last(struct devlog *l, uint64_t now_us, enum devlog_blame blame, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));

#endif
