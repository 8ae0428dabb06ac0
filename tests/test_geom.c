/*
 * test_geom.c - the analytic pieces of Appendix B against answers built
 * the other way round: closest points against the cross-product closed
 * form, a brute-force search and hand-worked vectors; ray and plane against
 * rays aimed at a known point of the plane; spoke angles against spokes
 * placed at known angles; all on seeded random inputs.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>

#include "figure/mathx.h"
#include "interact/geom.h"
#include "test_random.h"
#include "test_util.h"

#define TRIALS 200

/* u, v completing the unit a to a right-handed orthonormal basis (u x v = a) */
static void
basis(const double a[3], double u[3], double v[3])
{
	double t[3] = { 1, 0, 0 };
	if (fabs(a[0]) > 0.6) {
		t[0] = 0;
		t[1] = 1;
	}
	double k = mathx_dot(t, a);
	for (int i = 0; i < 3; i++)
		u[i] = t[i] - k * a[i];
	double n = sqrt(mathx_dot(u, u));
	for (int i = 0; i < 3; i++)
		u[i] /= n;
	mathx_cross(a, u, v);
}

static double
dist2_at(const double pa[3], const double da[3], const double pb[3], const double db[3],
	 double s, double t)
{
	double d2 = 0;
	for (int i = 0; i < 3; i++) {
		double w = pa[i] + s * da[i] - pb[i] - t * db[i];
		d2 += w * w;
	}
	return d2;
}

/* the hand-worked skew case: axis s(0,1,1), ray (1,2,5) + t(1,-1,-2): s = 3, t = 1/3 */
static void
test_closest_points_worked_example(void **unused)
{
	(void)unused;
	const double pa[3] = { 0, 0, 0 }, da[3] = { 0, 1, 1 };
	const double pb[3] = { 1, 2, 5 }, db[3] = { 1, -1, -2 };
	double st[2];
	assert_int_equal(geom_lines_closest(pa, da, pb, db, st), GEOM_HIT);
	assert_near(st[0], 3, 1e-12);
	assert_near(st[1], 1.0 / 3.0, 1e-12);

	/* an axis through the origin along x, a ray that crosses it at (2,0,0) */
	const double px[3] = { 0, 0, 0 }, dx[3] = { 1, 0, 0 };
	struct ray r = { { 2, 3, 10 }, { 0, -0.3, -1 } };
	double s, x[3];
	assert_int_equal(geom_axis_nearest_ray(px, dx, &r, &s, x), GEOM_HIT);
	assert_near(s, 2, 1e-12);
	assert_near(x[0], 2, 1e-12);
	assert_near(x[1], 0, 1e-12);
	assert_near(x[2], 0, 1e-12);
}

/*
 * Random skew lines: the closed form with cross products (an independent
 * derivation), the residual perpendicular to both lines, and no better
 * pair on a fine grid around the answer.
 */
static void
test_closest_points_random_skew_lines(void **unused)
{
	(void)unused;
	rng_state = 11;
	for (int k = 0; k < TRIALS; k++) {
		double pa[3], da[3], pb[3], db[3], n[3], w[3], c[3];
		rand_vec(-3, 3, pa);
		rand_vec(-3, 3, pb);
		rand_vec(-2, 2, da);
		rand_vec(-2, 2, db);
		mathx_cross(da, db, n);
		double nn = mathx_dot(n, n);
		if (nn < 1e-2 * mathx_dot(da, da) * mathx_dot(db, db))
			continue; /* nearly parallel: a separate test */
		double st[2];
		assert_int_equal(geom_lines_closest(pa, da, pb, db, st), GEOM_HIT);
		for (int i = 0; i < 3; i++)
			w[i] = pb[i] - pa[i];
		mathx_cross(w, db, c);
		double s_ref = mathx_dot(c, n) / nn;
		mathx_cross(w, da, c);
		double t_ref = mathx_dot(c, n) / nn;
		assert_near(st[0], s_ref, 1e-9 * (1 + fabs(s_ref)));
		assert_near(st[1], t_ref, 1e-9 * (1 + fabs(t_ref)));
		double r[3];
		for (int i = 0; i < 3; i++)
			r[i] = pa[i] + st[0] * da[i] - pb[i] - st[1] * db[i];
		assert_near(mathx_dot(r, da), 0, 1e-9);
		assert_near(mathx_dot(r, db), 0, 1e-9);
		/* brute force: nothing on a grid around the answer comes closer */
		double best = dist2_at(pa, da, pb, db, st[0], st[1]);
		for (int i = -5; i <= 5; i++)
			for (int j = -5; j <= 5; j++)
				assert_true(dist2_at(pa, da, pb, db, st[0] + 0.01 * i,
						     st[1] + 0.01 * j) >= best - 1e-12);
	}
}

