/*
 * family_bench - a family of boundary manikins made as `load family`
 * makes one: the centre and 16 boundary manikins of ANSUR II's women on
 * the 90 % ellipse of stature and weight (population_family), each
 * completed to a human's definition and built (human_build), and added to
 * an environment (its state, solver and kinematics: env_add_figure).
 *
 * Prints "BENCH family.build ms=... p95_ms=... max_ms=... manikins=17"
 * over 41 families (median, 95th percentile, slowest), and the parts:
 * "BENCH family.predict us=..." (the 17 predictions alone) and
 * "BENCH human.predict us=..." (one manikin's completion from two measures).
 * Not timed: the daemon's journal write and undo checkpoint of the command.
 */
#include <stdio.h>
#include <stdlib.h>

#include "bench_util.h"
#include "figure/population.h"
#include "pose/env.h"

#define RUNS 41
#define N 16

static struct env env;

int
main(void)
{
	const struct population *p = population_ansur2();
	int cols[2] = { population_column("stature"), population_column("weightkg") };
	static double rows[(N + 1) * POPULATION_NCOL];
	double dist[N + 1], total[RUNS], predict[RUNS], one[RUNS];
	char err[256];
	for (int r = 0; r < RUNS; r++) {
		env_init(&env);
		double t0 = bench_now_us();
		if (population_family(p, HUMAN_FEMALE, cols, 2, 0.9, N, rows, dist, err, sizeof err) < 0) {
			fprintf(stderr, "family_bench: %s\n", err);
			return 1;
		}
		double t1 = bench_now_us();
		for (int b = 0; b <= N; b++) {
			struct human_def hd = human_default_def(HUMAN_FEMALE);
			population_to_human(rows + (size_t)b * POPULATION_NCOL, &hd);
			struct model *m = human_build(&hd, err, sizeof err);
			char name[32];
			snprintf(name, sizeof name, "fam_%d", b);
			if (!m || env_add_figure(&env, m, name, 1, &hd, NULL) < 0) {
				fprintf(stderr, "family_bench: %s\n", m ? "could not add" : err);
				return 1;
			}
		}
		double t2 = bench_now_us();
		double x[2] = { 1650, 70 }, out[POPULATION_NCOL], d;
		population_predict(p, HUMAN_FEMALE, cols, x, 2, out, &d, err, sizeof err);
		double t3 = bench_now_us();
		env_clear(&env);
		total[r] = (t2 - t0) / 1000;
		predict[r] = t1 - t0;
		one[r] = t3 - t2;
	}
	double med = bench_percentile(total, RUNS, 0.5), p95 = bench_percentile(total, RUNS, 0.95);
	printf("BENCH family.build ms=%.3f p95_ms=%.3f max_ms=%.3f manikins=%d\n", med, p95,
	       total[RUNS - 1], N + 1);
	printf("BENCH family.predict us=%.1f\n", bench_percentile(predict, RUNS, 0.5));
	printf("BENCH human.predict us=%.2f\n", bench_percentile(one, RUNS, 0.5));
	return 0;
}
