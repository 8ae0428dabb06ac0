/*
 * assess_bench - the posture assessment's per-frame cost, as a drag pays it.
 *
 * usage: assess_bench
 * A family of 17 manikins (statures 1.50 to 1.98 m, both sexes), each in a
 * posture with every body part moved, is dragged for FRAMES frames: each
 * frame raises the arms and bends the trunk a little further and updates
 * the frames (kin_update, not timed), then the body angles of all 17 are
 * measured (timed as one block, so the clock's own cost is spread over
 * the family). Prints the median and 95th percentile:
 *   BENCH assess.angles us=... p95_us=... family_us=... family_p95_us=... manikins=17
 *     (us: one manikin's body_angles_measure, the family's block over 17;
 *      family_us: the 17 together)
 *   BENCH assess.niosh_measure us=...   (one manikin's H, V, A)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "assess/body_angles.h"
#include "assess/niosh_measure.h"
#include "bench_util.h"
#include "figure/human.h"
#include "figure/kin.h"
#include "figure/state.h"

#define N 17
#define FRAMES 2000

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

int
main(void)
{
	static struct manikin fam[N];
	static double t_family[FRAMES], t_one[FRAMES], t_niosh[FRAMES];
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
	printf("BENCH assess.niosh_measure us=%.2f\n", bench_percentile(t_niosh, FRAMES, 0.5));
	if (!isfinite(sink))
		fprintf(stderr, "assess_bench: non-finite angles\n");
	for (int i = 0; i < N; i++) {
		state_free(fam[i].s);
		model_free(fam[i].m);
	}
	return 0;
}
