/*
 * test_population.c - populations: the multivariate normal's arithmetic
 * against naive references and closed forms, the CSV reader against a
 * naive two-pass computation of the same file, its refusals, and the
 * predictions' and families' defining properties.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/mvn.h"
#include "figure/population.h"
#include "figure/population_csv.h"

/* a deterministic uniform in [0, 1) (splitmix64) */
static double
uniform(uint64_t *s)
{
	uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
	return (double)((z ^ (z >> 31)) >> 11) / 9007199254740992.0;
}

/* a random symmetric positive definite n x n matrix: B B^T + n I */
static void
random_spd(uint64_t *seed, int n, double *a)
{
	double b[16 * 16];
	for (int i = 0; i < n * n; i++)
		b[i] = uniform(seed) * 2 - 1;
	for (int i = 0; i < n; i++)
		for (int j = 0; j < n; j++) {
			double s = i == j ? n : 0;
			for (int k = 0; k < n; k++)
				s += b[i * n + k] * b[j * n + k];
			a[i * n + j] = s;
		}
}

static void
test_cholesky_solves(void **state)
{
	(void)state;
	uint64_t seed = 1;
	for (int n = 1; n <= 12; n++) {
		double a[144], l[144], b[12], x[12];
		random_spd(&seed, n, a);
		memcpy(l, a, sizeof a);
		assert_int_equal(mvn_cholesky(l, n), 0);
		/* L L^T = A, element by element */
		for (int i = 0; i < n; i++)
			for (int j = 0; j < n; j++) {
				double s = 0;
				for (int k = 0; k < n; k++)
					s += l[i * n + k] * l[j * n + k];
				assert_near(s, a[i * n + j], 1e-12 * n);
			}
		for (int i = 0; i < n; i++)
			x[i] = b[i] = uniform(&seed);
		mvn_cholesky_solve(l, n, x);
		for (int i = 0; i < n; i++) { /* A x = b */
			double s = 0;
			for (int k = 0; k < n; k++)
				s += a[i * n + k] * x[k];
			assert_near(s, b[i], 1e-12 * n);
		}
	}
	/* a singular matrix (second row twice the first) and a zero one are refused */
	double sing[4] = { 1, 2, 2, 4 }, zero[1] = { 0 };
	assert_int_equal(mvn_cholesky(sing, 2), -1);
	assert_int_equal(mvn_cholesky(zero, 1), -1);
}

static void
test_eigen_reconstructs(void **state)
{
	(void)state;
	uint64_t seed = 2;
	for (int n = 1; n <= 10; n++) {
		double a[100], w[100], lam[10], v[100];
		random_spd(&seed, n, a);
		memcpy(w, a, sizeof a);
		assert_int_equal(mvn_eigen(w, n, lam, v), 0);
		for (int i = 1; i < n; i++)
			assert_true(lam[i] <= lam[i - 1]);
		/* A v_i = lambda_i v_i, and the vectors orthonormal */
		for (int i = 0; i < n; i++)
			for (int r = 0; r < n; r++) {
				double s = 0;
				for (int k = 0; k < n; k++)
					s += a[r * n + k] * v[k * n + i];
				assert_near(s, lam[i] * v[r * n + i], 1e-11 * n * n);
			}
		for (int i = 0; i < n; i++)
			for (int j = 0; j < n; j++) {
				double s = 0;
				for (int k = 0; k < n; k++)
					s += v[k * n + i] * v[k * n + j];
				assert_near(s, i == j, 1e-12 * n);
			}
	}
	/* [[2, 1], [1, 2]]: 3 along (1, 1)/sqrt 2, 1 along (1, -1)/sqrt 2 (signs: largest positive) */
	double a[4] = { 2, 1, 1, 2 }, lam[2], v[4];
	assert_int_equal(mvn_eigen(a, 2, lam, v), 0);
	assert_near(lam[0], 3, 1e-15);
	assert_near(lam[1], 1, 1e-15);
	assert_near(v[0], M_SQRT1_2, 1e-15);
	assert_near(v[2], M_SQRT1_2, 1e-15);
	assert_near(fabs(v[1]), M_SQRT1_2, 1e-15);
	assert_near(v[1] * v[3], -0.5, 1e-15);
}

