/*
 * guest_package.c - the check inside the clean Debian 12 that test_guest_package.py
 * installs the package into and boots (systemd as init, QEMU's standard VGA, bochs-drm).
 * A unit of the test's, ordered after postured.service, runs it as root:
 *
 *   posture-check
 *
 * The packaged service, enabled by the package and started by systemd, is active and
 * runs as the user posture; the CRTC shows the kiosk's picture (more colours than the
 * console's 16-colour palette) and tty1 is in graphics mode; 12 s later it has not
 * been restarted (no crash, no watchdog kill); after `systemctl stop
 * postured` the service is inactive (a clean exit), tty1 is a text console again and
 * the CRTC shows another framebuffer (the console's). ok/FAIL lines; the exit status is
 * the number of failures.
 */
#define _GNU_SOURCE
#include <pwd.h>
#include <stdlib.h>
#include <sys/stat.h>

#include "tests/guest/guest_check.h"
#include "tests/guest/guest_drm.h"

#define WAIT_MS 150000 /* generous: TCG, and llvmpipe's first frames */

/* the first line cmd prints, without its newline; "" when none */
static const char *
first_line(const char *cmd, char *buf, size_t size)
{
	FILE *p = popen(cmd, "r");
	buf[0] = 0;
	if (p) {
		if (!fgets(buf, (int)size, p))
			buf[0] = 0;
		pclose(p);
	}
	buf[strcspn(buf, "\n")] = 0;
	return buf;
}

/* systemctl is-active postured, waited on while it is starting, stopping or restarting */
static const char *
service_state(char *buf, size_t size, long wait_ms)
{
	uint64_t t0 = now_us() / 1000;
	while ((!strcmp(first_line("systemctl is-active postured", buf, size), "activating") ||
		!strcmp(buf, "deactivating")) && now_us() / 1000 - t0 < (uint64_t)wait_ms)
		sleep_ms(500);
	return buf;
}

/* the framebuffer the CRTC shows, once it has more colours than the console can have (or
 * when wait_ms is over) */
static uint32_t
kiosk_frame(long wait_ms, int *colours, long *lit)
{
	uint32_t shown = 0, crtc = 0;
	uint64_t t0 = now_us() / 1000;
	*colours = -1;
	do {
		int card = open("/dev/dri/card0", O_RDWR | O_CLOEXEC);
		if (card >= 0) {
			shown = crtc_fb(card, &crtc);
			*colours = shown ? screen_colours(card, shown, lit) : -1;
			close(card);
		}
		if (*colours > 16 && *lit > 1000)
			break;
		sleep_ms(500);
	} while (now_us() / 1000 - t0 < (uint64_t)wait_ms);
	return shown;
}

int
main(void)
{
	setvbuf(stdout, NULL, _IOLBF, 0);
	char state[64], pid[32];
	check(!strcmp(service_state(state, sizeof state, WAIT_MS), "active"),
	      "postured.service active", "systemctl is-active: %s", state);

	struct passwd *pw = getpwnam("posture");
	struct stat st;
	char proc[64];
	first_line("systemctl show -p MainPID --value postured", pid, sizeof pid);
	snprintf(proc, sizeof proc, "/proc/%s", pid);
	check(pw && atoi(pid) > 0 && stat(proc, &st) == 0 && st.st_uid == pw->pw_uid,
	      "postured runs as the user posture", "main pid '%s', user posture %s", pid,
	      pw ? "exists" : "missing");

	int colours;
	long lit = 0;
	/* no daemon, no picture to wait for */
	uint32_t kiosk = kiosk_frame(strcmp(state, "active") ? 0 : WAIT_MS, &colours, &lit);
	check(kiosk && colours > 16 && lit > 1000, "the screen shows the kiosk's picture (KMS)",
	      "framebuffer %u, %d colours, %ld lit samples", kiosk, colours, lit);
	check(kd_mode("/dev/tty1") == KD_GRAPHICS, "tty1 in graphics mode while it runs",
	      "KDGETMODE %d", kd_mode("/dev/tty1"));

	/* over two of the unit's watchdog periods (WatchdogSec=5s): never killed, never restarted */
	char restarts[32], pid_after[32];
	sleep_ms(12000);
	first_line("systemctl show -p NRestarts --value postured", restarts, sizeof restarts);
	first_line("systemctl show -p MainPID --value postured", pid_after, sizeof pid_after);
	check(atoi(pid) > 0 && !strcmp(restarts, "0") && !strcmp(pid, pid_after),
	      "postured runs on, never restarted",
	      "NRestarts %s, main pid %s, 12 s later %s", restarts, pid, pid_after);

	/* stopped as a site stops it: SIGTERM, then the unit's ExecStopPost (--vt-restore) */
	int rc = system("systemctl stop postured");
	first_line("systemctl is-active postured", state, sizeof state);
	check(rc == 0 && !strcmp(state, "inactive"), "postured stops cleanly",
	      "systemctl stop: %d, then is-active: %s", rc, state);
	int card = open("/dev/dri/card0", O_RDWR | O_CLOEXEC);
	uint32_t crtc = 0, after = card >= 0 ? crtc_fb(card, &crtc) : 0;
	if (card >= 0)
		close(card);
	check(kd_mode("/dev/tty1") == KD_TEXT && after && after != kiosk,
	      "the console back after it stops",
	      "KDGETMODE %d, framebuffer %u (the kiosk's %u)", kd_mode("/dev/tty1"), after,
	      kiosk);
	printf("%d checks, %d failed\n", guest_checks, guest_failures);
	return guest_status();
}
