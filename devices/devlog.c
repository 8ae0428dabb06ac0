/* devlog.c - rate-limited log lines with a blame tag (see devlog.h) */
#include "devices/devlog.h"

#include <stdarg.h>
#include <string.h>

void
devlog_init(struct devlog *l, const char *who)
{
	memset(l, 0, sizeof *l);
	snprintf(l->who, sizeof l->who, "%s", who);
}

static const char *
blame_to_str(enum devlog_blame b)
{
	switch (b) {
	case DEVLOG_DEVICE:
		return "device fault";
	case DEVLOG_KERNEL:
		return "kernel";
	case DEVLOG_CLIENT:
		return "client fault";
	case DEVLOG_FILE:
		return "file fault";
	case DEVLOG_US:
		return "bug";
	}
	return "?";
}

static int
vdevlog(struct devlog *l, uint64_t now_us, int always, enum devlog_blame blame, const char *fmt,
	va_list ap)
{
	FILE *out = l->out ? l->out : stderr;
	if (now_us - l->window_t0 >= DEVLOG_WINDOW_US || now_us < l->window_t0) {
		if (l->suppressed)
			fprintf(out, "posture: %s: %u more lines suppressed\n", l->who, l->suppressed);
		l->window_t0 = now_us;
		l->lines = 0;
		l->suppressed = 0;
	}
	if (l->lines >= DEVLOG_BURST && !always) {
		l->suppressed++;
		return 0;
	}
	l->lines++;
	fprintf(out, "posture: %s: %s: ", l->who, blame_to_str(blame));
	vfprintf(out, fmt, ap);
	fputc('\n', out);
	return 1;
}

int
devlog(struct devlog *l, uint64_t now_us, enum devlog_blame blame, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	int r = vdevlog(l, now_us, 0, blame, fmt, ap);
	va_end(ap);
	return r;
}

int
devlog_last(struct devlog *l, uint64_t now_us, enum devlog_blame blame, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	int r = vdevlog(l, now_us, 1, blame, fmt, ap);
	va_end(ap);
	return r;
}
