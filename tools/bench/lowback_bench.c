/*
 * lowback_bench - the low back's and the strength model's share of a loads
 * frame (the budget: 30 us for a manikin's whole loads analysis).
 *
 * usage: lowback_bench
 * 256 varied disc loads (trunk flexion 0-90 deg, hand loads 0-30 kg,
 * sideways and twisting parts) through lowback_compute, and 256 varied
 * joint moments and angles of all 13 joints through strength_capable, each
 * set timed as one block ROUNDS times. Prints the median and 95th
 * percentile of one call:
 *   BENCH loads.lowback us=... p95_us=... inputs=256
 *   BENCH loads.strength us=... p95_us=... inputs=256 modelled=...
 */
#include <math.h>
#include <stdio.h>

#include "assess/lowback.h"
#include "assess/strength.h"
#include "bench_util.h"

#define INPUTS 256
#define ROUNDS 400

static struct lowback_input disc[INPUTS];
static struct strength_input joints[INPUTS];
static double t_lb[ROUNDS], t_st[ROUNDS];

int
main(void)
{
	for (int i = 0; i < INPUTS; i++) {
		double th = (i % 91) * M_PI / 180, w = 450 + 9.81 * (i % 31);
		struct lowback_input *in = &disc[i];
		in->disc_normal[1] = cos(th);
		in->disc_normal[2] = sin(th);
		in->anterior[1] = -sin(th);
		in->anterior[2] = cos(th);
		in->load_force[0] = (i % 7) - 3;
		in->load_force[1] = -w;
		in->load_moment[0] = w * 0.3 * sin(th) + (i % 13);
		in->load_moment[1] = (i % 5) - 2;
		in->load_moment[2] = (i % 3) - 1;
		struct strength_input *s = &joints[i];
		s->sex = i % 2 ? STRENGTH_FEMALE : STRENGTH_MALE;
		for (int j = 0; j < STRENGTH_NJOINTS; j++)
			for (int a = 0; a < STRENGTH_NAXES; a++) {
				s->moment[j][a] = ((i * 7 + j * 3 + a) % 41) - 20;
				s->angle[j][a] = ((i * 11 + j * 5 + a) % 121) - 30;
			}
	}
	char err[128];
	double sink = 0;
	int modelled = 0;
	for (int r = 0; r < ROUNDS; r++) {
		struct lowback_result lr;
		double t0 = bench_now_us();
		for (int i = 0; i < INPUTS; i++) {
			if (lowback_compute(&disc[i], &lr, err, sizeof err) < 0) {
				fprintf(stderr, "lowback_bench: %s\n", err);
				return 1;
			}
			sink += lr.compression;
		}
		double t1 = bench_now_us();
		struct strength_result sr;
		for (int i = 0; i < INPUTS; i++) {
			if (strength_capable(&joints[i], &sr, err, sizeof err) < 0) {
				fprintf(stderr, "lowback_bench: %s\n", err);
				return 1;
			}
			modelled = sr.modelled;
		}
		double t2 = bench_now_us();
		t_lb[r] = (t1 - t0) / INPUTS;
		t_st[r] = (t2 - t1) / INPUTS;
	}
	if (!isfinite(sink))
		return 1;
	double lb50 = bench_percentile(t_lb, ROUNDS, 0.5), lb95 = bench_percentile(t_lb, ROUNDS, 0.95);
	double st50 = bench_percentile(t_st, ROUNDS, 0.5), st95 = bench_percentile(t_st, ROUNDS, 0.95);
	printf("BENCH loads.lowback us=%.4f p95_us=%.4f inputs=%d\n", lb50, lb95, INPUTS);
	printf("BENCH loads.strength us=%.4f p95_us=%.4f inputs=%d modelled=%d\n", st50, st95, INPUTS,
	       modelled);
	return 0;
}
