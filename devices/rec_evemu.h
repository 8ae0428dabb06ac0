/*
 * rec_evemu.h - evemu recordings of evdev devices (evemu-record's files,
 * format 1.3 and the older ones evemu still reads), read and written.
 *
 * A file is lines: "# EVEMU 1.3" first (no such line: format 1.0), then
 * the device's description, then its events:
 *   N: <name>                        the rest of the line
 *   I: <bus> <vendor> <product> <version>      hex
 *   P: <8 hex bytes>                 the property bitmask, 8 bytes a line
 *   B: <type> <8 hex bytes>          a type's code bitmask, 8 bytes a line,
 *                                    each type's lines in a run from byte 0
 *   A: <code> <min> <max> <fuzz> <flat> <res>  hex code, decimal values
 *                                    (no res before format 1.2)
 *   L: <code> <state>, S: <code> <state>       LED and switch states (1.3)
 *   E: <sec>.<usec, 6 digits> <type> <code> <value>  hex type and code,
 *                                    decimal value: one struct input_event
 * '#' starts a comment on a line of its own or after an E: line's data.
 * The reader skips comments, blank and unknown lines, takes the whole
 * file or nothing, and names the file and line of what it refuses. The
 * description may be missing (a file of events only) or the events (a
 * description only), not both. Times are kept as written and rebased so
 * that the first event is at 0.
 */
#ifndef POSTURE_DEVICES_REC_EVEMU_H
#define POSTURE_DEVICES_REC_EVEMU_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <linux/input.h>

#include "devices/evdev_input.h"

#define REC_EVEMU_NAME_MAX 256
#define REC_EVEMU_PROP_BYTES 8                /* one P: line */
#define REC_EVEMU_MASK_BYTES (KEY_MAX / 8 + 1) /* the largest bitmask, EV_KEY's */

struct rec_evemu_event {
	uint64_t t_us; /* rebased: the first event at 0 */
	uint64_t sec;  /* the time as the file gives it */
	uint32_t usec;
	uint16_t type, code;
	int32_t value;
};

struct rec_evemu_abs {
	int32_t min, max, fuzz, flat, res;
};

struct rec_evemu {
	unsigned major, minor; /* the file's format version */
	int described;         /* N: and I: lines were given */
	char name[REC_EVEMU_NAME_MAX];
	uint16_t bustype, vendor, product, version;
	uint8_t props[REC_EVEMU_PROP_BYTES];
	uint8_t bits[EV_CNT][REC_EVEMU_MASK_BYTES];
	struct rec_evemu_abs abs[ABS_CNT];
	uint8_t abs_given[ABS_CNT]; /* an A: line, or the EV_ABS bit (all zero then) */
	int32_t led[LED_CNT], sw[SW_CNT];

	struct rec_evemu_event *ev; /* nev events, in file order */
	size_t nev;
};

/*
 * Parses n bytes of an evemu file; name is what errors call it. On success
 * fills dest (free it with rec_evemu_free) and returns 0. On failure
 * returns -1, writes "name:line: message" to err and leaves dest empty
 * (safe to free).
 */
int
rec_evemu_parse(const char *text, size_t n, const char *name, struct rec_evemu *dest, char *err,
		size_t errlen);

/* rec_evemu_parse on the file at path: 0, or -1 with the reason in err */
int
rec_evemu_read(const char *path, struct rec_evemu *dest, char *err, size_t errlen);

/*
 * Writes r as evemu-record does: the "# EVEMU 1.3" line, the description
 * as comments and as N/I/P/B/A/L/S lines, then one E: line per event at
 * its original time, with evemu's trailing comment. Returns 0, or -1 when
 * the stream reports an error.
 */
int
rec_evemu_write(FILE *out, const struct rec_evemu *r);

/*
 * Writes one E: line with its comment. *last_ms is the time in ms of the
 * previous EV_SYN written (0 before the first), which the comment of an
 * EV_SYN line shows the difference from; it is updated. Returns 0, or -1
 * on a stream error.
 */
int
rec_evemu_write_event(FILE *out, const struct rec_evemu_event *ev, uint64_t *last_ms);

/* frees the events and empties r */
void
rec_evemu_free(struct rec_evemu *r);

/*
 * Writes the events as struct input_event records (the bytes a device
 * sends) at their rebased times into dest, as many whole records as fit
 * in max bytes. Returns the bytes the whole recording takes, which may be
 * more than max (then call again with a larger dest).
 */
size_t
rec_evemu_to_records(const struct rec_evemu *r, uint8_t *dest, size_t max);

/*
 * Gives dest the ranges of ABS_X and ABS_Y from the description's A: lines
 * (evdev_input_set_abs). Returns the number of axes given a range.
 */
int
rec_evemu_apply_abs(const struct rec_evemu *r, struct evdev_input *dest);

/* rec_evemu_data.c: the kernel's name of an event type ("EV_KEY"), or NULL */
const char *
rec_evemu_type_name(unsigned type);

/* the kernel's name of an event code ("BTN_LEFT"), or NULL */
const char *
rec_evemu_code_name(unsigned type, unsigned code);

/* the kernel's name of an input property ("INPUT_PROP_POINTER"), or NULL */
const char *
rec_evemu_prop_name(unsigned prop);

#endif
