/* clearance.c - pairs of segments nearer than a threshold, and the smallest distance */
#include "fit/clearance.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct candidate {
	double bound; /* a lower bound of the pair's distance: its world boxes' gap */
	int a, b;
};

struct clearance_work {
	int max_seg;
	double *lo_a, *hi_a, *lo_b, *hi_b; /* max_seg x 3: world boxes this query */
	struct candidate *cand;            /* max_seg^2 */
	struct collide_scratch *scratch;
};

struct clearance_work *
clearance_work_make(int max_seg)
{
	if (max_seg < 1)
		max_seg = 1;
	struct clearance_work *w = calloc(1, sizeof *w);
	if (!w)
		return NULL;
	w->max_seg = max_seg;
	size_t n3 = 3 * (size_t)max_seg;
	w->lo_a = malloc(n3 * sizeof(double));
	w->hi_a = malloc(n3 * sizeof(double));
	w->lo_b = malloc(n3 * sizeof(double));
	w->hi_b = malloc(n3 * sizeof(double));
	w->cand = malloc((size_t)max_seg * (size_t)max_seg * sizeof *w->cand);
	w->scratch = collide_scratch_make();
	if (!w->lo_a || !w->hi_a || !w->lo_b || !w->hi_b || !w->cand || !w->scratch) {
		clearance_work_free(w);
		return NULL;
	}
	return w;
}

void
clearance_work_free(struct clearance_work *w)
{
	if (!w)
		return;
	free(w->lo_a);
	free(w->hi_a);
	free(w->lo_b);
	free(w->hi_b);
	free(w->cand);
	collide_scratch_free(w->scratch);
	free(w);
}

void
clearance_begin(struct clearance_result *res, double threshold)
{
	res->threshold = threshold;
	res->npairs = 0;
	res->more = 0;
	res->has_minimum = 0;
	res->candidates = 0;
	res->asked = 0;
}

/* the gap between two boxes: 0 when they overlap */
static double
box_gap(const double *la, const double *ha, const double *lb, const double *hb)
{
	double s = 0;
	for (int i = 0; i < 3; i++) {
		double g = fmax(lb[i] - ha[i], la[i] - hb[i]);
		if (g > 0)
			s += g * g;
	}
	return sqrt(s);
}

/* heap sort by bound, ascending: in place, no allocation (qsort may allocate) */
static void
sift(struct candidate *c, int root, int n)
{
	for (;;) {
		int child = 2 * root + 1;
		if (child >= n)
			return;
		if (child + 1 < n && c[child + 1].bound > c[child].bound)
			child++;
		if (c[root].bound >= c[child].bound)
			return;
		struct candidate t = c[root];
		c[root] = c[child];
		c[child] = t;
		root = child;
	}
}

static void
sort_candidates(struct candidate *c, int n)
{
	for (int i = n / 2 - 1; i >= 0; i--)
		sift(c, i, n);
	for (int end = n - 1; end > 0; end--) {
		struct candidate t = c[0];
		c[0] = c[end];
		c[end] = t;
		sift(c, 0, end);
	}
}

static void
world_boxes(const struct fit_model *f, const struct state *s, double *lo, double *hi)
{
	for (int g = 0; g < f->nseg; g++)
		if (f->mesh[g])
			fit_model_world_box(f, g, &s->seg_xf[g], lo + 3 * g, hi + 3 * g);
}

static void
keep(struct clearance_result *res, const struct clearance_pair *p)
{
	if (!res->has_minimum || p->distance < res->minimum.distance) {
		res->minimum = *p;
		res->has_minimum = 1;
	}
	if (p->distance >= res->threshold)
		return;
	if (res->npairs < CLEARANCE_PAIRS_MAX)
		res->pair[res->npairs++] = *p;
	else
		res->more++;
}

/* the candidates in nearest-bound order, asked while they could matter */
static int
ask(struct clearance_work *w, int n, int ia, const struct fit_model *fa, const struct state *sa,
    int ib, const struct fit_model *fb, const struct state *sb, struct clearance_result *res)
{
	sort_candidates(w->cand, n);
	res->candidates += n;
	for (int k = 0; k < n; k++) {
		const struct candidate *c = &w->cand[k];
		double reach = res->threshold;
		if (!res->has_minimum || res->minimum.distance > reach)
			reach = res->has_minimum ? res->minimum.distance : INFINITY;
		/* a gap between the boxes bounds the distance from below; overlapping boxes
		 * (a bound of 0) may hide any depth of penetration, so they are always asked */
		if (c->bound > 0 && c->bound >= reach && res->has_minimum)
			break; /* this and every later pair: neither within the threshold nor nearer */
		struct collide_result r;
		if (collide_distance(w->scratch, fa->mesh[c->a], &sa->seg_xf[c->a], fb->mesh[c->b], &sb->seg_xf[c->b],
				     &r) < 0)
			return -1;
		res->asked++;
		struct clearance_pair p = { ia, c->a, ib, c->b, r.distance, { 0 }, { 0 } };
		memcpy(p.pa, r.pa, sizeof p.pa);
		memcpy(p.pb, r.pb, sizeof p.pb);
		keep(res, &p);
	}
	return 0;
}

int
clearance_between(struct clearance_work *w, int ia, const struct fit_model *fa,
		  const struct state *sa, int ib, const struct fit_model *fb, const struct state *sb,
		  struct clearance_result *res)
{
	if (fa->nseg > w->max_seg || fb->nseg > w->max_seg)
		return -1;
	world_boxes(fa, sa, w->lo_a, w->hi_a);
	world_boxes(fb, sb, w->lo_b, w->hi_b);
	int n = 0;
	for (int a = 0; a < fa->nseg; a++) {
		if (!fa->mesh[a])
			continue;
		for (int b = 0; b < fb->nseg; b++) {
			if (!fb->mesh[b])
				continue;
			w->cand[n++] = (struct candidate){
				box_gap(w->lo_a + 3 * a, w->hi_a + 3 * a, w->lo_b + 3 * b, w->hi_b + 3 * b), a, b
			};
		}
	}
	return ask(w, n, ia, fa, sa, ib, fb, sb, res);
}

int
clearance_self(struct clearance_work *w, int i, const struct fit_model *f, const struct state *s,
	       struct clearance_result *res)
{
	if (f->nseg > w->max_seg)
		return -1;
	world_boxes(f, s, w->lo_a, w->hi_a);
	int n = 0;
	for (int a = 0; a < f->nseg; a++)
		for (int b = a + 1; b < f->nseg; b++)
			if (fit_model_skip(f, a, b) == FIT_CHECKED)
				w->cand[n++] = (struct candidate){
					box_gap(w->lo_a + 3 * a, w->hi_a + 3 * a, w->lo_a + 3 * b,
						w->hi_a + 3 * b),
					a, b
				};
	return ask(w, n, i, f, s, i, f, s, res);
}

void
clearance_sort(struct clearance_result *res)
{
	/* insertion sort: at most CLEARANCE_PAIRS_MAX, mostly in order, and no allocation */
	for (int i = 1; i < res->npairs; i++) {
		struct clearance_pair t = res->pair[i];
		int j = i;
		for (; j > 0 && res->pair[j - 1].distance > t.distance; j--)
			res->pair[j] = res->pair[j - 1];
		res->pair[j] = t;
	}
}
