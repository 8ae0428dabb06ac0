/* mouse_dpi.c - MOUSE_DPI read and parsed (see mouse_dpi.h) */
#include "devices/mouse_dpi.h"

#include <ctype.h>
#include <libudev.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "devices/input_backend.h"

/* one "DPI[@HZ]" entry at *p: its DPI, or 0; *p moves past it */
static double
mouse_dpi_entry(const char **p)
{
	char *end;
	long dpi = strtol(*p, &end, 10);
	if (end == *p || dpi < 1 || dpi > 100000)
		return 0;
	if (*end == '@') {
		const char *hz = end + 1;
		strtol(hz, &end, 10);
		if (end == hz)
			return 0;
	}
	*p = end;
	return (double)dpi;
}

double
mouse_dpi_parse(const char *value)
{
	double only = 0, marked = 0;
	int n = 0;
	const char *p = value;
	for (;;) {
		while (isspace((unsigned char)*p))
			p++;
		if (!*p)
			break;
		int star = *p == '*';
		p += star;
		double dpi = mouse_dpi_entry(&p);
		if (!dpi || (*p && !isspace((unsigned char)*p)))
			return 0;
		if (star) {
			if (marked)
				return 0; /* two defaults */
			marked = dpi;
		}
		only = dpi;
		n++;
	}
	if (marked)
		return marked;
	return n == 1 ? only : 0;
}

/* the udev device of an event node: by its name under /sys/class/input, else by number */
static struct udev_device *
mouse_dpi_device(struct udev *u, const char *path)
{
	/* by name first; a link (/dev/input/by-id/...) by its device number. Not realpath():
	 * cheap enough, but umockdev's wrapper of it corrupts the heap, and the tests run
	 * this under umockdev */
	const char *base = strrchr(path, '/');
	base = base ? base + 1 : path;
	struct udev_device *d = NULL;
	if (!strncmp(base, "event", 5))
		d = udev_device_new_from_subsystem_sysname(u, "input", base);
	struct stat st;
	if (!d && stat(path, &st) == 0 && S_ISCHR(st.st_mode))
		d = udev_device_new_from_devnum(u, 'c', st.st_rdev);
	return d;
}

double
mouse_dpi_of_node(const char *path)
{
	struct udev *u = udev_new();
	if (!u)
		return INPUT_DEV_DPI_DEFAULT;
	double dpi = 0;
	struct udev_device *d = mouse_dpi_device(u, path);
	if (d) {
		const char *v = udev_device_get_property_value(d, "MOUSE_DPI");
		if (v)
			dpi = mouse_dpi_parse(v);
		udev_device_unref(d);
	}
	udev_unref(u);
	return dpi > 0 ? dpi : INPUT_DEV_DPI_DEFAULT;
}
