/*
 * usb_dev.h - the USB backend: HID interfaces read through libusb-1.0,
 * with the kernel's driver set aside. Spec: usb:VID:PID[:IFACE] (hex);
 * every HID interface of every matching device (or only IFACE) is one
 * device of the set, at path "usb:BUS-PORTS:IFACE" (usb:1-1.2:0).
 *
 * Opening an interface: the kernel's driver is detached as the interface
 * is claimed (libusb's auto-detach, one ioctl, so usbhid cannot slip in
 * between), the report descriptor is read (GET_DESCRIPTOR 0x22) and
 * parsed by hid_desc. A descriptor the parser takes runs in report
 * protocol: SET_PROTOCOL(report) for boot-subclass interfaces (they may
 * have been left in boot protocol), SET_IDLE(0) (report only on change,
 * as usbhid asks), and the Resolution Multiplier features written
 * (SET_REPORT) so a hi-res wheel sends 1/n detents; a multiplier the
 * device refuses is taken back, so the wheel counts whole detents. A
 * descriptor refused (or unreadable) falls back to boot protocol on a
 * boot mouse or keyboard, and leaves any other interface closed, with
 * the reason in the skip list.
 *
 * Reading: one interrupt-IN transfer per interface, always submitted,
 * resubmitted from its callback (devices/usb_intr.h decides). All
 * interfaces share one libusb context, whose fds the daemon polls
 * (shared_fds) and whose events are handled with a zero timeout
 * (shared_work): the callbacks decode into the queue shared_work was
 * given. A device gone shows as a transfer ending with NO_DEVICE; the
 * device's read, called by the set after the work, then releases what it
 * held, queues INPUT_REMOVED and returns -1. Nothing of ours allocates
 * per report (the buffer and transfer are made at open); libusb's Linux
 * backend itself callocs a URB array on every submission
 * (os/linux_usbfs.c, submit_bulk_transfer), which we cannot avoid
 * through its asynchronous API. libusb also runs one thread of its own,
 * its udev monitor; that thread only posts to the context, whose events
 * are handled here on the daemon's thread.
 *
 * Hot-plug: a libusb hot-plug callback (it runs inside the event
 * handling, so it only notes the arrival) makes `arrived` say 1 once,
 * after which the set re-opens its specs (input_devs_rescan) outside any
 * libusb callback. Without udevd (libusb built with udev listens to
 * udevd's events) arrivals are not seen: a rescan opens them instead.
 *
 * Closing: the transfer is cancelled and its callback waited for (events
 * handled until it comes back, at most USB_DEV_CANCEL_WAIT_MS), the
 * interface released, which re-attaches the kernel's driver, and the
 * handle closed.
 */
#ifndef POSTURE_DEVICES_USB_DEV_H
#define POSTURE_DEVICES_USB_DEV_H

#include <stddef.h>
#include <stdint.h>

#include "devices/input_backend.h"
#include "devices/rec_hid.h"
#include "devices/usb_intr.h"

#define USB_DEV_CANCEL_WAIT_MS 500 /* a cancelled transfer's callback is waited for this long */
#define USB_DEV_CONTROL_MS 1000    /* timeout of each control request at open */

/*
 * Parses a spec's argument "VID:PID[:IFACE]" (hex, 1-4 digits each, IFACE
 * 1-2): 0, or -1 with the reason in err. *iface is -1 when not given.
 */
int usb_dev_parse_spec(const char *arg, uint16_t *vid, uint16_t *pid, int *iface, char *err,
		       size_t errlen);

/*
 * Ends the backend's libusb context when no device is open (tests, and
 * a daemon that wants a clean exit). Returns 0, or -1 while devices are open.
 */
int usb_dev_exit(void);

/* the backend for the device set: usb:VID:PID[:IFACE] (devices/input_backend.h) */
extern const struct input_backend input_backend_usb;

/*
 * For a recorder (posture-input record usb:...): fn gets a copy of every
 * report of the device (dev: a usb place's device in the set) as the
 * decoder takes it, stamped with the time of the loop's work.
 */
typedef void (*usb_dev_tap_fn)(void *ctx, uint64_t t_us, const uint8_t *report, size_t n);
void usb_dev_set_tap(void *dev, usb_dev_tap_fn fn, void *ctx);

/* what a hid-recorder file says of the device first: name, ids, the descriptor decoded by */
void usb_dev_describe(const void *dev, struct rec_hid_device *dest);

#endif
