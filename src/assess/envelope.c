/*
 * envelope.c - reach envelopes (envelope.h): the human's hand by the reach
 * solver (pose/reach.h), one reach object per thread, or any figure's chain
 * by the IK solver alone; the field and its surface are envelope_grid.c's.
 */
#include "assess/envelope.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "assess/envelope_comfort.h"
#include "assess/envelope_grid.h"
#include "figure/human_data.h"
#include "figure/kin.h"

/* m: a point counts as reached when the palm ends within this of it: a quarter of "can
 * reach"'s tolerance, so that a vertex "can reach" solves again is reached within its
 * own, whichever way the solver comes at it */
#define ENVELOPE_TOL (0.25 * REACH_TOL_POS)

static double
now_s(void)
{
	struct timespec t;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int
thread_count(int asked)
{
	long n = asked > 0 ? asked : sysconf(_SC_NPROCESSORS_ONLN);
	return n < 1 ? 1 : n > ENVELOPE_THREADS_MAX ? ENVELOPE_THREADS_MAX : (int)n;
}

static void
mesh_take(struct envelope_mesh *dest, struct mc_mesh *src)
{
	dest->nvert = src->nvert;
	dest->ntri = src->ntri;
	dest->vert = src->vert;
	dest->normal = src->normal;
	dest->tri = src->tri;
	dest->volume = src->volume;
	memcpy(dest->lo, src->lo, sizeof dest->lo);
	memcpy(dest->hi, src->hi, sizeof dest->hi);
	memset(src, 0, sizeof *src);
}

static void
mesh_free(struct envelope_mesh *mesh)
{
	free(mesh->vert);
	free(mesh->normal);
	free(mesh->tri);
	memset(mesh, 0, sizeof *mesh);
}

void
envelope_free(struct envelope *e)
{
	mesh_free(&e->reach);
	mesh_free(&e->comfort);
}

int
envelope_mesh_contains(const struct envelope_mesh *mesh, const double p[3])
{
	struct mc_mesh m = { mesh->nvert, mesh->ntri, mesh->vert, mesh->normal, mesh->tri,
			     mesh->volume, { mesh->lo[0], mesh->lo[1], mesh->lo[2] },
			     { mesh->hi[0], mesh->hi[1], mesh->hi[2] } };
	return mc_mesh_contains(&m, p);
}

static int
check_resolution(const struct envelope_request *req, char *err, size_t errlen)
{
	if (!isfinite(req->resolution) || req->resolution < ENVELOPE_RES_MIN - 1e-12 ||
	    req->resolution > ENVELOPE_RES_MAX + 1e-12) {
		snprintf(err, errlen, "resolution must be %g to %g m", ENVELOPE_RES_MIN,
			 ENVELOPE_RES_MAX);
		return -1;
	}
	if (req->threads < 0) {
		snprintf(err, errlen, "threads must be 0 (every core) or more");
		return -1;
	}
	return 0;
}

/* ---- the human's hand ---------------------------------------------------------- */

struct human_thr {
	struct reach *r;
	struct state *w; /* a warm start's posture */
	const int *dofs; /* the moved dofs a posture holds */
	int nq;
	double tol;
	const struct model *m;
	const struct state *s;
	const struct behave_params *p;
	const struct point_mass *pm;
	int n;
	struct reach_request q, qa; /* the request's mode, and the arm's */
};

static double
dist3(const double *a, const double *b)
{
	return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
		    (a[2] - b[2]) * (a[2] - b[2]));
}

/* one solve of request q toward p from start; the palm into dest */
static int
solve_once(struct human_thr *h, struct reach_request *q, const struct state *start,
	   const double p[3], double dest[3])
{
	struct reach_result res;
	memcpy(q->target, p, sizeof q->target);
	if (reach_solve(h->r, h->m, start, h->p, h->pm, h->n, q, &res) < 0)
		return -1;
	memcpy(dest, res.palm, sizeof res.palm);
	return 0;
}

