/*
 * test_lowback.c - the L5/S1 single-equivalent-muscle model (Chaffin,
 * Andersson & Martin, Occupational Biomechanics, ch. 6) against a free-body
 * derivation written out here in scalar trigonometry (a trunk flexed by
 * theta, its weight at d along the trunk, a hand load at a stated reach),
 * against the one applied example seen with numbers (a lifting-lab report,
 * freeonlineresearchpapers.com "Ergonomics Lifting Lab": 250.3 N m needs
 * 5006 N of the extensor), and for what must hold whatever the constants:
 * monotone in the load and in trunk flexion, NIOSH's 3400 N / 6400 N
 * zones, the same answer in any world frame, bad input refused.
 *
 * No worked example of the textbook itself (a load, a posture, the printed
 * compression) was found in the sources reachable here; see docs/loads.md.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "test_util.h"

#include <math.h>
#include <string.h>

#include "assess/lowback.h"

#define DEG (M_PI / 180)

/*
 * A trunk flexed forward by theta in the world's y-z plane (y up, z forward):
 * the disc normal tilts with it. The upper body's weight w_u acts at d along
 * the trunk; a hand load w_h hangs at z_h in front of the disc centre.
 */
static struct lowback_input
flexed(double theta, double w_u, double d, double w_h, double z_h)
{
	struct lowback_input in = { 0 };
	double c = cos(theta), s = sin(theta);
	in.disc_normal[1] = c;
	in.disc_normal[2] = s;
	in.anterior[1] = -s; /* the trunk's own forward, as L5's frame gives it */
	in.anterior[2] = c;
	in.load_force[1] = -(w_u + w_h);
	/* weights at z = d sin(theta) and z_h: each moment w z about +x */
	in.load_moment[0] = w_u * d * s + w_h * z_h;
	return in;
}

static void
test_free_body(void **state)
{
	(void)state;
	const double e = 0.05, w_u = 450, d = 0.22, w_h = 150;
	for (int deg = 0; deg <= 90; deg += 15) {
		double th = deg * DEG, z_h = 0.30 + 0.45 * sin(th);
		struct lowback_input in = flexed(th, w_u, d, w_h, z_h);
		struct lowback_result r;
		char err[128];
		assert_int_equal(lowback_compute_arm(&in, e, &r, err, sizeof err), 0);
		double m = w_u * d * sin(th) + w_h * z_h;
		/* compression: the extensor's pull plus the weights' part along the disc normal */
		assert_near(r.muscle_force, m / e, 1e-9);
		assert_near(r.compression, m / e + (w_u + w_h) * cos(th), 1e-9);
		/* shear: the weights' part down the tilted disc plane, forward */
		assert_near(r.shear_ap, (w_u + w_h) * sin(th), 1e-9);
		assert_near(r.shear_lat, 0, 1e-9);
		assert_near(r.moment_sagittal, m, 1e-9);
		assert_near(r.moment_lateral, 0, 1e-9);
		assert_near(r.moment_axial, 0, 1e-9);
		assert_string_equal(r.level, "L5/S1");
		assert_int_equal(r.flags, 0);
	}
	/* upright with nothing in front: the disc carries the weight alone */
	struct lowback_input up = flexed(0, 500, 0.2, 0, 0);
	struct lowback_result r;
	char err[128];
	assert_int_equal(lowback_compute(&up, &r, err, sizeof err), 0);
	assert_near(r.compression, 500, 1e-9);
	assert_near(r.shear_ap, 0, 1e-9);
}

static void
test_lab_report(void **state)
{
	(void)state;
	/* the report's crane lift: 250.3 N m about the disc, 5006 N in the extensor */
	struct lowback_input in = flexed(0, 0, 0, 0, 0);
	in.load_moment[0] = 250.3;
	struct lowback_result r;
	char err[128];
	assert_int_equal(lowback_compute(&in, &r, err, sizeof err), 0);
	assert_near(lowback_moment_arm(), 0.05, 0);
	assert_near(r.muscle_force, 5006, 0.5);
	/* what the sagittal model leaves out, named for the reply */
	assert_int_equal(lowback_nunmodelled, 3);
	assert_string_equal(lowback_unmodelled[0], "abdominal_pressure");
}

