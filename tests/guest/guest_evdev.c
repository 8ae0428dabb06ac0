/*
 * guest_evdev.c - the evdev backend (devices/evdev_dev.h) and the device set
 * (devices/input_devs.h) against the real kernel, inside the test guest
 * (tests/guest/README.md): uinput devices made from the evemu recordings'
 * descriptions replay their events into the backend (grab, SYN_DROPPED,
 * unplug mid-drag), and the kernel-to-queue latency is measured.
 *
 *   guest_evdev check DIR          every check, one line each: "ok <what>" or
 *                                  "FAIL <what>: <why>"; DIR holds the
 *                                  recordings (tests/input/evdev); the exit
 *                                  status is the number of failures
 *   guest_evdev latency N GAP_US   N motion frames written GAP_US apart by
 *                                  another process, each timed from its write
 *                                  to its event in the set's queue: one
 *                                  "latency ..." line (tools/bench/kernel_latency.py)
 *   guest_evdev calib              two fixed computations' times, "calib
 *                                  alu_ns=... decode_ns=...", run in the guest
 *                                  (after latency) and on the host alike to name
 *                                  the guest's slowdown
 *
 * The reference for the replays is the recording itself: its bytes decoded
 * offline by devices/evdev_input.h must give exactly the events that come out
 * of the backend when the kernel stands in the middle (uinput -> input core
 * -> evdev -> read), all but the timestamps, which the kernel makes. The
 * other checks take their ground truth from the kernel (EVIOCGKEY, a second
 * reader of the same node, the error a grab gets). Needs root, the modules
 * uinput and evdev, and a kernel with no udev (the guest's).
 */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <linux/input.h>
#include <linux/uinput.h>

#include "devices/evdev_dev.h"
#include "devices/evdev_input.h"
#include "devices/input_backends.h"
#include "devices/input_devs.h"
#include "devices/queue.h"
#include "devices/rec_evemu.h"
#include "tests/guest/guest_check.h"

static double
mono_us_f(void)
{
	struct timespec t;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return (double)t.tv_sec * 1e6 + (double)t.tv_nsec / 1e3;
}

static int
bit_is_set(const uint8_t *mask, unsigned c)
{
	return mask[c / 8] >> (c % 8) & 1;
}

/* ---- uinput devices from evemu descriptions ---- */

struct vdev {
	int fd;         /* the uinput fd; -1: none */
	char node[64];  /* /dev/input/eventN */
};

/* the UI_SET_*BIT request of an event type's codes, or 0 for a type that has none to set */
static unsigned long
vdev_bit_request(unsigned type)
{
	switch (type) {
	case EV_KEY:
		return UI_SET_KEYBIT;
	case EV_REL:
		return UI_SET_RELBIT;
	case EV_ABS:
		return UI_SET_ABSBIT;
	case EV_MSC:
		return UI_SET_MSCBIT;
	case EV_LED:
		return UI_SET_LEDBIT;
	case EV_SND:
		return UI_SET_SNDBIT;
	case EV_SW:
		return UI_SET_SWBIT;
	}
	return 0;
}

/* one record and its SYN_REPORT in one write through uinput: 0, or -1 */
static int
vdev_frame(const struct vdev *v, unsigned type, unsigned code, int value)
{
	struct input_event ev[2];
	memset(ev, 0, sizeof ev);
	ev[0].type = (uint16_t)type;
	ev[0].code = (uint16_t)code;
	ev[0].value = value;
	ev[1].type = EV_SYN;
	ev[1].code = SYN_REPORT;
	return uinput_write(v->fd, ev, 2);
}

/* one motion frame (REL_X x, REL_Y y, SYN_REPORT) in one write through uinput: 0, or -1 */
static int
vdev_motion(const struct vdev *v, int x, int y)
{
	struct input_event ev[3];
	memset(ev, 0, sizeof ev);
	ev[0].type = ev[1].type = EV_REL;
	ev[0].code = REL_X;
	ev[0].value = x;
	ev[1].code = REL_Y;
	ev[1].value = y;
	ev[2].type = EV_SYN;
	ev[2].code = SYN_REPORT;
	return uinput_write(v->fd, ev, 3);
}

static void
vdev_destroy(struct vdev *v)
{
	if (v->fd >= 0) {
		ioctl(v->fd, UI_DEV_DESTROY);
		close(v->fd);
	}
	v->fd = -1;
}

/*
 * Makes a uinput device with r's description (name, id, properties, every
 * type's codes, the absolute axes' ranges) and finds its event node.
 * Returns 0, or -1 with the reason in why. A device with EV_REP gets the
 * kernel's software autorepeat turned off (REP_PERIOD 0): the recordings hold
 * the repeats their keyboard sent, and a replay must not add the kernel's.
 */
static int
vdev_make(const struct rec_evemu *r, struct vdev *v, char *why, size_t n)
{
	v->fd = open("/dev/uinput", O_WRONLY | O_NONBLOCK | O_CLOEXEC);
	v->node[0] = '\0';
	if (v->fd < 0) {
		snprintf(why, n, "open /dev/uinput: %s", strerror(errno));
		return -1;
	}
	for (unsigned p = 0; p < REC_EVEMU_PROP_BYTES * 8 && p <= INPUT_PROP_MAX; p++)
		if (bit_is_set(r->props, p) && ioctl(v->fd, UI_SET_PROPBIT, p) < 0) {
			snprintf(why, n, "UI_SET_PROPBIT %u: %s", p, strerror(errno));
			goto fail;
		}
	for (unsigned t = EV_SYN + 1; t < EV_CNT; t++) {
		int any = 0;
		for (unsigned c = 0; c < REC_EVEMU_MASK_BYTES * 8 && !any; c++)
			any = bit_is_set(r->bits[t], c);
		if (!any || t == EV_FF) /* force feedback needs effects: no recording has it */
			continue;
		if (ioctl(v->fd, UI_SET_EVBIT, t) < 0) {
			snprintf(why, n, "UI_SET_EVBIT %u: %s", t, strerror(errno));
			goto fail;
		}
		unsigned long req = vdev_bit_request(t);
		for (unsigned c = 0; req && c < REC_EVEMU_MASK_BYTES * 8; c++) {
			if (!bit_is_set(r->bits[t], c))
				continue;
			if (ioctl(v->fd, req, c) < 0) {
				snprintf(why, n, "UI_SET_*BIT type %u code %u: %s", t, c,
					 strerror(errno));
				goto fail;
			}
			if (t != EV_ABS)
				continue;
			struct uinput_abs_setup a;
			memset(&a, 0, sizeof a);
			a.code = (uint16_t)c;
			a.absinfo.minimum = r->abs[c].min;
			a.absinfo.maximum = r->abs[c].max;
			a.absinfo.fuzz = r->abs[c].fuzz;
			a.absinfo.flat = r->abs[c].flat;
			a.absinfo.resolution = r->abs[c].res;
			if (ioctl(v->fd, UI_ABS_SETUP, &a) < 0) {
				snprintf(why, n, "UI_ABS_SETUP %u: %s", c, strerror(errno));
				goto fail;
			}
		}
	}
	struct uinput_setup us;
	memset(&us, 0, sizeof us);
	us.id.bustype = r->bustype;
	us.id.vendor = r->vendor;
	us.id.product = r->product;
	us.id.version = r->version;
	snprintf(us.name, sizeof us.name, "%.*s", (int)sizeof us.name - 1, r->name);
	if (ioctl(v->fd, UI_DEV_SETUP, &us) < 0 || ioctl(v->fd, UI_DEV_CREATE) < 0) {
		snprintf(why, n, "UI_DEV_SETUP/UI_DEV_CREATE: %s", strerror(errno));
		goto fail;
	}
	char sysname[64] = "", dir[160];
	if (ioctl(v->fd, UI_GET_SYSNAME(sizeof sysname), sysname) < 0) {
		snprintf(why, n, "UI_GET_SYSNAME: %s", strerror(errno));
		goto fail;
	}
	snprintf(dir, sizeof dir, "/sys/devices/virtual/input/%s", sysname);
	for (int tries = 0; tries < 100; tries++) {
		if (event_node(dir, v->node, sizeof v->node) == 0 && access(v->node, R_OK) == 0)
			break;
		v->node[0] = '\0';
		sleep_ms(20);
	}
	if (!v->node[0]) {
		snprintf(why, n, "no event node under %s (is evdev loaded?)", dir);
		goto fail;
	}
	/* with its SYN_REPORT, or the input core holds it and sends it with the next frame */
	if (bit_is_set(r->bits[EV_REP], REP_DELAY) &&
	    (uinput_emit(v->fd, EV_REP, REP_PERIOD, 0) < 0 ||
	     uinput_emit(v->fd, EV_SYN, SYN_REPORT, 0) < 0)) {
		snprintf(why, n, "turning the software autorepeat off: %s", strerror(errno));
		goto fail;
	}
	return 0;
fail:
	vdev_destroy(v);
	return -1;
}

