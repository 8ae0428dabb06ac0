/* evdev_dev.c - the evdev backend: open, fd, read into the decoder, close (see evdev_dev.h) */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

#include "devices/evdev_dev.h"
#include "devices/input_devs.h"
#include "devices/mouse_dpi.h"

static const size_t record_size = sizeof(struct input_event);

/* the class by the capabilities (see struct evdev_dev_info) */
static void
evdev_dev_classify(const struct libevdev *ev, struct evdev_dev_info *dest)
{
	dest->mouse = libevdev_has_event_code(ev, EV_REL, REL_X) &&
		      libevdev_has_event_code(ev, EV_REL, REL_Y) &&
		      libevdev_has_event_code(ev, EV_KEY, BTN_LEFT);
	/* the letters: KEY_A..KEY_Z are not one range of codes, so each is asked */
	static const uint16_t letters[] = {
		KEY_A, KEY_B, KEY_C, KEY_D, KEY_E, KEY_F, KEY_G, KEY_H, KEY_I,
		KEY_J, KEY_K, KEY_L, KEY_M, KEY_N, KEY_O, KEY_P, KEY_Q, KEY_R,
		KEY_S, KEY_T, KEY_U, KEY_V, KEY_W, KEY_X, KEY_Y, KEY_Z,
	};
	unsigned n = 0;
	for (size_t i = 0; i < sizeof letters / sizeof letters[0]; i++)
		n += libevdev_has_event_code(ev, EV_KEY, letters[i]) != 0;
	dest->keyboard = n == sizeof letters / sizeof letters[0];
	if (dest->mouse)
		dest->cls = INPUT_CLASS_MOUSE;
	else if (dest->keyboard)
		dest->cls = INPUT_CLASS_KEYBOARD;
	else
		dest->cls = INPUT_CLASS_OTHER;
}

/* opens path and reads its description: the fd (and *evp), or -1 with err */
static int
evdev_dev_open_described(const char *path, struct libevdev **evp, struct evdev_dev_info *info,
			 char *err, size_t errlen)
{
	int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
	if (fd < 0) {
		snprintf(err, errlen, "%s: %s", path, strerror(errno));
		return -1;
	}
	struct libevdev *ev = NULL;
	int rc = libevdev_new_from_fd(fd, &ev);
	if (rc < 0) {
		if (rc == -ENOTTY || rc == -EINVAL)
			snprintf(err, errlen, "%s: not an evdev device (%s)", path, strerror(-rc));
		else
			snprintf(err, errlen, "%s: cannot read the device's description: %s", path,
				 strerror(-rc));
		close(fd);
		return -1;
	}
	memset(info, 0, sizeof *info);
	snprintf(info->name, sizeof info->name, "%s",
		 libevdev_get_name(ev) ? libevdev_get_name(ev) : "");
	info->bustype = (uint16_t)libevdev_get_id_bustype(ev);
	info->vendor = (uint16_t)libevdev_get_id_vendor(ev);
	info->product = (uint16_t)libevdev_get_id_product(ev);
	info->version = (uint16_t)libevdev_get_id_version(ev);
	evdev_dev_classify(ev, info);
	*evp = ev;
	return fd;
}

int
evdev_dev_probe(const char *path, struct evdev_dev_info *dest, char *err, size_t errlen)
{
	struct libevdev *ev;
	int fd = evdev_dev_open_described(path, &ev, dest, err, errlen);
	if (fd < 0)
		return -1;
	libevdev_free(ev);
	close(fd);
	return 0;
}

