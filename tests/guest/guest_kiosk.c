/*
 * guest_kiosk.c - the real daemon (postured) at the kiosk, inside the test
 * guest (tests/guest/README.md), driven through real devices and checked
 * through its Unix socket:
 *
 *   guest_kiosk can POSTURED MAP BINDINGS ID REF TURN1 TURN2 PRESS WANT1 WANT2
 *
 *       the dial panel on vcan0 (modules vcan, can_raw). ID is the CAN id of
 *       the panel's frame as candump writes it, REF, TURN1, TURN2 and PRESS
 *       its data in hex: the dial bound to DOF 0 of the picked joint at a
 *       reference value, turned once, turned again, and the same with the
 *       panel button bound to "undo" pressed. WANT1 and WANT2 are the picked
 *       joint's values (radians) after the two turns, worked out by the
 *       caller from the map and the bindings.
 *
 *   guest_kiosk keyboard POSTURED
 *
 *       a uinput keyboard (module uinput) typing at the kiosk's edit line,
 *       unplugged mid-edit with Shift held, then a new one plugged.
 *
 * The daemon runs as a child with its stderr on the console. One line a
 * check: "ok WHAT" or "FAIL WHAT: why"; the exit status is the number of
 * failures.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <linux/can.h>
#include <linux/uinput.h>
#include <math.h>
#include <net/if.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <jansson.h>

#include "tests/guest/guest_check.h"
#include "tests/guest/guest_daemon.h"

#define SOCK "/tmp/kiosk/sock"
#define STATE "/tmp/kiosk/state"
#define START_MS 90000   /* generous: it listens 0.6-1.4 s after its start here (TCG) */
#define SETTLE_MS 5000   /* how long a change may take to show through the socket */
#define STILL_MS 800     /* longer than the dials' 0.5 s of stillness that ends a step */
#define EPS 1e-9

/* DOF 0 of FIG's JOINT, or NAN (last_error says why) */
static double
joint_value(struct conn *c, const char *fig, const char *joint)
{
	json_t *r = request(c, "get joint %s %s", fig, joint);
	double v = r ? json_number_value(json_array_get(json_object_get(r, "values"), 0)) : NAN;
	json_decref(r);
	return v;
}

/* polls DOF 0 of human's elbow_r until it is want (or ms pass): its last value */
static double
wait_elbow(struct conn *c, double want, int ms)
{
	uint64_t end = now_us() + (uint64_t)ms * 1000u;
	double v;
	while (fabs((v = joint_value(c, "human", "elbow_r")) - want) > EPS && now_us() < end &&
	       !isnan(v))
		sleep_ms(20);
	return v;
}

/* polls until FIG is there (its elbow_r answers), up to ms: 1 when it is */
static int
wait_figure(struct conn *c, const char *fig, int ms)
{
	uint64_t end = now_us() + (uint64_t)ms * 1000u;
	while (isnan(joint_value(c, fig, "elbow_r"))) {
		if (now_us() >= end || !daemon_alive())
			return 0;
		sleep_ms(50);
	}
	return 1;
}



/* `get kiosk`'s KEY as text (a string, or JSON for anything else) into out */
static void
kiosk_field(struct conn *c, const char *key, char *out, size_t n)
{
	json_t *r = request(c, "get kiosk");
	json_t *v = json_object_get(r, key);
	if (json_is_string(v)) {
		snprintf(out, n, "%s", json_string_value(v));
	} else {
		char *s = v ? json_dumps(v, JSON_ENCODE_ANY) : NULL;
		snprintf(out, n, "%s", s ? s : "(no reply)");
		free(s);
	}
	json_decref(r);
}

/* polls the kiosk's edit line until it reads want (or ms pass): 1 when it did; the line in out */
static int
wait_line(struct conn *c, const char *want, char *out, size_t n, int ms)
{
	uint64_t end = now_us() + (uint64_t)ms * 1000u;
	for (;;) {
		kiosk_field(c, "line", out, n);
		if (!strcmp(out, want))
			return 1;
		if (now_us() >= end || !daemon_alive())
			return 0;
		sleep_ms(20);
	}
}

