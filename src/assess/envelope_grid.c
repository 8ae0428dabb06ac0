/*
 * envelope_grid.c - the reachability field, coarse to fine, and its surface
 * (envelope_grid.h).
 */
#include "assess/envelope_grid.h"

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* the coarsest cell: the first lattice is solved at this spacing or finer */
#define COARSE_CELL 0.16
/* m: a cell at most this size with every corner inside, and no neighbour crossing the
 * surface, is taken as inside without solving its points (a pocket of unreachable
 * points smaller than this, away from the surface, is not looked for) */
#define TRUST_CELL 0.16
/* the grid's size, points (13 bytes each: at most about 200 MB) */
#define GRID_POINTS_MAX (16L << 20)

enum { ST_NONE, ST_SOLVED, ST_BOUND, ST_ASSUMED, ST_QUEUED };

struct field {
	const struct env_oracle *o;
	int n[3];
	long nx, nxy, npt;
	double origin[3], step;
	float *val;        /* distance - tol: <= 0 inside */
	unsigned char *st; /* ST_ */
	int *slot;         /* a solved point's row in near and qs, else -1 */
	int *src;          /* the row of the posture a solve near the point starts from, or -1 */
	float *near;       /* 3 per solved point: where the effector ended */
	float *qs;         /* nq per solved point: its posture */
	long nnear, capnear;
	long *list;        /* points to solve, each with the point it starts from (or -1) */
	long nlist, caplist;
	long solves;
};

/* ---- solving on every thread ---------------------------------------------- */

struct batch {
	const struct env_oracle *o;
	const double *pts;     /* 3 n */
	const float *const *q0; /* n starting postures (NULL: the starting posture), or NULL */
	double *ends;          /* 3 n */
	float *qout;           /* nq n, or NULL */
	long n;
	atomic_long next;
	atomic_int fail;
};

struct worker {
	struct batch *b;
	void *thr;
};

static void *
work(void *arg)
{
	struct worker *w = arg;
	struct batch *b = w->b;
	for (;;) {
		long i0 = atomic_fetch_add(&b->next, 8);
		if (i0 >= b->n)
			break;
		long i1 = i0 + 8 < b->n ? i0 + 8 : b->n;
		for (long i = i0; i < i1; i++)
			if (b->o->solve(w->thr, &b->pts[3 * i], b->q0 ? b->q0[i] : NULL,
					&b->ends[3 * i],
					b->qout ? &b->qout[(size_t)i * b->o->nq] : NULL) < 0)
				atomic_store(&b->fail, 1);
	}
	return NULL;
}

/* ends[i] = where the effector ended sent toward pts[i], on the oracle's threads */
static int
run_batch(const struct env_oracle *o, const double *pts, const float *const *q0, double *ends,
	  float *qout, long n)
{
	struct batch b = { .o = o, .pts = pts, .q0 = q0, .ends = ends, .qout = qout, .n = n };
	atomic_init(&b.next, 0);
	atomic_init(&b.fail, 0);
	pthread_t tid[ENVELOPE_THREADS_MAX];
	struct worker w[ENVELOPE_THREADS_MAX];
	int started[ENVELOPE_THREADS_MAX] = { 0 };
	int nt = n < 32 ? 1 : o->nthreads;
	for (int t = 0; t < nt; t++)
		w[t] = (struct worker){ &b, o->thr[t] };
	/* a thread that cannot start leaves its share to the others */
	for (int t = 1; t < nt; t++)
		started[t] = pthread_create(&tid[t], NULL, work, &w[t]) == 0;
	work(&w[0]);
	for (int t = 1; t < nt; t++)
		if (started[t])
			pthread_join(tid[t], NULL);
	return atomic_load(&b.fail) ? -1 : 0;
}

/* ---- the field -------------------------------------------------------------- */

static void
point_pos(const struct field *f, long i, double p[3])
{
	p[0] = f->origin[0] + f->step * (double)(i % f->nx);
	p[1] = f->origin[1] + f->step * (double)(i % f->nxy / f->nx);
	p[2] = f->origin[2] + f->step * (double)(i / f->nxy);
}

