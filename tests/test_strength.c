/*
 * test_strength.c - percent capable: Phi against the standard normal's
 * printed quantiles and a Simpson integration of its density (both apart
 * from erfc); 100 Phi((S - |M|) / sigma) by hand; the tint's bands and
 * NIOSH's per-sex criteria at their edges; the shipped table's null answer
 * (no published curve transcribed, strength.c); and the curve machinery on
 * a made-up table whose numbers are the test's own, not a source's: the
 * resisting direction picked by the moment's sign, the sex, linear
 * interpolation between rows, nothing outside them, the least over joints.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "test_util.h"

#include <math.h>
#include <string.h>

#include "assess/strength.h"

/* the standard normal density integrated by Simpson's rule from -12 to z */
static double
simpson_phi(double z)
{
	const int n = 200000;
	double a = -12, h = (z - a) / n, s = 0;
	for (int i = 0; i <= n; i++) {
		double x = a + i * h, f = exp(-0.5 * x * x) / sqrt(2 * M_PI);
		s += f * (i == 0 || i == n ? 1 : i % 2 ? 4 : 2);
	}
	return s * h / 3;
}

static void
test_phi(void **state)
{
	(void)state;
	/* quantiles as printed in normal tables: z for 1 %, 25 %, 50 %, 75 %, 99 %, 97.5 % */
	static const double q[][2] = {
		{ -2.3263478740408408, 0.01 }, { -0.6744897501960817, 0.25 }, { 0, 0.5 },
		{ 0.6744897501960817, 0.75 },  { 2.3263478740408408, 0.99 },  { 1.959963984540054, 0.975 },
	};
	for (size_t i = 0; i < sizeof q / sizeof q[0]; i++)
		assert_near(strength_phi(q[i][0]), q[i][1], 1e-15);
	for (double z = -6; z <= 6; z += 0.25)
		assert_near(strength_phi(z), simpson_phi(z), 1e-12);
	/* far tails stay in [0, 1] and monotone */
	assert_true(strength_phi(-40) >= 0 && strength_phi(40) <= 1);
	assert_true(strength_phi(-8) < strength_phi(-7.9));
}

static void
test_percent(void **state)
{
	(void)state;
	assert_near(strength_percent(100, 20, 100), 50, 1e-12);
	assert_near(strength_percent(100, 20, 60), 100 * simpson_phi(2), 1e-9);
	/* the moment's sign picks the muscles, not the percent */
	assert_near(strength_percent(100, 20, -60), 100 * simpson_phi(2), 1e-9);
	assert_true(isnan(strength_percent(100, 0, 10)));
	assert_true(isnan(strength_percent(NAN, 10, 10)));
	assert_true(isnan(strength_percent(100, 10, INFINITY)));
}

static void
test_bands(void **state)
{
	(void)state;
	static const struct {
		double pct;
		int band, male, female;
	} rows[] = {
		{ 100, 0, 0, 0 }, { 99, 0, 0, 0 },   { 98.99, 1, 1, 0 }, { 75, 1, 1, 0 },
		{ 74.99, 2, 1, 1 }, { 25, 2, 1, 1 }, { 24.99, 3, 2, 1 }, { 1, 3, 2, 1 },
		{ 0.99, 3, 2, 2 }, { 0, 3, 2, 2 },
	};
	for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
		assert_int_equal(strength_band(rows[i].pct), rows[i].band);
		assert_int_equal(strength_niosh_band(rows[i].pct, STRENGTH_MALE), rows[i].male);
		assert_int_equal(strength_niosh_band(rows[i].pct, STRENGTH_FEMALE), rows[i].female);
	}
	assert_int_equal(strength_band(NAN), -1);
	assert_int_equal(strength_niosh_band(NAN, STRENGTH_MALE), -1);
}

