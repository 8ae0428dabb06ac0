/* ik.c - constraint sets and the bounded variable-metric minimiser (Chapter 4) */
#include "pose/ik.h"

#include <stdlib.h>
#include <string.h>

#include "pose/ik_energy.h"
#include "pose/ik_metric.h"
#include "figure/kin.h"

#define SETTLE_ITER 4 /* the window of opt->settle_rel */
#define ARMIJO 1e-4     /* sufficient decrease of the line search */
#define MAX_HALVINGS 12 /* line search trials before the point counts as stationary */
#define MAX_STEP 0.5    /* radians or metres: the largest change of one variable per iteration */

/*
 * One group's variables and what they move, kept until the constraint set
 * or the root changes, so that moving goals rebuilds nothing.
 */
struct ik_chain {
	int valid;
	unsigned gen;  /* ik->gen when built */
	int root_site; /* the root it was built for */
	int nvar, ndyn;
	int *var_dof, *dof_var, *dyn_seg;
	double *lo, *hi;
	unsigned char *moves_eff, *moves_goal, *in_group;
};

struct ik {
	int cap;
	struct ik_terms e; /* the constraints, the springs and the prepared group */
	struct ik_chain chain[IK_MAX_GROUPS];
	unsigned gen;   /* bumped whenever a constraint is added, redefined or switched */
	int rebuilt;    /* chains rebuilt by the current solve */
	int *move_seg;  /* nseg scratch: every segment below a variable */

	/* the prepared group (e holds the rest): pointers into its chain */
	int group;
	int *dof_var;             /* ndof: variable index or -1 */
	unsigned char *seg_mark;  /* nseg scratch */

	/* minimiser workspace, all ndof (or ndof^2) long */
	double *x, *g, *xt, *gt, *d, *sv, *yv, *hy, *best, *H;
	double *B;  /* ndof^2: Gauss-Newton metric */
	double *H2; /* ndof^2: Cholesky factor */
	unsigned char *pin; /* ndof: variable pinned at a bound when the metric was made */
	int *free_idx;      /* ndof */

	/* weights the figure carries: part of the centre of mass its com effectors hold */
	struct point_mass mass[POINT_MASS_MAX];
	int nmass;
};

struct ik_options
ik_default_options(void)
{
	struct ik_options o = { 0 };
	o.step_pos = 0.25;            /* §4.7.1: 25 cm */
	o.step_ori = 5 * M_PI / 180;  /* §4.7.1: 5 degrees */
	o.max_iter = 200;
	o.budget_us = 10000;          /* §4.7.2: a frame's share at 60 Hz; the loop passes its own */
	o.tol_pos = 1e-4;
	o.tol_ori = 1e-3;
	o.settle_rel = 1e-3; /* at that pace 50 more iterations would lower it by about 1 % */
	o.balance_rounds = 8;
	o.balance_tol = 1e-4;
	o.restarts = 0;
	o.restart_after = 50;
	o.restart_groups = ~0u;
	o.seed = 1;
	return o;
}

const char *
ik_status_to_str(enum ik_status st)
{
	switch (st) {
	case IK_CONVERGED:
		return "converged";
	case IK_ITER_LIMIT:
		return "iteration-limit";
	case IK_TIME_LIMIT:
		return "time-limit";
	}
	return "unknown";
}

