/*
 * event.h - the one input event record every backend produces (DESIGN.md,
 * "Input"): fixed size, no pointers, so it can sit in a queue, a recording
 * or a socket line alike. Key and button codes are Linux evdev codes
 * (linux/input-event-codes.h) whatever the source, so a keyboard gives the
 * same codes read through evdev, raw HID or USB.
 */
#ifndef POSTURE_DEVICES_EVENT_H
#define POSTURE_DEVICES_EVENT_H

#include <stdint.h>

enum input_kind {
	INPUT_MOTION,   /* relative pointer motion: x, y in device counts */
	INPUT_POINTER,  /* absolute position: x, y normalised 0..1, or pixels in view `code` */
	INPUT_BUTTON,   /* code: BTN_*; value 1 press, 0 release */
	INPUT_WHEEL,    /* code: INPUT_WHEEL_V or _H; value detents, x the same in 1/120 */
	INPUT_KEY,      /* code: KEY_*; value 1 press, 0 release, 2 repeat */
	INPUT_VALUATOR, /* code: the panel map's axis index; x the physical value */
	INPUT_ADDED,    /* a device arrived (code: its class, enum input_class) */
	INPUT_REMOVED,  /* ... and left; its buttons and keys were released first */
	INPUT_FRAME,    /* the end of a device's frame: SYN_REPORT, or the end of a report */
};

enum input_wheel_axis { INPUT_WHEEL_V, INPUT_WHEEL_H };

enum input_class { INPUT_CLASS_MOUSE, INPUT_CLASS_KEYBOARD, INPUT_CLASS_PANEL, INPUT_CLASS_OTHER };

/* flags */
#define INPUT_F_STALE 0x01   /* a valuator whose value is older than its timeout */
#define INPUT_F_HIRES 0x02   /* a wheel that reports in 1/120 detents (x exact, value rounded) */
#define INPUT_F_VIEW 0x04    /* a pointer position in pixels of view `code`, not 0..1 */

#define INPUT_POINTER_VIEW_NONE 0xffff

struct input_event_rec {
	uint64_t t_us;    /* CLOCK_MONOTONIC, or the kernel's timestamp where the device gives one */
	uint16_t device;  /* the daemon's device index; 0xffff: injected over the socket */
	uint8_t kind;     /* enum input_kind */
	uint8_t flags;
	uint16_t code;
	int32_t value;
	double x, y;
};

#define INPUT_DEVICE_SOCKET 0xffff

#include <linux/input-event-codes.h>

/* a press or release of the left, middle or right mouse button: the manipulation's buttons */
static inline int
input_is_mouse_button(const struct input_event_rec *e)
{
	return e->kind == INPUT_BUTTON &&
	       (e->code == BTN_LEFT || e->code == BTN_MIDDLE || e->code == BTN_RIGHT);
}

/* a short lowercase name of the kind, for logs and the decoders' text output */
const char *input_kind_to_str(enum input_kind k);

#endif