static void
test_published_is_null(void **state)
{
	(void)state;
	struct strength_input in = { .sex = STRENGTH_FEMALE };
	in.moment[STRENGTH_ELBOW_R][STRENGTH_FLEXION] = 30;
	in.moment[STRENGTH_L5S1][STRENGTH_FLEXION] = -150;
	struct strength_result r;
	char err[128];
	assert_int_equal(strength_capable(&in, &r, err, sizeof err), 0);
	for (int j = 0; j < STRENGTH_NJOINTS; j++)
		for (int a = 0; a < STRENGTH_NAXES; a++) {
			assert_true(isnan(r.percent[j][a]));
			assert_true(isnan(r.mean[j][a]));
		}
	assert_true(isnan(r.capable));
	assert_int_equal(r.weakest_joint, -1);
	assert_int_equal(r.modelled, 0);
	assert_int_equal(strength_published.count, 0);
}

/* a made-up table (the test's numbers, no source): elbow flexors and extensors */
static const double flex_m[3][3] = { { 30, 60, 12 }, { 90, 80, 16 }, { 150, 50, 10 } };
static const double flex_f[2][3] = { { 30, 30, 6 }, { 150, 25, 5 } };
static const double ext_m[1][3] = { { 90, 40, 8 } };
static const double hip_m[2][3] = { { -20, 200, 40 }, { 120, 300, 60 } };
static const struct strength_curve made_up[] = {
	{ STRENGTH_ELBOW, STRENGTH_FLEXION, +1, STRENGTH_MALE, STRENGTH_FLEXION, 3, flex_m, "test" },
	{ STRENGTH_ELBOW, STRENGTH_FLEXION, +1, STRENGTH_FEMALE, STRENGTH_FLEXION, 2, flex_f, "test" },
	{ STRENGTH_ELBOW, STRENGTH_FLEXION, -1, STRENGTH_MALE, STRENGTH_FLEXION, 1, ext_m, "test" },
	{ STRENGTH_HIP, STRENGTH_FLEXION, -1, STRENGTH_MALE, STRENGTH_FLEXION, 2, hip_m, "test" },
};
static const struct strength_table table = { made_up, sizeof made_up / sizeof made_up[0] };

