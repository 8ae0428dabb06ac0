/*
 * hid_keymap.c - keyboard usages (HID Usage Tables, page 0x07) to Linux key
 * codes. The table holds the values of the Linux kernel's hid_keyboard[256]
 * in drivers/hid/hid-input.c (mainline, 2024): 0 means the usage is
 * ignored, 240 is KEY_UNKNOWN. Only the numbers are taken.
 */
#include "devices/hid_keymap.h"

#include <linux/input-event-codes.h>

#define unk KEY_UNKNOWN

static const uint8_t keymap[256] = {
	/* 0x00 */ 0, 0, 0, 0, 30, 48, 46, 32, 18, 33, 34, 35, 23, 36, 37, 38,
	/* 0x10 */ 50, 49, 24, 25, 16, 19, 31, 20, 22, 47, 17, 45, 21, 44, 2, 3,
	/* 0x20 */ 4, 5, 6, 7, 8, 9, 10, 11, 28, 1, 14, 15, 57, 12, 13, 26,
	/* 0x30 */ 27, 43, 43, 39, 40, 41, 51, 52, 53, 58, 59, 60, 61, 62, 63, 64,
	/* 0x40 */ 65, 66, 67, 68, 87, 88, 99, 70, 119, 110, 102, 104, 111, 107, 109, 106,
	/* 0x50 */ 105, 108, 103, 69, 98, 55, 74, 78, 96, 79, 80, 81, 75, 76, 77, 71,
	/* 0x60 */ 72, 73, 82, 83, 86, 127, 116, 117, 183, 184, 185, 186, 187, 188, 189, 190,
	/* 0x70 */ 191, 192, 193, 194, 134, 138, 130, 132, 128, 129, 131, 137, 133, 135, 136, 113,
	/* 0x80 */ 115, 114, unk, unk, unk, 121, unk, 89, 93, 124, 92, 94, 95, unk, unk, unk,
	/* 0x90 */ 122, 123, 90, 91, 85, unk, unk, unk, unk, unk, unk, unk, 111, unk, unk, unk,
	/* 0xa0 */ unk, unk, unk, unk, unk, unk, unk, unk, unk, unk, unk, unk, unk, unk, unk, unk,
	/* 0xb0 */ unk, unk, unk, unk, unk, unk, 179, 180, unk, unk, unk, unk, unk, unk, unk, unk,
	/* 0xc0 */ unk, unk, unk, unk, unk, unk, unk, unk, unk, unk, unk, unk, unk, unk, unk, unk,
	/* 0xd0 */ unk, unk, unk, unk, unk, unk, unk, unk, 111, unk, unk, unk, unk, unk, unk, unk,
	/* 0xe0 */ 29, 42, 56, 125, 97, 54, 100, 126, 164, 166, 165, 163, 161, 115, 114, 113,
	/* 0xf0 */ 150, 158, 159, 128, 136, 177, 178, 176, 142, 152, 173, 140, unk, unk, unk, unk,
};

uint16_t
hid_keymap_key(uint32_t id)
{
	if (id >= 256)
		return KEY_UNKNOWN;
	return keymap[id];
}
