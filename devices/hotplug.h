/*
 * hotplug.h - devices arriving while the daemon runs: a libudev monitor
 * whose fd sits in the poll loop. It says only "something of interest
 * arrived" (an input event node, a hidraw node, a USB device, a network
 * interface that may be CAN); the device set then opens its specs again
 * (input_devs_rescan), which opens what is new and leaves the rest. A
 * device leaving needs no monitor: its reads fail (ENODEV) and the set
 * removes it.
 *
 * The source is "udev" (events after udevd ran its rules, so the node's
 * group and mode are final: what a kiosk wants) or "kernel" (the kernel's
 * own uevents, for a system without udevd, such as the test guest; needs
 * root, and a node may still have root's mode when the event comes).
 */
#ifndef POSTURE_DEVICES_HOTPLUG_H
#define POSTURE_DEVICES_HOTPLUG_H

#include <stddef.h>
#include <stdint.h>

struct udev;
struct udev_monitor;

struct hotplug {
	struct udev *udev;
	struct udev_monitor *mon;
	int fd;             /* -1 when closed */
	uint64_t arrivals;  /* add events of interest seen */
	uint64_t other;     /* every other event read */
	uint64_t screens;   /* DRM connector changes (a "change" with HOTPLUG=1) */
};

/* opens a monitor on source "udev" or "kernel": 0, or -1 with err (h closed) */
int hotplug_open(struct hotplug *h, const char *source, char *err, size_t errlen);

/* the fd to poll for reading, or -1 */
int hotplug_fd(const struct hotplug *h);

/*
 * Reads the events waiting (at most a bounded number a call). Returns how
 * many of them were arrivals of interest: more than 0 means "rescan".
 */
int hotplug_read(struct hotplug *h);

void hotplug_close(struct hotplug *h);

#endif
