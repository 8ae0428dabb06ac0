/*
 * test_clearance.c - clearance between figures and of a figure with
 * itself (fit/clearance.h): the pruned query gives what asking every pair
 * gives (the pairs within the threshold, their distances and points, and
 * the minimum) on random postures of the human in the vehicle seat; the
 * pairs left out of self-clearance are the jointed ones and the table's,
 * and nothing else; with the caches of the last frames, a drag's every
 * frame still gives the every-pair answer; the hands gripping the steering
 * wheel are reported as
 * interpenetrating; and a query allocates nothing once warm.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "draw/demo_scene.h"
#include "figure/kin.h"
#include "fit/clearance.h"

#include "alloc_count.h"

#define SEAT "src/figure/library/vehicle_seat.fig"

struct rig {
	struct demo_scene sc;
	struct fit_model *fh, *fs;
	struct clearance_work *w;
	struct clearance_result res;
};

static struct rig *
rig_make(void)
{
	struct rig *g = calloc(1, sizeof *g);
	char err[256];
	assert_int_equal(demo_scene_make(&g->sc, "seated", SEAT, err, sizeof err), 0);
	g->fh = fit_model_make(g->sc.human, err, sizeof err);
	g->fs = fit_model_make(g->sc.seat, err, sizeof err);
	assert_non_null(g->fh);
	assert_non_null(g->fs);
	g->w = clearance_work_make(64);
	assert_non_null(g->w);
	return g;
}

static void
rig_free(struct rig *g)
{
	clearance_work_free(g->w);
	fit_model_free(g->fh);
	fit_model_free(g->fs);
	demo_scene_free(&g->sc);
	free(g);
}

/* a random posture within the limits, a fraction `amount` of the way from the seated one */
static void
jiggle(const struct model *m, struct state *s, const double *q0, double amount, unsigned *seed)
{
	for (int d = 0; d < m->ndof; d++) {
		double u = (double)rand_r(seed) / RAND_MAX;
		double target = m->dof_lo[d] + u * (m->dof_hi[d] - m->dof_lo[d]);
		if (!isfinite(target))
			target = q0[d];
		s->q[d] = q0[d] + amount * (target - q0[d]);
	}
	kin_forward(m, s);
}

/* every pair asked, the reference the pruned query must equal */
static void
exhaustive(const struct fit_model *fa, const struct state *sa, const struct fit_model *fb,
	   const struct state *sb, int self, double threshold, struct clearance_result *ref)
{
	static struct collide_scratch *sc;
	if (!sc)
		sc = collide_scratch_make();
	clearance_begin(ref, threshold);
	for (int a = 0; a < fa->nseg; a++)
		for (int b = self ? a + 1 : 0; b < fb->nseg; b++) {
			if (!fa->mesh[a] || !fb->mesh[b])
				continue;
			if (self && fit_model_skip(fa, a, b) != FIT_CHECKED)
				continue;
			struct collide_result r;
			assert_int_equal(collide_distance(sc, fa->mesh[a], &sa->seg_xf[a], fb->mesh[b],
							  &sb->seg_xf[b], &r),
					 0);
			struct clearance_pair p = { 0, a, self ? 0 : 1, b, r.distance, { 0 }, { 0 } };
			memcpy(p.pa, r.pa, sizeof p.pa);
			memcpy(p.pb, r.pb, sizeof p.pb);
			if (!ref->has_minimum || p.distance < ref->minimum.distance) {
				ref->minimum = p;
				ref->has_minimum = 1;
			}
			if (p.distance < threshold && ref->npairs < CLEARANCE_PAIRS_MAX)
				ref->pair[ref->npairs++] = p;
		}
	clearance_sort(ref);
}

static void
same(const struct clearance_result *got, const struct clearance_result *ref)
{
	assert_int_equal(got->npairs, ref->npairs);
	for (int i = 0; i < ref->npairs; i++) {
		const struct clearance_pair *a = &got->pair[i], *b = &ref->pair[i];
		assert_true(fabs(a->distance - b->distance) < 1e-11);
		assert_true(a->seg_a == b->seg_a && a->seg_b == b->seg_b);
		for (int k = 0; k < 3; k++)
			assert_true(fabs(a->pa[k] - b->pa[k]) < 1e-9 && fabs(a->pb[k] - b->pb[k]) < 1e-9);
	}
	assert_int_equal(got->has_minimum, ref->has_minimum);
	assert_true(fabs(got->minimum.distance - ref->minimum.distance) < 1e-11);
}

