/*
 * test_collide.c - mesh distances and contacts (fit/collide.h) against
 * analytic answers: two boxes apart along an axis (the gap, and closest
 * points on the facing faces), a box turned 45 degrees (its edge's
 * distance), boxes overlapping (the overlap as the penetration depth),
 * tessellated spheres (the centres' distance less the radii, within the
 * tessellation's sag), and malformed meshes refused.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fit/collide.h"

/* an axis-aligned box of half sizes h about the origin: 8 vertices, 12 triangles */
static struct collide_mesh *
box(double hx, double hy, double hz)
{
	float p[24];
	for (int i = 0; i < 8; i++) {
		p[3 * i] = (float)((i & 1) ? hx : -hx);
		p[3 * i + 1] = (float)((i & 2) ? hy : -hy);
		p[3 * i + 2] = (float)((i & 4) ? hz : -hz);
	}
	static const unsigned t[36] = { 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
					2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5 };
	char err[128];
	struct collide_mesh *m = collide_mesh_make(p, 8, t, 12, err, sizeof err);
	assert_non_null(m);
	return m;
}

/* a sphere of radius r: an octahedron subdivided n times, its vertices on the sphere */
static struct collide_mesh *
sphere(double r, int n, double *sag)
{
	int nv = 6, nt = 8, cap_t = 8 << (2 * n), cap_v = cap_t * 3;
	float *p = malloc(sizeof(float) * 3 * (size_t)cap_v);
	unsigned *t = malloc(sizeof(unsigned) * 3 * (size_t)cap_t);
	unsigned *t2 = malloc(sizeof(unsigned) * 3 * (size_t)cap_t);
	static const float o[18] = { 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1 };
	static const unsigned ot[24] = { 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4,
					 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5 };
	memcpy(p, o, sizeof o);
	memcpy(t, ot, sizeof ot);
	for (int level = 0; level < n; level++) {
		int k = 0;
		for (int i = 0; i < nt; i++) {
			unsigned v[3] = { t[3 * i], t[3 * i + 1], t[3 * i + 2] }, mid[3];
			for (int e = 0; e < 3; e++) { /* a midpoint a triangle (duplicates are harmless) */
				float *a = p + 3 * v[e], *b = p + 3 * v[(e + 1) % 3], *c = p + 3 * nv;
				double l = 0;
				for (int j = 0; j < 3; j++) {
					c[j] = (a[j] + b[j]) / 2;
					l += (double)c[j] * c[j];
				}
				for (int j = 0; j < 3; j++)
					c[j] = (float)(c[j] / sqrt(l));
				mid[e] = (unsigned)nv++;
			}
			unsigned q[12] = { v[0], mid[0], mid[2], mid[0], v[1], mid[1],
					   mid[2], mid[1], v[2], mid[0], mid[1], mid[2] };
			memcpy(t2 + 3 * k, q, sizeof q);
			k += 4;
		}
		nt = k;
		memcpy(t, t2, sizeof(unsigned) * 3 * (size_t)nt);
	}
	/* the sag: the smallest distance from the centre to a triangle's plane */
	double inner = 1;
	for (int i = 0; i < nt; i++) {
		float *a = p + 3 * t[3 * i], *b = p + 3 * t[3 * i + 1], *c = p + 3 * t[3 * i + 2];
		double u[3], w[3], nrm[3];
		for (int j = 0; j < 3; j++) {
			u[j] = b[j] - a[j];
			w[j] = c[j] - a[j];
		}
		nrm[0] = u[1] * w[2] - u[2] * w[1];
		nrm[1] = u[2] * w[0] - u[0] * w[2];
		nrm[2] = u[0] * w[1] - u[1] * w[0];
		double l = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
		double d = fabs(nrm[0] * a[0] + nrm[1] * a[1] + nrm[2] * a[2]) / l;
		inner = d < inner ? d : inner;
	}
	*sag = r * (1 - inner);
	for (int i = 0; i < 3 * nv; i++)
		p[i] = (float)(p[i] * r);
	char err[128];
	struct collide_mesh *m = collide_mesh_make(p, nv, t, nt, err, sizeof err);
	assert_non_null(m);
	free(p);
	free(t);
	free(t2);
	return m;
}

static struct xform
at(double x, double y, double z, double yaw_deg)
{
	struct xform f;
	double c = cos(yaw_deg * M_PI / 180), s = sin(yaw_deg * M_PI / 180);
	double r[9] = { c, -s, 0, s, c, 0, 0, 0, 1 }; /* about z */
	memcpy(f.r, r, sizeof r);
	f.p[0] = x;
	f.p[1] = y;
	f.p[2] = z;
	return f;
}

static void
test_boxes_apart(void **st)
{
	(void)st;
	struct collide_mesh *a = box(0.5, 0.5, 0.5), *b = box(0.5, 0.5, 0.5);
	struct xform xa = at(0, 0, 0, 0), xb = at(1.5, 0.2, -0.1, 0);
	struct collide_result r;
	struct collide_scratch *sc = collide_scratch_make();
	assert_int_equal(collide_distance(sc, a, &xa, b, &xb, &r), 0);
	assert_true(fabs(r.distance - 0.5) < 1e-9);
	/* the closest points lie on the facing faces, straight across */
	assert_true(fabs(r.pa[0] - 0.5) < 1e-9);
	assert_true(fabs(r.pb[0] - 1.0) < 1e-9);
	assert_true(fabs(r.pa[1] - r.pb[1]) < 1e-9 && fabs(r.pa[2] - r.pb[2]) < 1e-9);
	assert_true(r.pa[1] >= -0.3 - 1e-9 && r.pa[1] <= 0.5 + 1e-9);
	assert_int_equal(collide_overlap(sc, a, &xa, b, &xb), 0);
	/* moved apart: the mesh itself is not rebuilt, only placed */
	xb = at(0, 3, 0, 0);
	assert_int_equal(collide_distance(sc, a, &xa, b, &xb, &r), 0);
	assert_true(fabs(r.distance - 2.0) < 1e-9);
	collide_mesh_free(a);
	collide_mesh_free(b);
	collide_scratch_free(sc);
}

