/* test_frame_writer.c - frames handed to sinks on the writer's thread: newest first, drops counted */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <fcntl.h>
#include <linux/fb.h>
#include <png.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "alloc_count.h"
#include "draw/frame_writer.h"
#include "draw/pixfmt.h"

/* ---- a sink the test holds the door of ----------------------------------- */

#define SEEN_MAX 64

/*
 * Records the frames it is given (their seq and first pixel) and, while
 * `hold` is set, keeps the writer's thread inside write until the test
 * opens it: the test decides when the writer is busy. Closing only marks it.
 */
struct gate_sink {
	struct sink base;
	pthread_mutex_t lock;
	pthread_cond_t cond;
	int hold;	/* writes wait while set */
	int inside;	/* a write is waiting at the door */
	int fail_seq;	/* a frame with this seq fails (0: none) */
	int closed;
	int n;
	uint64_t seq[SEEN_MAX];
	uint64_t done[SEEN_MAX]; /* their done_us */
	uint8_t first[SEEN_MAX][4];
	int w[SEEN_MAX], h[SEEN_MAX];
};

static int
gate_write(struct sink *s, const struct frame *f, char *err, size_t errlen)
{
	struct gate_sink *g = (struct gate_sink *)s;
	pthread_mutex_lock(&g->lock);
	g->inside = 1;
	pthread_cond_broadcast(&g->cond);
	while (g->hold)
		pthread_cond_wait(&g->cond, &g->lock);
	g->inside = 0;
	int rc = 0;
	if (g->fail_seq && f->seq == (uint64_t)g->fail_seq) {
		snprintf(err, errlen, "gate: frame %llu refused", (unsigned long long)f->seq);
		rc = -1;
	} else if (g->n < SEEN_MAX) {
		g->seq[g->n] = f->seq;
		g->done[g->n] = f->done_us;
		memcpy(g->first[g->n], f->rgba, 4);
		g->w[g->n] = f->width;
		g->h[g->n] = f->height;
		g->n++;
	}
	pthread_mutex_unlock(&g->lock);
	return rc;
}

static void
gate_close(struct sink *s)
{
	struct gate_sink *g = (struct gate_sink *)s;
	pthread_mutex_lock(&g->lock);
	g->closed = 1;
	pthread_mutex_unlock(&g->lock);
}

static const struct sink_ops gate_ops = { "gate", gate_write, gate_close };

static void
gate_init(struct gate_sink *g)
{
	memset(g, 0, sizeof *g);
	g->base.ops = &gate_ops;
	pthread_mutex_init(&g->lock, NULL);
	pthread_cond_init(&g->cond, NULL);
}

static void
gate_destroy(struct gate_sink *g)
{
	pthread_cond_destroy(&g->cond);
	pthread_mutex_destroy(&g->lock);
}

static void
gate_hold(struct gate_sink *g, int hold)
{
	pthread_mutex_lock(&g->lock);
	g->hold = hold;
	pthread_cond_broadcast(&g->cond);
	pthread_mutex_unlock(&g->lock);
}

/* returns once the writer's thread waits inside a write */
static void
gate_wait_inside(struct gate_sink *g)
{
	pthread_mutex_lock(&g->lock);
	while (!g->inside)
		pthread_cond_wait(&g->cond, &g->lock);
	pthread_mutex_unlock(&g->lock);
}

/* ---- frames ---------------------------------------------------------------- */

/* frame seq of w x h over buf, rows pad bytes apart beyond 4 * w; pixel bytes name the frame */
static struct frame
make_frame(uint8_t *buf, int w, int h, int pad, uint64_t seq)
{
	struct frame f;
	frame_init(&f, w, h, buf);
	f.stride = 4 * w + pad;
	f.seq = seq;
	for (int y = 0; y < h; y++)
		for (int x = 0; x < f.stride; x++)
			buf[y * f.stride + x] = x < 4 * w ? (uint8_t)(seq * 31 + (uint64_t)(y * 7 + x))
							   : 0xee; /* padding: never copied */
	return f;
}

static struct frame_writer *
writer(void)
{
	char err[256];
	struct frame_writer *w = frame_writer_make(0, err, sizeof err);
	assert_non_null(w);
	return w;
}

/* ---- tests ---------------------------------------------------------------- */

