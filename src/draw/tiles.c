/* tiles.c - the kiosk's screen shared by its views (see tiles.h) */
#include "draw/tiles.h"

#include <math.h>

/* share `total` pixels (gaps taken out) among k parts: part i's start and size */
static void
share(int total, int k, int i, int *start, int *size)
{
	int free = total - (k - 1) * TILES_GAP, base = free / k, extra = free % k;
	*size = base + (i < extra);
	*start = i * (base + TILES_GAP) + (i < extra ? i : extra);
}

int
tiles_make(struct tiles *T, int screen_w, int screen_h, int band, int n)
{
	if (n < 1 || n > TILES_MAX || band < 0 || screen_w < 16 || screen_h - band < 16)
		return -1;
	int cols = (int)ceil(sqrt((double)n)), rows = (n + cols - 1) / cols;
	int area_h = screen_h - band;
	if ((screen_w - (cols - 1) * TILES_GAP) / cols < 16 ||
	    (area_h - (rows - 1) * TILES_GAP) / rows < 16)
		return -1;
	T->screen_w = screen_w;
	T->screen_h = screen_h;
	T->band = band;
	T->n = n;
	T->cols = cols;
	T->rows = rows;
	for (int i = 0; i < n; i++) {
		struct tile *t = &T->t[i];
		share(screen_w, cols, i % cols, &t->x, &t->w);
		share(area_h, rows, i / cols, &t->y, &t->h);
	}
	return 0;
}

int
tiles_at(const struct tiles *T, double sx, double sy, double *vx, double *vy)
{
	for (int i = 0; i < T->n; i++) {
		const struct tile *t = &T->t[i];
		if (sx >= t->x && sx < t->x + t->w && sy >= t->y && sy < t->y + t->h) {
			*vx = sx - t->x;
			*vy = sy - t->y;
			return i;
		}
	}
	return -1;
}

void
tiles_to_screen(const struct tiles *T, int i, double vx, double vy, double *sx, double *sy)
{
	const struct tile *t = &T->t[i];
	*sx = t->x + fmin(fmax(vx, 0), t->w - 1e-9);
	*sy = t->y + fmin(fmax(vy, 0), t->h - 1e-9);
}
