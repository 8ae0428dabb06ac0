/* pixfmt.c - packed pixel formats and exact RGBA conversion (see pixfmt.h) */
#include "draw/pixfmt.h"

#include <stdio.h>
#include <string.h>

#define PIXFMT_CHANNEL_BITS_MAX 16

/* the named formats: bpp, then offset and length of R, G, B, A (DRM fourcc order) */
static const struct pixfmt_named {
	const char *name;
	int bpp;
	int r_off, r_len, g_off, g_len, b_off, b_len, a_off, a_len;
} pixfmt_names[] = {
	{ "RGB565", 16, 11, 5, 5, 6, 0, 5, 0, 0 },
	{ "BGR565", 16, 0, 5, 5, 6, 11, 5, 0, 0 },
	{ "RGB888", 24, 16, 8, 8, 8, 0, 8, 0, 0 },
	{ "BGR888", 24, 0, 8, 8, 8, 16, 8, 0, 0 },
	{ "XRGB8888", 32, 16, 8, 8, 8, 0, 8, 0, 0 },
	{ "ARGB8888", 32, 16, 8, 8, 8, 0, 8, 24, 8 },
	{ "XBGR8888", 32, 0, 8, 8, 8, 16, 8, 0, 0 },
	{ "ABGR8888", 32, 0, 8, 8, 8, 16, 8, 24, 8 },
	{ "RGBX8888", 32, 24, 8, 16, 8, 8, 8, 0, 0 },
	{ "RGBA8888", 32, 24, 8, 16, 8, 8, 8, 0, 8 },
	{ "BGRX8888", 32, 8, 8, 16, 8, 24, 8, 0, 0 },
	{ "BGRA8888", 32, 8, 8, 16, 8, 24, 8, 0, 8 },
};

#define PIXFMT_NNAMES (int)(sizeof pixfmt_names / sizeof pixfmt_names[0])

/* the bits of field f within a 32-bit pixel value (f already checked) */
static uint32_t
pixfmt_field_mask(const struct pixfmt_field *f)
{
	if (f->length == 0)
		return 0;
	uint32_t ones = f->length >= 32 ? 0xffffffffu : (1u << f->length) - 1;
	return ones << f->offset;
}

/* checks one field; min_len is 1 for colours and 0 for transp */
static int
pixfmt_check_field(const struct pixfmt *pf, const struct pixfmt_field *f, const char *what,
		   int min_len, char *err, size_t errlen)
{
	if (f->msb_right) {
		snprintf(err, errlen, "pixel format: %s bitfield has msb_right set (bit-reversed "
			 "channels are not supported)", what);
		return -1;
	}
	if (f->length < min_len || f->length > PIXFMT_CHANNEL_BITS_MAX) {
		snprintf(err, errlen, "pixel format: %s is %d bits (supported: %d..%d)", what,
			 f->length, min_len, PIXFMT_CHANNEL_BITS_MAX);
		return -1;
	}
	if (f->length > 0 && (f->offset < 0 || f->offset + f->length > pf->bpp)) {
		snprintf(err, errlen, "pixel format: %s bits %d..%d lie outside a %d-bit pixel",
			 what, f->offset, f->offset + f->length - 1, pf->bpp);
		return -1;
	}
	return 0;
}

/* out = v * (2^n - 1) / 255 rounded to nearest, for n = 0..16 (see pixfmt.h) */
static uint32_t
pixfmt_scale(uint32_t v, int n)
{
	uint32_t max = (1u << n) - 1;
	return (v * max + 127) / 255;
}

int
pixfmt_init(struct pixfmt *pf, char *err, size_t errlen)
{
	static const char *what[4] = { "red", "green", "blue", "transp" };
	const struct pixfmt_field *f[4] = { &pf->red, &pf->green, &pf->blue, &pf->transp };
	char tmp[1];
	if (!err || !errlen) {
		err = tmp;
		errlen = sizeof tmp;
	}

	/* whole pixels of 2, 3 or 4 bytes only: no palettes, no sub-byte pixels */
	if (pf->bpp != 16 && pf->bpp != 24 && pf->bpp != 32) {
		snprintf(err, errlen, "pixel format: %d bits per pixel is not supported "
			 "(supported: 16, 24, 32)", pf->bpp);
		return -1;
	}

	/* each field within the pixel, and no two sharing a bit */
	uint32_t used = 0;
	for (int c = 0; c < 4; c++) {
		if (pixfmt_check_field(pf, f[c], what[c], c == 3 ? 0 : 1, err, errlen) < 0)
			return -1;
		uint32_t m = pixfmt_field_mask(f[c]);
		if (used & m) {
			snprintf(err, errlen, "pixel format: %s bits %d..%d overlap another "
				 "channel", what[c], f[c]->offset, f[c]->offset + f[c]->length - 1);
			return -1;
		}
		used |= m;
	}

	/* tables: each 8-bit value already scaled and shifted into place */
	uint32_t all = pf->bpp == 32 ? 0xffffffffu : (1u << pf->bpp) - 1;
	pf->bytes = pf->bpp / 8;
	pf->pad = all & ~used;
	pf->xrgb = pf->bpp == 32 && pf->red.offset == 16 && pf->red.length == 8 &&
		   pf->green.offset == 8 && pf->green.length == 8 && pf->blue.offset == 0 &&
		   pf->blue.length == 8 && (pf->transp.length == 0 ||
					    (pf->transp.offset == 24 && pf->transp.length == 8));
	for (int c = 0; c < 4; c++) {
		for (uint32_t v = 0; v < 256; v++) {
			if (f[c]->length == 0)
				pf->lut[c][v] = 0;
			else
				pf->lut[c][v] = pixfmt_scale(v, f[c]->length) << f[c]->offset;
		}
	}
	return 0;
}