int
evdev_dev_open(struct evdev_dev *d, const char *path, uint16_t device, int grab, char *err,
	       size_t errlen)
{
	memset(d, 0, offsetof(struct evdev_dev, buf));
	d->fd = -1;
	d->nlast = d->ntail = 0;
	d->reads = d->capped = d->resyncs = 0; /* after buf: not cleared above */
	struct libevdev *ev;
	int fd = evdev_dev_open_described(path, &ev, &d->info, err, errlen);
	if (fd < 0)
		return -1;
	snprintf(d->path, sizeof d->path, "%s", path);

	/* the decoder, named "name (eventN)" in log lines */
	const char *base = strrchr(path, '/');
	char who[sizeof d->in.log.who];
	snprintf(who, sizeof who, "%.24s (%.16s)", d->info.name[0] ? d->info.name : "evdev",
		 base ? base + 1 : path);
	evdev_input_init(&d->in, device, who);
	for (uint16_t c = ABS_X; c <= ABS_Y; c++) {
		const struct input_absinfo *a = libevdev_get_abs_info(ev, c);
		if (a && evdev_input_set_abs(&d->in, c, a->minimum, a->maximum) < 0)
			devlog(&d->in.log, 0, DEVLOG_DEVICE, "axis %u has an empty range %d..%d",
			       c, a->minimum, a->maximum);
	}

	/* timestamps on the daemon's clock */
	int clock = CLOCK_MONOTONIC;
	d->monotonic = ioctl(fd, EVIOCSCLOCKID, &clock) == 0;
	if (!d->monotonic)
		devlog(&d->in.log, 0, DEVLOG_KERNEL,
		       "no CLOCK_MONOTONIC timestamps (%s): the kernel's clock is used",
		       strerror(errno));

	d->fd = fd;
	d->evdev = ev;
	d->grab = grab != 0;
	if (grab && evdev_dev_set_grab(d, 1) < 0) {
		snprintf(err, errlen, "%s: cannot grab: %s", path,
			 errno == EBUSY ? "another reader holds the grab" : strerror(errno));
		libevdev_free(ev);
		close(fd);
		d->fd = -1;
		d->evdev = NULL;
		return -1;
	}
	return 0;
}

int
evdev_dev_adopt(struct evdev_dev *d, int fd, uint16_t device, const char *who, char *err,
		size_t errlen)
{
	memset(d, 0, offsetof(struct evdev_dev, buf));
	d->fd = -1;
	d->nlast = d->ntail = 0;
	d->reads = d->capped = d->resyncs = 0;
	int flags = fcntl(fd, F_GETFL);
	if (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0) {
		snprintf(err, errlen, "fd %d: %s", fd, strerror(errno));
		return -1;
	}
	snprintf(d->path, sizeof d->path, "%s", who);
	snprintf(d->info.name, sizeof d->info.name, "%s", who);
	d->info.cls = INPUT_CLASS_OTHER;
	evdev_input_init(&d->in, device, who);
	d->fd = fd;
	return 0;
}

int
evdev_dev_fd(const struct evdev_dev *d)
{
	return d->fd;
}

int
evdev_dev_set_grab(struct evdev_dev *d, int on)
{
	if (d->fd < 0)
		return -1;
	if (ioctl(d->fd, EVIOCGRAB, on ? 1 : 0) < 0)
		return -1;
	d->grabbed = on != 0;
	d->grab = on != 0;
	return 0;
}

/* the device is gone: release what it held, say so, queue INPUT_REMOVED */
static void
evdev_dev_gone(struct evdev_dev *d, uint64_t now_us, struct input_queue *q, int err)
{
	int released = evdev_input_release_all(&d->in, now_us, q);
	if (err)
		devlog(&d->in.log, now_us, err == EIO || err == ENODEV ? DEVLOG_DEVICE : DEVLOG_KERNEL,
		       "gone (%s); %d key(s) and button(s) released", strerror(err), released);
	else
		devlog(&d->in.log, now_us, DEVLOG_KERNEL,
		       "gone (end of the stream); %d key(s) and button(s) released", released);
	input_queue_removed(q, now_us, d->in.device, d->info.cls);
}

/* after SYN_DROPPED: the kernel's key state put right; unknown (ioctl refused) means all up */
static void
evdev_dev_resync(struct evdev_dev *d, uint64_t now_us, struct input_queue *q)
{
	uint8_t keys[EVDEV_INPUT_KEYBITS];
	memset(keys, 0, sizeof keys);
	if (ioctl(d->fd, EVIOCGKEY(sizeof keys), keys) < 0) {
		devlog(&d->in.log, now_us, DEVLOG_KERNEL,
		       "cannot read the key state after dropped events (%s): "
		       "every key and button released",
		       strerror(errno));
		memset(keys, 0, sizeof keys);
	}
	evdev_input_resync(&d->in, keys, now_us, q);
	d->resyncs++;
}

/* 1 when records are waiting in the kernel's buffer for this fd */
static int
evdev_dev_waiting(const struct evdev_dev *d)
{
	struct pollfd p = { .fd = d->fd, .events = POLLIN };
	return poll(&p, 1, 0) > 0 && (p.revents & POLLIN);
}

