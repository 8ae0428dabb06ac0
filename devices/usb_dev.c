/* usb_dev.c - the USB backend: HID interfaces through libusb-1.0 (see usb_dev.h) */
#include <errno.h>
#include <libusb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "devices/devlog.h"
#include "devices/input_devs.h"
#include "devices/textfile.h"
#include "devices/usb_dev.h"

/* HID 1.11: the class descriptor, the report descriptor, the class requests */
#define USB_HID_CLASS 0x03
#define USB_HID_SUBCLASS_BOOT 0x01
#define USB_HID_PROTOCOL_KEYBOARD 0x01
#define USB_HID_PROTOCOL_MOUSE 0x02
#define USB_DT_HID 0x21
#define USB_DT_REPORT 0x22
#define HID_REQ_SET_REPORT 0x09
#define HID_REQ_SET_IDLE 0x0a
#define HID_REQ_SET_PROTOCOL 0x0b
#define HID_REPORT_FEATURE 3
#define HID_PROTOCOL_BOOT 0
#define HID_PROTOCOL_REPORT 1

/* sizes of the boot reports (HID 1.11 Appendix B) */
#define USB_BOOT_MOUSE_BYTES 3
#define USB_BOOT_KEYBOARD_BYTES 8

struct usb_dev {
	libusb_device_handle *h;
	struct libusb_transfer *xfer;
	uint8_t *buf;
	int buflen;
	uint8_t iface, ep;
	uint8_t claimed;
	uint8_t detached;   /* we detached the driver by hand: attach it again at close */
	uint8_t submitted;  /* the transfer is with the kernel: its callback is due */
	uint8_t halted;     /* a stall: the halt is cleared in read, outside the callback */
	uint8_t closing;    /* the callback decodes nothing more */
	char path[INPUT_DEV_PATH_MAX];
	/* a recorder's copy of every report, and what it writes first */
	usb_dev_tap_fn tap;
	void *tap_ctx;
	struct rec_hid_device rec; /* the descriptor decoded by (the boot one in boot protocol) */
	struct usb_intr u;  /* last: large */
};

/*
 * The backend's one libusb context, made by the first usb spec. The
 * callbacks run inside libusb_handle_events, which only shared_work and
 * close call; they decode into `q` at `now_us`, set just before. When no
 * queue is there (a device closed with nowhere to say so), their events
 * go to `discard`.
 */
static struct {
	libusb_context *ctx;
	int ndevs;
	libusb_hotplug_callback_handle hotplug;
	int hotplug_on;
	int arrived;
	struct input_queue *q;
	uint64_t now_us;
	/* the context's fds, kept by libusb's notifiers: polling allocates nothing */
	struct pollfd fds[INPUT_DEVS_SHARED_FDS];
	int nfds;
	int fds_lost;  /* fds that did not fit */
	struct devlog log;
} usb;

static struct input_queue usb_discard;

/* ---- the spec ---------------------------------------------------------- */

/* hex of 1..maxdigits digits up to ':' or the end: 0 and *end, or -1 */
static int
usb_dev_hex(const char *s, int maxdigits, unsigned *dest, const char **end)
{
	unsigned v = 0;
	int n = 0;
	for (; s[n] && s[n] != ':'; n++) {
		int d = textfile_hex_digit(s[n]);
		if (d < 0 || n == maxdigits)
			return -1;
		v = v * 16 + (unsigned)d;
	}
	if (n == 0)
		return -1;
	*dest = v;
	*end = s + n;
	return 0;
}

int
usb_dev_parse_spec(const char *arg, uint16_t *vid, uint16_t *pid, int *iface, char *err,
		   size_t errlen)
{
	unsigned v, p, i;
	const char *s = arg;
	if (!arg || usb_dev_hex(s, 4, &v, &s) < 0 || *s++ != ':' || usb_dev_hex(s, 4, &p, &s) < 0)
		goto bad;
	*iface = -1;
	if (*s == ':') {
		if (usb_dev_hex(s + 1, 2, &i, &s) < 0 || *s)
			goto bad;
		*iface = (int)i;
	} else if (*s) {
		goto bad;
	}
	*vid = (uint16_t)v;
	*pid = (uint16_t)p;
	return 0;
bad:
	snprintf(err, errlen, "input 'usb:%.100s': expected usb:VID:PID[:IFACE] in hex (usb:046d:c077)",
		 arg ? arg : "");
	return -1;
}