static int
human_solve(void *thr, const double p[3], const float *q0, double dest[3], float *q_out)
{
	struct human_thr *h = thr;
	const struct state *start = h->s;
	if (q0) {
		state_copy(h->m, h->s, h->w);
		for (int i = 0; i < h->nq; i++)
			h->w->q[h->dofs[i]] = q0[i];
		kin_update(h->m, h->w);
		start = h->w;
	}
	if (solve_once(h, &h->q, start, p, dest) < 0)
		return -1;
	const struct state *end = reach_posture(h->r);
	for (int i = 0; q_out && i < h->nq; i++)
		q_out[i] = (float)end->q[h->dofs[i]];
	if (h->q.mode == REACH_ARM || dist3(dest, p) <= h->tol)
		return 0;
	/* the torso or the body stuck short: what the arm alone reaches they reach too, so
	 * from the arm's reaching posture (the rest as it stands) the whole again */
	double arm_end[3], end2[3];
	if (solve_once(h, &h->qa, h->s, p, arm_end) < 0)
		return -1;
	if (dist3(arm_end, p) > h->tol) {
		/* the nearer of the two is the better bound on the distance to the set */
		if (dist3(arm_end, p) < dist3(dest, p))
			memcpy(dest, arm_end, sizeof arm_end);
		return 0;
	}
	state_copy(h->m, reach_posture(h->r), h->w);
	kin_update(h->m, h->w);
	if (solve_once(h, &h->q, h->w, p, end2) < 0)
		return -1;
	if (dist3(end2, p) >= dist3(dest, p))
		return 0;
	memcpy(dest, end2, sizeof end2);
	end = reach_posture(h->r);
	for (int i = 0; q_out && i < h->nq; i++)
		q_out[i] = (float)end->q[h->dofs[i]];
	return 0;
}

/* the dofs mode moves for hand side: the arm's from the clavicle, the spine's for the
 * torso, every body dof but the eyes' for the body; returns their count */
static int
moved_dofs(const struct model *m, int side, enum reach_mode mode, int *dest)
{
	int n = 0;
	for (int j = 0; j < m->njnt; j++) {
		const char *name = m->jnt_name[j];
		int take;
		if (mode == REACH_BODY) {
			take = strncmp(name, "eye", 3) != 0;
		} else {
			take = !strncmp(name, "spine_", 6) && mode == REACH_TORSO;
			static const char *const arm[] = { "clavicle", "shoulder", "elbow", "wrist" };
			for (int a = 0; a < 4 && !take; a++) {
				size_t l = strlen(arm[a]);
				take = !strncmp(name, arm[a], l) && !strcmp(name + l, human_side_sfx[side]);
			}
		}
		for (int d = 0; take && d < m->jnt_ndof[j]; d++)
			dest[n++] = m->jnt_dof0[j] + d;
	}
	return n;
}

