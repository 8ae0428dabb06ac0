/* test_sink.c - frame sinks: PNG files, the framebuffer over files, memory */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <fcntl.h>
#include <linux/fb.h>
#include <png.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "draw/pixfmt.h"
#include "draw/sink.h"

/* ---- helpers ------------------------------------------------------------ */

/* the pixel (x, y) of frame number n: n in R and G, so one pixel names the frame */
static void
pattern(uint32_t n, int x, int y, uint8_t *dest)
{
	dest[0] = (uint8_t)n;
	dest[1] = (uint8_t)(n >> 8);
	dest[2] = (uint8_t)(x * 3 + y * 5 + n * 7);
	dest[3] = (uint8_t)(255 - ((x ^ y ^ n) & 0x3f));
}

static int pattern_w(uint32_t n) { return 40 + (int)(n % 7) * 11; }
static int pattern_h(uint32_t n) { return 30 + (int)(n % 5) * 9; }

/* frame n of w x h, rows pad junk bytes apart; free rgba */
static struct frame
make_frame(uint32_t n, int w, int h, int pad)
{
	struct frame f;
	frame_init(&f, w, h, NULL);
	f.stride = 4 * w + pad;
	f.seq = n;
	f.rgba = malloc((size_t)f.stride * (size_t)h);
	assert_non_null(f.rgba);
	memset(f.rgba, 0xcd, (size_t)f.stride * (size_t)h);
	for (int y = 0; y < h; y++)
		for (int x = 0; x < w; x++)
			pattern(n, x, y, f.rgba + (size_t)y * f.stride + 4 * (size_t)x);
	return f;
}

/* PNG (from path, else mem) -> malloc'ed RGBA and its size, or NULL with msg set */
static uint8_t *
png_decode(const char *path, const uint8_t *mem, size_t len, int *w, int *h, char *msg, size_t n)
{
	png_image im;
	memset(&im, 0, sizeof im);
	im.version = PNG_IMAGE_VERSION;
	int ok = path ? png_image_begin_read_from_file(&im, path)
		      : png_image_begin_read_from_memory(&im, mem, len);
	if (!ok) {
		snprintf(msg, n, "begin: %s", im.message);
		return NULL;
	}
	if (im.format != PNG_FORMAT_RGBA) {
		snprintf(msg, n, "not 8-bit RGBA: format %u", im.format);
		png_image_free(&im);
		return NULL;
	}
	uint8_t *buf = malloc(PNG_IMAGE_SIZE(im));
	if (!buf || !png_image_finish_read(&im, NULL, buf, 0, NULL)) {
		snprintf(msg, n, "finish: %s", buf ? im.message : "no memory");
		free(buf);
		png_image_free(&im);
		return NULL;
	}
	*w = (int)im.width;
	*h = (int)im.height;
	return buf;
}

/* asserts that the PNG decodes to exactly the frame's pixels */
static void
assert_png_is(const char *path, const uint8_t *mem, size_t len, const struct frame *f)
{
	char msg[256];
	int w, h;
	uint8_t *px = png_decode(path, mem, len, &w, &h, msg, sizeof msg);
	if (!px)
		fail_msg("%s: %s", path ? path : "memory", msg);
	assert_int_equal(w, f->width);
	assert_int_equal(h, f->height);
	for (int y = 0; y < h; y++)
		assert_memory_equal(px + 4 * (size_t)w * y, f->rgba + (size_t)f->stride * y,
				    4 * (size_t)w);
	free(px);
}

static uint8_t *
read_all(const char *path, size_t *len)
{
	FILE *fp = fopen(path, "rb");
	assert_non_null(fp);
	fseek(fp, 0, SEEK_END);
	*len = (size_t)ftell(fp);
	rewind(fp);
	uint8_t *b = malloc(*len + 1);
	assert_non_null(b);
	assert_int_equal(fread(b, 1, *len, fp), *len);
	fclose(fp);
	return b;
}

