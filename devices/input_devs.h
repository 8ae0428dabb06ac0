/*
 * input_devs.h - the input devices the daemon has open, from the --input
 * specs: `auto` (every mouse and keyboard among /dev/input/event*),
 * `evdev:PATH`, `none`. The backends for `hidraw:`, `usb:` and `can:` specs are
 * not built yet: such a spec is listed as skipped with that reason. What
 * could not be opened is kept with its reason, for `list devices`.
 * Fixed size; nothing allocates after input_devs_init.
 */
#ifndef POSTURE_DEVICES_INPUT_DEVS_H
#define POSTURE_DEVICES_INPUT_DEVS_H

#include <stdint.h>

#include "devices/evdev_dev.h"
#include "devices/queue.h"

#define INPUT_DEVS_MAX 16   /* open at once */
#define INPUT_DEVS_SKIP_MAX 32
#define INPUT_DEVS_SPEC_MAX 256
#define INPUT_DEVS_WHY_MAX 200

struct input_devs_skip {
	char what[INPUT_DEVS_SPEC_MAX]; /* the spec or the path */
	char why[INPUT_DEVS_WHY_MAX];
};

struct input_devs {
	struct evdev_dev dev[INPUT_DEVS_MAX]; /* fd -1: a free place */
	int grab;                             /* EVIOCGRAB the devices opened */
	int nskip;
	struct input_devs_skip skip[INPUT_DEVS_SKIP_MAX];
	const char *input_dir; /* /dev/input; tests may point it elsewhere */
};

void input_devs_init(struct input_devs *s, int grab);

/*
 * Opens what spec names, each device under its place's index as device id.
 * Returns how many devices it opened (0 is not an error: what was not
 * opened is recorded with its reason), or -1 for a spec it cannot read
 * (err says why).
 */
int input_devs_open(struct input_devs *s, const char *spec, char *err, size_t errlen);

/* the fd of place i, or -1 when the place is free */
int input_devs_fd(const struct input_devs *s, int i);

/*
 * Reads what place i has for us into q. A device that went away releases
 * what it held, is reported removed (INPUT_REMOVED) and is closed; its
 * place is free again. Returns 0, or -1 when the device went away.
 */
int input_devs_read(struct input_devs *s, int i, uint64_t now_us, struct input_queue *q);

/* closes every device, releasing what each held into q (NULL: nothing queued) */
void input_devs_close_all(struct input_devs *s, uint64_t now_us, struct input_queue *q);

#endif