int
pixfmt_from_name(const char *name, struct pixfmt *dest, char *err, size_t errlen)
{
	for (int i = 0; name && i < PIXFMT_NNAMES; i++) {
		const struct pixfmt_named *n = &pixfmt_names[i];
		if (strcmp(name, n->name) != 0)
			continue;
		memset(dest, 0, sizeof *dest);
		dest->bpp = n->bpp;
		dest->red = (struct pixfmt_field){ n->r_off, n->r_len, 0 };
		dest->green = (struct pixfmt_field){ n->g_off, n->g_len, 0 };
		dest->blue = (struct pixfmt_field){ n->b_off, n->b_len, 0 };
		dest->transp = (struct pixfmt_field){ n->a_off, n->a_len, 0 };
		return pixfmt_init(dest, err, errlen);
	}
	if (err && errlen)
		snprintf(err, errlen, "pixel format: unknown name '%s'", name ? name : "(null)");
	return -1;
}

/* 1 when fields a and b describe the same bits (any offset when both are absent) */
static int
pixfmt_field_same(const struct pixfmt_field *a, int off, int len)
{
	if (a->length == 0 && len == 0)
		return 1;
	return a->length == len && a->offset == off && a->msb_right == 0;
}

const char *
pixfmt_name(const struct pixfmt *pf)
{
	for (int i = 0; i < PIXFMT_NNAMES; i++) {
		const struct pixfmt_named *n = &pixfmt_names[i];
		if (pf->bpp == n->bpp && pixfmt_field_same(&pf->red, n->r_off, n->r_len) &&
		    pixfmt_field_same(&pf->green, n->g_off, n->g_len) &&
		    pixfmt_field_same(&pf->blue, n->b_off, n->b_len) &&
		    pixfmt_field_same(&pf->transp, n->a_off, n->a_len))
			return n->name;
	}
	return NULL;
}

void
pixfmt_describe(const struct pixfmt *pf, char *dest, size_t len)
{
	const struct pixfmt_field *f[4] = { &pf->red, &pf->green, &pf->blue, &pf->transp };
	const char *name = pixfmt_name(pf);
	size_t at = 0;
	int n = snprintf(dest, len, "%d bpp", pf->bpp);
	for (int c = 0; c < 4 && n >= 0 && (at += (size_t)n) < len; c++)
		n = snprintf(dest + at, len - at, " %c%d:%d%s", "rgba"[c], f[c]->offset,
			     f[c]->length, f[c]->msb_right ? " msb_right" : "");
	if (name && n >= 0 && (at += (size_t)n) < len)
		snprintf(dest + at, len - at, " (%s)", name);
}

void
pixfmt_convert_row(const struct pixfmt *pf, const uint8_t *rgba, int n, uint8_t *dest)
{
	const uint32_t(*lut)[256] = pf->lut;
	uint32_t pad = pf->pad;

	/* one loop per pixel size; each pixel value is stored little-endian */
	switch (pf->bytes) {
	case 2:
		for (int i = 0; i < n; i++, rgba += 4, dest += 2) {
			uint32_t v = lut[0][rgba[0]] | lut[1][rgba[1]] | lut[2][rgba[2]] |
				     lut[3][rgba[3]] | pad;
			dest[0] = (uint8_t)v;
			dest[1] = (uint8_t)(v >> 8);
		}
		break;
	case 3:
		for (int i = 0; i < n; i++, rgba += 4, dest += 3) {
			uint32_t v = lut[0][rgba[0]] | lut[1][rgba[1]] | lut[2][rgba[2]] |
				     lut[3][rgba[3]] | pad;
			dest[0] = (uint8_t)v;
			dest[1] = (uint8_t)(v >> 8);
			dest[2] = (uint8_t)(v >> 16);
		}
		break;
	case 4:
		if (pf->xrgb) { /* the usual screen format: bytes moved, no tables (vectorises) */
			uint32_t alpha = pf->transp.length ? 0 : pad;
			for (int i = 0; i < n; i++, rgba += 4, dest += 4) {
				uint32_t v = (uint32_t)rgba[0] << 16 | (uint32_t)rgba[1] << 8 | rgba[2] |
					     (pf->transp.length ? (uint32_t)rgba[3] << 24 : alpha);
				memcpy(dest, &v, 4); /* little-endian, as the tables' path stores it */
			}
			break;
		}
		for (int i = 0; i < n; i++, rgba += 4, dest += 4) {
			uint32_t v = lut[0][rgba[0]] | lut[1][rgba[1]] | lut[2][rgba[2]] |
				     lut[3][rgba[3]] | pad;
			dest[0] = (uint8_t)v;
			dest[1] = (uint8_t)(v >> 8);
			dest[2] = (uint8_t)(v >> 16);
			dest[3] = (uint8_t)(v >> 24);
		}
		break;
	}
}
