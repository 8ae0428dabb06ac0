/*
 * guest_vt.c - the kiosk's VT (daemon/vt.h) and the KMS screen given up
 * and taken back on a real kernel: run in the test guest with QEMU's
 * standard VGA (module bochs), so that /dev/tty1 is a VT on fbcon.
 *
 * The VT taken: graphics mode, keyboard off, VT_PROCESS with our signals.
 * A switch to tty2 asks us first (the release signal): the KMS sink gives
 * up DRM master (a flip then fails), we agree, and tty2 is shown; back to
 * tty1, the acquire signal: acknowledged, master taken again, a frame flips
 * and reads back whole. Given back: text mode and the keyboard as they
 * were, automatic switching. A process holding the VT killed with SIGKILL
 * leaves it in graphics mode; vt_restore_console (what `postured
 * --vt-restore`, the unit's ExecStopPost, runs) makes it a text console.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <linux/kd.h>
#include <linux/vt.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/signalfd.h>
#include <sys/wait.h>
#include <unistd.h>

#include "daemon/vt.h"
#include "draw/sink.h"
#include "tests/guest/guest_check.h"

static int sigfd = -1;

static int
modes(const char *tty, int *kd, int *kb, int *vtmode)
{
	int fd = open(tty, O_RDWR | O_NOCTTY | O_CLOEXEC);
	struct vt_mode m;
	int rc = fd >= 0 && ioctl(fd, KDGETMODE, kd) == 0 && ioctl(fd, KDGKBMODE, kb) == 0 &&
			 ioctl(fd, VT_GETMODE, &m) == 0
		 ? 0 : -1;
	*vtmode = m.mode;
	if (fd >= 0)
		close(fd);
	return rc;
}

static int
active_vt(void)
{
	int fd = open("/dev/tty0", O_RDWR | O_NOCTTY | O_CLOEXEC);
	struct vt_stat st = { 0 };
	ioctl(fd, VT_GETSTATE, &st);
	close(fd);
	return st.v_active;
}

static void
activate(int n)
{
	int fd = open("/dev/tty0", O_RDWR | O_NOCTTY | O_CLOEXEC);
	ioctl(fd, VT_ACTIVATE, n);
	close(fd);
}

/* the next VT signal, within ms; 0: none */
static int
next_signal(int ms)
{
	struct pollfd p = { .fd = sigfd, .events = POLLIN };
	struct signalfd_siginfo si;
	if (poll(&p, 1, ms) <= 0 || read(sigfd, &si, sizeof si) != (ssize_t)sizeof si)
		return 0;
	return (int)si.ssi_signo;
}

/* a frame through the sink read back from the shown buffer: 0 equal, -1 the flip failed, 1 differs */
static int
flip_one(struct sink *s, int w, int h, int k)
{
	uint8_t *rgba = malloc((size_t)w * (size_t)h * 4);
	for (int i = 0; i < w * h; i++) {
		rgba[4 * i] = (uint8_t)(i + k), rgba[4 * i + 1] = (uint8_t)(i >> 8);
		rgba[4 * i + 2] = (uint8_t)k, rgba[4 * i + 3] = 255;
	}
	struct frame f = { .width = w, .height = h, .stride = 4 * w, .rgba = rgba };
	char err[300];
	int rc = sink_write(s, &f, err, sizeof err) < 0 || sink_kms_settle(s) < 0 ? -1 : 0;
	if (rc == 0) {
		uint32_t pitch;
		uint64_t flips, dropped;
		const uint8_t *scan = sink_kms_front(s, &pitch, &flips, &dropped);
		for (int y = 0; y < h && rc == 0; y++)
			for (int x = 0; x < w && rc == 0; x++) {
				const uint8_t *p = rgba + ((size_t)y * w + x) * 4;
				uint32_t want = 0xff000000u | (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2],
					 got;
				memcpy(&got, scan + (size_t)y * pitch + (size_t)x * 4, 4);
				rc = got != want;
			}
	}
	free(rgba);
	return rc;
}