static void
test_chi2_closed_forms(void **state)
{
	(void)state;
	static const double ps[] = { 1e-6, 0.01, 0.1, 0.5, 0.9, 0.95, 0.99, 0.999 };
	for (size_t i = 0; i < sizeof ps / sizeof *ps; i++) {
		double p = ps[i];
		/* two degrees of freedom: F(x) = 1 - exp(-x/2), so x = -2 ln(1 - p) */
		assert_near(mvn_chi2_quantile(p, 2), -2 * log1p(-p), 1e-13 * -2 * log1p(-p));
		/* four: F(x) = 1 - exp(-x/2)(1 + x/2) at the quantile is p */
		double x = mvn_chi2_quantile(p, 4);
		assert_near(1 - exp(-x / 2) * (1 + x / 2), p, 1e-13);
		/* one: F(x) = erf(sqrt(x/2)) */
		x = mvn_chi2_quantile(p, 1);
		assert_near(erf(sqrt(x / 2)), p, 1e-13);
	}
	/* the distribution function itself: k = 2 */
	for (double x = 0.1; x < 50; x *= 1.7)
		assert_near(mvn_chi2_cdf(x, 2), -expm1(-x / 2), 1e-14);
	assert_true(isnan(mvn_chi2_quantile(0, 3)));
	assert_true(isnan(mvn_chi2_quantile(1, 3)));
	assert_true(isnan(mvn_chi2_quantile(0.5, 0)));
}

/* ---- the CSV reader ----------------------------------------------------------- */

#define NPEOPLE 67

/* a synthetic population: people of both sexes with stature, weightkg (tenths) and span */
static char *
synthetic(double x[NPEOPLE][3], int sex[NPEOPLE])
{
	uint64_t seed = 3;
	size_t cap = 64 * NPEOPLE + 64, n = 0;
	char *text = malloc(cap);
	n += (size_t)snprintf(text + n, cap - n, "id,Stature,notes,Gender,weightkg,span\r\n");
	for (int i = 0; i < NPEOPLE; i++) {
		sex[i] = i < 31 ? HUMAN_FEMALE : HUMAN_MALE;
		double s = (sex[i] == HUMAN_FEMALE ? 1630 : 1750) + 120 * (uniform(&seed) - 0.5);
		x[i][0] = round(s);
		x[i][1] = round(300 + 0.25 * s + 150 * uniform(&seed)); /* tenths of a kilogram */
		x[i][2] = round(1.04 * s + 60 * (uniform(&seed) - 0.5));
		n += (size_t)snprintf(text + n, cap - n, "%d,%.0f,\"a, \"\"b\"\"\",%s,%.0f,%.0f\r\n", i,
				      x[i][0], sex[i] == HUMAN_FEMALE ? "Female" : "MALE", x[i][1],
				      x[i][2]);
	}
	return text;
}

