/* test_pixfmt.c - packed pixel formats against a naive bit-by-bit reference */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "draw/pixfmt.h"

static const char *const NAMES[] = {
	"RGB565",   "BGR565",	"RGB888",   "BGR888",	"XRGB8888", "ARGB8888",
	"XBGR8888", "ABGR8888", "RGBX8888", "RGBA8888", "BGRX8888", "BGRA8888",
};
#define NNAMES (int)(sizeof NAMES / sizeof NAMES[0])

/* the reference's own description: per channel R, G, B, A an offset and a length */
struct ref {
	int bpp;
	int off[4], len[4];
};

/*
 * a DRM-style name read letter by letter: the letters name the channels from
 * the most significant bit down, the digits give their widths in the same
 * order (one digit each); X is padding
 */
static struct ref
ref_from_name(const char *name)
{
	struct ref r;
	memset(&r, 0, sizeof r);
	int nl = 0;
	while (isalpha((unsigned char)name[nl]))
		nl++;
	assert_int_equal((int)strlen(name), 2 * nl);
	int bit = 0;
	for (int i = 0; i < nl; i++)
		bit += name[nl + i] - '0';
	r.bpp = bit;
	for (int i = 0; i < nl; i++) {
		int w = name[nl + i] - '0';
		bit -= w;
		const char *c = strchr("RGBA", name[i]);
		if (name[i] == 'X')
			continue;
		assert_non_null(c);
		r.off[c - "RGBA"] = bit;
		r.len[c - "RGBA"] = w;
	}
	assert_int_equal(bit, 0);
	return r;
}

static struct ref
ref_from_pixfmt(const struct pixfmt *pf)
{
	const struct pixfmt_field *f[4] = { &pf->red, &pf->green, &pf->blue, &pf->transp };
	struct ref r;
	r.bpp = pf->bpp;
	for (int c = 0; c < 4; c++) {
		r.off[c] = f[c]->offset;
		r.len[c] = f[c]->length;
	}
	return r;
}

/*
 * dest: the pixel's bytes, built one bit at a time: every bit starts as 1
 * (padding), then each channel's value, rounded in floating point, lands
 * bit i at pixel bit off + i, which is bit (off+i)%8 of byte (off+i)/8
 */
static void
ref_pixel(const struct ref *r, const uint8_t rgba[4], uint8_t *dest)
{
	int nb = r->bpp / 8;
	memset(dest, 0xff, (size_t)nb);
	for (int c = 0; c < 4; c++) {
		if (r->len[c] == 0)
			continue;
		double max = ldexp(1.0, r->len[c]) - 1.0;
		unsigned long v = (unsigned long)floor(rgba[c] * max / 255.0 + 0.5);
		for (int i = 0; i < r->len[c]; i++) {
			int b = r->off[c] + i;
			uint8_t m = (uint8_t)(1u << (b % 8));
			if ((v >> i) & 1)
				dest[b / 8] |= m;
			else
				dest[b / 8] &= (uint8_t)~m;
		}
	}
}

/* formats beyond the named ones: wide, narrow, gappy channels */
static void
custom_formats(struct pixfmt *dest, int *n)
{
	static const int spec[][9] = {
		/* bpp, r off/len, g off/len, b off/len, a off/len */
		{ 32, 20, 10, 10, 10, 0, 10, 30, 2 },  /* ARGB2101010 */
		{ 32, 0, 10, 10, 10, 20, 10, 0, 0 },   /* XBGR2101010 */
		{ 16, 10, 5, 5, 5, 0, 5, 15, 1 },      /* ARGB1555 */
		{ 16, 8, 4, 4, 4, 0, 4, 12, 4 },       /* ARGB4444 */
		{ 16, 0, 1, 5, 1, 10, 1, 15, 1 },      /* one bit each, gaps */
		{ 24, 0, 3, 3, 13, 16, 8, 0, 0 },      /* 3/13/8 */
		{ 32, 16, 16, 8, 8, 0, 8, 0, 0 },      /* a 16-bit red */
		{ 32, 1, 9, 12, 11, 23, 7, 0, 0 },     /* odd offsets */
	};
	*n = (int)(sizeof spec / sizeof spec[0]);
	for (int i = 0; i < *n; i++) {
		struct pixfmt *pf = &dest[i];
		memset(pf, 0, sizeof *pf);
		pf->bpp = spec[i][0];
		pf->red = (struct pixfmt_field){ spec[i][1], spec[i][2], 0 };
		pf->green = (struct pixfmt_field){ spec[i][3], spec[i][4], 0 };
		pf->blue = (struct pixfmt_field){ spec[i][5], spec[i][6], 0 };
		pf->transp = (struct pixfmt_field){ spec[i][7], spec[i][8], 0 };
		char err[200];
		int r = pixfmt_init(pf, err, sizeof err);
		if (r < 0)
			fail_msg("custom format %d: %s", i, err);
	}
}