/* ---- the context ------------------------------------------------------- */

static void LIBUSB_CALL
usb_dev_fd_added(int fd, short events, void *user)
{
	(void)user;
	for (int k = 0; k < usb.nfds; k++)
		if (usb.fds[k].fd == fd) {
			usb.fds[k].events = events;
			return;
		}
	if (usb.nfds == INPUT_DEVS_SHARED_FDS) {
		usb.fds_lost++;
		devlog(&usb.log, usb.now_us, DEVLOG_US,
		       "more than %d libusb fds: fd %d is not polled", INPUT_DEVS_SHARED_FDS, fd);
		return;
	}
	usb.fds[usb.nfds++] = (struct pollfd){ .fd = fd, .events = events };
}

static void LIBUSB_CALL
usb_dev_fd_removed(int fd, void *user)
{
	(void)user;
	for (int k = 0; k < usb.nfds; k++)
		if (usb.fds[k].fd == fd) {
			usb.fds[k] = usb.fds[--usb.nfds];
			return;
		}
}

/* runs inside libusb_handle_events: note the arrival, act after (usb_dev.h) */
static int LIBUSB_CALL
usb_dev_hotplug(libusb_context *ctx, libusb_device *dev, libusb_hotplug_event event, void *user)
{
	(void)ctx;
	(void)dev;
	(void)user;
	if (event == LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED)
		usb.arrived = 1;
	return 0; /* stay registered */
}

/*
 * The context: 0, or -1 with err. Made once, except without udevd:
 * libusb's device list then never changes after it starts (it hears of
 * arrivals and departures only from udevd), so a context with no device
 * open is made anew, and its first scan of sysfs sees what is there now.
 */
static int
usb_dev_context(char *err, size_t errlen)
{
	if (usb.ctx && !usb.ndevs && access("/run/udev/control", F_OK) != 0)
		usb_dev_exit();
	if (usb.ctx)
		return 0;
	devlog_init(&usb.log, "usb");
	int rc = libusb_init(&usb.ctx);
	if (rc < 0) {
		usb.ctx = NULL;
		snprintf(err, errlen, "libusb cannot start: %s", libusb_strerror(rc));
		return -1;
	}
	/*
	 * The fds to poll, kept up to date by the notifiers. Timeouts: libusb
	 * keeps them on a timerfd among these fds on Linux
	 * (libusb_pollfds_handle_timeouts says 1), and our interrupt transfers
	 * have none anyway, so the loop needs no timer of ours.
	 */
	usb.nfds = 0;
	libusb_set_pollfd_notifiers(usb.ctx, usb_dev_fd_added, usb_dev_fd_removed, NULL);
	const struct libusb_pollfd **pf = libusb_get_pollfds(usb.ctx);
	for (int k = 0; pf && pf[k]; k++)
		usb_dev_fd_added(pf[k]->fd, pf[k]->events, NULL);
	libusb_free_pollfds(pf);
	if (!libusb_pollfds_handle_timeouts(usb.ctx))
		devlog(&usb.log, 0, DEVLOG_KERNEL,
		       "libusb has no timerfd here: its own timeouts are not kept (ours need none)");
	if (libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG)) {
		rc = libusb_hotplug_register_callback(
			usb.ctx, LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED, 0, LIBUSB_HOTPLUG_MATCH_ANY,
			LIBUSB_HOTPLUG_MATCH_ANY, LIBUSB_HOTPLUG_MATCH_ANY, usb_dev_hotplug, NULL,
			&usb.hotplug);
		usb.hotplug_on = rc == LIBUSB_SUCCESS;
		if (!usb.hotplug_on)
			devlog(&usb.log, 0, DEVLOG_KERNEL, "no hot-plug: %s", libusb_strerror(rc));
	}
	return 0;
}

int
usb_dev_exit(void)
{
	if (usb.ndevs)
		return -1;
	if (!usb.ctx)
		return 0;
	if (usb.hotplug_on)
		libusb_hotplug_deregister_callback(usb.ctx, usb.hotplug);
	libusb_set_pollfd_notifiers(usb.ctx, NULL, NULL, NULL);
	libusb_exit(usb.ctx);
	memset(&usb, 0, sizeof usb);
	return 0;
}

