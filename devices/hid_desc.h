/*
 * hid_desc.h - the HID 1.11 report descriptor, read as the Linux kernel
 * reads it (drivers/hid/hid-core.c): short items of 0, 1, 2 or 4 data
 * bytes, main, global and local items, Push/Pop, extended (32-bit) usages,
 * Usage Minimum/Maximum ranges that accumulate (a second pair appends to
 * the first), Logical Maximum read as signed only when Logical Minimum is
 * negative, report ids, padding, arrays and variables of 1-32 bits at any
 * bit offset, and any number of top-level collections.
 *
 * The result is one fixed-size struct with no pointers: input reports by
 * id, each with its fields. A field's usages are kept as runs (one Usage
 * item is a run of one, a Usage Minimum/Maximum pair a run of many), in
 * the order the descriptor gives them, so the i-th usage of a field is the
 * kernel's field->usage[i].hid without expanding the ranges. Output and
 * feature reports are sized and checked but not kept, except the
 * Resolution Multiplier features, which set the hi-res wheels.
 *
 * Where we differ from the kernel: long items are skipped (the kernel
 * refuses them); input data fields must be 1-32 bits (the kernel truncates
 * larger ones); an input report is at most HID_DESC_MAX_REPORT_BITS; an
 * input array field holds at most HID_DESC_MAX_ARRAY values (the decoder
 * compares old and new values pairwise); a Usage Minimum above its
 * Maximum is refused; and the fixed arrays below bound what a descriptor
 * may hold. Each is an error naming the byte.
 */
#ifndef POSTURE_DEVICES_HID_DESC_H
#define POSTURE_DEVICES_HID_DESC_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#define HID_DESC_MAX_BYTES 4096        /* the kernel's HID_MAX_DESCRIPTOR_SIZE */
#define HID_DESC_MAX_REPORTS 32        /* input reports */
#define HID_DESC_MAX_FIELDS 128        /* input fields, padding included */
#define HID_DESC_MAX_RUNS 512          /* usage runs over all input fields */
#define HID_DESC_MAX_COLLECTIONS 64
#define HID_DESC_MAX_DEPTH 16          /* collections open at once */
#define HID_DESC_MAX_VALUES 2048       /* values of data fields, over all input reports */
#define HID_DESC_MAX_ARRAY 64          /* values of one array field (keyboards have 6-14) */
#define HID_DESC_MAX_MULTIPLIERS 8     /* Resolution Multiplier features */
#define HID_DESC_MAX_REPORT_BITS 4096  /* one input report's data, id byte not counted */
#define HID_DESC_MAX_OTHER_BITS (16383 * 8) /* output and feature reports (the kernel's bound) */
#define HID_DESC_MAX_USAGES 12288      /* usages of one field (the kernel's HID_MAX_USAGES) */
#define HID_DESC_MAX_COUNT 12288       /* Report Count (the kernel's bound) */
#define HID_DESC_MAX_SIZE 256          /* Report Size (the kernel's bound) */
#define HID_DESC_STACK 4               /* Push depth (the kernel's HID_GLOBAL_STACK_SIZE) */
#define HID_DESC_NONE 0xffff           /* no collection, no report */

/* the main item's data bits (HID 1.11 6.2.2.5) */
#define HID_FIELD_CONSTANT 0x001
#define HID_FIELD_VARIABLE 0x002
#define HID_FIELD_RELATIVE 0x004
#define HID_FIELD_WRAP 0x008
#define HID_FIELD_NONLINEAR 0x010
#define HID_FIELD_NO_PREFERRED 0x020
#define HID_FIELD_NULL_STATE 0x040
#define HID_FIELD_BUFFERED_BYTES 0x100

/* usages the decoder and the parser know by value: page << 16 | id */
#define HID_USAGE_GD_POINTER 0x00010001u
#define HID_USAGE_GD_MOUSE 0x00010002u
#define HID_USAGE_GD_JOYSTICK 0x00010004u
#define HID_USAGE_GD_GAMEPAD 0x00010005u
#define HID_USAGE_GD_KEYBOARD 0x00010006u
#define HID_USAGE_GD_X 0x00010030u
#define HID_USAGE_GD_Y 0x00010031u
#define HID_USAGE_GD_WHEEL 0x00010038u
#define HID_USAGE_GD_RESOLUTION_MULTIPLIER 0x00010048u
#define HID_USAGE_KEYBOARD_ERROR_ROLLOVER 0x00070001u
#define HID_USAGE_CONSUMER_AC_PAN 0x000c0238u
#define HID_PAGE_KEYBOARD 0x0007u
#define HID_PAGE_BUTTON 0x0009u

enum hid_collection_type {
	HID_COLLECTION_PHYSICAL = 0,
	HID_COLLECTION_APPLICATION = 1,
	HID_COLLECTION_LOGICAL = 2,
};

enum hid_boot { HID_BOOT_MOUSE, HID_BOOT_KEYBOARD };

/* consecutive usages: first, first + 1, ... (a Usage item is a run of one) */
struct hid_desc_run {
	uint32_t first; /* page << 16 | id */
	uint32_t count;
};

