/*
 * guest_can.c - the SocketCAN backend (devices/can_dev.h) on a real kernel:
 * run inside the test guest (tests/guest/guest.py) as root with the modules
 * vcan and can_raw, and canplayer (and posture-input, for the recording
 * step) copied in.
 *
 *   guest_can MAP LOG1 N1 LOG2 N2 [POSTURE_INPUT]
 *
 * vcan0 missing: the spec is skipped with its reason; created: a rescan
 * opens it. canplayer plays LOG1 (N1 frames) onto vcan0, vcan0 goes down
 * and up, canplayer plays LOG2 (N2 frames) while posture-input records
 * vcan0 into a candump log; frames of ids outside the map are sent and
 * must never arrive (the kernel's filters); a bus-off error frame; a frame
 * of id 185 and then silence (its dial goes stale by the backend's timer
 * alone); vcan0 deleted (the device removed) and created again, down (a
 * rescan opens it again, and it reads once vcan0 is up).
 *
 * Every event the device set gives is printed, one a line:
 *   ev KIND CODE VALUE X FLAGS
 * between "mark WHAT" lines, for tests/guest/test_guest_can.py to compare
 * with cantools' decoding of the same logs; checks print "ok WHAT" or
 * "FAIL WHAT: why"; the recording is printed between "rec-begin" and
 * "rec-end". Exit status: the number of failures.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <net/if.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "devices/can_dev.h"
#include "devices/input_backends.h"
#include "devices/input_devs.h"
#include "tests/guest/guest_check.h"

static struct input_devs set;
static struct input_queue queue;

static void
mark(const char *what)
{
	printf("mark %s\n", what);
	fflush(stdout);
}

static int
sh(const char *cmd)
{
	int st = system(cmd);
	return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* the open CAN device (the backend's allocation starts with its struct can_dev), or NULL */
static struct can_dev *
can_device(void)
{
	for (int i = 0; i < INPUT_DEVS_MAX; i++)
		if (set.place[i].be == &input_backend_can)
			return set.place[i].dev;
	return NULL;
}

static void
print_events(void)
{
	struct input_event_rec e;
	while (input_queue_pop(&queue, &e))
		printf("ev %s %u %d %.17g %u\n", input_kind_to_str((enum input_kind)e.kind), e.code,
		       e.value, e.x, e.flags);
	fflush(stdout);
}

/*
 * The daemon's loop in small: poll the set's fds, read what is ready,
 * print the events. Until *counter reaches target (counter NULL: until ms
 * have passed) or ms pass. Returns 0 when the target was reached.
 */
static int
pump(int ms, const uint64_t *counter, uint64_t target)
{
	uint64_t end = now_us() + (uint64_t)ms * 1000;
	for (;;) {
		if (counter && *counter >= target)
			return 0;
		uint64_t t = now_us();
		if (t >= end)
			return counter ? -1 : 0;
		struct pollfd fds[INPUT_DEVS_POLL_MAX];
		int tags[INPUT_DEVS_POLL_MAX];
		int n = input_devs_pollfds(&set, fds, tags, INPUT_DEVS_POLL_MAX);
		int wait = (int)((end - t) / 1000) + 1;
		if (poll(fds, (nfds_t)n, wait > 100 ? 100 : wait) < 0 && errno != EINTR)
			return -1;
		for (int k = 0; k < n; k++)
			if (fds[k].revents) {
				int gone = input_devs_ready(&set, tags[k], now_us(), &queue) < 0;
				print_events();
				if (gone)
					return counter ? -1 : 0; /* the device is freed: stop looking */
			}
		print_events();
	}
}

static pid_t
spawn(char *const argv[])
{
	pid_t pid = fork();
	if (pid == 0) {
		execvp(argv[0], argv);
		_exit(127);
	}
	return pid;
}

/* waits up to ms for pid; kills it after that. Returns its exit status, or -1 */
static int
reap(pid_t pid, int ms)
{
	for (int waited = 0; waited < ms; waited += 20) {
		int st;
		if (waitpid(pid, &st, WNOHANG) == pid)
			return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
		sleep_ms(20);
	}
	kill(pid, SIGKILL);
	waitpid(pid, NULL, 0);
	return -1;
}

/* canplayer: LOG's frames (logged on can0) onto vcan0, read as they come */
static void
play(const char *log, const char *what, struct can_dev *d, uint64_t frames_after)
{
	char *argv[] = { "canplayer", "-I", (char *)log, "vcan0=can0", NULL };
	pid_t pid = spawn(argv);
	if (pump(60000, &d->frames, frames_after) < 0)
		fail(what, "%llu frames read, want %llu (kernel dropped %llu)",
		     (unsigned long long)d->frames, (unsigned long long)frames_after,
		     (unsigned long long)d->kernel_dropped);
	else
		ok("%s", what);
	if (reap(pid, 30000) != 0)
		fail(what, "canplayer failed");
}