static int
list_push(struct field *f, long i, long from)
{
	if (f->nlist == f->caplist) {
		long cap = f->caplist ? 2 * f->caplist : 4096;
		long *l = realloc(f->list, (size_t)cap * 2 * sizeof *l);
		if (!l)
			return -1;
		f->list = l;
		f->caplist = cap;
	}
	f->list[2 * f->nlist] = i;
	f->list[2 * f->nlist + 1] = from;
	f->nlist++;
	f->st[i] = ST_QUEUED;
	return 0;
}

/* the posture a solve from point `from` starts with, or NULL */
static const float *
start_posture(const struct field *f, long from)
{
	if (!f->o->nq || from < 0 || f->src[from] < 0)
		return NULL;
	return &f->qs[(size_t)f->src[from] * f->o->nq];
}

static double
dist_pts(const struct field *f, long a, long b)
{
	double pa[3], pb[3];
	point_pos(f, a, pa);
	point_pos(f, b, pb);
	return sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) +
		    (pa[2] - pb[2]) * (pa[2] - pb[2]));
}

/* the field's lower bound at p from q outside (1-Lipschitz), as a value; <= 0 proves nothing */
static float
lipschitz_value(const struct field *f, long p, long q)
{
	if ((f->st[q] != ST_SOLVED && f->st[q] != ST_BOUND) || f->val[q] <= 0)
		return 0;
	return (float)(f->val[q] - dist_pts(f, p, q));
}

/* p outside by q's bound: filled, its warm start q's */
static void
fill_bound(struct field *f, long p, long q, float v)
{
	f->val[p] = v;
	f->st[p] = ST_BOUND;
	f->src[p] = f->src[q];
}

/* solves the listed points and empties the list */
static int
solve_list(struct field *f)
{
	long n = f->nlist;
	if (!n)
		return 0;
	int nq = f->o->nq;
	if (f->nnear + n > f->capnear) {
		long cap = f->capnear ? f->capnear : 4096;
		while (cap < f->nnear + n)
			cap *= 2;
		float *near = realloc(f->near, (size_t)cap * 3 * sizeof *near);
		if (near)
			f->near = near;
		float *qs = nq ? realloc(f->qs, (size_t)cap * nq * sizeof *qs) : NULL;
		if (qs)
			f->qs = qs;
		if (!near || (nq && !qs))
			return -1;
		f->capnear = cap;
	}
	double *pts = malloc((size_t)n * 6 * sizeof *pts);
	const float **q0 = malloc((size_t)n * sizeof *q0);
	if (!pts || !q0) {
		free(pts);
		free(q0);
		return -1;
	}
	double *ends = pts + 3 * n;
	for (long k = 0; k < n; k++) {
		point_pos(f, f->list[2 * k], &pts[3 * k]);
		q0[k] = f->o->warm_field ? start_posture(f, f->list[2 * k + 1]) : NULL;
	}
	int r = run_batch(f->o, pts, q0, ends, nq ? &f->qs[(size_t)f->nnear * nq] : NULL, n);
	free(q0);
	if (r < 0) {
		free(pts);
		return -2;
	}
	for (long k = 0; k < n; k++) {
		long i = f->list[2 * k];
		const double *p = &pts[3 * k], *e = &ends[3 * k];
		double d = sqrt((p[0] - e[0]) * (p[0] - e[0]) + (p[1] - e[1]) * (p[1] - e[1]) +
				(p[2] - e[2]) * (p[2] - e[2]));
		f->val[i] = (float)(d - f->o->tol);
		f->st[i] = ST_SOLVED;
		f->slot[i] = f->src[i] = (int)f->nnear;
		for (int c = 0; c < 3; c++)
			f->near[3 * f->nnear + c] = (float)e[c];
		f->nnear++;
	}
	f->solves += n;
	f->nlist = 0;
	free(pts);
	return 0;
}

enum cell_class { CELL_OUT_PROVED, CELL_OUT, CELL_IN, CELL_MIXED };

static long
idx(const struct field *f, int i, int j, int k)
{
	return (long)k * f->nxy + (long)j * f->nx + i;
}

