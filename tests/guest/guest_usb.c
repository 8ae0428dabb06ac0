/*
 * guest_usb.c - the USB backend against a real kernel, inside the test
 * guest (tests/guest): a configfs HID gadget with a mouse (hid.usb0) and
 * a keyboard (hid.usb1) on dummy_hcd, which usbhid claims on the host
 * side. The kernel's meaning of a series of reports is read first from
 * its own evdev nodes; then the backend opens usb:1d6b:0104, the kernel's
 * nodes must go (driver detached), the same reports written to
 * /dev/hidg0 and /dev/hidg1 must mean the same through our decoder, and
 * closing must bring the kernel's nodes back (driver re-attached).
 * Last, the gadget is unbound mid-press: buttons and keys released, both
 * devices removed; bound again: opened again by the hot-plug callback,
 * and with no udevd at all by a rescan. Then a descriptor our parser
 * refuses (boot protocol on the boot mouse, the other interface skipped),
 * and a hi-res wheel: the Resolution Multiplier feature we write must be
 * the bytes usbhid wrote as it bound (the gadget, with no_out_endpoint,
 * hands SET_REPORT data to read()), and the wheel must count as the
 * kernel counts.
 *
 * The guest has no udevd, and Debian's libusb hears of devices coming and
 * going only from udevd (libudev's "udev" netlink group). So a child
 * process stands in for udevd's one job here: it passes the kernel's
 * uevents on to that group in libudev's message format.
 *
 * One line per check: "ok ...", "FAIL ...: why", "skip ...: why". Exit
 * status: the number of failures. Needs root and the modules usb_f_hid
 * (with libcomposite, dummy_hcd, usbhid, hid_generic, evdev).
 */
#include <arpa/inet.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <linux/input.h>
#include <linux/netlink.h>

#include "devices/input_devs.h"
#include "devices/queue.h"
#include "devices/rec_hid.h"
#include "devices/usb_dev.h"
#include "tests/guest/guest_check.h"

#define GADGET "/sys/kernel/config/usb_gadget/posture_usb"
#define VID "1d6b"
#define PID "0104"

/* QEMU's USB mouse (hw/usb/dev-hid.c, MIT): buttons 1-3, X, Y, wheel; 4-byte reports */
static const unsigned char mouse_rdesc[] = {
	0x05, 0x01, 0x09, 0x02, 0xa1, 0x01, 0x09, 0x01, 0xa1, 0x00, 0x05, 0x09, 0x19,
	0x01, 0x29, 0x03, 0x15, 0x00, 0x25, 0x01, 0x95, 0x03, 0x75, 0x01, 0x81, 0x02,
	0x95, 0x01, 0x75, 0x05, 0x81, 0x01, 0x05, 0x01, 0x09, 0x30, 0x09, 0x31, 0x09,
	0x38, 0x15, 0x81, 0x25, 0x7f, 0x75, 0x08, 0x95, 0x03, 0x81, 0x06, 0xc0, 0xc0,
};

/* QEMU's USB keyboard (hw/usb/dev-hid.c, MIT): the boot keyboard with LEDs */
static const unsigned char keyboard_rdesc[] = {
	0x05, 0x01, 0x09, 0x06, 0xa1, 0x01, 0x75, 0x01, 0x95, 0x08, 0x05, 0x07, 0x19,
	0xe0, 0x29, 0xe7, 0x15, 0x00, 0x25, 0x01, 0x81, 0x02, 0x95, 0x01, 0x75, 0x08,
	0x81, 0x01, 0x95, 0x05, 0x75, 0x01, 0x05, 0x08, 0x19, 0x01, 0x29, 0x05, 0x91,
	0x02, 0x95, 0x01, 0x75, 0x03, 0x91, 0x01, 0x95, 0x06, 0x75, 0x08, 0x15, 0x00,
	0x25, 0xff, 0x05, 0x07, 0x19, 0x00, 0x29, 0xff, 0x81, 0x00, 0xc0,
};

/* the reports written, in order: which gadget node, the bytes */
struct report {
	int kbd;
	unsigned char b[8];
};

static const struct report script[] = {
	{ 0, { 0x01, 0x00, 0x00, 0x00 } }, /* left down */
	{ 0, { 0x01, 0x05, 0xfb, 0x00 } }, /* move +5, -5 */
	{ 0, { 0x01, 0x00, 0x00, 0x01 } }, /* wheel up one */
	{ 0, { 0x05, 0x00, 0x00, 0xff } }, /* middle down too, wheel down one */
	{ 0, { 0x00, 0x81, 0x7f, 0x00 } }, /* both up, move -127, +127 */
	{ 1, { 0x02, 0, 0x04, 0, 0, 0, 0, 0 } }, /* left shift + a */
	{ 1, { 0x00, 0, 0x04, 0x05, 0, 0, 0, 0 } }, /* shift up, b down too */
	{ 1, { 0x00, 0, 0, 0, 0, 0, 0, 0 } }, /* all up */
};
#define NSCRIPT (int)(sizeof script / sizeof script[0])

/* what a report means, as evdev says it: "key CODE VALUE" / "rel CODE VALUE", sorted per report */
#define MEANING_MAX 16
struct meaning {
	int n;
	char line[MEANING_MAX][32];
};

static int
cmp_line(const void *a, const void *b)
{
	return strcmp(a, b);
}

static void
meaning_add(struct meaning *m, const char *kind, int code, int value)
{
	if (m->n < MEANING_MAX)
		snprintf(m->line[m->n++], sizeof m->line[0], "%s %d %d", kind, code, value);
}

static void
meaning_text(struct meaning *m, char *dest, size_t n)
{
	qsort(m->line, (size_t)m->n, sizeof m->line[0], cmp_line);
	dest[0] = '\0';
	for (int k = 0; k < m->n; k++)
		snprintf(dest + strlen(dest), n - strlen(dest), "%s%s", k ? ", " : "", m->line[k]);
}

/* ---- udevd's relay ------------------------------------------------------ */