static void
test_csv_moments_against_two_pass(void **state)
{
	(void)state;
	double x[NPEOPLE][3];
	int sex[NPEOPLE];
	char *text = synthetic(x, sex), err[256] = "", ignored[64];
	struct population *p = population_csv_read(text, strlen(text), "t.csv", ignored,
						   sizeof ignored, err, sizeof err);
	assert_non_null(p);
	assert_string_equal(ignored, "id,notes");
	int col[3] = { population_column("stature"), population_column("weightkg"),
		       population_column("span") };
	for (int c = 0; c < POPULATION_NCOL; c++)
		assert_int_equal(p->lacks[c], c != col[0] && c != col[1] && c != col[2]);
	for (int s = 0; s < 2; s++) {
		/* naive two-pass moments, weightkg in kilograms */
		double mean[3] = { 0 }, cov[3][3] = { { 0 } }, st[NPEOPLE];
		int n = 0;
		for (int i = 0; i < NPEOPLE; i++)
			if (sex[i] == s) {
				st[n++] = x[i][0];
				for (int j = 0; j < 3; j++)
					mean[j] += x[i][j] / (j == 1 ? 10 : 1);
			}
		for (int j = 0; j < 3; j++)
			mean[j] /= n;
		for (int i = 0; i < NPEOPLE; i++)
			if (sex[i] == s)
				for (int a = 0; a < 3; a++)
					for (int b = 0; b < 3; b++)
						cov[a][b] += (x[i][a] / (a == 1 ? 10 : 1) - mean[a]) *
							     (x[i][b] / (b == 1 ? 10 : 1) - mean[b]) / (n - 1);
		const struct population_group *g = &p->sex[s];
		assert_int_equal(g->n, n);
		for (int a = 0; a < 3; a++) {
			assert_near(g->mean[col[a]], mean[a], 1e-10 * fabs(mean[a]));
			for (int b = 0; b < 3; b++)
				assert_near(population_cov(g, col[a], col[b]), cov[a][b],
					    1e-9 * sqrt(cov[a][a] * cov[b][b]));
		}
		/* the statures sorted: percentile 0 the least, 100 the most */
		double lo, hi, med;
		assert_int_equal(population_percentile(p, s, 0, &lo, err, sizeof err), 0);
		assert_int_equal(population_percentile(p, s, 100, &hi, err, sizeof err), 0);
		assert_int_equal(population_percentile(p, s, 50, &med, err, sizeof err), 0);
		int below = 0, above = 0;
		for (int i = 0; i < n; i++) {
			assert_true(st[i] >= lo && st[i] <= hi);
			below += st[i] < med;
			above += st[i] > med;
		}
		assert_true(below <= n / 2 && above <= n / 2);
	}
	/* its statistics as text read back bit for bit */
	char *buf = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&buf, &len);
	assert_int_equal(population_stats_write(p, f), 0);
	fclose(f);
	struct population *q = population_stats_read(buf, len, err, sizeof err);
	assert_non_null(q);
	assert_memory_equal(q->lacks, p->lacks, sizeof p->lacks);
	for (int s = 0; s < 2; s++) {
		assert_int_equal(q->sex[s].n, p->sex[s].n);
		assert_memory_equal(q->sex[s].mean, p->sex[s].mean, sizeof(double) * POPULATION_NCOL);
		assert_memory_equal(q->sex[s].cov, p->sex[s].cov, sizeof(double) * POPULATION_NTRI);
		assert_memory_equal(q->sex[s].stature, p->sex[s].stature, sizeof(double) * p->sex[s].n);
	}
	/* cut anywhere, it is refused */
	for (size_t cut = 0; cut < len; cut += len / 37 + 1)
		assert_null(population_stats_read(buf, cut, err, sizeof err));
	free(buf);
	population_free(q);
	population_free(p);
	free(text);
}

static void
expect_refused_len(const char *text, size_t len, const char *why)
{
	char err[256] = "";
	struct population *p = population_csv_read(text, len, "p.csv", NULL, 0, err, sizeof err);
	if (p || !strstr(err, why))
		fail_msg("'%s': got '%s', want '%s'", text, err, why);
}

static void
expect_refused(const char *text, const char *why)
{
	expect_refused_len(text, strlen(text), why);
}

static void
test_csv_refusals(void **state)
{
	(void)state;
	expect_refused("", "p.csv:1: empty: no header");
	expect_refused("\n\n", "p.csv:2: empty: no header");
	expect_refused("stature\n1600\n", "p.csv:1: no sex column");
	expect_refused("sex,Gender,stature\n", "p.csv:1: two sex columns");
	expect_refused("sex,stature,STATURE\n", "p.csv:1: the column STATURE appears twice");
	expect_refused("sex,height\n", "p.csv:1: no column is one of ANSUR II's");
	expect_refused("sex,stature\n", "p.csv:1: no people");
	expect_refused("sex,stature\nf,1600\n\nf,\n", "p.csv:4: stature is empty");
	expect_refused("sex,stature\nf,0x640\n", "p.csv:2: stature '0x640' is not a number");
	expect_refused("sex,stature\nf,inf\n", "p.csv:2: stature 'inf' is not a number");
	expect_refused("sex,stature\nf,1600mm\n", "p.csv:2: stature '1600mm' is not a number");
	expect_refused("sex,stature\nf,-1600\n", "p.csv:2: stature -1600 is outside");
	expect_refused("sex,stature\nf,16000\n", "p.csv:2: stature 16000 is outside");
	expect_refused("sex,weightkg\nf,70\n", "p.csv:2: weightkg 70 is outside");
	expect_refused("sex,stature\nx,1600\n", "p.csv:2: sex 'x' is neither Male nor Female");
	expect_refused("sex,stature\n\"\",1600\n", "p.csv:2: no sex");
	expect_refused("sex,stature\nf\n", "p.csv:2: 1 fields where the header has 2");
	expect_refused("sex,stature\n\"f,1600\n", "p.csv:2: a quoted field does not close");
	expect_refused("sex,stature\n\"f\"x,1600\n", "p.csv:2: text after a quoted field");
	expect_refused_len("sex,stature\nf,16\00000\n", 19, "p.csv:2: a NUL byte");
	expect_refused("sex,stature\nf,1600\n", "p.csv:2: 1 women: a sex needs at least 30");
	/* the 1e9 check: numbers in exponent form are numbers */
	char text[4096] = "sex,stature\n";
	for (int i = 0; i < 30; i++)
		strcat(text, i % 2 ? "f,1.6e3\n" : "F,1650\n");
	char err[256];
	struct population *p = population_csv_read(text, strlen(text), "p.csv", NULL, 0, err,
						   sizeof err);
	assert_non_null(p);
	assert_int_equal(p->sex[HUMAN_FEMALE].n, 30);
	assert_int_equal(p->sex[HUMAN_MALE].n, 0);
	double mm;
	assert_int_equal(population_percentile(p, HUMAN_MALE, 50, &mm, err, sizeof err), -1);
	assert_string_equal(err, "the population has no men");
	population_free(p);
}