/* the class of the cell of stride s at lattice corner (i, j, k) */
static enum cell_class
cell_class(const struct field *f, int i, int j, int k, int s)
{
	int nin = 0;
	double dmax = -1;
	for (int c = 0; c < 8; c++) {
		long p = idx(f, i + (c & 1) * s, j + ((c >> 1) & 1) * s, k + ((c >> 2) & 1) * s);
		if (f->val[p] <= 0)
			nin++;
		else if (f->val[p] + f->o->tol > dmax)
			dmax = f->val[p] + f->o->tol;
	}
	if (nin == 8)
		return CELL_IN;
	if (nin)
		return CELL_MIXED;
	/* every point of the cell is within its diagonal of that corner: 1-Lipschitz */
	return dmax - sqrt(3.0) * s * f->step > f->o->tol ? CELL_OUT_PROVED : CELL_OUT;
}

/* the best lower bound on the field at p from the corners of the cell of stride s at
 * (i, j, k), as a value (<= 0 proves nothing), and the corner it came from */
static float
bound_value(const struct field *f, long p, int i, int j, int k, int s, long *corner)
{
	float best = -1;
	for (int c = 0; c < 8; c++) {
		long q = idx(f, i + (c & 1) * s, j + ((c >> 1) & 1) * s, k + ((c >> 2) & 1) * s);
		float v = lipschitz_value(f, p, q);
		if (v > best || c == 0) {
			best = v;
			*corner = q;
		}
	}
	return best;
}

/* cells of stride s: refine (solve the points of stride s/2 in them) or fill them */
static int
refine_level(struct field *f, int s)
{
	int c[3];
	for (int a = 0; a < 3; a++)
		c[a] = (f->n[a] - 1) / s;
	long ncell = (long)c[0] * c[1] * c[2];
	unsigned char *cls = malloc((size_t)ncell), *need = malloc((size_t)ncell);
	if (!cls || !need) {
		free(cls);
		free(need);
		return -1;
	}
	for (int k = 0; k < c[2]; k++)
		for (int j = 0; j < c[1]; j++)
			for (int i = 0; i < c[0]; i++)
				cls[((long)k * c[1] + j) * c[0] + i] =
					(unsigned char)cell_class(f, i * s, j * s, k * s, s);
	int trusted = s * f->step <= TRUST_CELL + 1e-9;
	for (int k = 0; k < c[2]; k++)
		for (int j = 0; j < c[1]; j++)
			for (int i = 0; i < c[0]; i++) {
				long ci = ((long)k * c[1] + j) * c[0] + i;
				int n = cls[ci] == CELL_OUT || cls[ci] == CELL_MIXED ||
					(cls[ci] == CELL_IN && !trusted);
				/* an inside cell next to the surface may hide a part of it */
				for (int d = 0; d < 27 && !n && cls[ci] == CELL_IN; d++) {
					int ii = i + d % 3 - 1, jj = j + d / 3 % 3 - 1, kk = k + d / 9 - 1;
					if (ii >= 0 && jj >= 0 && kk >= 0 && ii < c[0] && jj < c[1] &&
					    kk < c[2])
						n = cls[((long)kk * c[1] + jj) * c[0] + ii] == CELL_MIXED;
				}
				need[ci] = (unsigned char)n;
			}
	int h = s / 2, err = 0;
	for (int pass = 0; pass < 2 && !err; pass++)
		for (int k = 0; k < c[2] && !err; k++)
			for (int j = 0; j < c[1] && !err; j++)
				for (int i = 0; i < c[0] && !err; i++) {
					long ci = ((long)k * c[1] + j) * c[0] + i;
					if (need[ci] != (pass == 0))
						continue;
					for (int d = 0; d < 27 && !err; d++) {
						int a = d % 3, b = d / 3 % 3, e = d / 9;
						long p = idx(f, i * s + a * h, j * s + b * h, k * s + e * h);
						if (f->st[p] != ST_NONE)
							continue;
						/* the nearest corner starts its solve */
						long near = idx(f, i * s + a / 2 * s, j * s + b / 2 * s,
								k * s + e / 2 * s), q;
						float v = bound_value(f, p, i * s, j * s, k * s, s, &q);
						if (v > 0) {
							fill_bound(f, p, q, v);
						} else if (pass == 0) {
							err = list_push(f, p, near);
						} else {
							f->val[p] = (float)(-0.5 * f->step);
							f->st[p] = ST_ASSUMED;
							f->src[p] = f->src[near];
						}
					}
				}
	free(cls);
	free(need);
	if (err)
		return -1;
	return solve_list(f);
}