static void
switches(void)
{
	char err[300];
	int kd0, kb0, m0, kd, kb, m;
	if (modes("/dev/tty1", &kd0, &kb0, &m0) < 0) {
		fail("vt tty1", "no VT: %s", strerror(errno));
		return;
	}
	struct sink *s = sink_kms_open(NULL, NULL, NULL, err, sizeof err);
	if (!s) {
		fail("vt kms", "%s", err);
		return;
	}
	int w, h;
	char desc[160];
	sink_kms_info(s, &w, &h, desc, sizeof desc);
	struct vt v;
	if (vt_take(&v, "/dev/tty1", err, sizeof err) < 0) {
		fail("vt take", "%s", err);
		sink_close(s);
		return;
	}
	modes("/dev/tty1", &kd, &kb, &m);
	check(kd == KD_GRAPHICS && kb == K_OFF && m == VT_PROCESS, "vt taken",
	      "KDGETMODE %d, KDGKBMODE %d, VT_GETMODE %d", kd, kb, m);
	check(flip_one(s, w, h, 1) == 0, "vt kms flips on tty1", "a frame did not read back");

	activate(2); /* what Ctrl+Alt+F2 does */
	int sig = next_signal(2000);
	check(sig == VT_SIG_RELEASE, "vt asked to release", "signal %d", sig);
	check(sink_kms_master(s, 0) == 0, "vt kms master dropped", "%s", strerror(errno));
	check(flip_one(s, w, h, 2) == -1, "vt kms no flip without master", "a flip went through");
	vt_release(&v);
	usleep(200000);
	check(active_vt() == 2, "vt switched away", "VT %d shown", active_vt());

	activate(1);
	sig = next_signal(2000);
	check(sig == VT_SIG_ACQUIRE, "vt back", "signal %d", sig);
	vt_acquire(&v);
	check(sink_kms_master(s, 1) == 0, "vt kms master again", "%s", strerror(errno));
	check(flip_one(s, w, h, 3) == 0, "vt kms flips again", "the frame after the switch back");
	check(active_vt() == 1, "vt 1 shown", "VT %d", active_vt());

	sink_close(s);
	vt_give_back(&v);
	modes("/dev/tty1", &kd, &kb, &m);
	check(kd == kd0 && kb == kb0 && m == VT_AUTO, "vt given back",
	      "KDGETMODE %d (was %d), KDGKBMODE %d (was %d), VT_GETMODE %d", kd, kd0, kb, kb0, m);
}

static void
crash(void)
{
	char err[300];
	pid_t pid = fork();
	if (pid == 0) {
		struct vt v;
		if (vt_take(&v, "/dev/tty1", err, sizeof err) < 0)
			_exit(3);
		raise(SIGKILL);
		_exit(4);
	}
	int st, kd, kb, m;
	waitpid(pid, &st, 0);
	modes("/dev/tty1", &kd, &kb, &m);
	check(WIFSIGNALED(st) && kd == KD_GRAPHICS, "vt killed holder leaves graphics",
	      "status %d, KDGETMODE %d", st, kd);
	check(vt_restore_console("/dev/tty1", err, sizeof err) == 0, "vt restore runs", "%s", err);
	modes("/dev/tty1", &kd, &kb, &m);
	check(kd == KD_TEXT && kb == K_UNICODE && m == VT_AUTO, "vt restored to text",
	      "KDGETMODE %d, KDGKBMODE %d, VT_GETMODE %d", kd, kb, m);
}

int
main(void)
{
	sigset_t set;
	sigemptyset(&set);
	sigaddset(&set, VT_SIG_RELEASE);
	sigaddset(&set, VT_SIG_ACQUIRE);
	sigprocmask(SIG_BLOCK, &set, NULL);
	sigfd = signalfd(-1, &set, SFD_CLOEXEC);
	switches();
	crash();
	printf("guest_vt: %d failures\n", guest_status());
	return guest_status();
}
