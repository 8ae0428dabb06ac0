/*
 * population.h - anthropometric populations: per sex, the mean and the
 * covariance of ANSUR II's measured dimensions and the order statistics of
 * stature; what they predict of a body from some of its measures, the
 * percentile manikin, Mahalanobis distances and families of boundary
 * manikins.
 *
 * The model is the multivariate normal per sex. Given some measures x1 of
 * a person, the others are predicted by the conditional expectation
 * mu2 + S21 S11^-1 (x1 - mu1), which is also the least-squares linear
 * regression of the others on x1 in the population: it meets the given
 * ones exactly, and the Mahalanobis distance of the completed vector is
 * that of x1 alone (the prediction adds no distance).
 *
 * Columns are ANSUR II's 93 measured dimensions (ansur2_data.h) by index;
 * a population may hold any subset of them. Units: millimetres; weightkg in
 * kilograms. Functions that fail return -1 with a message in err.
 */
#ifndef POSTURE_POPULATION_H
#define POSTURE_POPULATION_H

#include <stddef.h>
#include <stdio.h>

#include "figure/ansur2_data.h"
#include "figure/human.h"

#define POPULATION_NCOL ANSUR2_NCOL
#define POPULATION_NTRI ANSUR2_NTRI
#define POPULATION_MIN_PEOPLE 30     /* a sex with fewer is refused (with none it is absent) */
#define POPULATION_MAX_PEOPLE 1000000
#define POPULATION_MAX_FIELDS 1024   /* columns in a file's header */
#define POPULATION_FAMILY_MAX 64     /* boundary manikins of one family */

/* one sex of a population */
struct population_group {
	int n;                /* people; 0: the sex is absent */
	const double *mean;   /* [POPULATION_NCOL]; 0 where the population lacks the column */
	const double *cov;    /* lower triangle, row by row (ansur2_data.h); n - 1 divisor */
	const double *stature; /* [n] ascending; NULL when the population has no stature */
};

struct population {
	unsigned char lacks[POPULATION_NCOL]; /* 1: the column is not in the population */
	struct population_group sex[2];     /* indexed by enum human_sex */
	void *owned;                        /* what population_free frees; NULL: built in */
};

/* the built-in population ansur2 (static: never freed) */
const struct population *population_ansur2(void);

/* frees a population read or parsed (NULL and the built-in one are ignored) */
void population_free(struct population *p);

/* a column's index by its ANSUR II name, case-insensitive; -1 when none */
int population_column(const char *name);
const char *population_column_name(int col);

/* the plausible range of a column's values, in the population's units */
void population_bounds(int col, double *lo, double *hi);

/* element (i, j) of a group's covariance */
double population_cov(const struct population_group *g, int i, int j);

/*
 * Writes a population's statistics as text (population_stats_read reads it
 * back bit for bit): the state a journal snapshot keeps of a population
 * loaded from a file. 0, or -1 on a stream error.
 */
int population_stats_write(const struct population *p, FILE *f);
struct population *population_stats_read(const char *text, size_t len, char *err, size_t errlen);

/*
 * The p-th percentile (0 <= p <= 100) of the sex's stature (mm), by linear
 * interpolation between its order statistics: at rank (n - 1) p / 100.
 */
int population_percentile(const struct population *p, enum human_sex sex, double pct, double *mm,
			  char *err, size_t errlen);

/*
 * The inverse: the percentile (0 to 100) at which the sex's interpolated
 * stature is mm; where several people share that stature, the middle of
 * their ranks. 0 below the shortest, 100 above the tallest.
 */
int population_stature_rank(const struct population *p, enum human_sex sex, double mm,
			    double *pct, char *err, size_t errlen);

/*
 * The conditional expectation of every column of the population given k of
 * them (cols[i] = vals[i]; k = 0: the means): dest[POPULATION_NCOL], NAN
 * where the population lacks the column. *dist, when not NULL, gets the
 * Mahalanobis distance of the given values from the sex's mean. Fails for
 * an absent sex, a column the population lacks or given twice, or given
 * columns whose covariance is singular.
 */
int population_predict(const struct population *p, enum human_sex sex, const int *cols,
		       const double *vals, int k, double *dest, double *dist, char *err, size_t errlen);

/*
 * A family of boundary manikins (Zehner, Meindl & Hudson 1993): for the k
 * chosen columns, the centre (the mean) and n points on the ellipsoid that
 * holds the fraction coverage (0 < coverage < 1) of the sex, at Mahalanobis
 * distance sqrt(chi2 quantile(coverage, k)); every other column conditional
 * on each point. The points lie along the principal axes of the chosen
 * measures' correlation matrix (standardised, so units do not matter):
 * first the axis ends in order of variance (+1, -1 of the first, then of
 * the second ...: 2k of them); beyond 2k, points in between, on the circle
 * of each plane of two axes, pairs in order (1,2) (1,3) (2,3) (1,4) ...,
 * halving the angles: 45 degrees first (4 a plane), then 22.5 (8 a plane)
 * and so on. Two measures and n = 8 give the classic eight cases at 45
 * degree steps; one measure has only its two ends (n <= 2).
 *
 * dest: (n + 1) x POPULATION_NCOL, row 0 the centre; dist: n + 1 distances.
 */
int population_family(const struct population *p, enum human_sex sex, const int *cols, int k,
		      double coverage, int n, double *dest, double *dist, char *err, size_t errlen);

/*
 * A human's definition from a completed vector of measures (NAN: absent):
 * each of measures.h's measures present is set and marked given, stature
 * and mass from stature and weightkg when present. Everything else of dest
 * (sex, and stature and mass when absent) is left as it was.
 */
void population_to_human(const double *vals, struct human_def *dest);

#endif