/* the grid neighbours of p across the split's edges (both ways); returns their count */
static int
kuhn_neighbours(const struct field *f, long p, long dest[14])
{
	int i = (int)(p % f->nx), j = (int)(p % f->nxy / f->nx), k = (int)(p / f->nxy), n = 0;
	for (int c = 1; c < 8; c++) {
		int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
		if (i + dx < f->n[0] && j + dy < f->n[1] && k + dz < f->n[2])
			dest[n++] = idx(f, i + dx, j + dy, k + dz);
		if (i - dx >= 0 && j - dy >= 0 && k - dz >= 0)
			dest[n++] = idx(f, i - dx, j - dy, k - dz);
	}
	return n;
}

/* a filled point across a change of sign is solved, from that neighbour's posture: returns
 * the neighbour, or -1 */
static long
needs_solve(const struct field *f, long p)
{
	if (f->st[p] != ST_BOUND && f->st[p] != ST_ASSUMED)
		return -1;
	long nb[14];
	int n = kuhn_neighbours(f, p, nb), in = f->val[p] <= 0;
	for (int q = 0; q < n; q++)
		if ((f->val[nb[q]] <= 0) != in)
			return nb[q];
	return -1;
}

/* solves the filled points along the surface until none is left */
static int
trace_surface(struct field *f)
{
	for (long p = 0; p < f->npt; p++) {
		long from = needs_solve(f, p);
		if (from >= 0 && list_push(f, p, from) < 0)
			return -1;
	}
	long *last = NULL, nlast = 0;
	while (f->nlist) {
		free(last);
		nlast = f->nlist;
		last = malloc((size_t)nlast * sizeof *last);
		if (!last)
			return -1;
		for (long k = 0; k < nlast; k++)
			last[k] = f->list[2 * k];
		int r = solve_list(f);
		if (r < 0) {
			free(last);
			return r;
		}
		for (long k = 0; k < nlast; k++) {
			long nb[14];
			int n = kuhn_neighbours(f, last[k], nb);
			for (int q = 0; q < n; q++) {
				long from = needs_solve(f, nb[q]);
				if (from >= 0 && list_push(f, nb[q], from) < 0) {
					free(last);
					return -1;
				}
			}
		}
	}
	free(last);
	return 0;
}

/* ---- the surface's vertices --------------------------------------------------- */

/*
 * How far a vertex stays from its edge's grid points (m): vertices of
 * different edges meet only there, so none coincides with another and the
 * surface stays a 2-manifold when read back welded by position. Twice the
 * reached tolerance: a vertex this near its reached inside point is reached
 * within three times the tolerance (0.75 mm), inside can reach's 1 mm.
 */
static double
edge_margin(const struct field *f)
{
	return fmin(2 * f->o->tol, 0.02 * f->step);
}

/* where the plane tangent to the reachable set at b's nearest reached point, moved in by a
 * margin, crosses a-b */
static void
vertex_guess(const struct field *f, long a, long b, double dest[3])
{
	double pa[3], pb[3], t = 0.5;
	point_pos(f, a, pa);
	point_pos(f, b, pb);
	if (f->slot[b] >= 0) {
		const float *c = &f->near[3 * f->slot[b]];
		double nv[3] = { pb[0] - c[0], pb[1] - c[1], pb[2] - c[2] };
		double d = sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
		double ab[3] = { pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2] };
		double len = sqrt(ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2]);
		double den = d > 0 ? (ab[0] * nv[0] + ab[1] * nv[1] + ab[2] * nv[2]) / d : 0;
		/* the plane a millimetre (at most a twentieth of a step) inside: a vertex on
		 * a curved surface's tangent plane would mostly be just out of reach, and
		 * its solve would fail after every restart */
		double margin = fmin(1e-3, 0.05 * f->step);
		if (den > 1e-6 * len)
			t = (((c[0] - pa[0]) * nv[0] + (c[1] - pa[1]) * nv[1] + (c[2] - pa[2]) * nv[2]) / d -
			     margin) /
			    den;
		else
			t = 1 - d / len;
	}
	double len = sqrt((pb[0] - pa[0]) * (pb[0] - pa[0]) + (pb[1] - pa[1]) * (pb[1] - pa[1]) +
			  (pb[2] - pa[2]) * (pb[2] - pa[2]));
	double e = len > 0 ? edge_margin(f) / len : 0;
	t = fmin(1 - e, fmax(e, t));
	for (int i = 0; i < 3; i++)
		dest[i] = pa[i] + t * (pb[i] - pa[i]);
}