static void
test_closest_points_parallel_lines(void **unused)
{
	(void)unused;
	const double pa[3] = { 1, 2, 3 }, da[3] = { 0, 0, 2 };
	const double pb[3] = { 4, 2, -1 }, db[3] = { 0, 0, -1 };
	double st[2];
	assert_int_equal(geom_lines_closest(pa, da, pb, db, st), GEOM_PARALLEL);
	/* s = 0, t the foot of pa on b: pb + t db has z = 3 at t = -4 */
	assert_near(st[0], 0, 0);
	assert_near(st[1], -4, 1e-12);
	const double zero[3] = { 0, 0, 0 };
	assert_int_equal(geom_lines_closest(pa, zero, pb, db, st), GEOM_DEGENERATE);
	/* a mouse line along the axis has no nearest point */
	struct ray r = { { 0, 0, 5 }, { 0, 0, -1 } };
	assert_int_equal(geom_axis_nearest_ray(pa, da, &r, NULL, NULL), GEOM_PARALLEL);
}

/* a mouse line pointing away from the axis: its nearest point is behind the eye */
static void
test_axis_nearest_ray_behind(void **unused)
{
	(void)unused;
	const double p[3] = { 0, 0, 0 }, a[3] = { 1, 0, 0 };
	struct ray r = { { 0, 1, 5 }, { 0, 0.6, 0.8 } };
	double s = 42;
	assert_int_equal(geom_axis_nearest_ray(p, a, &r, &s, NULL), GEOM_BEHIND);
	assert_near(s, 42, 0);
}

static void
test_ray_plane_worked_example(void **unused)
{
	(void)unused;
	/* plane y = 0; ray (1,2,3) + t(0,-1,-1) meets it at t = 2, (1,0,1) */
	const double p0[3] = { 5, 0, -7 }, n[3] = { 0, 3, 0 };
	double d[3] = { 0, -1, -1 };
	struct ray r = { { 1, 2, 3 }, { 0, 0, 0 } };
	geom_normalize(d, r.d);
	double t, x[3];
	assert_int_equal(geom_ray_plane(&r, p0, n, &t, x), GEOM_HIT);
	assert_near(t, 2 * sqrt(2), 1e-12);
	assert_near(x[0], 1, 1e-12);
	assert_near(x[1], 0, 1e-12);
	assert_near(x[2], 1, 1e-12);
}

/* rays aimed at a known point of a random plane, from in front and from behind */
static void
test_ray_plane_random(void **unused)
{
	(void)unused;
	rng_state = 12;
	for (int k = 0; k < TRIALS; k++) {
		double p0[3], n[3], u[3], v[3], d[3], x[3], o[3];
		rand_vec(-3, 3, p0);
		rand_unit(n);
		basis(n, u, v);
		double a = span(-2, 2), b = span(-2, 2), t = span(0.1, 10);
		for (int i = 0; i < 3; i++)
			x[i] = p0[i] + a * u[i] + b * v[i];
		do
			rand_unit(d);
		while (fabs(mathx_dot(d, n)) < 0.05);
		for (int i = 0; i < 3; i++)
			o[i] = x[i] - t * d[i];
		struct ray r = { { o[0], o[1], o[2] }, { d[0], d[1], d[2] } };
		double nk[3] = { 2.5 * n[0], 2.5 * n[1], 2.5 * n[2] }, tt, hit[3];
		assert_int_equal(geom_ray_plane(&r, p0, nk, &tt, hit), GEOM_HIT);
		assert_near(tt, t, 1e-9);
		for (int i = 0; i < 3; i++)
			assert_near(hit[i], x[i], 1e-9);
		/* the same line walked the other way meets the plane behind its origin */
		for (int i = 0; i < 3; i++)
			r.d[i] = -d[i];
		assert_int_equal(geom_ray_plane(&r, p0, nk, &tt, hit), GEOM_BEHIND);
		/* and a ray along the plane never meets it */
		for (int i = 0; i < 3; i++)
			r.d[i] = u[i];
		assert_int_equal(geom_ray_plane(&r, p0, nk, &tt, hit), GEOM_PARALLEL);
	}
}

