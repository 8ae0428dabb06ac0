/* population.c - predictions, percentiles and boundary manikins of a population */
#include "figure/population.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "figure/mvn.h"
#include "figure/population_internal.h"

static const char *const sex_people[2] = { "men", "women" }; /* HUMAN_MALE, HUMAN_FEMALE */

static int
fail(char *err, size_t errlen, const char *fmt, ...)
{
	if (err && errlen) {
		va_list ap;
		va_start(ap, fmt);
		vsnprintf(err, errlen, fmt, ap);
		va_end(ap);
	}
	return -1;
}

const struct population *
population_ansur2(void)
{
	static const struct population ansur2 = {
		.sex = {
			[HUMAN_MALE] = { ANSUR2_N_MALE, ansur2_mean_male, ansur2_cov_male,
					 ansur2_stature_male },
			[HUMAN_FEMALE] = { ANSUR2_N_FEMALE, ansur2_mean_female, ansur2_cov_female,
					   ansur2_stature_female },
		},
	};
	return &ansur2;
}

void
population_free(struct population *p)
{
	if (!p || !p->owned)
		return;
	free((void *)p->sex[0].stature);
	free((void *)p->sex[1].stature);
	free(p->owned);
	free(p);
}

int
population_column(const char *name)
{
	for (int i = 0; i < POPULATION_NCOL; i++)
		if (!strcasecmp(name, ansur2_names[i]))
			return i;
	return -1;
}

const char *
population_column_name(int col)
{
	return col >= 0 && col < POPULATION_NCOL ? ansur2_names[col] : NULL;
}

/*
 * Half the smallest value of the column in ANSUR II to twice its largest:
 * wide enough for any adult population (ANSUR II's 6,068 soldiers span
 * small women to large men), narrow enough to catch a unit slip (a
 * stature in centimetres, a weight in kilograms where ANSUR II has tenths).
 */
void
population_bounds(int col, double *lo, double *hi)
{
	*lo = 0.5 * ansur2_min[col];
	*hi = 2.0 * ansur2_max[col];
}

double
population_cov(const struct population_group *g, int i, int j)
{
	return i >= j ? g->cov[i * (i + 1) / 2 + j] : g->cov[j * (j + 1) / 2 + i];
}

/* ---- statistics as text ---------------------------------------------------- */

int
population_stats_write(const struct population *p, FILE *f)
{
	fprintf(f, "population 1\ncolumns");
	for (int i = 0; i < POPULATION_NCOL; i++)
		if (!p->lacks[i])
			fprintf(f, " %s", ansur2_names[i]);
	fprintf(f, "\n");
	for (int s = 0; s < 2; s++) {
		const struct population_group *g = &p->sex[s];
		fprintf(f, "group %s %d\n", sex_people[s], g->n);
		if (!g->n)
			continue;
		fprintf(f, "mean");
		for (int i = 0; i < POPULATION_NCOL; i++)
			if (!p->lacks[i])
				fprintf(f, " %.17g", g->mean[i]);
		fprintf(f, "\ncov");
		for (int i = 0; i < POPULATION_NCOL; i++)
			for (int j = 0; j <= i; j++)
				if (!p->lacks[i] && !p->lacks[j])
					fprintf(f, " %.17g", population_cov(g, i, j));
		fprintf(f, "\nstature");
		if (!g->stature)
			fprintf(f, " -");
		for (int i = 0; g->stature && i < g->n; i++)
			fprintf(f, " %.17g", g->stature[i]);
		fprintf(f, "\n");
	}
	fprintf(f, "end\n");
	return ferror(f) ? -1 : 0;
}

/* the owned arrays of a population made here */
struct owned {
	double mean[2][POPULATION_NCOL];
	double cov[2][POPULATION_NTRI];
};

struct population *
population_new_owned(void)
{
	struct population *p = calloc(1, sizeof *p);
	struct owned *o = calloc(1, sizeof *o);
	if (!p || !o) {
		free(p);
		free(o);
		return NULL;
	}
	p->owned = o;
	memset(p->lacks, 1, sizeof p->lacks);
	for (int s = 0; s < 2; s++) {
		p->sex[s].mean = o->mean[s];
		p->sex[s].cov = o->cov[s];
	}
	return p;
}

/* a whitespace-separated token reader over the text */
struct tokens {
	const char *p, *end;
	char tok[64];
};