int
evdev_dev_read(struct evdev_dev *d, uint64_t now_us, struct input_queue *q)
{
	if (d->fd < 0)
		return -1;

	/* a split record's start, kept from the last call, goes first */
	if (d->ntail)
		memmove(d->buf, d->buf + d->nlast, d->ntail);
	size_t want = EVDEV_DEV_READ_MAX * record_size;
	ssize_t n = read(d->fd, d->buf + d->ntail, want);
	d->nlast = 0;
	if (n < 0) {
		if (errno == EINTR)
			return 0;
		if (errno == EAGAIN || errno == EWOULDBLOCK) {
			if (d->in.resync_wanted) /* nothing left waiting: see below */
				evdev_dev_resync(d, now_us, q);
			return 0;
		}
		evdev_dev_gone(d, now_us, q, errno);
		return -1;
	}
	if (n == 0) {
		/* the kernel's evdev never ends a stream: only a device gone does */
		evdev_dev_gone(d, now_us, q, 0);
		return -1;
	}

	/* whole records to the decoder, the rest kept */
	size_t have = d->ntail + (size_t)n;
	d->nlast = have - have % record_size;
	d->ntail = have % record_size;
	d->reads++;
	if ((size_t)n == want)
		d->capped++;
	evdev_input_feed(&d->in, d->buf, d->nlast, q);

	/*
	 * after SYN_DROPPED: EVIOCGKEY gives the key state after every record
	 * still waiting in the kernel's buffer (up to its size less one: 127 for
	 * a mouse, more than one read takes), so it is applied once they are
	 * decoded, or a press would come out before the motion that preceded it.
	 * A capped read leaves the resync to the call that finds the buffer
	 * empty; a record arriving between that and the ioctl is reflected early
	 * (the decoder then ignores its repeat of the new state).
	 */
	if (d->in.resync_wanted && ((size_t)n < want || !evdev_dev_waiting(d)))
		evdev_dev_resync(d, now_us, q);
	return (int)(d->nlast / record_size);
}

void
evdev_dev_close(struct evdev_dev *d, uint64_t now_us, struct input_queue *q)
{
	if (q)
		evdev_input_release_all(&d->in, now_us, q);
	if (d->evdev)
		libevdev_free(d->evdev);
	d->evdev = NULL;
	if (d->fd >= 0)
		close(d->fd); /* the grab ends with the file */
	d->fd = -1;
	d->grabbed = 0;
}

/* sets bit c of a bitmask in the kernel's byte layout */
static void
evdev_dev_set_bit(uint8_t *mask, unsigned c)
{
	mask[c / 8] |= (uint8_t)(1u << (c % 8));
}

void
evdev_dev_describe(const struct evdev_dev *d, struct rec_evemu *dest)
{
	const struct libevdev *ev = d->evdev;
	memset(dest, 0, sizeof *dest);
	dest->major = 1;
	dest->minor = 3;
	if (!ev)
		return;
	dest->described = 1;
	snprintf(dest->name, sizeof dest->name, "%s",
		 libevdev_get_name(ev) ? libevdev_get_name(ev) : "");
	dest->bustype = (uint16_t)libevdev_get_id_bustype(ev);
	dest->vendor = (uint16_t)libevdev_get_id_vendor(ev);
	dest->product = (uint16_t)libevdev_get_id_product(ev);
	dest->version = (uint16_t)libevdev_get_id_version(ev);
	for (unsigned p = 0; p < REC_EVEMU_PROP_BYTES * 8 && p <= INPUT_PROP_MAX; p++)
		if (libevdev_has_property(ev, p))
			evdev_dev_set_bit(dest->props, p);
	for (unsigned t = 0; t < EV_CNT; t++) {
		if (!libevdev_has_event_type(ev, t))
			continue;
		/* evemu's B: lines hold each type's codes, EV_SYN's too */
		int max = libevdev_event_type_get_max(t);
		for (int c = 0; c <= max && (unsigned)c < REC_EVEMU_MASK_BYTES * 8; c++)
			if (libevdev_has_event_code(ev, t, (unsigned)c))
				evdev_dev_set_bit(dest->bits[t], (unsigned)c);
	}
	for (unsigned c = 0; c < ABS_CNT; c++) {
		const struct input_absinfo *a = libevdev_get_abs_info(ev, c);
		if (!a || !libevdev_has_event_code(ev, EV_ABS, c))
			continue;
		dest->abs_given[c] = 1;
		dest->abs[c] = (struct rec_evemu_abs){ a->minimum, a->maximum, a->fuzz, a->flat,
						       a->resolution };
	}
	for (unsigned c = 0; c < LED_CNT; c++)
		if (libevdev_has_event_code(ev, EV_LED, c))
			dest->led[c] = libevdev_get_event_value(ev, EV_LED, c);
	for (unsigned c = 0; c < SW_CNT; c++)
		if (libevdev_has_event_code(ev, EV_SW, c))
			dest->sw[c] = libevdev_get_event_value(ev, EV_SW, c);
}

