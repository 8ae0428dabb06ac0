/*
 * clearance.h - the clearance between figures' segments, and of a figure
 * with itself: every pair nearer than a threshold (their distance, or the
 * penetration depth as a negative distance, and the two closest points),
 * and the smallest distance of all.
 *
 * The exact distance (collide.h) is asked only where it could matter. Each
 * pair has a lower bound of its distance: the gap between the segments'
 * world bounding boxes, and, with a cache of the last frames, the distance
 * found when last asked less how far any point of one mesh can have moved
 * relative to the other since (the relative transform's translation plus
 * its rotation's chord times the mesh's radius). Pairs are taken nearest
 * bound first, and a pair whose bound is positive and beyond both the
 * threshold and the smallest distance found so far is left unasked: its
 * distance can change neither. A pair whose relative transform has not
 * moved (1e-12 m) takes its last answer as it was. The result is the same
 * as asking every pair, to that 1e-12 m.
 *
 * A clearance_work holds the scratch of a query, allocated once
 * (clearance_work_make); a clearance_cache what a pair of figures' last
 * query found. Queries allocate nothing.
 */
#ifndef POSTURE_CLEARANCE_H
#define POSTURE_CLEARANCE_H

#include "figure/state.h"
#include "fit/fit_model.h"

#define CLEARANCE_PAIRS_MAX 256 /* pairs a result lists; more are counted */

struct clearance_pair {
	int fig_a, seg_a; /* the caller's figure numbers and the segments */
	int fig_b, seg_b;
	double distance;  /* m: < 0 interpenetrating by that depth */
	double pa[3], pb[3]; /* world: a's point nearest b, b's nearest a (the contact's when < 0) */
};

struct clearance_result {
	double threshold;
	int npairs;      /* pairs listed, nearest first */
	int more;        /* pairs within the threshold beyond CLEARANCE_PAIRS_MAX */
	struct clearance_pair pair[CLEARANCE_PAIRS_MAX];
	int has_minimum; /* 0: no pair was checked */
	struct clearance_pair minimum;
	long candidates; /* pairs considered */
	long asked;      /* pairs whose exact distance was computed */
	long reused;     /* pairs whose last answer stood (nothing moved between them) */
};

struct clearance_work;
/* scratch for figures of up to max_seg segments; NULL when out of memory */
struct clearance_work *clearance_work_make(int max_seg);
void clearance_work_free(struct clearance_work *w);

struct clearance_cache;
/* the cache of figures fa and fb (the same for a figure with itself); NULL when out of memory */
struct clearance_cache *clearance_cache_make(const struct fit_model *fa, const struct fit_model *fb);
void clearance_cache_free(struct clearance_cache *c);
/* forgets every answer (the next query asks afresh) */
void clearance_cache_forget(struct clearance_cache *c);

/* an empty result for threshold (m, >= 0) */
void clearance_begin(struct clearance_result *res, double threshold);

/*
 * Adds the pairs between figure a (number ia, model fa, posture sa with
 * kin_forward done) and figure b (ib, fb, sb) to res, with cache c made
 * for fa and fb (NULL: none, every bound from the boxes alone). Returns 0,
 * or -1 when a figure has more segments than the work was made for, the
 * cache is another pair's, or the collision library fails.
 */
int clearance_between(struct clearance_work *w, struct clearance_cache *c, int ia,
		      const struct fit_model *fa, const struct state *sa, int ib,
		      const struct fit_model *fb, const struct state *sb,
		      struct clearance_result *res);

/* the same for figure i with itself (c made for f and f), leaving out the pairs its model skips */
int clearance_self(struct clearance_work *w, struct clearance_cache *c, int i,
		   const struct fit_model *f, const struct state *s, struct clearance_result *res);

/* sorts res's pairs nearest first (the queries keep them in the order found) */
void clearance_sort(struct clearance_result *res);

#endif