/* MurmurHash2, seed 0: libudev's string_hash32, which its socket filter compares */
static uint32_t
murmur2(const char *s)
{
	const uint32_t m = 0x5bd1e995;
	size_t len = strlen(s);
	uint32_t h = (uint32_t)len;
	const unsigned char *d = (const unsigned char *)s;
	for (; len >= 4; d += 4, len -= 4) {
		uint32_t k = (uint32_t)d[0] | (uint32_t)d[1] << 8 | (uint32_t)d[2] << 16 |
			     (uint32_t)d[3] << 24;
		k *= m;
		k ^= k >> 24;
		k *= m;
		h = h * m ^ k;
	}
	switch (len) {
	case 3:
		h ^= (uint32_t)d[2] << 16; /* fall through */
	case 2:
		h ^= (uint32_t)d[1] << 8; /* fall through */
	case 1:
		h ^= d[0];
		h *= m;
	}
	h ^= h >> 13;
	h *= m;
	h ^= h >> 15;
	return h;
}

/* systemd's monitor_netlink_header (src/libsystemd/sd-device/device-monitor.c) */
struct udev_header {
	char prefix[8]; /* "libudev" */
	uint32_t magic; /* 0xfeedcafe, big-endian */
	uint32_t header_size, properties_off, properties_len;
	uint32_t subsystem_hash, devtype_hash; /* big-endian */
	uint32_t tag_bloom_hi, tag_bloom_lo;
};

/* the child: kernel uevents in, libudev messages out, until killed */
static void
relay(int ready)
{
	int in = socket(AF_NETLINK, SOCK_RAW | SOCK_CLOEXEC, NETLINK_KOBJECT_UEVENT);
	int out = socket(AF_NETLINK, SOCK_RAW | SOCK_CLOEXEC, NETLINK_KOBJECT_UEVENT);
	struct sockaddr_nl kernel = { .nl_family = AF_NETLINK, .nl_groups = 1 };
	struct sockaddr_nl udev = { .nl_family = AF_NETLINK, .nl_groups = 2 };
	if (in < 0 || out < 0 || bind(in, (struct sockaddr *)&kernel, sizeof kernel) < 0)
		_exit(1);
	(void)!write(ready, "r", 1);
	close(ready);
	static char buf[8192], msg[8192 + sizeof(struct udev_header)];
	for (;;) {
		ssize_t n = recv(in, buf, sizeof buf - 1, 0);
		if (n <= 0)
			continue;
		buf[n] = '\0';
		/* "action@devpath", then KEY=value strings */
		size_t at = strlen(buf) + 1;
		if (!strchr(buf, '@') || at >= (size_t)n)
			continue;
		struct udev_header h = { .prefix = "libudev", .magic = htonl(0xfeedcafe) };
		h.header_size = h.properties_off = sizeof h;
		h.properties_len = (uint32_t)((size_t)n - at);
		for (size_t k = at; k < (size_t)n; k += strlen(buf + k) + 1) {
			if (!strncmp(buf + k, "SUBSYSTEM=", 10))
				h.subsystem_hash = htonl(murmur2(buf + k + 10));
			else if (!strncmp(buf + k, "DEVTYPE=", 8))
				h.devtype_hash = htonl(murmur2(buf + k + 8));
		}
		memcpy(msg, &h, sizeof h);
		memcpy(msg + sizeof h, buf + at, h.properties_len);
		sendto(out, msg, sizeof h + h.properties_len, 0, (struct sockaddr *)&udev, sizeof udev);
	}
}

static pid_t
relay_start(void)
{
	int p[2];
	char c;
	if (pipe(p) < 0)
		return -1;
	pid_t pid = fork();
	if (pid == 0) {
		close(p[0]);
		relay(p[1]);
	}
	close(p[1]);
	if (pid < 0 || read(p[0], &c, 1) != 1) {
		close(p[0]);
		return -1;
	}
	close(p[0]);
	return pid;
}

/* ---- sysfs and configfs ----------------------------------------------- */

static int
put(const char *path, const void *data, size_t len)
{
	int fd = open(path, O_WRONLY | O_CLOEXEC);
	if (fd < 0)
		return -1;
	ssize_t w = write(fd, data, len);
	int e = errno;
	close(fd);
	errno = e;
	return w == (ssize_t)len ? 0 : -1;
}

static int
put_text(const char *path, const char *text)
{
	return put(path, text, strlen(text));
}

/* the gadget's function name's attribute attr: 0, or -1 (errno) */
static int
function_put(const char *name, const char *attr, const void *data, size_t len)
{
	char path[200];
	snprintf(path, sizeof path, GADGET "/functions/%s/%s", name, attr);
	return put(path, data, len);
}

/*
 * The gadget's HID function name (made unless there) with its protocol,
 * subclass, report length and report descriptor: 0, or -1 (errno)
 */
static int
hid_function(const char *name, const char *protocol, const char *subclass,
	     const char *report_length, const unsigned char *desc, size_t len)
{
	char path[200];
	snprintf(path, sizeof path, GADGET "/functions/%s", name);
	if (mkdir(path, 0755) < 0 && errno != EEXIST)
		return -1;
	if (function_put(name, "protocol", protocol, strlen(protocol)) ||
	    function_put(name, "subclass", subclass, strlen(subclass)) ||
	    function_put(name, "report_length", report_length, strlen(report_length)) ||
	    function_put(name, "report_desc", desc, len))
		return -1;
	return 0;
}

/* the function name linked into the configuration (or linked already): 0, or -1 (errno) */
static int
function_link(const char *name)
{
	char from[200], to[200];
	snprintf(from, sizeof from, GADGET "/functions/%s", name);
	snprintf(to, sizeof to, GADGET "/configs/c.1/%s", name);
	return symlink(from, to) < 0 && errno != EEXIST ? -1 : 0;
}

static char udc[128];

