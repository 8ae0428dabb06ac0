/*
 * fuzz_population.c - the population reader on any bytes: no crash, no
 * leak; an error names the file and a line; a population it accepts has
 * at least 30 people of each sex present, means within the measures'
 * bounds, variances not negative, statures in order, statistics that are
 * written and read back bit for bit, and predictions it can make or refuse.
 * The round trip is made for populations of at most 12 measures: wider
 * ones take the same paths, 90 times the printing (and ten times the time).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/population.h"
#include "figure/population_csv.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void
check_round_trip(const struct population *p)
{
	char *text = NULL, err[256];
	size_t n = 0;
	FILE *f = open_memstream(&text, &n);
	if (population_stats_write(p, f))
		abort();
	fclose(f);
	struct population *q = population_stats_read(text, n, err, sizeof err);
	if (!q || memcmp(q->lacks, p->lacks, sizeof p->lacks))
		abort();
	for (int s = 0; s < 2; s++) {
		const struct population_group *a = &p->sex[s], *b = &q->sex[s];
		if (a->n != b->n || (a->n && (memcmp(a->mean, b->mean, sizeof(double) * POPULATION_NCOL) ||
					      memcmp(a->cov, b->cov, sizeof(double) * POPULATION_NTRI))))
			abort();
		if (a->stature && memcmp(a->stature, b->stature, sizeof(double) * (size_t)a->n))
			abort();
	}
	population_free(q);
	free(text);
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	char err[256] = "", ignored[128];
	struct population *p = population_csv_read((const char *)data, size, "fuzz", ignored,
						   sizeof ignored, err, sizeof err);
	if (!p) {
		if (strncmp(err, "fuzz:", 5) || !memchr(err, 0, sizeof err))
			abort();
		return 0;
	}
	int stature = population_column("stature");
	for (int s = 0; s < 2; s++) {
		const struct population_group *g = &p->sex[s];
		if (g->n && g->n < POPULATION_MIN_PEOPLE)
			abort();
		if (!g->n)
			continue;
		for (int c = 0; c < POPULATION_NCOL; c++) {
			double lo, hi;
			population_bounds(c, &lo, &hi);
			if (!p->lacks[c] && (!(g->mean[c] >= lo - 1e-9 * hi && g->mean[c] <= hi * (1 + 1e-9)) ||
					     !(population_cov(g, c, c) >= 0)))
				abort();
		}
		for (int i = 1; g->stature && i < g->n; i++)
			if (g->stature[i] < g->stature[i - 1])
				abort();
		/* predictions at the median stature: made, or refused with a reason */
		double mm, out[POPULATION_NCOL], dist;
		if (g->stature) {
			if (population_percentile(p, s, 50, &mm, err, sizeof err))
				abort();
			if (!population_predict(p, s, &stature, &mm, 1, out, &dist, err, sizeof err) &&
			    (out[stature] != mm || !(dist >= 0)))
				abort();
		}
	}
	int ncol = 0;
	for (int c = 0; c < POPULATION_NCOL; c++)
		ncol += !p->lacks[c];
	if (ncol <= 12)
		check_round_trip(p);
	population_free(p);
	return 0;
}