/* while the sink is busy, newer frames replace the waiting one: the newest is written next */
static void
test_latest_wins(void **state)
{
	(void)state;
	static uint8_t buf[4 * 8 * 6];
	struct gate_sink g;
	gate_init(&g);
	struct frame_writer *w = writer();
	char err[256];
	assert_int_equal(frame_writer_attach(w, 0, &g.base, 8, 6, err, sizeof err), 0);

	gate_hold(&g, 1);
	struct frame f = make_frame(buf, 8, 6, 0, 1);
	assert_int_equal(frame_writer_submit(w, 0, &f, err, sizeof err), 0);
	gate_wait_inside(&g); /* frame 1 is being written */
	for (uint64_t s = 2; s <= 5; s++) {
		f = make_frame(buf, 8, 6, 0, s);
		assert_int_equal(frame_writer_submit(w, 0, &f, err, sizeof err), 0);
	}
	gate_hold(&g, 0);
	frame_writer_flush(w);

	assert_int_equal(g.n, 2);
	assert_int_equal(g.seq[0], 1);
	assert_int_equal(g.seq[1], 5);
	struct frame_writer_stats st;
	frame_writer_stats(w, &st);
	assert_int_equal(st.written, 2);
	assert_int_equal(st.dropped, 3); /* 2, 3 and 4 */
	assert_int_equal(st.failed, 0);
	frame_writer_free(w);
	assert_true(g.closed);
	gate_destroy(&g);
}

/* the sink gets a packed copy: padding left out, the caller's buffer free at once */
static void
test_frame_is_copied(void **state)
{
	(void)state;
	enum { W = 13, H = 9, PAD = 12 };
	static uint8_t buf[(4 * W + PAD) * H];
	struct gate_sink g;
	gate_init(&g);
	struct frame_writer *w = writer();
	char err[256];
	assert_int_equal(frame_writer_attach(w, 3, &g.base, W, H, err, sizeof err), 0);
	gate_hold(&g, 1);
	struct frame f = make_frame(buf, W, H, PAD, 7);
	assert_int_equal(frame_writer_submit(w, 3, &f, err, sizeof err), 0);
	uint8_t want[4];
	memcpy(want, buf, 4);
	memset(buf, 0, sizeof buf); /* the caller draws the next frame over it */
	gate_hold(&g, 0);
	frame_writer_flush(w);
	assert_int_equal(g.n, 1);
	assert_int_equal(g.w[0], W);
	assert_int_equal(g.h[0], H);
	assert_memory_equal(g.first[0], want, 4);
	frame_writer_free(w);
	gate_destroy(&g);
}

/* a frame is stamped as finished when handed over, unless it came stamped */
static void
test_handed_over_is_stamped(void **state)
{
	(void)state;
	static uint8_t buf[4 * 4 * 4];
	struct gate_sink g;
	gate_init(&g);
	struct frame_writer *w = writer();
	char err[256];
	assert_int_equal(frame_writer_attach(w, 0, &g.base, 4, 4, err, sizeof err), 0);
	struct frame f = make_frame(buf, 4, 4, 0, 1);
	uint64_t before = frame_now_us();
	assert_int_equal(frame_writer_submit(w, 0, &f, err, sizeof err), 0);
	uint64_t after = frame_now_us();
	frame_writer_flush(w);
	f = make_frame(buf, 4, 4, 0, 2);
	f.done_us = 1234;
	assert_int_equal(frame_writer_submit(w, 0, &f, err, sizeof err), 0);
	frame_writer_flush(w);
	assert_int_equal(g.n, 2);
	assert_in_range(g.done[0], before, after);
	assert_int_equal(g.done[1], 1234);
	frame_writer_free(w);
	gate_destroy(&g);
}

/* stopping writes the newest frame still waiting, then joins; nothing is lost but the stale */
static void
test_free_flushes_newest(void **state)
{
	(void)state;
	static uint8_t buf[4 * 4 * 4];
	struct gate_sink g;
	gate_init(&g);
	struct frame_writer *w = writer();
	char err[256];
	assert_int_equal(frame_writer_attach(w, 0, &g.base, 4, 4, err, sizeof err), 0);
	gate_hold(&g, 1);
	struct frame f = make_frame(buf, 4, 4, 0, 1);
	assert_int_equal(frame_writer_submit(w, 0, &f, err, sizeof err), 0);
	gate_wait_inside(&g);
	f = make_frame(buf, 4, 4, 0, 2);
	assert_int_equal(frame_writer_submit(w, 0, &f, err, sizeof err), 0);
	f = make_frame(buf, 4, 4, 0, 3);
	assert_int_equal(frame_writer_submit(w, 0, &f, err, sizeof err), 0);
	gate_hold(&g, 0);
	frame_writer_free(w); /* no flush first */
	assert_int_equal(g.n, 2);
	assert_int_equal(g.seq[1], 3);
	assert_true(g.closed);
	gate_destroy(&g);
}