static int
gadget_make(void)
{
	static const char *dirs[] = {
		GADGET,
		GADGET "/strings/0x409",
		GADGET "/configs/c.1",
		GADGET "/functions/hid.usb0",
		GADGET "/functions/hid.usb1",
	};
	DIR *d = opendir("/sys/class/udc");
	struct dirent *e;
	udc[0] = '\0';
	while (d && (e = readdir(d)))
		if (e->d_name[0] != '.')
			snprintf(udc, sizeof udc, "%.100s", e->d_name);
	if (d)
		closedir(d);
	if (!udc[0]) {
		fail("gadget", "no UDC (dummy_hcd not loaded?)");
		return -1;
	}
	for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++)
		if (mkdir(dirs[i], 0755) < 0 && errno != EEXIST) {
			fail("gadget", "mkdir %s: %s", dirs[i], strerror(errno));
			return -1;
		}
	if (put_text(GADGET "/idVendor", "0x" VID) || put_text(GADGET "/idProduct", "0x" PID) ||
	    put_text(GADGET "/strings/0x409/manufacturer", "posture") ||
	    put_text(GADGET "/strings/0x409/product", "usb test gadget") ||
	    hid_function("hid.usb0", "2", "1", "4", mouse_rdesc, sizeof mouse_rdesc) ||
	    hid_function("hid.usb1", "1", "1", "8", keyboard_rdesc, sizeof keyboard_rdesc)) {
		fail("gadget", "configfs attribute: %s", strerror(errno));
		return -1;
	}
	if (function_link("hid.usb0") || function_link("hid.usb1")) {
		fail("gadget", "link functions: %s", strerror(errno));
		return -1;
	}
	return 0;
}

static int
gadget_bind(int on)
{
	return put_text(GADGET "/UDC", on ? udc : "\n");
}

/*
 * Unplugged: the gadget unbound, its functions a and b taken out of the
 * configuration, and the host has let the old device go (or 3 s passed).
 * 0, or -1 (errno).
 */
static int
gadget_unplug(const char *a, const char *b)
{
	char link[2][200];
	snprintf(link[0], sizeof link[0], GADGET "/configs/c.1/%s", a);
	snprintf(link[1], sizeof link[1], GADGET "/configs/c.1/%s", b);
	if (gadget_bind(0) < 0 || unlink(link[0]) < 0 || unlink(link[1]) < 0)
		return -1;
	for (int t = 0; t < 150 && !access("/sys/bus/usb/devices/1-1", F_OK); t++)
		sleep_ms(20);
	return 0;
}

/*
 * The kernel's nodes of the gadget's interface iface (hidraw and evdev):
 * how many hidraw nodes it has, the evdev node into event (may be "").
 */
static int
kernel_nodes(int iface, char *event, size_t n)
{
	DIR *d = opendir("/sys/class/hidraw");
	struct dirent *e;
	int found = 0;
	char want[16];
	snprintf(want, sizeof want, ":1.%d/", iface);
	if (event)
		event[0] = '\0';
	while (d && (e = readdir(d))) {
		if (e->d_name[0] == '.')
			continue;
		char path[300], real[PATH_MAX];
		snprintf(path, sizeof path, "/sys/class/hidraw/%s/device", e->d_name);
		if (!realpath(path, real) || !strstr(real, want) ||
		    !strstr(real, ":1D6B:0104."))
			continue;
		found++;
		if (!event)
			continue;
		char in[PATH_MAX + 16];
		snprintf(in, sizeof in, "%s/input", real);
		DIR *di = opendir(in);
		struct dirent *ie;
		while (di && (ie = readdir(di)) && !event[0]) {
			if (strncmp(ie->d_name, "input", 5))
				continue;
			char sub[PATH_MAX + 300];
			snprintf(sub, sizeof sub, "%s/%s", in, ie->d_name);
			event_node(sub, event, n);
		}
		if (di)
			closedir(di);
	}
	if (d)
		closedir(d);
	return found;
}

/* waits up to ms for both interfaces to have (want 1) or lack (want 0) kernel nodes */
static int
wait_kernel_nodes(int want, int ms)
{
	for (int t = 0; t <= ms; t += 20) {
		char e0[64], e1[64];
		int n0 = kernel_nodes(0, e0, sizeof e0), n1 = kernel_nodes(1, e1, sizeof e1);
		if (want && n0 && n1 && e0[0] && e1[0] && !access(e0, R_OK) && !access(e1, R_OK))
			return 0;
		if (!want && !n0 && !n1)
			return 0;
		sleep_ms(20);
	}
	return -1;
}

/* ---- the kernel's meaning --------------------------------------------- */

/* writes a report to a gadget node, retrying while the last is pending */
static int
gadget_write(int fd, const unsigned char *b, size_t n, void (*pump)(int ms))
{
	for (int t = 0; t < 200; t++) {
		ssize_t w = write(fd, b, n);
		if (w == (ssize_t)n)
			return 0;
		if (w < 0 && errno != EAGAIN)
			return -1;
		if (pump)
			pump(10);
		else
			sleep_ms(10);
	}
	errno = ETIMEDOUT;
	return -1;
}

/* reads one evdev frame (to SYN_REPORT) into m; 0, or -1 on timeout */
static int
evdev_frame(int fd, struct meaning *m, int ms)
{
	m->n = 0;
	for (;;) {
		struct input_event ie;
		if (read_event(fd, &ie, ms) <= 0)
			return -1;
		if (ie.type == EV_SYN && ie.code == SYN_REPORT)
			return 0;
		if (ie.type == EV_KEY)
			meaning_add(m, "key", ie.code, ie.value);
		else if (ie.type == EV_REL && (ie.code == REL_X || ie.code == REL_Y || ie.code == REL_WHEEL))
			meaning_add(m, "rel", ie.code, ie.value);
	}
}

static char kernel_says[NSCRIPT][256];