static void
write_all(const char *path, const uint8_t *data, size_t len)
{
	FILE *fp = fopen(path, "wb");
	assert_non_null(fp);
	assert_int_equal(fwrite(data, 1, len, fp), len);
	assert_int_equal(fclose(fp), 0);
}

/* the names in dir, sorted, joined by spaces */
static void
list_dir(const char *dir, char *dest, size_t n)
{
	struct dirent **ents;
	int k = scandir(dir, &ents, NULL, alphasort);
	assert_true(k >= 0);
	dest[0] = '\0';
	for (int i = 0; i < k; i++) {
		if (strcmp(ents[i]->d_name, ".") != 0 && strcmp(ents[i]->d_name, "..") != 0)
			snprintf(dest + strlen(dest), n - strlen(dest), "%s%s", dest[0] ? " " : "",
				 ents[i]->d_name);
		free(ents[i]);
	}
	free(ents);
}

static int
dir_setup(void **state)
{
	static char dir[64];
	snprintf(dir, sizeof dir, "/tmp/posture-sink-XXXXXX");
	if (!mkdtemp(dir))
		return -1;
	*state = dir;
	return 0;
}

static int
dir_teardown(void **state)
{
	char cmd[128];
	snprintf(cmd, sizeof cmd, "rm -rf '%s'", (char *)*state);
	return system(cmd) == 0 ? 0 : -1;
}

/* ---- PNG files -------------------------------------------------------------- */

static void
test_png_latest_roundtrip(void **state)
{
	char path[128], err[256];
	snprintf(path, sizeof path, "%s/latest.png", (char *)*state);
	struct sink *s = sink_png_latest(path, err, sizeof err);
	assert_non_null(s);
	assert_string_equal(s->ops->name, "png-latest");
	struct frame a = make_frame(7, 33, 17, 12), b = make_frame(8, 1, 1, 0);
	assert_int_equal(sink_write(s, &a, err, sizeof err), 0);
	assert_png_is(path, NULL, 0, &a);
	assert_int_equal(sink_write(s, &b, err, sizeof err), 0);
	assert_png_is(path, NULL, 0, &b);
	assert_int_equal(s->frames, 2);
	char names[256];
	list_dir(*state, names, sizeof names);
	assert_string_equal(names, "latest.png");
	sink_close(s);
	free(a.rgba);
	free(b.rgba);
}

static void
test_png_sequence_naming(void **state)
{
	const char *dir = *state;
	char err[256], names[256], path[160];
	struct sink *s = sink_png_sequence(dir, "shot", err, sizeof err);
	assert_non_null(s);
	uint32_t seqs[3] = { 10, 11, 50 }; /* numbered by write, not by seq */
	struct frame f[3];
	for (int i = 0; i < 3; i++) {
		f[i] = make_frame(seqs[i], pattern_w(seqs[i]), pattern_h(seqs[i]), 4 * i);
		assert_int_equal(sink_write(s, &f[i], err, sizeof err), 0);
	}
	list_dir(dir, names, sizeof names);
	assert_string_equal(names, "shot-000001.png shot-000002.png shot-000003.png");
	for (int i = 0; i < 3; i++) {
		snprintf(path, sizeof path, "%s/shot-%06d.png", dir, i + 1);
		assert_png_is(path, NULL, 0, &f[i]);
		free(f[i].rgba);
	}
	sink_close(s);
}

/* the reader side of the atomicity test: decodes until stop_fd reaches EOF */
static void __attribute__((noreturn))
atomic_reader(const char *path, int stop_fd, int report_fd)
{
	char msg[256] = "";
	long reads = 0, changes = 0;
	uint32_t last = 0;
	int stopping = 0, bad = 0;
	while (!bad) {
		struct pollfd p = { stop_fd, POLLIN, 0 };
		stopping = poll(&p, 1, 0) > 0;
		int w, h;
		uint8_t *px = png_decode(path, NULL, 0, &w, &h, msg, sizeof msg);
		if (!px) {
			bad = 1;
			break;
		}

		/* the frame number from one pixel, then the whole image must agree */
		uint32_t n = px[0] | (uint32_t)px[1] << 8;
		if (w != pattern_w(n) || h != pattern_h(n)) {
			snprintf(msg, sizeof msg, "frame %u is %dx%d", n, w, h);
			bad = 1;
		}
		for (int i = 0; !bad && i < w * h; i++) {
			uint8_t want[4];
			pattern(n, i % w, i / w, want);
			if (memcmp(px + 4 * i, want, 4) != 0) {
				snprintf(msg, sizeof msg, "frame %u: pixel %d differs", n, i);
				bad = 1;
			}
		}
		free(px);
		reads++;
		changes += n != last;
		last = n;
		if (stopping)
			break;
	}
	dprintf(report_fd, "%d %ld %ld %s", bad, reads, changes, msg);
	_exit(bad);
}

