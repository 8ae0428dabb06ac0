/*
 * sink.h - where finished frames go: PNG files, a Linux framebuffer, memory.
 *
 * One small table of functions per kind of sink, one file per backend:
 *   sink_png.c   numbered PNG files, or one "latest" PNG replaced atomically
 *   sink_fb.c    /dev/fbN (or an ordinary file with a given fbdev geometry)
 *   sink_mem.c   the latest frame kept in memory, with its PNG on demand
 *   sink_relay.c each frame as PNG, made on the writing thread, taken by another
 * Callers go through sink_write / sink_close. Every write returns 0, or -1
 * with a message naming what failed (the path, the errno text); a failed
 * write leaves the previous frame in place (file untouched, screen
 * unchanged, memory frame kept). Sinks are single-threaded objects, but for
 * sink_relay_take, made to be called from another thread than the writes.
 */
#ifndef POSTURE_SINK_H
#define POSTURE_SINK_H

#include <stddef.h>
#include <stdint.h>

#include "draw/frame.h"

/* largest frame side accepted, in pixels: rows and byte counts stay far below INT_MAX */
#define SINK_FRAME_SIDE_MAX 16384

struct sink;

struct sink_ops {
	const char *name;
	/* frame already checked by sink_write; 0, or -1 with err filled */
	int (*write)(struct sink *s, const struct frame *f, char *err, size_t errlen);
	/* releases everything, s included */
	void (*close)(struct sink *s);
};

/* the head of every backend's own struct */
struct sink {
	const struct sink_ops *ops;
	uint64_t frames;   /* writes that succeeded */
	uint64_t failures; /* writes that returned -1 */
};

/*
 * 0 when f is a frame sinks accept: 1..SINK_FRAME_SIDE_MAX pixels each way,
 * pixels present, stride >= 4 * width; else -1 with a message.
 */
int sink_frame_check(const struct frame *f, char *err, size_t errlen);

/* checks f, then hands it to s. Returns 0, or -1 with a message in err */
int sink_write(struct sink *s, const struct frame *f, char *err, size_t errlen);

/* closes s and frees it; NULL is allowed */
void sink_close(struct sink *s);

/*
 * Numbered PNG files DIR/PREFIX-000001.png, -000002.png, ... numbered by a
 * counter of successful writes starting at 1, not by frame->seq: the numbers
 * stay contiguous when the renderer skips frames, which is what video tools
 * expect (ffmpeg -i PREFIX-%06d.png); the counter widens past 999999.
 * Each file is written to a temporary name and renamed, so it appears
 * complete or not at all; files of an earlier run with the same names are
 * replaced. prefix must be non-empty and contain no '/'. dir must exist.
 * Returns the sink, or NULL with a message in err.
 */
struct sink *sink_png_sequence(const char *dir, const char *prefix, char *err, size_t errlen);

/*
 * ONE file at path, replaced atomically on every write: the PNG goes to
 * PATH.PID.tmp, which is fsync'ed and then rename()d over PATH, so a reader
 * opening PATH always gets a whole frame, the previous or the new one. A
 * failed write removes its temporary file and leaves PATH as it was.
 * Returns the sink, or NULL with a message in err.
 */
struct sink *sink_png_latest(const char *path, char *err, size_t errlen);

/*
 * A Linux framebuffer device (/dev/fbN): the frame is drawn centred into the
 * visible xres x yres area, cropped when larger, the rest of that area
 * black, converted to the device's pixel format (pixfmt.h). When
 * yres_virtual >= 2 * yres and the driver can pan by yres, frames alternate
 * between two pages: drawn into the hidden one, then shown by
 * FBIOPAN_DISPLAY; if panning fails, the sink falls back for good to drawing
 * into the visible page. Palette, grayscale, FOURCC and bit-reversed modes
 * are refused. The video mode itself is never changed.
 * Returns the sink, or NULL with a message in err.
 */
struct sink *sink_fb_open(const char *device, char *err, size_t errlen);

struct fb_var_screeninfo;
struct fb_fix_screeninfo;

/*
 * The same sink over an ordinary file standing for the framebuffer memory
 * (at least fix->smem_len bytes), with the geometry and format given instead
 * of read by ioctl: the same checks, drawing and conversion, and "panning"
 * only records which page is visible. For tests and for capturing what a
 * device would show.
 */
struct sink *sink_fb_open_file(const char *path, const struct fb_var_screeninfo *var,
			       const struct fb_fix_screeninfo *fix, char *err, size_t errlen);

/* the visible page (0: yoffset 0, 1: yoffset yres) when s double-buffers, else -1 */
int sink_fb_page(const struct sink *s);

/* the framebuffer's visible size (xres x yres) into *w, *h: 0, or -1 for another sink */
int sink_fb_size(const struct sink *s, int *w, int *h);

