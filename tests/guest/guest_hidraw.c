/*
 * guest_hidraw.c - the hidraw backend against the kernel, inside the test
 * guest (tests/guest/test_guest_hidraw.py runs it): uhid makes the mouse
 * and the keyboard of a hid-recorder recording (their descriptors, names
 * and ids), the backend opens them as the daemon does (the device set,
 * spec hidraw:VID:PID: hidapi enumerates and opens), and the kernel's own
 * hid-input decodes the same reports into its evdev nodes. For every
 * report, the recording's and a few more, what the backend makes of it
 * must agree with what the kernel's evdev node gives (buttons, motion,
 * wheel, keys). Then the mouse is destroyed with a button held: the
 * backend must release the button and remove the device; the keyboard
 * must still work; then it goes too.
 *
 *   guest_hidraw TWO.hid MOUSE.hid HIRES.rdesc
 * TWO.hid: a recording of a mouse (device 0) and a keyboard (device 1)
 * with the same ids; MOUSE.hid: more reports of the same mouse;
 * HIRES.rdesc: a mouse whose wheels have Resolution Multipliers, made
 * last: the kernel and the backend write them, the fake answers (in a
 * thread of its own, as the requests block the writer), and the hi-res
 * wheel events must agree. One line
 * a check ("ok ...", "FAIL ...: why"); the exit status is the failures.
 */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <hidapi/hidapi.h>
#include <linux/input.h>
#include <linux/uhid.h>
#include <poll.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

#include "devices/hidraw_dev.h"
#include "devices/input_backends.h"
#include "devices/input_devs.h"
#include "devices/queue.h"
#include "devices/rec_hid.h"
#include "tests/guest/guest_check.h"

/* ---- uhid ----------------------------------------------------------------------------- */

struct fake {
	const char *role;       /* "mouse", "keyboard" */
	int uhid;               /* /dev/uhid, one a device */
	char hidraw[64], event[64];
	int evfd;               /* the kernel's evdev node, read raw */
	int place;              /* its place in the device set, -1 */
	const struct rec_hid_device *rec;
	/* a device with feature reports answers the kernel's requests in its own thread */
	pthread_t answerer;
	int answering;
	atomic_int stop;
	pthread_mutex_t lock;
	uint8_t feature[16];    /* the feature report as the device holds it (id byte first) */
	size_t feature_len;
	uint8_t get_answer[16]; /* what GET_REPORT answers once, then the held report */
	size_t get_answer_len;
	int gets, sets;
	uint8_t last_set[16];
	size_t last_set_len;
};

static int
uhid_create(struct fake *f, const char *phys)
{
	f->uhid = open("/dev/uhid", O_RDWR | O_CLOEXEC);
	if (f->uhid < 0)
		return -1;
	static struct uhid_event ev;
	memset(&ev, 0, sizeof ev);
	ev.type = UHID_CREATE2;
	snprintf((char *)ev.u.create2.name, sizeof ev.u.create2.name, "%.127s", f->rec->name);
	snprintf((char *)ev.u.create2.phys, sizeof ev.u.create2.phys, "%s", phys);
	ev.u.create2.rd_size = f->rec->desc_len;
	ev.u.create2.bus = f->rec->bus;
	ev.u.create2.vendor = f->rec->vid;
	ev.u.create2.product = f->rec->pid;
	memcpy(ev.u.create2.rd_data, f->rec->desc, f->rec->desc_len);
	return write(f->uhid, &ev, sizeof ev) == (ssize_t)sizeof ev ? 0 : -1;
}

static int
uhid_input(struct fake *f, const uint8_t *bytes, size_t n)
{
	static struct uhid_event ev;
	memset(&ev, 0, sizeof ev);
	ev.type = UHID_INPUT2;
	ev.u.input2.size = (uint16_t)n;
	memcpy(ev.u.input2.data, bytes, n);
	return write(f->uhid, &ev, sizeof ev) == (ssize_t)sizeof ev ? 0 : -1;
}

static int
uhid_destroy(struct fake *f)
{
	static struct uhid_event ev;
	memset(&ev, 0, sizeof ev);
	ev.type = UHID_DESTROY;
	return write(f->uhid, &ev, sizeof ev) == (ssize_t)sizeof ev ? 0 : -1;
}