/* ---- the backend for the device set (devices/input_backend.h) ---- */

static int
evdev_backend_fd(const void *dev)
{
	return evdev_dev_fd(dev);
}

static int
evdev_backend_read(void *dev, uint64_t now_us, struct input_queue *q)
{
	return evdev_dev_read(dev, now_us, q) < 0 ? -1 : 0;
}

static void
evdev_backend_close(void *dev, uint64_t now_us, struct input_queue *q)
{
	evdev_dev_close(dev, now_us, q);
	free(dev);
}

static void
evdev_backend_stats(const void *dev, struct input_dev_stats *dest)
{
	const struct evdev_dev *d = dev;
	*dest = (struct input_dev_stats){ .reads = d->reads, .capped = d->capped,
					  .resyncs = d->resyncs,
					  .errors = d->in.short_records + d->in.unknown_events };
}

static int
evdev_backend_set_grab(void *dev, int on)
{
	return evdev_dev_set_grab(dev, on);
}

/* 1 when opened, 0 when skipped (with its reason) */
static int
evdev_backend_open_path(struct input_devs *s, const char *path, int only_pointing_and_keys)
{
	char err[256];
	if (input_devs_find(s, &input_backend_evdev, path) >= 0)
		return 0;
	int i = input_devs_free_place(s, path);
	if (i < 0)
		return 0;
	struct evdev_dev *d = malloc(sizeof *d);
	if (!d) {
		input_devs_skip(s, path, "out of memory");
		return 0;
	}
	if (evdev_dev_open(d, path, (uint16_t)i, s->grab, err, sizeof err) < 0) {
		input_devs_skip(s, path, err);
		free(d);
		return 0;
	}
	if (only_pointing_and_keys && d->info.cls == INPUT_CLASS_OTHER) {
		evdev_backend_close(d, 0, NULL);
		input_devs_skip(s, path, "neither a mouse nor a keyboard");
		return 0;
	}
	struct input_dev_info info = { .vendor = d->info.vendor, .product = d->info.product,
				       .iface = -1, .cls = d->info.cls, .grabbed = d->grabbed,
				       .dpi = mouse_dpi_of_node(path) };
	snprintf(info.path, sizeof info.path, "%s", path);
	snprintf(info.name, sizeof info.name, "%s", d->info.name);
	input_devs_put(s, i, &input_backend_evdev, d, &info);
	return 1;
}

/* every mouse and keyboard among the event nodes, in name order */
static int
evdev_backend_open_auto(struct input_devs *s)
{
	DIR *dir = opendir(s->input_dir);
	if (!dir) {
		input_devs_skip(s, "auto", "no input devices (the input directory cannot be read)");
		return 0;
	}
	char names[64][32];
	int n = 0;
	struct dirent *e;
	while ((e = readdir(dir)) && n < 64)
		if (!strncmp(e->d_name, "event", 5) && strlen(e->d_name) < sizeof names[0])
			snprintf(names[n++], sizeof names[0], "%.31s", e->d_name);
	closedir(dir);
	qsort(names, (size_t)n, sizeof names[0], (int (*)(const void *, const void *))strcmp);
	int opened = 0;
	for (int k = 0; k < n; k++) {
		char path[512];
		snprintf(path, sizeof path, "%.400s/%.31s", s->input_dir, names[k]);
		opened += evdev_backend_open_path(s, path, 1);
	}
	if (!n)
		input_devs_skip(s, "auto", "no input devices");
	return opened;
}

static int
evdev_backend_open_spec(struct input_devs *s, const char *arg, char *err, size_t errlen)
{
	(void)err;
	(void)errlen;
	return arg ? evdev_backend_open_path(s, arg, 0) : evdev_backend_open_auto(s);
}

/* the evemu file's head: the device's description, no events */
static int
evdev_backend_describe(const void *dev, FILE *out)
{
	struct rec_evemu r;
	memset(&r, 0, sizeof r);
	evdev_dev_describe(dev, &r);
	int rc = rec_evemu_write(out, &r);
	rec_evemu_free(&r);
	return rc;
}

const struct input_backend input_backend_evdev = {
	.name = "evdev",
	.usage = "evdev:PATH",
	.open_spec = evdev_backend_open_spec,
	.fd = evdev_backend_fd,
	.read = evdev_backend_read,
	.close = evdev_backend_close,
	.stats = evdev_backend_stats,
	.set_grab = evdev_backend_set_grab,
	.rec_format = "evemu",
	.describe = evdev_backend_describe,
};