static int
kernel_meaning(int g[2])
{
	char ev[2][64];
	int fd[2] = { -1, -1 };
	int rc = -1;
	for (int k = 0; k < 2; k++) {
		kernel_nodes(k, ev[k], sizeof ev[k]);
		if (!ev[k][0] || (fd[k] = open(ev[k], O_RDONLY | O_NONBLOCK)) < 0) {
			fail("kernel meaning", "no evdev node for interface %d", k);
			goto out;
		}
	}
	/* the host polls once a reader is there; a report written earlier may be lost: warm up */
	for (int k = 0; k < NSCRIPT; k++) {
		const struct report *r = &script[k];
		struct meaning m;
		int tries = 0;
		for (; tries < 5; tries++) {
			if (gadget_write(g[r->kbd], r->b, r->kbd ? 8 : 4, NULL) < 0) {
				fail("kernel meaning", "write hidg%d: %s", r->kbd, strerror(errno));
				goto out;
			}
			if (evdev_frame(fd[r->kbd], &m, 1000) == 0)
				break;
			if (k > 0)
				break; /* only the first report may be lost */
		}
		if (tries == 5 || (k > 0 && tries > 0)) {
			fail("kernel meaning", "no evdev frame for report %d", k);
			goto out;
		}
		meaning_text(&m, kernel_says[k], sizeof kernel_says[k]);
	}
	ok("the kernel's meaning of %d reports read from %s and %s", NSCRIPT, ev[0], ev[1]);
	rc = 0;
out:
	for (int k = 0; k < 2; k++)
		if (fd[k] >= 0)
			close(fd[k]);
	return rc;
}

/* ---- ours --------------------------------------------------------------- */

static struct input_queue q;
static struct input_devs set;
static const struct input_backend *const backends[] = { &input_backend_usb };

/* events taken off the queue, kept for the checks */
#define SEEN_MAX 512
static struct input_event_rec seen[SEEN_MAX];
static int nseen;

/* runs the loop's device part for ms: poll the set's fds, work them, keep the events */
static void
pump(int ms)
{
	uint64_t end = now_us() + (uint64_t)ms * 1000u;
	do {
		uint64_t t = now_us();
		int left = t >= end ? 0 : (int)((end - t) / 1000);
		poll_devs(&set, &q, left > 10 ? 10 : left);
		struct input_event_rec e;
		while (input_queue_pop(&q, &e))
			if (nseen < SEEN_MAX)
				seen[nseen++] = e;
	} while (now_us() < end);
}

/* the place of the open device with interface iface, or -1 */
static int
place_of(int iface)
{
	for (int i = 0; i < INPUT_DEVS_MAX; i++)
		if (set.place[i].be && set.place[i].info.iface == iface)
			return i;
	return -1;
}

/* the meaning of our events of device dev from seen[from..], up to a frame end; *next after it */
static int
our_frame(int dev, int from, struct meaning *m, int *next)
{
	m->n = 0;
	for (int k = from; k < nseen; k++) {
		const struct input_event_rec *e = &seen[k];
		if (e->device != dev)
			continue;
		switch ((enum input_kind)e->kind) {
		case INPUT_BUTTON:
		case INPUT_KEY:
			meaning_add(m, "key", e->code, e->value);
			break;
		case INPUT_MOTION:
			if (e->x != 0)
				meaning_add(m, "rel", REL_X, (int)e->x);
			if (e->y != 0)
				meaning_add(m, "rel", REL_Y, (int)e->y);
			break;
		case INPUT_WHEEL:
			meaning_add(m, "rel", e->code == INPUT_WHEEL_V ? REL_WHEEL : REL_HWHEEL,
				    e->value);
			break;
		case INPUT_FRAME:
			*next = k + 1;
			return 0;
		case INPUT_POINTER:
		case INPUT_VALUATOR:
		case INPUT_ADDED:
		case INPUT_REMOVED:
			break;
		}
	}
	return -1;
}

static void
our_meaning(int g[2])
{
	int dev[2] = { place_of(0), place_of(1) };
	int agree = 0;
	for (int k = 0; k < NSCRIPT; k++) {
		const struct report *r = &script[k];
		int from = nseen, next = 0;
		struct meaning m;
		if (gadget_write(g[r->kbd], r->b, r->kbd ? 8 : 4, pump) < 0) {
			fail("usb reports", "write hidg%d: %s", r->kbd, strerror(errno));
			return;
		}
		int got = -1;
		for (int t = 0; t < 100 && got < 0; t++) {
			pump(20);
			got = our_frame(dev[r->kbd], from, &m, &next);
		}
		char text[256];
		if (got < 0) {
			fail("usb reports", "report %d: no frame from device %d", k, dev[r->kbd]);
			continue;
		}
		meaning_text(&m, text, sizeof text);
		if (strcmp(text, kernel_says[k]))
			fail("usb reports", "report %d: ours [%s], the kernel's [%s]", k, text,
			     kernel_says[k]);
		else
			agree++;
	}
	if (agree == NSCRIPT)
		ok("usb reports: all %d reports mean what the kernel says (e.g. [%s], [%s])", NSCRIPT,
		   kernel_says[1], kernel_says[5]);
}

static int
count_kind(int from, int dev, enum input_kind kind, int code, int value)
{
	int n = 0;
	for (int k = from; k < nseen; k++)
		n += seen[k].device == dev && seen[k].kind == kind &&
		     (code < 0 || seen[k].code == code) && (value < 0 || seen[k].value == value);
	return n;
}

static int
index_of(int from, int dev, enum input_kind kind, int code, int value)
{
	for (int k = from; k < nseen; k++)
		if (seen[k].device == dev && seen[k].kind == kind &&
		    (code < 0 || seen[k].code == code) && (value < 0 || seen[k].value == value))
			return k;
	return -1;
}

static int
open_spec(const char *spec)
{
	char err[256];
	int n = input_devs_open(&set, spec, now_us(), err, sizeof err);
	if (n < 0)
		fail("open", "%s", err);
	for (int k = 0; k < set.nskip; k++)
		printf("note: skipped %s: %s\n", set.skip[k].what, set.skip[k].why);
	return n;
}

/*
 * A boot mouse whose descriptor our parser refuses (HID 1.11 B.2 with an
 * extra array of 65 values, more than HID_DESC_MAX_ARRAY): it must run in
 * boot protocol; the same descriptor on a non-boot interface is skipped.
 */
