/*
 * sink_png.c - PNG encoding, and the two PNG file sinks (see sink.h):
 * a numbered sequence and one "latest" file replaced atomically.
 */
#include "draw/sink.h"

#include <errno.h>
#include <fcntl.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/*
 * Compression: zlib level 2 and the "sub" filter on every row. A frame is
 * encoded on the frame path and goes to a client or a disk at once, so
 * latency counts more than bytes. Measured on the standing-human scene of
 * tools/render-scene (shaded figure, gridded floor, sky; one x86-64 core,
 * libpng 1.6.39), 640x480 and 1280x720:
 *   libpng's default (level 6, adaptive filters)   23 ms  128 KB   57 ms  279 KB
 *   level 3, sub                                  6.9 ms  138 KB   17 ms  302 KB
 *   level 2, sub                                  5.3 ms  145 KB   13 ms  321 KB
 *   level 2, up                                   6.0 ms  189 KB   15 ms  432 KB
 *   level 2, no filter                            5.0 ms  165 KB   12 ms  373 KB
 *   level 1, sub                                  5.0 ms  153 KB   13 ms  338 KB
 * libpng's per-row trial of all five filters costs more than deflate itself
 * at these levels; of the fast settings, "sub" gives the smallest files.
 */
#define SINK_PNG_LEVEL 2
#define SINK_PNG_FILTERS PNG_FILTER_SUB

struct sink_png {
	struct sink base;
	struct sink_png_encoder enc;
	int sequence;	/* 1: numbered files, 0: one latest file */
	int durable;	/* fsync before rename */
	char *dir;	/* sequence: the directory */
	char *prefix;	/* sequence: the file name prefix */
	char *path;	/* the file written next (latest: always the same) */
	size_t pathcap; /* bytes allocated at path */
	char *tmp;	/* the temporary file, renamed onto path */
	uint64_t next;	/* sequence: the number of the next file */
};

/* ---- the encoder ------------------------------------------------------ */

/* libpng's allocator: a free pooled block of the best size, else malloc */
static png_voidp
sink_png_malloc(png_structp png, png_alloc_size_t size)
{
	struct sink_png_encoder *e = png_get_mem_ptr(png);
	int best = -1;
	for (int i = 0; i < e->npool; i++) {
		struct sink_png_block *b = &e->pool[i];
		if (!b->used && b->size >= size && (best < 0 || b->size < e->pool[best].size))
			best = i;
	}
	if (best >= 0) {
		e->pool[best].used = 1;
		return e->pool[best].p;
	}

	/* a new block, pooled while the pool has room */
	void *p = malloc(size);
	e->allocs++;
	if (p && e->npool < SINK_PNG_POOL_MAX)
		e->pool[e->npool++] = (struct sink_png_block){ p, size, 1 };
	return p;
}

static void
sink_png_free(png_structp png, png_voidp p)
{
	struct sink_png_encoder *e = png_get_mem_ptr(png);
	for (int i = 0; i < e->npool; i++) {
		if (e->pool[i].p == p) {
			e->pool[i].used = 0;
			return;
		}
	}
	free(p);
}

static void
sink_png_error(png_structp png, png_const_charp msg)
{
	struct sink_png_encoder *e = png_get_error_ptr(png);
	snprintf(e->msg, sizeof e->msg, "%s", msg);
	png_longjmp(png, 1);
}

static void
sink_png_warning(png_structp png, png_const_charp msg)
{
	(void)png;
	(void)msg;
}

/* appends to e->data, which sink_png_encode sized for the worst case */
static void
sink_png_write_data(png_structp png, png_bytep data, png_size_t n)
{
	struct sink_png_encoder *e = png_get_io_ptr(png);
	if (n > e->cap - e->len) {
		size_t cap = e->cap * 2 > e->len + n ? e->cap * 2 : e->len + n;
		uint8_t *d = realloc(e->data, cap);
		e->allocs++;
		if (!d)
			png_error(png, "out of memory for the PNG data");
		e->data = d;
		e->cap = cap;
	}
	memcpy(e->data + e->len, data, n);
	e->len += n;
}

static void
sink_png_flush(png_structp png)
{
	(void)png;
}

void
sink_png_encoder_init(struct sink_png_encoder *e)
{
	memset(e, 0, sizeof *e);
}

void
sink_png_encoder_free(struct sink_png_encoder *e)
{
	for (int i = 0; i < e->npool; i++)
		free(e->pool[i].p);
	free(e->data);
	memset(e, 0, sizeof *e);
}