struct ik *
ik_make(const struct model *m, int max_constraints)
{
	if (max_constraints < 1)
		return NULL;
	struct ik *ik = calloc(1, sizeof *ik);
	if (!ik)
		return NULL;
	size_t nd = (size_t)(m->ndof > 0 ? m->ndof : 1), cap = (size_t)max_constraints;
	ik->cap = max_constraints;
	ik->e.ndof = m->ndof;
	ik->e.con = calloc(cap, sizeof *ik->e.con);
	ik->e.spring_angle = calloc(nd, sizeof(double));
	ik->e.spring_weight = calloc(nd, sizeof(double));
	ik->e.spring_side = calloc(nd, 1);
	int ok = 1;
	for (int g = 0; g < IK_MAX_GROUPS; g++) {
		struct ik_chain *ch = &ik->chain[g];
		ch->var_dof = calloc(nd, sizeof(int));
		ch->dof_var = calloc(nd, sizeof(int));
		ch->lo = calloc(nd, sizeof(double));
		ch->hi = calloc(nd, sizeof(double));
		ch->dyn_seg = calloc((size_t)m->nseg, sizeof(int));
		ch->moves_eff = calloc(cap * nd, 1);
		ch->moves_goal = calloc(cap * nd, 1);
		ch->in_group = calloc(cap, 1);
		ok = ok && ch->var_dof && ch->dof_var && ch->lo && ch->hi && ch->dyn_seg &&
		     ch->moves_eff && ch->moves_goal && ch->in_group;
	}
	ik->move_seg = calloc((size_t)m->nseg, sizeof(int));
	ik->seg_mark = calloc((size_t)m->nseg, 1);
	double **work[] = { &ik->x, &ik->g, &ik->xt, &ik->gt, &ik->d, &ik->sv, &ik->yv, &ik->hy,
			    &ik->best };
	ok = ok && ik->e.con && ik->e.spring_angle && ik->e.spring_weight && ik->e.spring_side &&
	     ik->move_seg && ik->seg_mark;
	for (size_t i = 0; i < sizeof work / sizeof *work; i++) {
		*work[i] = calloc(nd, sizeof(double));
		ok = ok && *work[i];
	}
	ik->H = calloc(nd * nd, sizeof(double));
	ik->B = calloc(nd * nd, sizeof(double));
	ik->e.jr = calloc(nd * IK_RESIDUAL_MAX, sizeof(double));
	ik->pin = calloc(nd, 1);
	ik->free_idx = calloc(nd, sizeof(int));
	ik->H2 = calloc(nd * nd, sizeof(double));
	if (!ok || !ik->H || !ik->B || !ik->e.jr || !ik->pin || !ik->free_idx || !ik->H2) {
		ik_free(ik);
		return NULL;
	}
	return ik;
}

void
ik_free(struct ik *ik)
{
	if (!ik)
		return;
	free(ik->e.con);
	free(ik->e.spring_angle);
	free(ik->e.spring_weight);
	free(ik->e.spring_side);
	for (int g = 0; g < IK_MAX_GROUPS; g++) {
		struct ik_chain *ch = &ik->chain[g];
		free(ch->var_dof);
		free(ch->dof_var);
		free(ch->lo);
		free(ch->hi);
		free(ch->dyn_seg);
		free(ch->moves_eff);
		free(ch->moves_goal);
		free(ch->in_group);
	}
	free(ik->move_seg);
	free(ik->seg_mark);
	free(ik->x);
	free(ik->g);
	free(ik->xt);
	free(ik->gt);
	free(ik->d);
	free(ik->sv);
	free(ik->yv);
	free(ik->hy);
	free(ik->best);
	free(ik->H);
	free(ik->B);
	free(ik->e.jr);
	free(ik->pin);
	free(ik->free_idx);
	free(ik->H2);
	free(ik);
}

int
ik_add(struct ik *ik, const struct model *m, const struct ik_constraint_def *def)
{
	if (ik->e.n >= ik->cap || !ik_constraint_valid(m, def))
		return -1;
	memset(&ik->e.con[ik->e.n], 0, sizeof ik->e.con[ik->e.n]);
	ik->e.con[ik->e.n].def = *def;
	ik->e.con[ik->e.n].goal_pos = ik->e.con[ik->e.n].goal_ori = def->goal_xf;
	ik->gen++;
	return ik->e.n++;
}

int
ik_set(struct ik *ik, const struct model *m, int c, const struct ik_constraint_def *def)
{
	if (c < 0 || c >= ik->e.n || !ik_constraint_valid(m, def))
		return -1;
	ik->e.con[c].def = *def;
	ik->e.con[c].goal_pos = ik->e.con[c].goal_ori = def->goal_xf;
	ik->gen++;
	return 0;
}