/* what the kernel asks the fake (start, open, LED output reports): read and ignored */
static void
uhid_drain(struct fake *f)
{
	static struct uhid_event ev;
	if (f->answering)
		return; /* its thread reads */
	struct pollfd p = { .fd = f->uhid, .events = POLLIN };
	while (poll(&p, 1, 0) == 1 && (p.revents & POLLIN))
		if (read(f->uhid, &ev, sizeof ev) <= 0)
			break;
}

/* the fake's side of GET_REPORT and SET_REPORT (feature reports), until told to stop */
static void *
uhid_answer(void *arg)
{
	struct fake *f = arg;
	static struct uhid_event ev, reply;
	while (!atomic_load(&f->stop)) {
		struct pollfd p = { .fd = f->uhid, .events = POLLIN };
		if (poll(&p, 1, 50) != 1 || read(f->uhid, &ev, sizeof ev) <= 0)
			continue;
		memset(&reply, 0, sizeof reply);
		pthread_mutex_lock(&f->lock);
		if (ev.type == UHID_GET_REPORT) {
			reply.type = UHID_GET_REPORT_REPLY;
			reply.u.get_report_reply.id = ev.u.get_report.id;
			const uint8_t *src = f->get_answer_len ? f->get_answer : f->feature;
			size_t n = f->get_answer_len ? f->get_answer_len : f->feature_len;
			reply.u.get_report_reply.size = (uint16_t)n;
			memcpy(reply.u.get_report_reply.data, src, n);
			f->get_answer_len = 0;
			f->gets++;
		} else if (ev.type == UHID_SET_REPORT) {
			reply.type = UHID_SET_REPORT_REPLY;
			reply.u.set_report_reply.id = ev.u.set_report.id;
			size_t n = ev.u.set_report.size < sizeof f->feature ? ev.u.set_report.size
									 : sizeof f->feature;
			memcpy(f->feature, ev.u.set_report.data, n);
			f->feature_len = n;
			memcpy(f->last_set, ev.u.set_report.data, n);
			f->last_set_len = n;
			f->sets++;
		}
		pthread_mutex_unlock(&f->lock);
		if (reply.type && write(f->uhid, &reply, sizeof reply) != (ssize_t)sizeof reply)
			break;
	}
	return NULL;
}

/* /dev/hidrawN and hid-input's /dev/input/eventM of the HID device with this phys */
static int
find_nodes(struct fake *f, const char *phys)
{
	DIR *d = opendir("/sys/class/hidraw");
	if (!d)
		return -1;
	struct dirent *e;
	int found = -1;
	while (found < 0 && (e = readdir(d))) {
		if (e->d_name[0] == '.')
			continue;
		char path[512], line[300];
		snprintf(path, sizeof path, "/sys/class/hidraw/%.64s/device/uevent", e->d_name);
		FILE *u = fopen(path, "r");
		if (!u)
			continue;
		while (fgets(line, sizeof line, u))
			if (!strncmp(line, "HID_PHYS=", 9) && !strncmp(line + 9, phys, strlen(phys)) &&
			    line[9 + strlen(phys)] == '\n')
				found = 0;
		fclose(u);
		if (found)
			continue;
		snprintf(f->hidraw, sizeof f->hidraw, "/dev/%.32s", e->d_name);
		snprintf(path, sizeof path, "/sys/class/hidraw/%.64s/device/input", e->d_name);
		DIR *in = opendir(path);
		f->event[0] = '\0';
		struct dirent *i;
		while (in && (i = readdir(in)))
			if (!strncmp(i->d_name, "input", 5)) {
				char sub[800];
				snprintf(sub, sizeof sub, "%s/%.64s", path, i->d_name);
				if (!event_node(sub, f->event, sizeof f->event))
					break;
			}
		if (in)
			closedir(in);
		if (!f->event[0] || access(f->event, R_OK))
			found = -1; /* not yet */
	}
	closedir(d);
	return found;
}

/* ---- the two sides' events, as (type, code, value) ------------------------------------ */

struct ev3 {
	int type, code, value;
};

#define EV_MAX_FRAME 64

static int
ev3_cmp(const void *a, const void *b)
{
	const struct ev3 *x = a, *y = b;
	if (x->type != y->type)
		return x->type - y->type;
	if (x->code != y->code)
		return x->code - y->code;
	return x->value - y->value;
}

static void
ev3_put(struct ev3 *dest, int *n, int type, int code, int value)
{
	if (*n < EV_MAX_FRAME)
		dest[(*n)++] = (struct ev3){ type, code, value };
}

