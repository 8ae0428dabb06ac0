/*
 * test_mcubes.c - the surface of a sampled field (assess/mcubes.h) against
 * analytic solids: a sphere's mesh is watertight (every edge in exactly two
 * triangles, once each way), its volume is 4/3 pi r^3 within the chords'
 * error, its normals point outwards and ray parity says inside from outside;
 * a hollow ball's inner surface faces its hollow, so the volume is the
 * shell's; two balls give two closed pieces.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "assess/mcubes.h"

typedef double (*field_fn)(const double p[3]);

static double
sphere(const double p[3])
{
	return sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 0.3;
}

/* a ball of radius 0.3 with a hollow of radius 0.15 */
static double
hollow(const double p[3])
{
	double r = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
	return fmax(r - 0.3, 0.15 - r);
}

/* two balls of radius 0.15 at x = -0.2 and 0.2 */
static double
two_balls(const double p[3])
{
	double a = sqrt((p[0] + 0.2) * (p[0] + 0.2) + p[1] * p[1] + p[2] * p[2]) - 0.15;
	double b = sqrt((p[0] - 0.2) * (p[0] - 0.2) + p[1] * p[1] + p[2] * p[2]) - 0.15;
	return fmin(a, b);
}

static float *
sample(field_fn f, double h, struct mc_grid *g)
{
	int n = (int)ceil(0.8 / h) + 1;
	for (int a = 0; a < 3; a++) {
		g->n[a] = n;
		g->origin[a] = -0.4 - 0.37 * h; /* off the solid's symmetry */
	}
	g->step = h;
	float *val = malloc((size_t)n * n * n * sizeof *val);
	assert_non_null(val);
	for (int k = 0; k < n; k++)
		for (int j = 0; j < n; j++)
			for (int i = 0; i < n; i++) {
				double p[3] = { g->origin[0] + i * h, g->origin[1] + j * h,
						g->origin[2] + k * h };
				val[mc_index(g, i, j, k)] = (float)f(p);
			}
	g->val = val;
	return val;
}

static int
cmp_ll(const void *a, const void *b)
{
	long long x = *(const long long *)a, y = *(const long long *)b;
	return (x > y) - (x < y);
}

/* every directed edge once, and its reverse once: closed and consistently oriented */
static void
assert_watertight(const struct mc_mesh *m)
{
	long long n = m->ntri * 3LL, nv = m->nvert;
	long long *e = malloc((size_t)n * sizeof *e);
	assert_non_null(e);
	for (int t = 0; t < m->ntri; t++)
		for (int k = 0; k < 3; k++) {
			long long a = m->tri[3 * t + k], b = m->tri[3 * t + (k + 1) % 3];
			assert_true(a != b);
			e[3 * t + k] = a * nv + b;
		}
	qsort(e, (size_t)n, sizeof *e, cmp_ll);
	for (long long i = 0; i < n; i++) {
		if (i)
			assert_true(e[i] != e[i - 1]); /* no directed edge twice */
		long long rev = (e[i] % nv) * nv + e[i] / nv;
		assert_non_null(bsearch(&rev, e, (size_t)n, sizeof *e, cmp_ll));
	}
	free(e);
}

static void
test_sphere_is_watertight_with_its_volume_and_outward_normals(void **unused)
{
	(void)unused;
	const double r = 0.3, pi = 3.14159265358979323846;
	for (int res = 0; res < 2; res++) {
		double h = res ? 0.02 : 0.04;
		struct mc_grid g;
		float *val = sample(sphere, h, &g);
		struct mc_mesh m;
		assert_int_equal(mc_extract(&g, &m, NULL), 0);
		assert_true(m.ntri > 100);
		assert_watertight(&m);
		/* chords of a circle of radius r sag by at most h^2 / (8 r) (a vertex-to-vertex
		 * span is within a cube's diagonal, sqrt(3) h): the volume lies between the
		 * ball's and the ball shrunk by that sag */
		double exact = 4.0 / 3 * pi * r * r * r, sag = 3 * h * h / (8 * r);
		double inner = 4.0 / 3 * pi * pow(r - sag, 3);
		assert_true(m.volume <= exact * 1.0005);
		assert_true(m.volume >= inner);
		/* outward: along the radius */
		for (int v = 0; v < m.nvert; v++) {
			const float *p = &m.vert[3 * v], *nv = &m.normal[3 * v];
			double len = sqrt((double)p[0] * p[0] + (double)p[1] * p[1] + (double)p[2] * p[2]);
			assert_true(fabs(len - r) < sag + 1e-6);
			double dot = (p[0] * nv[0] + p[1] * nv[1] + p[2] * nv[2]) / len;
			assert_true(dot > 0.95);
		}
		double in[3] = { 0.1, -0.05, 0.2 }, out[3] = { 0.2, 0.2, 0.2 }, far[3] = { 2, 0, 0 };
		assert_int_equal(mc_mesh_contains(&m, in), 1);
		assert_int_equal(mc_mesh_contains(&m, out), 0);
		assert_int_equal(mc_mesh_contains(&m, far), 0);
		for (int a = 0; a < 3; a++) {
			assert_true(fabs(m.lo[a] + r) < sag + 1e-3);
			assert_true(fabs(m.hi[a] - r) < sag + 1e-3);
		}
		mc_mesh_free(&m);
		free(val);
	}
}

