/* bench_util.h - the clocks and statistics the C benchmarks share */
#ifndef POSTURE_BENCH_UTIL_H
#define POSTURE_BENCH_UTIL_H

#include <stdint.h>
#include <stdlib.h>
#include <time.h>

/* microseconds, monotonic, as the solver's clock wants them */
static inline uint64_t
bench_clock_us(void *ctx)
{
	(void)ctx;
	struct timespec t;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return (uint64_t)t.tv_sec * 1000000u + (uint64_t)t.tv_nsec / 1000u;
}

/* microseconds with the nanoseconds kept, for timing short things */
static inline double
bench_now_us(void)
{
	struct timespec t;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return t.tv_sec * 1e6 + t.tv_nsec / 1e3;
}

static inline int
bench_cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* the p-quantile (0..1) of v by nearest rank; sorts v */
static inline double
bench_percentile(double *v, int n, double p)
{
	qsort(v, (size_t)n, sizeof *v, bench_cmp_double);
	return v[(int)(p * (n - 1) + 0.5)];
}

#endif