/*
 * The device `list devices` shows whose backend is backend and whose name or
 * path is what: its place (the "device" of its input events), or -1; the
 * whole list in out when out is given.
 */
static int
device_listed(struct conn *c, const char *backend, const char *what, char *out, size_t n)
{
	json_t *r = request(c, "list devices");
	int found = -1;
	size_t i;
	json_t *d;
	json_array_foreach(json_object_get(r, "devices"), i, d) {
		const char *be = json_string_value(json_object_get(d, "backend"));
		const char *name = json_string_value(json_object_get(d, "name"));
		const char *path = json_string_value(json_object_get(d, "path"));
		if (be && !strcmp(be, backend) &&
		    ((name && !strcmp(name, what)) || (path && !strcmp(path, what))))
			found = (int)json_integer_value(json_object_get(d, "device"));
	}
	if (out) {
		char *s = r ? json_dumps(r, JSON_COMPACT) : NULL;
		snprintf(out, n, "%s", s ? s : last_error);
		free(s);
	}
	json_decref(r);
	return found;
}

/* polls `list devices` until the device is there (want 1) or gone (want 0): its place or -1 */
static int
wait_device(struct conn *c, const char *backend, const char *what, int want, int ms)
{
	uint64_t end = now_us() + (uint64_t)ms * 1000u;
	int at;
	while (((at = device_listed(c, backend, what, NULL, 0)) >= 0) != want && now_us() < end &&
	       daemon_alive())
		sleep_ms(50);
	return at;
}

/*
 * The environment as the socket shows it: the figures, every posture, the
 * constraints and the undo and redo depths, one text (the replies carry no
 * state hash, so their bytes stand for it). Malloc'ed.
 */
static char *
environment(struct conn *c)
{
	json_t *all = json_object();
	json_object_set_new(all, "figures", request(c, "list figures"));
	json_t *figs = json_object_get(json_object_get(all, "figures"), "figures");
	json_t *postures = json_object();
	size_t i;
	json_t *f;
	json_array_foreach(figs, i, f) {
		const char *name = json_string_value(json_object_get(f, "name"));
		json_object_set_new(postures, name, request(c, "get posture %s", name));
	}
	json_object_set_new(all, "postures", postures);
	json_object_set_new(all, "constraints", request(c, "list constraints"));
	json_object_set_new(all, "undo", json_integer(status_field(c, "undo")));
	json_object_set_new(all, "redo", json_integer(status_field(c, "redo")));
	char *s = json_dumps(all, JSON_COMPACT | JSON_SORT_KEYS);
	json_decref(all);
	return s;
}

/* ---- the dial panel ---- */

/* a CAN_RAW socket bound to ifname: the fd, or -1 */
static int
can_open(const char *ifname)
{
	int s = socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
	if (s < 0)
		return -1;
	struct sockaddr_can a = { .can_family = AF_CAN, .can_ifindex = (int)if_nametoindex(ifname) };
	if (!a.can_ifindex || bind(s, (struct sockaddr *)&a, sizeof a) < 0) {
		close(s);
		return -1;
	}
	return s;
}

/* a frame of id (3 hex digits: standard, 8: extended) and data in hex: 0, or -1 */
static int
can_send(int s, const char *id, const char *hex)
{
	struct can_frame f;
	memset(&f, 0, sizeof f);
	f.can_id = (canid_t)strtoul(id, NULL, 16) | (strlen(id) == 8 ? CAN_EFF_FLAG : 0);
	size_t n = strlen(hex) / 2;
	if (n > CAN_MAX_DLEN)
		return -1;
	for (size_t i = 0; i < n; i++)
		if (sscanf(hex + 2 * i, "%2hhx", &f.data[i]) != 1)
			return -1;
	f.can_dlc = (uint8_t)n;
	if (write(s, &f, sizeof f) != (ssize_t)sizeof f) {
		printf("CAN write: %s\n", strerror(errno));
		return -1;
	}
	return 0;
}

