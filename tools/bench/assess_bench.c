/*
 * assess_bench - the three posture scores of one manikin as a frame
 * computes them: RULA and REBA on the worse side (both arms scored) and
 * OWAS, each with its whole derivation (reasons formatted), from measured
 * body angles. The angles' measuring is not timed here (body_angles.c).
 *
 * Prints "BENCH assess.scores us=... p95_us=... rula_us=... reba_us=...
 * owas_us=... postures=64" (median and 95th percentile of one manikin's
 * three scores over 2000 rounds of 64 varied postures, per posture).
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "assess/owas.h"
#include "assess/reba.h"
#include "assess/rula.h"
#include "bench_util.h"

#define POSTURES 64
#define ROUNDS 2000

/* a deterministic uniform in [lo, hi) */
static double
uniform(unsigned long long *s, double lo, double hi)
{
	*s = *s * 6364136223846793005ull + 1442695040888963407ull;
	return lo + (hi - lo) * (double)(*s >> 11) / 9007199254740992.0;
}

int
main(void)
{
	static struct body_angles a[POSTURES];
	unsigned long long seed = 25;
	for (int i = 0; i < POSTURES; i++) {
		struct body_angles *p = &a[i];
		memset(p, 0, sizeof *p);
		p->trunk_flexion = uniform(&seed, -30, 90);
		p->trunk_side_bend = uniform(&seed, -30, 30);
		p->trunk_twist = uniform(&seed, -30, 30);
		p->hip_trunk_angle = uniform(&seed, 60, 180);
		p->neck_flexion = uniform(&seed, -30, 50);
		p->neck_side_bend = uniform(&seed, -20, 20);
		p->neck_twist = uniform(&seed, -30, 30);
		for (int s = 0; s < 2; s++) {
			struct body_arm *m = &p->arm[s];
			m->upper_arm_flexion = uniform(&seed, -40, 150);
			m->upper_arm_abduction = uniform(&seed, 0, 90);
			m->upper_arm_rotation = uniform(&seed, -60, 60);
			m->shoulder_elevation = uniform(&seed, 0, 25);
			m->elbow_flexion = uniform(&seed, 0, 150);
			m->wrist_flexion = uniform(&seed, -50, 50);
			m->wrist_deviation = uniform(&seed, -25, 25);
			m->wrist_twist_fraction = uniform(&seed, 0, 1);
			m->hand_across_midline = uniform(&seed, -0.3, 0.1);
			m->hand_out_to_side = uniform(&seed, -0.1, 0.3);
			m->elbow_above_shoulder = uniform(&seed, -0.4, 0.2);
			p->leg[s].knee_flexion = uniform(&seed, 0, 100);
			p->leg[s].weight_share = 0.5;
			p->leg[s].foot_on_floor = 1;
		}
		p->legs_on_floor = 2;
		p->seated = i % 5 == 0;
	}
	struct assess_config cfg = assess_config_default();
	struct rula_options ro = rula_options_default();
	struct reba_options eo = reba_options_default();
	struct owas_options oo = { 12 };
	ro.load_kg = eo.load_kg = 12;
	static struct assess_result r;
	static double all[ROUNDS], rula[ROUNDS], reba[ROUNDS], owas[ROUNDS];
	int sink = 0;
	for (int k = 0; k < ROUNDS; k++) {
		double t0 = bench_now_us();
		for (int i = 0; i < POSTURES; i++) {
			rula_score(&a[i], &cfg, &ro, &r);
			sink += r.score;
		}
		double t1 = bench_now_us();
		for (int i = 0; i < POSTURES; i++) {
			reba_score(&a[i], &cfg, &eo, &r);
			sink += r.score;
		}
		double t2 = bench_now_us();
		for (int i = 0; i < POSTURES; i++) {
			owas_score(&a[i], &cfg, &oo, &r);
			sink += r.score;
		}
		double t3 = bench_now_us();
		rula[k] = (t1 - t0) / POSTURES;
		reba[k] = (t2 - t1) / POSTURES;
		owas[k] = (t3 - t2) / POSTURES;
		all[k] = (t3 - t0) / POSTURES;
	}
	double med = bench_percentile(all, ROUNDS, 0.5), p95 = bench_percentile(all, ROUNDS, 0.95);
	printf("BENCH assess.scores us=%.3f p95_us=%.3f rula_us=%.3f reba_us=%.3f owas_us=%.3f "
	       "postures=%d\n",
	       med, p95, bench_percentile(rula, ROUNDS, 0.5), bench_percentile(reba, ROUNDS, 0.5),
	       bench_percentile(owas, ROUNDS, 0.5), POSTURES);
	return sink == 0; /* the scores are at least 1: 0 */
}