/* handles what is pending, decoding into q (NULL: discarded) at now_us */
static void
usb_dev_handle_events(uint64_t now_us, struct input_queue *q, long wait_us)
{
	struct timeval tv = { .tv_sec = 0, .tv_usec = wait_us };
	usb.q = q ? q : &usb_discard;
	usb.now_us = now_us;
	libusb_handle_events_timeout_completed(usb.ctx, &tv, NULL);
	if (!q)
		input_queue_init(&usb_discard);
	usb.q = NULL;
}

/* ---- transfers --------------------------------------------------------- */

static enum usb_intr_status
usb_dev_status(enum libusb_transfer_status st)
{
	switch (st) {
	case LIBUSB_TRANSFER_COMPLETED:
		return USB_INTR_COMPLETED;
	case LIBUSB_TRANSFER_ERROR:
		return USB_INTR_ERROR;
	case LIBUSB_TRANSFER_TIMED_OUT:
		return USB_INTR_TIMED_OUT;
	case LIBUSB_TRANSFER_CANCELLED:
		return USB_INTR_CANCELLED;
	case LIBUSB_TRANSFER_STALL:
		return USB_INTR_STALL;
	case LIBUSB_TRANSFER_NO_DEVICE:
		return USB_INTR_NO_DEVICE;
	case LIBUSB_TRANSFER_OVERFLOW:
		return USB_INTR_OVERFLOW;
	}
	return USB_INTR_ERROR;
}

/* submits the transfer; a refusal makes the device gone */
static void
usb_dev_submit(struct usb_dev *d, uint64_t now_us)
{
	int rc = libusb_submit_transfer(d->xfer);
	if (rc == LIBUSB_SUCCESS) {
		d->submitted = 1;
		return;
	}
	usb_intr_lost(&d->u, libusb_strerror(rc), rc == LIBUSB_ERROR_NO_DEVICE, now_us);
}

static void LIBUSB_CALL
usb_dev_transfer_done(struct libusb_transfer *t)
{
	struct usb_dev *d = t->user_data;
	d->submitted = 0;
	if (d->closing)
		return;
	if (d->tap && t->status == LIBUSB_TRANSFER_COMPLETED && t->actual_length > 0) {
		size_t n = (size_t)t->actual_length;
		if (d->u.boot_len && n > d->u.boot_len) /* what the decoder takes of a boot report */
			n = d->u.boot_len;
		d->tap(d->tap_ctx, usb.now_us, t->buffer, n);
	}
	enum usb_intr_next next =
		usb_intr_complete(&d->u, usb_dev_status(t->status), t->buffer,
				  (size_t)(t->actual_length > 0 ? t->actual_length : 0), usb.now_us,
				  usb.q ? usb.q : &usb_discard);
	switch (next) {
	case USB_INTR_RESUBMIT:
		usb_dev_submit(d, usb.now_us);
		break;
	case USB_INTR_CLEAR_HALT:
		d->halted = 1; /* clear_halt is synchronous: done in read */
		break;
	case USB_INTR_STOP:
		break;
	}
}

/* ---- opening ----------------------------------------------------------- */

/* the report descriptor's length from the HID class descriptor in extra, or 0 */
static int
usb_dev_report_desc_len(const unsigned char *extra, int n)
{
	for (int at = 0; at + 2 <= n && extra[at] >= 2; at += extra[at]) {
		int len = extra[at];
		if (extra[at + 1] != USB_DT_HID || at + len > n || len < 9)
			continue;
		/* bcdHID(2) bCountryCode bNumDescriptors, then (type, length) pairs */
		int num = extra[at + 5];
		for (int k = 0; k < num && at + 6 + 3 * k + 2 < at + len; k++) {
			const unsigned char *p = extra + at + 6 + 3 * k;
			if (p[0] == USB_DT_REPORT)
				return p[1] | p[2] << 8;
		}
	}
	return 0;
}

/* "usb:BUS-P1.P2:IFACE", the place's path */
static void
usb_dev_path(libusb_device *dev, int iface, char *dest, size_t n)
{
	uint8_t ports[8];
	int np = libusb_get_port_numbers(dev, ports, (int)sizeof ports);
	int at = snprintf(dest, n, "usb:%u-", libusb_get_bus_number(dev));
	if (np <= 0)
		at += snprintf(dest + at, n - (size_t)at, "a%u", libusb_get_device_address(dev));
	for (int k = 0; k < np && (size_t)at < n; k++)
		at += snprintf(dest + at, n - (size_t)at, k ? ".%u" : "%u", ports[k]);
	if ((size_t)at < n)
		snprintf(dest + at, n - (size_t)at, ":%d", iface);
}