/*
 * Waits until a socket receiving every frame (no filter: posture-input
 * record's) is bound to vcan0, as the kernel's receive list shows it, so
 * that nothing is played before the recorder listens. 0, or -1 after 30 s.
 */
static int
wait_for_listener(void)
{
	for (int waited = 0; waited < 30000; waited += 50) {
		FILE *f = fopen("/proc/net/can/rcvlist_all", "r");
		char line[256];
		int found = 0;
		while (f && fgets(line, sizeof line, f))
			found |= strstr(line, "vcan0") && !strstr(line, "no entry");
		if (f)
			fclose(f);
		if (found) {
			printf("recorder listening after %d ms\n", waited);
			return 0;
		}
		pump(50, NULL, 0);
	}
	return -1;
}

static int
raw_socket(void)
{
	int s = socket(PF_CAN, SOCK_RAW, CAN_RAW);
	struct sockaddr_can a;
	memset(&a, 0, sizeof a);
	a.can_family = AF_CAN;
	a.can_ifindex = (int)if_nametoindex("vcan0");
	if (s < 0 || bind(s, (struct sockaddr *)&a, sizeof a) < 0)
		return -1;
	return s;
}

static int
send_frame(int s, uint32_t id, const char *data, uint8_t len)
{
	struct can_frame f;
	memset(&f, 0, sizeof f);
	f.can_id = id;
	f.len = len;
	if (data)
		memcpy(f.data, data, len);
	return write(s, &f, sizeof f) == (ssize_t)sizeof f ? 0 : -1;
}

