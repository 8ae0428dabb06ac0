/*
 * guest_kms.c - the DRM/KMS sink (draw/sink_kms.c) on a real kernel: run in
 * the test guest with QEMU's standard VGA (bochs-drm), module bochs.
 *
 *   guest_kms FRAMES
 *
 * The sink opens the first card, sets its preferred mode and flips FRAMES
 * frames, each a different pattern; after each flip's event the pixels
 * read back from the scanout buffer shown must equal the frame converted
 * to XRGB8888 (computed here, not by the sink's converter). Closing puts
 * back the CRTC's framebuffer as it was (the console's). Then the fbdev
 * emulation on the same card: without overallocation its virtual height
 * is the visible one, so the fbdev sink falls back to one buffer, and a
 * frame written reads back from /dev/fb0 as drawn. tty1 is held in
 * graphics mode meanwhile, as the daemon holds it: else the console may
 * draw into the same memory (a failure one run in four without it). Prints ok/FAIL lines;
 * the exit status is the number of failures.
 *
 *   guest_kms bench SECONDS W H
 *
 * The render-to-flip benchmark (tools/bench/kms_flip_bench.py): W x H
 * frames handed to a frame writer at 60 Hz for SECONDS, as the daemon's
 * loop hands them, written by its thread to the KMS sink; prints one
 * "kms_flip key=value..." line of the sink's timing (sink_kms_times).
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <linux/fb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <time.h>
#include <unistd.h>

#include <xf86drm.h>
#include <xf86drmMode.h>

#include "daemon/vt.h"
#include "draw/frame_writer.h"
#include "draw/kms_pick.h"
#include "draw/sink.h"
#include "tests/guest/guest_check.h"
#include "tests/guest/guest_drm.h"

/* frame k's pixel (x, y): every channel moves with k, x and y */
static void
pattern(uint8_t *rgba, int w, int h, int k)
{
	for (int y = 0; y < h; y++)
		for (int x = 0; x < w; x++) {
			uint8_t *p = rgba + ((size_t)y * (size_t)w + (size_t)x) * 4;
			p[0] = (uint8_t)(x + 3 * k);
			p[1] = (uint8_t)(y + 5 * k);
			p[2] = (uint8_t)(x ^ y ^ k);
			p[3] = 255;
		}
}