static const unsigned char refused_rdesc[] = {
	0x05, 0x01, 0x09, 0x02, 0xa1, 0x01, 0x09, 0x01, 0xa1, 0x00, 0x05, 0x09, 0x19, 0x01,
	0x29, 0x03, 0x15, 0x00, 0x25, 0x01, 0x95, 0x03, 0x75, 0x01, 0x81, 0x02, 0x95, 0x01,
	0x75, 0x05, 0x81, 0x01, 0x05, 0x01, 0x09, 0x30, 0x09, 0x31, 0x15, 0x81, 0x25, 0x7f,
	0x75, 0x08, 0x95, 0x02, 0x81, 0x06,
	0x05, 0x09, 0x19, 0x01, 0x29, 0x01, 0x15, 0x00, 0x25, 0x01, 0x75, 0x01, 0x95, 0x41,
	0x81, 0x00, /* Input (Data, Array): 65 values */
	0xc0, 0xc0,
};

/* the /dev/hidgN of a gadget function, from its dev attribute (major:minor) */
static int
hidg_of(const char *function, char *dest, size_t n)
{
	char path[200], text[32] = "";
	snprintf(path, sizeof path, GADGET "/functions/%s/dev", function);
	FILE *f = fopen(path, "r");
	unsigned major, minor;
	if (!f)
		return -1;
	int got = fgets(text, sizeof text, f) && sscanf(text, "%u:%u", &major, &minor) == 2;
	fclose(f);
	if (!got)
		return -1;
	snprintf(dest, n, "/dev/hidg%u", minor);
	return 0;
}

static void
boot_fallback(void)
{
	const char *W = "boot fallback";
	if (gadget_unplug("hid.usb0", "hid.usb1") < 0) {
		fail(W, "unbind and unlink: %s", strerror(errno));
		return;
	}
	if (hid_function("hid.usb2", "2", "1", "12", refused_rdesc, sizeof refused_rdesc) ||
	    hid_function("hid.usb3", "0", "0", "12", refused_rdesc, sizeof refused_rdesc) ||
	    function_link("hid.usb2") || function_link("hid.usb3") || gadget_bind(1) < 0) {
		fail(W, "the second gadget: %s", strerror(errno));
		return;
	}
	char hidg[64];
	if (hidg_of("hid.usb2", hidg, sizeof hidg) < 0) {
		fail(W, "no dev attribute for hid.usb2");
		return;
	}
	/* configured: interface 1 in sysfs is the new, non-boot one; then usbhid settles */
	for (int t = 0; t < 250; t++) {
		char sub[8] = "";
		FILE *f = fopen("/sys/bus/usb/devices/1-1:1.1/bInterfaceSubClass", "r");
		if (f) {
			(void)!fgets(sub, sizeof sub, f);
			fclose(f);
		}
		if (!strncmp(sub, "00", 2))
			break;
		sleep_ms(20);
	}
	sleep_ms(500);
	input_devs_init(&set, backends, 1, 0, &q);
	int n = open_spec("usb:" VID ":" PID);
	int i0 = place_of(0);
	const char *why1 = NULL;
	for (int k = 0; k < set.nskip; k++)
		if (!strcmp(set.skip[k].what, "usb:1-1:1"))
			why1 = set.skip[k].why;
	if (n != 1 || i0 < 0 || set.place[i0].info.cls != INPUT_CLASS_MOUSE)
		fail(W, "opened %d interfaces, want the boot mouse alone", n);
	else
		ok("boot fallback: the refused descriptor's boot mouse opened (%s)",
		   set.place[i0].info.path);
	if (!why1 || !strstr(why1, "not a boot interface"))
		fail(W, "interface 1 should be skipped as not a boot interface (%s)",
		     why1 ? why1 : "not skipped");
	else
		ok("boot fallback: the non-boot interface skipped: %s", why1);
	if (i0 < 0)
		return;

	/* boot reports (Appendix B.2): left down, +5 -5; then up */
	int g = open(hidg, O_WRONLY | O_NONBLOCK | O_CLOEXEC);
	static const unsigned char down[3] = { 0x01, 0x05, 0xfb }, up[3] = { 0, 0, 0 };
	int from = nseen;
	if (g < 0 || gadget_write(g, down, 3, pump) < 0 || gadget_write(g, up, 3, pump) < 0) {
		fail(W, "write %s: %s", hidg, strerror(errno));
		if (g >= 0)
			close(g);
		return;
	}
	close(g);
	for (int t = 0; t < 100 && !count_kind(from, i0, INPUT_BUTTON, BTN_LEFT, 0); t++)
		pump(20);
	int press = index_of(from, i0, INPUT_BUTTON, BTN_LEFT, 1);
	int motion = index_of(from, i0, INPUT_MOTION, -1, -1);
	int release = index_of(from, i0, INPUT_BUTTON, BTN_LEFT, 0);
	if (press < 0 || motion < 0 || release < 0 || seen[motion].x != 5 || seen[motion].y != -5)
		fail(W, "boot reports: press %d motion %d (%g %g) release %d", press, motion,
		     motion >= 0 ? seen[motion].x : 0, motion >= 0 ? seen[motion].y : 0, release);
	else
		ok("boot fallback: boot reports read: BTN_LEFT 1, motion +5 -5, BTN_LEFT 0");
	input_devs_close_all(&set, now_us(), &q);
}

/*
 * tests/input/hid/hires_wheel.rdesc (hand-written): a hi-res wheel (x8)
 * and AC Pan (x4), each with a Resolution Multiplier feature, one 2-byte
 * feature report without an id; 7-byte input reports
 */