int
sink_png_encode(struct sink_png_encoder *e, const struct frame *f, char *err, size_t errlen)
{
	/*
	 * room for the worst case up front (deflate's stored blocks: raw size
	 * plus 5 bytes per 16 KiB, IDAT chunks of 8 KiB with 12 bytes each,
	 * and the fixed chunks), so the buffer never grows while encoding
	 */
	size_t raw = (size_t)f->height * (1 + 4 * (size_t)f->width);
	size_t bound = raw + raw / 2048 + 12 * (raw / 8192 + 2) + 1024;
	if (e->cap < bound) {
		uint8_t *d = realloc(e->data, bound);
		e->allocs++;
		if (!d) {
			snprintf(err, errlen, "png encode: out of memory (%zu bytes)", bound);
			return -1;
		}
		e->data = d;
		e->cap = bound;
	}
	e->len = 0;
	e->msg[0] = '\0';

	png_structp png = png_create_write_struct_2(PNG_LIBPNG_VER_STRING, e, sink_png_error,
						    sink_png_warning, e, sink_png_malloc,
						    sink_png_free);
	png_infop info = png ? png_create_info_struct(png) : NULL;
	if (!info) {
		png_destroy_write_struct(&png, NULL);
		snprintf(err, errlen, "png encode: out of memory for libpng");
		return -1;
	}
	if (setjmp(png_jmpbuf(png))) {
		png_destroy_write_struct(&png, &info);
		snprintf(err, errlen, "png encode: %s", e->msg);
		e->len = 0;
		return -1;
	}

	/* 8-bit RGBA, rows straight from the frame */
	png_set_write_fn(png, e, sink_png_write_data, sink_png_flush);
	png_set_compression_level(png, SINK_PNG_LEVEL);
	png_set_filter(png, PNG_FILTER_TYPE_BASE, SINK_PNG_FILTERS);
	png_set_IHDR(png, info, (png_uint_32)f->width, (png_uint_32)f->height, 8,
		     PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
		     PNG_FILTER_TYPE_DEFAULT);
	png_write_info(png, info);
	for (int y = 0; y < f->height; y++)
		png_write_row(png, f->rgba + (size_t)y * (size_t)f->stride);
	png_write_end(png, info);
	png_destroy_write_struct(&png, &info);
	return 0;
}

/* ---- files ------------------------------------------------------------ */

/*
 * writes data to tmp, fsyncs it when durable, renames it onto path. On
 * failure removes tmp and leaves path alone. Returns 0 or -1 with err set.
 */