/* the point of edge a-b (a inside) the edge margin from a: reached, as a is */
static void
vertex_inside(const struct field *f, long a, long b, double dest[3])
{
	double pa[3], pb[3];
	point_pos(f, a, pa);
	point_pos(f, b, pb);
	double len = sqrt((pb[0] - pa[0]) * (pb[0] - pa[0]) + (pb[1] - pa[1]) * (pb[1] - pa[1]) +
			  (pb[2] - pa[2]) * (pb[2] - pa[2]));
	double e = len > 0 ? edge_margin(f) / len : 0;
	for (int i = 0; i < 3; i++)
		dest[i] = pa[i] + e * (pb[i] - pa[i]);
}

/* vertices by position, for finding those that coincide */
static const float *sort_vert;

static int
by_position(const void *x, const void *y)
{
	const float *a = sort_vert + 3 * *(const long *)x, *b = sort_vert + 3 * *(const long *)y;
	for (int c = 0; c < 3; c++)
		if (a[c] != b[c])
			return a[c] < b[c] ? -1 : 1;
	return 0;
}

#define NUDGE 2e-6 /* m: a vertex moved off another it coincides with, towards its inside point */

/*
 * Two vertices the solver sent to one point (two targets out of reach whose
 * solves end alike) would make the surface touch itself there once read back
 * welded by position, as every STL reader does: each but the first of a run
 * of coincident vertices is moved a few micrometres towards its edge's
 * inside point. Returns 0, or -1 when out of memory.
 */
static int
separate_coincident(const struct field *f, struct mc_mesh *mesh, const long *edges)
{
	long n = mesh->nvert;
	long *order = malloc((size_t)n * sizeof *order);
	if (!order)
		return -1;
	for (long v = 0; v < n; v++)
		order[v] = v;
	sort_vert = mesh->vert;
	qsort(order, (size_t)n, sizeof *order, by_position);
	for (long i = 1, run = 0; i < n; i++) {
		run = by_position(&order[i - 1], &order[i]) ? 0 : run + 1;
		if (!run)
			continue;
		long v = order[i];
		float *q = &mesh->vert[3 * v];
		double pa[3], d[3], len = 0;
		point_pos(f, edges[2 * v], pa);
		for (int c = 0; c < 3; c++) {
			d[c] = pa[c] - q[c];
			len += d[c] * d[c];
		}
		len = sqrt(len);
		for (int c = 0; c < 3; c++)
			q[c] = (float)(q[c] + (len > 0 ? d[c] / len : 1) * NUDGE * (double)run);
	}
	free(order);
	return 0;
}

/* each vertex placed on its edge and sent to the solver: a vertex not reached moves to
 * where the effector ended, or, if that is further than a step, along its edge to the
 * edge margin from its inside point */
static int
place_vertices(struct field *f, struct mc_mesh *mesh, const long *edges)
{
	long n = mesh->nvert;
	if (!n)
		return 0;
	double *pts = malloc((size_t)n * 6 * sizeof *pts);
	if (!pts)
		return -1;
	double *ends = pts + 3 * n;
	const float **q0 = malloc((size_t)n * sizeof *q0);
	if (!q0) {
		free(pts);
		return -1;
	}
	/* as the field was solved: from the starting posture, or from the posture of the
	 * outside point, whose palm ended near the vertex */
	for (long v = 0; v < n; v++) {
		vertex_guess(f, edges[2 * v], edges[2 * v + 1], &pts[3 * v]);
		q0[v] = f->o->warm_field ? start_posture(f, edges[2 * v + 1]) : NULL;
	}
	int r = run_batch(f->o, pts, q0, ends, NULL, n);
	free(q0);
	if (r < 0) {
		free(pts);
		return -2;
	}
	f->solves += n;
	for (long v = 0; v < n; v++) {
		double *p = &pts[3 * v], *e = &ends[3 * v];
		double d = sqrt((p[0] - e[0]) * (p[0] - e[0]) + (p[1] - e[1]) * (p[1] - e[1]) +
				(p[2] - e[2]) * (p[2] - e[2]));
		double q[3];
		if (d <= f->o->tol)
			memcpy(q, p, sizeof q);
		else if (d <= f->step)
			memcpy(q, e, sizeof q);
		else
			vertex_inside(f, edges[2 * v], edges[2 * v + 1], q);
		for (int c = 0; c < 3; c++)
			mesh->vert[3 * v + c] = (float)q[c];
	}
	free(pts);
	if (separate_coincident(f, mesh, edges) < 0)
		return -1;
	mc_mesh_finish(mesh);
	return 0;
}