/* ---- the device set, pumped as the daemon's loop pumps it ---- */

static struct input_queue q, qref;
static struct input_devs set;

/*
 * Polls the set's fds for up to ms and reads what is ready, until nothing
 * is ready within quiet_ms. Returns how many times a device went away.
 */
static int
pump(struct input_devs *s, int ms, int quiet_ms)
{
	int gone = 0, wait = ms;
	for (;;) {
		struct pollfd fds[INPUT_DEVS_POLL_MAX];
		int tags[INPUT_DEVS_POLL_MAX];
		int n = input_devs_pollfds(s, fds, tags, INPUT_DEVS_POLL_MAX);
		if (n == 0 || poll(fds, (nfds_t)n, wait) <= 0)
			return gone;
		for (int k = 0; k < n; k++)
			if (fds[k].revents && input_devs_ready(s, tags[k], now_us(), &q) < 0)
				gone++;
		wait = quiet_ms;
	}
}

/* every event in the queue into out (at most max): the count taken */
static size_t
drain(struct input_queue *from, struct input_event_rec *out, size_t max)
{
	size_t n = 0;
	struct input_event_rec e;
	while (input_queue_pop(from, &e))
		if (n < max)
			out[n++] = e;
	return n;
}

static const char *
kind_name(unsigned k)
{
	return input_kind_to_str((enum input_kind)k);
}

/* the place of the set's open device at node, or -1 */
static int
set_place(const struct input_devs *s, const char *node)
{
	return input_devs_find(s, &input_backend_evdev, node);
}

static struct evdev_dev *
set_dev(struct input_devs *s, int i)
{
	return i >= 0 && s->place[i].be == &input_backend_evdev ? s->place[i].dev : NULL;
}

/* ---- the recordings ---- */

struct recording {
	const char *file;
	enum input_class cls; /* what the device is: the test's own knowledge of the recording */
};

static const struct recording recordings[] = {
	{ "mouse.evemu", INPUT_CLASS_MOUSE },
	{ "keyboard.evemu", INPUT_CLASS_KEYBOARD },
	{ "tablet.evemu", INPUT_CLASS_OTHER },
	{ "tablet-v1.0.evemu", INPUT_CLASS_OTHER },
};
#define NRECORDINGS (sizeof recordings / sizeof recordings[0])

static int
load(const char *dir, const char *file, struct rec_evemu *r)
{
	char path[512], err[512];
	snprintf(path, sizeof path, "%s/%s", dir, file);
	if (rec_evemu_read(path, r, err, sizeof err) < 0) {
		fail("recording", "%s", err);
		return -1;
	}
	return 0;
}

#define MAXEV 2048
static struct input_event_rec got[MAXEV], want[MAXEV];

/*
 * The set, emptied (holding the grab when asked), opening v's node as
 * evdev:NODE (written into spec): what input_devs_open returns, its reason
 * in why.
 */
static int
set_open(const struct vdev *v, int grab, char *spec, size_t n, char *why, size_t nwhy)
{
	input_queue_init(&q);
	input_devs_init(&set, input_backends, input_backends_count, grab, &q);
	snprintf(spec, n, "evdev:%s", v->node);
	return input_devs_open(&set, spec, now_us(), why, nwhy);
}

/* a recording, its uinput device and the device's place in the set: what most checks start from */
struct rig {
	struct rec_evemu r;
	struct vdev v;
	char spec[96]; /* evdev:NODE */
	int place;
};

/* the recording file of dir into g: 0, or -1 (said; nothing to undo) */
static int
rig_load(struct rig *g, const char *dir, const char *file)
{
	g->v.fd = -1;
	g->place = -1;
	return load(dir, file, &g->r);
}

/* g's uinput device made: 0, or -1 said as what's failure */
static int
rig_make(struct rig *g, const char *what)
{
	char why[256];
	if (vdev_make(&g->r, &g->v, why, sizeof why) < 0) {
		fail(what, "%s", why);
		return -1;
	}
	return 0;
}

/* g's uinput device made and opened through the set (holding the grab when asked): 0, or -1 */
static int
rig_open(struct rig *g, int grab, const char *what)
{
	char why[256];
	if (rig_make(g, what) < 0)
		return -1;
	if (set_open(&g->v, grab, g->spec, sizeof g->spec, why, sizeof why) != 1) {
		fail(what, "%s not opened: %s", g->spec, set.nskip ? set.skip[0].why : why);
		return -1;
	}
	g->place = set_place(&set, g->v.node);
	return 0;
}

/* what rig_load and rig_open did, undone: the set closed, the device destroyed */
static void
rig_close(struct rig *g)
{
	input_devs_close_all(&set, now_us(), NULL);
	vdev_destroy(&g->v);
	rec_evemu_free(&g->r);
}


/*
 * evdev_dev_probe on a real node says what the recording's description
 * says: name, id and class; a node that is not evdev and a missing one are
 * refused with their reasons.
 */
