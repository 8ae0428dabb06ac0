/*
 * hid_input.h - HID input reports to events, by the mapping the Linux
 * kernel's hid-input applies (drivers/hid/hid-input.c,
 * hidinput_configure_usage and hidinput_hid_event) for what mice and
 * keyboards use:
 *
 *   Generic Desktop X, Y      relative: INPUT_MOTION (device counts);
 *                             absolute: INPUT_POINTER, 0..1 over the logical range
 *   Generic Desktop Wheel     relative: INPUT_WHEEL, INPUT_WHEEL_V
 *   Consumer AC Pan (0x238)   INPUT_WHEEL, INPUT_WHEEL_H
 *   Button page               INPUT_BUTTON: button n -> BTN_MOUSE + n - 1 in a mouse or
 *                             pointer (BTN_LEFT, BTN_RIGHT, BTN_MIDDLE, BTN_SIDE, ...),
 *                             BTN_JOYSTICK/BTN_GAMEPAD/BTN_MISC + n - 1 elsewhere
 *   Keyboard page             INPUT_KEY by the kernel's table (hid_keymap.c)
 *
 * Everything else is ignored, as are constant fields. Variable fields
 * report on change (values clamped to the logical range; out-of-range
 * values dropped where the field has a null state); array fields press
 * what appears and release what disappears since the last report of the
 * same field, and a report holding ErrorRollOver (keyboard usage 0x01)
 * leaves its array field as it was. Wheels with a Resolution Multiplier
 * count in 1/multiplier detents: x is the motion in 1/120 detent,
 * value the whole detents accumulated, flags INPUT_F_HIRES. A button or
 * key is pressed once and released once whatever its fields say. Each
 * report ends with one INPUT_FRAME.
 *
 * Where we differ from the kernel: a short report is dropped (the kernel
 * pads it with zeros), a long one too (the kernel ignores the excess);
 * a usage mapped twice is not dropped (the kernel keeps the first button
 * or relative axis of a code), so two X fields add up.
 */
#ifndef POSTURE_DEVICES_HID_INPUT_H
#define POSTURE_DEVICES_HID_INPUT_H

#include <stddef.h>
#include <stdint.h>

#include "devices/devlog.h"
#include "devices/hid_desc.h"
#include "devices/queue.h"

#define HID_INPUT_CODES 768 /* KEY_MAX + 1 */

/* what one value of a variable field (or one usage of an array) does */
enum hid_input_role {
	HID_ROLE_NONE,
	HID_ROLE_KEY,
	HID_ROLE_BUTTON,
	HID_ROLE_REL_X,
	HID_ROLE_REL_Y,
	HID_ROLE_ABS_X,
	HID_ROLE_ABS_Y,
	HID_ROLE_WHEEL,
	HID_ROLE_HWHEEL,
};

struct hid_input {
	const struct hid_desc *d;
	uint16_t device;
	struct devlog log;
	uint64_t reports;         /* decoded */
	uint64_t short_reports;   /* dropped: fewer bytes than the report has */
	uint64_t long_reports;    /* dropped: more bytes */
	uint64_t unknown_reports; /* dropped: an id the descriptor does not have, or empty */
	double x, y;              /* the absolute position, 0..1 */
	/*
	 * per value slot (hid_desc_field.value_first + i): the role and code
	 * of a variable field's value, and the last value seen (arrays and
	 * absolute variables) or the wheel's remainder in 1/120 (wheels)
	 */
	uint8_t role[HID_DESC_MAX_VALUES];
	uint16_t code[HID_DESC_MAX_VALUES];
	int32_t value[HID_DESC_MAX_VALUES];
	/* a bitmap's bits as last seen, 8 at a time, at each chunk's first value slot */
	uint8_t bits[HID_DESC_MAX_VALUES];
	uint8_t held[HID_INPUT_CODES]; /* 0 up, else the enum input_kind + 1 it was pressed as */
};

/*
 * Prepares h to decode reports of descriptor d (kept as a pointer: d must
 * outlive h) for device index `device`; `who` names it in log lines.
 * Nothing is held down.
 */
void hid_input_init(struct hid_input *h, const struct hid_desc *d, uint16_t device,
		    const char *who);

/*
 * Decodes one report (the id byte first when the descriptor has ids) into
 * events on q, stamped t_us, ending with INPUT_FRAME. Returns 0, or -1
 * when the report was dropped (short, long, unknown id or empty: counted
 * in h and logged with the device to blame; nothing else changes).
 */
int hid_input_feed(struct hid_input *h, const uint8_t *report, size_t n, uint64_t t_us,
		   struct input_queue *q);

/*
 * Releases every button and key h holds (a device that went away), then
 * a frame end if anything was released; the next report starts afresh.
 */
void hid_input_release_all(struct hid_input *h, uint64_t t_us, struct input_queue *q);

/*
 * The i-th value of field f in a report's data (after the id byte), as the
 * kernel extracts it: sign-extended when the logical minimum is negative.
 * The caller makes sure data holds the field.
 */
int32_t hid_input_value(const struct hid_desc_field *f, const uint8_t *data, unsigned i);

/*
 * The role of a usage in field f and, for keys and buttons, its evdev
 * code in *code (0 otherwise).
 */
enum hid_input_role hid_input_map(const struct hid_desc_field *f, uint32_t usage,
				  uint16_t *code);

#endif