const struct ik_constraint_def *
ik_get(const struct ik *ik, int c)
{
	return c >= 0 && c < ik->e.n ? &ik->e.con[c].def : NULL;
}

int
ik_count(const struct ik *ik)
{
	return ik->e.n;
}

void
ik_clear(struct ik *ik)
{
	ik->e.n = 0;
	ik->gen++;
}

int
ik_set_goal(struct ik *ik, int c, const struct xform *goal_xf)
{
	if (c < 0 || c >= ik->e.n || !xform_finite(goal_xf))
		return -1;
	ik->e.con[c].def.goal_xf = *goal_xf;
	ik->e.con[c].goal_pos = ik->e.con[c].goal_ori = *goal_xf;
	return 0;
}

int
ik_enable(struct ik *ik, int c, int on)
{
	if (c < 0 || c >= ik->e.n)
		return -1;
	if (ik->e.con[c].def.enabled != !!on)
		ik->gen++;
	ik->e.con[c].def.enabled = !!on;
	return 0;
}

int
ik_set_spring(struct ik *ik, const struct model *m, int dof, int side, double angle, double weight)
{
	if (dof < 0 || dof >= m->ndof || (side != -1 && side != 1) || !(angle > 0) ||
	    !(weight >= 0) || !isfinite(angle) || !isfinite(weight))
		return -1;
	ik->e.spring_side[dof] = (signed char)side;
	ik->e.spring_angle[dof] = angle;
	ik->e.spring_weight[dof] = weight;
	return 0;
}

/* adds the dofs of the chain from seg up to start_joint (or the root) as variables */
static void
add_chain(struct ik *ik, const struct model *m, const struct state *s, int seg, int start_joint)
{
	for (int t = seg; s->seg_root_joint[t] >= 0; t = s->seg_parent[t]) {
		int j = s->seg_root_joint[t];
		for (int d = m->jnt_dof0[j]; d < m->jnt_dof0[j] + m->jnt_ndof[j]; d++) {
			if (ik->dof_var[d] >= 0 || m->dof_lo[d] == m->dof_hi[d])
				continue;
			ik->dof_var[d] = ik->e.nvar;
			ik->e.var_dof[ik->e.nvar] = d;
			ik->e.lo[ik->e.nvar] = m->dof_lo[d];
			ik->e.hi[ik->e.nvar] = m->dof_hi[d];
			ik->e.nvar++;
		}
		if (j == start_joint)
			return;
	}
}

/* marks seg and its ancestors */
static void
mark_path(struct ik *ik, const struct state *s, int seg)
{
	for (int t = seg; t >= 0 && !ik->seg_mark[t]; t = s->seg_parent[t])
		ik->seg_mark[t] = 1;
}

