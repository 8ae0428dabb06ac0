/*
 * tape_dev.h - the devices in a recording (tape.h): every call into a
 * decoder (queue.h's tap: the bytes a read gave, a resync, a release, a
 * stale timer) and every device arriving or leaving, written down as it
 * happens; the bytes in the device's own ecosystem format (devN.evemu,
 * devN.hid, devN.log with devN.map), the calls in the frame log:
 *
 *   device DEV FORMAT FILE MAP dpi=D   the device's file begins (MAP: "-" but for candump)
 *   dev DEV bytes T COUNT              its decoder fed the file's next COUNT records at T
 *   dev DEV resync T HEX               ... given the key bitmask read back
 *   dev DEV release T ARG              ... told to release what it holds
 *   dev DEV tick T                     ... its stale timer run
 *   event DEV T KIND CODE VALUE FLAGS X Y    an event no decoder made
 *
 * In a replay the same calls go into decoders made from the files
 * (devices/replay_dev.h), so the same bytes give the same events.
 */
#ifndef POSTURE_DAEMON_TAPE_DEV_H
#define POSTURE_DAEMON_TAPE_DEV_H

#include "daemon/tape.h"
#include "devices/input_devs.h"
#include "devices/queue.h"

/* recording: taps q, whose devices are devs (their descriptions, dpi) */
void tape_dev_attach(struct tape *t, struct input_queue *q, const struct input_devs *devs);
/* ... and no longer */
void tape_dev_detach(struct tape *t, struct input_queue *q);

/* replaying: the record e (DEVICE, DEVCALL or EVENT) done into q; 0, or -1 (t->broken says why) */
int tape_dev_replay(struct tape *t, const struct tape_entry *e, struct input_queue *q);
/* the devices a replay opened, closed */
void tape_dev_free(struct tape *t);

/* a mouse's dots per inch as the recording knew them (1000 when it did not) */
double tape_dev_dpi(const struct tape *t, int device);

#endif
