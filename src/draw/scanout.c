/* scanout.c - a frame centred into a screen's memory, in its pixel format (scanout.h) */
#include "draw/scanout.h"

#include <string.h>

/* n pixels of b bytes at dest, each px */
static void
fill(uint8_t *dest, int n, const uint8_t *px, int b)
{
	for (int i = 0; i < n; i++, dest += b)
		memcpy(dest, px, (size_t)b);
}

void
scanout_draw(const struct pixfmt *pf, const uint8_t *black, const struct frame *f, uint8_t *mem,
	     size_t pitch, int w, int h)
{
	int b = pf->bytes;
	int cw = f->width < w ? f->width : w;
	int ch = f->height < h ? f->height : h;
	int sx = (f->width - cw) / 2, sy = (f->height - ch) / 2; /* first frame pixel shown */
	int dx = (w - cw) / 2, dy = (h - ch) / 2;                /* where it lands */
	for (int y = 0; y < h; y++) {
		uint8_t *row = mem + (size_t)y * pitch;
		if (y < dy || y >= dy + ch) { /* black above and below the frame */
			fill(row, w, black, b);
			continue;
		}
		/* black left, the frame's row, black right */
		const uint8_t *src = f->rgba + (size_t)(sy + y - dy) * f->stride + (size_t)sx * 4;
		fill(row, dx, black, b);
		pixfmt_convert_row(pf, src, cw, row + (size_t)dx * b);
		fill(row + (size_t)(dx + cw) * b, w - dx - cw, black, b);
	}
}
