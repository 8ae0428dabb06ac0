/*
 * test_view_sight.c - the sight cones drawn in other views
 * (view_add_sight_cones) against their analytic geometry: every side
 * triangle has its apex at the eye and its two rim corners at the cone's
 * half angle from the line of sight and its length from the eye; the rim
 * goes round the whole circle; the sides are translucent, the rim lines
 * on the same circle; nothing for no line of sight; no allocation.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "draw/view.h"

#include "alloc_count.h"
#include "test_util.h"

static const double EYE[3] = { 0.1, 1.6, 0.2 };
static const double DIR[3] = { 1.0, -0.3, 0.5 }; /* not unit: the icon normalises it */
static const double DEG[4] = { 3, 20, 40, 60 };
static const double LEN = 0.8;

static struct drawlist *
list_with_cones(int n, double len)
{
	struct drawlist *dl = view_drawlist_make();
	struct camera cam;
	assert_non_null(dl);
	view_camera_default(&cam);
	view_begin(dl, &cam, 320, 240);
	view_add_sight_cones(dl, EYE, DIR, DEG, n, len);
	return dl;
}

/* the angle (degrees) of p - EYE from DIR, and its length */
static double
angle_off(const float p[3], double *dist)
{
	double n = sqrt(DIR[0] * DIR[0] + DIR[1] * DIR[1] + DIR[2] * DIR[2]), v[3], dot = 0;
	for (int k = 0; k < 3; k++) {
		v[k] = p[k] - EYE[k];
		dot += v[k] * DIR[k] / n;
	}
	*dist = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
	return acos(fmax(-1, fmin(1, dot / *dist))) * 180 / M_PI;
}

/* the vertices of dl drawn as prim, in order, into *dest; returns how many */
static int
vertices_of(const struct drawlist *dl, enum view_prim prim, const struct view_vertex **dest,
	    int cap)
{
	int n = 0;
	for (int b = 0; b < dl->nbatch; b++) {
		if (dl->batch[b].prim != prim || dl->batch[b].space != VIEW_WORLD)
			continue;
		for (int i = 0; i < dl->batch[b].count && n < cap; i++)
			dest[n++] = &dl->vert[dl->batch[b].first + i];
	}
	return n;
}