static void
check_probe(const char *dir)
{
	for (size_t k = 0; k < NRECORDINGS; k++) {
		struct rec_evemu r;
		if (load(dir, recordings[k].file, &r) < 0)
			continue;
		struct vdev v;
		char why[256];
		if (vdev_make(&r, &v, why, sizeof why) < 0) {
			fail("probe", "%s: %s", recordings[k].file, why);
			rec_evemu_free(&r);
			continue;
		}
		struct evdev_dev_info info;
		if (evdev_dev_probe(v.node, &info, why, sizeof why) < 0)
			fail("probe", "%s: %s", v.node, why);
		else if (strcmp(info.name, r.name) || info.bustype != r.bustype ||
			 info.vendor != r.vendor || info.product != r.product ||
			 info.version != r.version || info.cls != recordings[k].cls)
			fail("probe", "%s: '%s' %04x:%04x:%04x:%04x class %d, the recording says "
			     "'%s' %04x:%04x:%04x:%04x class %d", v.node, info.name, info.bustype,
			     info.vendor, info.product, info.version, (int)info.cls, r.name,
			     r.bustype, r.vendor, r.product, r.version, (int)recordings[k].cls);
		else
			ok("probe %s (%s): '%s' %04x:%04x class %d", v.node, recordings[k].file,
			   info.name, info.vendor, info.product, (int)info.cls);
		vdev_destroy(&v);
		rec_evemu_free(&r);
	}
	struct evdev_dev_info info;
	char why[256] = "";
	if (evdev_dev_probe("/dev/null", &info, why, sizeof why) == 0 ||
	    !strstr(why, "not an evdev device"))
		fail("probe /dev/null", "not refused as not evdev: '%s'", why);
	else
		ok("probe /dev/null refused: %s", why);
	why[0] = '\0';
	if (evdev_dev_probe("/dev/input/event999", &info, why, sizeof why) == 0 ||
	    !strstr(why, strerror(ENOENT)))
		fail("probe missing node", "not refused with ENOENT: '%s'", why);
	else
		ok("probe of a missing node refused: %s", why);
}

/*
 * Whether evdev_dev_describe of the open device (what `posture-input
 * record` writes) differs from the recording's description: name, id,
 * properties, every type's codes but EV_SYN's (libevdev reports every SYN
 * code, evemu-record what the kernel's bitmask says), the absolute axes and
 * the LED and switch states. 0, or 1 with the first difference in why.
 */
static int
describe_differs(const struct evdev_dev *d, const struct rec_evemu *r, char *why, size_t n)
{
	static struct rec_evemu got_desc;
	evdev_dev_describe(d, &got_desc);
	const struct rec_evemu *g = &got_desc;
	if (strcmp(g->name, r->name) || g->bustype != r->bustype || g->vendor != r->vendor ||
	    g->product != r->product || g->version != r->version) {
		snprintf(why, n, "name or id: '%.60s' %04x:%04x:%04x:%04x", g->name, g->bustype,
			 g->vendor, g->product, g->version);
		return 1;
	}
	if (memcmp(g->props, r->props, sizeof g->props)) {
		snprintf(why, n, "the properties");
		return 1;
	}
	for (unsigned t = EV_SYN + 1; t < EV_CNT; t++)
		for (unsigned c = 0; c < REC_EVEMU_MASK_BYTES * 8; c++)
			if (bit_is_set(g->bits[t], c) != bit_is_set(r->bits[t], c)) {
				snprintf(why, n, "type %u code %u: %s here, %s in the recording", t, c,
					 bit_is_set(g->bits[t], c) ? "set" : "clear",
					 bit_is_set(r->bits[t], c) ? "set" : "clear");
				return 1;
			}
	for (unsigned c = 0; c < ABS_CNT; c++) {
		const struct rec_evemu_abs *a = &g->abs[c], *b = &r->abs[c];
		if (g->abs_given[c] != r->abs_given[c] || a->min != b->min || a->max != b->max ||
		    a->fuzz != b->fuzz || a->flat != b->flat || a->res != b->res) {
			snprintf(why, n, "axis %u: %d..%d fuzz %d flat %d res %d", c, a->min, a->max,
				 a->fuzz, a->flat, a->res);
			return 1;
		}
	}
	if (memcmp(g->led, r->led, sizeof g->led) || memcmp(g->sw, r->sw, sizeof g->sw)) {
		snprintf(why, n, "the LED or switch states");
		return 1;
	}
	return 0;
}

/*
 * The recording's description as a uinput device, opened through the set
 * as evdev:NODE; its events written through uinput frame by frame, the set
 * pumped after each frame. What comes out must be what decoding the
 * recording's bytes offline gives, but for the times, which must be the
 * kernel's CLOCK_MONOTONIC stamps of the replay.
 */