static void
test_spoke_angle_worked_examples(void **unused)
{
	(void)unused;
	const double x[3] = { 1, 0, 0 }, y[3] = { 0, 1, 0 }, z[3] = { 0, 0, 1 };
	const double mz[3] = { 0, 0, -1 }, xy[3] = { 1, 1, 0 };
	double a;
	assert_int_equal(geom_spoke_angle(z, x, y, &a), GEOM_HIT);
	assert_near(a, M_PI / 2, 1e-15);
	assert_int_equal(geom_spoke_angle(mz, x, xy, &a), GEOM_HIT);
	assert_near(a, -M_PI / 4, 1e-15);
	/* just past the back of the wheel: the short way round, negative */
	const double back[3] = { -1, -1e-9, 0 };
	assert_int_equal(geom_spoke_angle(z, x, back, &a), GEOM_HIT);
	assert_near(a, -M_PI, 1e-8);
	/* a spoke along the axis has no direction in the wheel's plane */
	assert_int_equal(geom_spoke_angle(z, x, z, &a), GEOM_DEGENERATE);
}

/* spokes placed at known angles in a random wheel, with an offset along the axis */
static void
test_spoke_angle_random(void **unused)
{
	(void)unused;
	rng_state = 13;
	for (int k = 0; k < TRIALS; k++) {
		double a[3], u[3], v[3], s0[3], s1[3];
		rand_unit(a);
		basis(a, u, v);
		double t0 = span(-M_PI, M_PI), t1 = span(-M_PI, M_PI);
		double r0 = span(0.1, 3), r1 = span(0.1, 3), h0 = span(-2, 2), h1 = span(-2, 2);
		for (int i = 0; i < 3; i++) {
			s0[i] = r0 * (cos(t0) * u[i] + sin(t0) * v[i]) + h0 * a[i];
			s1[i] = r1 * (cos(t1) * u[i] + sin(t1) * v[i]) + h1 * a[i];
		}
		double want = t1 - t0, got;
		while (want > M_PI)
			want -= 2 * M_PI;
		while (want <= -M_PI)
			want += 2 * M_PI;
		/* a longer axis gives the same angle */
		double a3[3] = { 3 * a[0], 3 * a[1], 3 * a[2] };
		assert_int_equal(geom_spoke_angle(a3, s0, s1, &got), GEOM_HIT);
		assert_near(got, want, 1e-9);
	}
}

/* a direction built at a known angle from the axis */
static void
test_line_angle(void **unused)
{
	(void)unused;
	rng_state = 14;
	for (int k = 0; k < TRIALS; k++) {
		double a[3], u[3], v[3], b[3];
		rand_unit(a);
		basis(a, u, v);
		double theta = span(0, M_PI), len = span(0.1, 5);
		for (int i = 0; i < 3; i++)
			b[i] = len * (cos(theta) * a[i] + sin(theta) * u[i]);
		double want = theta <= M_PI / 2 ? theta : M_PI - theta;
		assert_near(geom_line_angle(a, b), want, 1e-12);
	}
	const double zero[3] = { 0, 0, 0 }, x[3] = { 1, 0, 0 };
	assert_near(geom_line_angle(zero, x), 0, 0);
}

/* against the quaternion route of mathx, and what a rotation must do to its own basis */
static void
test_rotation(void **unused)
{
	(void)unused;
	rng_state = 15;
	for (int k = 0; k < TRIALS; k++) {
		double a[3], u[3], v[3], q[4], ref[9], r[9];
		rand_unit(a);
		basis(a, u, v);
		double angle = span(-7, 7);
		mathx_quat_axis_angle(a, angle, q);
		mathx_quat_to_mat(q, ref);
		geom_rotation(a, angle, r);
		for (int i = 0; i < 9; i++)
			assert_near(r[i], ref[i], 1e-12);
		double ru[3], au[3];
		for (int i = 0; i < 3; i++) {
			ru[i] = r[3 * i] * u[0] + r[3 * i + 1] * u[1] + r[3 * i + 2] * u[2];
			au[i] = r[3 * i] * a[0] + r[3 * i + 1] * a[1] + r[3 * i + 2] * a[2];
		}
		for (int i = 0; i < 3; i++) {
			assert_near(ru[i], cos(angle) * u[i] + sin(angle) * v[i], 1e-12);
			assert_near(au[i], a[i], 1e-12);
		}
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_closest_points_worked_example),
		cmocka_unit_test(test_closest_points_random_skew_lines),
		cmocka_unit_test(test_closest_points_parallel_lines),
		cmocka_unit_test(test_axis_nearest_ray_behind),
		cmocka_unit_test(test_ray_plane_worked_example),
		cmocka_unit_test(test_ray_plane_random),
		cmocka_unit_test(test_spoke_angle_worked_examples),
		cmocka_unit_test(test_spoke_angle_random),
		cmocka_unit_test(test_line_angle),
		cmocka_unit_test(test_rotation),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
