/*
 * sink_fb.c - frames onto a Linux framebuffer (fbdev), see sink.h.
 *
 * The device part is thin: sink_fb_open reads the geometry with two ioctls
 * and pans with a third; everything else (checks, format, drawing, page
 * choice) is shared with sink_fb_open_file, which the tests drive.
 */
#include "draw/sink.h"

#include <errno.h>
#include <fcntl.h>
#include <linux/fb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "draw/pixfmt.h"
#include "draw/scanout.h"

#define SINK_FB_SIDE_MAX 65536 /* xres, yres and their virtual sizes */

/*
 * The visible area is xres x yres at (xoffset, top) of the framebuffer
 * memory, rows line_length bytes apart. Double-buffered, the two pages are
 * the rows 0 .. yres-1 and yres .. 2*yres-1 (at the same xoffset), and top
 * follows the page shown; single-buffered, top is the mode's yoffset.
 */
struct sink_fb {
	struct sink base;
	int fd;
	int is_device;		      /* 0: an ordinary file, panning only recorded */
	uint8_t *mem;		      /* the framebuffer memory, memlen bytes mapped */
	size_t memlen;
	struct pixfmt pf;
	struct fb_var_screeninfo var; /* the mode; its offsets are what we last panned to */
	int xres, yres, xoffset, top;
	size_t line_length;
	int dbuf;		      /* 1 while double buffering */
	int page;		      /* dbuf: the visible page, 0 or 1 */
	uint8_t black[4];	      /* an opaque black pixel in pf */
	char *name;		      /* device or file path, for messages */
};

/* draws f centred and cropped into the xres x yres area whose top row is top */
static void
sink_fb_draw(struct sink_fb *fb, const struct frame *f, int top)
{
	scanout_draw(&fb->pf, fb->black, f,
		     fb->mem + (size_t)top * fb->line_length + (size_t)fb->xoffset * (size_t)fb->pf.bytes,
		     fb->line_length, fb->xres, fb->yres);
}

/* shows page p: FBIOPAN_DISPLAY on a device, bookkeeping only on a file. 0 or -1 */
static int
sink_fb_pan(struct sink_fb *fb, int p)
{
	struct fb_var_screeninfo v = fb->var;
	v.yoffset = (uint32_t)(p * fb->yres);
	v.activate = FB_ACTIVATE_VBL; /* at the next vertical blank, where the driver can */
	if (fb->is_device && ioctl(fb->fd, FBIOPAN_DISPLAY, &v) < 0)
		return -1;
	fb->var.yoffset = v.yoffset;
	fb->page = p;
	fb->top = p * fb->yres;
	return 0;
}

static int
sink_fb_write(struct sink *s, const struct frame *f, char *err, size_t errlen)
{
	struct sink_fb *fb = (struct sink_fb *)s;
	(void)err;
	(void)errlen;

	/* into the hidden page, then show it */
	if (fb->dbuf) {
		int hidden = 1 - fb->page;
		sink_fb_draw(fb, f, hidden * fb->yres);
		if (sink_fb_pan(fb, hidden) == 0)
			return 0;
		/* the driver cannot pan after all: single buffering from now on */
		fb->dbuf = 0;
	}
	sink_fb_draw(fb, f, fb->top);
	return 0;
}

static void
sink_fb_close(struct sink *s)
{
	struct sink_fb *fb = (struct sink_fb *)s;
	if (fb->mem)
		munmap(fb->mem, fb->memlen);
	if (fb->fd >= 0)
		close(fb->fd);
	free(fb->name);
	free(fb);
}

static const struct sink_ops sink_fb_ops = {
	.name = "fb",
	.write = sink_fb_write,
	.close = sink_fb_close,
};

static void
sink_fb_field(const struct fb_bitfield *b, struct pixfmt_field *dest)
{
	dest->offset = b->offset > 64 ? 64 : (int)b->offset;
	dest->length = b->length > 64 ? 64 : (int)b->length;
	dest->msb_right = b->msb_right != 0;
}