static void
check_replay(const char *dir, const struct recording *rec)
{
	char what[96];
	snprintf(what, sizeof what, "replay %s", rec->file);
	struct rig g;
	if (rig_load(&g, dir, rec->file) < 0)
		return;
	char why[256];
	int raw = -1;
	if (rig_open(&g, 0, what) < 0)
		goto out;
	int i = g.place;
	struct input_event_rec e;
	if (!input_queue_pop(&q, &e) || e.kind != INPUT_ADDED || e.device != i ||
	    e.code != rec->cls) {
		fail(what, "no INPUT_ADDED of class %d for device %d", (int)rec->cls, i);
		goto out;
	}
	struct evdev_dev *d = set_dev(&set, i);
	if (!d->monotonic)
		fail(what, "EVIOCSCLOCKID(CLOCK_MONOTONIC) was refused");
	if (describe_differs(d, &g.r, why, sizeof why))
		fail(what, "the description the backend reads back differs: %s", why);
	else
		ok("%s: the description read back from the kernel (what `posture-input record` "
		   "writes) is the recording's", what);

	/* the reference: the recording's bytes through the decoder, offline */
	struct evdev_input ref;
	evdev_input_init(&ref, (uint16_t)i, "reference");
	rec_evemu_apply_abs(&g.r, &ref);
	size_t nbytes = rec_evemu_to_records(&g.r, NULL, 0);
	uint8_t *bytes = malloc(nbytes ? nbytes : 1);
	rec_evemu_to_records(&g.r, bytes, nbytes);
	input_queue_init(&qref);
	evdev_input_feed(&ref, bytes, nbytes, &qref);
	free(bytes);
	size_t nwant = drain(&qref, want, MAXEV);

	/* a plain reader of the same node beside the set: the records the kernel passes */
	raw = open(g.v.node, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
	if (raw < 0) {
		fail(what, "second open of %s: %s", g.v.node, strerror(errno));
		goto out;
	}

	/* the replay: each frame written in one write(), as a device's driver sends it */
	uint64_t t0 = now_us();
	struct input_event frame[64];
	size_t nf = 0, ngot = 0;
	for (size_t k = 0; k < g.r.nev; k++) {
		memset(&frame[nf], 0, sizeof frame[nf]);
		frame[nf].type = g.r.ev[k].type;
		frame[nf].code = g.r.ev[k].code;
		frame[nf].value = g.r.ev[k].value;
		nf++;
		int end = g.r.ev[k].type == EV_SYN && g.r.ev[k].code == SYN_REPORT;
		if (!end && nf < 64 && k + 1 < g.r.nev)
			continue;
		if (uinput_write(g.v.fd, frame, nf) < 0) {
			fail(what, "uinput write: %s", strerror(errno));
			goto out;
		}
		nf = 0;
		pump(&set, 1000, 0);
		ngot += drain(&q, got + ngot, MAXEV - ngot);
	}
	pump(&set, 100, 50);
	ngot += drain(&q, got + ngot, MAXEV - ngot);
	uint64_t t1 = now_us();

	/* the kernel passed every record unchanged (but its time), in order */
	static struct input_event passed[MAXEV];
	size_t nraw = 0, k;
	ssize_t rn;
	while (nraw < MAXEV && (rn = read(raw, passed + nraw, (MAXEV - nraw) * sizeof passed[0])) > 0)
		nraw += (size_t)rn / sizeof passed[0];
	for (k = 0; k < nraw && k < g.r.nev; k++)
		if (passed[k].type != g.r.ev[k].type || passed[k].code != g.r.ev[k].code ||
		    passed[k].value != g.r.ev[k].value)
			break;
	if (k != g.r.nev || nraw != g.r.nev) {
		fail(what, "the kernel passed %zu records for the recording's %zu; first difference "
		     "at %zu: %04x %04x %d", nraw, g.r.nev, k, k < nraw ? passed[k].type : 0,
		     k < nraw ? passed[k].code : 0, k < nraw ? passed[k].value : 0);
		goto out;
	}
	/* the same events, and times from the kernel's monotonic clock during the replay */
	for (k = 0; k < nwant && k < ngot; k++) {
		const struct input_event_rec *a = &got[k], *b = &want[k];
		if (a->kind != b->kind || a->code != b->code || a->value != b->value ||
		    a->flags != b->flags || a->device != b->device || a->x != b->x || a->y != b->y)
			break;
	}
	if (k != nwant || ngot != nwant || nwant == 0) {
		fail(what, "%zu events out of the backend, %zu from the recording; first "
		     "difference at %zu: got %s code %u value %d x %g y %g, want %s code %u "
		     "value %d x %g y %g", ngot, nwant, k, k < ngot ? kind_name(got[k].kind) : "-",
		     got[k].code, got[k].value, got[k].x, got[k].y,
		     k < nwant ? kind_name(want[k].kind) : "-", want[k].code, want[k].value,
		     want[k].x, want[k].y);
		goto out;
	}
	uint64_t prev = t0;
	for (k = 0; k < ngot; k++) {
		if (got[k].t_us < prev || got[k].t_us > t1) {
			fail(what, "event %zu stamped %llu us, outside the replay's %llu..%llu or "
			     "before the one before", k, (unsigned long long)got[k].t_us,
			     (unsigned long long)t0, (unsigned long long)t1);
			goto out;
		}
		prev = got[k].t_us;
	}
	ok("%s: the kernel passed its %zu records unchanged; the backend's %zu events equal "
	   "the recording decoded offline (times: the kernel's monotonic stamps)", what, g.r.nev,
	   ngot);
out:
	if (raw >= 0)
		close(raw);
	rig_close(&g);
}

/*
 * `auto` with the recordings' devices plugged in: the mouse and the
 * keyboard opened, the tablets skipped with the reason.
 */
static void
check_auto(const char *dir)
{
	struct rec_evemu r[NRECORDINGS];
	struct vdev v[NRECORDINGS];
	int n = 0;
	char why[256];
	for (size_t k = 0; k < NRECORDINGS; k++) {
		v[k].fd = -1;
		if (load(dir, recordings[k].file, &r[k]) < 0)
			continue;
		if (vdev_make(&r[k], &v[k], why, sizeof why) < 0)
			fail("auto", "%s: %s", recordings[k].file, why);
		else
			n++;
	}
	input_queue_init(&q);
	input_devs_init(&set, input_backends, input_backends_count, 0, &q);
	int opened = input_devs_open(&set, "auto", now_us(), why, sizeof why);
	int bad = 0;
	for (size_t k = 0; k < NRECORDINGS; k++) {
		if (v[k].fd < 0)
			continue;
		int i = set_place(&set, v[k].node);
		const char *skipped = NULL;
		for (int s = 0; s < set.nskip; s++)
			if (!strcmp(set.skip[s].what, v[k].node))
				skipped = set.skip[s].why;
		if (recordings[k].cls != INPUT_CLASS_OTHER) {
			if (i < 0 || set.place[i].info.cls != recordings[k].cls ||
			    strcmp(set.place[i].info.name, r[k].name)) {
				fail("auto", "%s (%s) not opened as class %d (%s)", v[k].node,
				     recordings[k].file, (int)recordings[k].cls,
				     skipped ? skipped : "not skipped either");
				bad++;
			}
		} else if (i >= 0 || !skipped || strcmp(skipped, "neither a mouse nor a keyboard")) {
			fail("auto", "%s (%s) should be skipped as neither a mouse nor a keyboard, "
			     "is %s", v[k].node, recordings[k].file,
			     i >= 0 ? "open" : skipped ? skipped : "neither open nor skipped");
			bad++;
		}
	}
	/* the guest's own devices (the AT keyboard, the power button...) as they come */
	for (int i = 0; i < INPUT_DEVS_MAX; i++)
		if (set.place[i].be)
			printf("auto: open %s '%s' class %d\n", set.place[i].info.path,
			       set.place[i].info.name, (int)set.place[i].info.cls);
	for (int s = 0; s < set.nskip; s++) {
		printf("auto: skipped %s: %s\n", set.skip[s].what, set.skip[s].why);
		if (!set.skip[s].why[0]) {
			fail("auto", "%s skipped with no reason", set.skip[s].what);
			bad++;
		}
	}
	if (!bad && n == (int)NRECORDINGS)
		ok("auto: %d devices opened; the recordings' mouse and keyboard among them, their "
		   "tablets skipped as neither a mouse nor a keyboard", opened);
	input_devs_close_all(&set, now_us(), NULL);
	for (size_t k = 0; k < NRECORDINGS; k++) {
		vdev_destroy(&v[k]);
		rec_evemu_free(&r[k]);
	}
}

/* one motion frame through uinput: REL_X dx */
static int
motion(const struct vdev *v, int dx)
{
	return vdev_frame(v, EV_REL, REL_X, dx);
}

/* the set took one INPUT_MOTION of dx (and its frame end): 1, or 0 */
static int
set_saw(int dx)
{
	pump(&set, 1000, 20);
	struct input_event_rec e;
	int seen = 0, other = 0;
	while (input_queue_pop(&q, &e)) {
		if (e.kind == INPUT_MOTION && e.x == dx)
			seen++;
		else if (e.kind != INPUT_FRAME)
			other++;
	}
	return seen == 1 && !other;
}

/* the other reader's records of REL_X (after waiting a little): dx of the last, 0 for none */
static int
other_saw(int fd)
{
	struct pollfd p = { .fd = fd, .events = POLLIN };
	poll(&p, 1, 100);
	struct input_event ev[16];
	int dx = 0;
	ssize_t n;
	while ((n = read(fd, ev, sizeof ev)) > 0)
		for (size_t k = 0; k < (size_t)n / sizeof ev[0]; k++)
			if (ev[k].type == EV_REL && ev[k].code == REL_X)
				dx = ev[k].value;
	return dx;
}

/*
 * REL_X dx through uinput: the set must see it, and the other reader on
 * fd other only when shared (the grab not held). 0, or -1 said as W's
 * failure in state.
 */
static int
grab_motion(const struct vdev *v, int other, int dx, int shared, const char *W,
	    const char *state)
{
	motion(v, dx);
	int a = set_saw(dx), b = other_saw(other);
	if (a && b == (shared ? dx : 0))
		return 0;
	fail(W, "%s: the set %s REL_X %d, the other reader saw %d", state, a ? "saw" : "missed",
	     dx, b);
	return -1;
}

/*
 * The kiosk grab on a real node: with it, a second reader (a plain open and
 * read of the same node) sees nothing while the set sees everything; given
 * up, the other sees again; taken again, not; the set closed, the grab is
 * gone; the node opened again, it is taken again.
 */
static void
check_grab(const char *dir)
{
	const char *W = "grab";
	struct rig g;
	if (rig_load(&g, dir, "mouse.evemu") < 0)
		return;
	char why[256];
	int other = -1;
	if (rig_open(&g, 1, W) < 0)
		goto out;
	int i = g.place;
	drain(&q, got, MAXEV);
	other = open(g.v.node, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
	if (other < 0) {
		fail(W, "second open of %s: %s", g.v.node, strerror(errno));
		goto out;
	}
	if (!set.place[i].info.grabbed || !set_dev(&set, i)->grabbed) {
		fail(W, "the set does not say the grab is held");
		goto out;
	}
	if (ioctl(other, EVIOCGRAB, 1) == 0 || errno != EBUSY) {
		fail(W, "the kernel did not refuse a second grab with EBUSY (%s)", strerror(errno));
		goto out;
	}
	if (grab_motion(&g.v, other, 5, 0, W, "grabbed") < 0)
		goto out;
	ok("grab held: the set saw REL_X 5, the other reader nothing, a second EVIOCGRAB EBUSY");
	if (input_devs_set_grab(&set, 0) < 0 || set.place[i].info.grabbed) {
		fail(W, "input_devs_set_grab(0) refused");
		goto out;
	}
	if (grab_motion(&g.v, other, 6, 1, W, "ungrabbed") < 0)
		goto out;
	ok("ungrab: both the set and the other reader saw REL_X 6");
	if (input_devs_set_grab(&set, 1) < 0) {
		fail(W, "input_devs_set_grab(1) refused: %s", strerror(errno));
		goto out;
	}
	if (grab_motion(&g.v, other, 7, 0, W, "grabbed again") < 0)
		goto out;
	ok("grab taken again: the set saw REL_X 7, the other reader nothing");
	input_devs_close_all(&set, now_us(), &q);
	drain(&q, got, MAXEV);
	motion(&g.v, 8);
	int b = other_saw(other);
	if (b != 8) {
		fail(W, "closed: the other reader saw %d, not REL_X 8 (the grab outlived the fd)", b);
		goto out;
	}
	ok("close: the grab is gone with the fd (the other reader saw REL_X 8)");
	if (input_devs_open(&set, g.spec, now_us(), why, sizeof why) != 1) {
		fail(W, "reopen: %s", set.nskip ? set.skip[0].why : why);
		goto out;
	}
	drain(&q, got, MAXEV);
	if (grab_motion(&g.v, other, 9, 0, W, "reopened") < 0)
		goto out;
	ok("reopen: the grab is taken again (the set saw REL_X 9, the other reader nothing)");
out:
	if (other >= 0)
		close(other);
	rig_close(&g);
}

/*
 * Another process holds the grab: evdev_dev_open with grab fails with the
 * clear reason, and so does the set's open of the node (recorded as a
 * skip); without the grab it opens; once the other lets go, the grab is ours.
 */
static void
check_grab_held(const char *dir)
{
	const char *W = "grab held elsewhere";
	struct rig g;
	if (rig_load(&g, dir, "mouse.evemu") < 0)
		return;
	char why[256] = "";
	int ready[2] = { -1, -1 }, hold[2] = { -1, -1 };
	pid_t pid = -1;
	if (rig_make(&g, W) < 0)
		goto out;
	if (pipe(ready) < 0 || pipe(hold) < 0) {
		fail(W, "pipe: %s", strerror(errno));
		goto out;
	}
	pid = fork();
	if (pid == 0) { /* the other process: grab, say so, hold until told */
		close(ready[0]);
		close(hold[1]);
		int fd = open(g.v.node, O_RDONLY | O_CLOEXEC);
		char c = fd >= 0 && ioctl(fd, EVIOCGRAB, 1) == 0 ? 'g' : 'x';
		if (write(ready[1], &c, 1) != 1)
			_exit(2);
		while (read(hold[0], &c, 1) > 0)
			;
		_exit(0);
	}
	close(ready[1]);
	close(hold[0]);
	ready[1] = hold[0] = -1;
	char c = 0;
	if (pid < 0 || read(ready[0], &c, 1) != 1 || c != 'g') {
		fail(W, "the other process could not grab %s", g.v.node);
		goto out;
	}
	struct evdev_dev d;
	if (evdev_dev_open(&d, g.v.node, 0, 1, why, sizeof why) == 0) {
		fail(W, "evdev_dev_open with grab succeeded");
		evdev_dev_close(&d, 0, NULL);
		goto out;
	}
	if (!strstr(why, "another reader holds the grab") || !strstr(why, g.v.node)) {
		fail(W, "the reason is not clear: '%s'", why);
		goto out;
	}
	ok("evdev_dev_open with grab on a node another process grabbed: %s", why);
	int n = set_open(&g.v, 1, g.spec, sizeof g.spec, why, sizeof why);
	if (n != 0 || set.nskip != 1 || !strstr(set.skip[0].why, "another reader holds the grab"))
		fail(W, "the set opened %d, skipped %d: '%s'", n, set.nskip,
		     set.nskip ? set.skip[0].why : "");
	else
		ok("the set's open with grab skips it: %s: %s", set.skip[0].what, set.skip[0].why);
	input_devs_close_all(&set, now_us(), NULL);
	if (evdev_dev_open(&d, g.v.node, 0, 0, why, sizeof why) < 0)
		fail(W, "evdev_dev_open without grab: %s", why);
	else
		evdev_dev_close(&d, 0, NULL);
	close(hold[1]);
	hold[1] = -1;
	waitpid(pid, NULL, 0);
	pid = -1;
	if (evdev_dev_open(&d, g.v.node, 0, 1, why, sizeof why) < 0) {
		fail(W, "after the other process ended, the grab is still refused: %s", why);
	} else {
		if (!d.grabbed)
			fail(W, "after the other process ended, opened without the grab");
		else
			ok("without grab it opens; after the other process ended the grab is ours");
		evdev_dev_close(&d, 0, NULL);
	}
out:
	for (int k = 0; k < 2; k++) {
		if (ready[k] >= 0)
			close(ready[k]);
		if (hold[k] >= 0)
			close(hold[k]);
	}
	if (pid > 0)
		waitpid(pid, NULL, 0);
	rig_close(&g);
}

/* one key frame through uinput: the key's record and SYN_REPORT */
static int
key_frame(const struct vdev *v, unsigned code, int value)
{
	return vdev_frame(v, EV_KEY, code, value);
}

/* key c of a key bitmask (EVIOCGKEY's layout) set to down */
static void
set_key(uint8_t *mask, unsigned c, int down)
{
	mask[c / 8] = (uint8_t)((mask[c / 8] & ~(1u << c % 8)) | (down ? 1u << c % 8 : 0));
}

/*
 * SYN_DROPPED from a real overflow: the keyboard's evdev client buffer
 * (64 records for its capabilities: the kernel sizes it 8 packets of
 * (1 + 7 + axes) events, at least 64) overflowed by writing far more
 * without reading. A and B are down before; during the stretch the kernel
 * drops, A is released and C pressed, and D pressed and released many
 * times; after it, E pressed. The backend must resync once, come out with
 * A released, C pressed and B never released, and believe what EVIOCGKEY
 * on another fd says.
 */
static void
check_syn_dropped(const char *dir)
{
	const char *W = "SYN_DROPPED";
	struct rig g;
	if (rig_load(&g, dir, "keyboard.evemu") < 0)
		return;
	int truth_fd = -1;
	if (rig_open(&g, 0, W) < 0)
		goto out;
	struct evdev_dev *d = set_dev(&set, g.place);
	drain(&q, got, MAXEV);

	/* A and B down, read */
	key_frame(&g.v, KEY_A, 1);
	key_frame(&g.v, KEY_B, 1);
	pump(&set, 1000, 20);
	uint8_t state[EVDEV_INPUT_KEYBITS];
	memset(state, 0, sizeof state);
	size_t n = drain(&q, got, MAXEV);
	for (size_t k = 0; k < n; k++)
		if (got[k].kind == INPUT_KEY && got[k].code < KEY_CNT)
			set_key(state, got[k].code, got[k].value);
	if (!bit_is_set(state, KEY_A) || !bit_is_set(state, KEY_B)) {
		fail(W, "A and B did not come out pressed before the overflow");
		goto out;
	}
	uint64_t resyncs0 = d->resyncs, drops0 = d->in.dropped_frames;

	/* the stretch the kernel drops, then E after it; nothing read meanwhile */
	int wrote = 0;
	wrote |= key_frame(&g.v, KEY_A, 0);
	wrote |= key_frame(&g.v, KEY_C, 1);
	for (int k = 0; k < 100; k++) {
		wrote |= key_frame(&g.v, KEY_D, 1);
		wrote |= key_frame(&g.v, KEY_D, 0);
	}
	wrote |= key_frame(&g.v, KEY_E, 1);
	if (wrote) {
		fail(W, "uinput write: %s", strerror(errno));
		goto out;
	}

	/* the kernel's own key state, from another reader: the ground truth */
	uint8_t truth[EVDEV_INPUT_KEYBITS];
	memset(truth, 0, sizeof truth);
	truth_fd = open(g.v.node, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
	if (truth_fd < 0 || ioctl(truth_fd, EVIOCGKEY(sizeof truth), truth) < 0) {
		fail(W, "EVIOCGKEY on a second fd: %s", strerror(errno));
		goto out;
	}

	pump(&set, 1000, 50);
	n = drain(&q, got, MAXEV);
	int a_up = 0, b_up = 0, c_down = 0;
	for (size_t k = 0; k < n; k++) {
		if (got[k].kind != INPUT_KEY || got[k].code >= KEY_CNT)
			continue;
		unsigned c = got[k].code;
		a_up |= c == KEY_A && got[k].value == 0;
		b_up |= c == KEY_B && got[k].value == 0;
		c_down |= c == KEY_C && got[k].value == 1;
		set_key(state, c, got[k].value);
	}
	uint64_t resyncs = d->resyncs - resyncs0, drops = d->in.dropped_frames - drops0;
	int believed_ok = 1, events_ok = 1;
	for (unsigned c = 0; c < KEY_CNT; c++) {
		believed_ok &= evdev_input_key_down(&d->in, (uint16_t)c) == bit_is_set(truth, c);
		events_ok &= bit_is_set(state, c) == bit_is_set(truth, c);
	}
	if (drops != 1 || resyncs != 1)
		fail(W, "%llu SYN_DROPPED seen and %llu resyncs, want 1 and 1",
		     (unsigned long long)drops, (unsigned long long)resyncs);
	else if (!bit_is_set(truth, KEY_B) || !bit_is_set(truth, KEY_C) ||
		 !bit_is_set(truth, KEY_E) || bit_is_set(truth, KEY_A) || bit_is_set(truth, KEY_D))
		fail(W, "EVIOCGKEY is not what was written (A up, B C E down, D up)");
	else if (!a_up || !c_down || b_up)
		fail(W, "after the resync: A released %d, C pressed %d, B released %d "
		     "(want 1, 1, 0)", a_up, c_down, b_up);
	else if (!believed_ok || !events_ok)
		fail(W, "the key state differs from EVIOCGKEY's: the decoder's %s, the events' %s",
		     believed_ok ? "agrees" : "differs", events_ok ? "agree" : "differ");
	else
		ok("SYN_DROPPED from a real overflow: 1 drop, 1 resync; A came out released, C "
		   "pressed, B held; the key state equals EVIOCGKEY's (%zu events after the drop)",
		   n);
out:
	if (truth_fd >= 0)
		close(truth_fd);
	rig_close(&g);
}

/*
 * SYN_DROPPED with more left after the drop than one read takes: the
 * mouse's client buffer holds 128 records, so after an overflow up to 127
 * wait, and evdev_dev_read takes 64 at a time. 122 motion frames (REL_X,
 * SYN_REPORT) and then the left button's press are written unread: 246
 * records, which leave the buffer holding SYN_DROPPED and the last 119 (the
 * kernel keeps SYN_DROPPED and the newest record when it overflows, then
 * fills up again). The press is the newest thing the device did, so no
 * motion may come out after it: the key state EVIOCGKEY gives is the
 * state after every record still waiting, and must not be applied before
 * them.
 */
static void
check_syn_dropped_tail(const char *dir)
{
	const char *W = "SYN_DROPPED, a long tail";
	struct rig g;
	if (rig_load(&g, dir, "mouse.evemu") < 0)
		return;
	if (rig_open(&g, 0, W) < 0)
		goto out;
	struct evdev_dev *d = set_dev(&set, g.place);
	drain(&q, got, MAXEV);
	for (int k = 1; k <= 122; k++)
		motion(&g.v, k);
	key_frame(&g.v, BTN_LEFT, 1);

	uint64_t reads0 = d->reads, resyncs0 = d->resyncs;
	pump(&set, 1000, 50);
	size_t n = drain(&q, got, MAXEV);
	int press = -1, after = 0, motions = 0;
	for (size_t k = 0; k < n; k++) {
		if (got[k].kind == INPUT_BUTTON && got[k].code == BTN_LEFT && got[k].value == 1)
			press = (int)k;
		if (got[k].kind == INPUT_MOTION) {
			motions++;
			after += press >= 0;
		}
	}
	if (d->resyncs - resyncs0 != 1 || press < 0 || !evdev_input_key_down(&d->in, BTN_LEFT))
		fail(W, "%llu resyncs, %llu drops, %llu reads, %zu events, the press at %d, BTN_LEFT "
		     "believed %s", (unsigned long long)(d->resyncs - resyncs0),
		     (unsigned long long)d->in.dropped_frames, (unsigned long long)(d->reads - reads0),
		     n, press, evdev_input_key_down(&d->in, BTN_LEFT) ? "down" : "up");
	else if (after)
		fail(W, "%d of the %d motions the device sent before its press came out after it "
		     "(the resync applied the key state before the records still waiting; %llu "
		     "reads)", after, motions, (unsigned long long)(d->reads - reads0));
	else
		ok("SYN_DROPPED with a long tail: %d motions, then the press, in the device's order "
		   "(%llu reads, 1 resync)", motions, (unsigned long long)(d->reads - reads0));
out:
	rig_close(&g);
}

/*
 * The read cap against the kernel: 40 motion frames (REL_X k, REL_Y 1,
 * SYN_REPORT: 120 records, within
 * the mouse's 128-record client buffer) written with nothing read; the first
 * evdev_dev_read takes EVDEV_DEV_READ_MAX (64) records, 21 frames and the
 * start of the 22nd, and counts itself capped; the second takes the other 56
 * and finishes the split frame; the third finds nothing. The events are the
 * 40 motions written, in order. The counters start at 0 on memory that held
 * something else.
 */
static void
check_read_cap(const char *dir)
{
	const char *W = "read cap";
	struct rig g;
	if (rig_load(&g, dir, "mouse.evemu") < 0)
		return;
	char why[256];
	static struct evdev_dev d;
	memset(&d, 0xa5, sizeof d); /* the counters must start at 0 whatever the memory held */
	d.fd = -1;
	d.evdev = NULL;
	if (rig_make(&g, W) < 0)
		goto out;
	if (evdev_dev_open(&d, g.v.node, 0, 0, why, sizeof why) < 0) {
		fail(W, "%s", why);
		goto out;
	}
	if (d.reads || d.capped || d.resyncs) {
		fail(W, "evdev_dev_open left the counters at reads %llu capped %llu resyncs %llu",
		     (unsigned long long)d.reads, (unsigned long long)d.capped,
		     (unsigned long long)d.resyncs);
		goto out;
	}
	for (int k = 1; k <= 40; k++)
		vdev_motion(&g.v, k, 1);
	input_queue_init(&q);
	int n1 = evdev_dev_read(&d, now_us(), &q);
	uint64_t capped1 = d.capped;
	int n2 = evdev_dev_read(&d, now_us(), &q);
	int n3 = evdev_dev_read(&d, now_us(), &q);
	size_t n = drain(&q, got, MAXEV);
	int motions = 0, in_order = 1;
	for (size_t k = 0; k < n; k++)
		if (got[k].kind == INPUT_MOTION)
			in_order &= got[k].x == ++motions;
	if (n1 != EVDEV_DEV_READ_MAX || capped1 != 1 || n2 != 120 - EVDEV_DEV_READ_MAX || n3 != 0)
		fail(W, "reads took %d, %d, %d records (capped %llu), want %d, %d, 0 (capped 1)", n1,
		     n2, n3, (unsigned long long)capped1, EVDEV_DEV_READ_MAX,
		     120 - EVDEV_DEV_READ_MAX);
	else if (motions != 40 || !in_order)
		fail(W, "%d motions came out (in order: %d), want the 40 written", motions, in_order);
	else
		ok("read cap: 120 waiting records read as %d + %d (the first read capped), the 40 "
		   "motions whole and in order across the split frame", n1, n2);
out:
	evdev_dev_close(&d, 0, NULL);
	rig_close(&g);
}

/*
 * Unplug mid-drag: the left button down and the mouse moving, then the
 * uinput device destroyed. The set must release the button (INPUT_BUTTON
 * BTN_LEFT 0), queue INPUT_REMOVED, free the device's place, and log a line
 * naming the device.
 */
static void
check_unplug(const char *dir)
{
	const char *W = "unplug mid-drag";
	struct rig g;
	if (rig_load(&g, dir, "mouse.evemu") < 0)
		return;
	char *log = NULL;
	size_t loglen = 0;
	FILE *logf = open_memstream(&log, &loglen);
	if (rig_open(&g, 1, W) < 0)
		goto out;
	int i = g.place;
	set_dev(&set, i)->in.log.out = logf;
	drain(&q, got, MAXEV);

	/* the drag: button down, two motions */
	key_frame(&g.v, BTN_LEFT, 1);
	motion(&g.v, 3);
	vdev_motion(&g.v, 4, -1);
	pump(&set, 1000, 20);
	size_t n = drain(&q, got, MAXEV);
	int down = 0, moved = 0;
	for (size_t k = 0; k < n; k++) {
		down |= got[k].kind == INPUT_BUTTON && got[k].code == BTN_LEFT && got[k].value == 1;
		moved += got[k].kind == INPUT_MOTION;
	}
	if (!down || moved != 2) {
		fail(W, "the drag did not come through (button down %d, %d motions)", down, moved);
		goto out;
	}

	/* the unplug */
	if (ioctl(g.v.fd, UI_DEV_DESTROY) < 0) {
		fail(W, "UI_DEV_DESTROY: %s", strerror(errno));
		goto out;
	}
	int gone = pump(&set, 2000, 20);
	n = drain(&q, got, MAXEV);
	int released = -1, removed = -1;
	for (size_t k = 0; k < n; k++) {
		if (got[k].kind == INPUT_BUTTON && got[k].code == BTN_LEFT && got[k].value == 0 &&
		    got[k].device == i)
			released = (int)k;
		if (got[k].kind == INPUT_REMOVED && got[k].device == i &&
		    got[k].code == INPUT_CLASS_MOUSE)
			removed = (int)k;
	}
	fflush(logf);
	char who[64];
	snprintf(who, sizeof who, "(%s)", strrchr(g.v.node, '/') + 1);
	if (gone != 1 || released < 0 || removed < released)
		fail(W, "gone %d; BTN_LEFT released at %d, INPUT_REMOVED at %d (of %zu events)", gone,
		     released, removed, n);
	else if (input_devs_count(&set) != 0 || set.place[i].be ||
		 input_devs_free_place(&set, "x") != i)
		fail(W, "the device's place %d was not freed", i);
	else if (!log || !strstr(log, who) || !strstr(log, "gone") ||
		 !strstr(log, "1 key(s) and button(s) released"))
		fail(W, "no log line naming %s: '%s'", who, log ? log : "");
	else {
		char *nl = strchr(log, '\n');
		if (nl)
			*nl = '\0';
		ok("unplug mid-drag: BTN_LEFT released, INPUT_REMOVED queued, place %d free; log: %s",
		   i, log);
	}
out:
	rig_close(&g);
	fclose(logf);
	free(log);
}

static int
run_checks(const char *dir)
{
	if (geteuid() != 0)
		printf("note: not root; expect permission failures\n");
	check_probe(dir);
	for (size_t k = 0; k < NRECORDINGS; k++)
		check_replay(dir, &recordings[k]);
	check_auto(dir);
	check_grab(dir);
	check_grab_held(dir);
	check_syn_dropped(dir);
	check_syn_dropped_tail(dir);
	check_read_cap(dir);
	check_unplug(dir);
	printf("guest_evdev: %d failure%s\n", guest_failures, guest_failures == 1 ? "" : "s");
	return guest_status();
}

/* ---- the latency benchmark ---- */

static int
cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* the p-quantile of v[0..n) by nearest rank (sorts v) */
static double
quantile(double *v, int n, double p)
{
	qsort(v, (size_t)n, sizeof *v, cmp_double);
	return v[(int)(p * (n - 1) + 0.5)];
}

/*
 * Two fixed computations, the same instructions on the host and in the guest,
 * whose time ratio names the guest's slowdown beside the latency: alu, 20 M
 * xorshift64 steps (registers only, the best case for TCG's translated
 * code), and decode, the backend's own work on the latency's path: 200 000
 * motion frames (REL_X, REL_Y, SYN_REPORT) through evdev_input_feed in reads
 * of 63 records, the queue emptied after each. Each is the best of three, in
 * ns (decode: ns a frame).
 */
static void
calib(double *alu_ns, double *decode_ns)
{
	enum { FRAMES = 1000, PASSES = 200, CHUNK = 63 };
	static struct input_event recs[FRAMES * 3];
	memset(recs, 0, sizeof recs);
	for (int f = 0; f < FRAMES; f++) {
		recs[3 * f] = (struct input_event){ .type = EV_REL, .code = REL_X, .value = f % 7 - 3 };
		recs[3 * f + 1] = (struct input_event){ .type = EV_REL, .code = REL_Y, .value = 1 };
		recs[3 * f + 2] = (struct input_event){ .type = EV_SYN, .code = SYN_REPORT };
	}
	*alu_ns = *decode_ns = 0;
	for (int rep = 0; rep < 3; rep++) {
		double t0 = mono_us_f();
		volatile uint64_t sink;
		uint64_t x = 88172645463325252ull, sum = 0;
		for (long k = 0; k < 20000000L; k++) {
			x ^= x << 13;
			x ^= x >> 7;
			x ^= x << 17;
			sum += x;
		}
		sink = sum;
		(void)sink;
		double ns = (mono_us_f() - t0) * 1e3;
		*alu_ns = rep == 0 || ns < *alu_ns ? ns : *alu_ns;

		struct evdev_input in;
		evdev_input_init(&in, 0, "calib");
		input_queue_init(&qref);
		struct input_event_rec e;
		t0 = mono_us_f();
		for (int pass = 0; pass < PASSES; pass++)
			for (int r = 0; r < FRAMES * 3; r += CHUNK) {
				int n = FRAMES * 3 - r < CHUNK ? FRAMES * 3 - r : CHUNK;
				evdev_input_feed(&in, (const uint8_t *)(recs + r),
						 (size_t)n * sizeof recs[0], &qref);
				while (input_queue_pop(&qref, &e))
					;
			}
		ns = (mono_us_f() - t0) * 1e3 / (FRAMES * PASSES);
		*decode_ns = rep == 0 || ns < *decode_ns ? ns : *decode_ns;
	}
}

static void
print_calib(void)
{
	double alu, decode;
	calib(&alu, &decode);
	printf("calib alu_ns=%.0f decode_ns=%.1f\n", alu, decode);
}

/*
 * n motion frames (REL_X 1, REL_Y 1, SYN_REPORT in one write) written
 * gap_us apart by a child process through uinput; this process waits in
 * poll() on the set's fds as the daemon's loop does, calls input_devs_ready
 * and reads the clock when the event is in the queue. Each frame's latency
 * is taken from the kernel's stamp (its CLOCK_MONOTONIC time at the write)
 * and from the writer's clock_gettime just before write(). The first 20
 * are a warm-up and left out. Frames the kernel dropped (this process fell
 * behind by a whole client buffer: SYN_DROPPED) are counted as lost.
 */
static int
run_latency(int n, int gap_us)
{
	struct rec_evemu r;
	memset(&r, 0, sizeof r);
	snprintf(r.name, sizeof r.name, "posture latency mouse");
	r.bustype = BUS_VIRTUAL;
	r.bits[EV_KEY][BTN_LEFT / 8] |= (uint8_t)(1u << BTN_LEFT % 8);
	r.bits[EV_REL][0] = 1u << REL_X | 1u << REL_Y;
	struct vdev v;
	char why[256], spec[96];
	if (vdev_make(&r, &v, why, sizeof why) < 0) {
		printf("latency: %s\n", why);
		return 1;
	}
	if (set_open(&v, 0, spec, sizeof spec, why, sizeof why) != 1) {
		printf("latency: %s not opened\n", spec);
		return 1;
	}
	drain(&q, got, MAXEV);
	int warm = 20, total = n + warm;
	double *t_write = mmap(NULL, (size_t)total * sizeof(double), PROT_READ | PROT_WRITE,
			       MAP_SHARED | MAP_ANONYMOUS, -1, 0);
	double *lat_k = calloc((size_t)total, sizeof(double));
	double *lat_w = calloc((size_t)total, sizeof(double));
	if (t_write == MAP_FAILED || !lat_k || !lat_w) {
		printf("latency: out of memory\n");
		return 1;
	}
	pid_t pid = fork();
	if (pid == 0) { /* the device: a frame every gap_us */
		struct timespec next;
		clock_gettime(CLOCK_MONOTONIC, &next);
		struct input_event ev[3];
		memset(ev, 0, sizeof ev);
		ev[0].type = ev[1].type = EV_REL;
		ev[0].code = REL_X;
		ev[1].code = REL_Y;
		ev[1].value = 1;
		ev[2].type = EV_SYN;
		for (int k = 0; k < total; k++) {
			ev[0].value = k + 1;
			next.tv_nsec += (long)gap_us * 1000;
			while (next.tv_nsec >= 1000000000L) {
				next.tv_nsec -= 1000000000L;
				next.tv_sec++;
			}
			clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, NULL);
			t_write[k] = mono_us_f();
			if (uinput_write(v.fd, ev, 3) < 0)
				_exit(1);
		}
		_exit(0);
	}
	/* frame k moves REL_X by k + 1, which says which write an event is */
	int k = 0, last = 0;
	while (last < total) {
		if (poll_devs(&set, &q, 2000) < 0)
			break;
		double t_q = mono_us_f();
		struct input_event_rec e;
		while (input_queue_pop(&q, &e)) {
			int w = (int)e.x - 1;
			if (e.kind != INPUT_MOTION || w < 0 || w >= total)
				continue;
			last = w + 1;
			if (w < warm)
				continue;
			lat_k[k] = t_q - (double)e.t_us;
			lat_w[k] = t_q - t_write[w];
			k++;
		}
	}
	int status = 0;
	waitpid(pid, &status, 0);
	struct evdev_dev *d = set_dev(&set, set_place(&set, v.node));
	if (k < 1 || last < total || !WIFEXITED(status) || WEXITSTATUS(status)) {
		printf("latency: %d of %d frames came through (the writer: status %d)\n", k, n,
		       status);
		return 1;
	}
	double max = 0;
	for (int j = 0; j < k; j++)
		max = lat_k[j] > max ? lat_k[j] : max;
	double med = quantile(lat_k, k, 0.5), p99 = quantile(lat_k, k, 0.99);
	double wmed = quantile(lat_w, k, 0.5), wp99 = quantile(lat_w, k, 0.99);
	printf("latency n=%d lost=%d drops=%llu gap_us=%d median_us=%.1f p99_us=%.1f max_us=%.1f "
	       "write_median_us=%.1f write_p99_us=%.1f\n", k, n - k,
	       (unsigned long long)d->in.dropped_frames, gap_us, med, p99, max, wmed, wp99);
	print_calib();
	input_devs_close_all(&set, now_us(), NULL);
	vdev_destroy(&v);
	return 0;
}

int
main(int argc, char **argv)
{
	if (argc == 3 && !strcmp(argv[1], "check"))
		return run_checks(argv[2]);
	if (argc == 4 && !strcmp(argv[1], "latency"))
		return run_latency(atoi(argv[2]), atoi(argv[3]));
	if (argc == 2 && !strcmp(argv[1], "calib")) {
		print_calib();
		return 0;
	}
	fprintf(stderr, "usage: guest_evdev check DIR | latency N GAP_US | calib\n");
	return 2;
}