static void
test_png_latest_atomic(void **state)
{
	enum { NWRITES = 400 };
	char path[128], err[256];
	snprintf(path, sizeof path, "%s/latest.png", (char *)*state);
	struct sink *s = sink_png_latest(path, err, sizeof err);
	assert_non_null(s);
	struct frame f = make_frame(0, pattern_w(0), pattern_h(0), 0);
	assert_int_equal(sink_write(s, &f, err, sizeof err), 0);
	free(f.rgba);

	/* a reader decoding the file over and over while we replace it */
	int stop[2], report[2];
	assert_int_equal(pipe(stop), 0);
	assert_int_equal(pipe(report), 0);
	pid_t pid = fork();
	assert_true(pid >= 0);
	if (pid == 0) {
		close(stop[1]);
		close(report[0]);
		atomic_reader(path, stop[0], report[1]);
	}
	close(stop[0]);
	close(report[1]);
	for (uint32_t n = 1; n <= NWRITES; n++) {
		f = make_frame(n, pattern_w(n), pattern_h(n), (int)(n % 3) * 4);
		if (sink_write(s, &f, err, sizeof err) != 0)
			fail_msg("write %u: %s", n, err);
		free(f.rgba);
	}
	close(stop[1]);

	/* its verdict */
	char rep[400] = "";
	ssize_t k = read(report[0], rep, sizeof rep - 1);
	close(report[0]);
	int status;
	assert_int_equal(waitpid(pid, &status, 0), pid);
	int bad = 1;
	long reads = 0, changes = 0;
	assert_true(k > 0 && sscanf(rep, "%d %ld %ld", &bad, &reads, &changes) == 3);
	print_message("reader: %ld full decodes, %ld frame changes seen during %d writes\n", reads,
		      changes, NWRITES);
	if (bad || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
		fail_msg("reader saw a bad frame: %s", rep);
	assert_true(changes >= 2); /* it really ran while the file was being replaced */
	char names[256];
	list_dir(*state, names, sizeof names);
	assert_string_equal(names, "latest.png"); /* no temporary file left */
	sink_close(s);
}

static void
test_png_errors(void **state)
{
	const char *dir = *state;
	char err[256] = "", path[128], tmp[160];

	/* constructors refuse what cannot work */
	assert_null(sink_png_sequence("/nonexistent/posture", "p", err, sizeof err));
	assert_non_null(strstr(err, "/nonexistent/posture: No such file or directory"));
	assert_null(sink_png_sequence(dir, "a/b", err, sizeof err));
	assert_non_null(strstr(err, "'a/b'"));
	assert_null(sink_png_sequence(dir, "", err, sizeof err));
	assert_null(sink_png_latest("/nonexistent/posture/latest.png", err, sizeof err));
	assert_non_null(strstr(err, "/nonexistent/posture"));
	assert_null(sink_png_latest(dir, err, sizeof err));
	assert_non_null(strstr(err, "is a directory"));

	/* a failed write (its temporary name taken by a directory) leaves the file as it was */
	snprintf(path, sizeof path, "%s/latest.png", dir);
	struct sink *s = sink_png_latest(path, err, sizeof err);
	assert_non_null(s);
	struct frame a = make_frame(1, 20, 10, 0), b = make_frame(2, 30, 12, 0);
	assert_int_equal(sink_write(s, &a, err, sizeof err), 0);
	snprintf(tmp, sizeof tmp, "%s.%ld.tmp", path, (long)getpid());
	assert_int_equal(mkdir(tmp, 0755), 0);
	assert_int_equal(sink_write(s, &b, err, sizeof err), -1);
	assert_non_null(strstr(err, tmp));
	assert_non_null(strstr(err, "Is a directory"));
	assert_png_is(path, NULL, 0, &a);
	assert_int_equal(rmdir(tmp), 0);

	/* bad frames: nothing written */
	struct frame z = a;
	z.width = 0;
	assert_int_equal(sink_write(s, &z, err, sizeof err), -1);
	assert_non_null(strstr(err, "size 0x10"));
	z = a;
	z.stride = 4 * z.width - 1;
	assert_int_equal(sink_write(s, &z, err, sizeof err), -1);
	z = a;
	z.rgba = NULL;
	assert_int_equal(sink_write(s, &z, err, sizeof err), -1);
	assert_png_is(path, NULL, 0, &a);
	assert_int_equal(s->failures, 4);
	assert_int_equal(sink_write(s, &b, err, sizeof err), 0);
	assert_png_is(path, NULL, 0, &b);
	sink_close(s);

	/* a failed sequence write takes no number */
	s = sink_png_sequence(dir, "p", err, sizeof err);
	assert_non_null(s);
	snprintf(tmp, sizeof tmp, "%s/.p.%ld.tmp", dir, (long)getpid());
	assert_int_equal(mkdir(tmp, 0755), 0);
	assert_int_equal(sink_write(s, &a, err, sizeof err), -1);
	assert_int_equal(rmdir(tmp), 0);
	assert_int_equal(sink_write(s, &b, err, sizeof err), 0);
	char names[256];
	list_dir(dir, names, sizeof names);
	assert_string_equal(names, "latest.png p-000001.png");
	sink_close(s);
	free(a.rgba);
	free(b.rgba);
}

/* after a first frame of a size, encoding more frames of it allocates nothing */
static void
test_png_encoder_reuse(void **unused)
{
	(void)unused;
	struct sink_png_encoder e;
	char err[256];
	sink_png_encoder_init(&e);
	struct frame f = make_frame(3, 201, 151, 8);
	assert_int_equal(sink_png_encode(&e, &f, err, sizeof err), 0);
	uint64_t allocs = e.allocs;
	srand(5);
	for (int k = 0; k < 20; k++) {
		/* different content each time, some of it incompressible noise */
		for (int i = 0; i < f.height * f.stride; i++)
			f.rgba[i] = (uint8_t)(k % 2 ? rand() : i * k);
		assert_int_equal(sink_png_encode(&e, &f, err, sizeof err), 0);
		assert_png_is(NULL, e.data, e.len, &f);
	}
	assert_int_equal(e.allocs, allocs);
	sink_png_encoder_free(&e);
	free(f.rgba);
}

/* ---- the framebuffer, over files -------------------------------------------- */

struct geo {
	const char *fmt;
	int xres, yres, yvirt, xoff, yoff, line, ypanstep;
};

/* the mode of g; the memory is line * yvirt bytes */
static void
fb_info(const struct geo *g, struct fb_var_screeninfo *var, struct fb_fix_screeninfo *fix)
{
	struct pixfmt pf;
	assert_int_equal(pixfmt_from_name(g->fmt, &pf, NULL, 0), 0);
	memset(var, 0, sizeof *var);
	memset(fix, 0, sizeof *fix);
	var->xres = (uint32_t)g->xres;
	var->yres = (uint32_t)g->yres;
	var->xres_virtual = (uint32_t)(g->line / pf.bytes);
	var->yres_virtual = (uint32_t)g->yvirt;
	var->xoffset = (uint32_t)g->xoff;
	var->yoffset = (uint32_t)g->yoff;
	var->bits_per_pixel = (uint32_t)pf.bpp;
	const struct pixfmt_field *src[4] = { &pf.red, &pf.green, &pf.blue, &pf.transp };
	struct fb_bitfield *dst[4] = { &var->red, &var->green, &var->blue, &var->transp };
	for (int c = 0; c < 4; c++)
		*dst[c] = (struct fb_bitfield){ (uint32_t)src[c]->offset,
						(uint32_t)src[c]->length, 0 };
	fix->type = FB_TYPE_PACKED_PIXELS;
	fix->visual = FB_VISUAL_TRUECOLOR;
	fix->line_length = (uint32_t)g->line;
	fix->smem_len = (uint32_t)(g->line * g->yvirt);
	fix->ypanstep = (uint16_t)g->ypanstep;
}

/* path filled with n junk bytes standing for the framebuffer memory; returns a copy */
static uint8_t *
fb_file(const char *path, size_t n)
{
	uint8_t *b = malloc(n);
	assert_non_null(b);
	for (size_t i = 0; i < n; i++)
		b[i] = (uint8_t)(i * 37 + 11);
	write_all(path, b, n);
	return b;
}

/* mem as it should be after f is drawn at row top: centred, black around */
static void
fb_expect(const struct geo *g, int top, const struct frame *f, uint8_t *mem)
{
	static const uint8_t black[4] = { 0, 0, 0, 255 };
	struct pixfmt pf;
	assert_int_equal(pixfmt_from_name(g->fmt, &pf, NULL, 0), 0);
	int ox = (g->xres - f->width) / 2, oy = (g->yres - f->height) / 2;
	for (int y = 0; y < g->yres; y++) {
		for (int x = 0; x < g->xres; x++) {
			int fx = x - ox, fy = y - oy;
			int in = fx >= 0 && fx < f->width && fy >= 0 && fy < f->height;
			const uint8_t *src = black;
			if (in)
				src = f->rgba + (size_t)fy * f->stride + 4 * fx;
			size_t at = (size_t)(top + y) * g->line + (size_t)(g->xoff + x) * pf.bytes;
			pixfmt_convert_row(&pf, src, 1, mem + at);
		}
	}
}

/* small frames in two formats, byte by byte, with the line padding untouched */
static void
test_fb_exact_bytes(void **state)
{
	char path[128], err[256];
	snprintf(path, sizeof path, "%s/fb", (char *)*state);
	struct fb_var_screeninfo var;
	struct fb_fix_screeninfo fix;
	uint8_t px[8] = { 255, 0, 0, 255, 0, 0, 255, 128 }; /* red, half-transparent blue */
	struct frame f;
	size_t len;

	/* RGB565, 4x3 in lines of 12 bytes: 2x1 lands at (1, 1) */
	static const uint8_t want565[36] = {
		0, 0, 0, 0, 0, 0, 0, 0, 0xee, 0xee, 0xee, 0xee,
		0, 0, 0x00, 0xf8, 0x1f, 0x00, 0, 0, 0xee, 0xee, 0xee, 0xee,
		0, 0, 0, 0, 0, 0, 0, 0, 0xee, 0xee, 0xee, 0xee,
	};
	struct geo g565 = { "RGB565", 4, 3, 3, 0, 0, 12, 0 };
	fb_info(&g565, &var, &fix);
	uint8_t fill[36];
	memset(fill, 0xee, sizeof fill);
	write_all(path, fill, sizeof fill);
	struct sink *s = sink_fb_open_file(path, &var, &fix, err, sizeof err);
	assert_non_null(s);
	assert_string_equal(s->ops->name, "fb");
	frame_init(&f, 2, 1, px);
	assert_int_equal(sink_write(s, &f, err, sizeof err), 0);
	sink_close(s);
	uint8_t *got = read_all(path, &len);
	assert_int_equal(len, 36);
	assert_memory_equal(got, want565, 36);
	free(got);

	/* XRGB8888, 3x2 in lines of 16 bytes: 1x1 lands at (1, 0); X is 0xff */
	static const uint8_t want8888[32] = {
		0, 0, 0, 0xff, 0, 0, 0xff, 0xff, 0, 0, 0, 0xff, 0xee, 0xee, 0xee, 0xee,
		0, 0, 0, 0xff, 0, 0, 0, 0xff, 0, 0, 0, 0xff, 0xee, 0xee, 0xee, 0xee,
	};
	struct geo g8888 = { "XRGB8888", 3, 2, 2, 0, 0, 16, 0 };
	fb_info(&g8888, &var, &fix);
	write_all(path, fill, 32);
	s = sink_fb_open_file(path, &var, &fix, err, sizeof err);
	assert_non_null(s);
	frame_init(&f, 1, 1, px);
	assert_int_equal(sink_write(s, &f, err, sizeof err), 0);
	sink_close(s);
	got = read_all(path, &len);
	assert_memory_equal(got, want8888, 32);
	free(got);
}

/* formats, offsets, padding; frames smaller, larger and mixed against the screen */
static void
test_fb_geometries(void **state)
{
	static const struct geo geos[] = {
		{ "RGB565", 7, 5, 5, 0, 0, 16, 0 },
		{ "RGB888", 6, 4, 9, 2, 3, 30, 0 },
		{ "XBGR8888", 5, 6, 6, 0, 0, 20, 1 },
		{ "BGRA8888", 9, 3, 3, 1, 0, 48, 0 },
		{ "BGR565", 8, 8, 8, 0, 0, 16, 0 },
		{ "RGBX8888", 4, 4, 5, 0, 1, 16, 1 },
	};
	/* smaller, larger, wider, taller, one pixel, the size of the first screen */
	static const int sizes[][2] = {
		{ 3, 2 }, { 12, 11 }, { 11, 2 }, { 2, 9 }, { 1, 1 }, { 7, 5 },
	};
	char path[128], err[256];
	snprintf(path, sizeof path, "%s/fb", (char *)*state);
	for (size_t i = 0; i < sizeof geos / sizeof geos[0]; i++) {
		for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
			const struct geo *g = &geos[i];
			struct fb_var_screeninfo var;
			struct fb_fix_screeninfo fix;
			fb_info(g, &var, &fix);
			uint8_t *want = fb_file(path, fix.smem_len);
			struct sink *s = sink_fb_open_file(path, &var, &fix, err, sizeof err);
			if (!s)
				fail_msg("%s: %s", g->fmt, err);
			assert_int_equal(sink_fb_page(s), -1);
			uint32_t n = (uint32_t)(i * 10 + k);
			struct frame f = make_frame(n, sizes[k][0], sizes[k][1], 4);
			assert_int_equal(sink_write(s, &f, err, sizeof err), 0);
			sink_close(s);
			fb_expect(g, g->yoff, &f, want);
			size_t len;
			uint8_t *got = read_all(path, &len);
			assert_int_equal(len, fix.smem_len);
			if (memcmp(got, want, len) != 0)
				fail_msg("%s %dx%d, frame %dx%d: memory differs", g->fmt, g->xres,
					 g->yres, f.width, f.height);
			free(got);
			free(want);
			free(f.rgba);
		}
	}
}