/*
 * checks the mode and derives the format and the areas; fb->name set.
 * Returns 0, or -1 with a message naming the device or file.
 */
static int
sink_fb_setup(struct sink_fb *fb, const struct fb_var_screeninfo *var,
	      const struct fb_fix_screeninfo *fix, char *err, size_t errlen)
{
	char msg[200];

	/* packed true colour only: no planes, palettes, grayscale or FOURCC modes */
	if (fix->type != FB_TYPE_PACKED_PIXELS) {
		snprintf(err, errlen, "fb %s: framebuffer type %u is not packed pixels", fb->name,
			 fix->type);
		return -1;
	}
	if (fix->visual != FB_VISUAL_TRUECOLOR) {
		snprintf(err, errlen, "fb %s: visual %u is not supported (palette, mono or "
			 "direct colour; only true colour is)", fb->name, fix->visual);
		return -1;
	}
	if (var->grayscale != 0 || var->nonstd != 0) {
		snprintf(err, errlen, "fb %s: grayscale, FOURCC or non-standard pixel mode "
			 "(grayscale %u, nonstd %u) is not supported", fb->name, var->grayscale,
			 var->nonstd);
		return -1;
	}

	/* the pixel format */
	memset(&fb->pf, 0, sizeof fb->pf);
	fb->pf.bpp = var->bits_per_pixel > 64 ? 64 : (int)var->bits_per_pixel;
	sink_fb_field(&var->red, &fb->pf.red);
	sink_fb_field(&var->green, &fb->pf.green);
	sink_fb_field(&var->blue, &fb->pf.blue);
	sink_fb_field(&var->transp, &fb->pf.transp);
	if (pixfmt_init(&fb->pf, msg, sizeof msg) < 0) {
		char desc[96];
		pixfmt_describe(&fb->pf, desc, sizeof desc);
		snprintf(err, errlen, "fb %s: %s [%s]", fb->name, msg, desc);
		return -1;
	}
	static const uint8_t opaque_black[4] = { 0, 0, 0, 255 };
	pixfmt_convert_row(&fb->pf, opaque_black, 1, fb->black);

	/* the visible area inside the memory */
	if (var->xres < 1 || var->yres < 1 || var->xres > SINK_FB_SIDE_MAX ||
	    var->yres > SINK_FB_SIDE_MAX || var->xoffset > SINK_FB_SIDE_MAX ||
	    var->yoffset > SINK_FB_SIDE_MAX || var->yres_virtual > SINK_FB_SIDE_MAX) {
		snprintf(err, errlen, "fb %s: geometry %ux%u at %u,%u is out of range", fb->name,
			 var->xres, var->yres, var->xoffset, var->yoffset);
		return -1;
	}
	fb->xres = (int)var->xres;
	fb->yres = (int)var->yres;
	fb->xoffset = (int)var->xoffset;
	fb->top = (int)var->yoffset;
	fb->line_length = fix->line_length;
	fb->memlen = fix->smem_len;
	if ((size_t)(fb->xoffset + fb->xres) * (size_t)fb->pf.bytes > fb->line_length) {
		snprintf(err, errlen, "fb %s: line_length %u is too short for %u pixels at "
			 "xoffset %u (%d bytes each)", fb->name, fix->line_length, var->xres,
			 var->xoffset, fb->pf.bytes);
		return -1;
	}
	if ((size_t)(fb->top + fb->yres) * fb->line_length > fb->memlen) {
		snprintf(err, errlen, "fb %s: smem_len %u is too small for %u rows of %u bytes "
			 "at yoffset %u", fb->name, fix->smem_len, var->yres, fix->line_length,
			 var->yoffset);
		return -1;
	}

	/* two pages when the memory holds them and the driver pans by whole pages */
	fb->var = *var;
	fb->dbuf = var->yres_virtual >= 2 * var->yres && fix->ypanstep > 0 &&
		   var->yres % fix->ypanstep == 0 &&
		   (size_t)(2 * fb->yres) * fb->line_length <= fb->memlen;
	fb->page = fb->dbuf && fb->top >= fb->yres ? 1 : 0;
	return 0;
}