/* ---- entry points ------------------------------------------------------------- */

int
env_bounds(const struct env_oracle *o, const double centre[3], double step, double lo[3],
	   double hi[3])
{
	double pts[26 * 3], ends[26 * 3];
	int n = 0;
	for (int d = 0; d < 27; d++) {
		int v[3] = { d % 3 - 1, d / 3 % 3 - 1, d / 9 - 1 };
		if (!v[0] && !v[1] && !v[2])
			continue;
		double len = sqrt((double)(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
		for (int i = 0; i < 3; i++)
			pts[3 * n + i] = centre[i] + 50.0 * v[i] / len;
		n++;
	}
	if (run_batch(o, pts, NULL, ends, NULL, n) < 0)
		return -1;
	for (int i = 0; i < 3; i++)
		lo[i] = hi[i] = centre[i];
	for (int k = 0; k < n; k++)
		for (int i = 0; i < 3; i++) {
			lo[i] = fmin(lo[i], ends[3 * k + i]);
			hi[i] = fmax(hi[i], ends[3 * k + i]);
		}
	/* the far solves find the extremes only roughly: a margin of a tenth of the size */
	for (int i = 0; i < 3; i++) {
		double m = 0.1 * (hi[i] - lo[i]) + 2 * step;
		lo[i] -= m;
		hi[i] += m;
	}
	return 0;
}

/* the coarse lattice (stride S) in waves outwards from the seed's nearest lattice point,
 * each point from its neighbour towards the seed: proved outside by it, or solved from
 * its posture */
static int
coarse_waves(struct field *f, const double seed[3], int S)
{
	int c[3], sc[3], maxw = 0;
	for (int a = 0; a < 3; a++) {
		c[a] = (f->n[a] - 1) / S + 1;
		sc[a] = (int)lround((seed[a] - f->origin[a]) / (f->step * S));
		sc[a] = sc[a] < 0 ? 0 : sc[a] >= c[a] ? c[a] - 1 : sc[a];
		maxw = fmax(maxw, fmax(sc[a], c[a] - 1 - sc[a]));
	}
	for (int w = 0; w <= maxw; w++) {
		for (int k = 0; k < c[2]; k++)
			for (int j = 0; j < c[1]; j++)
				for (int i = 0; i < c[0]; i++) {
					int l[3] = { i, j, k }, from[3], wave = 0;
					for (int a = 0; a < 3; a++) {
						int d = l[a] - sc[a];
						wave = abs(d) > wave ? abs(d) : wave;
						from[a] = l[a] - (d > 0) + (d < 0);
					}
					if (wave != w)
						continue;
					long p = idx(f, i * S, j * S, k * S);
					long q = w ? idx(f, from[0] * S, from[1] * S, from[2] * S) : -1;
					float v = q >= 0 ? lipschitz_value(f, p, q) : 0;
					if (v > 0)
						fill_bound(f, p, q, v);
					else if (list_push(f, p, q) < 0)
						return -1;
				}
		int r = solve_list(f);
		if (r < 0)
			return r;
	}
	return 0;
}

static void
field_free(struct field *f)
{
	free(f->val);
	free(f->st);
	free(f->slot);
	free(f->src);
	free(f->near);
	free(f->qs);
	free(f->list);
}

/* the surface within the box; 1 (and the box's faces the set reaches in clipped, -x +x -y
 * +y -z +z) when the reachable set reaches its outermost layer */
static int
surface_in_box(const struct env_oracle *o, const double lo[3], const double hi[3],
	       const double seed[3], double step, struct mc_mesh *dest, struct env_stats *st,
	       int clipped[6], char *err, size_t errlen)
{
	memset(dest, 0, sizeof *dest);
	struct field f = { .o = o, .step = step };
	/* the coarse stride: a power of two, its cell at most COARSE_CELL */
	int S = 1;
	while (2 * S * step <= COARSE_CELL + 1e-9)
		S *= 2;
	for (int a = 0; a < 3; a++) {
		int cells = (int)ceil((hi[a] - lo[a]) / step / S);
		f.n[a] = (cells < 1 ? 1 : cells) * S + 1;
		/* centred on the box */
		f.origin[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * (f.n[a] - 1) * step;
		st->grid[a] = f.n[a];
	}
	f.nx = f.n[0];
	f.nxy = (long)f.n[0] * f.n[1];
	f.npt = f.nxy * f.n[2];
	if (f.npt > GRID_POINTS_MAX) {
		snprintf(err, errlen, "resolution %g m is too fine for this reach: %ld grid points (at most %ld)",
			 step, f.npt, GRID_POINTS_MAX);
		return -1;
	}
	f.val = malloc((size_t)f.npt * sizeof *f.val);
	f.st = calloc((size_t)f.npt, 1);
	f.slot = malloc((size_t)f.npt * sizeof *f.slot);
	f.src = malloc((size_t)f.npt * sizeof *f.src);
	int r = f.val && f.st && f.slot && f.src ? 0 : -1;
	if (!r) {
		memset(f.slot, 0xff, (size_t)f.npt * sizeof *f.slot);
		memset(f.src, 0xff, (size_t)f.npt * sizeof *f.src);
		r = coarse_waves(&f, seed, S);
	}
	for (int s = S; s >= 2 && !r; s /= 2)
		r = refine_level(&f, s);
	if (!r)
		r = trace_surface(&f);
	/* the outermost layer must be outside, so that the surface is closed */
	int nclip = 0;
	for (long p = 0; p < f.npt && !r; p++) {
		int l[3] = { (int)(p % f.nx), (int)(p % f.nxy / f.nx), (int)(p / f.nxy) };
		for (int a = 0; a < 3 && f.val[p] <= 0; a++) {
			if (l[a] == 0)
				nclip += clipped[2 * a] = 1;
			if (l[a] == f.n[a] - 1)
				nclip += clipped[2 * a + 1] = 1;
		}
	}
	if (!r && nclip) {
		st->solves = f.solves;
		field_free(&f);
		return 1;
	}
	long *edges = NULL;
	if (!r) {
		struct mc_grid g = { { f.n[0], f.n[1], f.n[2] },
				     { f.origin[0], f.origin[1], f.origin[2] },
				     step,
				     f.val };
		r = mc_extract(&g, dest, &edges);
	}
	if (!r)
		r = place_vertices(&f, dest, edges);
	free(edges);
	st->solves = f.solves;
	field_free(&f);
	if (r) {
		mc_mesh_free(dest);
		snprintf(err, errlen, r == -2 ? "the solver refused a point" : "out of memory");
		return -1;
	}
	return 0;
}

int
env_surface(const struct env_oracle *o, const double lo[3], const double hi[3],
	    const double seed[3], double step, struct mc_mesh *dest, struct env_stats *st,
	    char *err, size_t errlen)
{
	double l[3], h[3];
	memcpy(l, lo, sizeof l);
	memcpy(h, hi, sizeof h);
	long solves = 0;
	/* the box from the far solves can miss a direction the solver got stuck in: a side the
	 * set reaches is moved out by half the box, and the field solved again */
	for (int attempt = 0; attempt < 4; attempt++) {
		int clipped[6] = { 0 };
		int r = surface_in_box(o, l, h, seed, step, dest, st, clipped, err, errlen);
		solves += st->solves;
		st->solves = solves;
		if (r <= 0)
			return r;
		for (int a = 0; a < 3; a++) {
			double grow = 0.5 * (h[a] - l[a]) + 2 * step;
			l[a] -= clipped[2 * a] ? grow : 0;
			h[a] += clipped[2 * a + 1] ? grow : 0;
		}
	}
	snprintf(err, errlen, "the reachable set does not fit the box it was searched in");
	return -1;
}