int
ik_prepare(struct ik *ik, const struct model *m, struct state *s, int group)
{
	if (group < 0 || group >= IK_MAX_GROUPS)
		return 0;
	struct ik_chain *ch = &ik->chain[group];
	ik->group = group;
	ik->e.var_dof = ch->var_dof;
	ik->dof_var = ch->dof_var;
	ik->e.lo = ch->lo;
	ik->e.hi = ch->hi;
	ik->e.dyn_seg = ch->dyn_seg;
	ik->e.moves_eff = ch->moves_eff;
	ik->e.moves_goal = ch->moves_goal;
	ik->e.in_group = ch->in_group;
	if (ch->valid && ch->gen == ik->gen && ch->root_site == s->root_site) {
		ik->e.nvar = ch->nvar;
		ik->e.ndyn = ch->ndyn;
		return ik->e.nvar;
	}
	ik->rebuilt++;
	ik->e.nvar = 0;
	for (int d = 0; d < m->ndof; d++)
		ik->dof_var[d] = -1;
	for (int ci = 0; ci < ik->e.n; ci++) {
		const struct ik_constraint_def *d = &ik->e.con[ci].def;
		ik->e.in_group[ci] = d->enabled && d->group == group && d->weight > 0;
		if (ik->e.in_group[ci])
			add_chain(ik, m, s, m->site_seg[d->effector_site], d->start_joint);
	}
	/* the segments to recompute: on a path to an effector or goal, below a variable */
	memset(ik->seg_mark, 0, (size_t)m->nseg);
	for (int ci = 0; ci < ik->e.n; ci++) {
		if (!ik->e.in_group[ci])
			continue;
		const struct ik_constraint_def *d = &ik->e.con[ci].def;
		mark_path(ik, s, m->site_seg[d->effector_site]);
		if (d->goal_site >= 0)
			mark_path(ik, s, m->site_seg[d->goal_site]);
	}
	ik->e.ndyn = 0;
	for (int i = 0; i < m->nseg; i++) {
		int seg = s->seg_order[i], moving = 0;
		for (int t = seg; s->seg_root_joint[t] >= 0 && !moving; t = s->seg_parent[t]) {
			int j = s->seg_root_joint[t];
			for (int d = m->jnt_dof0[j]; d < m->jnt_dof0[j] + m->jnt_ndof[j]; d++)
				moving |= ik->dof_var[d] >= 0;
		}
		if (moving && ik->seg_mark[seg])
			ik->e.dyn_seg[ik->e.ndyn++] = seg;
	}
	/* which variables move each effector and goal */
	for (int ci = 0; ci < ik->e.n; ci++) {
		if (!ik->e.in_group[ci])
			continue;
		const struct ik_constraint_def *d = &ik->e.con[ci].def;
		unsigned char *me = &ik->e.moves_eff[ci * ik->e.ndof], *mg = &ik->e.moves_goal[ci * ik->e.ndof];
		for (int v = 0; v < ik->e.nvar; v++) {
			me[v] = (unsigned char)kin_dof_moves(m, s, ik->e.var_dof[v],
							     m->site_seg[d->effector_site]);
			mg[v] = d->goal_site >= 0 &&
				kin_dof_moves(m, s, ik->e.var_dof[v], m->site_seg[d->goal_site]);
		}
	}
	ch->valid = 1;
	ch->gen = ik->gen;
	ch->root_site = s->root_site;
	ch->nvar = ik->e.nvar;
	ch->ndyn = ik->e.ndyn;
	return ik->e.nvar;
}

double
ik_energy(struct ik *ik, const struct model *m, struct state *s, const double *x, double *grad)
{
	return ik_energy_eval(&ik->e, m, s, x, grad, NULL);
}

int
ik_var_dof(const struct ik *ik, int i)
{
	return i >= 0 && i < ik->e.nvar ? ik->e.var_dof[i] : -1;
}

static void
clamp_into(const struct ik *ik, double *x)
{
	for (int i = 0; i < ik->e.nvar; i++)
		x[i] = x[i] < ik->e.lo[i] ? ik->e.lo[i] : x[i] > ik->e.hi[i] ? ik->e.hi[i] : x[i];
}

/* variable i rests on a bound that the gradient pushes it against */
static int
pinned(const struct ik *ik, const double *x, const double *g, int i)
{
	return (x[i] <= ik->e.lo[i] && g[i] > 0) || (x[i] >= ik->e.hi[i] && g[i] < 0);
}

static uint64_t
clock_now(const struct ik_clock *clock)
{
	return clock ? clock->now_us(clock->ctx) : 0;
}

/* xorshift32 for restarts: reproducible from opt->seed */
static double
uniform(uint32_t *st)
{
	uint32_t x = *st ? *st : 0x9e3779b9u;
	x ^= x << 13;
	x ^= x >> 17;
	x ^= x << 5;
	*st = x;
	return (x >> 8) * (1.0 / 16777216.0);
}

struct group_run {
	const struct ik_options *opt;
	const struct ik_clock *clock;
	uint64_t deadline; /* 0: none */
	struct ik_result *res;
	uint32_t rng;
};

