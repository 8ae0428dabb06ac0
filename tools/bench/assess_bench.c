/*
 * assess_bench - the posture assessment's per-frame cost, as a drag pays it.
 *
 * usage: assess_bench
 * A family of 17 manikins (statures 1.50 to 1.98 m, both sexes), each in a
 * posture with every body part moved, is dragged for FRAMES frames: each
 * frame raises the arms and bends the trunk a little further and updates
 * the frames (kin_update, not timed), then the body angles of all 17 are
 * measured (timed as one block, so the clock's own cost is spread over
 * the family), then the angles and the three scores (RULA and REBA on the
 * worse side, both arms scored, and OWAS, each with its whole derivation)
 * of all 17, as a frame of the live assessment computes them. Last, the
 * three scores alone over 64 varied angle sets. Prints the median and 95th
 * percentile:
 *   BENCH assess.angles us=... p95_us=... family_us=... family_p95_us=... manikins=17
 *     (us: one manikin's body_angles_measure, the family's block over 17;
 *      family_us: the 17 together)
 *   BENCH assess.frame us=... p95_us=... family_us=... family_p95_us=... manikins=17
 *     (angles and all three scores; the budget: 20 us one, 500 us 17)
 *   BENCH assess.niosh_measure us=...   (one manikin's H, V, A)
 *   BENCH assess.scores us=... p95_us=... rula_us=... reba_us=... owas_us=... postures=64
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assess/body_angles.h"
#include "assess/niosh_measure.h"
#include "assess/owas.h"
#include "assess/reba.h"
#include "assess/rula.h"
#include "bench_util.h"
#include "figure/human.h"
#include "figure/kin.h"
#include "figure/state.h"

#define N 17
#define FRAMES 2000
#define POSTURES 64
#define ROUNDS 2000

struct manikin {
	struct model *m;
	struct state *s;
	int shoulder[2], spine5, elbow[2], wrist[2], knee[2], neck;
};

static int
dof0(const struct model *m, const char *joint)
{
	int j = model_find_joint(m, joint);
	if (j < 0) {
		fprintf(stderr, "assess_bench: no joint %s\n", joint);
		exit(1);
	}
	return m->jnt_dof0[j];
}

static void
make(struct manikin *k, int i)
{
	char err[256];
	struct human_def d = human_default_def(i % 2 ? HUMAN_FEMALE : HUMAN_MALE);
	d.stature = 1.50 + 0.03 * i;
	d.mass = 24 * d.stature * d.stature;
	k->m = human_build(&d, err, sizeof err);
	if (!k->m || !(k->s = state_make(k->m))) {
		fprintf(stderr, "assess_bench: %s\n", k->m ? "out of memory" : err);
		exit(1);
	}
	static const char *const sfx[2] = { "_l", "_r" };
	char name[32];
	for (int side = 0; side < 2; side++) {
		snprintf(name, sizeof name, "shoulder%s", sfx[side]);
		k->shoulder[side] = dof0(k->m, name);
		snprintf(name, sizeof name, "elbow%s", sfx[side]);
		k->elbow[side] = dof0(k->m, name);
		snprintf(name, sizeof name, "wrist%s", sfx[side]);
		k->wrist[side] = dof0(k->m, name);
		snprintf(name, sizeof name, "knee%s", sfx[side]);
		k->knee[side] = dof0(k->m, name);
	}
	k->spine5 = dof0(k->m, "spine_5");
	k->neck = dof0(k->m, "spine_17");
}

/* frame f of the drag: arms rising, trunk bending, the rest held */
static void
pose(struct manikin *k, int f)
{
	double t = (double)f / FRAMES, *q = k->s->q;
	for (int side = 0; side < 2; side++) {
		q[k->shoulder[side]] = 2.5 * t;
		q[k->shoulder[side] + 1] = 0.3 + 0.4 * side;
		q[k->shoulder[side] + 2] = -0.2;
		q[k->elbow[side]] = 1.2;
		q[k->wrist[side]] = 0.3 - 0.6 * side;
		q[k->wrist[side] + 1] = -0.1;
		q[k->wrist[side] + 2] = 0.8;
		q[k->knee[side]] = 0.4 * side;
	}
	q[k->spine5] = 0.4 * t;
	q[k->spine5 + 1] = 0.1;
	q[k->spine5 + 2] = 0.15;
	q[k->neck] = 0.3;
	q[k->neck + 2] = 0.2;
	kin_update(k->m, k->s);
}