/* one of our events as the evdev events hid-input sends for it */
static void
ours_to_evdev(const struct input_event_rec *e, struct ev3 *dest, int *n)
{
	switch ((enum input_kind)e->kind) {
	case INPUT_MOTION:
		if (e->x)
			ev3_put(dest, n, EV_REL, REL_X, (int)e->x);
		if (e->y)
			ev3_put(dest, n, EV_REL, REL_Y, (int)e->y);
		break;
	case INPUT_WHEEL: {
		int h = e->code == INPUT_WHEEL_H;
		if (e->value)
			ev3_put(dest, n, EV_REL, h ? REL_HWHEEL : REL_WHEEL, e->value);
		if (e->x)
			ev3_put(dest, n, EV_REL, h ? REL_HWHEEL_HI_RES : REL_WHEEL_HI_RES, (int)e->x);
		break;
	}
	case INPUT_BUTTON:
	case INPUT_KEY:
		ev3_put(dest, n, EV_KEY, e->code, e->value);
		break;
	case INPUT_POINTER:
	case INPUT_VALUATOR:
	case INPUT_ADDED:
	case INPUT_REMOVED:
	case INPUT_FRAME:
		break;
	}
}

static void
ev3_print(const char *who, const struct ev3 *e, int n)
{
	printf("   %s:", who);
	for (int i = 0; i < n; i++)
		printf(" %d/%d/%d", e[i].type, e[i].code, e[i].value);
	printf("\n");
}

static struct input_devs set;
static struct input_queue q;

/* our events of device place up to its next frame end (or kind `until`): 0, or -1 timed out */
static int
ours_frame(int place, struct ev3 *dest, int *n, enum input_kind until, int *removed)
{
	static struct input_event_rec pending[INPUT_QUEUE_CAP];
	static unsigned npending;
	uint64_t t0 = now_us();
	*n = 0;
	for (;;) {
		struct input_event_rec e;
		while (input_queue_pop(&q, &e))
			if (npending < INPUT_QUEUE_CAP)
				pending[npending++] = e;
		for (unsigned i = 0; i < npending; i++) {
			if (pending[i].device != place)
				continue;
			enum input_kind k = (enum input_kind)pending[i].kind;
			if (k == INPUT_REMOVED && removed)
				*removed = 1;
			ours_to_evdev(&pending[i], dest, n);
			memmove(&pending[i], &pending[i + 1], (npending - i - 1) * sizeof pending[0]);
			npending--;
			i--;
			if (k == until)
				return 0;
		}
		if (now_us() - t0 > 3000000)
			return -1;
		poll_devs(&set, &q, 50);
	}
}

/* the kernel's next non-empty frame on fd (no MSC, no EV_REP, no repeats): 0, or -1 timed out */
static int
kernel_frame(int fd, struct ev3 *dest, int *n)
{
	uint64_t t0 = now_us();
	*n = 0;
	while (now_us() - t0 < 3000000) {
		struct input_event e;
		int got = read_event(fd, &e, 50);
		if (got == 0)
			continue;
		if (got < 0)
			return -1;
		if (e.type == EV_SYN && e.code == SYN_REPORT) {
			if (*n)
				return 0;
			continue; /* a frame that held only what we leave out */
		}
		if (e.type == EV_MSC || e.type == EV_SYN || e.type == EV_REP ||
		    (e.type == EV_KEY && e.value == 2))
			continue;
		ev3_put(dest, n, e.type, e.code, e.value);
	}
	return -1;
}

/* one report into the fake, and the two sides' frames compared */
static int
agree(struct fake *f, const uint8_t *bytes, size_t len, const char *label)
{
	struct ev3 ours[EV_MAX_FRAME], kern[EV_MAX_FRAME];
	int no = 0, nk = 0;
	char what[128];
	snprintf(what, sizeof what, "%s %s report", f->role, label);
	if (uhid_input(f, bytes, len) < 0) {
		fail(what, "UHID_INPUT2: %s", strerror(errno));
		return -1;
	}
	if (ours_frame(f->place, ours, &no, INPUT_FRAME, NULL) < 0) {
		fail(what, "the backend gave no frame");
		return -1;
	}
	/* a report that changes nothing: the kernel sends no frame, we an empty one */
	if (no && kernel_frame(f->evfd, kern, &nk) < 0) {
		fail(what, "hid-input's evdev node gave no frame");
		return -1;
	}
	uhid_drain(f);
	qsort(ours, (size_t)no, sizeof ours[0], ev3_cmp);
	qsort(kern, (size_t)nk, sizeof kern[0], ev3_cmp);
	if (no != nk || memcmp(ours, kern, (size_t)no * sizeof ours[0])) {
		fail(what, "the backend and hid-input disagree");
		ev3_print("ours  ", ours, no);
		ev3_print("kernel", kern, nk);
		return -1;
	}
	printf("   %s:", what);
	for (size_t i = 0; i < len; i++)
		printf(" %02x", bytes[i]);
	ev3_print(" ->", ours, no);
	ok("%s: %d event(s) agree", what, no);
	return 0;
}