static const char *
next_token(struct tokens *t)
{
	while (t->p < t->end && (*t->p == ' ' || *t->p == '\n'))
		t->p++;
	size_t n = 0;
	while (t->p < t->end && *t->p != ' ' && *t->p != '\n') {
		if (n + 1 >= sizeof t->tok)
			return NULL;
		t->tok[n++] = *t->p++;
	}
	t->tok[n] = 0;
	return n ? t->tok : NULL;
}

static int
token_number(struct tokens *t, double *dest)
{
	const char *s = next_token(t);
	char *end;
	if (!s)
		return -1;
	*dest = strtod(s, &end);
	return *end || !isfinite(*dest) ? -1 : 0;
}

static int
expect(struct tokens *t, const char *word)
{
	const char *s = next_token(t);
	return s && !strcmp(s, word) ? 0 : -1;
}

struct population *
population_stats_read(const char *text, size_t len, char *err, size_t errlen)
{
	struct tokens t = { text, text + len, { 0 } };
	struct population *p = population_new_owned();
	struct owned *o = p ? p->owned : NULL;
	const char *s;
	if (!p) {
		fail(err, errlen, "out of memory");
		return NULL;
	}
	if (expect(&t, "population") < 0 || expect(&t, "1") < 0 || expect(&t, "columns") < 0)
		goto bad;
	/* the column names run to the first "group" */
	while ((s = next_token(&t)) && strcmp(s, "group")) {
		int c = population_column(s);
		if (c < 0 || !p->lacks[c])
			goto bad;
		p->lacks[c] = 0;
	}
	for (int sx = 0; sx < 2; sx++) {
		double n;
		if ((sx && expect(&t, "group") < 0) || expect(&t, sex_people[sx]) < 0 ||
		    token_number(&t, &n) < 0 || n < 0 || n > POPULATION_MAX_PEOPLE || n != floor(n))
			goto bad;
		struct population_group *g = &p->sex[sx];
		g->n = (int)n;
		if (!g->n)
			continue;
		if (expect(&t, "mean") < 0)
			goto bad;
		for (int i = 0; i < POPULATION_NCOL; i++)
			if (!p->lacks[i] && token_number(&t, &o->mean[sx][i]) < 0)
				goto bad;
		if (expect(&t, "cov") < 0)
			goto bad;
		for (int i = 0; i < POPULATION_NCOL; i++)
			for (int j = 0; j <= i; j++)
				if (!p->lacks[i] && !p->lacks[j] &&
				    token_number(&t, &o->cov[sx][i * (i + 1) / 2 + j]) < 0)
					goto bad;
		if (expect(&t, "stature") < 0)
			goto bad;
		if (p->lacks[population_column("stature")]) {
			if (expect(&t, "-") < 0)
				goto bad;
			continue;
		}
		double *st = malloc(sizeof *st * (size_t)g->n);
		g->stature = st;
		if (!st)
			goto bad;
		for (int i = 0; i < g->n; i++)
			if (token_number(&t, &st[i]) < 0 || (i && st[i] < st[i - 1]))
				goto bad;
	}
	if (expect(&t, "end") < 0)
		goto bad;
	return p;
bad:
	population_free(p);
	fail(err, errlen, "not a population's statistics");
	return NULL;
}

/* ---- predictions ------------------------------------------------------------ */

/* the group of a sex, or NULL with the error set */
static const struct population_group *
group(const struct population *p, enum human_sex sex, char *err, size_t errlen)
{
	if ((sex != HUMAN_MALE && sex != HUMAN_FEMALE) || !p->sex[sex].n) {
		fail(err, errlen, "the population has no %s",
		     sex == HUMAN_FEMALE ? "women" : sex == HUMAN_MALE ? "men" : "such sex");
		return NULL;
	}
	return &p->sex[sex];
}

int
population_percentile(const struct population *p, enum human_sex sex, double pct, double *mm,
		      char *err, size_t errlen)
{
	const struct population_group *g = group(p, sex, err, errlen);
	if (!g)
		return -1;
	if (!g->stature)
		return fail(err, errlen, "the population has no stature");
	if (!(pct >= 0 && pct <= 100))
		return fail(err, errlen, "a percentile is 0 to 100");
	double h = (g->n - 1) * pct / 100;
	int lo = (int)floor(h);
	if (lo >= g->n - 1) {
		*mm = g->stature[g->n - 1];
		return 0;
	}
	*mm = g->stature[lo] + (h - lo) * (g->stature[lo + 1] - g->stature[lo]);
	return 0;
}