/* checks one pixel of pf against the reference */
static void
check_pixel(const struct pixfmt *pf, const struct ref *r, const uint8_t rgba[4], const char *what)
{
	uint8_t got[4] = { 0 }, want[4] = { 0 }; /* bytes past the pixel print as 0 */
	pixfmt_convert_row(pf, rgba, 1, got);
	ref_pixel(r, rgba, want);
	if (memcmp(got, want, (size_t)pf->bytes) != 0)
		fail_msg("%s: rgba %u,%u,%u,%u -> %02x %02x %02x %02x, "
			 "reference %02x %02x %02x %02x", what, rgba[0], rgba[1], rgba[2], rgba[3],
			 got[0], got[1], got[2], got[3], want[0], want[1], want[2], want[3]);
}

/* every value of every channel (others random), then a long row of random pixels */
static void
check_format(const struct pixfmt *pf, const struct ref *r, const char *what)
{
	uint8_t px[4];
	for (int c = 0; c < 4; c++) {
		for (int v = 0; v < 256; v++) {
			for (int k = 0; k < 4; k++)
				px[k] = (uint8_t)rand();
			px[c] = (uint8_t)v;
			check_pixel(pf, r, px, what);
			memset(px, 0, 4);
			px[c] = (uint8_t)v;
			check_pixel(pf, r, px, what);
		}
	}

	/* a row of random pixels at once; the byte after it is untouched */
	enum { N = 4099 };
	static uint8_t rgba[4 * N], got[4 * N + 1], want[4];
	for (int i = 0; i < 4 * N; i++)
		rgba[i] = (uint8_t)rand();
	got[N * pf->bytes] = 0x5a;
	pixfmt_convert_row(pf, rgba, N, got);
	assert_int_equal(got[N * pf->bytes], 0x5a);
	for (int i = 0; i < N; i++) {
		ref_pixel(r, rgba + 4 * i, want);
		if (memcmp(got + i * pf->bytes, want, (size_t)pf->bytes) != 0)
			fail_msg("%s: row pixel %d differs from the reference", what, i);
	}
}

static void
test_named_layouts(void **unused)
{
	(void)unused;
	for (int i = 0; i < NNAMES; i++) {
		struct pixfmt pf;
		char err[200];
		assert_int_equal(pixfmt_from_name(NAMES[i], &pf, err, sizeof err), 0);
		struct ref want = ref_from_name(NAMES[i]), got = ref_from_pixfmt(&pf);
		assert_int_equal(got.bpp, want.bpp);
		assert_int_equal(pf.bytes, want.bpp / 8);
		for (int c = 0; c < 4; c++) {
			assert_int_equal(got.len[c], want.len[c]);
			if (want.len[c])
				assert_int_equal(got.off[c], want.off[c]);
		}
		assert_string_equal(pixfmt_name(&pf), NAMES[i]);
	}
}

static void
test_named_against_reference(void **unused)
{
	(void)unused;
	srand(1);
	for (int i = 0; i < NNAMES; i++) {
		struct pixfmt pf;
		assert_int_equal(pixfmt_from_name(NAMES[i], &pf, NULL, 0), 0);
		struct ref r = ref_from_name(NAMES[i]);
		check_format(&pf, &r, NAMES[i]);
	}
}