static void
test_hollow_ball_inner_surface_faces_the_hollow(void **unused)
{
	(void)unused;
	const double pi = 3.14159265358979323846, h = 0.02;
	struct mc_grid g;
	float *val = sample(hollow, h, &g);
	struct mc_mesh m;
	assert_int_equal(mc_extract(&g, &m, NULL), 0);
	assert_watertight(&m);
	double exact = 4.0 / 3 * pi * (0.3 * 0.3 * 0.3 - 0.15 * 0.15 * 0.15);
	assert_true(fabs(m.volume - exact) < 0.01 * exact);
	int inner = 0;
	for (int v = 0; v < m.nvert; v++) {
		const float *p = &m.vert[3 * v], *nv = &m.normal[3 * v];
		double len = sqrt((double)p[0] * p[0] + (double)p[1] * p[1] + (double)p[2] * p[2]);
		double dot = (p[0] * nv[0] + p[1] * nv[1] + p[2] * nv[2]) / len;
		if (len < 0.2) { /* the hollow's surface: its normals point to the centre */
			inner++;
			assert_true(dot < -0.9);
		} else {
			assert_true(dot > 0.9);
		}
	}
	assert_true(inner > 50);
	double centre[3] = { 0, 0, 0 }, wall[3] = { 0.22, 0, 0.05 };
	assert_int_equal(mc_mesh_contains(&m, centre), 0);
	assert_int_equal(mc_mesh_contains(&m, wall), 1);
	mc_mesh_free(&m);
	free(val);
}

static void
test_two_balls_two_pieces(void **unused)
{
	(void)unused;
	const double pi = 3.14159265358979323846, h = 0.02;
	struct mc_grid g;
	float *val = sample(two_balls, h, &g);
	struct mc_mesh m;
	assert_int_equal(mc_extract(&g, &m, NULL), 0);
	assert_watertight(&m);
	double exact = 2 * 4.0 / 3 * pi * 0.15 * 0.15 * 0.15;
	assert_true(fabs(m.volume - exact) < 0.02 * exact);
	double gap[3] = { 0, 0, 0 }, a[3] = { -0.2, 0.05, 0 }, b[3] = { 0.25, 0, -0.05 };
	assert_int_equal(mc_mesh_contains(&m, gap), 0);
	assert_int_equal(mc_mesh_contains(&m, a), 1);
	assert_int_equal(mc_mesh_contains(&m, b), 1);
	mc_mesh_free(&m);
	free(val);
}

static void
test_empty_and_full_fields_give_no_surface(void **unused)
{
	(void)unused;
	float val[27];
	struct mc_grid g = { { 3, 3, 3 }, { 0, 0, 0 }, 1, val };
	for (int i = 0; i < 27; i++)
		val[i] = 1;
	struct mc_mesh m;
	assert_int_equal(mc_extract(&g, &m, NULL), 0);
	assert_int_equal(m.ntri, 0);
	assert_true(m.volume == 0);
	double p[3] = { 1, 1, 1 };
	assert_int_equal(mc_mesh_contains(&m, p), 0);
	mc_mesh_free(&m);
	/* one point inside: a closed little octahedron-like piece around it */
	val[13] = -1;
	long *edges = NULL;
	assert_int_equal(mc_extract(&g, &m, &edges), 0);
	assert_true(m.ntri > 0);
	assert_watertight(&m);
	assert_true(m.volume > 0);
	for (int v = 0; v < m.nvert; v++)
		assert_int_equal(edges[2 * v], 13); /* every edge from the inside point */
	assert_int_equal(mc_mesh_contains(&m, p), 1);
	free(edges);
	mc_mesh_free(&m);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sphere_is_watertight_with_its_volume_and_outward_normals),
		cmocka_unit_test(test_hollow_ball_inner_surface_faces_the_hollow),
		cmocka_unit_test(test_two_balls_two_pieces),
		cmocka_unit_test(test_empty_and_full_fields_give_no_surface),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