static int
sink_png_replace(const char *tmp, const char *path, const uint8_t *data, size_t len, int durable,
		 char *err, size_t errlen)
{
	const char *what = "open";
	int fd = open(tmp, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
	if (fd < 0)
		goto fail;

	/* all bytes, through short writes and signals */
	what = "write";
	for (size_t done = 0; done < len;) {
		ssize_t n = write(fd, data + done, len - done);
		if (n < 0 && errno == EINTR)
			continue;
		if (n <= 0) {
			if (n == 0)
				errno = EIO;
			goto fail;
		}
		done += (size_t)n;
	}
	what = "fsync";
	if (durable && fsync(fd) < 0)
		goto fail;
	what = "close";
	int r = close(fd);
	fd = -1;
	if (r < 0)
		goto fail;
	what = "rename";
	if (rename(tmp, path) < 0)
		goto fail;
	return 0;

fail:;
	int e = errno;
	if (fd >= 0)
		close(fd);
	unlink(tmp);
	if (e == 0)
		e = EIO;
	if (strcmp(what, "rename") == 0)
		snprintf(err, errlen, "png: rename %s to %s: %s", tmp, path, strerror(e));
	else
		snprintf(err, errlen, "png: %s %s: %s", what, tmp, strerror(e));
	return -1;
}

static int
sink_png_write(struct sink *s, const struct frame *f, char *err, size_t errlen)
{
	struct sink_png *p = (struct sink_png *)s;
	if (sink_png_encode(&p->enc, f, err, errlen) < 0)
		return -1;
	if (p->sequence)
		snprintf(p->path, p->pathcap, "%s/%s-%06llu.png", p->dir, p->prefix,
			 (unsigned long long)p->next);
	if (sink_png_replace(p->tmp, p->path, p->enc.data, p->enc.len, p->durable, err,
			     errlen) < 0)
		return -1;
	p->next++;
	return 0;
}

static void
sink_png_close(struct sink *s)
{
	struct sink_png *p = (struct sink_png *)s;
	sink_png_encoder_free(&p->enc);
	free(p->dir);
	free(p->prefix);
	free(p->path);
	free(p->tmp);
	free(p);
}

static const struct sink_ops sink_png_sequence_ops = {
	.name = "png-sequence",
	.write = sink_png_write,
	.close = sink_png_close,
};

static const struct sink_ops sink_png_latest_ops = {
	.name = "png-latest",
	.write = sink_png_write,
	.close = sink_png_close,
};

/* 0 when dir is a directory we may create files in, else -1 with err set */
static int
sink_png_check_dir(const char *dir, char *err, size_t errlen)
{
	struct stat st;
	if (stat(dir, &st) < 0) {
		snprintf(err, errlen, "png: directory %s: %s", dir, strerror(errno));
		return -1;
	}
	if (!S_ISDIR(st.st_mode)) {
		snprintf(err, errlen, "png: %s is not a directory", dir);
		return -1;
	}
	if (access(dir, W_OK | X_OK) < 0) {
		snprintf(err, errlen, "png: directory %s: %s", dir, strerror(errno));
		return -1;
	}
	return 0;
}

/* a new sink with its names allocated, or NULL (out of memory, err set) */
static struct sink_png *
sink_png_alloc(const struct sink_ops *ops, size_t pathcap, size_t tmpcap, char *err,
	       size_t errlen)
{
	struct sink_png *p = calloc(1, sizeof *p);
	if (p) {
		p->path = malloc(pathcap);
		p->tmp = malloc(tmpcap);
	}
	if (!p || !p->path || !p->tmp) {
		if (p) {
			free(p->path);
			free(p->tmp);
		}
		free(p);
		snprintf(err, errlen, "png: out of memory");
		return NULL;
	}
	p->base.ops = ops;
	p->pathcap = pathcap;
	sink_png_encoder_init(&p->enc);
	p->next = 1;
	return p;
}

struct sink *
sink_png_sequence(const char *dir, const char *prefix, char *err, size_t errlen)
{
	if (!prefix || !prefix[0] || strchr(prefix, '/')) {
		snprintf(err, errlen, "png: file prefix '%s' must be non-empty and without '/'",
			 prefix ? prefix : "");
		return NULL;
	}
	if (sink_png_check_dir(dir, err, errlen) < 0)
		return NULL;

	/* DIR/PREFIX-<up to 20 digits>.png; the temporary DIR/.PREFIX.<pid>.tmp */
	size_t n = strlen(dir) + strlen(prefix) + 48;
	struct sink_png *p = sink_png_alloc(&sink_png_sequence_ops, n, n, err, errlen);
	if (!p)
		return NULL;
	p->sequence = 1;
	p->durable = 0;
	p->dir = strdup(dir);
	p->prefix = strdup(prefix);
	if (!p->dir || !p->prefix) {
		sink_png_close(&p->base);
		snprintf(err, errlen, "png: out of memory");
		return NULL;
	}
	snprintf(p->tmp, n, "%s/.%s.%ld.tmp", dir, prefix, (long)getpid());
	return &p->base;
}

struct sink *
sink_png_latest(const char *path, char *err, size_t errlen)
{
	if (!path || !path[0]) {
		snprintf(err, errlen, "png: empty path for the latest frame");
		return NULL;
	}

	/* the file's directory must take new files (the temporary one) */
	const char *slash = strrchr(path, '/');
	char *dir = slash ? strndup(path, (size_t)(slash - path)) : strdup(".");
	if (!dir) {
		snprintf(err, errlen, "png: out of memory");
		return NULL;
	}
	int r = sink_png_check_dir(dir[0] ? dir : "/", err, errlen);
	free(dir);
	if (r < 0)
		return NULL;
	struct stat st;
	if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
		snprintf(err, errlen, "png: %s is a directory", path);
		return NULL;
	}

	/* PATH itself, and PATH.<pid>.tmp */
	size_t n = strlen(path) + 32;
	struct sink_png *p = sink_png_alloc(&sink_png_latest_ops, n, n, err, errlen);
	if (!p)
		return NULL;
	p->sequence = 0;
	p->durable = 1;
	snprintf(p->path, n, "%s", path);
	snprintf(p->tmp, n, "%s.%ld.tmp", path, (long)getpid());
	return &p->base;
}