static int
sh(const char *cmd)
{
	int st = system(cmd);
	return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* what the CAN run needs from its command line */
struct panel_plan {
	const char *id;
	const char *ref, *turn1, *turn2, *press; /* frame data in hex */
	double want1, want2;                     /* the elbow after turn1, after turn2 */
};

/* the human loaded and its elbow_r picked (the mode entered, then left by ESC): 0, or -1 */
static int
pick_elbow(struct conn *c)
{
	static const char *const lines[] = {
		"load human as human",
		"add view front width=64 height=48 eye=0,1,3 target=0,1,0",
		"manipulate joint human elbow_r", "input key KEY_ESC down", "input key KEY_ESC up",
	};
	for (size_t i = 0; i < sizeof lines / sizeof *lines; i++)
		if (command(c, lines[i]) < 0)
			return -1;
	return 0;
}

/* the turn of the dial: two moves, one step of the kiosk, one undo */
static void
check_turn(struct conn *c, int can, const struct panel_plan *p)
{
	long depth = status_field(c, "undo");
	can_send(can, p->id, p->ref);
	uint64_t turned = now_us();
	can_send(can, p->id, p->turn1);
	double v = wait_elbow(c, p->want1, SETTLE_MS);
	check(fabs(v - p->want1) <= EPS, "the dial turns the picked joint by the binding's gain",
	      "elbow_r %.17g, want %.17g (%s)", v, p->want1, last_error);
	char step[64];
	kiosk_field(c, "step", step, sizeof step);
	/* the step ends 0.5 s after the turn: a slow guest says so here */
	check(!strcmp(step, "true"), "a turning dial is a step under way",
	      "step %s, asked %.0f ms after the turn", step, (double)(now_us() - turned) / 1e3);
	can_send(can, p->id, p->turn2);
	v = wait_elbow(c, p->want2, SETTLE_MS);
	check(fabs(v - p->want2) <= EPS, "a second turn adds up", "elbow_r %.17g, want %.17g", v,
	      p->want2);
	/* the turn is a step: a client's undo now would take back the step before it */
	json_t *early = request(c, "undo");
	check(!early && strstr(last_error, "\"busy\""),
	      "a client's undo while the dials turn is refused busy", "%s",
	      early ? "it ran" : last_error);
	json_decref(early);
	/* ... and so does a change to the figure it turns, which undoing the turn took back */
	early = request(c, "set joint human knee_l 30deg");
	check(!early && strstr(last_error, "\"busy\""),
	      "a client's change to the turned figure waits too (busy)", "%s",
	      early ? "it ran" : last_error);
	json_decref(early);
	sleep_ms(STILL_MS);
	kiosk_field(c, "step", step, sizeof step);
	long after = status_field(c, "undo");
	check(!strcmp(step, "false") && after == depth + 1,
	      "the dials still for 0.5 s end the step: one undo step",
	      "step %s, undo depth %ld, want %ld", step, after, depth + 1);
	json_t *r = request(c, "undo");
	json_decref(r);
	v = joint_value(c, "human", "elbow_r");
	check(r && fabs(v) <= EPS, "undo returns the joint", "elbow_r %.17g after undo (%s)", v,
	      r ? "" : last_error);
}

/* the foot button, bound to "undo", takes back a `set joint` */
static void
check_button(struct conn *c, int can, const struct panel_plan *p)
{
	command(c, "set joint human elbow_r 20deg");
	double before = joint_value(c, "human", "elbow_r");
	can_send(can, p->id, p->press);
	double v = wait_elbow(c, 0, SETTLE_MS);
	check(fabs(before - 20 * M_PI / 180) <= EPS && fabs(v) <= EPS,
	      "the panel button runs its command (undo)", "elbow_r %.17g before, %.17g after",
	      before, v);
	can_send(can, p->id, p->turn2); /* released */
}

/* vcan0 down and up: the daemon lives on and reads the panel again */
static void
check_down_up(struct conn *c, int can, const struct panel_plan *p)
{
	int down = sh("ip link set vcan0 down");
	sleep_ms(300);
	int alive_down = daemon_alive();
	int up = sh("ip link set vcan0 up");
	sleep_ms(300);
	/* the down left ENETDOWN pending on our own sender too: taken, or the next send fails */
	int pending;
	socklen_t len = sizeof pending;
	getsockopt(can, SOL_SOCKET, SO_ERROR, &pending, &len);
	char list[2048];
	int at = device_listed(c, "can", "vcan0", list, sizeof list);
	check(!down && !up && alive_down && daemon_alive() && at >= 0,
	      "vcan0 down then up: the daemon runs on, the panel still listed",
	      "ip %d %d, alive %d %d, list devices %s", down, up, alive_down, daemon_alive(), list);
	/* the panel was stale while down: the first value sets the dial's reference again */
	can_send(can, p->id, p->ref);
	can_send(can, p->id, p->turn1);
	double v = wait_elbow(c, p->want1, SETTLE_MS);
	check(fabs(v - p->want1) <= EPS, "after up the dial turns the joint again",
	      "elbow_r %.17g, want %.17g", v, p->want1);
}

static int
run_can(char **argv)
{
	struct panel_plan p = { argv[4], argv[5], argv[6], argv[7], argv[8],
				strtod(argv[9], NULL), strtod(argv[10], NULL) };
	check(sh("ip link add dev vcan0 type vcan && ip link set vcan0 up") == 0, "vcan0 made",
	      "ip link failed");
	char spec[512];
	snprintf(spec, sizeof spec, "can:vcan0:%s", argv[2]);
	char *const args[] = { argv[1], "--socket", SOCK, "--state-dir", STATE, "--input", spec,
			       "--bindings", argv[3], "--hotplug", "kernel", NULL };
	struct conn c;
	uint64_t t0 = now_us();
	if (daemon_start(args) < 0 || conn_open(&c, START_MS) < 0) {
		fail("postured started", "no socket after %d ms", START_MS);
		return guest_status();
	}
	printf("postured listening after %.1f s\n", (double)(now_us() - t0) / 1e6);
	char list[2048];
	check(device_listed(&c, "can", "vcan0", list, sizeof list) >= 0,
	      "list devices shows the panel on vcan0 (can backend)", "%s", list);
	int can = can_open("vcan0");
	if (can < 0 || pick_elbow(&c) < 0) {
		fail("set up", "CAN socket %d, or the joint not picked: %s", can, last_error);
		return guest_status();
	}
	check_turn(&c, can, &p);
	check_button(&c, can, &p);
	check_down_up(&c, can, &p);
	conn_close(&c);
	int st = daemon_stop();
	check(st == 0, "postured stops cleanly on SIGTERM", "exit status %d", st);
	return guest_status();
}

/* ---- the keyboard ---- */

/* a uinput keyboard named name (the keys a US keyboard types with): its fd, or -1 */
static int
make_keyboard(const char *name)
{
	int fd = open("/dev/uinput", O_WRONLY | O_CLOEXEC);
	if (fd < 0)
		return -1;
	ioctl(fd, UI_SET_EVBIT, EV_KEY);
	for (int k = KEY_ESC; k <= KEY_KPDOT; k++)
		ioctl(fd, UI_SET_KEYBIT, k);
	for (int k = KEY_UP; k <= KEY_DELETE; k++)
		ioctl(fd, UI_SET_KEYBIT, k);
	struct uinput_setup us = { .id = { .bustype = BUS_USB, .vendor = 0x1234, .product = 0x5700 } };
	snprintf(us.name, sizeof us.name, "%s", name);
	if (ioctl(fd, UI_DEV_SETUP, &us) < 0 || ioctl(fd, UI_DEV_CREATE) < 0) {
		close(fd);
		return -1;
	}
	return fd;
}

/* one key's edge as a frame of its own */
static void
key(int fd, unsigned code, int value)
{
	if (uinput_emit(fd, EV_KEY, code, value) < 0 || uinput_emit(fd, EV_SYN, SYN_REPORT, 0) < 0)
		printf("uinput write: %s\n", strerror(errno));
	sleep_ms(2);
}

static void
tap(int fd, unsigned code)
{
	key(fd, code, 1);
	key(fd, code, 0);
}

/* the key that types c on a US layout (lower case), or 0 */
static unsigned
key_of(char c)
{
	static const unsigned letter[26] = {
		KEY_A, KEY_B, KEY_C, KEY_D, KEY_E, KEY_F, KEY_G, KEY_H, KEY_I, KEY_J, KEY_K, KEY_L,
		KEY_M, KEY_N, KEY_O, KEY_P, KEY_Q, KEY_R, KEY_S, KEY_T, KEY_U, KEY_V, KEY_W, KEY_X,
		KEY_Y, KEY_Z,
	};
	if (c >= 'a' && c <= 'z')
		return letter[c - 'a'];
	if (c == ' ')
		return KEY_SPACE;
	if (c == '\n')
		return KEY_ENTER;
	return 0;
}

/* types text (lower case, spaces, newlines) as a person would, a key at a time */
static void
type(int fd, const char *text)
{
	for (; *text; text++)
		tap(fd, key_of(*text));
}

/* the input events a subscriber saw, up to ms or the device's removal; flags what it saw */
struct seen {
	int shift_released; /* KEY_LEFTSHIFT value 0 from the device */
	int removed;        /* its "removed" event */
};

static void
watch_events(struct conn *ev, int device, int ms, struct seen *s)
{
	uint64_t end = now_us() + (uint64_t)ms * 1000u;
	while (!s->removed && now_us() < end) {
		char *text = conn_line(ev, 100);
		json_t *e = text ? json_loads(text, 0, NULL) : NULL;
		free(text);
		if (!e)
			continue;
		const char *kind = json_string_value(json_object_get(e, "kind"));
		const char *name = json_string_value(json_object_get(e, "name"));
		json_t *dev = json_object_get(e, "device");
		if (kind && json_is_integer(dev) && json_integer_value(dev) == device) {
			if (!strcmp(kind, "key") && name && !strcmp(name, "KEY_LEFTSHIFT") &&
			    json_integer_value(json_object_get(e, "value")) == 0)
				s->shift_released = 1;
			if (!strcmp(kind, "removed"))
				s->removed = 1;
		}
		json_decref(e);
	}
}

/* drops the events a subscriber has waiting */
static void
drain(struct conn *ev)
{
	char *text;
	while ((text = conn_line(ev, 0)) != NULL)
		free(text);
}

#define KB1 "posture kiosk keyboard 1"
#define KB2 "posture kiosk keyboard 2"
#define TYPED "load human as K" /* what is on the line when the keyboard goes */

/* the first keyboard: a command typed and run, then a line left mid-edit with Shift held */
static void
edit_and_unplug(struct conn *c, struct conn *ev, int kb, int at, char **env_before)
{
	char line[256];
	type(kb, "load human as human\n");
	check(wait_figure(c, "human", SETTLE_MS), "a command typed on the keyboard runs (load human)",
	      "%s", last_error);
	*env_before = environment(c);
	type(kb, "load human as ");
	key(kb, KEY_LEFTSHIFT, 1);
	tap(kb, KEY_K); /* Shift stays down: the keyboard goes with it held */
	check(wait_line(c, TYPED, line, sizeof line, SETTLE_MS),
	      "the edit line holds the typed text, Shift on its last letter", "line '%s', want '%s'",
	      line, TYPED);
	drain(ev);
	/*
	 * The kernel releases a vanishing device's held keys itself, but a reader
	 * that comes late gets ENODEV instead of those releases: stopped across the
	 * unplug, the daemon must release Shift on its own (the backend's rule).
	 */
	kill(daemon_pid, SIGSTOP);
	ioctl(kb, UI_DEV_DESTROY);
	close(kb);
	kill(daemon_pid, SIGCONT);
	struct seen s = { 0, 0 };
	watch_events(ev, at, SETTLE_MS, &s);
	check(s.removed, "the daemon saw the keyboard go (a removed event)", "none in %d ms",
	      SETTLE_MS);
	check(s.shift_released, "the held Shift released as an event when it went",
	      "no KEY_LEFTSHIFT up from device %d", at);
}

/* after the unplug: alive, the line gone, nothing else changed */
static void
check_after_unplug(struct conn *c, const char *env_before)
{
	check(daemon_alive(), "the daemon runs on after the unplug", "it ended");
	char line[256];
	check(wait_line(c, "", line, sizeof line, SETTLE_MS), "the typed line is gone",
	      "line '%s'", line);
	char *env_after = environment(c);
	check(env_before && env_after && !strcmp(env_before, env_after),
	      "the environment is unchanged (figures, postures, constraints, undo)",
	      "before %.300s\nafter %.300s", env_before ? env_before : "?",
	      env_after ? env_after : "?");
	free(env_after);
}

/* a new keyboard, hot-plugged: it types lower case (no Shift stuck) and finds the history */
static void
check_new_keyboard(struct conn *c)
{
	int kb = make_keyboard(KB2);
	int at = kb >= 0 ? wait_device(c, "evdev", KB2, 1, 15000) : -1;
	check(at >= 0, "a new keyboard plugged in is opened (hot-plug, kernel uevents)",
	      "uinput %d, not in list devices", kb);
	if (at < 0)
		return;
	char line[256];
	type(kb, "a");
	check(wait_line(c, "a", line, sizeof line, SETTLE_MS), "it types lower case: no Shift stuck",
	      "line '%s', want 'a'", line);
	tap(kb, KEY_ESC);
	tap(kb, KEY_UP);
	check(wait_line(c, "load human as human", line, sizeof line, SETTLE_MS),
	      "the history is kept (Up recalls the command typed before)", "line '%s'", line);
	tap(kb, KEY_ESC);
	type(kb, "load human as kid\n");
	check(wait_figure(c, "kid", SETTLE_MS), "it types a command that runs (load human as kid)",
	      "%s", last_error);
	ioctl(kb, UI_DEV_DESTROY);
	close(kb);
}

static int
run_keyboard(char **argv)
{
	int kb = make_keyboard(KB1);
	if (kb < 0) {
		fail("uinput keyboard made", "%s", strerror(errno));
		return guest_status();
	}
	char *const args[] = { argv[1], "--socket", SOCK, "--state-dir", STATE, "--input", "auto",
			       "--hotplug", "kernel", NULL };
	struct conn c, ev;
	uint64_t t0 = now_us();
	if (daemon_start(args) < 0 || conn_open(&c, START_MS) < 0 || conn_open(&ev, 1000) < 0) {
		fail("postured started", "no socket after %d ms", START_MS);
		return guest_status();
	}
	printf("postured listening after %.1f s\n", (double)(now_us() - t0) / 1e6);
	command(&ev, "subscribe input");
	char list[4096];
	int at = device_listed(&c, "evdev", KB1, list, sizeof list);
	check(at >= 0, "list devices shows the uinput keyboard (evdev backend)", "%s", list);
	char *env_before = NULL;
	if (at >= 0) {
		edit_and_unplug(&c, &ev, kb, at, &env_before);
		check_after_unplug(&c, env_before);
		check_new_keyboard(&c);
	}
	free(env_before);
	conn_close(&ev);
	conn_close(&c);
	int st = daemon_stop();
	check(st == 0, "postured stops cleanly on SIGTERM", "exit status %d", st);
	return guest_status();
}

int
main(int argc, char **argv)
{
	setvbuf(stdout, NULL, _IOLBF, 0);
	signal(SIGPIPE, SIG_IGN);
	int st;
	if (argc == 12 && !strcmp(argv[1], "can"))
		st = run_can(argv + 1);
	else if (argc == 3 && !strcmp(argv[1], "keyboard"))
		st = run_keyboard(argv + 1);

	else {
		fprintf(stderr, "usage: guest_kiosk can POSTURED MAP BINDINGS ID REF TURN1 TURN2 "
				"PRESS WANT1 WANT2\n       guest_kiosk keyboard POSTURED\n");
		return 2;
	}
	printf("%d checks, %d failed\n", guest_checks, guest_failures);
	return st;
}