/*
 * The one place a solve looks at time, before each iteration: live, the
 * clock against the deadline; in replay, the recorded count of iterations
 * at the cut (ik_work.h), with no clock read.
 */
static int
out_of_time(const struct group_run *run)
{
	const struct ik_work *replay = run->opt->replay;
	if (replay)
		return replay->cut && run->res->iterations == replay->iterations;
	return run->deadline && clock_now(run->clock) >= run->deadline;
}

static void
trace(struct group_run *run, double f)
{
	if (run->opt->trace && run->res->trace_len < run->opt->trace_cap)
		run->opt->trace[run->res->trace_len++] = f;
}

/* energy, gradient and a fresh Gauss-Newton metric at x */
static double
refresh_metric(struct ik *ik, const struct model *m, struct state *s, const double *x, double *g,
	       struct ik_result *res)
{
	double f = ik_energy_eval(&ik->e, m, s, x, g, ik->B);
	res->evaluations++;
	for (int i = 0; i < ik->e.nvar; i++)
		ik->pin[i] = (unsigned char)pinned(ik, x, g, i);
	if (ik_metric_invert(ik->e.nvar, ik->B, ik->pin, ik->H2, ik->free_idx, ik->H) < 0)
		ik_metric_reset(ik->e.nvar, 1, ik->H);
	return f;
}

/*
 * Minimises the prepared group's energy from the state's posture. Returns
 * 1 when the deadline cut it. The state is left at the best point.
 */