/* two pages: each write lands in the hidden one, which then becomes visible */
static void
test_fb_double_buffer(void **state)
{
	char path[128], err[256];
	snprintf(path, sizeof path, "%s/fb", (char *)*state);
	struct fb_var_screeninfo var;
	struct fb_fix_screeninfo fix;
	struct frame f[3];
	for (int i = 0; i < 3; i++)
		f[i] = make_frame(100 + (uint32_t)i, 4, 2, 0);

	/* page 0 shown first: frames go to pages 1, 0, 1 */
	struct geo g = { "ARGB8888", 4, 2, 4, 0, 0, 20, 1 };
	fb_info(&g, &var, &fix);
	uint8_t *want = fb_file(path, fix.smem_len);
	struct sink *s = sink_fb_open_file(path, &var, &fix, err, sizeof err);
	assert_non_null(s);
	assert_int_equal(sink_fb_page(s), 0);
	for (int i = 0; i < 3; i++) {
		int page = i % 2 ? 0 : 1;
		assert_int_equal(sink_write(s, &f[i], err, sizeof err), 0);
		assert_int_equal(sink_fb_page(s), page);
		fb_expect(&g, page * g.yres, &f[i], want);
		size_t len;
		uint8_t *got = read_all(path, &len);
		assert_memory_equal(got, want, len); /* the other page keeps the frame before */
		free(got);
	}
	sink_close(s);
	free(want);

	/* page 1 shown first: the first frame goes to page 0 */
	g.yoff = 2;
	fb_info(&g, &var, &fix);
	want = fb_file(path, fix.smem_len);
	s = sink_fb_open_file(path, &var, &fix, err, sizeof err);
	assert_int_equal(sink_fb_page(s), 1);
	assert_int_equal(sink_write(s, &f[0], err, sizeof err), 0);
	assert_int_equal(sink_fb_page(s), 0);
	sink_close(s);
	free(want);

	/* no panning, a pan step that misses yres, or memory for one page: single buffer */
	for (int c = 0; c < 3; c++) {
		struct geo h = { "ARGB8888", 4, 2, 4, 0, 1, 20, c == 0 ? 0 : c == 1 ? 3 : 1 };
		fb_info(&h, &var, &fix);
		if (c == 2)
			fix.smem_len = 20 * 4 - 1;
		want = fb_file(path, fix.smem_len);
		s = sink_fb_open_file(path, &var, &fix, err, sizeof err);
		assert_non_null(s);
		assert_int_equal(sink_fb_page(s), -1);
		assert_int_equal(sink_write(s, &f[c], err, sizeof err), 0);
		sink_close(s);
		fb_expect(&h, h.yoff, &f[c], want);
		size_t len;
		uint8_t *got = read_all(path, &len);
		assert_memory_equal(got, want, len);
		free(got);
		free(want);
	}
	for (int i = 0; i < 3; i++)
		free(f[i].rgba);
}

