/*
 * anthro_bench - a manikin built from measures, and a manikin measured.
 *
 * usage: anthro_bench
 * Builds RUNS humans from all 20 ANSUR II measures (statures 1.45 to 2.00 m,
 * both sexes, each measure the population's mean ratio to stature, as a
 * build with stature and weight alone fills them in) and measures each one
 * as `get anthropometry` does. Prints the median and p95 of each:
 *   BENCH human.build ms=... p95_ms=... default_ms=...   (default_ms: today's
 *                                                        figure, no measures)
 *   BENCH anthropometry.measure ms=... p95_ms=...
 */
#include <stdio.h>
#include <stdlib.h>

#include "bench_util.h"
#include "figure/human.h"
#include "figure/model.h"
#include "pose/anthropometry.h"

#define RUNS 400

static struct model *
build(const struct human_def *d)
{
	char err[256];
	struct model *m = human_build(d, err, sizeof err);
	if (!m) {
		fprintf(stderr, "anthro_bench: %s\n", err);
		exit(1);
	}
	return m;
}

int
main(void)
{
	static double t_build[RUNS], t_default[RUNS], t_measure[RUNS];
	double v[HUMAN_MEASURE_N];
	char err[256];
	for (int i = 0; i < RUNS; i++) {
		enum human_sex sex = i % 2 ? HUMAN_FEMALE : HUMAN_MALE;
		struct human_def d = human_default_def(sex);
		d.stature = 1.45 + 0.55 * (i / 2) / (RUNS / 2 - 1);
		d.mass = 25 * d.stature * d.stature;
		/* the 20 measures of the population's proportions at this stature */
		d.measure[HUMAN_M_STATURE] = d.stature * 1000;
		d.measure[HUMAN_M_WEIGHTKG] = d.mass;
		d.measure_given = 1u << HUMAN_M_STATURE | 1u << HUMAN_M_WEIGHTKG;
		struct model *m = build(&d);
		if (anthro_measure(m, v, err, sizeof err) < 0) {
			fprintf(stderr, "anthro_bench: %s\n", err);
			return 1;
		}
		model_free(m);
		for (int k = 0; k < HUMAN_MEASURE_N; k++)
			d.measure[k] = v[k];
		d.measure_given = (1u << HUMAN_MEASURE_N) - 1;

		double t0 = bench_now_us();
		m = build(&d);
		double t1 = bench_now_us();
		if (anthro_measure(m, v, err, sizeof err) < 0) {
			fprintf(stderr, "anthro_bench: %s\n", err);
			return 1;
		}
		double t2 = bench_now_us();
		model_free(m);
		struct human_def plain = human_default_def(sex);
		plain.stature = d.stature;
		plain.mass = d.mass;
		double t3 = bench_now_us();
		m = build(&plain);
		double t4 = bench_now_us();
		model_free(m);
		t_build[i] = (t1 - t0) / 1000;
		t_measure[i] = (t2 - t1) / 1000;
		t_default[i] = (t4 - t3) / 1000;
	}
	printf("BENCH human.build ms=%.3f p95_ms=%.3f default_ms=%.3f\n",
	       bench_percentile(t_build, RUNS, 0.5), bench_percentile(t_build, RUNS, 0.95),
	       bench_percentile(t_default, RUNS, 0.5));
	printf("BENCH anthropometry.measure ms=%.3f p95_ms=%.3f\n", bench_percentile(t_measure, RUNS, 0.5),
	       bench_percentile(t_measure, RUNS, 0.95));
	return 0;
}
