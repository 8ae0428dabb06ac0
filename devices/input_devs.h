/*
 * input_devs.h - the input devices the daemon has open, from the --input
 * specs: `auto` (every mouse and keyboard among /dev/input/event*), `none`,
 * and `BACKEND:ARG` for each backend in the table the set was made with
 * (devices/input_backends.h: evdev:PATH, hidraw:VID:PID[:IFACE],
 * usb:VID:PID[:IFACE], can:IFACE:MAPFILE). What could not be opened is kept
 * with its reason, for `list devices`. The specs are remembered, so a
 * hot-plug (input_devs_rescan) opens what they name that has arrived since.
 *
 * The set knows no backend by name (devices/input_backend.h). Fixed size:
 * the set allocates nothing; a backend allocates its device at open.
 */
#ifndef POSTURE_DEVICES_INPUT_DEVS_H
#define POSTURE_DEVICES_INPUT_DEVS_H

#include <poll.h>
#include <stddef.h>
#include <stdint.h>

#include "devices/input_backend.h"
#include "devices/queue.h"

#define INPUT_DEVS_MAX 16   /* open at once */
#define INPUT_DEVS_SKIP_MAX 32
#define INPUT_DEVS_SPECS_MAX 16
#define INPUT_DEVS_SPEC_MAX 256
#define INPUT_DEVS_WHY_MAX 200
#define INPUT_DEVS_BACKENDS_MAX 8
#define INPUT_DEVS_SHARED_FDS 16 /* a backend's shared fds polled at most */
#define INPUT_DEVS_POLL_MAX (INPUT_DEVS_MAX + 2 * INPUT_DEVS_SHARED_FDS) /* fds to poll, at most */

struct input_devs_skip {
	char what[INPUT_DEVS_SPEC_MAX]; /* the spec or the path */
	char why[INPUT_DEVS_WHY_MAX];
};

struct input_devs_place {
	const struct input_backend *be; /* NULL: a free place */
	void *dev;
	struct input_dev_info info;
	uint8_t announced;              /* input_devs_next_new has given it out */
};

struct input_devs {
	struct input_devs_place place[INPUT_DEVS_MAX];
	const struct input_backend *const *backends;
	int nbackends;
	int grab;                         /* take the kiosk grab on the devices opened */
	char spec[INPUT_DEVS_SPECS_MAX][INPUT_DEVS_SPEC_MAX];
	int nspec;
	int nskip;
	struct input_devs_skip skip[INPUT_DEVS_SKIP_MAX];
	const char *input_dir;            /* /dev/input; tests point it elsewhere */
	struct input_queue *q;            /* INPUT_ADDED goes here (NULL: nowhere) */
	uint64_t now_us;                  /* the time of the open under way */
};

/* an empty set over backends[0..n) (n <= INPUT_DEVS_BACKENDS_MAX); q takes INPUT_ADDED */
void input_devs_init(struct input_devs *s, const struct input_backend *const *backends, int n,
		     int grab, struct input_queue *q);

/*
 * Opens what spec names and remembers it. Returns how many devices it
 * opened (0 is not an error: what was not opened is recorded with its
 * reason), or -1 for a spec it cannot read (err says why; nothing changed).
 */
int input_devs_open(struct input_devs *s, const char *spec, uint64_t now_us, char *err,
		    size_t errlen);

/*
 * Opens again every remembered spec, after a device arrived: what is open
 * stays, what has come is opened, the skipped list is made anew. Returns
 * the devices opened.
 */
int input_devs_rescan(struct input_devs *s, uint64_t now_us);

/*
 * The fds to poll: each device's, then each backend's shared ones, at most
 * max, with tags[k] for input_devs_ready. Returns the count.
 */
int input_devs_pollfds(const struct input_devs *s, struct pollfd *fds, int *tags, int max);

/*
 * The fd tagged tag is ready: reads the device (a device that went away
 * released what it held, was reported removed and is closed: its place is
 * free again), or does the backend's shared work and reads its devices,
 * then opens the specs again (input_devs_rescan) when the backend says a
 * device arrived. Returns 0, or -1 when a device went away.
 */
int input_devs_ready(struct input_devs *s, int tag, uint64_t now_us, struct input_queue *q);

/* takes (on) or gives up the kiosk grab on every device that has one; 0, or -1 if any refused */
int input_devs_set_grab(struct input_devs *s, int on);

/* closes every device, releasing what each held into q (NULL: nothing queued) */
void input_devs_close_all(struct input_devs *s, uint64_t now_us, struct input_queue *q);

/* the number of open devices */
int input_devs_count(const struct input_devs *s);

/* the next device opened and not yet given out (its place), or -1: for announcing */
int input_devs_next_new(struct input_devs *s);

/* ---- for the backends' open_spec ---- */

/* a free place's index, or -1 when the set is full (recorded as a skip of what) */
int input_devs_free_place(struct input_devs *s, const char *what);

/* the place of the open device of backend be at path, or -1 */
int input_devs_find(const struct input_devs *s, const struct input_backend *be, const char *path);

/* hands dev (opened as device index i) to the set; queues INPUT_ADDED */
void input_devs_put(struct input_devs *s, int i, const struct input_backend *be, void *dev,
		    const struct input_dev_info *info);

/* records that what (a spec, a path) was not opened, and why */
void input_devs_skip(struct input_devs *s, const char *what, const char *why);

#endif