/* the class a descriptor's application collections say */
static enum input_class
usb_dev_class(const struct hid_desc *d)
{
	int keyboard = 0;
	for (unsigned c = 0; c < d->ncollections; c++) {
		const struct hid_desc_collection *col = &d->collections[c];
		if (col->type != HID_COLLECTION_APPLICATION)
			continue;
		if (col->usage == HID_USAGE_GD_MOUSE || col->usage == HID_USAGE_GD_POINTER)
			return INPUT_CLASS_MOUSE;
		keyboard |= col->usage == HID_USAGE_GD_KEYBOARD;
	}
	return keyboard ? INPUT_CLASS_KEYBOARD : INPUT_CLASS_OTHER;
}

/* a class request to the interface; libusb's code */
static int
usb_dev_class_out(struct usb_dev *d, uint8_t req, uint16_t value, uint8_t *data, uint16_t len)
{
	return libusb_control_transfer(d->h,
				       LIBUSB_ENDPOINT_OUT | LIBUSB_REQUEST_TYPE_CLASS |
					       LIBUSB_RECIPIENT_INTERFACE,
				       req, value, d->iface, data, len, USB_DEV_CONTROL_MS);
}

/* sets value v of size bits at bit offset in a report's data (HID: little-endian bits) */
static void
usb_dev_put_bits(uint8_t *data, unsigned offset, unsigned size, uint32_t v)
{
	for (unsigned b = 0; b < size; b++, offset++)
		if (v >> b & 1)
			data[offset / 8] |= (uint8_t)(1u << (offset % 8));
}

/*
 * Writes the Resolution Multiplier features (each feature report once,
 * every multiplier in it at its logical maximum, as hid-input does); a
 * report the device refuses takes its multipliers back to 1.
 */
static void
usb_dev_write_multipliers(struct usb_dev *d, struct hid_desc *desc, uint64_t now_us)
{
	int changed = 0;
	for (unsigned m = 0; m < desc->nmultipliers; m++) {
		unsigned id = desc->multipliers[m].report_id;
		int first = 1;
		for (unsigned k = 0; k < m; k++)
			first &= desc->multipliers[k].report_id != id;
		if (!first)
			continue;
		/* a report with an id (never 0: HID 1.11 6.2.2.7) starts with it */
		size_t bytes = (desc->multipliers[m].report_bits + 7) / 8 + (id ? 1 : 0);
		uint8_t *buf = calloc(1, bytes ? bytes : 1);
		if (!buf)
			return;
		uint8_t *data = buf + (id ? 1 : 0);
		if (id)
			buf[0] = (uint8_t)id;
		for (unsigned k = m; k < desc->nmultipliers; k++)
			if (desc->multipliers[k].report_id == id)
				usb_dev_put_bits(data, desc->multipliers[k].bit_offset,
						 desc->multipliers[k].size,
						 (uint32_t)desc->multipliers[k].logical_max);
		int rc = usb_dev_class_out(d, HID_REQ_SET_REPORT,
					   (uint16_t)(HID_REPORT_FEATURE << 8 | id), buf,
					   (uint16_t)bytes);
		free(buf);
		if (rc == (int)bytes)
			continue;
		devlog(&d->u.in.log, now_us, DEVLOG_DEVICE,
		       "refused the Resolution Multiplier (feature report %u: %s): "
		       "the wheel counts whole detents",
		       id, rc < 0 ? libusb_strerror(rc) : "short write");
		for (unsigned k = m; k < desc->nmultipliers; k++)
			if (desc->multipliers[k].report_id == id)
				desc->multipliers[k].effective = 1;
		changed = 1;
	}
	if (changed)
		hid_desc_apply_multipliers(desc);
}

/* undoes an open that went part of the way */
static void
usb_dev_unclaim(struct usb_dev *d)
{
	if (d->claimed)
		libusb_release_interface(d->h, d->iface); /* auto-detach: re-attaches the driver */
	if (d->detached)
		libusb_attach_kernel_driver(d->h, d->iface);
	d->claimed = d->detached = 0;
	if (d->h)
		libusb_close(d->h);
	d->h = NULL;
}