/* the shared part of both constructors: fb->fd open, fb->name set; consumes fb */
static struct sink *
sink_fb_finish(struct sink_fb *fb, const struct fb_var_screeninfo *var,
	       const struct fb_fix_screeninfo *fix, char *err, size_t errlen)
{
	if (sink_fb_setup(fb, var, fix, err, errlen) < 0)
		goto fail;
	void *m = mmap(NULL, fb->memlen, PROT_READ | PROT_WRITE, MAP_SHARED, fb->fd, 0);
	if (m == MAP_FAILED) {
		snprintf(err, errlen, "fb %s: mmap of %zu bytes: %s", fb->name, fb->memlen,
			 strerror(errno));
		goto fail;
	}
	fb->mem = m;
	return &fb->base;

fail:
	sink_fb_close(&fb->base);
	return NULL;
}

/* a sink_fb with path opened read-write, or NULL with err set */
static struct sink_fb *
sink_fb_alloc(const char *path, char *err, size_t errlen)
{
	struct sink_fb *fb = calloc(1, sizeof *fb);
	char *name = strdup(path ? path : "");
	if (!fb || !name) {
		free(fb);
		free(name);
		snprintf(err, errlen, "fb %s: out of memory", path ? path : "");
		return NULL;
	}
	fb->base.ops = &sink_fb_ops;
	fb->name = name;
	fb->fd = open(path, O_RDWR | O_CLOEXEC);
	if (fb->fd < 0) {
		snprintf(err, errlen, "fb %s: open: %s", path, strerror(errno));
		sink_fb_close(&fb->base);
		return NULL;
	}
	return fb;
}

struct sink *
sink_fb_open(const char *device, char *err, size_t errlen)
{
	struct sink_fb *fb = sink_fb_alloc(device, err, errlen);
	if (!fb)
		return NULL;
	fb->is_device = 1;
	struct fb_var_screeninfo var;
	struct fb_fix_screeninfo fix;
	if (ioctl(fb->fd, FBIOGET_VSCREENINFO, &var) < 0 ||
	    ioctl(fb->fd, FBIOGET_FSCREENINFO, &fix) < 0) {
		snprintf(err, errlen, "fb %s: reading the screen info: %s", device,
			 strerror(errno));
		sink_fb_close(&fb->base);
		return NULL;
	}
	return sink_fb_finish(fb, &var, &fix, err, errlen);
}

struct sink *
sink_fb_open_file(const char *path, const struct fb_var_screeninfo *var,
		  const struct fb_fix_screeninfo *fix, char *err, size_t errlen)
{
	struct sink_fb *fb = sink_fb_alloc(path, err, errlen);
	if (!fb)
		return NULL;
	struct stat st;
	if (fstat(fb->fd, &st) < 0 || !S_ISREG(st.st_mode) ||
	    (uint64_t)st.st_size < fix->smem_len) {
		snprintf(err, errlen, "fb %s: not a regular file of at least smem_len %u bytes",
			 path, fix->smem_len);
		sink_fb_close(&fb->base);
		return NULL;
	}
	return sink_fb_finish(fb, var, fix, err, errlen);
}

int
sink_fb_page(const struct sink *s)
{
	const struct sink_fb *fb = (const struct sink_fb *)s;
	if (s->ops != &sink_fb_ops || !fb->dbuf)
		return -1;
	return fb->page;
}

int
sink_fb_size(const struct sink *s, int *w, int *h)
{
	const struct sink_fb *fb = (const struct sink_fb *)s;
	if (s->ops != &sink_fb_ops)
		return -1;
	*w = fb->xres;
	*h = fb->yres;
	return 0;
}
