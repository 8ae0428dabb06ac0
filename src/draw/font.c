/* font.c - a FreeType glyph atlas (see font.h) */
#include <ft2build.h>
#include FT_FREETYPE_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "draw/font.h"

#define NGLYPH (FONT_LAST - FONT_FIRST + 1)
#define PAD 1 /* empty pixels around each glyph, so filtering never bleeds */

/* packs the rendered glyphs row by row into a 256 pixel wide atlas */
static int
pack(struct font *f, FT_Face face)
{
	int x = PAD, y = PAD, row = 0, w = 256;
	for (int i = 0; i < NGLYPH; i++) {
		if (FT_Load_Char(face, (FT_ULong)(FONT_FIRST + i), FT_LOAD_RENDER | FT_LOAD_TARGET_LIGHT))
			return -1;
		FT_GlyphSlot g = face->glyph;
		struct font_glyph *d = &f->glyph[i];
		d->w = (int)g->bitmap.width;
		d->h = (int)g->bitmap.rows;
		d->left = g->bitmap_left;
		d->top = g->bitmap_top;
		d->advance = (int)((g->advance.x + 32) >> 6);
		if (x + d->w + PAD > w) {
			x = PAD;
			y += row + PAD;
			row = 0;
		}
		d->x = x;
		d->y = y;
		x += d->w + PAD;
		row = d->h > row ? d->h : row;
	}
	f->atlas_w = w;
	f->atlas_h = 1;
	while (f->atlas_h < y + row + PAD)
		f->atlas_h *= 2;
	return 0;
}

struct font *
font_load(const char *path, int px, char *err, size_t errlen)
{
	FT_Library lib = NULL;
	FT_Face face = NULL;
	struct font *f = calloc(1, sizeof *f);
	const char *what = NULL;
	if (!f) {
		what = "out of memory";
		goto fail;
	}
	if (FT_Init_FreeType(&lib)) {
		what = "FreeType did not initialise";
		goto fail;
	}
	if (FT_New_Face(lib, path, 0, &face)) {
		what = "cannot open the font file";
		goto fail;
	}
	if (px < 4 || px > 256 || FT_Set_Pixel_Sizes(face, 0, (FT_UInt)px)) {
		what = "unusable pixel size";
		goto fail;
	}
	f->px = px;
	f->ascent = (int)((face->size->metrics.ascender + 63) >> 6);
	f->descent = (int)((-face->size->metrics.descender + 63) >> 6);
	f->line_height = (int)((face->size->metrics.height + 32) >> 6);

	/* first pass places the glyphs, the second draws them into the atlas */
	if (pack(f, face)) {
		what = "a glyph did not render";
		goto fail;
	}
	f->atlas = calloc((size_t)f->atlas_w * (size_t)f->atlas_h, 1);
	if (!f->atlas) {
		what = "out of memory";
		goto fail;
	}
	for (int i = 0; i < NGLYPH; i++) {
		if (FT_Load_Char(face, (FT_ULong)(FONT_FIRST + i), FT_LOAD_RENDER | FT_LOAD_TARGET_LIGHT)) {
			what = "a glyph did not render";
			goto fail;
		}
		const FT_Bitmap *b = &face->glyph->bitmap;
		const struct font_glyph *d = &f->glyph[i];
		for (int r = 0; r < d->h; r++)
			memcpy(f->atlas + (size_t)(d->y + r) * (size_t)f->atlas_w + (size_t)d->x,
			       b->buffer + (ptrdiff_t)r * b->pitch, (size_t)d->w);
	}
	FT_Done_Face(face);
	FT_Done_FreeType(lib);
	return f;
fail:
	snprintf(err, errlen, "%s: %s", path, what);
	if (face)
		FT_Done_Face(face);
	if (lib)
		FT_Done_FreeType(lib);
	font_free(f);
	return NULL;
}

void
font_free(struct font *f)
{
	if (!f)
		return;
	free(f->atlas);
	free(f);
}

const struct font_glyph *
font_glyph(const struct font *f, unsigned char c)
{
	if (c < FONT_FIRST || c > FONT_LAST)
		c = '?';
	return &f->glyph[c - FONT_FIRST];
}

int
font_text_width(const struct font *f, const char *text)
{
	int w = 0;
	for (const unsigned char *p = (const unsigned char *)text; *p; p++)
		w += font_glyph(f, *p)->advance;
	return w;
}
