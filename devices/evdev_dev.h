/*
 * evdev_dev.h - the evdev backend: a /dev/input/eventN device opened, its
 * fd for the poll loop, its bytes into the decoder (devices/evdev_input.h),
 * closed with the keys and buttons it held released as events.
 *
 * libevdev gives the name, the id, the capabilities (which say whether the
 * device is a mouse or a keyboard) and the ABS_X/ABS_Y ranges; the reads
 * are plain read()s of whole struct input_event records, so the decoder
 * sees exactly the bytes the kernel sent. Timestamps are CLOCK_MONOTONIC
 * (EVIOCSCLOCKID), the clock the daemon runs on.
 *
 * The kiosk grab (EVIOCGRAB) makes the kernel deliver the device's events
 * to this fd alone: the console, other readers and the VT switch keys no
 * longer see them. The grab belongs to the open file, so it ends when the
 * fd is closed (the daemon stopping, or evdev_dev_set_grab(d, 0)) and is
 * taken again on every open. The way out for an operator is to stop the
 * daemon (or send it the command that ungrabs); a grab never outlives it.
 */
#ifndef POSTURE_DEVICES_EVDEV_DEV_H
#define POSTURE_DEVICES_EVDEV_DEV_H

#include <stddef.h>
#include <stdint.h>

#include <linux/input.h>

#include "devices/event.h"
#include "devices/evdev_input.h"
#include "devices/input_backend.h"
#include "devices/queue.h"
#include "devices/rec_evemu.h"

/*
 * Records one evdev_dev_read takes at most: a device flooding events
 * cannot keep the loop reading it; what is left waits for the next call
 * (the poll loop comes back at once, the fd still being readable).
 */
#define EVDEV_DEV_READ_MAX 64

#define EVDEV_DEV_NAME_MAX 128
#define EVDEV_DEV_PATH_MAX 256

struct libevdev;

/* what a device is, for listing and for choosing it */
struct evdev_dev_info {
	char name[EVDEV_DEV_NAME_MAX];
	uint16_t bustype, vendor, product, version;
	/*
	 * INPUT_CLASS_MOUSE: REL_X, REL_Y and BTN_LEFT; INPUT_CLASS_KEYBOARD:
	 * the letter keys KEY_A..KEY_Z; INPUT_CLASS_OTHER: neither. A device
	 * that is both (a keyboard with a pointing stick) is called a mouse
	 * and has both flags.
	 */
	enum input_class cls;
	uint8_t mouse, keyboard;
};

struct evdev_dev {
	int fd;                         /* -1 when closed */
	char path[EVDEV_DEV_PATH_MAX];
	struct evdev_dev_info info;
	struct libevdev *evdev;         /* the description, kept while open */
	struct evdev_input in;          /* the decoder */
	uint8_t grab;                   /* EVIOCGRAB wanted (taken again on each open) */
	uint8_t grabbed;                /* ... and held */
	uint8_t monotonic;              /* EVIOCSCLOCKID took CLOCK_MONOTONIC */

	/*
	 * The bytes of the last read: its whole records are at buf[0..nlast),
	 * for a recorder that wants the kernel's own records; a stream that
	 * split a record (never the kernel, but a socket standing in for it)
	 * leaves the start of the next one at buf[nlast..nlast + ntail).
	 */
	uint8_t buf[(EVDEV_DEV_READ_MAX + 1) * sizeof(struct input_event)];
	size_t nlast, ntail;

	/* counters */
	uint64_t reads;    /* evdev_dev_read calls that read something */
	uint64_t capped;   /* ... that stopped at EVDEV_DEV_READ_MAX, leaving records behind */
	uint64_t resyncs;  /* key states read back after SYN_DROPPED */
};

/*
 * Opens the evdev device at path (O_RDONLY | O_NONBLOCK | O_CLOEXEC) as
 * the daemon's device index `device`: reads its description, gives the
 * decoder the ABS_X/ABS_Y ranges, asks for CLOCK_MONOTONIC timestamps and,
 * when grab is set, takes the grab. Returns 0, or -1 with the reason in
 * err (the file cannot be opened, is not an evdev device, or the grab is
 * held by another reader) and d closed. A clock the kernel refuses is not
 * an error: it is logged and the kernel's clock is used.
 */
int
evdev_dev_open(struct evdev_dev *d, const char *path, uint16_t device, int grab, char *err,
	       size_t errlen);

/* the fd to poll for reading, or -1 when closed */
int
evdev_dev_fd(const struct evdev_dev *d);

/*
 * Reads what the device has, at most EVDEV_DEV_READ_MAX records, and
 * feeds it to the decoder, which pushes the events of every frame that
 * ends into q; after a SYN_DROPPED the key state is read back (EVIOCGKEY)
 * and put right once no records are left waiting (the call whose read
 * comes back short of the cap, or finds nothing), all at now_us. Returns
 * the records read (0: nothing
 * waiting), or -1 when the device is gone (ENODEV or EIO, blamed on the
 * device; the end of the stream or another read error, on the kernel):
 * its keys and buttons were released as events, INPUT_REMOVED queued and
 * a line logged; the caller closes it with evdev_dev_close.
 */
int
evdev_dev_read(struct evdev_dev *d, uint64_t now_us, struct input_queue *q);

/*
 * Takes (on) or gives up the grab. Returns 0, or -1 when the kernel
 * refuses (EBUSY: another reader holds it).
 */
int
evdev_dev_set_grab(struct evdev_dev *d, int on);

/*
 * Releases the keys and buttons the device held (as events into q, at
 * now_us) and closes it; q may be NULL when nobody listens. Safe on a
 * closed or never opened (zeroed, fd -1) device.
 */
void
evdev_dev_close(struct evdev_dev *d, uint64_t now_us, struct input_queue *q);

/*
 * The description of the open device as an evemu recording's (name, id,
 * properties, every type's code bits, the absolute axes' ranges, LED and
 * switch states), for writing with rec_evemu_write; dest gets no events.
 */
void
evdev_dev_describe(const struct evdev_dev *d, struct rec_evemu *dest);

/*
 * The test seam: takes fd, an open descriptor standing in for a device (a
 * socketpair, a pipe or a pty whose records a test writes), as
 * evdev_dev_open takes a device, but with no description: class
 * INPUT_CLASS_OTHER, no axis ranges, no grab. The fd is made non-blocking
 * and is d's from then on (closed by evdev_dev_close). Returns 0, or -1
 * with the reason in err (not an open descriptor).
 */
int
evdev_dev_adopt(struct evdev_dev *d, int fd, uint16_t device, const char *who, char *err,
		size_t errlen);

/*
 * Opens path just long enough to read its name, id and class into dest.
 * Returns 0, or -1 with the reason in err.
 */
int
evdev_dev_probe(const char *path, struct evdev_dev_info *dest, char *err, size_t errlen);

/* the backend for the device set: `auto` and evdev:PATH (devices/input_backend.h) */
extern const struct input_backend input_backend_evdev;

#endif
