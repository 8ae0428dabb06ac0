/*
 * tiles.h - the kiosk's screen: one view filling it, or several
 * tiled in a grid, above the band that holds the message and status lines.
 * Pure geometry in whole pixels: where each view goes on the screen, and
 * which view (and which pixel of it) a point of the screen falls in.
 *
 * The grid: n views in ceil(sqrt(n)) columns and as many rows as they
 * need, row by row from the top left; the space above the band shared as
 * evenly as whole pixels allow (the first columns and rows take the
 * remainder), TILES_GAP pixels between neighbours. A last row with fewer
 * views leaves its right part empty, so every view keeps the same size.
 */
#ifndef POSTURE_DRAW_TILES_H
#define POSTURE_DRAW_TILES_H

#define TILES_MAX 9  /* views on one screen: a 3 x 3 grid */
#define TILES_GAP 2  /* pixels between two views */

struct tile {
	int x, y, w, h; /* the view's rectangle on the screen: [x, x+w) x [y, y+h) */
};

struct tiles {
	int screen_w, screen_h;
	int band;  /* the band's height at the bottom (the message and status lines) */
	int n, cols, rows;
	struct tile t[TILES_MAX];
};

/*
 * Lays n views (1..TILES_MAX) out on a screen_w x screen_h screen above a
 * band of band pixels. Returns 0, or -1 (T untouched) when n is out of
 * range or a view would be smaller than 16 x 16 pixels.
 */
int tiles_make(struct tiles *T, int screen_w, int screen_h, int band, int n);

/*
 * The view under screen point (sx, sy), with the point in that view's
 * pixels in *vx, *vy; -1 in the band, a gap or outside the screen.
 */
int tiles_at(const struct tiles *T, double sx, double sy, double *vx, double *vy);

/*
 * The screen point of pixel (vx, vy) of view i, clamped inside its tile:
 * how the kiosk's pointer stays put when it moves from pixel to pixel.
 */
void tiles_to_screen(const struct tiles *T, int i, double vx, double vy, double *sx, double *sy);

#endif
