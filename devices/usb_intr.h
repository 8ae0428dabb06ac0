/*
 * usb_intr.h - what the USB backend does with each completed interrupt-IN
 * transfer of a HID interface, kept apart from libusb so that a test can
 * drive it with recorded reports: the payload goes to the HID decoder
 * (the same bytes hidraw would give), and the status decides what the
 * transfer does next.
 *
 *   completed      the report is decoded; resubmit
 *   stall          the endpoint halted: clear the halt, then resubmit
 *   timed out      (we submit without a timeout, so only a kernel's own) resubmit
 *   overflow       the device sent more than the buffer holds: logged; resubmit
 *   error          logged; resubmit
 *   no device      the device is gone: nothing more is submitted
 *   cancelled      we are closing: nothing more is submitted
 *
 * A device that only stalls or fails (USB_INTR_FAULTS_MAX completions in a
 * row with no report) is treated as gone, so a broken endpoint cannot
 * keep the loop busy. Each fault is logged through devlog, rate-limited,
 * blaming the device (or the kernel for errors it does not explain), and
 * changes nothing else. In boot protocol the report is the boot one
 * (3 bytes for a mouse, 8 for a keyboard) and what follows it is vendor
 * data (HID 1.11 Appendix B), so it is cut off before decoding.
 *
 * The transfer callback only records; what the device lost is released,
 * and INPUT_REMOVED queued, by usb_intr_reap, called from the backend's
 * read after the event handling: the device set's rule for every backend.
 */
#ifndef POSTURE_DEVICES_USB_INTR_H
#define POSTURE_DEVICES_USB_INTR_H

#include <stddef.h>
#include <stdint.h>

#include "devices/event.h"
#include "devices/hid_desc.h"
#include "devices/hid_input.h"
#include "devices/queue.h"

#define USB_INTR_FAULTS_MAX 16 /* stalls and errors in a row before the device counts as gone */

/* how a transfer ended (libusb_transfer_status, in our words) */
enum usb_intr_status {
	USB_INTR_COMPLETED,
	USB_INTR_ERROR,
	USB_INTR_TIMED_OUT,
	USB_INTR_CANCELLED,
	USB_INTR_STALL,
	USB_INTR_NO_DEVICE,
	USB_INTR_OVERFLOW,
};

/* what to do with the transfer next */
enum usb_intr_next {
	USB_INTR_RESUBMIT,
	USB_INTR_CLEAR_HALT, /* clear the endpoint's halt, then resubmit */
	USB_INTR_STOP,       /* submit nothing more (closing, or the device is gone) */
};

struct usb_intr {
	struct hid_desc desc;  /* the interface's descriptor (or the boot one) */
	struct hid_input in;   /* the decoder, over desc */
	enum input_class cls;  /* for INPUT_REMOVED */
	size_t boot_len;       /* boot protocol: the report's length; 0 in report protocol */
	uint8_t gone;          /* the device went away or broke: reap it */
	uint8_t reaped;        /* ... and that was reported */
	unsigned faults;       /* stalls and errors since the last completed transfer */

	/* counters */
	uint64_t transfers;    /* completed */
	uint64_t stalls, errors, timeouts, overflows, cut;
};

/*
 * Prepares u for an interface with descriptor desc (copied: u must not
 * move afterwards, its decoder points into it), decoding as device index
 * `device` of class cls; boot_len is the boot report's length when the
 * interface runs in boot protocol, else 0. `who` names it in log lines.
 */
void usb_intr_init(struct usb_intr *u, const struct hid_desc *desc, size_t boot_len,
		   enum input_class cls, uint16_t device, const char *who);

/*
 * One transfer ended with status st and len bytes in buf: decodes a
 * completed report into q (stamped now_us) and says what comes next.
 * After USB_INTR_STOP for a gone device, u->gone is set.
 */
enum usb_intr_next usb_intr_complete(struct usb_intr *u, enum usb_intr_status st,
				     const uint8_t *buf, size_t len, uint64_t now_us,
				     struct input_queue *q);

/*
 * The transfer could not be submitted again (err: libusb's words, gone:
 * the device is no longer there): the device counts as gone.
 */
void usb_intr_lost(struct usb_intr *u, const char *err, int gone, uint64_t now_us);

/*
 * What read says: 0 while the device is there; -1 once it is gone, the
 * first time after releasing every button and key it held and queuing
 * INPUT_REMOVED into q.
 */
int usb_intr_reap(struct usb_intr *u, uint64_t now_us, struct input_queue *q);

/* a short name of a status, for logs */
const char *usb_intr_status_to_str(enum usb_intr_status st);

#endif