static const unsigned char hires_rdesc[] = {
	0x05, 0x01, 0x09, 0x02, 0xa1, 0x01, 0x09, 0x01, 0xa1, 0x00, 0x05, 0x09, 0x19, 0x01,
	0x29, 0x05, 0x15, 0x00, 0x25, 0x01, 0x95, 0x05, 0x75, 0x01, 0x81, 0x02, 0x95, 0x01,
	0x75, 0x03, 0x81, 0x01, 0x05, 0x01, 0x09, 0x30, 0x09, 0x31, 0x16, 0x01, 0x80, 0x26,
	0xff, 0x7f, 0x75, 0x10, 0x95, 0x02, 0x81, 0x06, 0xa1, 0x02, 0x09, 0x48, 0x15, 0x00,
	0x25, 0x01, 0x35, 0x01, 0x45, 0x08, 0x75, 0x02, 0x95, 0x01, 0xb1, 0x02, 0x35, 0x00,
	0x45, 0x00, 0x75, 0x06, 0xb1, 0x01, 0x09, 0x38, 0x15, 0x81, 0x25, 0x7f, 0x75, 0x08,
	0x95, 0x01, 0x81, 0x06, 0xc0, 0xa1, 0x02, 0x09, 0x48, 0x15, 0x00, 0x25, 0x01, 0x35,
	0x01, 0x45, 0x04, 0x75, 0x02, 0x95, 0x01, 0xb1, 0x02, 0x35, 0x00, 0x45, 0x00, 0x75,
	0x06, 0xb1, 0x01, 0x05, 0x0c, 0x0a, 0x38, 0x02, 0x15, 0x81, 0x25, 0x7f, 0x75, 0x08,
	0x95, 0x01, 0x81, 0x06, 0xc0, 0xc0, 0xc0,
};

/* the SET_REPORT the gadget last took (no_out_endpoint: it is what read gives), or -1 */
static ssize_t
set_report_read(int fd, unsigned char *buf, size_t n, int ms)
{
	for (int t = 0; t <= ms; t += 20) {
		ssize_t r = read(fd, buf, n);
		if (r > 0)
			return r;
		pump(20);
	}
	return -1;
}

static void
hex_text(const unsigned char *b, ssize_t n, char *dest, size_t len)
{
	dest[0] = '\0';
	for (ssize_t k = 0; k < n && strlen(dest) + 4 < len; k++)
		snprintf(dest + strlen(dest), len - strlen(dest), "%s%02x", k ? " " : "", b[k]);
}

/*
 * The Resolution Multiplier: the feature report usbhid writes as it binds
 * (hid-input sets every multiplier to its logical maximum) and the one we
 * write must be the same bytes; and wheel reports must then count what
 * the kernel's REL_WHEEL and REL_WHEEL_HI_RES count.
 */
static void
multiplier(void)
{
	const char *W = "multiplier";
	if (gadget_unplug("hid.usb2", "hid.usb3") < 0) {
		fail(W, "unbind and unlink: %s", strerror(errno));
		return;
	}
	/* f_hid has four minors: hid.usb0's (unlinked by now) is given back for this one */
	if (rmdir(GADGET "/functions/hid.usb0") < 0 ||
	    hid_function("hid.usb4", "0", "0", "7", hires_rdesc, sizeof hires_rdesc) ||
	    put_text(GADGET "/functions/hid.usb4/no_out_endpoint", "1") ||
	    function_link("hid.usb4")) {
		fail(W, "the third gadget: %s", strerror(errno));
		return;
	}
	char hidg[64];
	int g = -1, ev = -1;
	if (gadget_bind(1) < 0 || hidg_of("hid.usb4", hidg, sizeof hidg) < 0) {
		fail(W, "bind: %s", strerror(errno));
		return;
	}
	for (int t = 0; t < 100 && g < 0; t++) /* the node comes with the bind */
		if ((g = open(hidg, O_RDWR | O_NONBLOCK | O_CLOEXEC)) < 0)
			sleep_ms(20);
	if (g < 0) {
		fail(W, "open %s: %s", hidg, strerror(errno));
		return;
	}
	char event[64] = "";
	for (int t = 0; t < 250 && !event[0]; t++) {
		if (kernel_nodes(0, event, sizeof event) && event[0] && !access(event, R_OK))
			break;
		event[0] = '\0';
		sleep_ms(20);
	}
	unsigned char kernel[64], ours[64];
	ssize_t nk = set_report_read(g, kernel, sizeof kernel, 2000);
	if (!event[0] || nk <= 0) {
		fail(W, "usbhid bound %s, its SET_REPORT %zd bytes", event[0] ? event : "nothing",
		     nk);
		goto out;
	}
	/* the kernel's wheel: +1 then +7 eighths of a detent */
	static const unsigned char one[7] = { 0, 0, 0, 0, 0, 0x01, 0 };
	static const unsigned char seven[7] = { 0, 0, 0, 0, 0, 0x07, 0 };
	long k_hi = 0, k_detents = 0;
	if ((ev = open(event, O_RDONLY | O_NONBLOCK | O_CLOEXEC)) < 0) {
		fail(W, "open %s: %s", event, strerror(errno));
		goto out;
	}
	for (int r = 0; r < 2; r++) {
		struct input_event ie;
		int frames = 0;
		for (int tries = 0; tries < 5 && !frames; tries++) {
			if (gadget_write(g, r ? seven : one, 7, NULL) < 0)
				break;
			for (int t = 0; t < 50 && !frames; t++) {
				struct pollfd p = { .fd = ev, .events = POLLIN };
				if (poll(&p, 1, 20) <= 0)
					continue;
				while (read(ev, &ie, sizeof ie) == (ssize_t)sizeof ie) {
					if (ie.type == EV_REL && ie.code == REL_WHEEL)
						k_detents += ie.value;
					else if (ie.type == EV_REL && ie.code == REL_WHEEL_HI_RES)
						k_hi += ie.value;
					else if (ie.type == EV_SYN && ie.code == SYN_REPORT)
						frames++;
				}
			}
			if (r > 0)
				break; /* only the first report may be lost while polling starts */
		}
	}
	close(ev);
	ev = -1;

	/* ours */
	input_devs_init(&set, backends, 1, 0, &q);
	if (open_spec("usb:" VID ":" PID) != 1) {
		fail(W, "not opened");
		goto out;
	}
	int i0 = place_of(0);
	ssize_t no = set_report_read(g, ours, sizeof ours, 2000);
	char kt[200], ot[200];
	hex_text(kernel, nk, kt, sizeof kt);
	hex_text(ours, no, ot, sizeof ot);
	if (no != nk || memcmp(kernel, ours, (size_t)nk))
		fail(W, "we wrote [%s], usbhid wrote [%s]", ot, kt);
	else
		ok("multiplier: the feature report we write is usbhid's own [%s]", kt);
	int from = nseen;
	if (gadget_write(g, one, 7, pump) < 0 || gadget_write(g, seven, 7, pump) < 0) {
		fail(W, "write: %s", strerror(errno));
		goto out;
	}
	long o_hi = 0, o_detents = 0;
	for (int t = 0; t < 100 && count_kind(from, i0, INPUT_FRAME, -1, -1) < 2; t++)
		pump(20);
	for (int k = from; k < nseen; k++)
		if (seen[k].device == i0 && seen[k].kind == INPUT_WHEEL &&
		    seen[k].code == INPUT_WHEEL_V) {
			o_hi += (long)seen[k].x;
			o_detents += seen[k].value;
		}
	if (o_hi != k_hi || o_detents != k_detents || k_hi != 120)
		fail(W, "wheel: ours %ld/120 and %ld detents, the kernel's %ld and %ld", o_hi,
		     o_detents, k_hi, k_detents);
	else
		ok("multiplier: 1/8 + 7/8 of a detent: %ld/120 and %ld detent, as the kernel counts",
		   o_hi, o_detents);
	input_devs_close_all(&set, now_us(), &q);
out:
	if (ev >= 0)
		close(ev);
	close(g);
}