static void
test_pruned_equals_every_pair(void **st)
{
	(void)st;
	struct rig *g = rig_make();
	const struct model *m = g->sc.human;
	double *q0 = malloc(sizeof(double) * (size_t)m->ndof);
	memcpy(q0, g->sc.hs->q, sizeof(double) * (size_t)m->ndof);
	unsigned seed = 7;
	static struct clearance_result ref;
	long asked = 0, candidates = 0;
	for (int k = 0; k < 40; k++) {
		jiggle(m, g->sc.hs, q0, 0.3 * (k % 4), &seed);
		double threshold = 0.01 * (k % 5);
		clearance_begin(&g->res, threshold);
		assert_int_equal(clearance_between(g->w, NULL, 0, g->fh, g->sc.hs, 1, g->fs, g->sc.ss, &g->res), 0);
		clearance_sort(&g->res);
		exhaustive(g->fh, g->sc.hs, g->fs, g->sc.ss, 0, threshold, &ref);
		same(&g->res, &ref);
		asked += g->res.asked;
		candidates += g->res.candidates;
		clearance_begin(&g->res, threshold);
		assert_int_equal(clearance_self(g->w, NULL, 0, g->fh, g->sc.hs, &g->res), 0);
		clearance_sort(&g->res);
		exhaustive(g->fh, g->sc.hs, g->fh, g->sc.hs, 1, threshold, &ref);
		same(&g->res, &ref);
		asked += g->res.asked;
		candidates += g->res.candidates;
	}
	printf("clearance: %ld of %ld pairs asked\n", asked, candidates);
	assert_true(asked < candidates / 2); /* the bounds do prune */
	free(q0);
	rig_free(g);
}

/*
 * A drag: the right arm raised a little each frame, then the whole body
 * swept; with the caches, every frame's answer is the every-pair answer,
 * and most pairs are settled by their last answer.
 */
static void
test_cached_frames_equal_every_pair(void **st)
{
	(void)st;
	struct rig *g = rig_make();
	const struct model *m = g->sc.human;
	struct clearance_cache *cb = clearance_cache_make(g->fh, g->fs);
	struct clearance_cache *cs = clearance_cache_make(g->fh, g->fh);
	assert_non_null(cb);
	assert_non_null(cs);
	/* another pair's cache is refused */
	clearance_begin(&g->res, 0.02);
	assert_int_equal(clearance_between(g->w, cs, 0, g->fh, g->sc.hs, 1, g->fs, g->sc.ss, &g->res), -1);
	double *q0 = malloc(sizeof(double) * (size_t)m->ndof);
	memcpy(q0, g->sc.hs->q, sizeof(double) * (size_t)m->ndof);
	int sh = m->jnt_dof0[model_find_joint(m, "shoulder_r")];
	int el = m->jnt_dof0[model_find_joint(m, "elbow_r")];
	static struct clearance_result ref;
	unsigned seed = 3;
	long asked = 0, reused = 0, candidates = 0;
	for (int f = 0; f < 120; f++) {
		if (f < 60) { /* the arm alone moves */
			g->sc.hs->q[sh] = q0[sh] - 0.02 * f;
			g->sc.hs->q[el] = q0[el] + 0.01 * f;
			kin_forward(m, g->sc.hs);
		} else {
			jiggle(m, g->sc.hs, q0, 0.05 * (f % 7), &seed);
		}
		clearance_begin(&g->res, 0.02);
		assert_int_equal(clearance_between(g->w, cb, 0, g->fh, g->sc.hs, 1, g->fs, g->sc.ss, &g->res), 0);
		clearance_sort(&g->res);
		exhaustive(g->fh, g->sc.hs, g->fs, g->sc.ss, 0, 0.02, &ref);
		same(&g->res, &ref);
		asked += g->res.asked;
		reused += g->res.reused;
		candidates += g->res.candidates;
		clearance_begin(&g->res, 0.02);
		assert_int_equal(clearance_self(g->w, cs, 0, g->fh, g->sc.hs, &g->res), 0);
		clearance_sort(&g->res);
		exhaustive(g->fh, g->sc.hs, g->fh, g->sc.hs, 1, 0.02, &ref);
		same(&g->res, &ref);
		asked += g->res.asked;
		reused += g->res.reused;
		candidates += g->res.candidates;
	}
	printf("clearance: cached: %ld asked, %ld reused of %ld pairs\n", asked, reused, candidates);
	assert_true(reused > 0);
	free(q0);
	clearance_cache_free(cb);
	clearance_cache_free(cs);
	rig_free(g);
}