/* a sink's failure on the thread reaches the caller once, with its message */
static void
test_error_reported(void **state)
{
	(void)state;
	static uint8_t buf[4 * 4 * 4];
	struct gate_sink g;
	gate_init(&g);
	g.fail_seq = 2;
	struct frame_writer *w = writer();
	char err[256];
	assert_int_equal(frame_writer_attach(w, 0, &g.base, 4, 4, err, sizeof err), 0);
	assert_int_equal(frame_writer_error(w, err, sizeof err), 0);
	for (uint64_t s = 1; s <= 3; s++) {
		struct frame f = make_frame(buf, 4, 4, 0, s);
		assert_int_equal(frame_writer_submit(w, 0, &f, err, sizeof err), 0);
		frame_writer_flush(w);
	}
	char msg[256] = "";
	assert_int_equal(frame_writer_error(w, msg, sizeof msg), 1);
	assert_string_equal(msg, "gate: frame 2 refused");
	assert_int_equal(frame_writer_error(w, msg, sizeof msg), 0); /* taken */
	struct frame_writer_stats st;
	frame_writer_stats(w, &st);
	assert_int_equal(st.written, 2);
	assert_int_equal(st.failed, 1);
	assert_int_equal(g.n, 2);
	frame_writer_free(w);
	gate_destroy(&g);
}

/* refusals at the caller: no sink, a bad slot, a frame sinks do not take */
static void
test_refusals(void **state)
{
	(void)state;
	static uint8_t buf[4 * 4 * 4];
	struct frame_writer *w = writer();
	char err[256];
	struct frame f = make_frame(buf, 4, 4, 0, 1);
	assert_int_equal(frame_writer_submit(w, 0, &f, err, sizeof err), -1);
	assert_non_null(strstr(err, "no sink"));
	assert_int_equal(frame_writer_submit(w, FRAME_WRITER_SLOTS, &f, err, sizeof err), -1);
	struct gate_sink g;
	gate_init(&g);
	assert_int_equal(frame_writer_attach(w, 0, &g.base, 4, 4, err, sizeof err), 0);
	f.width = 0;
	assert_int_equal(frame_writer_submit(w, 0, &f, err, sizeof err), -1);
	frame_writer_free(w);
	gate_destroy(&g);
}

/* a sink replaced while it writes is closed by the thread after; the waiting frame goes to the new one */
static void
test_replace_sink(void **state)
{
	(void)state;
	static uint8_t buf[4 * 4 * 4];
	struct gate_sink a, b;
	gate_init(&a);
	gate_init(&b);
	struct frame_writer *w = writer();
	char err[256];
	assert_int_equal(frame_writer_attach(w, 1, &a.base, 4, 4, err, sizeof err), 0);
	gate_hold(&a, 1);
	struct frame f = make_frame(buf, 4, 4, 0, 1);
	assert_int_equal(frame_writer_submit(w, 1, &f, err, sizeof err), 0);
	gate_wait_inside(&a);
	f = make_frame(buf, 4, 4, 0, 2);
	assert_int_equal(frame_writer_submit(w, 1, &f, err, sizeof err), 0);
	assert_int_equal(frame_writer_attach(w, 1, &b.base, 4, 4, err, sizeof err), 0);
	assert_false(a.closed); /* still writing */
	gate_hold(&a, 0);
	frame_writer_flush(w);
	assert_true(a.closed);
	assert_int_equal(a.n, 1);
	assert_int_equal(b.n, 1);
	assert_int_equal(b.seq[0], 2);

	/* emptied: a frame waiting is dropped, later ones refused */
	gate_hold(&b, 1);
	f = make_frame(buf, 4, 4, 0, 3);
	assert_int_equal(frame_writer_submit(w, 1, &f, err, sizeof err), 0);
	gate_wait_inside(&b);
	f = make_frame(buf, 4, 4, 0, 4);
	assert_int_equal(frame_writer_submit(w, 1, &f, err, sizeof err), 0);
	assert_int_equal(frame_writer_attach(w, 1, NULL, 0, 0, err, sizeof err), 0);
	assert_int_equal(frame_writer_submit(w, 1, &f, err, sizeof err), -1);
	gate_hold(&b, 0);
	frame_writer_flush(w);
	assert_true(b.closed);
	assert_int_equal(b.n, 2);
	assert_int_equal(b.seq[1], 3);
	struct frame_writer_stats st;
	frame_writer_stats(w, &st);
	assert_int_equal(st.dropped, 1);
	frame_writer_free(w);
	gate_destroy(&a);
	gate_destroy(&b);
}

