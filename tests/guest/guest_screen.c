/*
 * guest_screen.c - the real daemon on the machine's screen, inside the
 * test guest with QEMU's standard VGA (module bochs: bochs-drm, fbcon on
 * tty1):
 *
 *   guest_screen POSTURED INIT
 *
 * postured --display auto --vt /dev/tty1 --init INIT: auto takes KMS; the
 * frames written to the screen are what the CRTC shows (not the console's
 * framebuffer; the kiosk's picture, many colours); tty1 is in graphics mode
 * while it runs; on SIGTERM it exits 0, tty1 is in text mode again and the
 * console's framebuffer is back on the CRTC; status reports the frames' render to flip
 * request (flip_us). ok/FAIL lines; the exit status
 * is the number of failures.
 */
#define _GNU_SOURCE
#define SOCK "/tmp/screen/sock"
#define STATE "/tmp/screen/state"
#define START_MS 90000 /* generous: TCG */

#include "tests/guest/guest_daemon.h"
#include "tests/guest/guest_drm.h"


/*
 * status's flip_us: the frames' way from the loop to their flip requests, timed. A frame's
 * whole way is no shorter than its conversion, so the median of one is no smaller than the
 * median of the other.
 */
static void
flip_times(struct conn *c)
{
	json_t *r = request(c, "status"), *t = r ? json_object_get(r, "flip_us") : NULL;
	long n = (long)json_integer_value(json_object_get(t, "n"));
	long median = (long)json_integer_value(json_object_get(t, "median"));
	long p99 = (long)json_integer_value(json_object_get(t, "p99"));
	long copy = (long)json_integer_value(json_object_get(t, "copy"));
	long queue = (long)json_integer_value(json_object_get(t, "queue"));
	long wait = (long)json_integer_value(json_object_get(t, "wait"));
	long ioctl = (long)json_integer_value(json_object_get(t, "ioctl"));
	if (json_is_object(t) && n >= 1 && median > 0 && median >= copy && median >= queue) {
		ok("status reports render to flip: median %ld us, p99 %ld us (queue %ld, wait %ld, "
		   "copy %ld, ioctl %ld), %ld frames", median, p99, queue, wait, copy, ioctl, n);
	} else {
		char *got = t ? json_dumps(t, JSON_COMPACT | JSON_ENCODE_ANY) : NULL;
		fail("status reports render to flip", "flip_us %s", got ? got : "missing");
		free(got);
	}
	json_decref(r);
}

/* the daemon on the machine's screen: KMS chosen by auto, the human drawn, the console back after */
static int
run_screen(char **argv)
{
	/* the card opened only to look: its first opener is DRM master, which the daemon must be */
	int card = open("/dev/dri/card0", O_RDWR | O_CLOEXEC);
	uint32_t crtc = 0, console = card >= 0 ? crtc_fb(card, &crtc) : 0;
	check(console != 0, "the console shows on a CRTC", "no framebuffer on any CRTC");
	if (card >= 0)
		close(card);
	char *const args[] = { argv[1], "--socket", SOCK, "--state-dir", STATE, "--input", "none",
			       "--hotplug", "none", "--display", "auto", "--vt", "/dev/tty1",
			       "--init", argv[2], NULL };
	struct conn c;
	if (daemon_start(args) < 0 || conn_open(&c, START_MS) < 0) {
		fail("postured started", "no socket after %d ms", START_MS);
		return guest_status();
	}
	long written = 0;
	for (int k = 0; k < 300 && written < 1; k++, sleep_ms(50))
		written = status_field(&c, "frames_written");
	check(written >= 1, "frames written to the screen", "%ld after 15 s", written);
	sleep_ms(500); /* the flip's event */
	flip_times(&c);
	card = open("/dev/dri/card0", O_RDWR | O_CLOEXEC);
	uint32_t shown = crtc_fb(card, &crtc);
	long lit = 0;
	int colours = shown && shown != console ? screen_colours(card, shown, &lit) : -1;
	check(shown && shown != console && colours >= 16 && lit > 1000,
	      "the screen shows the kiosk's picture (KMS)",
	      "framebuffer %u (the console's %u), %d colours, %ld lit samples", shown, console,
	      colours, lit);
	check(kd_mode("/dev/tty1") == KD_GRAPHICS, "tty1 in graphics mode while it runs",
	      "KDGETMODE %d", kd_mode("/dev/tty1"));
	conn_close(&c);
	int st = daemon_stop();
	check(st == 0, "postured stops cleanly on SIGTERM", "exit status %d", st);
	check(kd_mode("/dev/tty1") == KD_TEXT && crtc_fb(card, &crtc) == console,
	      "the console back after it stops", "KDGETMODE %d, framebuffer %u (the console's %u)",
	      kd_mode("/dev/tty1"), crtc_fb(card, &crtc), console);
	close(card);
	return guest_status();
}

int
main(int argc, char **argv)
{
	setvbuf(stdout, NULL, _IOLBF, 0);
	signal(SIGPIPE, SIG_IGN);
	if (argc != 3) {
		fprintf(stderr, "usage: guest_screen POSTURED INIT\n");
		return 2;
	}
	int st = run_screen(argv);
	printf("%d checks, %d failed\n", guest_checks, guest_failures);
	return st;
}