/* "manufacturer product", as the kernel names a USB HID device */
static void
usb_dev_name(libusb_device_handle *h, const struct libusb_device_descriptor *dd, char *dest,
	     size_t n)
{
	unsigned char m[64] = "", p[64] = "";
	if (dd->iManufacturer)
		libusb_get_string_descriptor_ascii(h, dd->iManufacturer, m, sizeof m);
	if (dd->iProduct)
		libusb_get_string_descriptor_ascii(h, dd->iProduct, p, sizeof p);
	if (m[0] && p[0])
		snprintf(dest, n, "%s %s", (char *)m, (char *)p);
	else if (m[0] || p[0])
		snprintf(dest, n, "%s", m[0] ? (char *)m : (char *)p);
	else
		snprintf(dest, n, "USB %04x:%04x", dd->idVendor, dd->idProduct);
}

/*
 * Opens interface alt (altsetting 0) of dev as place i: 0, or -1 with why
 * (what to record in the skip list).
 */
static int
usb_dev_open_iface(struct usb_dev *d, libusb_device *dev, const struct libusb_device_descriptor *dd,
		   const struct libusb_interface_descriptor *alt, int i, uint64_t now_us,
		   struct input_dev_info *info, char *why, size_t whylen)
{
	const struct libusb_endpoint_descriptor *ep = NULL;
	for (int k = 0; k < alt->bNumEndpoints && !ep; k++) {
		const struct libusb_endpoint_descriptor *e = &alt->endpoint[k];
		if ((e->bmAttributes & 3) == LIBUSB_TRANSFER_TYPE_INTERRUPT &&
		    (e->bEndpointAddress & LIBUSB_ENDPOINT_IN))
			ep = e;
	}
	if (!ep) {
		snprintf(why, whylen, "no interrupt-IN endpoint");
		return -1;
	}
	d->iface = alt->bInterfaceNumber;
	d->ep = ep->bEndpointAddress;
	int rc = libusb_open(dev, &d->h);
	if (rc < 0) {
		d->h = NULL;
		snprintf(why, whylen, "cannot open: %s%s", libusb_strerror(rc),
			 rc == LIBUSB_ERROR_ACCESS ? " (write access to /dev/bus/usb is needed)" : "");
		return -1;
	}
	usb_dev_name(d->h, dd, info->name, sizeof info->name);
	snprintf(d->rec.name, sizeof d->rec.name, "%s", info->name);
	snprintf(d->rec.phys, sizeof d->rec.phys, "%s", d->path);
	d->rec.bus = 0x03; /* BUS_USB, as hid-recorder's I: line gives it */
	d->rec.vid = dd->idVendor;
	d->rec.pid = dd->idProduct;
	char who[48];
	snprintf(who, sizeof who, "%.24s (%.20s)", info->name, d->path + 4);

	/* the driver set aside as the interface is claimed; by hand where auto-detach is missing */
	if (libusb_set_auto_detach_kernel_driver(d->h, 1) != LIBUSB_SUCCESS &&
	    libusb_kernel_driver_active(d->h, d->iface) == 1) {
		rc = libusb_detach_kernel_driver(d->h, d->iface);
		if (rc < 0 && rc != LIBUSB_ERROR_NOT_FOUND) {
			snprintf(why, whylen, "cannot detach the kernel's driver: %s",
				 libusb_strerror(rc));
			usb_dev_unclaim(d);
			return -1;
		}
		d->detached = rc == 0;
	}
	rc = libusb_claim_interface(d->h, d->iface);
	if (rc < 0) {
		snprintf(why, whylen, "cannot claim the interface: %s%s", libusb_strerror(rc),
			 rc == LIBUSB_ERROR_BUSY ? " (another program has it)" : "");
		usb_dev_unclaim(d);
		return -1;
	}
	d->claimed = 1;