struct hid_desc_collection {
	uint32_t usage;  /* the first usage declared before it, 0 if none */
	uint16_t parent; /* HID_DESC_NONE at the top level */
	uint8_t type;    /* the item's data byte; enum hid_collection_type for the common ones */
	uint8_t depth;   /* 0 at the top level */
};

struct hid_desc_field {
	uint16_t report;         /* index into reports */
	uint16_t bit_offset;     /* from the first data byte (after the id byte) */
	uint16_t size;           /* bits per value: 1-32 for data, up to 256 for constants */
	uint16_t count;          /* values */
	uint32_t flags;          /* HID_FIELD_*: the main item's data */
	int32_t logical_min, logical_max;
	int32_t physical_min, physical_max;
	uint32_t application;    /* usage of the enclosing application collection, 0 if none */
	uint32_t physical;       /* ... of the nearest physical collection */
	uint32_t logical;        /* ... of the nearest logical collection */
	uint16_t collection;     /* the innermost open collection, HID_DESC_NONE if none */
	uint16_t run_first;      /* usage runs: runs[run_first .. run_first + run_count) */
	uint16_t run_count;
	uint16_t value_first;    /* where its values live in a decoder's state */
	uint32_t usages;         /* the usages declared (runs summed) */
	int16_t resolution_multiplier; /* 1 unless a Resolution Multiplier applies */
};

struct hid_desc_report {
	uint8_t id;            /* 0 when the descriptor has no report ids */
	uint16_t bits;         /* data length in bits */
	uint16_t bytes;        /* the whole report as it arrives: id byte included when numbered */
	uint16_t field_first;  /* fields[field_first .. field_first + field_count) */
	uint16_t field_count;
};

/* a Resolution Multiplier feature: what a backend writes to enable hi-res */
struct hid_desc_multiplier {
	uint8_t report_id;
	uint16_t bit_offset;   /* in the feature report's data */
	uint16_t size;
	int32_t logical_max;   /* the value the kernel sets (and we assume) */
	int32_t effective;     /* the multiplier that value gives, 1 when unusable */
	uint16_t collection;   /* the innermost collection it sits in */
	uint32_t report_bits;  /* the whole feature report's data, to write it */
};

struct hid_desc {
	int numbered;          /* input reports start with their id byte */
	unsigned nreports, nfields, nruns, ncollections, nvalues, nmultipliers;
	uint8_t report_index[256]; /* report id -> index into reports, 0xff none */
	struct hid_desc_report reports[HID_DESC_MAX_REPORTS];
	struct hid_desc_field fields[HID_DESC_MAX_FIELDS];
	struct hid_desc_run runs[HID_DESC_MAX_RUNS];
	struct hid_desc_collection collections[HID_DESC_MAX_COLLECTIONS];
	struct hid_desc_multiplier multipliers[HID_DESC_MAX_MULTIPLIERS];
};

/*
 * Parses n descriptor bytes into dest. Returns 0, or -1 with a message in
 * err (at most errlen bytes, always terminated) naming the byte offset of
 * the item at fault, e.g. "byte 17: End Collection without Collection";
 * dest is then an empty descriptor (no reports).
 */
int hid_desc_parse(const uint8_t *bytes, size_t n, struct hid_desc *dest, char *err,
		   size_t errlen);

/*
 * Builds the boot protocol's fixed descriptor (HID 1.11 Appendix B): the
 * 3-byte mouse report (buttons 1-3, X, Y) or the 8-byte keyboard report
 * (modifiers, reserved, six key slots). Returns 0, or -1 for an unknown kind.
 */
int hid_desc_boot(enum hid_boot kind, struct hid_desc *dest);

/*
 * The Appendix B descriptor bytes for kind, and their number in *n;
 * NULL for an unknown kind.
 */
const uint8_t *hid_desc_boot_bytes(enum hid_boot kind, size_t *n);

/*
 * Sets every input field's resolution_multiplier again from the
 * multipliers' `effective` values, as hid_desc_parse does at its end: a
 * backend whose device refused a multiplier sets that one's effective to
 * 1 and calls this, so its wheels count whole detents again.
 */
void hid_desc_apply_multipliers(struct hid_desc *d);

/*
 * The i-th usage of field f (page << 16 | id), as the kernel numbers them:
 * past the last declared usage, the last one repeats. 0 when the field has
 * no usages.
 */
uint32_t hid_desc_usage(const struct hid_desc *d, const struct hid_desc_field *f, uint32_t i);

/*
 * The report with this id, or NULL. For a descriptor without ids, id 0.
 */
const struct hid_desc_report *hid_desc_report_by_id(const struct hid_desc *d, unsigned id);

/* a short name of a usage we know ("X", "Wheel", "Button 3"), or NULL */
const char *hid_desc_usage_name(uint32_t usage);

/*
 * Writes a human-readable account of d to out: each input report (id,
 * length in bytes), and each field (bit offset, size, count,
 * variable/array/constant, relative, logical range, usages as
 * page:usage in hex with the common names).
 */
void hid_desc_describe(const struct hid_desc *d, FILE *out);

#endif