/* ---- posture-input record usb: ---------------------------------------- */

/*
 * The recorder, a separate process as a person runs it, records both
 * interfaces while the script plays: its file must give back both
 * descriptors as the gadget declares them and every report in order, and
 * usbhid must have the interfaces again once it exits.
 */
static void
record_check(int g[2])
{
	const char *tool = "/usr/local/bin/posture-input", *file = "/tmp/usb.hid";
	if (access(tool, X_OK) != 0) {
		fail("record", "%s is not in the guest (run with --exe)", tool);
		return;
	}
	char count[16];
	snprintf(count, sizeof count, "%d", NSCRIPT);
	pid_t pid = fork();
	if (pid == 0) {
		execl(tool, tool, "record", "usb:" VID ":" PID, "-o", file, "--count", count,
		      "--seconds", "30", (char *)NULL);
		_exit(127);
	}
	if (pid < 0 || wait_kernel_nodes(0, 5000) < 0) {
		fail("record", "the recorder did not take the interfaces");
		return;
	}
	sleep_ms(300); /* its transfers submitted */
	for (int k = 0; k < NSCRIPT; k++) {
		const struct report *r = &script[k];
		if (gadget_write(g[r->kbd], r->b, r->kbd ? 8 : 4, NULL) < 0) {
			fail("record", "write hidg%d: %s", r->kbd, strerror(errno));
			break;
		}
		sleep_ms(30);
	}
	int status = 0;
	waitpid(pid, &status, 0);
	if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
		fail("record", "the recorder ended with status %d", status);
		return;
	}
	static struct rec_hid rec;
	char err[256];
	if (rec_hid_read(file, &rec, err, sizeof err) < 0) {
		fail("record", "%s", err);
		return;
	}
	int good = rec.ndevices == 2 && rec.nevents == (size_t)NSCRIPT &&
		   rec.devices[0].desc_len == sizeof mouse_rdesc &&
		   !memcmp(rec.devices[0].desc, mouse_rdesc, sizeof mouse_rdesc) &&
		   rec.devices[1].desc_len == sizeof keyboard_rdesc &&
		   !memcmp(rec.devices[1].desc, keyboard_rdesc, sizeof keyboard_rdesc) &&
		   rec.devices[0].vid == 0x1d6b && rec.devices[0].pid == 0x0104;
	for (int k = 0; good && k < NSCRIPT; k++) {
		const struct report *r = &script[k];
		size_t n = r->kbd ? 8 : 4;
		good = rec.events[k].device == r->kbd && rec.events[k].len == n &&
		       !memcmp(rec.events[k].bytes, r->b, n);
	}
	if (!good)
		fail("record", "%s: %u devices, %zu reports; not the gadget's descriptors and the "
		     "script's %d reports", file, rec.ndevices, rec.nevents, NSCRIPT);
	else
		ok("record: posture-input record usb: gave both descriptors and all %d reports", NSCRIPT);
	rec_hid_free(&rec);
	if (wait_kernel_nodes(1, 3000) < 0)
		fail("record", "usbhid did not get the interfaces back after the recorder");
}