static int
minimise(struct ik *ik, const struct model *m, struct state *s, struct group_run *run,
	 double *f_first, double *f_last)
{
	const struct ik_options *opt = run->opt;
	int n = ik->e.nvar, timed_out = 0, met = 0, since_start = 0;
	int restarts_left = ik->group < 32 && (opt->restart_groups >> ik->group & 1) ? opt->restarts : 0;
	int fresh = 1; /* 1: the metric is fresh, 2: and steepest descent was tried */
	double *x = ik->x, *g = ik->g, *xt = ik->xt, *gt = ik->gt, *d = ik->d;
	for (int i = 0; i < n; i++)
		x[i] = s->q[ik->e.var_dof[i]];
	clamp_into(ik, x);
	double f = refresh_metric(ik, m, s, x, g, run->res), best_f = f;
	*f_first = f;
	trace(run, f);
	memcpy(ik->best, x, sizeof *x * (size_t)n);
	double recent[8]; /* the energy over the last iterations of this start */
	for (;;) {
		if ((met = ik_energy_met(&ik->e, opt->tol_pos, opt->tol_ori)))
			break;
		if (since_start >= opt->max_iter) {
			run->res->status = IK_ITER_LIMIT;
			break;
		}
		if (out_of_time(run)) {
			timed_out = 1;
			break;
		}
		run->res->iterations++;
		/* a start that has stopped making headway gives way to the next one
		 * (counted whether or not restarts are allowed: max_iter bounds it) */
		double f_8ago = since_start >= 8 ? recent[since_start % 8] : INFINITY;
		recent[since_start % 8] = f;
		since_start++;
		run->res->work.start_iterations = since_start;
		if (restarts_left > 0 && since_start > opt->restart_after && f > 0.5 * f_8ago)
			goto stationary;
		/* a goal out of reach: the energy has settled near its floor, and
		 * grinding on only polishes digits nobody sees (the next frame
		 * starts from here anyway); with restarts left, the rule above
		 * decides when to look elsewhere */
		double f_then = since_start > SETTLE_ITER ? recent[(since_start - 1 - SETTLE_ITER) % 8]
							  : INFINITY;
		if (restarts_left <= 0 && opt->settle_rel > 0 && f >= (1 - opt->settle_rel) * f_then)
			goto stationary;
		/* a variable came off or onto a bound: the metric is stale */
		int changed = 0;
		for (int i = 0; i < n && !changed; i++)
			changed = pinned(ik, x, g, i) != ik->pin[i];
		if (changed)
			refresh_metric(ik, m, s, x, g, run->res);
		/* quasi-Newton direction over the free variables */
		double gd = 0, gnorm = 0;
		for (int i = 0; i < n; i++) {
			d[i] = 0;
			if (ik->pin[i])
				continue;
			for (int j = 0; j < n; j++)
				d[i] -= ik->H[i * n + j] * g[j];
			gd += g[i] * d[i];
			gnorm += g[i] * g[i];
		}
		if (gnorm < 1e-30)
			goto stationary;
		if (gd >= -1e-12 * gnorm) { /* not a descent direction: steepest descent */
			gd = 0;
			for (int i = 0; i < n; i++) {
				d[i] = ik->pin[i] ? 0 : -g[i];
				gd -= g[i] * g[i];
			}
		}
		double dmax = 0;
		for (int i = 0; i < n; i++)
			dmax = fmax(dmax, fabs(d[i]));
		double alpha = dmax > MAX_STEP ? MAX_STEP / dmax : 1, ft = f;
		int accepted = 0;
		/* projected backtracking line search: accept only a sufficient
		 * decrease; shorten by the minimiser of the quadratic through
		 * f, the slope and the rejected value, kept within [0.1, 0.5] */
		for (int h = 0; h < MAX_HALVINGS; h++) {
			double decrease = 0;
			for (int i = 0; i < n; i++) {
				xt[i] = x[i] + alpha * d[i];
				xt[i] = xt[i] < ik->e.lo[i] ? ik->e.lo[i] : xt[i] > ik->e.hi[i] ? ik->e.hi[i] : xt[i];
				decrease += g[i] * (xt[i] - x[i]);
			}
			ft = ik_energy_eval(&ik->e, m, s, xt, gt, NULL);
			run->res->evaluations++;
			if (ft < f && ft <= f + ARMIJO * decrease) {
				accepted = 1;
				break;
			}
			double slope = decrease / alpha, curve = ft - f - decrease;
			double shrink = curve > 0 ? -slope * alpha / (2 * curve) : 0.5;
			alpha *= shrink < 0.1 ? 0.1 : shrink > 0.5 ? 0.5 : shrink;
		}
		if (!accepted) {
			/* the failed trials moved the state; a stale metric may be to
			 * blame, so try again from a fresh one, then from steepest
			 * descent, before calling the point stationary */
			if (fresh < 2) {
				fresh++;
				f = refresh_metric(ik, m, s, x, g, run->res);
				if (fresh == 2)
					ik_metric_reset(ik->e.nvar, 1e-3, ik->H);
				continue;
			}
			ik_energy_eval(&ik->e, m, s, x, NULL, NULL);
			goto stationary;
		}
		fresh = 0;
		double sy = 0, yy = 0;
		for (int i = 0; i < n; i++) {
			ik->sv[i] = xt[i] - x[i];
			ik->yv[i] = ik->pin[i] ? 0 : gt[i] - g[i];
			sy += ik->sv[i] * ik->yv[i];
			yy += ik->yv[i] * ik->yv[i];
		}
		if (sy > 1e-12 * sqrt(yy) * sqrt(yy > 0 ? yy : 1) && sy > 0)
			ik_metric_bfgs(ik->e.nvar, ik->sv, ik->yv, sy, ik->hy, ik->H);
		memcpy(x, xt, sizeof *x * (size_t)n);
		memcpy(g, gt, sizeof *g * (size_t)n);
		f = ft;
		trace(run, f);
		continue;
	stationary:
		/* a local minimum that misses a goal: start again elsewhere if allowed */
		if (f < best_f) {
			best_f = f;
			memcpy(ik->best, x, sizeof *x * (size_t)n);
		}
		if (restarts_left-- <= 0)
			break;
		run->res->restarts++;
		run->res->work.start++;
		run->res->work.start_iterations = 0;
		since_start = 0;
		fresh = 1;
		for (int i = 0; i < n; i++)
			x[i] = ik->e.lo[i] + (ik->e.hi[i] - ik->e.lo[i]) * uniform(&run->rng);
		f = refresh_metric(ik, m, s, x, g, run->res);
	}
	/* leave the best posture found in the state */
	if (!met && best_f < f) {
		memcpy(x, ik->best, sizeof *x * (size_t)n);
		f = ik_energy_eval(&ik->e, m, s, x, NULL, NULL);
	}
	*f_last = f;
	return timed_out;
}