/* modes we cannot draw are refused with the reason, and the memory is left alone */
static void
test_fb_rejects(void **state)
{
	char path[128], err[256];
	snprintf(path, sizeof path, "%s/fb", (char *)*state);
	struct geo g = { "RGB565", 8, 4, 4, 0, 0, 16, 0 };
	static const char *const why[] = {
		"visual 3", "12 bits per pixel", "msb_right", "grayscale", "nonstd 1",
		"not packed pixels", "line_length 14 is too short", "at least smem_len",
		"smem_len 64 is too small",
	};
	for (int c = 0; c < (int)(sizeof why / sizeof why[0]); c++) {
		struct fb_var_screeninfo var;
		struct fb_fix_screeninfo fix;
		fb_info(&g, &var, &fix);
		uint8_t *before = fb_file(path, fix.smem_len);
		switch (c) {
		case 0: fix.visual = FB_VISUAL_PSEUDOCOLOR; var.bits_per_pixel = 8; break;
		case 1: var.bits_per_pixel = 12; break;
		case 2: var.green.msb_right = 1; break;
		case 3: var.grayscale = 1; break;
		case 4: var.nonstd = 1; break;
		case 5: fix.type = FB_TYPE_PLANES; break;
		case 6: fix.line_length = 14; break;
		case 7: fix.smem_len = 65; break;
		case 8: var.yoffset = 1; break;
		}
		err[0] = '\0';
		assert_null(sink_fb_open_file(path, &var, &fix, err, sizeof err));
		if (!strstr(err, why[c]) || !strstr(err, path))
			fail_msg("case %d: '%s' lacks '%s' or the path", c, err, why[c]);
		size_t len;
		uint8_t *after = read_all(path, &len);
		assert_int_equal(len, 64);
		assert_memory_equal(after, before, len);
		free(after);
		free(before);
	}

	/* no device there; a file is no device; a bad frame changes nothing */
	assert_null(sink_fb_open("/nonexistent/fb0", err, sizeof err));
	assert_non_null(strstr(err, "/nonexistent/fb0: open: No such file or directory"));
	assert_null(sink_fb_open(path, err, sizeof err));
	assert_non_null(strstr(err, "reading the screen info"));
	struct fb_var_screeninfo var;
	struct fb_fix_screeninfo fix;
	fb_info(&g, &var, &fix);
	uint8_t *before = fb_file(path, fix.smem_len);
	struct sink *s = sink_fb_open_file(path, &var, &fix, err, sizeof err);
	assert_non_null(s);
	struct frame f = make_frame(1, 0, 3, 0);
	assert_int_equal(sink_write(s, &f, err, sizeof err), -1);
	assert_non_null(strstr(err, "size 0x3"));
	sink_close(s);
	size_t len;
	uint8_t *after = read_all(path, &len);
	assert_memory_equal(after, before, len);
	free(after);
	free(before);
	free(f.rgba);
}