static void
test_custom_against_reference(void **unused)
{
	(void)unused;
	struct pixfmt pf[16];
	int n;
	srand(2);
	custom_formats(pf, &n);
	for (int i = 0; i < n; i++) {
		char what[96];
		pixfmt_describe(&pf[i], what, sizeof what);
		struct ref r = ref_from_pixfmt(&pf[i]);
		check_format(&pf[i], &r, what);
		assert_null(pixfmt_name(&pf[i]));
	}
}

/* known pixels, byte by byte in memory order */
static void
test_byte_order(void **unused)
{
	(void)unused;
	static const struct {
		const char *name;
		uint8_t rgba[4];
		uint8_t bytes[4];
	} cases[] = {
		{ "RGB565", { 255, 0, 0, 255 }, { 0x00, 0xf8 } },
		{ "RGB565", { 0, 255, 0, 255 }, { 0xe0, 0x07 } },
		{ "RGB565", { 0, 0, 255, 255 }, { 0x1f, 0x00 } },
		{ "RGB565", { 255, 255, 255, 0 }, { 0xff, 0xff } },
		{ "BGR565", { 255, 0, 0, 255 }, { 0x1f, 0x00 } },
		{ "BGR565", { 0, 0, 255, 255 }, { 0x00, 0xf8 } },
		{ "RGB565", { 128, 128, 128, 255 }, { 0x10, 0x84 } }, /* 16, 32, 16 */
		{ "RGB888", { 0x11, 0x22, 0x33, 0x44 }, { 0x33, 0x22, 0x11 } },
		{ "BGR888", { 0x11, 0x22, 0x33, 0x44 }, { 0x11, 0x22, 0x33 } },
		{ "XRGB8888", { 0x11, 0x22, 0x33, 0x44 }, { 0x33, 0x22, 0x11, 0xff } },
		{ "ARGB8888", { 0x11, 0x22, 0x33, 0x44 }, { 0x33, 0x22, 0x11, 0x44 } },
		{ "XBGR8888", { 0x11, 0x22, 0x33, 0x44 }, { 0x11, 0x22, 0x33, 0xff } },
		{ "ABGR8888", { 0x11, 0x22, 0x33, 0x44 }, { 0x11, 0x22, 0x33, 0x44 } },
		{ "RGBX8888", { 0x11, 0x22, 0x33, 0x44 }, { 0xff, 0x33, 0x22, 0x11 } },
		{ "RGBA8888", { 0x11, 0x22, 0x33, 0x44 }, { 0x44, 0x33, 0x22, 0x11 } },
		{ "BGRX8888", { 0x11, 0x22, 0x33, 0x44 }, { 0xff, 0x11, 0x22, 0x33 } },
		{ "BGRA8888", { 0x11, 0x22, 0x33, 0x44 }, { 0x44, 0x11, 0x22, 0x33 } },
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		struct pixfmt pf;
		assert_int_equal(pixfmt_from_name(cases[i].name, &pf, NULL, 0), 0);
		uint8_t got[5] = { 0xaa, 0xaa, 0xaa, 0xaa, 0xaa };
		pixfmt_convert_row(&pf, cases[i].rgba, 1, got);
		assert_memory_equal(got, cases[i].bytes, (size_t)pf.bytes);
		assert_int_equal(got[pf.bytes], 0xaa);
	}
}

/* the documented rounding rule on its examples, and its ends */
static void
test_rounding_rule(void **unused)
{
	(void)unused;
	struct pixfmt pf;
	memset(&pf, 0, sizeof pf);
	pf.bpp = 32;
	pf.red = (struct pixfmt_field){ 0, 5, 0 };
	pf.green = (struct pixfmt_field){ 8, 10, 0 };
	pf.blue = (struct pixfmt_field){ 18, 1, 0 };
	pf.transp = (struct pixfmt_field){ 19, 13, 0 };
	assert_int_equal(pixfmt_init(&pf, NULL, 0), 0);
	assert_int_equal(pf.lut[0][128], 16u);
	assert_int_equal(pf.lut[0][255], 31u);
	assert_int_equal(pf.lut[1][1] >> 8, 4u);
	assert_int_equal(pf.lut[1][43] >> 8, 173u);
	assert_int_equal(pf.lut[1][255] >> 8, 1023u);
	assert_int_equal(pf.lut[2][127] >> 18, 0u);
	assert_int_equal(pf.lut[2][128] >> 18, 1u);
	assert_int_equal(pf.lut[3][255] >> 19, 8191u);
	assert_int_equal(pf.pad, 0xe0u); /* bits 5..7 */
	for (int c = 0; c < 4; c++) {
		assert_int_equal(pf.lut[c][0], 0u);
		for (int v = 1; v < 256; v++)
			assert_true(pf.lut[c][v] >= pf.lut[c][v - 1]);
	}
}