/* ---- predictions and families ------------------------------------------------ */

static void
test_prediction_properties(void **state)
{
	(void)state;
	const struct population *p = population_ansur2();
	char err[256];
	int st = population_column("stature"), wt = population_column("weightkg");
	int sit = population_column("sittingheight");
	double mean[POPULATION_NCOL], out[POPULATION_NCOL], again[POPULATION_NCOL], d, d2;
	/* nothing given: the means, distance 0 */
	assert_int_equal(population_predict(p, HUMAN_MALE, NULL, NULL, 0, mean, &d, err, sizeof err), 0);
	for (int c = 0; c < POPULATION_NCOL; c++)
		assert_near(mean[c], p->sex[HUMAN_MALE].mean[c], 0);
	assert_near(d, 0, 0);
	/* given the mean: the mean back */
	int cols[2] = { st, wt };
	double vals[2] = { mean[st], mean[wt] };
	assert_int_equal(population_predict(p, HUMAN_MALE, cols, vals, 2, out, &d, err, sizeof err), 0);
	for (int c = 0; c < POPULATION_NCOL; c++)
		assert_near(out[c], mean[c], 1e-9 * fabs(mean[c]));
	/* given stature and weight, the completed vector's distance over more columns is theirs */
	vals[0] = 1900;
	vals[1] = 70;
	assert_int_equal(population_predict(p, HUMAN_MALE, cols, vals, 2, out, &d, err, sizeof err), 0);
	assert_near(out[st], 1900, 0);
	assert_near(out[wt], 70, 0);
	int more[3] = { st, wt, sit };
	double mv[3] = { out[st], out[wt], out[sit] };
	assert_int_equal(population_predict(p, HUMAN_MALE, more, mv, 3, again, &d2, err, sizeof err), 0);
	assert_near(d2, d, 1e-9 * d);
	/* one sd of stature alone: distance 1 */
	double one = mean[st] + sqrt(population_cov(&p->sex[HUMAN_MALE], st, st));
	assert_int_equal(population_predict(p, HUMAN_MALE, &st, &one, 1, out, &d, err, sizeof err), 0);
	assert_near(d, 1, 1e-12);
	/* refusals */
	int twice[2] = { st, st };
	assert_int_equal(population_predict(p, HUMAN_MALE, twice, vals, 2, out, &d, err, sizeof err), -1);
	assert_string_equal(err, "stature is given twice");
	double nan2[2] = { NAN, 70 };
	assert_int_equal(population_predict(p, HUMAN_MALE, cols, nan2, 2, out, &d, err, sizeof err), -1);
	assert_string_equal(err, "stature is not a number");
	/* a human's definition from the completed vector */
	struct human_def hd = human_default_def(HUMAN_MALE);
	population_predict(p, HUMAN_MALE, cols, vals, 2, out, &d, err, sizeof err);
	population_to_human(out, &hd);
	assert_int_equal(hd.measure_given, (1u << HUMAN_MEASURE_N) - 1);
	assert_near(hd.stature, 1.9, 1e-15);
	assert_near(hd.mass, 70, 0);
	assert_near(hd.measure[HUMAN_M_SITTINGHEIGHT], out[sit], 0);
}

