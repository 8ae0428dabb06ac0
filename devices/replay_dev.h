/*
 * replay_dev.h - a device of a recording (daemon/tape.h) played back: its
 * file in its ecosystem's format (an evemu recording, a hid-recorder file,
 * a candump log with the panel's map), and a decoder of the device's kind
 * made as the live backend makes it, which the replay calls as the live
 * decoder was called (queue.h, enum input_tap_kind): the same bytes through
 * the same code give the same events.
 */
#ifndef POSTURE_DEVICES_REPLAY_DEV_H
#define POSTURE_DEVICES_REPLAY_DEV_H

#include <stddef.h>
#include <stdint.h>

#include "devices/can_input.h"
#include "devices/can_map.h"
#include "devices/evdev_input.h"
#include "devices/hid_desc.h"
#include "devices/hid_input.h"
#include "devices/queue.h"
#include "devices/rec_candump.h"
#include "devices/rec_evemu.h"
#include "devices/rec_hid.h"

enum replay_dev_format { REPLAY_DEV_EVEMU, REPLAY_DEV_HID, REPLAY_DEV_CANDUMP };

struct replay_dev {
	enum replay_dev_format format;
	char path[4096];      /* the file, for messages */
	size_t next;          /* the file's next record */
	struct rec_evemu evemu;
	struct evdev_input ev;
	struct rec_hid hid;
	struct hid_desc desc;
	struct hid_input hin;
	struct rec_candump can;
	struct can_map map;
	struct can_input cin;
};

/* "evemu", "hid-recorder" or "candump" as enum replay_dev_format; -1: none of them */
int replay_dev_format_of(const char *name);

/*
 * Reads the device's file at path (for candump, its map at map_path) and
 * makes its decoder as device index device. 0, or -1 with "file:line: why"
 * in err (nothing to free then). r is large: place it, do not stack it.
 */
int replay_dev_open(struct replay_dev *r, enum replay_dev_format format, const char *path,
		    const char *map_path, uint16_t device, char *err, size_t errlen);

/*
 * The decoder called as the recording says it was: kind (and arg) as the
 * tap gave them; for INPUT_TAP_BYTES, the file's next count records (evemu
 * records, a report, a frame) with the time t_us; for INPUT_TAP_RESYNC,
 * bytes (n of them: the key bitmask). 0, or -1 when the file has no such
 * records (err says where).
 */
int replay_dev_call(struct replay_dev *r, enum input_tap_kind kind, int arg, size_t count,
		    const uint8_t *bytes, size_t n, uint64_t t_us, struct input_queue *q,
		    char *err, size_t errlen);

void replay_dev_free(struct replay_dev *r);

#endif