static int
place_of(const char *hidraw)
{
	for (int i = 0; i < INPUT_DEVS_MAX; i++)
		if (set.place[i].be && !strcmp(set.place[i].info.path, hidraw))
			return i;
	return -1;
}

/* ---- a hi-res wheel: the Resolution Multipliers written ---------------------------------- */

static size_t
read_rdesc(const char *path, uint8_t *dest, size_t max)
{
	FILE *f = fopen(path, "r");
	if (!f)
		return 0;
	char line[512];
	size_t n = 0;
	while (fgets(line, sizeof line, f)) {
		char *hash = strchr(line, '#');
		if (hash)
			*hash = '\0';
		for (char *p = strtok(line, " \t\r\n"); p && n < max; p = strtok(NULL, " \t\r\n"))
			dest[n++] = (uint8_t)strtoul(p, NULL, 16);
	}
	fclose(f);
	return n;
}

/*
 * A mouse whose wheel and AC Pan have Resolution Multipliers (8 and 4) in
 * feature report 0. The kernel's hid-input writes them when it binds; then
 * the fake forgets them (as a device that was reset would) and answers the
 * backend's GET with other bits set: the backend must write the
 * multipliers again, keeping those bits, and its wheel events must agree
 * with hid-input's REL_WHEEL_HI_RES and REL_HWHEEL_HI_RES.
 */
