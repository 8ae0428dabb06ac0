/*
 * font.h - text through FreeType: the printable ASCII glyphs of one face
 * at one pixel size, rasterised once into an 8-bit coverage atlas that the
 * renderer uploads as a texture. Metrics are whole pixels.
 */
#ifndef POSTURE_FONT_H
#define POSTURE_FONT_H

#include <stddef.h>
#include <stdint.h>

#define FONT_FIRST 32 /* ' ' */
#define FONT_LAST 126 /* '~' */
#define FONT_DEFAULT_PATH "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf"

struct font_glyph {
	int x, y, w, h;  /* the glyph's box in the atlas, pixels */
	int left, top;   /* bitmap offset from the pen: right, and up from the baseline */
	int advance;     /* pen advance, pixels */
};

struct font {
	int px;                   /* nominal size (em height), pixels */
	int ascent, descent;      /* above and below the baseline, pixels (descent >= 0) */
	int line_height;          /* baseline to baseline */
	int atlas_w, atlas_h;
	uint8_t *atlas;           /* atlas_w x atlas_h coverage, rows top to bottom */
	struct font_glyph glyph[FONT_LAST - FONT_FIRST + 1];
};

/*
 * Loads the face at path (a TrueType/OpenType file) at px pixels and
 * rasterises its glyphs with FreeType's light hinting. Returns the font, or
 * NULL with a message in err (missing file, not a font, out of memory).
 */
struct font *font_load(const char *path, int px, char *err, size_t errlen);
void font_free(struct font *f);

/* the glyph drawn for byte c: its own for printable ASCII, '?' for others */
const struct font_glyph *font_glyph(const struct font *f, unsigned char c);

/* width in pixels of text drawn on one line */
int font_text_width(const struct font *f, const char *text);

#endif
