/* input_devs.c - the open input devices and the specs that named them (see input_devs.h) */
#include "devices/input_devs.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void
input_devs_init(struct input_devs *s, int grab)
{
	memset(s, 0, sizeof *s);
	for (int i = 0; i < INPUT_DEVS_MAX; i++)
		s->dev[i].fd = -1;
	s->grab = grab;
	s->input_dir = "/dev/input";
}

static void
skipped(struct input_devs *s, const char *what, const char *why)
{
	if (s->nskip == INPUT_DEVS_SKIP_MAX)
		return;
	struct input_devs_skip *k = &s->skip[s->nskip++];
	snprintf(k->what, sizeof k->what, "%.*s", (int)sizeof k->what - 1, what);
	snprintf(k->why, sizeof k->why, "%.*s", (int)sizeof k->why - 1, why);
}

static int
is_open(const struct input_devs *s, const char *path)
{
	for (int i = 0; i < INPUT_DEVS_MAX; i++)
		if (s->dev[i].fd >= 0 && !strcmp(s->dev[i].path, path))
			return 1;
	return 0;
}

/* 1 when opened, 0 when skipped (with its reason) */
static int
open_evdev(struct input_devs *s, const char *path, int only_pointing_and_keys)
{
	char err[256];
	if (is_open(s, path))
		return 0;
	int i = 0;
	while (i < INPUT_DEVS_MAX && s->dev[i].fd >= 0)
		i++;
	if (i == INPUT_DEVS_MAX) {
		skipped(s, path, "too many devices open");
		return 0;
	}
	if (evdev_dev_open(&s->dev[i], path, (uint16_t)i, s->grab, err, sizeof err) < 0) {
		skipped(s, path, err);
		return 0;
	}
	if (only_pointing_and_keys && s->dev[i].info.cls == INPUT_CLASS_OTHER) {
		evdev_dev_close(&s->dev[i], 0, NULL);
		skipped(s, path, "neither a mouse nor a keyboard");
		return 0;
	}
	return 1;
}

/* every mouse and keyboard among the event nodes, in name order */
static int
open_auto(struct input_devs *s)
{
	DIR *d = opendir(s->input_dir);
	if (!d) {
		skipped(s, "auto", "no input devices (the input directory cannot be read)");
		return 0;
	}
	char names[64][32];
	int n = 0;
	struct dirent *e;
	while ((e = readdir(d)) && n < 64)
		if (!strncmp(e->d_name, "event", 5) && strlen(e->d_name) < sizeof names[0])
			snprintf(names[n++], sizeof names[0], "%.31s", e->d_name);
	closedir(d);
	qsort(names, (size_t)n, sizeof names[0], (int (*)(const void *, const void *))strcmp);
	int opened = 0;
	for (int k = 0; k < n; k++) {
		char path[512];
		snprintf(path, sizeof path, "%.400s/%.31s", s->input_dir, names[k]);
		opened += open_evdev(s, path, 1);
	}
	if (!n)
		skipped(s, "auto", "no input devices");
	return opened;
}

int
input_devs_open(struct input_devs *s, const char *spec, char *err, size_t errlen)
{
	if (!strcmp(spec, "none"))
		return 0;
	if (!strcmp(spec, "auto"))
		return open_auto(s);
	if (!strncmp(spec, "evdev:", 6) && spec[6])
		return open_evdev(s, spec + 6, 0);
	static const char *const later[] = { "hidraw:", "usb:", "can:" };
	for (size_t k = 0; k < sizeof later / sizeof *later; k++)
		if (!strncmp(spec, later[k], strlen(later[k]))) {
			skipped(s, spec, "this backend is not built yet");
			return 0;
		}
	snprintf(err, errlen, "input '%.100s': auto, none, evdev:PATH, hidraw:VID:PID[:IFACE], "
		 "usb:VID:PID[:IFACE] or can:IFACE:MAPFILE", spec);
	return -1;
}

int
input_devs_fd(const struct input_devs *s, int i)
{
	return i >= 0 && i < INPUT_DEVS_MAX ? s->dev[i].fd : -1;
}

int
input_devs_read(struct input_devs *s, int i, uint64_t now_us, struct input_queue *q)
{
	struct evdev_dev *d = &s->dev[i];
	if (d->fd < 0)
		return -1;
	if (evdev_dev_read(d, now_us, q) >= 0) /* the records it read, maybe none */
		return 0;
	/* gone: evdev_dev_read released what it held and queued the removal */
	evdev_dev_close(d, now_us, q);
	d->fd = -1;
	return -1;
}

void
input_devs_close_all(struct input_devs *s, uint64_t now_us, struct input_queue *q)
{
	for (int i = 0; i < INPUT_DEVS_MAX; i++)
		if (s->dev[i].fd >= 0) {
			evdev_dev_close(&s->dev[i], now_us, q);
			s->dev[i].fd = -1;
		}
}