static void
test_monotone_in_load(void **state)
{
	(void)state;
	for (int deg = 0; deg <= 90; deg += 10) {
		double th = deg * DEG, prev = -INFINITY;
		for (int kg = 0; kg <= 40; kg++) {
			struct lowback_input in = flexed(th, 450, 0.22, kg * 9.81, 0.3 + 0.45 * sin(th));
			struct lowback_result r;
			char err[128];
			assert_int_equal(lowback_compute(&in, &r, err, sizeof err), 0);
			assert_true(r.compression > prev);
			prev = r.compression;
		}
	}
}

/*
 * d(compression)/d(theta) = (w_u d + w_h s) cos(theta) / E - (w_u + w_h) sin(theta)
 * with the hands at s sin(theta) + c in front: positive while
 * tan(theta) < (w_u d + w_h s) / (E (w_u + w_h)), here above 75 deg. Past
 * that the disc turns away from the weight faster than the moment grows;
 * the test covers 0-70 deg and checks the turn where the formula puts it.
 */
static void
test_monotone_in_flexion(void **state)
{
	(void)state;
	const double w_u = 450, d = 0.22, s = 0.45, c = 0.3;
	for (int kg = 0; kg <= 30; kg += 5) {
		double w_h = kg * 9.81, prev = -INFINITY;
		for (int tenth = 0; tenth <= 700; tenth++) {
			double th = tenth * 0.1 * DEG;
			struct lowback_input in = flexed(th, w_u, d, w_h, c + s * sin(th));
			struct lowback_result r;
			char err[128];
			assert_int_equal(lowback_compute(&in, &r, err, sizeof err), 0);
			assert_true(r.compression > prev);
			prev = r.compression;
		}
		double turn = atan((w_u * d + w_h * s) / (lowback_moment_arm() * (w_u + w_h)));
		assert_true(turn > 75 * DEG);
		struct lowback_result a, b;
		char err[128];
		struct lowback_input ia = flexed(turn - 0.01, w_u, d, w_h, c + s * sin(turn - 0.01));
		struct lowback_input ib = flexed(turn + 0.01, w_u, d, w_h, c + s * sin(turn + 0.01));
		struct lowback_input im = flexed(turn, w_u, d, w_h, c + s * sin(turn));
		struct lowback_result m;
		assert_int_equal(lowback_compute(&ia, &a, err, sizeof err), 0);
		assert_int_equal(lowback_compute(&ib, &b, err, sizeof err), 0);
		assert_int_equal(lowback_compute(&im, &m, err, sizeof err), 0);
		assert_true(m.compression > a.compression && m.compression > b.compression);
	}
}

static void
test_limits(void **state)
{
	(void)state;
	static const struct {
		double compression;
		enum lowback_zone zone;
	} rows[] = {
		{ 0, LOWBACK_BELOW_ACTION },	    { 3400, LOWBACK_BELOW_ACTION },
		{ 3400.001, LOWBACK_ABOVE_ACTION }, { 6400, LOWBACK_ABOVE_ACTION },
		{ 6400.001, LOWBACK_ABOVE_MAX },    { 20000, LOWBACK_ABOVE_MAX },
	};
	for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
		/* upright: the compression is the downward load */
		struct lowback_input in = flexed(0, rows[i].compression, 0, 0, 0);
		struct lowback_result r;
		char err[128];
		assert_int_equal(lowback_compute(&in, &r, err, sizeof err), 0);
		assert_near(r.compression, rows[i].compression, 1e-9);
		assert_int_equal(r.zone, rows[i].zone);
		assert_near(r.action_limit, 3400, 0);
		assert_near(r.max_limit, 6400, 0);
	}
	assert_string_equal(lowback_zone_name(LOWBACK_ABOVE_ACTION), "above_action");
}