static void
test_self_skips_jointed_and_table_only(void **st)
{
	(void)st;
	struct rig *g = rig_make();
	const struct model *m = g->sc.human;
	int jointed = 0, touching = 0, checked = 0;
	for (int a = 0; a < m->nseg; a++)
		for (int b = a + 1; b < m->nseg; b++) {
			enum fit_skip k = fit_model_skip(g->fh, a, b);
			assert_int_equal(k, fit_model_skip(g->fh, b, a));
			jointed += k == FIT_JOINTED;
			touching += k == FIT_TOUCHING;
			checked += k == FIT_CHECKED;
		}
	/* one jointed pair a joint */
	assert_int_equal(jointed, m->njnt);
	int s = model_find_segment(m, "thigh_l"), p = model_find_segment(m, "pelvis");
	int l4 = model_find_segment(m, "L4"), t7 = model_find_segment(m, "T7");
	int h = model_find_segment(m, "hand_r"), ua = model_find_segment(m, "upperarm_l");
	int sh = model_find_segment(m, "shank_l"), sr = model_find_segment(m, "shank_r");
	assert_int_equal(fit_model_skip(g->fh, s, p), FIT_JOINTED);
	assert_int_equal(fit_model_skip(g->fh, s, l4), FIT_TOUCHING);
	assert_int_equal(fit_model_skip(g->fh, l4, t7), FIT_TOUCHING);
	assert_int_equal(fit_model_skip(g->fh, h, s), FIT_CHECKED);   /* a hand on the thigh */
	assert_int_equal(fit_model_skip(g->fh, ua, t7), FIT_CHECKED); /* an arm against the chest */
	assert_int_equal(fit_model_skip(g->fh, sh, sr), FIT_CHECKED); /* the knees together */
	/* the seat's pairs are not the human's table */
	for (int a = 0; a < g->sc.seat->nseg; a++)
		for (int b = a + 1; b < g->sc.seat->nseg; b++)
			assert_true(fit_model_skip(g->fs, a, b) != FIT_TOUCHING);
	printf("clearance: self pairs: %d jointed, %d in the table, %d checked\n", jointed, touching,
	       checked);
	/* at rest, standing or seated, no checked pair interpenetrates */
	clearance_begin(&g->res, 0);
	assert_int_equal(clearance_self(g->w, NULL, 0, g->fh, g->sc.hs, &g->res), 0);
	assert_true(g->res.minimum.distance > 0);
	rig_free(g);
}

static void
test_hand_into_the_wheel(void **st)
{
	(void)st;
	struct rig *g = rig_make();
	const struct model *sm = g->sc.seat;
	int wheel = model_find_segment(sm, "wheel");
	int hand = model_find_segment(g->sc.human, "hand_r");
	assert_true(wheel >= 0 && hand >= 0);
	clearance_begin(&g->res, 0.02);
	assert_int_equal(clearance_between(g->w, NULL, 0, g->fh, g->sc.hs, 1, g->fs, g->sc.ss, &g->res), 0);
	int found = 0;
	for (int i = 0; i < g->res.npairs; i++)
		if (g->res.pair[i].seg_a == hand && g->res.pair[i].seg_b == wheel) {
			found = 1;
			assert_true(g->res.pair[i].distance < 0); /* the palm grips the rim: they overlap */
		}
	assert_true(found);
	assert_true(g->res.minimum.distance < 0);
	rig_free(g);
}

static void
test_no_alloc_of_ours(void **st)
{
	(void)st;
#if COUNT_ALLOCS
	struct rig *g = rig_make();
	struct clearance_cache *cb = clearance_cache_make(g->fh, g->fs);
	clearance_begin(&g->res, 0.02);
	clearance_between(g->w, cb, 0, g->fh, g->sc.hs, 1, g->fs, g->sc.ss, &g->res);
	long a0 = allocs;
	for (int i = 0; i < 10; i++) {
		g->sc.hs->q[0] += 0.001; /* something moves: the pairs are asked again */
		kin_forward(g->sc.human, g->sc.hs);
		clearance_begin(&g->res, 0.02);
		clearance_between(g->w, cb, 0, g->fh, g->sc.hs, 1, g->fs, g->sc.ss, &g->res);
		clearance_self(g->w, NULL, 0, g->fh, g->sc.hs, &g->res);
		clearance_sort(&g->res);
	}
	printf("clearance: 10 queries, %ld heap calls\n", allocs - a0);
	assert_int_equal(allocs - a0, 0);
	clearance_cache_free(cb);
	rig_free(g);
#endif
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_pruned_equals_every_pair),
		cmocka_unit_test(test_cached_frames_equal_every_pair),
		cmocka_unit_test(test_self_skips_jointed_and_table_only),
		cmocka_unit_test(test_hand_into_the_wheel),
		cmocka_unit_test(test_no_alloc_of_ours),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
