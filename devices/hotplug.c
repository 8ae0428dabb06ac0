/* hotplug.c - a libudev monitor that says when to rescan (see hotplug.h) */
#include "devices/hotplug.h"

#include <errno.h>
#include <libudev.h>
#include <stdio.h>
#include <string.h>

#define HOTPLUG_READ_MAX 64 /* events one call takes: a storm cannot hold the loop */

/* the subsystems whose arrivals can be a device some spec names */
static const char *const hotplug_subsystems[] = { "input", "hidraw", "usb", "net", "drm" };

int
hotplug_open(struct hotplug *h, const char *source, char *err, size_t errlen)
{
	memset(h, 0, sizeof *h);
	h->fd = -1;
	if (strcmp(source, "udev") && strcmp(source, "kernel")) {
		snprintf(err, errlen, "hotplug source '%.40s': udev or kernel", source);
		return -1;
	}
	if (!(h->udev = udev_new())) {
		snprintf(err, errlen, "libudev: %s", strerror(errno));
		return -1;
	}
	h->mon = udev_monitor_new_from_netlink(h->udev, source);
	if (!h->mon) {
		snprintf(err, errlen, "cannot listen to %s events: %s", source, strerror(errno));
		hotplug_close(h);
		return -1;
	}
	for (size_t k = 0; k < sizeof hotplug_subsystems / sizeof *hotplug_subsystems; k++)
		udev_monitor_filter_add_match_subsystem_devtype(h->mon, hotplug_subsystems[k], NULL);
	int rc = udev_monitor_enable_receiving(h->mon);
	if (rc < 0) {
		snprintf(err, errlen, "cannot listen to %s events: %s", source, strerror(-rc));
		hotplug_close(h);
		return -1;
	}
	h->fd = udev_monitor_get_fd(h->mon);
	return 0;
}

int
hotplug_fd(const struct hotplug *h)
{
	return h->fd;
}

/* an arrival some backend may want: an event or hidraw node, a USB device, an interface */
static int
hotplug_of_interest(struct udev_device *d)
{
	const char *action = udev_device_get_action(d);
	if (!action || (strcmp(action, "add") && strcmp(action, "bind")))
		return 0;
	const char *sub = udev_device_get_subsystem(d);
	const char *sysname = udev_device_get_sysname(d);
	if (!sub || !sysname)
		return 0;
	if (!strcmp(sub, "input"))
		return !strncmp(sysname, "event", 5) && !strcmp(action, "add");
	if (!strcmp(sub, "hidraw"))
		return !strcmp(action, "add");
	if (!strcmp(sub, "usb")) {
		const char *type = udev_device_get_devtype(d);
		return type && !strcmp(type, "usb_device") && !strcmp(action, "add");
	}
	if (!strcmp(sub, "net")) {
		/* ARPHRD_CAN (280): only CAN interfaces */
		const char *type = udev_device_get_sysattr_value(d, "type");
		return type && !strcmp(type, "280") && !strcmp(action, "add");
	}
	return 0;
}

int
hotplug_read(struct hotplug *h)
{
	int arrived = 0;
	for (int k = 0; h->mon && k < HOTPLUG_READ_MAX; k++) {
		struct udev_device *d = udev_monitor_receive_device(h->mon);
		if (!d)
			break; /* nothing more now (the fd is non-blocking) */
		const char *sub = udev_device_get_subsystem(d), *action = udev_device_get_action(d);
		const char *plug = udev_device_get_property_value(d, "HOTPLUG");
		if (sub && !strcmp(sub, "drm") && action && !strcmp(action, "change") && plug &&
		    !strcmp(plug, "1")) {
			h->screens++; /* a screen plugged or unplugged: the display probes again */
		} else if (hotplug_of_interest(d)) {
			arrived++;
			h->arrivals++;
		} else {
			h->other++;
		}
		udev_device_unref(d);
	}
	return arrived;
}

void
hotplug_close(struct hotplug *h)
{
	if (h->mon)
		udev_monitor_unref(h->mon);
	if (h->udev)
		udev_unref(h->udev);
	h->mon = NULL;
	h->udev = NULL;
	h->fd = -1;
}