int
main(void)
{
	int g[2] = { -1, -1 };
	input_queue_init(&q);
	input_devs_init(&set, backends, 1, 0, &q);
	pid_t relay_pid = relay_start();
	if (relay_pid < 0)
		fail("relay", "cannot relay uevents: %s", strerror(errno));
	if (access("/dev/bus/usb", F_OK) != 0)
		printf("note: /dev/bus/usb missing before the gadget\n");
	if (gadget_make() < 0 || gadget_bind(1) < 0) {
		if (!guest_failures)
			fail("gadget", "bind: %s", strerror(errno));
		goto out;
	}
	if (wait_kernel_nodes(1, 5000) < 0) {
		fail("gadget", "usbhid did not take both interfaces");
		goto out;
	}
	ok("gadget %s:%s bound to %s: usbhid gave hidraw and evdev nodes to both interfaces", VID,
	   PID, udc);
	g[0] = open("/dev/hidg0", O_WRONLY | O_NONBLOCK | O_CLOEXEC);
	g[1] = open("/dev/hidg1", O_WRONLY | O_NONBLOCK | O_CLOEXEC);
	if (g[0] < 0 || g[1] < 0) {
		fail("gadget", "open /dev/hidg0, hidg1: %s", strerror(errno));
		goto out;
	}
	if (kernel_meaning(g) < 0)
		goto out;

	/* ours: opened, the kernel's driver set aside */
	int n = open_spec("usb:" VID ":" PID);
	if (n != 2) {
		fail("open", "usb:" VID ":" PID " opened %d interfaces, want 2", n);
		goto out;
	}
	int i0 = place_of(0), i1 = place_of(1);
	if (i0 < 0 || i1 < 0 || set.place[i0].info.cls != INPUT_CLASS_MOUSE ||
	    set.place[i1].info.cls != INPUT_CLASS_KEYBOARD)
		fail("open", "interface 0 should be a mouse and 1 a keyboard");
	else
		ok("opened %s (%s, mouse) and %s (keyboard)", set.place[i0].info.path,
		   set.place[i0].info.name, set.place[i1].info.path);
	if (wait_kernel_nodes(0, 2000) < 0)
		fail("detach", "the kernel's hidraw nodes are still there");
	else
		ok("detach: the kernel's hidraw and evdev nodes of both interfaces are gone");
	our_meaning(g);

	/* closed: the kernel's driver back */
	input_devs_close_all(&set, now_us(), &q);
	if (wait_kernel_nodes(1, 3000) < 0)
		fail("re-attach", "no hidraw/evdev nodes for the interfaces after close");
	else
		ok("re-attach: usbhid has both interfaces again after close (hidraw and evdev nodes)");
	record_check(g);

	/* unplug mid-press */
	n = open_spec("usb:" VID ":" PID);
	i0 = place_of(0);
	i1 = place_of(1);
	if (n != 2 || i0 < 0 || i1 < 0) {
		fail("unplug", "reopen gave %d interfaces", n);
		goto out;
	}
	int from = nseen;
	static const unsigned char press[4] = { 0x01, 0, 0, 0 };
	static const unsigned char key[8] = { 0, 0, 0x04, 0, 0, 0, 0, 0 };
	if (gadget_write(g[0], press, 4, pump) < 0 || gadget_write(g[1], key, 8, pump) < 0)
		fail("unplug", "write: %s", strerror(errno));
	for (int t = 0; t < 100; t++) {
		pump(20);
		if (count_kind(from, i0, INPUT_BUTTON, BTN_LEFT, 1) &&
		    count_kind(from, i1, INPUT_KEY, KEY_A, 1))
			break;
	}
	if (!count_kind(from, i0, INPUT_BUTTON, BTN_LEFT, 1) ||
	    !count_kind(from, i1, INPUT_KEY, KEY_A, 1)) {
		fail("unplug", "the press did not arrive");
		goto out;
	}
	from = nseen;
	close(g[0]);
	close(g[1]);
	g[0] = g[1] = -1;
	if (gadget_bind(0) < 0) {
		fail("unplug", "unbind: %s", strerror(errno));
		goto out;
	}
	for (int t = 0; t < 150 && input_devs_count(&set); t++)
		pump(20);
	int up0 = index_of(from, i0, INPUT_BUTTON, BTN_LEFT, 0);
	int up1 = index_of(from, i1, INPUT_KEY, KEY_A, 0);
	int rm0 = index_of(from, i0, INPUT_REMOVED, -1, -1);
	int rm1 = index_of(from, i1, INPUT_REMOVED, -1, -1);
	if (input_devs_count(&set) != 0 || rm0 < 0 || rm1 < 0)
		fail("unplug", "%d devices still open, removed: %d %d", input_devs_count(&set),
		     rm0 >= 0, rm1 >= 0);
	else if (up0 < 0 || up1 < 0 || up0 > rm0 || up1 > rm1)
		fail("unplug", "button/key not released before the removal (%d<%d, %d<%d)", up0, rm0,
		     up1, rm1);
	else
		ok("unplug mid-press: BTN_LEFT and KEY_A released, both devices removed, none open");

	/* plugged again: the hot-plug callback, or a rescan */
	from = nseen;
	if (gadget_bind(1) < 0) {
		fail("replug", "bind: %s", strerror(errno));
		goto out;
	}
	for (int t = 0; t < 150 && input_devs_count(&set) < 2; t++)
		pump(20);
	if (input_devs_count(&set) == 2 && count_kind(from, place_of(0), INPUT_ADDED, -1, -1) &&
	    count_kind(from, place_of(1), INPUT_ADDED, -1, -1))
		ok("hot-plug: libusb's arrival callback had both interfaces opened again (INPUT_ADDED)");
	else
		fail("hot-plug", "%d interfaces open 3 s after plugging in", input_devs_count(&set));

	/*
	 * without udevd (the relay stopped): libusb hears nothing, so the
	 * daemon's own uevent monitor (--hotplug kernel) asks for a rescan,
	 * done here by hand, once a second as the device comes back
	 */
	if (relay_pid > 0) {
		kill(relay_pid, SIGKILL);
		waitpid(relay_pid, NULL, 0);
		relay_pid = -1;
	}
	if (gadget_bind(0) < 0) {
		fail("no udevd", "unbind: %s", strerror(errno));
		goto out;
	}
	for (int t = 0; t < 150 && input_devs_count(&set); t++)
		pump(20);
	if (input_devs_count(&set) != 0)
		fail("no udevd", "%d devices still open after unplugging", input_devs_count(&set));
	if (gadget_bind(1) < 0) {
		fail("no udevd", "bind: %s", strerror(errno));
		goto out;
	}
	pump(1000);
	int before = input_devs_count(&set), rescans = 0;
	while (rescans < 5 && input_devs_count(&set) < 2) {
		input_devs_rescan(&set, now_us());
		rescans++;
		pump(1000);
	}
	if (before == 0 && input_devs_count(&set) == 2)
		ok("no udevd: a rescan after re-plugging opened both interfaces (%d rescan%s)",
		   rescans, rescans == 1 ? "" : "s");
	else
		fail("no udevd", "%d open before the rescans, %d after %d", before,
		     input_devs_count(&set), rescans);
	input_devs_close_all(&set, now_us(), &q);
	boot_fallback();
	multiplier();
	if (usb_dev_exit() < 0)
		fail("exit", "devices still open");
out:
	for (int k = 0; k < 2; k++)
		if (g[k] >= 0)
			close(g[k]);
	if (relay_pid > 0) {
		kill(relay_pid, SIGKILL);
		waitpid(relay_pid, NULL, 0);
	}
	printf("guest_usb: %d failure%s\n", guest_failures, guest_failures == 1 ? "" : "s");
	return guest_status();
}