/* buffers sized at attach: submitting frames up to that size allocates nothing */
static void
test_no_allocation_per_frame(void **state)
{
	(void)state;
	static uint8_t buf[4 * 64 * 48];
	struct gate_sink g;
	gate_init(&g);
	struct frame_writer *w = writer();
	char err[256];
	assert_int_equal(frame_writer_attach(w, 0, &g.base, 64, 48, err, sizeof err), 0);
#if COUNT_ALLOCS
	long before = allocs;
#endif
	for (uint64_t s = 1; s <= 40; s++) {
		struct frame f = make_frame(buf, s % 2 ? 64 : 32, s % 3 ? 48 : 20, 0, s);
		assert_int_equal(frame_writer_submit(w, 0, &f, err, sizeof err), 0);
	}
	frame_writer_flush(w);
#if COUNT_ALLOCS
	assert_int_equal(allocs, before);
#endif
	frame_writer_free(w);
	gate_destroy(&g);
}

/* the "latest" PNG sink on the thread: the file decodes to the frame submitted last */
static void
test_png_on_thread(void **state)
{
	(void)state;
	enum { W = 37, H = 21 };
	static uint8_t buf[4 * W * H];
	char dir[] = "/tmp/test_frame_writer.XXXXXX", path[128], err[256];
	assert_non_null(mkdtemp(dir));
	snprintf(path, sizeof path, "%s/view.png", dir);
	struct frame_writer *w = writer();
	struct sink *s = sink_png_latest(path, err, sizeof err);
	assert_non_null(s);
	assert_int_equal(frame_writer_attach(w, 0, s, W, H, err, sizeof err), 0);
	struct frame f;
	for (uint64_t k = 1; k <= 5; k++) {
		f = make_frame(buf, W, H, 0, k);
		for (int i = 3; i < 4 * W * H; i += 4)
			buf[i] = 255; /* opaque: PNG keeps straight alpha anyway */
		assert_int_equal(frame_writer_submit(w, 0, &f, err, sizeof err), 0);
	}
	frame_writer_free(w);

	png_image img;
	memset(&img, 0, sizeof img);
	img.version = PNG_IMAGE_VERSION;
	assert_true(png_image_begin_read_from_file(&img, path));
	img.format = PNG_FORMAT_RGBA;
	assert_int_equal(img.width, W);
	assert_int_equal(img.height, H);
	static uint8_t got[4 * W * H];
	assert_true(png_image_finish_read(&img, NULL, got, 0, NULL));
	assert_memory_equal(got, buf, sizeof got);
	unlink(path);
	rmdir(dir);
}

/* png (len bytes) decodes to the w x h frame in want */
static void
assert_png_is(const uint8_t *png, size_t len, const uint8_t *want, int w, int h)
{
	png_image img;
	memset(&img, 0, sizeof img);
	img.version = PNG_IMAGE_VERSION;
	assert_true(png_image_begin_read_from_memory(&img, png, len));
	img.format = PNG_FORMAT_RGBA;
	assert_int_equal(img.width, w);
	assert_int_equal(img.height, h);
	uint8_t *got = malloc(4 * (size_t)w * (size_t)h);
	assert_non_null(got);
	assert_true(png_image_finish_read(&img, NULL, got, 0, NULL));
	assert_memory_equal(got, want, 4 * (size_t)w * (size_t)h);
	free(got);
}

