/*
 * test_tiles.c - the kiosk's screen shared by its views: one view fills the
 * space above the band; four make a 2 x 2 grid with the gap between; the
 * tiles never overlap, stay on the screen and cover it but for the gaps
 * (counted pixel by pixel on screens of many sizes); a point maps to its
 * view's pixel and back; bad requests change nothing.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "draw/tiles.h"

static void
test_one_view_fills_the_space_above_the_band(void **unused)
{
	(void)unused;
	struct tiles T;
	assert_int_equal(tiles_make(&T, 1280, 720, 40, 1), 0);
	assert_int_equal(T.t[0].x, 0);
	assert_int_equal(T.t[0].y, 0);
	assert_int_equal(T.t[0].w, 1280);
	assert_int_equal(T.t[0].h, 680);
	double vx, vy;
	assert_int_equal(tiles_at(&T, 100.5, 200.25, &vx, &vy), 0);
	assert_true(vx == 100.5 && vy == 200.25);
	assert_int_equal(tiles_at(&T, 10, 700, &vx, &vy), -1); /* the band */
	assert_int_equal(tiles_at(&T, -1, 10, &vx, &vy), -1);
}

static void
test_four_views_make_a_grid_with_gaps(void **unused)
{
	(void)unused;
	struct tiles T;
	assert_int_equal(tiles_make(&T, 1281, 722, 40, 4), 0);
	assert_int_equal(T.cols, 2);
	assert_int_equal(T.rows, 2);
	/* 1281 - 2 = 1279: 640 + 639; 682 - 2 = 680: 340 + 340 */
	assert_int_equal(T.t[0].w, 640);
	assert_int_equal(T.t[1].x, 642);
	assert_int_equal(T.t[1].w, 639);
	assert_int_equal(T.t[2].y, 342);
	assert_int_equal(T.t[3].h, 340);
	double vx, vy;
	assert_int_equal(tiles_at(&T, 641, 10, &vx, &vy), -1); /* the gap */
	assert_int_equal(tiles_at(&T, 700, 400, &vx, &vy), 3);
	assert_true(vx == 58 && vy == 58);
	double sx, sy;
	tiles_to_screen(&T, 3, vx, vy, &sx, &sy);
	assert_true(sx == 700 && sy == 400);
	/* clamped inside its tile */
	tiles_to_screen(&T, 0, -5, 9999, &sx, &sy);
	assert_true(sx == 0 && sy < 340 && sy > 339);
}

/* every pixel of the screen is in at most one tile; all but the gaps and the band are in one */
static void
test_tiles_cover_the_screen_once(void **unused)
{
	(void)unused;
	static unsigned char owner[400 * 300];
	for (int n = 1; n <= TILES_MAX; n++)
		for (int w = 100; w <= 400; w += 37)
			for (int h = 120; h <= 300; h += 41) {
				struct tiles T;
				if (tiles_make(&T, w, h, 20, n) < 0)
					continue;
				memset(owner, 0, sizeof owner);
				int area = 0;
				for (int i = 0; i < n; i++) {
					const struct tile *t = &T.t[i];
					assert_true(t->x >= 0 && t->y >= 0 && t->x + t->w <= w &&
						    t->y + t->h <= h - 20);
					assert_int_equal(t->w, T.t[i % T.cols].w); /* a column is one width */
					for (int y = t->y; y < t->y + t->h; y++)
						for (int x = t->x; x < t->x + t->w; x++) {
							assert_int_equal(owner[y * w + x], 0);
							owner[y * w + x] = 1;
							area++;
						}
				}
				/* the grid's cells (full rows and columns) take all but the gaps */
				int cells = T.cols * T.rows, covered_if_full = (w - (T.cols - 1) * TILES_GAP) *
								      (h - 20 - (T.rows - 1) * TILES_GAP);
				if (cells == n)
					assert_int_equal(area, covered_if_full);
			}
}

static void
test_bad_requests_change_nothing(void **unused)
{
	(void)unused;
	struct tiles T, before;
	memset(&T, 0x5a, sizeof T);
	before = T;
	assert_int_equal(tiles_make(&T, 640, 480, 40, 0), -1);
	assert_int_equal(tiles_make(&T, 640, 480, 40, TILES_MAX + 1), -1);
	assert_int_equal(tiles_make(&T, 40, 480, 40, 9), -1); /* views narrower than 16 px */
	assert_int_equal(tiles_make(&T, 640, 50, 40, 1), -1);
	assert_int_equal(tiles_make(&T, 640, 480, -1, 1), -1);
	assert_memory_equal(&T, &before, sizeof T);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_one_view_fills_the_space_above_the_band),
		cmocka_unit_test(test_four_views_make_a_grid_with_gaps),
		cmocka_unit_test(test_tiles_cover_the_screen_once),
		cmocka_unit_test(test_bad_requests_change_nothing),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