	/* the report descriptor, or the boot protocol's */
	static struct hid_desc desc; /* large: kept off the stack; open runs on one thread */
	char perr[160] = "";
	int len = usb_dev_report_desc_len(alt->extra, alt->extra_length);
	int boot_kind = alt->bInterfaceSubClass == USB_HID_SUBCLASS_BOOT
				? alt->bInterfaceProtocol == USB_HID_PROTOCOL_MOUSE      ? HID_BOOT_MOUSE
				  : alt->bInterfaceProtocol == USB_HID_PROTOCOL_KEYBOARD ? HID_BOOT_KEYBOARD
											 : -1
				: -1;
	int parsed = -1;
	if (len <= 0 || len > HID_DESC_MAX_BYTES) {
		snprintf(perr, sizeof perr, "no usable HID class descriptor (report length %d)", len);
	} else {
		uint8_t *raw = malloc((size_t)len);
		rc = raw ? libusb_control_transfer(d->h,
						   LIBUSB_ENDPOINT_IN | LIBUSB_REQUEST_TYPE_STANDARD |
							   LIBUSB_RECIPIENT_INTERFACE,
						   LIBUSB_REQUEST_GET_DESCRIPTOR,
						   (uint16_t)(USB_DT_REPORT << 8), d->iface, raw,
						   (uint16_t)len, USB_DEV_CONTROL_MS)
			 : LIBUSB_ERROR_NO_MEM;
		if (rc < 0)
			snprintf(perr, sizeof perr, "GET_DESCRIPTOR(report) failed: %s",
				 libusb_strerror(rc));
		else
			parsed = hid_desc_parse(raw, (size_t)rc, &desc, perr, sizeof perr);
		if (parsed == 0) {
			memcpy(d->rec.desc, raw, (size_t)rc);
			d->rec.desc_len = (uint16_t)rc;
		}
		free(raw);
	}
	size_t boot_len = 0;
	if (parsed == 0) {
		if (alt->bInterfaceSubClass == USB_HID_SUBCLASS_BOOT &&
		    (rc = usb_dev_class_out(d, HID_REQ_SET_PROTOCOL, HID_PROTOCOL_REPORT, NULL, 0)) < 0)
			devlog(&usb.log, now_us, DEVLOG_DEVICE, "%s: SET_PROTOCOL(report) refused: %s",
			       d->path, libusb_strerror(rc));
	} else if (boot_kind >= 0) {
		rc = usb_dev_class_out(d, HID_REQ_SET_PROTOCOL, HID_PROTOCOL_BOOT, NULL, 0);
		if (rc < 0) {
			snprintf(why, whylen, "report descriptor refused (%.80s) and SET_PROTOCOL(boot) "
				 "failed: %s", perr, libusb_strerror(rc));
			usb_dev_unclaim(d);
			return -1;
		}
		devlog(&usb.log, now_us, DEVLOG_DEVICE, "%s: report descriptor refused (%s): "
		       "boot protocol", d->path, perr);
		hid_desc_boot((enum hid_boot)boot_kind, &desc);
		boot_len = boot_kind == HID_BOOT_MOUSE ? USB_BOOT_MOUSE_BYTES : USB_BOOT_KEYBOARD_BYTES;
		size_t nb;
		const uint8_t *b = hid_desc_boot_bytes((enum hid_boot)boot_kind, &nb);
		memcpy(d->rec.desc, b, nb);
		d->rec.desc_len = (uint16_t)nb;
	} else {
		snprintf(why, whylen, "report descriptor refused (%.120s); not a boot interface", perr);
		usb_dev_unclaim(d);
		return -1;
	}
	/* report on change only; a device without SET_IDLE stalls it, which is allowed */
	rc = usb_dev_class_out(d, HID_REQ_SET_IDLE, 0, NULL, 0);
	if (rc < 0 && rc != LIBUSB_ERROR_PIPE)
		devlog(&usb.log, now_us, DEVLOG_DEVICE, "%s: SET_IDLE failed: %s", d->path,
		       libusb_strerror(rc));
	usb_intr_init(&d->u, &desc, boot_len, usb_dev_class(&desc), (uint16_t)i, who);
	if (!boot_len)
		usb_dev_write_multipliers(d, &d->u.desc, now_us);