/* the surface for model m (the human, or its copy with the comfort limits) */
static int
human_surface(const struct model *m, const struct state *s, const struct behave_params *p,
	      const struct point_mass *pm, int n, const struct envelope_request *req,
	      struct envelope_mesh *dest, struct env_stats *st, char *err, size_t errlen)
{
	struct env_oracle o = { .nthreads = thread_count(req->threads),
				.solve = human_solve,
				.tol = ENVELOPE_TOL };
	/* the arm's field from the standing posture, as "can reach" solves; the torso and
	 * the body are 10 and 200 times dearer so: from a neighbour's posture */
	o.warm_field = req->mode != REACH_ARM;
	int *dofs = malloc((size_t)m->ndof * sizeof *dofs);
	if (!dofs) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	o.nq = moved_dofs(m, req->side, req->mode, dofs);
	struct human_thr thr[ENVELOPE_THREADS_MAX];
	int r = 0, made = 0;
	for (; made < o.nthreads; made++) {
		struct human_thr *h = &thr[made];
		*h = (struct human_thr){ .r = reach_make(m), .w = state_make(m), .dofs = dofs,
					 .nq = o.nq, .m = m, .s = s, .p = p, .pm = pm, .n = n };
		if (!h->r || !h->w) {
			reach_free(h->r);
			state_free(h->w);
			break;
		}
		h->q.side = req->side;
		h->q.mode = req->mode;
		h->q.balance = req->balance;
		h->q.restarts = req->mode == REACH_ARM ? ENVELOPE_ARM_RESTARTS : 0;
		h->qa = h->q;
		h->qa.mode = REACH_ARM;
		h->qa.restarts = ENVELOPE_ARM_RESTARTS;
		h->tol = o.tol;
		o.thr[made] = h;
	}
	if (made < o.nthreads) {
		snprintf(err, errlen, "out of memory, or not a human figure");
		r = -1;
	}
	/* the box about the shoulder */
	double centre[3], lo[3], hi[3];
	if (!r) {
		char name[32];
		snprintf(name, sizeof name, "clavicle%s", human_side_sfx[req->side]);
		int j = model_find_joint(m, name);
		if (j < 0) {
			snprintf(err, errlen, "the figure has no joint %s", name);
			r = -1;
		} else {
			memcpy(centre, &s->dof_pivot_w[3 * m->jnt_dof0[j]], sizeof centre);
		}
	}
	if (!r && env_bounds(&o, centre, req->resolution, lo, hi) < 0) {
		snprintf(err, errlen, "the reach solver refused the request");
		r = -1;
	}
	/* the seed: where the palm is */
	double seed[3];
	if (!r) {
		char name[32];
		snprintf(name, sizeof name, "hand%s.palm", human_side_sfx[req->side]);
		int site = model_find_site(m, name);
		memcpy(seed, site >= 0 ? s->site_xf[site].p : centre, sizeof seed);
	}
	struct mc_mesh mesh;
	if (!r)
		r = env_surface(&o, lo, hi, seed, req->resolution, &mesh, st, err, errlen);
	if (!r)
		mesh_take(dest, &mesh);
	for (int t = 0; t < made; t++) {
		reach_free(thr[t].r);
		state_free(thr[t].w);
	}
	free(dofs);
	return r;
}

int
envelope_compute(const struct model *m, const struct state *s, const struct behave_params *p,
		 const struct point_mass *pm, int n, const struct envelope_request *req,
		 struct envelope *dest, char *err, size_t errlen)
{
	memset(dest, 0, sizeof *dest);
	if (req->side != BEHAVE_LEFT && req->side != BEHAVE_RIGHT) {
		snprintf(err, errlen, "side must be left or right");
		return -1;
	}
	if (req->mode != REACH_ARM && req->mode != REACH_TORSO && req->mode != REACH_BODY) {
		snprintf(err, errlen, "mode must be arm, torso or body");
		return -1;
	}
	if (check_resolution(req, err, errlen) < 0)
		return -1;
	struct model *cm = NULL;
	if (req->comfort) {
		if (req->comfort_ranges.n < 0 || req->comfort_ranges.n > ENVELOPE_COMFORT_MAX) {
			snprintf(err, errlen, "comfort: bad count of ranges");
			return -1;
		}
		cm = model_copy(m);
		if (!cm) {
			snprintf(err, errlen, "out of memory");
			return -1;
		}
		if (envelope_comfort_apply(&req->comfort_ranges, cm, req->side, err, errlen) < 0) {
			model_free(cm);
			return -1;
		}
	}
	double t0 = now_s();
	struct env_stats st = { { 0, 0, 0 }, 0 };
	int r = human_surface(m, s, p, pm, n, req, &dest->reach, &st, err, errlen);
	long solves = st.solves;
	memcpy(dest->grid, st.grid, sizeof dest->grid); /* the reach's grid */
	if (!r && cm) {
		r = human_surface(cm, s, p, pm, n, req, &dest->comfort, &st, err, errlen);
		solves += st.solves;
	}
	model_free(cm);
	if (r) {
		envelope_free(dest);
		return -1;
	}
	dest->req = *req;
	dest->solves = solves;
	dest->seconds = now_s() - t0;
	return 0;
}