static void
test_flexor_unmodelled(void **state)
{
	(void)state;
	/* a pull backward at the hands extends the trunk: no extensor force */
	struct lowback_input in = flexed(0, 450, 0.2, 0, 0);
	in.load_moment[0] = -40;
	struct lowback_result r;
	char err[128];
	assert_int_equal(lowback_compute(&in, &r, err, sizeof err), 0);
	assert_near(r.muscle_force, 0, 0);
	assert_near(r.compression, 450, 1e-9);
	assert_true(r.flags & LOWBACK_FLEXOR_UNMODELLED);
}

/* rotates v by the rotation vector w (Rodrigues) */
static void
rotate(const double w[3], double v[3])
{
	double t = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
	double k[3] = { w[0] / t, w[1] / t, w[2] / t };
	double c = cos(t), s = sin(t), kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
	double x[3] = { k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2],
			k[0] * v[1] - k[1] * v[0] };
	for (int i = 0; i < 3; i++)
		v[i] = v[i] * c + x[i] * s + k[i] * kv * (1 - c);
}

static void
test_any_frame(void **state)
{
	(void)state;
	/* an asymmetric load: forward, sideways and twisting parts */
	struct lowback_input in = flexed(35 * DEG, 420, 0.21, 120, 0.5);
	in.load_force[0] = 30;
	in.load_moment[1] = 12;
	in.load_moment[2] = -9;
	/* not in the disc plane: only its in-plane part counts */
	for (int i = 0; i < 3; i++)
		in.anterior[i] += 0.2 * in.disc_normal[i];
	struct lowback_result r0, r1;
	char err[128];
	assert_int_equal(lowback_compute(&in, &r0, err, sizeof err), 0);
	static const double turns[3][3] = { { 0.3, -1.1, 2.0 }, { 2.9, 0.1, 0.2 }, { -0.7, 0.7, -0.7 } };
	for (int t = 0; t < 3; t++) {
		struct lowback_input j = in;
		rotate(turns[t], j.load_force);
		rotate(turns[t], j.load_moment);
		rotate(turns[t], j.disc_normal);
		rotate(turns[t], j.anterior);
		assert_int_equal(lowback_compute(&j, &r1, err, sizeof err), 0);
		assert_near(r1.compression, r0.compression, 1e-9);
		assert_near(r1.shear_ap, r0.shear_ap, 1e-9);
		assert_near(r1.shear_lat, r0.shear_lat, 1e-9);
		assert_near(r1.moment_lateral, r0.moment_lateral, 1e-9);
		assert_near(r1.moment_axial, r0.moment_axial, 1e-9);
	}
	/* the sideways force is lateral shear; l = n x a is the world's +x here */
	assert_near(r0.shear_lat, 30, 1e-9);
}

static void
test_bad_input(void **state)
{
	(void)state;
	struct lowback_result r, keep;
	memset(&r, 0x5a, sizeof r);
	keep = r;
	char err[128];
	struct lowback_input in = flexed(0.3, 400, 0.2, 50, 0.4);
	struct lowback_input bad = in;
	bad.load_force[2] = NAN;
	assert_int_equal(lowback_compute(&bad, &r, err, sizeof err), -1);
	bad = in;
	bad.disc_normal[1] *= 2;
	assert_int_equal(lowback_compute(&bad, &r, err, sizeof err), -1);
	bad = in;
	memcpy(bad.anterior, bad.disc_normal, sizeof bad.anterior);
	assert_int_equal(lowback_compute(&bad, &r, err, sizeof err), -1);
	bad = in;
	memset(bad.anterior, 0, sizeof bad.anterior);
	assert_int_equal(lowback_compute(&bad, &r, err, sizeof err), -1);
	assert_int_equal(lowback_compute_arm(&in, 0, &r, err, sizeof err), -1);
	assert_int_equal(lowback_compute_arm(&in, NAN, &r, err, sizeof err), -1);
	assert_memory_equal(&r, &keep, sizeof r);
	assert_true(strlen(err) > 0);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_free_body),	  cmocka_unit_test(test_lab_report),
		cmocka_unit_test(test_monotone_in_load),  cmocka_unit_test(test_monotone_in_flexion),
		cmocka_unit_test(test_limits),		  cmocka_unit_test(test_flexor_unmodelled),
		cmocka_unit_test(test_any_frame),	  cmocka_unit_test(test_bad_input),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
