/*
 * rec_candump.h - CAN recordings as `candump -l` logs (can-utils), read and
 * written. One frame a line:
 *
 *   (SECONDS.FRACTION) IFACE FRAME [R|T] [anything else]
 *
 *   FRACTION  6 digits (microseconds), or 9 (nanoseconds, as `candump -N` writes)
 *   IFACE     the interface name, at most 31 characters
 *   FRAME     can-utils' compact frame syntax (lib.h):
 *             123#11223344       standard id: 3 hex digits; 0..8 data bytes in hex,
 *                                optionally separated by '.' (123#11.22.33)
 *             12345678#1122      extended id: 8 hex digits
 *             20000080#0000..    8 digits with CAN_ERR_FLAG (0x20000000): an error frame
 *             123#R  123#R5      a remote (RTR) frame, with its requested length
 *             123#1122334455667788_9   an 8-byte frame with its raw DLC 9..F (len8_dlc)
 *             123##1...          CAN FD: refused (a panel sends classic frames)
 *   R|T       the direction `candump -x` and python-can append: kept and written back
 *
 * Lines that do not begin with '(' (blank lines, comments) are skipped. The
 * times are the log's own (wall clock, as candump writes them); each frame
 * keeps its absolute time and a time rebased to the first frame. Reading is
 * all or nothing: a malformed frame line, or a time earlier than the line
 * before, refuses the file with "path:line: message".
 */
#ifndef POSTURE_DEVICES_REC_CANDUMP_H
#define POSTURE_DEVICES_REC_CANDUMP_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#define REC_CANDUMP_IFACE_MAX 32 /* with the terminating NUL */

struct rec_candump_frame {
	uint64_t t_abs_us;  /* the log's time in microseconds */
	uint64_t t_us;      /* rebased: 0 at the first frame */
	uint16_t t_ns;      /* nanoseconds below t_abs_us (9-digit logs) */
	char iface[REC_CANDUMP_IFACE_MAX];
	uint32_t can_id;    /* with CAN_EFF_FLAG, CAN_RTR_FLAG or CAN_ERR_FLAG */
	uint8_t len;        /* data bytes; an RTR frame's requested length */
	uint8_t len8_dlc;   /* 9..15 for an 8-byte frame with a raw DLC, else 0 */
	uint8_t data[8];
	char dir;           /* 'R', 'T', or 0 when the log gave none */
};

struct rec_candump {
	struct rec_candump_frame *frames;
	size_t n;
	int nanoseconds;    /* the log had 9-digit fractions: they are written back */
	size_t skipped;     /* lines skipped (blank, comments, not frames) */
};

/*
 * Parses n bytes of log text; name is the file name used in messages.
 * Returns 0 with *dest filled (free it with rec_candump_free), or -1 with
 * "name:line: message" in err and *dest empty.
 */
int rec_candump_parse(const char *text, size_t n, const char *name, struct rec_candump *dest,
		      char *err, size_t errlen);

/* reads and parses the log at path: as rec_candump_parse, and -1 when it cannot be read */
int rec_candump_read(const char *path, struct rec_candump *dest, char *err, size_t errlen);

/*
 * Writes r as candump -l writes it: "(%010u.%06u) IFACE FRAME", the
 * interface names right-aligned to the longest, ids and data in upper-case
 * hex, the direction when the frame has one. Returns 0, or -1 on a write
 * error.
 */
int rec_candump_write(FILE *out, const struct rec_candump *r);

/*
 * One frame's line as rec_candump_write writes it (the interface name
 * right-aligned to width, fractions of 9 digits when nanoseconds), into
 * dest (cap bytes, NUL-terminated; REC_CANDUMP_LINE_MAX is always enough).
 * Returns the line's length, newline included.
 */
#define REC_CANDUMP_LINE_MAX 96
size_t rec_candump_format(char *dest, size_t cap, const struct rec_candump_frame *f, int width,
			  int nanoseconds);

/* a frame as a CAN_RAW socket reads it (struct can_frame), at t_us on iface, as a log's frame */
void rec_candump_from_can_frame(const uint8_t frame[16], uint64_t t_us, const char *iface,
				struct rec_candump_frame *dest);

/* frees what rec_candump_parse or _read allocated and empties r */
void rec_candump_free(struct rec_candump *r);

/* the frame as the kernel's 16-byte struct can_frame, as a CAN_RAW socket reads it */
void rec_candump_to_can_frame(const struct rec_candump_frame *f, uint8_t dest[16]);

#endif
