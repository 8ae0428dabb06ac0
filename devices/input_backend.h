/*
 * input_backend.h - what every device backend (evdev, hidraw, usb, can)
 * offers the device set (devices/input_devs.h): one table of functions, so
 * the set and the poll loop know no backend by name.
 *
 * A backend's device is its own struct, made by its open_spec and handed to
 * the set with input_devs_put; from then on the set calls fd, read and
 * close on it. A backend whose devices share descriptors (libusb: one
 * context, several fds, transfers for every device) gives them through
 * shared_fds and does their work in shared_work; its devices then have no
 * fd of their own (fd returns -1) and the set calls their read after each
 * shared_work, so a device the work found gone is reaped the same way.
 */
#ifndef POSTURE_DEVICES_INPUT_BACKEND_H
#define POSTURE_DEVICES_INPUT_BACKEND_H

#include <poll.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "devices/event.h"
#include "devices/queue.h"

#define INPUT_DEV_PATH_MAX 256
#define INPUT_DEV_NAME_MAX 128
#define INPUT_DEV_DPI_DEFAULT 1000.0 /* a mouse that does not say: udev's default too */

struct input_devs;

/* what the set lists of every open device (`list devices`, posture-input list) */
struct input_dev_info {
	char path[INPUT_DEV_PATH_MAX];  /* the node, the USB bus-port, the CAN interface */
	char name[INPUT_DEV_NAME_MAX];
	uint16_t vendor, product;
	int iface;                      /* the USB interface, -1 where there is none */
	enum input_class cls;
	uint8_t grabbed;                /* the kiosk grab is held (evdev) */
	double dpi;                     /* counts per inch of a mouse (udev MOUSE_DPI, or 1000) */
};

/* what a device's reading has met, for `list devices` */
struct input_dev_stats {
	uint64_t reads;   /* reads that took something */
	uint64_t capped;  /* ... that stopped at the backend's cap with more waiting (a flood) */
	uint64_t resyncs; /* state read back after the kernel dropped events */
	uint64_t errors;  /* reports or frames refused, transfer or bus errors */
};

struct input_backend {
	const char *name;  /* "evdev": also the spec's prefix */
	const char *usage; /* the spec's form, for error messages: "evdev:PATH" */

	/*
	 * Opens what arg (the spec after "NAME:", or NULL for `auto`) names:
	 * each device at a place from input_devs_free_place, handed over with
	 * input_devs_put; what it cannot open it reports with input_devs_skip.
	 * A device the set has open already (input_devs_find) is left alone, so
	 * a spec can be opened again after a hot-plug. Returns the devices
	 * opened, or -1 with err for an arg it cannot read (a malformed spec).
	 */
	int (*open_spec)(struct input_devs *s, const char *arg, char *err, size_t errlen);

	/* the device's fd to poll for reading, or -1 (the shared fds serve it) */
	int (*fd)(const void *dev);

	/*
	 * Takes what the device has into q. Returns >= 0, or -1 when the device
	 * is gone: what it held was released as events and INPUT_REMOVED queued.
	 */
	int (*read)(void *dev, uint64_t now_us, struct input_queue *q);

	/* releases what the device held into q (NULL: nowhere), closes and frees it */
	void (*close)(void *dev, uint64_t now_us, struct input_queue *q);

	/* the device's counters into dest; NULL: it keeps none */
	void (*stats)(const void *dev, struct input_dev_stats *dest);

	/* takes (on) or gives up the kiosk grab: 0, or -1; NULL: not grabbable */
	int (*set_grab)(void *dev, int on);

	/* the backend's shared fds (up to max, into fds): their count; NULL: none */
	int (*shared_fds)(struct pollfd *fds, int max);

	/* the work a shared fd being ready (or a frame passing) asks for; NULL: none */
	void (*shared_work)(uint64_t now_us, struct input_queue *q);

	/*
	 * 1 (said once) when a device has arrived since the last call that a
	 * spec may name, so the set opens its specs again; NULL: never. A
	 * backend learns of arrivals inside its shared work (libusb's hot-plug
	 * callback runs inside the event handling, where nothing may be
	 * opened); the set asks after the work and its reads are done.
	 */
	int (*arrived)(void);
	/*
	 * The format a recording keeps the device's bytes in (rec_format:
	 * "evemu", "hid-recorder" or "candump", the ecosystems' own), and the
	 * device described in it (describe: the file's head; for candump, whose
	 * logs have none, the panel's map). 0, or -1 on a stream error. NULL:
	 * the device is not recorded.
	 */
	const char *rec_format;
	int (*describe)(const void *dev, FILE *out);
};

#endif
