/*
 * rec_hid.h - hid-recorder files (hid-tools), read and written. The format
 * is line based:
 *
 *   # a comment
 *   D: 1                          the device the lines below are about (several recorded)
 *   R: 52 05 01 09 02 a1 01 ...   report descriptor: its length, then the bytes in hex
 *   N: QEMU USB Mouse             name
 *   P: usb-0000:00:01.2-1/input0  physical path
 *   I: 3 0627 0001                bus, vendor, product (hex)
 *   E: 000000.120004 4 01 00 ff 00  a report: seconds.microseconds, length, bytes
 *
 * The reader skips comments, blank and unknown lines; takes fractions of
 * exactly six digits (the seconds may be zero-padded); checks each R: and
 * E: length against the bytes that follow; rebases times to the first
 * event; and is all or nothing, with "path:line: message" errors. The
 * writer writes what hid-tools' hidraw.py writes (without its decoded
 * comments), so read -> write -> read gives the same recording.
 */
#ifndef POSTURE_DEVICES_REC_HID_H
#define POSTURE_DEVICES_REC_HID_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "devices/hid_desc.h"

#define REC_HID_MAX_DEVICES 8
#define REC_HID_MAX_NAME 256    /* N: and P: text, terminator included */
#define REC_HID_MAX_REPORT 4096 /* bytes of one E: line (hid-tools reads 4096 at most) */

struct rec_hid_device {
	char name[REC_HID_MAX_NAME];
	char phys[REC_HID_MAX_NAME];
	uint16_t bus, vid, pid;
	uint16_t desc_len;
	uint8_t desc[HID_DESC_MAX_BYTES];
};

struct rec_hid_event {
	uint64_t t_us;        /* from the first event */
	uint16_t device;      /* index into devices */
	uint16_t len;
	uint32_t offset;      /* of the bytes in the pool */
	const uint8_t *bytes; /* len bytes: pool + offset */
};

struct rec_hid {
	unsigned ndevices;
	struct rec_hid_device devices[REC_HID_MAX_DEVICES];
	size_t nevents;
	struct rec_hid_event *events; /* allocated */
	uint8_t *pool;                /* allocated: every event's bytes */
};

/*
 * Parses n bytes of hid-recorder text; `name` is used in messages as the
 * file's path. Returns 0, or -1 with "name:line: message" in err (at most
 * errlen bytes) and dest empty (nothing to free). Every device index used
 * needs an R: line.
 */
int rec_hid_parse(const char *text, size_t n, const char *name, struct rec_hid *dest, char *err,
		  size_t errlen);

/* rec_hid_parse on the contents of the file at path: 0, or -1 with err */
int rec_hid_read(const char *path, struct rec_hid *dest, char *err, size_t errlen);

/* writes r to out in hid-recorder's format: 0, or -1 on a write error */
int rec_hid_write(FILE *out, const struct rec_hid *r);

/*
 * The pieces of rec_hid_write, for a recorder writing as reports arrive:
 * one device's header (preceded by "D: index" unless index is -1), and
 * one E: line (a recording of several devices puts "D: n" before the
 * lines of device n when it changes).
 */
void rec_hid_write_device(FILE *out, const struct rec_hid_device *dev, int index);
void rec_hid_write_event(FILE *out, uint64_t t_us, const uint8_t *bytes, unsigned len);

/* frees what r holds and leaves it empty */
void rec_hid_free(struct rec_hid *r);

#endif