/* the relay: PNGs made on the writer's thread, the newest taken here once */
static void
test_relay(void **state)
{
	(void)state;
	enum { W = 21, H = 17 };
	static uint8_t buf[4 * W * H], last[4 * W * H];
	char err[256];
	struct sink *r = sink_relay_open(err, sizeof err);
	assert_non_null(r);
	const uint8_t *png;
	size_t len;
	struct frame info;
	assert_int_equal(sink_relay_take(r, &png, &len, &info), 0); /* nothing yet */

	struct frame_writer *w = writer();
	assert_int_equal(frame_writer_attach(w, 2, r, W, H, err, sizeof err), 0);
	for (uint64_t k = 1; k <= 4; k++) {
		struct frame f = make_frame(buf, W, H, 0, k);
		for (int i = 3; i < 4 * W * H; i += 4)
			buf[i] = 255;
		assert_int_equal(frame_writer_submit(w, 2, &f, err, sizeof err), 0);
	}
	memcpy(last, buf, sizeof last);
	frame_writer_flush(w);
	assert_int_equal(sink_relay_take(r, &png, &len, &info), 1);
	assert_int_equal(info.seq, 4);
	assert_int_equal(info.width, W);
	assert_int_equal(info.height, H);
	assert_null(info.rgba);
	assert_png_is(png, len, last, W, H);
	assert_int_equal(sink_relay_take(r, &png, &len, &info), 0); /* taken */

	/* written while the last one is held: the held PNG stays whole */
	struct frame f = make_frame(buf, W, H, 0, 5);
	for (int i = 3; i < 4 * W * H; i += 4)
		buf[i] = 255;
	assert_int_equal(frame_writer_submit(w, 2, &f, err, sizeof err), 0);
	frame_writer_flush(w);
	assert_png_is(png, len, last, W, H);
	assert_int_equal(sink_relay_take(r, &png, &len, &info), 1);
	assert_int_equal(info.seq, 5);
	assert_png_is(png, len, buf, W, H);
	frame_writer_free(w); /* closes r */
}

/* the framebuffer (over a file) on the thread: after a burst of frames it shows the newest */
static void
test_fb_shows_newest(void **state)
{
	(void)state;
	enum { W = 24, H = 10 };
	static uint8_t buf[4 * W * H], want[4 * W * H], got[4 * W * H];
	char path[] = "/tmp/test_frame_writer_fb.XXXXXX", err[256];
	int fd = mkstemp(path);
	assert_true(fd >= 0);
	assert_int_equal(ftruncate(fd, sizeof got), 0);
	close(fd);

	/* XRGB8888, W x H, one page: what the visible area holds is the file */
	struct pixfmt pf;
	assert_int_equal(pixfmt_from_name("XRGB8888", &pf, err, sizeof err), 0);
	struct fb_var_screeninfo var = { .xres = W, .yres = H, .xres_virtual = W,
					 .yres_virtual = H, .bits_per_pixel = 32 };
	var.red = (struct fb_bitfield){ (uint32_t)pf.red.offset, (uint32_t)pf.red.length, 0 };
	var.green = (struct fb_bitfield){ (uint32_t)pf.green.offset, (uint32_t)pf.green.length, 0 };
	var.blue = (struct fb_bitfield){ (uint32_t)pf.blue.offset, (uint32_t)pf.blue.length, 0 };
	var.transp = (struct fb_bitfield){ (uint32_t)pf.transp.offset, (uint32_t)pf.transp.length, 0 };
	struct fb_fix_screeninfo fix = { .type = FB_TYPE_PACKED_PIXELS, .visual = FB_VISUAL_TRUECOLOR,
					 .line_length = 4 * W, .smem_len = sizeof got };
	struct sink *s = sink_fb_open_file(path, &var, &fix, err, sizeof err);
	assert_non_null(s);

	struct frame_writer *w = writer();
	assert_int_equal(frame_writer_attach(w, 0, s, W, H, err, sizeof err), 0);
	for (uint64_t k = 1; k <= 30; k++) {
		struct frame f = make_frame(buf, W, H, 0, k);
		assert_int_equal(frame_writer_submit(w, 0, &f, err, sizeof err), 0);
	}
	frame_writer_flush(w);
	for (int y = 0; y < H; y++)
		pixfmt_convert_row(&pf, buf + 4 * W * y, W, want + 4 * W * y);
	fd = open(path, O_RDONLY);
	assert_true(fd >= 0);
	assert_int_equal(read(fd, got, sizeof got), (ssize_t)sizeof got);
	close(fd);
	assert_memory_equal(got, want, sizeof got);
	struct frame_writer_stats st;
	frame_writer_stats(w, &st);
	assert_int_equal(st.written + st.dropped, 30); /* each frame shown or replaced */
	frame_writer_free(w);
	unlink(path);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_latest_wins),
		cmocka_unit_test(test_frame_is_copied),
		cmocka_unit_test(test_handed_over_is_stamped),
		cmocka_unit_test(test_free_flushes_newest),
		cmocka_unit_test(test_error_reported),
		cmocka_unit_test(test_refusals),
		cmocka_unit_test(test_replace_sink),
		cmocka_unit_test(test_no_allocation_per_frame),
		cmocka_unit_test(test_png_on_thread),
		cmocka_unit_test(test_relay),
		cmocka_unit_test(test_fb_shows_newest),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