static void
test_sides_and_rim_at_the_cone(void **st)
{
	(void)st;
	struct drawlist *dl = list_with_cones(4, LEN);
	static const struct view_vertex *tri[VIEW_MAX_VERT], *lin[VIEW_MAX_VERT];
	int nt = vertices_of(dl, VIEW_TRIANGLES, tri, VIEW_MAX_VERT);
	int nl = vertices_of(dl, VIEW_LINES, lin, VIEW_MAX_VERT);
	assert_int_equal(dl->dropped, 0);
	assert_int_equal(nt, 4 * VIEW_SIGHT_SEGMENTS * 3);
	assert_int_equal(nl, 4 * VIEW_SIGHT_SEGMENTS * 2);
	for (int c = 0; c < 4; c++) {
		/* the sides: apex at the eye, the rim corners at half the angle, LEN away */
		double az[VIEW_SIGHT_SEGMENTS * 2];
		int naz = 0;
		double u[3] = { 0, 0, 0 };
		for (int t = 0; t < VIEW_SIGHT_SEGMENTS; t++) {
			const struct view_vertex *const *v = &tri[3 * (c * VIEW_SIGHT_SEGMENTS + t)];
			for (int k = 0; k < 3; k++)
				assert_near(v[0]->p[k], EYE[k], 1e-6);
			for (int j = 1; j < 3; j++) {
				double dist, a = angle_off(v[j]->p, &dist);
				assert_near(a, DEG[c] / 2, 1e-3);
				assert_near(dist, LEN, 1e-5);
				assert_true(v[j]->c[3] < 128); /* translucent */
			}
			/* the azimuth about the axis of each first rim corner, from the first's */
			double n = sqrt(DIR[0] * DIR[0] + DIR[1] * DIR[1] + DIR[2] * DIR[2]), r[3],
			       d[3] = { DIR[0] / n, DIR[1] / n, DIR[2] / n }, along = 0;
			for (int k = 0; k < 3; k++)
				along += (v[1]->p[k] - EYE[k]) * d[k];
			for (int k = 0; k < 3; k++)
				r[k] = v[1]->p[k] - EYE[k] - along * d[k];
			if (t == 0)
				memcpy(u, r, sizeof u);
			double w[3] = { d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2],
					d[0] * u[1] - d[1] * u[0] };
			double x = r[0] * u[0] + r[1] * u[1] + r[2] * u[2],
			       y = r[0] * w[0] + r[1] * w[1] + r[2] * w[2];
			double a = atan2(y, x);
			az[naz++] = a < -1e-9 ? a + 2 * M_PI : a;
		}
		/* round the whole circle: sorted, no gap wider than a segment's */
		for (int i = 1; i < naz; i++)
			for (int j = i; j > 0 && az[j - 1] > az[j]; j--) {
				double s = az[j];
				az[j] = az[j - 1];
				az[j - 1] = s;
			}
		for (int i = 0; i < naz; i++) {
			double gap = (i + 1 < naz ? az[i + 1] : az[0] + 2 * M_PI) - az[i];
			assert_near(gap, 2 * M_PI / VIEW_SIGHT_SEGMENTS, 1e-4);
		}
		/* the rim lines on the same circle, opaque */
		for (int i = 0; i < 2 * VIEW_SIGHT_SEGMENTS; i++) {
			const struct view_vertex *v = lin[2 * c * VIEW_SIGHT_SEGMENTS + i];
			double dist, a = angle_off(v->p, &dist);
			assert_near(a, DEG[c] / 2, 1e-3);
			assert_near(dist, LEN, 1e-5);
			assert_int_equal(v->c[3], 255);
		}
	}
	view_drawlist_free(dl);
}

static void
test_length_scales_the_cone(void **st)
{
	(void)st;
	struct drawlist *dl = list_with_cones(1, 2.5);
	static const struct view_vertex *tri[VIEW_MAX_VERT];
	int nt = vertices_of(dl, VIEW_TRIANGLES, tri, VIEW_MAX_VERT);
	assert_int_equal(nt, VIEW_SIGHT_SEGMENTS * 3);
	for (int i = 0; i < nt; i++) {
		if (i % 3 == 0)
			continue;
		double dist, a = angle_off(tri[i]->p, &dist);
		assert_near(a, DEG[0] / 2, 1e-3);
		assert_near(dist, 2.5, 1e-5);
	}
	view_drawlist_free(dl);
}

static void
test_no_line_of_sight_no_cone(void **st)
{
	(void)st;
	static const double zero[3] = { 0, 0, 0 }, bad[3] = { NAN, 1, 0 };
	struct drawlist *dl = view_drawlist_make();
	struct camera cam;
	view_camera_default(&cam);
	view_begin(dl, &cam, 320, 240);
	view_add_sight_cones(dl, EYE, zero, DEG, 4, LEN);
	view_add_sight_cones(dl, EYE, bad, DEG, 4, LEN);
	assert_int_equal(dl->nvert, 0);
	view_drawlist_free(dl);
}

static void
test_no_alloc(void **st)
{
	(void)st;
	struct drawlist *dl = view_drawlist_make();
	struct camera cam;
	view_camera_default(&cam);
	view_begin(dl, &cam, 320, 240);
#if COUNT_ALLOCS
	long a0 = allocs;
#endif
	for (int i = 0; i < 10; i++)
		view_add_sight_cones(dl, EYE, DIR, DEG, 4, LEN);
#if COUNT_ALLOCS
	assert_int_equal(allocs - a0, 0);
#endif
	view_drawlist_free(dl);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sides_and_rim_at_the_cone),
		cmocka_unit_test(test_length_scales_the_cone),
		cmocka_unit_test(test_no_line_of_sight_no_cone),
		cmocka_unit_test(test_no_alloc),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