/*
 * A screen through DRM/KMS (sink_kms.c): on card (/dev/dri/cardN; NULL: the
 * first card that can show something), the connector named (NULL or "":
 * the first connected one) in mode ("WxH" or "WxH@HZ"; NULL or "": the
 * preferred one); two XRGB8888 dumb buffers, the frame drawn centred into
 * the one not shown, then a page flip; a frame that finds the last flip
 * still pending after 100 ms is skipped (counted). On close the CRTC as it
 * was is restored. Returns the sink, or NULL with why in err (which card,
 * which step: no KMS, nothing connected, no such mode, not DRM master...).
 */
struct sink *sink_kms_open(const char *card, const char *connector, const char *mode, char *err,
			   size_t errlen);
/* the mode's size, and "CARD CONNECTOR WxH@HZ" */
void sink_kms_info(const struct sink *s, int *w, int *h, char *desc, size_t desclen);
/* the buffer shown now (XRGB8888, rows pitch apart), flips done and frames skipped: for tests */
const uint8_t *sink_kms_front(const struct sink *s, uint32_t *pitch, uint64_t *flips,
			      uint64_t *dropped);
/* DRM master given up (on 0: the VT switched away) or taken back (on 1): 0, or -1 (errno) */
int sink_kms_master(struct sink *s, int on);
/*
 * The card's connectors read again (a hot-plug): the screen chosen anew as
 * at open; 0 when it is what shows already, 1 when the mode was set anew
 * (on another connector, or another size: new buffers), -1 with err (then
 * nothing shows until a later re-probe finds a screen).
 */
int sink_kms_reprobe(struct sink *s, char *err, size_t errlen);
/* waits (100 ms at most) for the flip in flight: 0 when none is left */
int sink_kms_settle(struct sink *s);
struct kms_times_summary;
/*
 * Render to flip request over the newest frames (kms_pick.h): from the
 * frame's done_us (else the write's start) to drmModePageFlip returning,
 * and its parts. Safe to call from another thread than the writes.
 */
void sink_kms_times(struct sink *s, struct kms_times_summary *dest);

/*
 * Keeps a copy of the latest frame for the daemon to send to clients. The
 * pixel buffer only grows, so frames no larger than one seen before cost no
 * allocation; the PNG is encoded on demand, once per frame.
 * Returns the sink, or NULL with a message in err.
 */
struct sink *sink_mem_open(char *err, size_t errlen);

/* the latest frame written to memory sink s (rgba owned by s), or NULL before the first */
const struct frame *sink_mem_frame(const struct sink *s);

/*
 * *data, *len: the latest frame of memory sink s as PNG, valid until the next
 * write or close. Returns 0, or -1 with a message (no frame yet, encoding
 * failed).
 */
int sink_mem_png(struct sink *s, const uint8_t **data, size_t *len, char *err, size_t errlen);

/*
 * Encodes each frame written as PNG and keeps the newest for another
 * thread to take: a frame writer's thread encodes (frame_writer.h), the
 * loop takes the PNG and sends it. Allocates only while the PNGs grow.
 * Returns the sink, or NULL with a message in err.
 */
struct sink *sink_relay_open(char *err, size_t errlen);

/*
 * The newest PNG written to relay sink s and not taken yet: 1 with *data,
 * *len (valid until the next take; 0 when that frame's encoding failed)
 * and *info (the frame's size, seq and time; no pixels), else 0. Safe
 * against writes on another thread; one taking thread.
 */
int sink_relay_take(struct sink *s, const uint8_t **data, size_t *len, struct frame *info);

/*
 * A reusable PNG encoder (sink_png.c) for the PNG and memory sinks. libpng's
 * working memory (its structs, zlib's window and hash tables, row buffers)
 * comes from a small pool kept across frames and the output buffer only
 * grows, so encoding frames of a size seen before allocates nothing.
 * Encoding uses zlib level 2 with the "sub" row filter: frames are encoded for
 * latency (on the frame path), size comes second: 4x faster than libpng's
 * default for files 12% larger (measurements in sink_png.c).
 */
#define SINK_PNG_POOL_MAX 24

struct sink_png_block {
	void *p;
	size_t size;
	int used;
};

struct sink_png_encoder {
	uint8_t *data; /* the last PNG: len bytes, cap allocated */
	size_t len, cap;
	struct sink_png_block pool[SINK_PNG_POOL_MAX];
	int npool;
	uint64_t allocs; /* calls to malloc/realloc so far (tests check it stays put) */
	char msg[160];	 /* libpng's message while encoding */
};

void sink_png_encoder_init(struct sink_png_encoder *e);
void sink_png_encoder_free(struct sink_png_encoder *e);

/*
 * encodes f (already checked) as an 8-bit RGBA PNG into e->data, e->len.
 * Returns 0, or -1 with a message in err (out of memory, libpng error).
 */
int sink_png_encode(struct sink_png_encoder *e, const struct frame *f, char *err, size_t errlen);

#endif