	/* the transfer: the largest report, or a packet if that is larger */
	int maxreport = 0;
	for (unsigned r = 0; r < d->u.desc.nreports; r++)
		if (d->u.desc.reports[r].bytes > maxreport)
			maxreport = d->u.desc.reports[r].bytes;
	int maxpacket = libusb_get_max_packet_size(dev, d->ep);
	d->buflen = maxreport > maxpacket ? maxreport : maxpacket;
	if (d->buflen <= 0)
		d->buflen = 64;
	d->buf = malloc((size_t)d->buflen);
	d->xfer = libusb_alloc_transfer(0);
	if (!d->buf || !d->xfer) {
		snprintf(why, whylen, "out of memory");
		goto fail;
	}
	libusb_fill_interrupt_transfer(d->xfer, d->h, d->ep, d->buf, d->buflen,
				       usb_dev_transfer_done, d, 0);
	rc = libusb_submit_transfer(d->xfer);
	if (rc < 0) {
		snprintf(why, whylen, "cannot submit the interrupt transfer: %s", libusb_strerror(rc));
		goto fail;
	}
	d->submitted = 1;
	info->vendor = dd->idVendor;
	info->product = dd->idProduct;
	info->iface = d->iface;
	info->cls = d->u.cls;
	info->dpi = INPUT_DEV_DPI_DEFAULT;
	snprintf(info->path, sizeof info->path, "%s", d->path);
	return 0;
fail:
	if (d->xfer)
		libusb_free_transfer(d->xfer);
	free(d->buf);
	d->xfer = NULL;
	d->buf = NULL;
	usb_dev_unclaim(d);
	return -1;
}

/* ---- the backend ------------------------------------------------------- */

static int
usb_backend_fd(const void *dev)
{
	(void)dev;
	return -1; /* the shared fds serve it */
}

static int
usb_backend_read(void *dev, uint64_t now_us, struct input_queue *q)
{
	struct usb_dev *d = dev;
	if (d->halted && !d->u.gone) {
		d->halted = 0;
		int rc = libusb_clear_halt(d->h, d->ep);
		if (rc < 0 && rc != LIBUSB_ERROR_NOT_FOUND)
			usb_intr_lost(&d->u, libusb_strerror(rc), rc == LIBUSB_ERROR_NO_DEVICE, now_us);
		else
			usb_dev_submit(d, now_us);
	}
	return usb_intr_reap(&d->u, now_us, q);
}

static void
usb_backend_close(void *dev, uint64_t now_us, struct input_queue *q)
{
	struct usb_dev *d = dev;
	/* the transfer back first: the kernel may write its buffer until then */
	d->closing = 1;
	if (d->submitted) {
		libusb_cancel_transfer(d->xfer);
		for (int waited = 0; d->submitted && waited < USB_DEV_CANCEL_WAIT_MS; waited += 10)
			usb_dev_handle_events(now_us, q, 10000);
	}
	if (q)
		hid_input_release_all(&d->u.in, now_us, q);
	if (d->submitted) /* never came back: leak it rather than free what the kernel holds */
		devlog(&d->u.in.log, now_us, DEVLOG_KERNEL,
		       "the cancelled transfer did not come back in %d ms", USB_DEV_CANCEL_WAIT_MS);
	else {
		libusb_free_transfer(d->xfer);
		free(d->buf);
	}
	usb_dev_unclaim(d);
	usb.ndevs--;
	free(d);
}

/* a completed transfer is a read; what the device or the bus got wrong, errors */
static void
usb_backend_stats(const void *dev, struct input_dev_stats *dest)
{
	const struct usb_intr *u = &((const struct usb_dev *)dev)->u;
	*dest = (struct input_dev_stats){
		.reads = u->transfers,
		.errors = u->stalls + u->errors + u->overflows + u->in.short_reports +
			  u->in.long_reports + u->in.unknown_reports,
	};
}