int
main(int argc, char **argv)
{
	if (argc < 6) {
		fprintf(stderr, "usage: guest_can MAP LOG1 N1 LOG2 N2 [POSTURE_INPUT]\n");
		return 100;
	}
	const char *map = argv[1], *log1 = argv[2], *log2 = argv[4];
	uint64_t n1 = strtoull(argv[3], NULL, 10), n2 = strtoull(argv[5], NULL, 10);
	const char *recorder = argc > 6 ? argv[6] : NULL;
	char spec[300], err[512], why[600];
	snprintf(spec, sizeof spec, "can:vcan0:%s", map);
	input_queue_init(&queue);
	input_devs_init(&set, input_backends, input_backends_count, 0, &queue);

	/* no vcan0 yet: skipped, with the reason */
	if (input_devs_open(&set, spec, now_us(), err, sizeof err) != 0 || set.nskip != 1 ||
	    strcmp(set.skip[0].why, "no such CAN interface"))
		fail("missing interface skipped", "nskip %d: %s", set.nskip,
		     set.nskip ? set.skip[0].why : err);
	else
		ok("missing interface skipped: no such CAN interface");

	/* vcan0 appears: a rescan opens it */
	if (sh("ip link add dev vcan0 type vcan") || sh("ip link set vcan0 up")) {
		fail("vcan0", "ip link failed");
		return 100;
	}
	if (input_devs_rescan(&set, now_us()) != 1 || !can_device()) {
		fail("rescan opens vcan0", "nothing opened (%s)", set.nskip ? set.skip[0].why : "");
		return 100;
	}
	struct can_dev *d = can_device();
	int place = input_devs_find(&set, &input_backend_can, "vcan0");
	if (place < 0 || set.place[place].info.cls != INPUT_CLASS_PANEL || set.nskip != 0)
		fail("rescan opens vcan0", "not a panel at vcan0, or still skipped");
	else
		ok("rescan opens vcan0 as a panel");
	print_events(); /* INPUT_ADDED */

	/* the first half of the log */
	mark("start");
	play(log1, "canplayer first half read", d, n1);

	/* down and up: the same device reads on */
	mark("down");
	if (sh("ip link set vcan0 down"))
		fail("vcan0 down", "ip link failed");
	if (pump(5000, &d->downs, 1) < 0)
		fail("vcan0 down", "no ENETDOWN seen");
	else
		ok("vcan0 down seen");
	if (sh("ip link set vcan0 up"))
		fail("vcan0 up", "ip link failed");
	mark("up");
	if (can_device() != d)
		fail("down and up", "the device was removed");

	/* the second half, recorded by posture-input at the same time */
	pid_t rec = -1;
	if (recorder) {
		char count[32];
		snprintf(count, sizeof count, "%llu", (unsigned long long)n2);
		char *rargv[] = { (char *)recorder, "record", "can:vcan0", "-o", "/tmp/rec.log",
				  "--count", count, "--seconds", "60", NULL };
		rec = spawn(rargv);
		if (wait_for_listener() < 0)
			fail("record", "posture-input did not bind to vcan0 in 30 s");
	}
	play(log2, "canplayer second half read after up", d, n1 + n2);
	if (rec > 0) {
		int st = reap(rec, 20000);
		if (st != 0)
			fail("record", "posture-input record exited %d", st);
		FILE *f = fopen("/tmp/rec.log", "r");
		char line[256];
		printf("rec-begin\n");
		while (f && fgets(line, sizeof line, f))
			fputs(line, stdout);
		printf("rec-end\n");
		if (f)
			fclose(f);
	}

	/* ids outside the map: the kernel drops them; an RTR frame of a map id passes */
	mark("filters");
	int s = raw_socket();
	if (s < 0) {
		fail("filters", "no raw socket");
	} else {
		uint64_t before = d->frames;
		send_frame(s, 0x123, "\x01\x02", 2);
		send_frame(s, 0x300, "\x01\x02\x03\x04", 4);              /* the map has 0x300 extended */
		send_frame(s, 0x18FF0A43 | CAN_EFF_FLAG, "\x01", 1);
		send_frame(s, 0x181 | CAN_EFF_FLAG, "\x01", 1);           /* 181 extended: not 181 */
		send_frame(s, 0x7FF, NULL, 0);
		send_frame(s, 0x181 | CAN_RTR_FLAG, NULL, 8);             /* the sentinel */
		if (pump(5000, &d->frames, before + 1) < 0 || d->in.rtr_frames != 1)
			fail("filters", "the sentinel did not arrive");
		else if (d->frames != before + 1 || d->in.unknown_ids != 0)
			fail("filters", "a frame outside the map's ids arrived");
		else
			ok("kernel filters: 5 frames outside the map never arrived, the RTR sentinel did");
	}

	/* a flood into a small receive buffer: what the kernel drops is counted, none lost unseen */
	mark("overflow");
	if (s >= 0) {
		int small = 4096; /* the kernel doubles it and keeps a minimum */
		setsockopt(can_dev_fd(d), SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
		uint64_t before_frames = d->frames, sent = 0;
		for (int k = 0; k < 300; k++)
			sent += send_frame(s, 0x181 | CAN_RTR_FLAG, NULL, 8) == 0;
		pump(2000, NULL, 0);
		/* the drop count rides on the next frame the socket takes */
		sent += send_frame(s, 0x181 | CAN_RTR_FLAG, NULL, 8) == 0;
		pump(2000, NULL, 0);
		uint64_t got = d->frames - before_frames;
		snprintf(why, sizeof why, "%llu sent, %llu read, %llu dropped by the kernel",
			 (unsigned long long)sent, (unsigned long long)got,
			 (unsigned long long)d->kernel_dropped);
		if (d->kernel_dropped == 0 || got + d->kernel_dropped != sent)
			fail("overflow counted", "%s", why);
		else
			ok("overflow counted: %s", why);
	}

	/* bus-off, as a controller would send it */
	mark("busoff");
	if (s >= 0 && send_frame(s, CAN_ERR_FLAG | CAN_ERR_BUSOFF, NULL, CAN_ERR_DLC) == 0 &&
	    pump(5000, &d->bus_off, 1) == 0)
		ok("bus-off error frame counted");
	else
		printf("skip bus-off: a user's error frame did not come through vcan0\n");

	/* a frame, then silence: its dial goes stale by the backend's timer alone */
	mark("probe");
	uint64_t before = d->frames;
	if (s < 0 || send_frame(s, 0x185, "\x34\x12", 2) || pump(5000, &d->frames, before + 1) < 0)
		fail("probe frame", "did not arrive");
	mark("silent");
	pump(1500, NULL, 0);

	/* vcan0 deleted: the device removed; created again: a rescan opens it again */
	mark("del");
	if (s >= 0)
		close(s);
	if (sh("ip link del vcan0"))
		fail("vcan0 del", "ip link failed");
	pump(5000, NULL, 0);
	if (can_device())
		fail("vcan0 deleted", "the device is still open");
	else
		ok("vcan0 deleted: the device removed");
	/* created again, still down: a rescan opens it; frames are read once it is up */
	mark("end");
	if (sh("ip link add dev vcan0 type vcan") || input_devs_rescan(&set, now_us()) != 1 ||
	    !(d = can_device())) {
		fail("vcan0 again", "a rescan did not open it");
	} else {
		ok("vcan0 created again (down): a rescan opens it");
		s = -1;
		if (sh("ip link set vcan0 up") || (s = raw_socket()) < 0 ||
		    send_frame(s, 0x185, "\x01\x00", 2) || pump(5000, &d->frames, 1) < 0)
			fail("vcan0 up after the open", "no frame read");
		else
			ok("vcan0 up after the open: frames read");
		if (s >= 0)
			close(s);
	}
	input_devs_close_all(&set, now_us(), NULL);
	printf("guest_can: %d failures\n", guest_failures);
	return guest_status();
}