/* every segment below a variable of the prepared group, top-down, into dest */
static int
moving_segments(const struct ik *ik, const struct model *m, const struct state *s, int *dest)
{
	int n = 0;
	memset(ik->seg_mark, 0, (size_t)m->nseg);
	for (int i = 0; i < m->nseg; i++) {
		int seg = s->seg_order[i], j = s->seg_root_joint[seg], moving = 0;
		if (j >= 0) {
			for (int d = m->jnt_dof0[j]; d < m->jnt_dof0[j] + m->jnt_ndof[j]; d++)
				moving |= ik->dof_var[d] >= 0;
			moving |= ik->seg_mark[s->seg_parent[seg]];
		}
		if (moving) {
			ik->seg_mark[seg] = 1;
			dest[n++] = seg;
		}
	}
	return n;
}

int
ik_set_point_masses(struct ik *ik, const struct model *m, const struct point_mass *pm, int n)
{
	if (point_mass_check(m, pm, n) < 0)
		return -1;
	if (n > 0)
		memcpy(ik->mass, pm, sizeof *pm * (size_t)n);
	ik->nmass = n;
	return 0;
}

int
ik_point_masses(const struct ik *ik, const struct point_mass **pm)
{
	*pm = ik->mass;
	return ik->nmass;
}

void
ik_com(const struct ik *ik, const struct state *s, double dest[3])
{
	point_mass_com(s, ik->mass, ik->nmass, dest);
}

/*
 * The centre of mass, with the weights carried, rides on its site during a
 * round (§4.5.2): the round's energy and its derivatives move it rigidly
 * with the site, and the next round measures it again. A weight joins it as
 * any segment's mass does.
 */
static void
attach_com(struct ik *ik, const struct state *s)
{
	double com[3];
	ik_com(ik, s, com);
	for (int ci = 0; ci < ik->e.n; ci++) {
		struct ik_con *c = &ik->e.con[ci];
		if (!c->def.com_effector)
			continue;
		struct xform inv;
		xform_inv(&s->site_xf[c->def.effector_site], &inv);
		xform_apply(&inv, com, c->com_local);
	}
}

/* the work's place moves to a group's first start */
static void
work_begin_group(struct ik_work *w, int round, int group)
{
	w->round = round;
	w->group = group;
	w->start = 0;
	w->start_iterations = 0;
}