/* ---- any figure's chain ------------------------------------------------------- */

struct chain_thr {
	struct ik *ik;
	struct state *copy;
	const struct model *m;
	const struct state *s;
	int effector;
	struct ik_options opt;
};

static int
chain_solve(void *thr, const double p[3], const float *q0, double dest[3], float *q_out)
{
	struct chain_thr *c = thr;
	struct xform goal;
	xform_identity(&goal);
	memcpy(goal.p, p, sizeof goal.p);
	state_copy(c->m, c->s, c->copy);
	for (int d = 0; q0 && d < c->m->ndof; d++)
		c->copy->q[d] = q0[d];
	kin_update(c->m, c->copy);
	if (ik_set_goal(c->ik, 0, &goal) < 0)
		return -1;
	ik_solve(c->ik, c->m, c->copy, &c->opt, NULL);
	memcpy(dest, c->copy->site_xf[c->effector].p, 3 * sizeof *dest);
	for (int d = 0; q_out && d < c->m->ndof; d++)
		q_out[d] = (float)c->copy->q[d];
	return 0;
}

int
envelope_compute_chain(const struct model *m, const struct state *s, int effector,
		       int start_joint, const struct envelope_request *req,
		       struct envelope_mesh *dest, long *solves, char *err, size_t errlen)
{
	memset(dest, 0, sizeof *dest);
	if (check_resolution(req, err, errlen) < 0)
		return -1;
	if (effector < 0 || effector >= m->nsite || start_joint < -1 || start_joint >= m->njnt) {
		snprintf(err, errlen, "no such effector site or start joint");
		return -1;
	}
	struct env_oracle o = { .nthreads = thread_count(req->threads),
				.solve = chain_solve,
				.nq = m->ndof,
				.tol = ENVELOPE_TOL };
	struct chain_thr thr[ENVELOPE_THREADS_MAX];
	struct ik_constraint_def d = ik_constraint_default_def();
	d.effector_site = effector;
	d.goal_site = -1;
	d.pos = IK_POINT;
	d.ori = IK_ORI_NONE;
	d.pos_weight = 1;
	d.start_joint = start_joint;
	d.enabled = 1;
	int r = 0, made = 0;
	for (; made < o.nthreads && !r; made++) {
		struct chain_thr *c = &thr[made];
		*c = (struct chain_thr){ .ik = ik_make(m, 1), .copy = state_make(m), .m = m,
					 .s = s, .effector = effector, .opt = ik_default_options() };
		c->opt.step_pos = c->opt.step_ori = 0;
		c->opt.budget_us = 0;
		/* a chain's solve can stop where a limit meets a singular turn (a twist the
		 * wrong way, a tilt at zero): random restarts find the rest of the set, and a
		 * short chain's solve is cheap enough to afford them */
		c->opt.restarts = 8;
		c->opt.restart_after = 20;
		c->opt.settle_rel = 0;
		if (!c->ik || !c->copy) {
			snprintf(err, errlen, "out of memory");
			r = -1;
		} else if (ik_add(c->ik, m, &d) != 0) {
			snprintf(err, errlen, "the chain is not one the solver can move");
			r = -1;
		}
		o.thr[made] = c;
	}
	double centre[3], lo[3], hi[3];
	if (!r) {
		memcpy(centre, start_joint >= 0 ? &s->dof_pivot_w[3 * m->jnt_dof0[start_joint]]
						: s->site_xf[effector].p,
		       sizeof centre);
		r = env_bounds(&o, centre, req->resolution, lo, hi);
	}
	struct mc_mesh mesh;
	struct env_stats st = { { 0, 0, 0 }, 0 };
	if (!r)
		r = env_surface(&o, lo, hi, s->site_xf[effector].p, req->resolution, &mesh, &st,
				err, errlen);
	if (!r)
		mesh_take(dest, &mesh);
	for (int t = 0; t < made; t++) {
		ik_free(thr[t].ik);
		state_free(thr[t].copy);
	}
	if (solves)
		*solves = st.solves;
	return r;
}