/* ---- memory -------------------------------------------------------------- */

static void
test_mem_sink(void **unused)
{
	(void)unused;
	char err[256];
	const uint8_t *png, *png2;
	size_t len, len2;
	struct sink *s = sink_mem_open(err, sizeof err);
	assert_non_null(s);
	assert_null(sink_mem_frame(s));
	assert_int_equal(sink_mem_png(s, &png, &len, err, sizeof err), -1);
	assert_non_null(strstr(err, "no frame"));

	/* the copy is packed and exact; its PNG decodes to it and is encoded once */
	struct frame a = make_frame(1, 50, 40, 12), b = make_frame(2, 50, 40, 0);
	struct frame c = make_frame(3, 20, 30, 4);
	assert_int_equal(sink_write(s, &a, err, sizeof err), 0);
	const struct frame *m = sink_mem_frame(s);
	assert_non_null(m);
	assert_int_equal(m->stride, 200);
	assert_int_equal(m->seq, 1);
	assert_true(m->rgba != a.rgba);
	const uint8_t *buf = m->rgba;
	assert_int_equal(sink_mem_png(s, &png, &len, err, sizeof err), 0);
	assert_png_is(NULL, png, len, &a);
	assert_int_equal(sink_mem_png(s, &png2, &len2, err, sizeof err), 0);
	assert_ptr_equal(png2, png);
	assert_int_equal(len2, len);

	/* frames of that size or smaller reuse the buffer */
	assert_int_equal(sink_write(s, &b, err, sizeof err), 0);
	assert_int_equal(sink_mem_png(s, &png, &len, err, sizeof err), 0);
	assert_png_is(NULL, png, len, &b);
	assert_int_equal(sink_write(s, &c, err, sizeof err), 0);
	m = sink_mem_frame(s);
	assert_ptr_equal(m->rgba, buf);
	assert_int_equal(sink_mem_png(s, &png, &len, err, sizeof err), 0);
	assert_png_is(NULL, png, len, &c);

	/* a bad frame keeps the last one */
	struct frame z = a;
	z.height = -1;
	assert_int_equal(sink_write(s, &z, err, sizeof err), -1);
	assert_int_equal(sink_mem_frame(s)->seq, 3);
	assert_png_is(NULL, png, len, &c);
	sink_close(s);

	/* only a memory sink has a PNG to give */
	struct sink *fb = sink_png_sequence("/tmp", "posture-never-written", err, sizeof err);
	assert_non_null(fb);
	assert_int_equal(sink_mem_png(fb, &png, &len, err, sizeof err), -1);
	assert_null(sink_mem_frame(fb));
	sink_close(fb);
	free(a.rgba);
	free(b.rgba);
	free(c.rgba);
}

#define IN_DIR(t) cmocka_unit_test_setup_teardown(t, dir_setup, dir_teardown)

int
main(void)
{
	const struct CMUnitTest tests[] = {
		IN_DIR(test_png_latest_roundtrip),
		IN_DIR(test_png_sequence_naming),
		IN_DIR(test_png_latest_atomic),
		IN_DIR(test_png_errors),
		cmocka_unit_test(test_png_encoder_reuse),
		IN_DIR(test_fb_exact_bytes),
		IN_DIR(test_fb_geometries),
		IN_DIR(test_fb_double_buffer),
		IN_DIR(test_fb_rejects),
		cmocka_unit_test(test_mem_sink),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
