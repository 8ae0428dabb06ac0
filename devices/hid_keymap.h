/*
 * hid_keymap.h - the Keyboard/Keypad usage page (0x07) to Linux key codes,
 * as the kernel's hid-input maps them.
 */
#ifndef POSTURE_DEVICES_HID_KEYMAP_H
#define POSTURE_DEVICES_HID_KEYMAP_H

#include <stdint.h>

/*
 * The KEY_* code (linux/input-event-codes.h) for keyboard usage id `id`:
 * 0 for the usages the kernel ignores (0x00-0x03 among them), KEY_UNKNOWN
 * for those it maps to no particular key and for ids of 256 and above.
 */
uint16_t hid_keymap_key(uint32_t id);

#endif