static void
hires_phase(const char *rdesc_path)
{
	static struct rec_hid_device rd = { .name = "Posture Hi-Res Wheel Mouse", .bus = 3,
					    .vid = 0xf055, .pid = 0x0048 };
	rd.desc_len = (uint16_t)read_rdesc(rdesc_path, rd.desc, sizeof rd.desc);
	if (!rd.desc_len) {
		fail("hires", "cannot read %s", rdesc_path);
		return;
	}
	static struct fake f = { .role = "hi-res mouse", .rec = &rd, .place = -1, .evfd = -1 };
	pthread_mutex_init(&f.lock, NULL);
	f.feature_len = 3; /* id 0, then the two multipliers' bytes */
	const char *phys = "posture-guest/hires";
	if (uhid_create(&f, phys) < 0) {
		fail("hires", "UHID_CREATE2: %s", strerror(errno));
		return;
	}
	atomic_init(&f.stop, 0);
	f.answering = pthread_create(&f.answerer, NULL, uhid_answer, &f) == 0;
	int tries = 0;
	while (find_nodes(&f, phys) < 0 && tries++ < 100)
		sleep_ms(50);
	if (!f.event[0]) {
		fail("hires", "no hidraw and evdev nodes");
		goto out;
	}
	f.evfd = open(f.event, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
	pthread_mutex_lock(&f.lock);
	int kernel_sets = f.sets;
	printf("   hid-input bound it: %d SET_REPORT(s), the last %02x %02x %02x\n", f.sets,
	       f.last_set[0], f.last_set[1], f.last_set[2]);
	/* forgotten; the next GET answers with bits the backend must keep */
	memset(f.feature, 0, sizeof f.feature);
	static const uint8_t other_bits[3] = { 0x00, 0xfc, 0x00 };
	memcpy(f.get_answer, other_bits, sizeof other_bits);
	f.get_answer_len = sizeof other_bits;
	f.sets = f.gets = 0;
	pthread_mutex_unlock(&f.lock);

	char err[256];
	if (input_devs_open(&set, "hidraw:f055:0048", now_us(), err, sizeof err) != 1 ||
	    (f.place = place_of(f.hidraw)) < 0) {
		fail("hires", "hidraw:f055:0048 was not opened");
		goto out;
	}
	struct input_event_rec e;
	while (input_queue_pop(&q, &e))
		;
	pthread_mutex_lock(&f.lock);
	int gets = f.gets, sets = f.sets;
	uint8_t set_bytes[3];
	memcpy(set_bytes, f.last_set, 3);
	size_t set_len = f.last_set_len;
	pthread_mutex_unlock(&f.lock);
	if (kernel_sets >= 1 && gets == 1 && sets == 1 && set_len == 3 && set_bytes[0] == 0x00 &&
	    set_bytes[1] == 0xfd && set_bytes[2] == 0x01)
		ok("hi-res: the backend read feature report 0 and wrote it back with both "
		   "multipliers at their logical maximum, the other bits kept (00 fd 01)");
	else
		fail("hires", "kernel SETs %d; ours: %d GET(s), %d SET(s) of %zu bytes %02x %02x %02x "
		     "(want 1, 1, 3: 00 fd 01)",
		     kernel_sets, gets, sets, set_len, set_bytes[0], set_bytes[1], set_bytes[2]);

	/* buttons, X and Y (16 bits each), the wheel, AC Pan */
	static const uint8_t wheel[][7] = {
		{ 0, 0, 0, 0, 0, 1, 0 },    /* 1/8 detent: 15 in 1/120 */
		{ 0, 0, 0, 0, 0, 1, 0 },
		{ 0, 0, 0, 0, 0, 1, 0 },
		{ 0, 0, 0, 0, 0, 5, 0 },    /* 75 more: a whole detent reached */
		{ 0, 0, 0, 0, 0, 0, 0xff }, /* pan -1/4 detent: -30 */
		{ 1, 3, 0, 0xfe, 0xff, 0, 0 }, /* BTN_LEFT, X 3, Y -2 */
		{ 0, 0, 0, 0, 0, 0, 0 },
	};
	for (size_t k = 0; k < sizeof wheel / sizeof wheel[0]; k++)
		agree(&f, wheel[k], sizeof wheel[k], "hi-res");

out:
	if (f.place >= 0)
		uhid_destroy(&f);
	int removed = 0, n = 0;
	struct ev3 gone[EV_MAX_FRAME];
	if (f.place >= 0 && ours_frame(f.place, gone, &n, INPUT_REMOVED, &removed) == 0 && removed)
		ok("hi-res mouse gone: removed");
	else if (f.place >= 0)
		fail("hires", "not removed after UHID_DESTROY");
	atomic_store(&f.stop, 1);
	if (f.answering)
		pthread_join(f.answerer, NULL);
	if (f.evfd >= 0)
		close(f.evfd);
	close(f.uhid);
	pthread_mutex_destroy(&f.lock);
}

int
main(int argc, char **argv)
{
	if (argc != 4) {
		fprintf(stderr, "usage: guest_hidraw TWO.hid MOUSE.hid HIRES.rdesc\n");
		return 100;
	}
	static struct rec_hid two, more;
	char err[512];
	if (rec_hid_read(argv[1], &two, err, sizeof err) < 0 ||
	    rec_hid_read(argv[2], &more, err, sizeof err) < 0) {
		fprintf(stderr, "guest_hidraw: %s\n", err);
		return 100;
	}
	if (two.ndevices != 2 || two.devices[0].vid != two.devices[1].vid ||
	    two.devices[0].pid != two.devices[1].pid) {
		fprintf(stderr, "guest_hidraw: %s: want a mouse and a keyboard with one id\n",
			argv[1]);
		return 100;
	}

	/* the recording's two devices, made by uhid */
	struct fake fk[2] = {
		{ .role = "mouse", .rec = &two.devices[0], .place = -1, .evfd = -1 },
		{ .role = "keyboard", .rec = &two.devices[1], .place = -1, .evfd = -1 },
	};
	const char *phys[2] = { "posture-guest/mouse", "posture-guest/keyboard" };
	for (int i = 0; i < 2; i++) {
		if (uhid_create(&fk[i], phys[i]) < 0) {
			fail("uhid", "UHID_CREATE2 %s: %s", fk[i].role, strerror(errno));
			return 100;
		}
	}
	for (int i = 0; i < 2; i++) {
		int tries = 0;
		while (find_nodes(&fk[i], phys[i]) < 0 && tries++ < 100) {
			uhid_drain(&fk[i]);
			sleep_ms(50);
		}
		if (!fk[i].event[0]) {
			fail("uhid", "no hidraw and evdev nodes for the %s", fk[i].role);
			return 100;
		}
		fk[i].evfd = open(fk[i].event, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
		/* no autorepeat while the keys are held between reports */
		int rep[2] = { 60000, 1000 };
		if (fk[i].evfd >= 0)
			ioctl(fk[i].evfd, EVIOCSREP, rep);
		ok("uhid %s '%s' %04x:%04x -> %s, hid-input -> %s", fk[i].role, fk[i].rec->name,
		   fk[i].rec->vid, fk[i].rec->pid, fk[i].hidraw, fk[i].event);
	}

	/* hidapi 0.13.1 lists every collection; the backend keeps one node a path */
	struct hid_device_info *all = hid_enumerate(two.devices[0].vid, two.devices[0].pid);
	int entries = 0;
	for (struct hid_device_info *e = all; e; e = e->next) {
		printf("   hid_enumerate: %s usage %02x/%02x iface %d\n", e->path, e->usage_page,
		       e->usage, e->interface_number);
		entries++;
	}
	hid_free_enumeration(all);
	struct hidraw_dev_found found[HIDRAW_DEV_FOUND_MAX];
	int nfound = hidraw_dev_enumerate(two.devices[0].vid, two.devices[0].pid, -1, found,
					  HIDRAW_DEV_FOUND_MAX, err, sizeof err);
	if (nfound == 2 && entries > 2)
		ok("enumeration: %d hidapi entries, 2 nodes (mouse and keyboard) after de-duplication",
		   entries);
	else
		fail("enumeration", "%d hidapi entries, %d nodes (want 2 nodes from more entries)",
		     entries, nfound);

	/* the daemon's way: the device set, the hidraw spec */
	char spec[64];
	snprintf(spec, sizeof spec, "hidraw:%04x:%04x", two.devices[0].vid, two.devices[0].pid);
	input_queue_init(&q);
	input_devs_init(&set, input_backends, input_backends_count, 0, &q);
	int opened = input_devs_open(&set, spec, now_us(), err, sizeof err);
	for (int k = 0; k < set.nskip; k++)
		printf("   skipped %s: %s\n", set.skip[k].what, set.skip[k].why);
	for (int i = 0; i < 2; i++) {
		fk[i].place = place_of(fk[i].hidraw);
		enum input_class want = i ? INPUT_CLASS_KEYBOARD : INPUT_CLASS_MOUSE;
		if (fk[i].place < 0)
			fail("open", "%s: the %s was not opened", spec, fk[i].role);
		else if (set.place[fk[i].place].info.cls != want)
			fail("open", "the %s was opened as class %d", fk[i].role,
			     set.place[fk[i].place].info.cls);
		else
			ok("%s opened the %s (%s) as place %d, '%s'", spec, fk[i].role, fk[i].hidraw,
			   fk[i].place, set.place[fk[i].place].info.name);
	}
	if (opened != 2 || fk[0].place < 0 || fk[1].place < 0) {
		fail("open", "%s opened %d device(s)", spec, opened);
		goto out;
	}

	/* the recordings' reports, in their order, then more of our own */
	for (size_t k = 0; k < two.nevents; k++)
		agree(&fk[two.events[k].device], two.events[k].bytes, two.events[k].len,
		      "recorded");
	for (size_t k = 0; k < more.nevents; k++)
		agree(&fk[0], more.events[k].bytes, more.events[k].len, "recorded");
	static const uint8_t mouse_more[][4] = {
		{ 0x00, 0xfd, 0x05, 0xff }, /* X -3, Y 5, the wheel a detent down */
		{ 0x06, 0x00, 0x00, 0x00 }, /* right and middle down */
		{ 0x02, 0x7f, 0x81, 0x00 }, /* middle up, right held, the extremes of X and Y */
		{ 0x00, 0x00, 0x00, 0x00 }, /* everything up */
	};
	static const uint8_t keys_more[][8] = {
		{ 0x02, 0, 0x04, 0x05, 0, 0, 0, 0 },    /* LeftShift, A, B */
		{ 0x00, 0, 0x05, 0x00, 0, 0, 0, 0 },    /* shift and A up, B held */
		{ 0x40, 0, 0x05, 0x28, 0x2c, 0, 0, 0 }, /* RightAlt, Enter, Space besides B */
		{ 0x00, 0, 0x01, 0x01, 0x01, 0x01, 0x01, 0x01 }, /* ErrorRollOver: nothing changes */
		{ 0x00, 0, 0, 0, 0, 0, 0, 0 },          /* all up */
	};
	for (size_t k = 0; k < sizeof mouse_more / sizeof mouse_more[0]; k++)
		agree(&fk[0], mouse_more[k], sizeof mouse_more[k], "extra");
	for (size_t k = 0; k < sizeof keys_more / sizeof keys_more[0]; k++)
		agree(&fk[1], keys_more[k], sizeof keys_more[k], "extra");

	/* the readers stop cleanly and the spec opens the nodes again */
	uint64_t t0 = now_us();
	input_devs_close_all(&set, now_us(), &q);
	uint64_t closed_us = now_us() - t0;
	struct input_event_rec e;
	int released = 0;
	while (input_queue_pop(&q, &e))
		released += e.kind == INPUT_BUTTON || e.kind == INPUT_KEY;
	if (input_devs_count(&set) || released)
		fail("close", "%d still open, %d released (nothing was held)",
		     input_devs_count(&set), released);
	else
		ok("both readers stopped and joined in %llu ms (reads time out every %d ms)",
		   (unsigned long long)(closed_us / 1000), HIDRAW_DEV_POLL_MS);
	input_devs_rescan(&set, now_us());
	fk[0].place = place_of(fk[0].hidraw);
	fk[1].place = place_of(fk[1].hidraw);
	while (input_queue_pop(&q, &e))
		;
	if (fk[0].place < 0 || fk[1].place < 0) {
		fail("reopen", "the rescan did not open both again");
		goto out;
	}
	ok("the rescan opened both again");

	/* the mouse goes away with its left button held */
	static const uint8_t left[4] = { 0x01, 0x00, 0x00, 0x00 };
	agree(&fk[0], left, sizeof left, "held");
	if (uhid_destroy(&fk[0]) < 0)
		fail("destroy", "UHID_DESTROY: %s", strerror(errno));
	struct ev3 gone[EV_MAX_FRAME];
	int ngone = 0, removed = 0;
	int rc = ours_frame(fk[0].place, gone, &ngone, INPUT_REMOVED, &removed);
	if (rc < 0 || !removed)
		fail("mouse gone", "no INPUT_REMOVED within 3 s");
	else if (ngone != 1 || gone[0].type != EV_KEY || gone[0].code != BTN_LEFT ||
		 gone[0].value != 0)
		fail("mouse gone", "want BTN_LEFT released, then removed");
	else
		ok("mouse gone mid-press: BTN_LEFT released, the device removed");
	if (input_devs_count(&set) == 1 && !set.place[fk[0].place].be)
		ok("its place is free; the keyboard is still open");
	else
		fail("mouse gone", "%d device(s) open", input_devs_count(&set));
	struct input_event raw;
	errno = 0;
	ssize_t r = read(fk[0].evfd, &raw, sizeof raw);
	printf("   hid-input's evdev node after the destroy: read %zd (%s)\n", r, strerror(errno));

	/* the keyboard still works, then goes (nothing held) */
	static const uint8_t a_down[8] = { 0, 0, 0x04, 0, 0, 0, 0, 0 };
	static const uint8_t a_up[8] = { 0 };
	agree(&fk[1], a_down, sizeof a_down, "after");
	agree(&fk[1], a_up, sizeof a_up, "after");
	uhid_destroy(&fk[1]);
	ngone = removed = 0;
	rc = ours_frame(fk[1].place, gone, &ngone, INPUT_REMOVED, &removed);
	if (rc < 0 || !removed || ngone)
		fail("keyboard gone", "want removed and nothing released (got %d event(s))", ngone);
	else
		ok("keyboard gone: removed, nothing to release");
	if (input_devs_count(&set) != 0)
		fail("keyboard gone", "%d device(s) still open", input_devs_count(&set));

	hires_phase(argv[3]);

out:
	input_devs_close_all(&set, now_us(), NULL);
	for (int i = 0; i < 2; i++) {
		if (fk[i].evfd >= 0)
			close(fk[i].evfd);
		if (fk[i].uhid >= 0)
			close(fk[i].uhid);
	}
	rec_hid_free(&two);
	rec_hid_free(&more);
	printf("guest_hidraw: %d checks, %d failures\n", guest_checks, guest_failures);
	return guest_status();
}