struct ik_result
ik_solve(struct ik *ik, const struct model *m, struct state *s, const struct ik_options *opt,
	 const struct ik_clock *clock)
{
	struct ik_result res = { 0 };
	struct group_run run = { opt, clock, 0, &res, opt->seed };
	ik->rebuilt = 0;
	res.status = IK_CONVERGED;
	res.work = ik_work_none();
	if (opt->budget_us && clock && !opt->replay)
		run.deadline = clock_now(clock) + opt->budget_us;
	int max_group = 0, has_com = 0;
	for (int ci = 0; ci < ik->e.n; ci++) {
		const struct ik_constraint_def *d = &ik->e.con[ci].def;
		if (!d->enabled)
			continue;
		max_group = d->group > max_group ? d->group : max_group;
		has_com |= d->com_effector;
	}
	res.stepped = ik_energy_step_factor(&ik->e, m, s, opt->step_pos, opt->step_ori);
	double com_prev[3], com_now[3];
	ik_com(ik, s, com_prev);
	int rounds = has_com ? opt->balance_rounds : 1, first = 1;
	for (int r = 0; r < rounds; r++) {
		res.balance_rounds = r + 1;
		attach_com(ik, s);
		int timed_out = 0;
		res.f_end = 0;
		res.active_limits = 0;
		/* groups in order: the body first, the hands after it (§D.1.5) */
		for (int gidx = 0; gidx <= max_group && !timed_out; gidx++) {
			if (ik_prepare(ik, m, s, gidx) == 0)
				continue;
			double f0, f1;
			work_begin_group(&res.work, r, gidx);
			timed_out = minimise(ik, m, s, &run, &f0, &f1);
			if (first)
				res.f_start += f0;
			res.f_end += f1;
			for (int i = 0; i < ik->e.nvar; i++)
				res.active_limits += ik->x[i] <= ik->e.lo[i] || ik->x[i] >= ik->e.hi[i];
			/* bring the rest of the figure below the moved joints along */
			kin_forward_segments(m, s, ik->move_seg, moving_segments(ik, m, s, ik->move_seg));
		}
		first = 0;
		kin_com(m, s);
		if (timed_out) {
			res.status = IK_TIME_LIMIT;
			res.work.cut = 1;
			break;
		}
		double moved = 0;
		ik_com(ik, s, com_now);
		for (int i = 0; i < 3; i++)
			moved += (com_now[i] - com_prev[i]) * (com_now[i] - com_prev[i]);
		memcpy(com_prev, com_now, sizeof com_prev);
		if (sqrt(moved) < opt->balance_tol)
			break;
	}
	res.chains_rebuilt = ik->rebuilt;
	res.work.iterations = res.iterations;
	/* met: every enabled constraint within tolerance of this solve's goals */
	attach_com(ik, s);
	res.met = 1;
	for (int ci = 0; ci < ik->e.n; ci++) {
		struct ik_con *c = &ik->e.con[ci];
		const struct ik_constraint_def *d = &c->def;
		if (!d->enabled || d->weight <= 0)
			continue;
		struct xform E, Gp, Go;
		ik_con_frames(c, m, s, &E, &Gp, &Go);
		ik_con_errors(c, &E, &Gp, &Go);
		if ((d->pos != IK_POS_NONE && d->pos_weight > 0 && c->pos_err > opt->tol_pos) ||
		    (d->ori != IK_ORI_NONE && d->pos_weight < 1 && c->ori_err > opt->tol_ori))
			res.met = 0;
	}
	return res;
}

void
ik_constraint_error(const struct ik *ik, const struct model *m, const struct state *s, int c,
		    double *pos_err, double *ori_err)
{
	*pos_err = *ori_err = 0;
	if (c < 0 || c >= ik->e.n)
		return;
	/* measured against the true goal, not this solve's intermediate one */
	struct ik_con tmp = ik->e.con[c];
	tmp.goal_pos = tmp.goal_ori = tmp.def.goal_xf;
	if (tmp.def.com_effector) {
		double com[3];
		struct xform inv;
		ik_com(ik, s, com);
		xform_inv(&s->site_xf[tmp.def.effector_site], &inv);
		xform_apply(&inv, com, tmp.com_local);
	}
	struct xform E, Gp, Go;
	ik_con_frames(&tmp, m, s, &E, &Gp, &Go);
	ik_con_errors(&tmp, &E, &Gp, &Go);
	*pos_err = tmp.pos_err;
	*ori_err = tmp.ori_err;
}

int
ik_active_limits(const struct ik *ik, const struct model *m, const struct state *s, int *dest,
		 int max)
{
	int n = 0;
	for (int d = 0; d < m->ndof && n < max; d++) {
		if (s->q[d] > m->dof_lo[d] && s->q[d] < m->dof_hi[d])
			continue;
		/* only the variables of chains as they stand now */
		int var = 0;
		for (int g = 0; g < IK_MAX_GROUPS && !var; g++) {
			const struct ik_chain *ch = &ik->chain[g];
			var = ch->valid && ch->gen == ik->gen && ch->root_site == s->root_site &&
			      ch->dof_var[d] >= 0 && ch->dof_var[d] < ch->nvar &&
			      ch->var_dof[ch->dof_var[d]] == d;
		}
		if (var)
			dest[n++] = d;
	}
	return n;
}
