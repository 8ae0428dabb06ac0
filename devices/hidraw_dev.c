/* hidraw_dev.c - the hidraw backend through hidapi: open, the reader thread, read, close
 * (see hidraw_dev.h) */
#include <errno.h>
#include <fcntl.h>
#include <hidapi/hidapi.h>
#include <linux/hidraw.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <time.h>
#include <unistd.h>
#include <wchar.h>

#include "devices/hidraw_dev.h"
#include "devices/input_devs.h"

/* what the reader thread and the loop share; the thread owns fd, the loop the rest */
struct hidraw_reader {
	hid_device *hid;
	pthread_t thread;
	int fd;                   /* the thread's end of the socketpair: closed by the thread */
	atomic_int stop;          /* set by hidraw_dev_close */
	atomic_int failed;        /* set by the thread, after why, when the device failed */
	char why[HIDRAW_DEV_WHY_MAX];
	uint8_t buf[HIDRAW_DEV_HEAD + HIDRAW_DEV_REPORT_MAX];
};

/* a hidapi wide string as ASCII ('?' for the rest) */
static void
hidraw_dev_narrow(const wchar_t *w, char *dest, size_t n)
{
	size_t k = 0;
	for (; w && *w && k + 1 < n; w++)
		dest[k++] = *w > 0 && *w < 0x7f ? (char)*w : '?';
	if (n)
		dest[k] = '\0';
}