static void
test_curves(void **state)
{
	(void)state;
	struct strength_input in = { .sex = STRENGTH_MALE };
	struct strength_result r;
	char err[128];
	/* right elbow at 60 deg: halfway between the 30 and 90 rows: mean 70, SD 14 */
	in.angle[STRENGTH_ELBOW_R][STRENGTH_FLEXION] = 60;
	in.moment[STRENGTH_ELBOW_R][STRENGTH_FLEXION] = 49;
	/* left elbow at 90 deg needing extensors: mean 40, SD 8 */
	in.angle[STRENGTH_ELBOW_L][STRENGTH_FLEXION] = 90;
	in.moment[STRENGTH_ELBOW_L][STRENGTH_FLEXION] = -32;
	/* left hip outside its rows: no percent */
	in.angle[STRENGTH_HIP_L][STRENGTH_FLEXION] = 130;
	in.moment[STRENGTH_HIP_L][STRENGTH_FLEXION] = -100;
	/* right hip at 50 deg extensors: mean 250, SD 50, moment 150 */
	in.angle[STRENGTH_HIP_R][STRENGTH_FLEXION] = 50;
	in.moment[STRENGTH_HIP_R][STRENGTH_FLEXION] = -150;
	assert_int_equal(strength_capable_table(&table, &in, &r, err, sizeof err), 0);
	assert_near(r.mean[STRENGTH_ELBOW_R][STRENGTH_FLEXION], 70, 1e-12);
	assert_near(r.sd[STRENGTH_ELBOW_R][STRENGTH_FLEXION], 14, 1e-12);
	assert_near(r.percent[STRENGTH_ELBOW_R][STRENGTH_FLEXION], 100 * simpson_phi(1.5), 1e-9);
	assert_near(r.percent[STRENGTH_ELBOW_L][STRENGTH_FLEXION], 100 * simpson_phi(1), 1e-9);
	assert_true(isnan(r.percent[STRENGTH_HIP_L][STRENGTH_FLEXION]));
	assert_near(r.percent[STRENGTH_HIP_R][STRENGTH_FLEXION], 100 * simpson_phi(2), 1e-9);
	assert_true(isnan(r.percent[STRENGTH_ELBOW_R][STRENGTH_ABDUCTION]));
	assert_int_equal(r.modelled, 3);
	assert_near(r.capable, 100 * simpson_phi(1), 1e-9);
	assert_int_equal(r.weakest_joint, STRENGTH_ELBOW_L);
	assert_int_equal(r.weakest_axis, STRENGTH_FLEXION);
	/* the same elbow flexion, a woman: her own rows (mean 27.5, SD 5.5 at 90 deg) */
	in.sex = STRENGTH_FEMALE;
	in.angle[STRENGTH_ELBOW_R][STRENGTH_FLEXION] = 90;
	in.moment[STRENGTH_ELBOW_R][STRENGTH_FLEXION] = 16.5;
	assert_int_equal(strength_capable_table(&table, &in, &r, err, sizeof err), 0);
	assert_near(r.mean[STRENGTH_ELBOW_R][STRENGTH_FLEXION], 27.5, 1e-12);
	assert_near(r.percent[STRENGTH_ELBOW_R][STRENGTH_FLEXION], 100 * simpson_phi(2), 1e-9);
	/* no female extensor curve: null there */
	assert_true(isnan(r.percent[STRENGTH_ELBOW_L][STRENGTH_FLEXION]));
	/* at a row exactly, and at the table's ends */
	in.sex = STRENGTH_MALE;
	for (int i = 0; i < 3; i++) {
		in.angle[STRENGTH_ELBOW_R][STRENGTH_FLEXION] = flex_m[i][0];
		assert_int_equal(strength_capable_table(&table, &in, &r, err, sizeof err), 0);
		assert_near(r.mean[STRENGTH_ELBOW_R][STRENGTH_FLEXION], flex_m[i][1], 0);
		assert_near(r.sd[STRENGTH_ELBOW_R][STRENGTH_FLEXION], flex_m[i][2], 0);
	}
	in.angle[STRENGTH_ELBOW_R][STRENGTH_FLEXION] = 150.001;
	assert_int_equal(strength_capable_table(&table, &in, &r, err, sizeof err), 0);
	assert_true(isnan(r.percent[STRENGTH_ELBOW_R][STRENGTH_FLEXION]));
}

static void
test_bad_input(void **state)
{
	(void)state;
	struct strength_input in = { .sex = STRENGTH_MALE };
	struct strength_result r, keep;
	memset(&r, 0x33, sizeof r);
	keep = r;
	char err[128] = "";
	in.moment[STRENGTH_KNEE_L][STRENGTH_ROTATION] = NAN;
	assert_int_equal(strength_capable(&in, &r, err, sizeof err), -1);
	assert_non_null(strstr(err, "knee_l"));
	in.moment[STRENGTH_KNEE_L][STRENGTH_ROTATION] = 0;
	in.angle[STRENGTH_WRIST_R][STRENGTH_ABDUCTION] = -INFINITY;
	assert_int_equal(strength_capable(&in, &r, err, sizeof err), -1);
	in.angle[STRENGTH_WRIST_R][STRENGTH_ABDUCTION] = 0;
	in.sex = (enum strength_sex)7;
	assert_int_equal(strength_capable(&in, &r, err, sizeof err), -1);
	assert_memory_equal(&r, &keep, sizeof r);
	assert_string_equal(strength_joint_name(STRENGTH_L5S1), "l5s1");
	assert_string_equal(strength_axis_name(STRENGTH_ROTATION), "rotation");
	assert_int_equal(strength_joint_kind(STRENGTH_ANKLE_R), STRENGTH_ANKLE);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_phi),	   cmocka_unit_test(test_percent),
		cmocka_unit_test(test_bands),	   cmocka_unit_test(test_published_is_null),
		cmocka_unit_test(test_curves),	   cmocka_unit_test(test_bad_input),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