static int
usb_backend_open_spec(struct input_devs *s, const char *arg, char *err, size_t errlen)
{
	uint16_t vid, pid;
	int want;
	char what[INPUT_DEVS_SPEC_MAX];
	if (!arg) {
		snprintf(err, errlen, "input 'usb': expected usb:VID:PID[:IFACE]");
		return -1;
	}
	if (usb_dev_parse_spec(arg, &vid, &pid, &want, err, errlen) < 0)
		return -1;
	snprintf(what, sizeof what, "usb:%.200s", arg);
	char why[INPUT_DEVS_WHY_MAX];
	if (usb_dev_context(why, sizeof why) < 0) {
		input_devs_skip(s, what, why);
		return 0;
	}
	/*
	 * the control requests below handle events too: the other devices'
	 * reports that complete meanwhile go to the set's queue
	 */
	usb.q = s->q ? s->q : &usb_discard;
	usb.now_us = s->now_us;
	libusb_device **list;
	ssize_t n = libusb_get_device_list(usb.ctx, &list);
	if (n < 0) {
		input_devs_skip(s, what, libusb_strerror((int)n));
		usb.q = NULL;
		return 0;
	}
	int opened = 0, found = 0;
	for (ssize_t k = 0; k < n; k++) {
		struct libusb_device_descriptor dd;
		struct libusb_config_descriptor *cfg;
		if (libusb_get_device_descriptor(list[k], &dd) < 0 || dd.idVendor != vid ||
		    dd.idProduct != pid)
			continue;
		if (libusb_get_active_config_descriptor(list[k], &cfg) < 0) {
			char path[INPUT_DEV_PATH_MAX];
			usb_dev_path(list[k], want < 0 ? 0 : want, path, sizeof path);
			input_devs_skip(s, path, "no active configuration");
			found = 1;
			continue;
		}
		for (int f = 0; f < cfg->bNumInterfaces; f++) {
			if (cfg->interface[f].num_altsetting < 1)
				continue;
			const struct libusb_interface_descriptor *alt = &cfg->interface[f].altsetting[0];
			if (alt->bInterfaceClass != USB_HID_CLASS ||
			    (want >= 0 && alt->bInterfaceNumber != want))
				continue;
			found = 1;
			char path[INPUT_DEV_PATH_MAX];
			usb_dev_path(list[k], alt->bInterfaceNumber, path, sizeof path);
			if (input_devs_find(s, &input_backend_usb, path) >= 0)
				continue;
			int i = input_devs_free_place(s, path);
			if (i < 0)
				continue;
			struct usb_dev *d = calloc(1, sizeof *d);
			if (!d) {
				input_devs_skip(s, path, "out of memory");
				continue;
			}
			snprintf(d->path, sizeof d->path, "%s", path);
			struct input_dev_info info;
			memset(&info, 0, sizeof info);
			if (usb_dev_open_iface(d, list[k], &dd, alt, i, s->now_us, &info, why,
					       sizeof why) < 0) {
				input_devs_skip(s, path, why);
				free(d);
				continue;
			}
			usb.ndevs++;
			input_devs_put(s, i, &input_backend_usb, d, &info);
			opened++;
		}
		libusb_free_config_descriptor(cfg);
	}
	libusb_free_device_list(list, 1);
	usb.q = NULL;
	if (!found) {
		char none[80];
		if (want >= 0)
			snprintf(none, sizeof none, "no USB device %04x:%04x with HID interface %x", vid,
				 pid, want);
		else
			snprintf(none, sizeof none, "no USB device %04x:%04x with a HID interface", vid,
				 pid);
		input_devs_skip(s, what, none);
	}
	return opened;
}

static int
usb_backend_shared_fds(struct pollfd *fds, int max)
{
	if (!usb.ctx)
		return 0;
	int n = usb.nfds < max ? usb.nfds : max;
	memcpy(fds, usb.fds, (size_t)n * sizeof *fds);
	return n;
}

static void
usb_backend_shared_work(uint64_t now_us, struct input_queue *q)
{
	if (usb.ctx)
		usb_dev_handle_events(now_us, q, 0);
}

static int
usb_backend_arrived(void)
{
	int a = usb.arrived;
	usb.arrived = 0;
	return a;
}

/* the hid-recorder file's head: the interface's descriptor as its decoder reads it */
static int
usb_backend_describe(const void *dev, FILE *out)
{
	const struct usb_dev *d = dev;
	rec_hid_write_device(out, &d->rec, -1);
	return ferror(out) ? -1 : 0;
}

const struct input_backend input_backend_usb = {
	.name = "usb",
	.usage = "usb:VID:PID[:IFACE]",
	.open_spec = usb_backend_open_spec,
	.fd = usb_backend_fd,
	.read = usb_backend_read,
	.close = usb_backend_close,
	.stats = usb_backend_stats,
	.shared_fds = usb_backend_shared_fds,
	.shared_work = usb_backend_shared_work,
	.arrived = usb_backend_arrived,
	.rec_format = "hid-recorder",
	.describe = usb_backend_describe,
};

void
usb_dev_set_tap(void *dev, usb_dev_tap_fn fn, void *ctx)
{
	struct usb_dev *d = dev;
	d->tap = fn;
	d->tap_ctx = ctx;
}

void
usb_dev_describe(const void *dev, struct rec_hid_device *dest)
{
	*dest = ((const struct usb_dev *)dev)->rec;
}
