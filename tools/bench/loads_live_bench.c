/*
 * loads_live_bench - what the daemon adds to a frame's loads analysis: the
 * live cache (loads_live_of: the figure's load set and its hash, then the
 * statics, the low back and strength when something moved) and a loads
 * event's JSON.
 *
 * usage: loads_live_bench
 * A family of 17 manikins (statures 1.50 to 1.98 m, both sexes) in the
 * daemon's environment, each with a 10 kg weight in the right hand and a
 * 40 N push on the left, is dragged for FRAMES frames, each frame raising
 * the arms and bending the trunk a little further (kin_update, not timed).
 * Per frame, timed as blocks over the 17: loads_live_of after the move (an
 * analysis each), loads_live_of again (the cache: what a frame costs a
 * figure at rest while someone subscribes), and a loads event's summary
 * written into a buffer made once. Prints the median and 95th percentile
 * over the frames, per manikin and per family:
 *   BENCH loads.frame us=... p95_us=... family_us=... family_p95_us=...
 *         cached_us=... event_us=... manikins=17
 */
#include <stdio.h>
#include <stdlib.h>

#include "bench_util.h"
#include "daemon/daemon.h"
#include "daemon/loads_json.h"
#include "daemon/loads_live.h"
#include "figure/human.h"
#include "figure/kin.h"

#define N 17
#define FRAMES 2000

static struct daemon d; /* the daemon's state as the handlers see it: not on the stack */

static int
dof0(const struct model *m, const char *joint)
{
	int j = model_find_joint(m, joint);
	if (j < 0) {
		fprintf(stderr, "loads_live_bench: no joint %s\n", joint);
		exit(1);
	}
	return m->jnt_dof0[j];
}

static void
pose(struct env_figure *f, int frame)
{
	double t = (double)frame / FRAMES, *q = f->state->q;
	const struct model *m = f->model;
	q[dof0(m, "shoulder_l")] = q[dof0(m, "shoulder_r")] = 2.5 * t;
	q[dof0(m, "elbow_l")] = q[dof0(m, "elbow_r")] = 1.2;
	q[dof0(m, "spine_5")] = 0.4 * t;
	q[dof0(m, "spine_17")] = 0.3;
	kin_update(m, f->state);
}

/* a load on figure slot fig at SEG.SITE: a weight (kg > 0) or a force */
static void
add(int fig, const char *site, double kg, const double force[3])
{
	struct env_load l = { .fig = fig, .site = model_find_site(d.env.fig[fig].model, site),
			      .mass = kg };
	for (int i = 0; i < 3; i++)
		l.force[i] = kg > 0 ? (i == 1 ? -kg * LOAD_GRAVITY : 0) : force[i];
	if (env_add_load(&d.env, NULL, &l) < 0) {
		fprintf(stderr, "loads_live_bench: the load at %s was refused\n", site);
		exit(1);
	}
}

int
main(void)
{
	int slot[N];
	char err[256];
	env_init(&d.env);
	for (int i = 0; i < N; i++) {
		struct human_def def = human_default_def(i % 2 ? HUMAN_FEMALE : HUMAN_MALE);
		def.stature = 1.50 + 0.03 * i;
		def.mass = 24 * def.stature * def.stature;
		struct model *m = human_build(&def, err, sizeof err);
		char name[16];
		snprintf(name, sizeof name, "m%d", i);
		if (!m || (slot[i] = env_add_figure(&d.env, m, name, 1, &def, NULL)) < 0) {
			fprintf(stderr, "loads_live_bench: %s\n", m ? "no room" : err);
			return 1;
		}
		add(slot[i], "hand_r.palm", 10, NULL);
		add(slot[i], "hand_l.palm", 0, (const double[3]){ 0, 0, 40 });
	}
	struct jbuf j;
	if (loads_live_init(&d) < 0 || jbuf_init(&j, 1 << 16) < 0) {
		fprintf(stderr, "loads_live_bench: out of memory\n");
		return 1;
	}
	static double live[FRAMES], cached[FRAMES], event[FRAMES];
	for (int f = 0; f < FRAMES; f++) {
		for (int i = 0; i < N; i++)
			pose(&d.env.fig[slot[i]], f);
		const struct loads_live_fig *a[N];
		double t0 = bench_now_us();
		for (int i = 0; i < N; i++)
			a[i] = loads_live_of(&d, slot[i]);
		double t1 = bench_now_us();
		for (int i = 0; i < N; i++)
			a[i] = loads_live_of(&d, slot[i]);
		double t2 = bench_now_us();
		for (int i = 0; i < N; i++) {
			jbuf_reset(&j);
			loads_json_summary_keys(&j, &d.env, slot[i], a[i]);
		}
		double t3 = bench_now_us();
		if (j.overflow || !a[N - 1] || !a[N - 1]->low_back) {
			fprintf(stderr, "loads_live_bench: %s\n", loads_live_why(&d, slot[N - 1]));
			return 1;
		}
		live[f] = t1 - t0, cached[f] = t2 - t1, event[f] = t3 - t2;
	}
	if (loads_live_computed(&d) != (uint64_t)N * FRAMES) {
		fprintf(stderr, "loads_live_bench: %llu computed, not one a manikin a frame\n",
			(unsigned long long)loads_live_computed(&d));
		return 1;
	}
	double fam = bench_percentile(live, FRAMES, 0.5), fam95 = bench_percentile(live, FRAMES, 0.95);
	printf("BENCH loads.frame us=%.2f p95_us=%.2f family_us=%.1f family_p95_us=%.1f "
	       "cached_us=%.3f event_us=%.2f manikins=%d\n",
	       fam / N, fam95 / N, fam, fam95, bench_percentile(cached, FRAMES, 0.5) / N,
	       bench_percentile(event, FRAMES, 0.5) / N, N);
	jbuf_free(&j);
	loads_live_free(&d);
	env_clear(&d.env);
	return 0;
}
