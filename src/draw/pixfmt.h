/*
 * pixfmt.h - packed pixel formats, and exact conversion from 8-bit RGBA.
 *
 * A format is described as fbdev does (struct fb_var_screeninfo): a pixel is
 * an unsigned integer of bpp bits (16, 24 or 32) stored LITTLE-ENDIAN in
 * bpp / 8 bytes, and each channel occupies the bits offset .. offset+length-1
 * of that integer (bit 0 = least significant). This is fbdev's layout on
 * little-endian machines and DRM's fourcc convention everywhere; big-endian
 * framebuffers are not supported.
 *
 * Named formats follow DRM (drm_fourcc.h): the letters list the channels from
 * the MOST significant bit of the pixel value down to bit 0, so the bytes in
 * memory come in the REVERSE order of the letters ("RGBA8888" is NOT the byte
 * order R,G,B,A; that is "ABGR8888"). X is padding.
 *
 *   name       bpp  bits (msb..lsb)          bytes in memory, lowest address first
 *   RGB565      16  R15-11 G10-5  B4-0       [G2-0 B4-0] [R4-0 G5-3]
 *   BGR565      16  B15-11 G10-5  R4-0       [G2-0 R4-0] [B4-0 G5-3]
 *   RGB888      24  R23-16 G15-8  B7-0       B G R
 *   BGR888      24  B23-16 G15-8  R7-0       R G B
 *   XRGB8888    32  X R G B                  B G R X
 *   ARGB8888    32  A R G B                  B G R A
 *   XBGR8888    32  X B G R                  R G B X
 *   ABGR8888    32  A B G R                  R G B A
 *   RGBX8888    32  R G B X                  X B G R
 *   RGBA8888    32  R G B A                  A B G R
 *   BGRX8888    32  B G R X                  X R G B
 *   BGRA8888    32  B G R A                  A R G B
 *
 * So pure red (255,0,0) in RGB565 is the value 0xf800, bytes 0x00 0xf8.
 *
 * Conversion rule, exact and the same for every channel width n (1..16):
 *     out = (v * (2^n - 1) + 127) / 255      (integer division)
 * which is v * (2^n - 1) / 255 rounded to the nearest integer (the quotient
 * is never exactly halfway, so there is no tie rule to choose). It reduces
 * (n < 8), keeps (n = 8) and expands (n > 8): 0 -> 0 and 255 -> 2^n - 1
 * always, e.g. 5 bits: 128 -> 16, 10 bits: 1 -> 4, 43 -> 173.
 * Alpha is converted the same way from the frame's alpha when the format
 * has a transp field. Every bit that no field covers (the X of the formats
 * above) is written as 1, so X bytes are 0xff: a reader that takes X for
 * alpha still sees an opaque pixel.
 */
#ifndef POSTURE_PIXFMT_H
#define POSTURE_PIXFMT_H

#include <stddef.h>
#include <stdint.h>

/* one channel, as fbdev's struct fb_bitfield */
struct pixfmt_field {
	int offset;    /* bit position of the channel's least significant bit */
	int length;    /* bits; 0 = absent (allowed for transp only) */
	int msb_right; /* fbdev's flag; anything but 0 is rejected */
};

/*
 * the description (bpp and the four fields) is filled by the caller, then
 * pixfmt_init checks it and derives the rest. Supported: bpp 16, 24 or 32;
 * red, green, blue 1..16 bits, transp 0..16 bits; every field inside the
 * pixel, no two overlapping, msb_right 0. Palettes (8 bpp and below) and
 * FOURCC modes are fbdev matters that sink_fb.c rejects before this.
 */
struct pixfmt {
	int bpp; /* bits per pixel: 16, 24 or 32 */
	struct pixfmt_field red, green, blue, transp;

	/* derived by pixfmt_init */
	int bytes;	       /* bpp / 8 */
	uint32_t pad;	       /* bits no field covers, always written as 1 */
	uint32_t lut[4][256];  /* R, G, B, A 8-bit value -> its bits in place */
	int xrgb;              /* 32-bit, red, green, blue in bytes 2, 1, 0: converted without tables */
};

/*
 * checks pf's description and derives its tables. Returns 0, or -1 with a
 * message in err naming what is unsupported (pf then unusable).
 */
int pixfmt_init(struct pixfmt *pf, char *err, size_t errlen);

/*
 * dest: the named format of the table above, initialised. Returns 0, or -1
 * with a message in err for an unknown name.
 */
int pixfmt_from_name(const char *name, struct pixfmt *dest, char *err, size_t errlen);

/* the table's name for pf's layout, or NULL when it has none */
const char *pixfmt_name(const struct pixfmt *pf);

/* dest: a short text like "32 bpp r16:8 g8:8 b0:8 a0:0" (offset:length), for messages */
void pixfmt_describe(const struct pixfmt *pf, char *dest, size_t len);

/*
 * converts n RGBA pixels (4 bytes each) to n * pf->bytes bytes at dest.
 * pf must have been initialised; never fails.
 */
void pixfmt_convert_row(const struct pixfmt *pf, const uint8_t *rgba, int n, uint8_t *dest);

#endif