int
population_stature_rank(const struct population *p, enum human_sex sex, double mm, double *pct,
			char *err, size_t errlen)
{
	const struct population_group *g = group(p, sex, err, errlen);
	if (!g)
		return -1;
	if (!g->stature)
		return fail(err, errlen, "the population has no stature");
	if (!isfinite(mm))
		return fail(err, errlen, "a stature is a number");
	const double *s = g->stature;
	int n = g->n;
	/* lo: the first at or above mm; hi: the last at or below it */
	int a = 0, b = n;
	while (a < b) {
		int m = (a + b) / 2;
		if (s[m] < mm)
			a = m + 1;
		else
			b = m;
	}
	int lo = a;
	a = 0, b = n;
	while (a < b) {
		int m = (a + b) / 2;
		if (s[m] <= mm)
			a = m + 1;
		else
			b = m;
	}
	int hi = a - 1;
	double h;
	if (lo <= hi) /* people of exactly that stature: the middle of their ranks */
		h = 0.5 * (lo + hi);
	else if (hi < 0)
		h = 0;
	else if (lo >= n)
		h = n - 1;
	else /* between two order statistics */
		h = hi + (mm - s[hi]) / (s[lo] - s[hi]);
	*pct = n > 1 ? 100 * h / (n - 1) : 50;
	return 0;
}

/* the given columns checked: present, in range, distinct, values finite */
static int
check_given(const struct population *p, const int *cols, const double *vals, int k, char *err,
	    size_t errlen)
{
	for (int i = 0; i < k; i++) {
		if (cols[i] < 0 || cols[i] >= POPULATION_NCOL)
			return fail(err, errlen, "no such measure");
		const char *name = ansur2_names[cols[i]];
		if (p->lacks[cols[i]])
			return fail(err, errlen, "the population has no %s", name);
		if (vals && !isfinite(vals[i]))
			return fail(err, errlen, "%s is not a number", name);
		for (int j = 0; j < i; j++)
			if (cols[j] == cols[i])
				return fail(err, errlen, "%s is given twice", name);
	}
	return 0;
}

int
population_predict(const struct population *p, enum human_sex sex, const int *cols,
		   const double *vals, int k, double *dest, double *dist, char *err, size_t errlen)
{
	const struct population_group *g = group(p, sex, err, errlen);
	if (!g || check_given(p, cols, vals, k, err, errlen) < 0)
		return -1;
	/* w = S11^-1 (x1 - mu1) by Cholesky */
	double *s11 = malloc(sizeof *s11 * (size_t)(k * k + k + 1)), *w = s11 ? s11 + k * k : NULL;
	if (!s11)
		return fail(err, errlen, "out of memory");
	for (int i = 0; i < k; i++) {
		for (int j = 0; j < k; j++)
			s11[i * k + j] = population_cov(g, cols[i], cols[j]);
		w[i] = vals[i] - g->mean[cols[i]];
	}
	if (mvn_cholesky(s11, k) < 0) {
		free(s11);
		return fail(err, errlen, "these %d measures are linearly dependent in the population "
			    "(their covariance is singular: too few people, or one follows from the others)",
			    k);
	}
	double d2 = 0;
	mvn_cholesky_solve(s11, k, w);
	for (int i = 0; i < k; i++)
		d2 += (vals[i] - g->mean[cols[i]]) * w[i];
	/* mu2 + S21 w */
	for (int c = 0; c < POPULATION_NCOL; c++) {
		if (p->lacks[c]) {
			dest[c] = NAN;
			continue;
		}
		double v = g->mean[c];
		for (int i = 0; i < k; i++)
			v += population_cov(g, c, cols[i]) * w[i];
		dest[c] = v;
	}
	for (int i = 0; i < k; i++)
		dest[cols[i]] = vals[i]; /* met exactly, not up to rounding */
	if (dist)
		*dist = sqrt(fmax(0, d2));
	free(s11);
	return 0;
}

/* ---- families of boundary manikins ----------------------------------------- */

/*
 * The unit direction of boundary manikin i (0-based) in the space of the
 * k principal components (population.h: axis ends, then halved angles in
 * the planes of two axes).
 */