static uint64_t
hidraw_dev_now_us(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

/* ---- finding and describing a node ---------------------------------------------------- */

int
hidraw_dev_parse_spec(const char *arg, uint16_t *vid, uint16_t *pid, int *iface,
		      const char **path, char *err, size_t errlen)
{
	*vid = *pid = 0;
	*iface = -1;
	*path = NULL;
	if (!arg || !*arg) {
		snprintf(err, errlen, "hidraw: expected VID:PID[:IFACE] or a /dev/hidrawN path");
		return -1;
	}
	if (arg[0] == '/') {
		*path = arg;
		return 0;
	}
	unsigned long v[3];
	int n = 0;
	const char *p = arg;
	int colon = 0; /* the last thing read was a ':' */
	while (n < 3) {
		char *end;
		if (!((*p >= '0' && *p <= '9') || (n < 2 && ((*p >= 'a' && *p <= 'f') ||
							 (*p >= 'A' && *p <= 'F')))))
			break;
		v[n] = strtoul(p, &end, n < 2 ? 16 : 10);
		if (end == p || (n < 2 && (end - p > 4 || v[n] > 0xffff)) || (n == 2 && v[n] > 255))
			break;
		n++;
		p = end;
		colon = *p == ':';
		if (!colon)
			break;
		p++;
	}
	if (n < 2 || *p || colon) {
		snprintf(err, errlen,
			 "hidraw:%.60s: expected VID:PID[:IFACE] (hex ids, a decimal interface) "
			 "or a /dev/hidrawN path",
			 arg);
		return -1;
	}
	*vid = (uint16_t)v[0];
	*pid = (uint16_t)v[1];
	*iface = n == 3 ? (int)v[2] : -1;
	return 0;
}

int
hidraw_dev_enumerate(uint16_t vid, uint16_t pid, int iface, struct hidraw_dev_found *dest,
		     int max, char *err, size_t errlen)
{
	struct hid_device_info *all = hid_enumerate(vid, pid);
	if (!all) {
		/* 0.13.1 says "none" and "cannot enumerate" the same way: its message tells */
		hidraw_dev_narrow(hid_error(NULL), err, errlen);
		return 0;
	}
	int n = 0;
	for (const struct hid_device_info *e = all; e; e = e->next) {
		int mouse = e->usage_page == 0x01 && e->usage == 0x02;
		int keyboard = e->usage_page == 0x01 && e->usage == 0x06;
		if (!(mouse || keyboard) || !e->path || (iface >= 0 && e->interface_number != iface))
			continue;
		/* one node per path: 0.13.1 lists every collection, nested ones too */
		int k = 0;
		while (k < n && strcmp(dest[k].path, e->path))
			k++;
		if (k == n) {
			if (n == max || strlen(e->path) >= sizeof dest[k].path)
				continue;
			memset(&dest[k], 0, sizeof dest[k]);
			snprintf(dest[k].path, sizeof dest[k].path, "%s", e->path);
			dest[k].vendor = e->vendor_id;
			dest[k].product = e->product_id;
			dest[k].iface = e->interface_number;
			n++;
		}
		dest[k].mouse |= (uint8_t)mouse;
		dest[k].keyboard |= (uint8_t)keyboard;
	}
	hid_free_enumeration(all);
	if (!n)
		snprintf(err, errlen, "no hidraw mouse or keyboard matches");
	return n;
}

/* the sysfs folder of the node's HID device: /sys/class/hidraw/hidrawN/device */
static void
hidraw_dev_sysfs(const char *path, const char *file, char *dest, size_t n)
{
	const char *base = strrchr(path, '/');
	snprintf(dest, n, "/sys/class/hidraw/%.64s/device/%s", base ? base + 1 : path, file);
}

/* the report descriptor: sysfs, else HIDIOCGRDESC; its length, or -1 with err */
static int
hidraw_dev_read_desc(const char *path, uint8_t *dest, char *err, size_t errlen)
{
	char sys[INPUT_DEV_PATH_MAX + 64];
	hidraw_dev_sysfs(path, "report_descriptor", sys, sizeof sys);
	int fd = open(sys, O_RDONLY | O_CLOEXEC);
	if (fd >= 0) {
		ssize_t n = read(fd, dest, HID_DESC_MAX_BYTES);
		close(fd);
		if (n > 0)
			return (int)n;
	}
	/* the node's own answer */
	fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
	if (fd < 0) {
		snprintf(err, errlen, "%s: %s", path, strerror(errno));
		return -1;
	}
	int size = 0;
	static struct hidraw_report_descriptor rd; /* 4 KiB: the loop's thread only */
	if (ioctl(fd, HIDIOCGRDESCSIZE, &size) < 0 || size <= 0 || size > HID_MAX_DESCRIPTOR_SIZE) {
		snprintf(err, errlen, "%s: no report descriptor (sysfs, HIDIOCGRDESCSIZE: %s)", path,
			 size > 0 ? "too long" : strerror(errno));
		close(fd);
		return -1;
	}
	memset(&rd, 0, sizeof rd);
	rd.size = (uint32_t)size;
	if (ioctl(fd, HIDIOCGRDESC, &rd) < 0) {
		snprintf(err, errlen, "%s: no report descriptor (HIDIOCGRDESC: %s)", path,
			 strerror(errno));
		close(fd);
		return -1;
	}
	close(fd);
	memcpy(dest, rd.value, (size_t)size);
	return size;
}

/* HID_NAME, HID_PHYS and HID_ID of the node's HID device (what is missing stays empty) */
static void
hidraw_dev_read_uevent(const char *path, struct hidraw_dev_info *info)
{
	char sys[INPUT_DEV_PATH_MAX + 64], text[2048];
	hidraw_dev_sysfs(path, "uevent", sys, sizeof sys);
	int fd = open(sys, O_RDONLY | O_CLOEXEC);
	if (fd < 0)
		return;
	ssize_t n = read(fd, text, sizeof text - 1);
	close(fd);
	if (n <= 0)
		return;
	text[n] = '\0';
	for (char *line = text, *next; line && *line; line = next) {
		next = strchr(line, '\n');
		if (next)
			*next++ = '\0';
		unsigned bus, vid, pid;
		if (!strncmp(line, "HID_NAME=", 9))
			snprintf(info->name, sizeof info->name, "%s", line + 9);
		else if (!strncmp(line, "HID_PHYS=", 9))
			snprintf(info->phys, sizeof info->phys, "%s", line + 9);
		else if (sscanf(line, "HID_ID=%x:%x:%x", &bus, &vid, &pid) == 3) {
			info->bus = (uint16_t)bus;
			info->vendor = (uint16_t)vid;
			info->product = (uint16_t)pid;
		}
	}
}

/* the class by the top-level Application collections (see struct hidraw_dev_info) */
static void
hidraw_dev_classify(const struct hid_desc *desc, struct hidraw_dev_info *info)
{
	info->mouse = info->keyboard = 0;
	for (unsigned c = 0; c < desc->ncollections; c++) {
		const struct hid_desc_collection *col = &desc->collections[c];
		if (col->depth || col->type != HID_COLLECTION_APPLICATION)
			continue;
		info->mouse |= col->usage == HID_USAGE_GD_MOUSE;
		info->keyboard |= col->usage == HID_USAGE_GD_KEYBOARD;
	}
	info->cls = info->mouse	     ? INPUT_CLASS_MOUSE
		    : info->keyboard ? INPUT_CLASS_KEYBOARD
				     : INPUT_CLASS_OTHER;
}

static void
hidraw_dev_reset(struct hidraw_dev *d)
{
	memset(d, 0, offsetof(struct hidraw_dev, buf));
	d->fd = -1;
	d->info.iface = -1;
}

/* d->desc_bytes[0..desc_len) parsed, the class, the decoder; -1 with err when refused */
static int
hidraw_dev_setup(struct hidraw_dev *d, const char *path, uint16_t device, char *err,
		 size_t errlen)
{
	char why[200];
	const char *base = strrchr(path, '/');
	char who[sizeof d->in.log.who];
	snprintf(who, sizeof who, "%.24s (%.16s)", d->info.name[0] ? d->info.name : "hidraw",
		 base ? base + 1 : path);
	if (hid_desc_parse(d->desc_bytes, d->desc_len, &d->desc, why, sizeof why) < 0) {
		/* the device stays closed: a log line that blames it, and the reason */
		struct devlog log;
		devlog_init(&log, who);
		devlog(&log, 0, DEVLOG_DEVICE, "report descriptor refused: %s; not opened", why);
		snprintf(err, errlen, "%s: report descriptor refused: %s", path, why);
		return -1;
	}
	hidraw_dev_classify(&d->desc, &d->info);
	hid_input_init(&d->in, &d->desc, device, who);
	return 0;
}

/* ---- the Resolution Multipliers -------------------------------------------------------- */

/* value's low size bits at bit offset of data (little-endian, as HID lays fields out) */
static void
hidraw_dev_put_bits(uint8_t *data, unsigned offset, unsigned size, uint32_t value)
{
	for (unsigned i = 0; i < size; i++) {
		unsigned bit = offset + i;
		if (value >> i & 1)
			data[bit / 8] |= (uint8_t)(1u << (bit % 8));
		else
			data[bit / 8] &= (uint8_t) ~(1u << (bit % 8));
	}
}

/*
 * The fields a multiplier governs get its value (hid_desc.c's apply_multiplier,
 * the kernel's hid_apply_multiplier): the input fields inside its nearest
 * Logical collection, or its top-level one.
 */
static void
hidraw_dev_apply(struct hid_desc *desc, const struct hid_desc_multiplier *m)
{
	if (m->collection == HID_DESC_NONE)
		return;
	uint16_t mc = m->collection;
	while (desc->collections[mc].parent != HID_DESC_NONE &&
	       desc->collections[mc].type != HID_COLLECTION_LOGICAL)
		mc = desc->collections[mc].parent;
	for (unsigned i = 0; i < desc->nfields; i++) {
		struct hid_desc_field *f = &desc->fields[i];
		uint16_t c = f->collection;
		if (c == HID_DESC_NONE)
			continue;
		while (desc->collections[c].parent != HID_DESC_NONE && c != mc)
			c = desc->collections[c].parent;
		if (desc->collections[c].parent != HID_DESC_NONE)
			f->resolution_multiplier = (int16_t)m->effective;
	}
}

int
hidraw_dev_set_multipliers(struct hidraw_dev *d, hidraw_dev_feature_fn feature, void *ctx)
{
	struct hid_desc *desc = &d->desc;
	uint8_t ok[HID_DESC_MAX_MULTIPLIERS] = { 0 }, done[HID_DESC_MAX_MULTIPLIERS] = { 0 };
	/*
	 * the id byte and the report: no longer than the kernel's
	 * HID_MAX_BUFFER_SIZE (4096 on 6.1), or HIDIOCGFEATURE fails with EINVAL
	 */
	uint8_t rep[HIDRAW_DEV_REPORT_MAX];
	int written = 0;

	/* one GET and one SET a feature report, all its multipliers set, as the kernel does */
	for (unsigned i = 0; i < desc->nmultipliers; i++) {
		if (done[i])
			continue;
		uint8_t id = desc->multipliers[i].report_id;
		size_t need = 1;
		for (unsigned k = i; k < desc->nmultipliers; k++)
			if (desc->multipliers[k].report_id == id) {
				const struct hid_desc_multiplier *m = &desc->multipliers[k];
				size_t end = 1 + ((size_t)m->bit_offset + m->size + 7) / 8;
				need = end > need ? end : need;
			}
		int rc = -1;
		if (need <= sizeof rep) {
			/* the report as the device has it, its other fields kept; else zeros */
			memset(rep, 0, sizeof rep);
			rep[0] = id;
			int got = feature(ctx, 0, rep, sizeof rep);
			size_t len = got > 0 && (size_t)got >= need ? (size_t)got : need;
			if (got <= 0 || (size_t)got < need) {
				memset(rep, 0, sizeof rep);
				rep[0] = id;
			}
			for (unsigned k = i; k < desc->nmultipliers; k++) {
				const struct hid_desc_multiplier *m = &desc->multipliers[k];
				if (m->report_id == id)
					hidraw_dev_put_bits(rep + 1, m->bit_offset, m->size,
							    (uint32_t)m->logical_max);
			}
			rc = feature(ctx, 1, rep, len);
		}
		for (unsigned k = i; k < desc->nmultipliers; k++) {
			if (desc->multipliers[k].report_id != id)
				continue;
			done[k] = 1;
			ok[k] = rc >= 0;
			if (rc >= 0) {
				written++;
				d->multipliers_set++;
			} else {
				d->multipliers_refused++;
			}
		}
		if (rc < 0)
			devlog(&d->in.log, 0, DEVLOG_DEVICE,
			       "the Resolution Multiplier (feature report %u) was not written: "
			       "its wheels report whole detents",
			       id);
	}

	/* the wheels count as the multipliers written say; the others in whole detents */
	for (unsigned i = 0; i < desc->nfields; i++)
		desc->fields[i].resolution_multiplier = 1;
	for (unsigned k = 0; k < desc->nmultipliers; k++)
		if (ok[k])
			hidraw_dev_apply(desc, &desc->multipliers[k]);
	return written;
}

static int
hidraw_dev_hidapi_feature(void *ctx, int set, uint8_t *buf, size_t n)
{
	hid_device *h = ctx;
	return set ? hid_send_feature_report(h, buf, n) : hid_get_feature_report(h, buf, n);
}

/* ---- the reader thread ------------------------------------------------------------------ */

/* the device failed: why, for the loop, then the flag */
static void
hidraw_reader_fail(struct hidraw_reader *r, const char *what)
{
	char text[HIDRAW_DEV_WHY_MAX - 32];
	hidraw_dev_narrow(hid_error(r->hid), text, sizeof text);
	snprintf(r->why, sizeof r->why, "%s: %s", what, text);
	atomic_store(&r->failed, 1);
}

static void *
hidraw_reader_main(void *arg)
{
	struct hidraw_reader *r = arg;
	while (!atomic_load(&r->stop)) {
		int n = hid_read_timeout(r->hid, r->buf + HIDRAW_DEV_HEAD, HIDRAW_DEV_REPORT_MAX,
					 HIDRAW_DEV_POLL_MS);
		if (n == 0)
			continue; /* the timeout: look at the stop flag */
		if (n < 0) {
			hidraw_reader_fail(r, "read");
			break;
		}
		uint64_t t = hidraw_dev_now_us();
		memcpy(r->buf, &t, sizeof t);
		/* blocks while the loop is behind; the loop's end closing wakes it (EPIPE) */
		ssize_t sent;
		while ((sent = send(r->fd, r->buf, HIDRAW_DEV_HEAD + (size_t)n, MSG_NOSIGNAL)) < 0 &&
		       (errno == EINTR || errno == EAGAIN) && !atomic_load(&r->stop))
			;
		if (sent < 0)
			break; /* the loop has closed its end */
	}
	close(r->fd); /* the loop reads the end of the stream */
	r->fd = -1;
	return NULL;
}

/* the socketpair and the thread, for d's open hid_device h; -1 with err */
static int
hidraw_reader_start(struct hidraw_dev *d, hid_device *h, char *err, size_t errlen)
{
	struct hidraw_reader *r = calloc(1, sizeof *r);
	if (!r) {
		snprintf(err, errlen, "%s: out of memory", d->path);
		return -1;
	}
	int sv[2];
	if (socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, sv) < 0) {
		snprintf(err, errlen, "%s: socketpair: %s", d->path, strerror(errno));
		free(r);
		return -1;
	}
	/* the loop's end never blocks; the thread's waits (with a timeout to see a stop) */
	struct timeval tv = { .tv_sec = 0, .tv_usec = HIDRAW_DEV_POLL_MS * 1000 };
	setsockopt(sv[1], SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
	fcntl(sv[0], F_SETFL, fcntl(sv[0], F_GETFL) | O_NONBLOCK);
	r->hid = h;
	r->fd = sv[1];
	atomic_init(&r->stop, 0);
	atomic_init(&r->failed, 0);

	/* every signal blocked in the thread: the loop's thread takes them */
	sigset_t all, old;
	sigfillset(&all);
	pthread_sigmask(SIG_SETMASK, &all, &old);
	int rc = pthread_create(&r->thread, NULL, hidraw_reader_main, r);
	pthread_sigmask(SIG_SETMASK, &old, NULL);
	if (rc) {
		snprintf(err, errlen, "%s: cannot start the reader: %s", d->path, strerror(rc));
		close(sv[0]);
		close(sv[1]);
		free(r);
		return -1;
	}
	d->fd = sv[0];
	d->reader = r;
	return 0;
}

/* ---- open, read, close ---------------------------------------------------------------- */

int
hidraw_dev_open(struct hidraw_dev *d, const char *path, int iface, uint16_t device, char *err,
		size_t errlen)
{
	hidraw_dev_reset(d);
	snprintf(d->path, sizeof d->path, "%s", path);
	d->info.iface = iface;
	int n = hidraw_dev_read_desc(path, d->desc_bytes, err, errlen);
	if (n < 0)
		return -1;
	d->desc_len = (uint16_t)n;
	hidraw_dev_read_uevent(path, &d->info);
	if (hidraw_dev_setup(d, path, device, err, errlen) < 0)
		return -1;

	hid_device *h = hid_open_path(path);
	if (!h) {
		char why[128];
		hidraw_dev_narrow(hid_error(NULL), why, sizeof why);
		snprintf(err, errlen, "%s: hidapi cannot open it: %s", path, why);
		return -1;
	}
	if (!d->info.name[0]) { /* no uevent: hidapi's product string */
		wchar_t w[REC_HID_MAX_NAME];
		if (hid_get_product_string(h, w, REC_HID_MAX_NAME) == 0)
			hidraw_dev_narrow(w, d->info.name, sizeof d->info.name);
	}
	/* before the thread starts: from then on it is the hid_device's only user */
	hidraw_dev_set_multipliers(d, hidraw_dev_hidapi_feature, h);
	if (hidraw_reader_start(d, h, err, errlen) < 0) {
		hid_close(h);
		return -1;
	}
	return 0;
}

int
hidraw_dev_adopt(struct hidraw_dev *d, int fd, const uint8_t *desc, size_t n, uint16_t device,
		 const char *who, char *err, size_t errlen)
{
	hidraw_dev_reset(d);
	snprintf(d->path, sizeof d->path, "%s", who);
	snprintf(d->info.name, sizeof d->info.name, "%s", who);
	if (n > HID_DESC_MAX_BYTES) {
		snprintf(err, errlen, "%s: report descriptor refused: longer than %d bytes", who,
			 HID_DESC_MAX_BYTES);
		return -1;
	}
	memcpy(d->desc_bytes, desc, n);
	d->desc_len = (uint16_t)n;
	if (hidraw_dev_setup(d, who, device, err, errlen) < 0)
		return -1;
	int flags = fcntl(fd, F_GETFL);
	if (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0) {
		snprintf(err, errlen, "fd %d: %s", fd, strerror(errno));
		return -1;
	}
	d->fd = fd;
	return 0;
}

int
hidraw_dev_fd(const struct hidraw_dev *d)
{
	return d->fd;
}

/* the device is gone: release what it held, say why, queue INPUT_REMOVED */
static void
hidraw_dev_gone(struct hidraw_dev *d, uint64_t now_us, struct input_queue *q, const char *why,
		enum devlog_blame blame)
{
	int held = 0;
	for (unsigned c = 0; c < HID_INPUT_CODES; c++)
		held += d->in.held[c] != 0;
	hid_input_release_all(&d->in, now_us, q);
	devlog_last(&d->in.log, now_us, blame, "gone (%s); %d key(s) and button(s) released", why, held);
	input_queue_removed(q, now_us, d->in.device, d->info.cls);
}

int
hidraw_dev_read(struct hidraw_dev *d, uint64_t now_us, struct input_queue *q)
{
	if (d->fd < 0)
		return -1;
	int k = 0;
	while (k < HIDRAW_DEV_READ_MAX) {
		ssize_t n = recv(d->fd, d->buf, sizeof d->buf, MSG_DONTWAIT | MSG_TRUNC);
		if (n < 0) {
			if (errno == EAGAIN || errno == EWOULDBLOCK)
				break;
			if (errno == EINTR)
				continue;
			char why[64];
			snprintf(why, sizeof why, "%s", strerror(errno));
			hidraw_dev_gone(d, now_us, q, why, DEVLOG_KERNEL);
			return -1;
		}
		if (n == 0) {
			/* the end of the stream: the reader stopped, and says why */
			struct hidraw_reader *r = d->reader;
			if (r && atomic_load(&r->failed))
				hidraw_dev_gone(d, now_us, q, r->why, DEVLOG_DEVICE);
			else
				hidraw_dev_gone(d, now_us, q, "end of the stream", DEVLOG_KERNEL);
			return -1;
		}
		k++;
		if ((size_t)n < HIDRAW_DEV_HEAD || (size_t)n > sizeof d->buf) {
			d->bad++;
			devlog(&d->in.log, now_us, DEVLOG_KERNEL,
			       "a datagram of %zd bytes dropped (%d to %zu expected)", n,
			       HIDRAW_DEV_HEAD, sizeof d->buf);
			continue;
		}
		uint64_t t;
		memcpy(&t, d->buf, sizeof t);
		const uint8_t *report = d->buf + HIDRAW_DEV_HEAD;
		size_t len = (size_t)n - HIDRAW_DEV_HEAD;
		if (d->tap)
			d->tap(d->tap_ctx, t, report, len);
		hid_input_feed(&d->in, report, len, t, q);
		d->reports++;
	}
	if (k) {
		d->reads++;
		if (k == HIDRAW_DEV_READ_MAX)
			d->capped++;
	}
	return k;
}

void
hidraw_dev_close(struct hidraw_dev *d, uint64_t now_us, struct input_queue *q)
{
	if (q && d->in.d)
		hid_input_release_all(&d->in, now_us, q);
	struct hidraw_reader *r = d->reader;
	if (r) {
		/* stop flag, the loop's end (wakes a send), join, then the device, then free */
		atomic_store(&r->stop, 1);
		if (d->fd >= 0)
			close(d->fd);
		d->fd = -1;
		pthread_join(r->thread, NULL);
		hid_close(r->hid);
		free(r);
		d->reader = NULL;
	}
	if (d->fd >= 0)
		close(d->fd);
	d->fd = -1;
}

void
hidraw_dev_describe(const struct hidraw_dev *d, struct rec_hid_device *dest)
{
	memset(dest, 0, sizeof *dest);
	snprintf(dest->name, sizeof dest->name, "%s", d->info.name);
	snprintf(dest->phys, sizeof dest->phys, "%s", d->info.phys);
	dest->bus = d->info.bus;
	dest->vid = d->info.vendor;
	dest->pid = d->info.product;
	dest->desc_len = d->desc_len;
	memcpy(dest->desc, d->desc_bytes, d->desc_len);
}

/* ---- the backend for the device set (devices/input_backend.h) ---------------------------- */

static int
hidraw_backend_fd(const void *dev)
{
	return hidraw_dev_fd(dev);
}

static int
hidraw_backend_read(void *dev, uint64_t now_us, struct input_queue *q)
{
	return hidraw_dev_read(dev, now_us, q) < 0 ? -1 : 0;
}

static void
hidraw_backend_close(void *dev, uint64_t now_us, struct input_queue *q)
{
	hidraw_dev_close(dev, now_us, q);
	free(dev);
}

/* 1 when opened, 0 when skipped (with its reason) */
static int
hidraw_backend_open_path(struct input_devs *s, const char *path, int iface)
{
	char err[256];
	if (input_devs_find(s, &input_backend_hidraw, path) >= 0)
		return 0;
	int i = input_devs_free_place(s, path);
	if (i < 0)
		return 0;
	struct hidraw_dev *d = malloc(sizeof *d);
	if (!d) {
		input_devs_skip(s, path, "out of memory");
		return 0;
	}
	if (hidraw_dev_open(d, path, iface, (uint16_t)i, err, sizeof err) < 0) {
		input_devs_skip(s, path, err);
		free(d);
		return 0;
	}
	struct input_dev_info info = { .vendor = d->info.vendor, .product = d->info.product,
				       .iface = d->info.iface, .cls = d->info.cls,
				       .dpi = INPUT_DEV_DPI_DEFAULT };
	snprintf(info.path, sizeof info.path, "%s", path);
	snprintf(info.name, sizeof info.name, "%.*s", (int)sizeof info.name - 1, d->info.name);
	input_devs_put(s, i, &input_backend_hidraw, d, &info);
	return 1;
}

static int
hidraw_backend_open_spec(struct input_devs *s, const char *arg, char *err, size_t errlen)
{
	uint16_t vid, pid;
	int iface;
	const char *path;
	if (!arg) { /* `auto` is evdev's */
		snprintf(err, errlen, "hidraw: expected VID:PID[:IFACE] or a /dev/hidrawN path");
		return -1;
	}
	if (hidraw_dev_parse_spec(arg, &vid, &pid, &iface, &path, err, errlen) < 0)
		return -1;
	if (path)
		return hidraw_backend_open_path(s, path, -1);
	struct hidraw_dev_found found[HIDRAW_DEV_FOUND_MAX];
	char why[INPUT_DEVS_WHY_MAX];
	int n = hidraw_dev_enumerate(vid, pid, iface, found, HIDRAW_DEV_FOUND_MAX, why, sizeof why);
	if (n <= 0) {
		char what[INPUT_DEVS_SPEC_MAX];
		snprintf(what, sizeof what, "hidraw:%.200s", arg);
		input_devs_skip(s, what, why);
		return 0;
	}
	int opened = 0;
	for (int k = 0; k < n; k++)
		opened += hidraw_backend_open_path(s, found[k].path, found[k].iface);
	return opened;
}

static void
hidraw_backend_stats(const void *dev, struct input_dev_stats *dest)
{
	const struct hidraw_dev *d = dev;
	*dest = (struct input_dev_stats){
		.reads = d->reads,
		.capped = d->capped,
		.errors = d->bad + d->in.short_reports + d->in.long_reports + d->in.unknown_reports,
	};
}

/* the hid-recorder file's head: name, path, ids and the report descriptor */
static int
hidraw_backend_describe(const void *dev, FILE *out)
{
	const struct hidraw_dev *d = dev;
	struct rec_hid_device r = { .bus = d->info.bus, .vid = d->info.vendor,
				    .pid = d->info.product, .desc_len = d->desc_len };
	snprintf(r.name, sizeof r.name, "%s", d->info.name);
	snprintf(r.phys, sizeof r.phys, "%s", d->info.phys);
	memcpy(r.desc, d->desc_bytes, d->desc_len);
	rec_hid_write_device(out, &r, -1);
	return ferror(out) ? -1 : 0;
}

const struct input_backend input_backend_hidraw = {
	.name = "hidraw",
	.usage = "hidraw:VID:PID[:IFACE], hidraw:PATH",
	.open_spec = hidraw_backend_open_spec,
	.fd = hidraw_backend_fd,
	.read = hidraw_backend_read,
	.close = hidraw_backend_close,
	.stats = hidraw_backend_stats,
	.rec_format = "hid-recorder",
	.describe = hidraw_backend_describe,
};
