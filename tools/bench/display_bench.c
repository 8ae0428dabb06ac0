/*
 * display_bench.c - a finished 1280x720 frame into the screen's memory:
 * what the KMS sink does before its flip request (the frame converted to
 * XRGB8888 into a dumb buffer's rows, pitch 5120, as bochs-drm gives it),
 * beside the fbdev sink's whole write on a framebuffer's memory (a file
 * mapped as sink_fb maps /dev/fbN): XRGB8888 double-buffered (it pans), and
 * RGB565 single-buffered (a 16-bit console framebuffer). 400 frames each,
 * the same frames, after 20 to warm up.
 *
 *   BENCH display.kms_copy us=MEDIAN p99_us=... size=1280x720
 *   BENCH display.fbdev_copy us=MEDIAN p99_us=... format=xrgb8888
 *   BENCH display.fbdev_copy_rgb565 us=MEDIAN p99_us=...
 */
#include <linux/fb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "draw/pixfmt.h"
#include "draw/scanout.h"
#include "draw/sink.h"
#include "tools/bench/bench_util.h"

#define W 1280
#define H 720
#define FRAMES 400
#define WARM 20

static uint8_t rgba[2][W * H * 4];

static void
frames(void)
{
	for (int k = 0; k < 2; k++)
		for (int i = 0; i < W * H * 4; i++)
			rgba[k][i] = (uint8_t)(i * 7 + k * 13);
}

static void
report(const char *name, double *us, const char *more)
{
	double p99 = bench_percentile(us, FRAMES, 0.99);
	printf("BENCH %s us=%.0f p99_us=%.0f size=%dx%d%s\n", name, bench_percentile(us, FRAMES, 0.5),
	       p99, W, H, more);
	fflush(stdout);
}

static void
kms(void)
{
	static double us[FRAMES];
	struct pixfmt pf = { .bpp = 32, .red = { 16, 8, 0 }, .green = { 8, 8, 0 }, .blue = { 0, 8, 0 } };
	char err[200];
	uint8_t black[4];
	static const uint8_t opaque[4] = { 0, 0, 0, 255 };
	if (pixfmt_init(&pf, err, sizeof err) < 0)
		exit(1);
	pixfmt_convert_row(&pf, opaque, 1, black);
	uint8_t *buf = malloc((size_t)5120 * H);
	for (int k = -WARM; k < FRAMES; k++) {
		struct frame f = { .width = W, .height = H, .stride = 4 * W, .rgba = rgba[k & 1] };
		double t0 = bench_now_us();
		scanout_draw(&pf, black, &f, buf, 5120, W, H);
		if (k >= 0)
			us[k] = bench_now_us() - t0;
	}
	free(buf);
	report("display.kms_copy", us, "");
}

static void
fbdev(int bpp, const char *name, const char *more)
{
	static double us[FRAMES];
	char path[] = "/tmp/display-bench-XXXXXX", err[300];
	int fd = mkstemp(path);
	if (fd < 0 || ftruncate(fd, (off_t)W * bpp / 8 * (bpp == 32 ? 2 * H : H)) < 0)
		exit(1);
	close(fd);
	struct fb_var_screeninfo var = { .xres = W, .yres = H, .xres_virtual = W,
					 .yres_virtual = bpp == 32 ? 2 * H : H, .bits_per_pixel =
					 (unsigned)bpp };
	if (bpp == 32) {
		var.red = (struct fb_bitfield){ 16, 8, 0 };
		var.green = (struct fb_bitfield){ 8, 8, 0 };
		var.blue = (struct fb_bitfield){ 0, 8, 0 };
	} else {
		var.red = (struct fb_bitfield){ 11, 5, 0 };
		var.green = (struct fb_bitfield){ 5, 6, 0 };
		var.blue = (struct fb_bitfield){ 0, 5, 0 };
	}
	struct fb_fix_screeninfo fix = { .line_length = (unsigned)(W * bpp / 8),
					 .smem_len = (unsigned)(W * bpp / 8) * var.yres_virtual,
					 .visual = FB_VISUAL_TRUECOLOR };
	struct sink *s = sink_fb_open_file(path, &var, &fix, err, sizeof err);
	if (!s) {
		fprintf(stderr, "display_bench: %s\n", err);
		exit(1);
	}
	for (int k = -WARM; k < FRAMES; k++) {
		struct frame f = { .width = W, .height = H, .stride = 4 * W, .rgba = rgba[k & 1] };
		double t0 = bench_now_us();
		if (sink_write(s, &f, err, sizeof err) < 0)
			exit(1);
		if (k >= 0)
			us[k] = bench_now_us() - t0;
	}
	sink_close(s);
	unlink(path);
	report(name, us, more);
}

int
main(void)
{
	frames();
	kms();
	fbdev(32, "display.fbdev_copy", " format=xrgb8888 double_buffered=1");
	fbdev(16, "display.fbdev_copy_rgb565", " format=rgb565 double_buffered=0");
	return 0;
}