static void
test_box_turned(void **st)
{
	(void)st;
	struct collide_mesh *a = box(0.5, 0.5, 0.5), *b = box(0.5, 0.5, 0.5);
	struct xform xa = at(0, 0, 0, 0), xb = at(2, 0, 0, 45);
	struct collide_result r;
	struct collide_scratch *sc = collide_scratch_make();
	assert_int_equal(collide_distance(sc, a, &xa, b, &xb, &r), 0);
	/* b's vertical edge at x = 2 - sqrt(2)/2 faces a's face at x = 0.5 */
	double want = 2 - sqrt(2) / 2 - 0.5;
	assert_true(fabs(r.distance - want) < 1e-6);
	assert_true(fabs(r.pb[0] - (2 - sqrt(2) / 2)) < 1e-6 && fabs(r.pb[1]) < 1e-6);
	collide_mesh_free(a);
	collide_mesh_free(b);
	collide_scratch_free(sc);
}

static void
test_boxes_overlap(void **st)
{
	(void)st;
	struct collide_mesh *a = box(0.5, 0.5, 0.5), *b = box(0.25, 0.25, 0.25);
	/* b's face 0.1 inside a's face at x = 0.5 */
	struct xform xa = at(0, 0, 0, 0), xb = at(0.5 + 0.25 - 0.1, 0, 0, 0);
	struct collide_result r;
	struct collide_scratch *sc = collide_scratch_make();
	assert_int_equal(collide_distance(sc, a, &xa, b, &xb, &r), 0);
	printf("collide: overlap 0.1: distance %.9f at %.6f %.6f %.6f\n", r.distance, r.pa[0], r.pa[1],
	       r.pa[2]);
	assert_true(r.distance < 0);
	assert_true(fabs(r.distance + 0.1) < 1e-6);
	assert_int_equal(collide_overlap(sc, a, &xa, b, &xb), 1);
	collide_mesh_free(a);
	collide_mesh_free(b);
	collide_scratch_free(sc);
}

static void
test_spheres(void **st)
{
	(void)st;
	double sag_a, sag_b;
	struct collide_mesh *a = sphere(0.3, 4, &sag_a), *b = sphere(0.2, 4, &sag_b);
	struct collide_scratch *sc = collide_scratch_make();
	for (int k = 0; k < 20; k++) {
		double d = 0.52 + 0.05 * k, yaw = 0.3 * k; /* radians */
		struct xform xa = at(0.1, 0.2, 0.3, 0), xb = at(0.1 + d * cos(yaw), 0.2 + d * sin(yaw), 0.3, 0);
		struct collide_result r;
		assert_int_equal(collide_distance(sc, a, &xa, b, &xb, &r), 0);
		double want = d - 0.5;
		/* the tessellated spheres lie between their inscribed and circumscribed ones
		 * (the vertices are floats: 1e-7 m at these radii) */
		if (r.distance < want - 1e-6 || r.distance > want + sag_a + sag_b + 1e-6)
			printf("collide: spheres %.3f apart: %.9f, want %.9f + [0, %.9f]\n", d, r.distance,
			       want, sag_a + sag_b);
		assert_true(r.distance >= want - 1e-6);
		assert_true(r.distance <= want + sag_a + sag_b + 1e-6);
		/* the closest points lie on the meshes: within the sag of each sphere */
		double la = 0, lb = 0;
		for (int j = 0; j < 3; j++) {
			la += (r.pa[j] - xa.p[j]) * (r.pa[j] - xa.p[j]);
			lb += (r.pb[j] - xb.p[j]) * (r.pb[j] - xb.p[j]);
		}
		assert_true(sqrt(la) <= 0.3 + 1e-6 && sqrt(la) >= 0.3 - sag_a - 1e-6);
		assert_true(sqrt(lb) <= 0.2 + 1e-6 && sqrt(lb) >= 0.2 - sag_b - 1e-6);
	}
	collide_mesh_free(a);
	collide_mesh_free(b);
	collide_scratch_free(sc);
}

static void
test_malformed_refused(void **st)
{
	(void)st;
	char err[128];
	float p[9] = { 0, 0, 0, 1, 0, 0, 0, 1, 0 };
	unsigned bad[3] = { 0, 1, 3 }, good[3] = { 0, 1, 2 };
	assert_null(collide_mesh_make(p, 3, bad, 1, err, sizeof err));
	assert_non_null(strstr(err, "vertex 3"));
	assert_null(collide_mesh_make(p, 0, good, 0, err, sizeof err));
	p[4] = NAN;
	assert_null(collide_mesh_make(p, 3, good, 1, err, sizeof err));
	assert_non_null(strstr(err, "not finite"));
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_boxes_apart),
		cmocka_unit_test(test_box_turned),
		cmocka_unit_test(test_boxes_overlap),
		cmocka_unit_test(test_spheres),
		cmocka_unit_test(test_malformed_refused),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