static void
family_direction(int i, int k, double *u)
{
	memset(u, 0, sizeof *u * (size_t)k);
	if (i < 2 * k) {
		u[i / 2] = i % 2 ? -1 : 1;
		return;
	}
	i -= 2 * k;
	int pairs = k * (k - 1) / 2;
	for (int per = 4;; per *= 2) { /* points a plane at this level: 4, 8, 16 ... */
		if (i >= pairs * per) {
			i -= pairs * per;
			continue;
		}
		int pair = i / per, m = i % per, a = 0, b = 1;
		/* pairs in order (0,1) (0,2) (1,2) (0,3) ... */
		for (int q = 0; q < pair; q++)
			if (++a == b) {
				a = 0;
				b++;
			}
		double theta = (2 * m + 1) * M_PI / per; /* odd multiples of 180/per degrees */
		u[a] = cos(theta);
		u[b] = sin(theta);
		return;
	}
}

int
population_family(const struct population *p, enum human_sex sex, const int *cols, int k,
		  double coverage, int n, double *dest, double *dist, char *err, size_t errlen)
{
	const struct population_group *g = group(p, sex, err, errlen);
	if (!g || check_given(p, cols, NULL, k, err, errlen) < 0)
		return -1;
	if (k < 1)
		return fail(err, errlen, "a family needs at least one measure");
	if (!(coverage > 0 && coverage < 1))
		return fail(err, errlen, "coverage is above 0 and below 100 percent");
	if (n < 0 || n > POPULATION_FAMILY_MAX)
		return fail(err, errlen, "a family has 0 to %d boundary manikins", POPULATION_FAMILY_MAX);
	if (k == 1 && n > 2)
		return fail(err, errlen, "one measure has two boundary manikins, its ends (n <= 2)");
	size_t kk = (size_t)k * (size_t)k;
	double *r = malloc(sizeof *r * (3 * kk + 4 * (size_t)k));
	if (!r)
		return fail(err, errlen, "out of memory");
	double *v = r + kk, *lambda = v + kk, *sd = lambda + k, *u = sd + k, *x = u + k;
	/* the correlation matrix of the chosen measures, and its principal axes */
	for (int i = 0; i < k; i++)
		sd[i] = sqrt(population_cov(g, cols[i], cols[i]));
	for (int i = 0; i < k; i++)
		for (int j = 0; j < k; j++)
			r[i * k + j] = population_cov(g, cols[i], cols[j]) / (sd[i] * sd[j]);
	int rc = -1;
	if (mvn_eigen(r, k, lambda, v) < 0 || !(lambda[k - 1] > 1e-10 * lambda[0])) {
		fail(err, errlen, "these %d measures are linearly dependent in the population "
		     "(their covariance is singular)", k);
		goto out;
	}
	double radius = sqrt(mvn_chi2_quantile(coverage, k));
	if (population_predict(p, sex, cols, NULL, 0, dest, &dist[0], err, errlen) < 0)
		goto out;
	for (int b = 1; b <= n; b++) {
		family_direction(b - 1, k, u);
		/* z = V diag(sqrt(lambda)) (radius u), then x = mu + sd z */
		for (int i = 0; i < k; i++) {
			double z = 0;
			for (int j = 0; j < k; j++)
				z += v[i * k + j] * sqrt(lambda[j]) * radius * u[j];
			x[i] = g->mean[cols[i]] + sd[i] * z;
		}
		if (population_predict(p, sex, cols, x, k, dest + (size_t)b * POPULATION_NCOL, &dist[b],
				       err, errlen) < 0)
			goto out;
	}
	rc = 0;
out:
	free(r);
	return rc;
}

void
population_to_human(const double *vals, struct human_def *dest)
{
	static const char *const names[HUMAN_MEASURE_N] = {
#define NAME(e, s) s,
		HUMAN_MEASURES(NAME)
#undef NAME
	};
	for (int m = 0; m < HUMAN_MEASURE_N; m++) {
		int c = population_column(names[m]);
		if (c < 0 || isnan(vals[c]))
			continue;
		dest->measure[m] = vals[c];
		dest->measure_given |= 1u << m;
	}
	if (dest->measure_given & (1u << HUMAN_M_STATURE))
		dest->stature = dest->measure[HUMAN_M_STATURE] / 1000;
	if (dest->measure_given & (1u << HUMAN_M_WEIGHTKG))
		dest->mass = dest->measure[HUMAN_M_WEIGHTKG];
}
