/* clearance.c - pairs of segments nearer than a threshold, and the smallest distance */
#include "fit/clearance.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define UNMOVED 1e-12 /* m: a pair moved less than this relative to itself takes its last answer */

struct candidate {
	double bound; /* a lower bound of the pair's distance */
	double moved; /* m: how far b can have moved relative to a since the cached answer */
	int a, b;
};

struct clearance_work {
	int max_seg;
	double *lo_a, *hi_a, *lo_b, *hi_b; /* max_seg x 3: world boxes this query */
	struct candidate *cand;            /* max_seg^2 */
	struct collide_scratch *scratch;
};

/* the last answer of a pair: in a's frame, b's place then, and the answer */
struct answer {
	double rel[12];   /* b's frame in a's frame: rotation (row-major), translation */
	double distance;
	double pa[3];     /* a's point, in a's frame */
	double pb[3];     /* b's point, in b's frame */
	unsigned char valid;
};

struct clearance_cache {
	const struct fit_model *fa, *fb;
	struct answer *ans; /* fa->nseg x fb->nseg */
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

struct clearance_cache *
clearance_cache_make(const struct fit_model *fa, const struct fit_model *fb)
{
	struct clearance_cache *c = calloc(1, sizeof *c);
	if (!c)
		return NULL;
	c->fa = fa;
	c->fb = fb;
	c->ans = calloc((size_t)fa->nseg * (size_t)fb->nseg + 1, sizeof *c->ans);
	if (!c->ans) {
		free(c);
		return NULL;
	}
	return c;
}

void
clearance_cache_free(struct clearance_cache *c)
{
	if (!c)
		return;
	free(c->ans);
	free(c);
}

void
clearance_cache_forget(struct clearance_cache *c)
{
	memset(c->ans, 0, sizeof *c->ans * (size_t)c->fa->nseg * (size_t)c->fb->nseg);
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
	res->reused = 0;
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

/* b's frame in a's: rel = a^-1 b */
static void
relative(const struct xform *a, const struct xform *b, double rel[12])
{
	for (int i = 0; i < 3; i++) {
		for (int j = 0; j < 3; j++) {
			double s = 0;
			for (int k = 0; k < 3; k++)
				s += a->r[3 * k + i] * b->r[3 * k + j];
			rel[3 * i + j] = s;
		}
		double t = 0;
		for (int k = 0; k < 3; k++)
			t += a->r[3 * k + i] * (b->p[k] - a->p[k]);
		rel[9 + i] = t;
	}
}

/*
 * How far a point of b within radius of b's origin can have moved in a's
 * frame between relative transforms r0 and r1: the translation's change
 * plus the chord of the rotation between them, |R1 R0^T - I| = 2 sin(θ/2)
 * = sqrt(3 - trace(R1 R0^T)), times the radius.
 */
static double
moved_by(const double *r0, const double *r1, double radius)
{
	double tr = 0, dt = 0;
	for (int i = 0; i < 3; i++)
		for (int k = 0; k < 3; k++)
			tr += r1[3 * i + k] * r0[3 * i + k];
	for (int i = 0; i < 3; i++)
		dt += (r1[9 + i] - r0[9 + i]) * (r1[9 + i] - r0[9 + i]);
	return sqrt(dt) + sqrt(fmax(0, 3 - tr)) * radius;
}

/* heap sort by bound, ascending: in place, no allocation (glibc's qsort may allocate) */
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

/* the pair (a, b) as a candidate: its bound from the boxes and the cache */
static void
add_candidate(struct clearance_work *w, int *n, struct clearance_cache *c, const struct fit_model *fb,
	      const struct state *sa, const struct state *sb, const double *la, const double *ha,
	      const double *lb, const double *hb, int a, int b)
{
	struct candidate k = { box_gap(la, ha, lb, hb), INFINITY, a, b };
	if (c && c->ans[a * fb->nseg + b].valid) {
		const struct answer *an = &c->ans[a * fb->nseg + b];
		double rel[12];
		relative(&sa->seg_xf[a], &sb->seg_xf[b], rel);
		k.moved = moved_by(an->rel, rel, fb->radius[b]);
		k.bound = fmax(k.bound, an->distance - k.moved);
	}
	w->cand[(*n)++] = k;
}

static void
to_world(const struct xform *f, const double local[3], double dest[3])
{
	for (int i = 0; i < 3; i++)
		dest[i] = f->r[3 * i] * local[0] + f->r[3 * i + 1] * local[1] + f->r[3 * i + 2] * local[2] +
			  f->p[i];
}

static void
to_local(const struct xform *f, const double world[3], double dest[3])
{
	for (int i = 0; i < 3; i++)
		dest[i] = f->r[i] * (world[0] - f->p[0]) + f->r[3 + i] * (world[1] - f->p[1]) +
			  f->r[6 + i] * (world[2] - f->p[2]);
}

/* the candidates in nearest-bound order, asked while they could matter */
static int
ask(struct clearance_work *w, struct clearance_cache *cache, int n, int ia,
    const struct fit_model *fa, const struct state *sa, int ib, const struct fit_model *fb,
    const struct state *sb, struct clearance_result *res)
{
	sort_candidates(w->cand, n);
	res->candidates += n;
	for (int k = 0; k < n; k++) {
		const struct candidate *c = &w->cand[k];
		double reach = res->threshold;
		if (!res->has_minimum || res->minimum.distance > reach)
			reach = res->has_minimum ? res->minimum.distance : INFINITY;
		/* a gap bounds the distance from below; a bound of 0 (boxes overlapping, or
		 * a pair that was touching) may hide any depth of penetration: always asked */
		if (c->bound > 0 && c->bound >= reach && res->has_minimum)
			break; /* this and every later pair: neither within the threshold nor nearer */
		struct clearance_pair p = { ia, c->a, ib, c->b, 0, { 0 }, { 0 } };
		struct answer *an = cache ? &cache->ans[c->a * fb->nseg + c->b] : NULL;
		if (an && an->valid && c->moved <= UNMOVED) {
			p.distance = an->distance;
			to_world(&sa->seg_xf[c->a], an->pa, p.pa);
			to_world(&sb->seg_xf[c->b], an->pb, p.pb);
			res->reused++;
		} else {
			struct collide_result r;
			if (collide_distance(w->scratch, fa->mesh[c->a], &sa->seg_xf[c->a],
					     fb->mesh[c->b], &sb->seg_xf[c->b], &r) < 0)
				return -1;
			res->asked++;
			p.distance = r.distance;
			memcpy(p.pa, r.pa, sizeof p.pa);
			memcpy(p.pb, r.pb, sizeof p.pb);
			if (an) {
				relative(&sa->seg_xf[c->a], &sb->seg_xf[c->b], an->rel);
				an->distance = r.distance;
				to_local(&sa->seg_xf[c->a], r.pa, an->pa);
				to_local(&sb->seg_xf[c->b], r.pb, an->pb);
				an->valid = 1;
			}
		}
		keep(res, &p);
	}
	return 0;
}

int
clearance_between(struct clearance_work *w, struct clearance_cache *c, int ia,
		  const struct fit_model *fa, const struct state *sa, int ib,
		  const struct fit_model *fb, const struct state *sb, struct clearance_result *res)
{
	if (fa->nseg > w->max_seg || fb->nseg > w->max_seg || (c && (c->fa != fa || c->fb != fb)))
		return -1;
	world_boxes(fa, sa, w->lo_a, w->hi_a);
	world_boxes(fb, sb, w->lo_b, w->hi_b);
	int n = 0;
	for (int a = 0; a < fa->nseg; a++) {
		if (!fa->mesh[a])
			continue;
		for (int b = 0; b < fb->nseg; b++)
			if (fb->mesh[b])
				add_candidate(w, &n, c, fb, sa, sb, w->lo_a + 3 * a, w->hi_a + 3 * a,
					      w->lo_b + 3 * b, w->hi_b + 3 * b, a, b);
	}
	return ask(w, c, n, ia, fa, sa, ib, fb, sb, res);
}

int
clearance_self(struct clearance_work *w, struct clearance_cache *c, int i,
	       const struct fit_model *f, const struct state *s, struct clearance_result *res)
{
	if (f->nseg > w->max_seg || (c && (c->fa != f || c->fb != f)))
		return -1;
	world_boxes(f, s, w->lo_a, w->hi_a);
	int n = 0;
	for (int a = 0; a < f->nseg; a++)
		for (int b = a + 1; b < f->nseg; b++)
			if (fit_model_skip(f, a, b) == FIT_CHECKED)
				add_candidate(w, &n, c, f, s, s, w->lo_a + 3 * a, w->hi_a + 3 * a,
					      w->lo_a + 3 * b, w->hi_a + 3 * b, a, b);
	return ask(w, c, n, i, f, s, i, f, s, res);
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