/* the first pixel of the scanout that is not the frame's, or -1 */
static long
first_difference(const uint8_t *rgba, int w, int h, const uint8_t *scan, uint32_t pitch)
{
	for (int y = 0; y < h; y++)
		for (int x = 0; x < w; x++) {
			const uint8_t *p = rgba + ((size_t)y * (size_t)w + (size_t)x) * 4;
			uint32_t want = 0xff000000u | (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
			uint32_t got;
			memcpy(&got, scan + (size_t)y * pitch + (size_t)x * 4, 4);
			if (got != want)
				return (long)y * w + x;
		}
	return -1;
}

/* the framebuffer the first CRTC with one shows (the console's, unless ours), 0: none */
static uint32_t
shown_fb(uint32_t *crtc_id)
{
	int fd = open("/dev/dri/card0", O_RDWR | O_CLOEXEC);
	uint32_t fb = fd >= 0 ? crtc_fb(fd, crtc_id) : 0;
	if (fd >= 0)
		close(fd);
	return fb;
}

static void
kms(int frames)
{
	char err[512], desc[160];
	uint32_t crtc_before = 0, fb_before = shown_fb(&crtc_before);
	struct sink *s = sink_kms_open(NULL, NULL, NULL, err, sizeof err);
	if (!s) {
		fail("kms open", "%s", err);
		return;
	}
	int w, h;
	sink_kms_info(s, &w, &h, desc, sizeof desc);
	ok("kms mode set: %s", desc);
	uint8_t *rgba = malloc((size_t)w * (size_t)h * 4);
	int wrong = 0;
	uint64_t t0 = now_us();
	for (int k = 0; k < frames && !wrong; k++) {
		pattern(rgba, w, h, k);
		struct frame f = { .width = w, .height = h, .stride = 4 * w, .rgba = rgba };
		if (sink_write(s, &f, err, sizeof err) < 0 || sink_kms_settle(s) < 0) {
			fail("kms flip", "frame %d: %s", k, err);
			wrong = 1;
			break;
		}
		uint32_t pitch;
		uint64_t flips, dropped;
		const uint8_t *scan = sink_kms_front(s, &pitch, &flips, &dropped);
		long at = first_difference(rgba, w, h, scan, pitch);
		if (at >= 0) {
			fail("kms scanout", "frame %d differs at pixel %ld (x %ld, y %ld), pitch %u", k,
			     at, at % w, at / w, pitch);
			wrong = 1;
		}
	}
	uint32_t pitch;
	uint64_t flips, dropped;
	sink_kms_front(s, &pitch, &flips, &dropped);
	if (!wrong)
		ok("kms %d frames flipped, each read back from the scanout equal (%llu flips, %llu "
		   "skipped, pitch %u, %.2f ms a frame)", frames, (unsigned long long)flips,
		   (unsigned long long)dropped, pitch, (double)(now_us() - t0) / 1000.0 / frames);
	check(flips == (uint64_t)frames, "kms flip events", "%llu flips for %d frames",
	      (unsigned long long)flips, frames);
	/*
	 * Each frame came with the last flip's event in, so the sink had nothing to wait for, and
	 * the flip request (the ioctl) must be a small part of a 60 Hz period; every frame is timed.
	 * The conversion is the emulated CPU's (7-17 ms under TCG where the host takes about 1),
	 * so the whole is reported, not bounded. QEMU sends flip events at once: a request that
	 * waited for its flip would not show here.
	 */
	struct kms_times_summary t;
	sink_kms_times(s, &t);
	if (t.n == (uint64_t)frames && t.p99.wait < 1000 && t.median.ioctl < 1000000 / 60 / 4)
		ok("kms render to flip: median %u us, p99 %u us (copy %u, ioctl %u, its p99 %u, wait "
		   "p99 %u us), %llu frames timed", t.median.total, t.p99.total, t.median.copy,
		   t.median.ioctl, t.p99.ioctl, t.p99.wait, (unsigned long long)t.n);
	else
		fail("kms render to flip", "%llu frames timed of %d, wait p99 %u us (nothing was in "
		     "flight), the flip request's median %u us (a quarter period: %d)",
		     (unsigned long long)t.n, frames, t.p99.wait, t.median.ioctl, 1000000 / 60 / 4);
	/* a connector re-probe (what a hot-plug event asks for), the kernel made to probe first */
	FILE *detect = fopen("/sys/class/drm/card0-Virtual-1/status", "w");
	if (detect) {
		fputs("detect", detect);
		fclose(detect);
	}
	int re = sink_kms_reprobe(s, err, sizeof err);
	pattern(rgba, w, h, 500);
	struct frame f = { .width = w, .height = h, .stride = 4 * w, .rgba = rgba };
	int wrote = sink_write(s, &f, err, sizeof err) == 0 && sink_kms_settle(s) == 0;
	const uint8_t *scan = sink_kms_front(s, &pitch, &flips, &dropped);
	check(re == 0 && wrote && first_difference(rgba, w, h, scan, pitch) < 0,
	      "kms re-probe keeps the screen", "re-probe %d (%s), write %d", re, re < 0 ? err : "",
	      wrote);
	sink_close(s);
	free(rgba);
	uint32_t crtc_after = 0, fb_after = shown_fb(&crtc_after);
	check(fb_before && fb_after == fb_before, "kms crtc restored",
	      "the console's framebuffer %u before, %u after", fb_before, fb_after);
}

static void
fbdev(void)
{
	char err[512];
	int fd = open("/dev/fb0", O_RDONLY | O_CLOEXEC);
	struct fb_var_screeninfo var;
	if (fd < 0 || ioctl(fd, FBIOGET_VSCREENINFO, &var) < 0) {
		fail("fbdev", "/dev/fb0: %s", strerror(errno));
		if (fd >= 0)
			close(fd);
		return;
	}
	close(fd);
	ok("fbdev emulation %ux%u, virtual %ux%u", var.xres, var.yres, var.xres_virtual,
	   var.yres_virtual);
	struct vt vt;
	if (vt_take(&vt, "/dev/tty1", err, sizeof err) < 0) {
		fail("fbdev console off", "%s", err);
		return;
	}
	struct sink *s = sink_fb_open("/dev/fb0", err, sizeof err);
	if (!s) {
		fail("fbdev open", "%s", err);
		vt_give_back(&vt);
		return;
	}
	int w = (int)var.xres, h = (int)var.yres;
	uint8_t *rgba = malloc((size_t)w * (size_t)h * 4);
	pattern(rgba, w, h, 7);
	struct frame f = { .width = w, .height = h, .stride = 4 * w, .rgba = rgba };
	int rc = sink_write(s, &f, err, sizeof err);
	check(rc == 0, "fbdev single buffer write", "%s", rc ? err : "");
	/* read back what the screen shows: the first yres rows (no pan: one buffer) */
	fd = open("/dev/fb0", O_RDONLY | O_CLOEXEC);
	size_t line = (size_t)var.xres_virtual * 4, n = line * (size_t)h;
	uint8_t *shown = malloc(n);
	ssize_t got = fd >= 0 ? pread(fd, shown, n, 0) : -1;
	long at = got == (ssize_t)n ? first_difference(rgba, w, h, shown, (uint32_t)line) : -2;
	check(at == -1, "fbdev read back", "read %zd of %zu bytes, first difference %ld", got, n, at);
	if (fd >= 0)
		close(fd);
	free(shown);
	free(rgba);
	sink_close(s);
	vt_give_back(&vt);
}

/* the previous frame's deadline plus one period (CLOCK_MONOTONIC, absolute) */
static void
next_period(struct timespec *t, long ns)
{
	t->tv_nsec += ns;
	if (t->tv_nsec >= 1000000000L) {
		t->tv_nsec -= 1000000000L;
		t->tv_sec++;
	}
}

static int
bench(int seconds, int w, int h)
{
	char err[512], desc[160];
	struct sink *s = sink_kms_open(NULL, NULL, NULL, err, sizeof err);
	struct frame_writer *fw = frame_writer_make(0, err, sizeof err);
	int sw, sh;
	if (!s || !fw) {
		printf("kms_flip: %s\n", err);
		return 1;
	}
	sink_kms_info(s, &sw, &sh, desc, sizeof desc);
	if (frame_writer_attach(fw, 0, s, w, h, err, sizeof err) < 0) {
		printf("kms_flip: %s\n", err);
		return 1;
	}
	/* two frames rendered beforehand: the render's own cost is not what is measured */
	uint8_t *rgba[2] = { malloc((size_t)w * (size_t)h * 4), malloc((size_t)w * (size_t)h * 4) };
	pattern(rgba[0], w, h, 1);
	pattern(rgba[1], w, h, 2);
	int frames = seconds * 60;
	struct timespec due;
	clock_gettime(CLOCK_MONOTONIC, &due);
	for (int k = 0; k < frames; k++) {
		struct frame f = { .width = w, .height = h, .stride = 4 * w, .rgba = rgba[k & 1],
				   .seq = (uint64_t)k + 1 };
		if (frame_writer_submit(fw, 0, &f, err, sizeof err) < 0) {
			printf("kms_flip: frame %d: %s\n", k, err);
			return 1;
		}
		next_period(&due, 1000000000L / 60);
		while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &due, NULL))
			; /* EINTR */
	}
	frame_writer_flush(fw);
	sink_kms_settle(s);
	struct kms_times_summary t;
	struct frame_writer_stats st;
	uint32_t pitch;
	uint64_t flips, skipped;
	sink_kms_times(s, &t);
	frame_writer_stats(fw, &st);
	sink_kms_front(s, &pitch, &flips, &skipped);
	printf("kms_flip median_us=%u p99_us=%u max_us=%u queue_us=%u wait_us=%u copy_us=%u "
	       "ioctl_us=%u frames=%llu kept=%d submitted=%d dropped=%llu skipped=%llu flips=%llu "
	       "size=%dx%d mode=%dx%d desc=%s\n", t.median.total, t.p99.total, t.max.total,
	       t.median.queue, t.median.wait, t.median.copy, t.median.ioctl,
	       (unsigned long long)t.n, t.kept, frames, (unsigned long long)st.dropped,
	       (unsigned long long)skipped, (unsigned long long)flips, w, h, sw, sh, desc);
	frame_writer_free(fw); /* the sink with it */
	free(rgba[0]);
	free(rgba[1]);
	return 0;
}

int
main(int argc, char **argv)
{
	if (argc == 5 && !strcmp(argv[1], "bench"))
		return bench(atoi(argv[2]), atoi(argv[3]), atoi(argv[4]));
	int frames = argc > 1 ? atoi(argv[1]) : 120;
	kms(frames);
	fbdev();
	printf("guest_kms: %d failures\n", guest_status());
	return guest_status();
}