static void
test_family_properties(void **state)
{
	(void)state;
	const struct population *p = population_ansur2();
	const char *names[4] = { "stature", "weightkg", "sittingheight", "span" };
	int cols[4];
	for (int i = 0; i < 4; i++)
		cols[i] = population_column(names[i]);
	char err[256];
	enum { N = 24 };
	static double rows[(N + 1) * POPULATION_NCOL];
	double dist[N + 1];
	for (int k = 1; k <= 4; k++) {
		int n = k == 1 ? 2 : N;
		double r = sqrt(mvn_chi2_quantile(0.9, k));
		assert_int_equal(population_family(p, HUMAN_FEMALE, cols, k, 0.9, n, rows, dist, err,
						   sizeof err), 0);
		assert_near(dist[0], 0, 1e-12);
		for (int b = 1; b <= n; b++)
			assert_near(dist[b], r, 1e-9 * r);
		/* opposite axis ends are symmetric about the centre */
		for (int c = 0; c < POPULATION_NCOL; c++)
			assert_near(rows[POPULATION_NCOL + c] + rows[2 * POPULATION_NCOL + c],
				    2 * rows[c], 1e-9 * fabs(rows[c]));
		/* no two manikins alike */
		for (int a = 1; a <= n; a++)
			for (int b = a + 1; b <= n; b++) {
				double diff = 0;
				for (int i = 0; i < k; i++)
					diff += fabs(rows[a * POPULATION_NCOL + cols[i]] -
						     rows[b * POPULATION_NCOL + cols[i]]);
				assert_true(diff > 1);
			}
	}
	assert_int_equal(population_family(p, HUMAN_FEMALE, cols, 1, 0.9, 3, rows, dist, err,
					   sizeof err), -1);
	assert_int_equal(population_family(p, HUMAN_FEMALE, cols, 2, 1.0, 8, rows, dist, err,
					   sizeof err), -1);
	int same[2] = { cols[0], cols[0] };
	assert_int_equal(population_family(p, HUMAN_FEMALE, same, 2, 0.9, 8, rows, dist, err,
					   sizeof err), -1);
}

static void
test_stature_rank_inverts_the_percentile(void **state)
{
	(void)state;
	const struct population *p = population_ansur2();
	char err[256];
	double prev = -1, pct, mm;
	for (double s = 1400; s <= 2000; s += 0.7) {
		assert_int_equal(population_stature_rank(p, HUMAN_FEMALE, s, &pct, err, sizeof err), 0);
		assert_true(pct >= prev && pct >= 0 && pct <= 100); /* monotone, in range */
		prev = pct;
		/* between two different statures the rank is exact: the percentile gives s back */
		if (pct > 0 && pct < 100 && s != floor(s)) {
			assert_int_equal(population_percentile(p, HUMAN_FEMALE, pct, &mm, err, sizeof err), 0);
			assert_near(mm, s, 1e-9);
		}
	}
	assert_int_equal(population_stature_rank(p, HUMAN_MALE, 1000, &pct, err, sizeof err), 0);
	assert_near(pct, 0, 0);
	assert_int_equal(population_stature_rank(p, HUMAN_MALE, 2500, &pct, err, sizeof err), 0);
	assert_near(pct, 100, 0);
	/* a stature many share: the middle of their ranks, whose percentile is that stature */
	assert_int_equal(population_stature_rank(p, HUMAN_FEMALE, 1525, &pct, err, sizeof err), 0);
	assert_int_equal(population_percentile(p, HUMAN_FEMALE, pct, &mm, err, sizeof err), 0);
	assert_near(mm, 1525, 0);
	assert_true(pct > 4 && pct < 6);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_cholesky_solves),
		cmocka_unit_test(test_eigen_reconstructs),
		cmocka_unit_test(test_chi2_closed_forms),
		cmocka_unit_test(test_csv_moments_against_two_pass),
		cmocka_unit_test(test_csv_refusals),
		cmocka_unit_test(test_prediction_properties),
		cmocka_unit_test(test_family_properties),
		cmocka_unit_test(test_stature_rank_inverts_the_percentile),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