/* each unsupported layout is refused with a message saying why */
static void
test_rejects(void **unused)
{
	(void)unused;
	static const struct {
		int spec[9];
		const char *msg; /* a piece of the message */
	} cases[] = {
		{ { 8, 5, 3, 2, 3, 0, 2, 0, 0 }, "8 bits per pixel" },
		{ { 12, 8, 4, 4, 4, 0, 4, 0, 0 }, "12 bits per pixel" },
		{ { 64, 0, 16, 16, 16, 32, 16, 48, 16 }, "64 bits per pixel" },
		{ { 16, 11, 5, 5, 6, 0, 0, 0, 0 }, "blue is 0 bits" },
		{ { 32, 0, 17, 17, 8, 25, 7, 0, 0 }, "red is 17 bits" },
		{ { 16, 12, 5, 5, 6, 0, 5, 0, 0 }, "red bits 12..16 lie outside" },
		{ { 16, 10, 6, 5, 6, 0, 5, 0, 0 }, "green bits 5..10 overlap" },
		{ { 32, 16, 8, 8, 8, 0, 8, 20, 8 }, "transp bits 20..27 overlap" },
		{ { 32, -1, 8, 8, 8, 16, 8, 0, 0 }, "red bits -1..6 lie outside" },
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		const int *s = cases[i].spec;
		struct pixfmt pf;
		memset(&pf, 0, sizeof pf);
		pf.bpp = s[0];
		pf.red = (struct pixfmt_field){ s[1], s[2], 0 };
		pf.green = (struct pixfmt_field){ s[3], s[4], 0 };
		pf.blue = (struct pixfmt_field){ s[5], s[6], 0 };
		pf.transp = (struct pixfmt_field){ s[7], s[8], 0 };
		char err[200] = "";
		assert_int_equal(pixfmt_init(&pf, err, sizeof err), -1);
		if (!strstr(err, cases[i].msg))
			fail_msg("case %zu: '%s' lacks '%s'", i, err, cases[i].msg);
	}

	/* bit-reversed channels, and names nobody defined */
	struct pixfmt pf;
	char err[200] = "";
	assert_int_equal(pixfmt_from_name("RGB565", &pf, NULL, 0), 0);
	pf.green.msb_right = 1;
	assert_int_equal(pixfmt_init(&pf, err, sizeof err), -1);
	assert_non_null(strstr(err, "msb_right"));
	assert_int_equal(pixfmt_from_name("RGBA5551", &pf, err, sizeof err), -1);
	assert_non_null(strstr(err, "unknown name 'RGBA5551'"));
	assert_int_equal(pixfmt_from_name("rgb565", &pf, err, sizeof err), -1);
}

static void
test_describe(void **unused)
{
	(void)unused;
	struct pixfmt pf;
	char d[96];
	assert_int_equal(pixfmt_from_name("ARGB8888", &pf, NULL, 0), 0);
	pixfmt_describe(&pf, d, sizeof d);
	assert_string_equal(d, "32 bpp r16:8 g8:8 b0:8 a24:8 (ARGB8888)");
	pixfmt_describe(&pf, d, 10); /* truncated, still terminated */
	assert_string_equal(d, "32 bpp r1");
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_named_layouts),
		cmocka_unit_test(test_named_against_reference),
		cmocka_unit_test(test_custom_against_reference),
		cmocka_unit_test(test_byte_order),
		cmocka_unit_test(test_rounding_rule),
		cmocka_unit_test(test_rejects),
		cmocka_unit_test(test_describe),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
