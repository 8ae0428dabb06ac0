/*
 * loads_bench - the static equilibrium's per-frame cost, as a drag pays it.
 *
 * usage: loads_bench
 * A family of 17 manikins (statures 1.50 to 1.98 m, both sexes) holds a
 * box (a weight in each hand) and pushes with the right hand while the
 * drag raises the arms and bends the trunk a little further each of FRAMES
 * frames; the frames are updated (kin_update, not timed), then the statics
 * of all 17 are solved standing (timed as one block, so the clock's own
 * cost is spread over the family), then all 17 again seated. Prints the
 * median and 95th percentile:
 *   BENCH loads.statics us=... p95_us=... seated_us=... seated_p95_us=...
 *         family_us=... family_p95_us=... manikins=17
 *     (us: one manikin's statics_solve standing, the family's block over
 *      17; seated_us: the same seated; family_us: the 17 standing together)
 * The budget: joint moments, low back and strength of one manikin
 * within 30 us a frame.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assess/statics.h"
#include "bench_util.h"
#include "figure/human.h"
#include "figure/kin.h"
#include "figure/state.h"
#include "pose/load.h"

#define N 17
#define FRAMES 2000
#define NLOADS 3

struct manikin {
	struct model *m;
	struct state *s;
	int shoulder[2], elbow[2], spine5;
	struct ext_load load[NLOADS];
};

static int
dof0(const struct model *m, const char *joint)
{
	int j = model_find_joint(m, joint);
	if (j < 0) {
		fprintf(stderr, "loads_bench: no joint %s\n", joint);
		exit(1);
	}
	return m->jnt_dof0[j];
}

/* a load at a site: a weight of kg, or (kg 0) the force f */
static struct ext_load
load_at(const struct model *m, const char *site, double kg, const double f[3])
{
	struct ext_load l = { 0 };
	int k = model_find_site(m, site);
	if (k < 0) {
		fprintf(stderr, "loads_bench: no site %s\n", site);
		exit(1);
	}
	l.seg = m->site_seg[k];
	memcpy(l.local, m->site_loc[k].p, sizeof l.local);
	l.mass = kg;
	if (kg > 0)
		l.force[1] = -kg * LOAD_GRAVITY;
	else
		memcpy(l.force, f, sizeof l.force);
	return l;
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
		fprintf(stderr, "loads_bench: %s\n", k->m ? "out of memory" : err);
		exit(1);
	}
	static const char *const sfx[2] = { "_l", "_r" };
	char name[32];
	for (int side = 0; side < 2; side++) {
		snprintf(name, sizeof name, "shoulder%s", sfx[side]);
		k->shoulder[side] = dof0(k->m, name);
		snprintf(name, sizeof name, "elbow%s", sfx[side]);
		k->elbow[side] = dof0(k->m, name);
	}
	k->spine5 = dof0(k->m, "spine_5");
	static const double push[3] = { 20, -10, 60 };
	k->load[0] = load_at(k->m, "hand_l.palm", 6, NULL);
	k->load[1] = load_at(k->m, "hand_r.palm", 6, NULL);
	k->load[2] = load_at(k->m, "hand_r.palm", 0, push);
}

/* frame f of the drag: arms rising, trunk bending, the rest held */
static void
pose(struct manikin *k, int f)
{
	double t = (double)f / FRAMES, *q = k->s->q;
	for (int side = 0; side < 2; side++) {
		q[k->shoulder[side]] = 1.5 * t;
		q[k->shoulder[side] + 1] = 0.2;
		q[k->elbow[side]] = 1.0;
	}
	q[k->spine5] = 0.4 * t;
	q[k->spine5 + 1] = 0.1;
	kin_update(k->m, k->s);
}

int
main(void)
{
	static struct manikin fam[N];
	static struct statics_result r[N];
	static double t_one[FRAMES], t_family[FRAMES], t_seated[FRAMES];
	char err[256];
	double sink = 0;
	for (int i = 0; i < N; i++)
		make(&fam[i], i);
	for (int f = 0; f < FRAMES; f++) {
		for (int i = 0; i < N; i++)
			pose(&fam[i], f);
		double t0 = bench_now_us();
		for (int i = 0; i < N; i++)
			if (statics_solve(fam[i].m, fam[i].s, fam[i].load, NLOADS, 0, &r[i], err,
					  sizeof err) < 0) {
				fprintf(stderr, "loads_bench: %s\n", err);
				return 1;
			}
		double t1 = bench_now_us();
		for (int i = 0; i < N; i++)
			sink += r[i].anat[0][0];
		double t2 = bench_now_us();
		for (int i = 0; i < N; i++)
			statics_solve(fam[i].m, fam[i].s, fam[i].load, NLOADS, 1, &r[i], err, sizeof err);
		double t3 = bench_now_us();
		for (int i = 0; i < N; i++)
			sink += r[i].anat[0][0];
		t_family[f] = t1 - t0;
		t_one[f] = (t1 - t0) / N;
		t_seated[f] = (t3 - t2) / N;
	}
	printf("BENCH loads.statics us=%.2f p95_us=%.2f seated_us=%.2f seated_p95_us=%.2f "
	       "family_us=%.1f family_p95_us=%.1f manikins=%d\n",
	       bench_percentile(t_one, FRAMES, 0.5), bench_percentile(t_one, FRAMES, 0.95),
	       bench_percentile(t_seated, FRAMES, 0.5), bench_percentile(t_seated, FRAMES, 0.95),
	       bench_percentile(t_family, FRAMES, 0.5), bench_percentile(t_family, FRAMES, 0.95), N);
	if (!isfinite(sink)) {
		fprintf(stderr, "loads_bench: non-finite moments\n");
		return 1;
	}
	for (int i = 0; i < N; i++) {
		state_free(fam[i].s);
		model_free(fam[i].m);
	}
	return 0;
}