/* a deterministic uniform in [lo, hi) */
static double
uniform(unsigned long long *s, double lo, double hi)
{
	*s = *s * 6364136223846793005ull + 1442695040888963407ull;
	return lo + (hi - lo) * (double)(*s >> 11) / 9007199254740992.0;
}

static int
scores_alone(void)
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

int
main(void)
{
	static struct manikin fam[N];
	static double t_family[FRAMES], t_one[FRAMES], t_niosh[FRAMES];
	static double t_frame[FRAMES], t_frame_one[FRAMES];
	static struct assess_result res[N][ASSESS_NMETHODS];
	struct assess_config cfg = assess_config_default();
	struct rula_options ro = rula_options_default();
	struct reba_options eo = reba_options_default();
	struct owas_options oo = { 0 };
	struct body_angles a[N];
	struct niosh_geometry g;
	char err[256];
	double sink = 0;
	for (int i = 0; i < N; i++)
		make(&fam[i], i);
	for (int f = 0; f < FRAMES; f++) {
		for (int i = 0; i < N; i++)
			pose(&fam[i], f);
		double t0 = bench_now_us();
		for (int i = 0; i < N; i++)
			if (body_angles_measure(fam[i].m, fam[i].s, 0, 0.05, &a[i], err, sizeof err) < 0) {
				fprintf(stderr, "assess_bench: %s\n", err);
				return 1;
			}
		double t1 = bench_now_us();
		if (niosh_measure(fam[f % N].m, fam[f % N].s, &g, err, sizeof err) < 0) {
			fprintf(stderr, "assess_bench: %s\n", err);
			return 1;
		}
		double t2 = bench_now_us();
		for (int i = 0; i < N; i++)
			pose(&fam[i], f);
		double t3 = bench_now_us();
		for (int i = 0; i < N; i++) {
			body_angles_measure(fam[i].m, fam[i].s, 0, cfg.kneel_height, &a[i], err, sizeof err);
			rula_score(&a[i], &cfg, &ro, &res[i][ASSESS_RULA]);
			reba_score(&a[i], &cfg, &eo, &res[i][ASSESS_REBA]);
			owas_score(&a[i], &cfg, &oo, &res[i][ASSESS_OWAS]);
		}
		double t4 = bench_now_us();
		for (int i = 0; i < N; i++)
			sink += res[i][ASSESS_RULA].score + res[i][ASSESS_REBA].score + res[i][ASSESS_OWAS].score;
		t_frame[f] = t4 - t3;
		t_frame_one[f] = (t4 - t3) / N;
		t_family[f] = t1 - t0;
		t_one[f] = (t1 - t0) / N;
		t_niosh[f] = t2 - t1;
		for (int i = 0; i < N; i++) /* keep the results alive */
			sink += a[i].arm[0].upper_arm_flexion;
		sink += g.h_cm;
	}
	printf("BENCH assess.angles us=%.2f p95_us=%.2f family_us=%.1f family_p95_us=%.1f manikins=%d\n",
	       bench_percentile(t_one, FRAMES, 0.5), bench_percentile(t_one, FRAMES, 0.95),
	       bench_percentile(t_family, FRAMES, 0.5), bench_percentile(t_family, FRAMES, 0.95), N);
	printf("BENCH assess.frame us=%.2f p95_us=%.2f family_us=%.1f family_p95_us=%.1f manikins=%d\n",
	       bench_percentile(t_frame_one, FRAMES, 0.5), bench_percentile(t_frame_one, FRAMES, 0.95),
	       bench_percentile(t_frame, FRAMES, 0.5), bench_percentile(t_frame, FRAMES, 0.95), N);
	printf("BENCH assess.niosh_measure us=%.2f\n", bench_percentile(t_niosh, FRAMES, 0.5));
	if (!isfinite(sink))
		fprintf(stderr, "assess_bench: non-finite angles\n");
	for (int i = 0; i < N; i++) {
		state_free(fam[i].s);
		model_free(fam[i].m);
	}
	return scores_alone();
}
