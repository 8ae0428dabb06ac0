/* usb_intr.c - completed interrupt transfers to decoder input and what comes next (see usb_intr.h) */
#include "devices/usb_intr.h"

#include <string.h>

void
usb_intr_init(struct usb_intr *u, const struct hid_desc *desc, size_t boot_len,
	      enum input_class cls, uint16_t device, const char *who)
{
	memset(u, 0, sizeof *u);
	u->desc = *desc;
	hid_input_init(&u->in, &u->desc, device, who);
	u->cls = cls;
	u->boot_len = boot_len;
}

const char *
usb_intr_status_to_str(enum usb_intr_status st)
{
	switch (st) {
	case USB_INTR_COMPLETED:
		return "completed";
	case USB_INTR_ERROR:
		return "error";
	case USB_INTR_TIMED_OUT:
		return "timed out";
	case USB_INTR_CANCELLED:
		return "cancelled";
	case USB_INTR_STALL:
		return "stall";
	case USB_INTR_NO_DEVICE:
		return "no device";
	case USB_INTR_OVERFLOW:
		return "overflow";
	}
	return "?";
}

/* a stall or an error: counted; too many in a row and the device is given up */
static enum usb_intr_next
usb_intr_fault(struct usb_intr *u, uint64_t now_us, enum usb_intr_next next)
{
	if (++u->faults < USB_INTR_FAULTS_MAX)
		return next;
	devlog(&u->in.log, now_us, DEVLOG_DEVICE,
	       "%u transfers in a row failed: the device is given up", u->faults);
	u->gone = 1;
	return USB_INTR_STOP;
}

enum usb_intr_next
usb_intr_complete(struct usb_intr *u, enum usb_intr_status st, const uint8_t *buf, size_t len,
		  uint64_t now_us, struct input_queue *q)
{
	if (u->gone)
		return USB_INTR_STOP;
	switch (st) {
	case USB_INTR_COMPLETED:
		u->faults = 0;
		u->transfers++;
		if (len == 0) /* a zero-length packet: no report */
			return USB_INTR_RESUBMIT;
		if (u->boot_len && len > u->boot_len) {
			len = u->boot_len; /* vendor bytes after the boot report */
			u->cut++;
		}
		hid_input_feed(&u->in, buf, len, now_us, q); /* a bad report is logged there */
		return USB_INTR_RESUBMIT;
	case USB_INTR_STALL:
		u->stalls++;
		devlog(&u->in.log, now_us, DEVLOG_DEVICE,
		       "the interrupt endpoint stalled: clearing the halt");
		return usb_intr_fault(u, now_us, USB_INTR_CLEAR_HALT);
	case USB_INTR_ERROR:
		u->errors++;
		devlog(&u->in.log, now_us, DEVLOG_KERNEL, "an interrupt transfer failed");
		return usb_intr_fault(u, now_us, USB_INTR_RESUBMIT);
	case USB_INTR_TIMED_OUT:
		u->timeouts++;
		return USB_INTR_RESUBMIT;
	case USB_INTR_OVERFLOW:
		u->overflows++;
		devlog(&u->in.log, now_us, DEVLOG_DEVICE,
		       "sent more than its largest report (%zu bytes): dropped", len);
		return usb_intr_fault(u, now_us, USB_INTR_RESUBMIT);
	case USB_INTR_NO_DEVICE:
		u->gone = 1;
		return USB_INTR_STOP;
	case USB_INTR_CANCELLED:
		return USB_INTR_STOP;
	}
	devlog(&u->in.log, now_us, DEVLOG_US, "unknown transfer status %d", (int)st);
	return USB_INTR_RESUBMIT;
}

void
usb_intr_lost(struct usb_intr *u, const char *err, int gone, uint64_t now_us)
{
	if (u->gone)
		return;
	if (!gone)
		devlog(&u->in.log, now_us, DEVLOG_KERNEL,
		       "the interrupt transfer cannot be submitted again (%s)", err);
	u->gone = 1;
}

int
usb_intr_reap(struct usb_intr *u, uint64_t now_us, struct input_queue *q)
{
	if (!u->gone)
		return 0;
	if (u->reaped)
		return -1;
	u->reaped = 1;
	int held = 0;
	for (unsigned c = 0; c < HID_INPUT_CODES; c++)
		held += u->in.held[c] != 0;
	hid_input_release_all(&u->in, now_us, q);
	devlog_last(&u->in.log, now_us, DEVLOG_DEVICE, "gone; %d key(s) and button(s) released", held);
	input_queue_removed(q, now_us, u->in.device, u->cls);
	return -1;
}
