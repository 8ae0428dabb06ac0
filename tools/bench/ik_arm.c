/*
 * ik_arm - the arm inverse-kinematics benchmark: ours beside
 * NLopt's LD_LBFGS and LD_SLSQP on exactly our objective and bounds.
 *
 * usage: ik_arm TARGETS_OUT [N]
 *
 * The right arm of the standard human (joints clavicle_r, shoulder_r,
 * elbow_r, wrist_r: 9 dofs) reaches for N (default 1000) 6-D targets: the
 * frame of site hand_r.palm after forward kinematics of postures drawn with
 * srand(1), each arm dof uniform within its limits, every other dof 0. The
 * targets go to TARGETS_OUT (format below) so that the peers of
 * ik_arm_bench.py solve the same problems.
 *
 * Each solve starts from the neutral posture (state_reset: all dofs 0).
 * - ours: ik_solve with one constraint (IK_POINT + IK_FRAME, pos_weight
 *   0.5, start joint clavicle_r), no step factor, tolerances 0.1 mm and
 *   1e-3 rad, up to 30 random restarts, a 2 ms budget on a real
 *   monotonic clock, ik_default_options' iteration limit (per start).
 *   Only ik_solve is timed.
 * - NLopt: the same energy and gradient (ik_prepare + ik_energy) and the
 *   dofs' limits as bounds, from neutral, no restarts; stops at energy
 *   5e-9 (which implies our tolerances), ftol_abs 1e-15, xtol_abs 1e-12,
 *   1000 evaluations or 2 ms (NLopt's own clock). ik_prepare +
 *   nlopt_optimize are timed.
 *
 * A solve succeeds when, recomputed by forward kinematics on a separate
 * state, the palm is within 1 mm and 1 degree of the target and every arm
 * dof is within its limits. Prints one "BENCH ik.arm6d.<solver> ..." line
 * per solver: success (%), median_us and p95_us over all solves (p95 by
 * nearest rank), mean iterations (ours only: NLopt reports evaluations),
 * evaluations and restarts, and limit_violations (solves that reached the
 * target only outside the limits), and why the solves stopped.
 *
 * TARGETS_OUT: '#' comment lines, then one line per target of 34 numbers:
 * the 9 arm dof values that made it, the 9 start values (zeros), and the
 * 4x4 target frame row by row (world coordinates, metres). The dof order
 * is clavicle_r 0 1, shoulder_r 0 1 2, elbow_r 0, wrist_r 0 1 2, i.e. the
 * URDF joints clavicle_r__0 ... wrist_r__2.
 */
#include <math.h>
#include <nlopt.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_util.h"
#include "figure/human.h"
#include "pose/ik.h"
#include "figure/kin.h"

#define NARM 9
#define MAX_TARGETS 100000
#define WARMUP 50
#define BUDGET_US 2000
#define RESTARTS 30
#define SUCCESS_POS 1e-3                /* metres */
#define SUCCESS_ORI (M_PI / 180)        /* radians */
/* energy 0.5 |dp|^2 + orientation term <= 5e-9 = 0.5 (0.1 mm)^2: both our tolerances are met */
#define NLOPT_STOPVAL 5e-9

static const char *const arm_joints[] = { "clavicle_r", "shoulder_r", "elbow_r", "wrist_r" };

struct target {
	double q[NARM];
	struct xform xf;
};

/* one solver's tallies */
struct tally {
	const char *name;
	int n;
	double *us;
	int success, reached, limit_violations;
	double iters, evals, restarts;
	int has_iters; /* NLopt reports evaluations, not iterations */
	int status[8]; /* solver-specific stop reasons */
};

struct arm {
	struct model *m;
	struct state *s, *check;
	int palm, clavicle;
	int dof[NARM];
};




/* builds the human and finds the arm; 0 or -1 */
static int
arm_make(struct arm *a)
{
	char err[256];
	struct human_def def = human_default_def(HUMAN_MALE);
	a->m = human_build(&def, err, sizeof err);
	if (!a->m) {
		fprintf(stderr, "ik_arm: %s\n", err);
		return -1;
	}
	a->s = state_make(a->m);
	kin_update(a->m, a->s);
	a->check = state_make(a->m);
	kin_update(a->m, a->check);
	a->palm = model_find_site(a->m, "hand_r.palm");
	a->clavicle = model_find_joint(a->m, "clavicle_r");
	if (!a->s || !a->check || a->palm < 0 || a->clavicle < 0) {
		fprintf(stderr, "ik_arm: no state, hand_r.palm or clavicle_r\n");
		return -1;
	}
	int n = 0;
	for (size_t i = 0; i < sizeof arm_joints / sizeof *arm_joints; i++) {
		int j = model_find_joint(a->m, arm_joints[i]);
		if (j < 0) {
			fprintf(stderr, "ik_arm: no joint %s\n", arm_joints[i]);
			return -1;
		}
		for (int d = a->m->jnt_dof0[j]; d < a->m->jnt_dof0[j] + a->m->jnt_ndof[j]; d++)
			if (n < NARM)
				a->dof[n++] = d;
			else
				n++;
	}
	if (n != NARM) {
		fprintf(stderr, "ik_arm: the arm has %d dofs, not %d\n", n, NARM);
		return -1;
	}
	return 0;
}

static void
make_targets(struct arm *a, struct target *t, int n)
{
	const struct model *m = a->m;
	srand(1);
	for (int i = 0; i < n; i++) {
		state_reset(m, a->check);
		kin_update(m, a->check);
		for (int k = 0; k < NARM; k++) {
			int d = a->dof[k];
			t[i].q[k] = m->dof_lo[d] + (m->dof_hi[d] - m->dof_lo[d]) * rand() / RAND_MAX;
			a->check->q[d] = t[i].q[k];
		}
		kin_update(m, a->check);
		t[i].xf = a->check->site_xf[a->palm];
	}
}

static int
write_targets(const struct arm *a, const struct target *t, int n, const char *path)
{
	FILE *f = fopen(path, "w");
	if (!f) {
		perror(path);
		return -1;
	}
	fprintf(f, "# ik_arm targets: %d, srand(1), site hand_r.palm, human male 1.75 m 75 kg\n", n);
	fprintf(f, "# per line: 9 posture values, 9 start values, 4x4 target row-major; dofs:");
	for (int k = 0; k < NARM; k++) {
		int d = a->dof[k], j = a->m->dof_jnt[d];
		fprintf(f, " %s__%d", a->m->jnt_name[j], d - a->m->jnt_dof0[j]);
	}
	fputc('\n', f);
	for (int i = 0; i < n; i++) {
		for (int k = 0; k < NARM; k++)
			fprintf(f, "%.17g ", t[i].q[k]);
		for (int k = 0; k < NARM; k++)
			fprintf(f, "0 ");
		const struct xform *x = &t[i].xf;
		for (int r = 0; r < 3; r++)
			fprintf(f, "%.17g %.17g %.17g %.17g ", x->r[3 * r], x->r[3 * r + 1],
				x->r[3 * r + 2], x->p[r]);
		fprintf(f, "0 0 0 1\n");
	}
	if (fclose(f) != 0) {
		perror(path);
		return -1;
	}
	return 0;
}

/*
 * The independent success test: forward kinematics of the arm values q
 * (arm order) on the check state. Adds the solve to the tally.
 */
static void
tally_solve(struct arm *a, struct tally *t, const double q[NARM], const struct target *tg,
	    double us, double iters, double evals, double restarts)
{
	const struct model *m = a->m;
	state_reset(m, a->check);
	kin_update(m, a->check);
	int inside = 1;
	for (int k = 0; k < NARM; k++) {
		int d = a->dof[k];
		a->check->q[d] = q[k];
		inside &= q[k] >= m->dof_lo[d] && q[k] <= m->dof_hi[d];
	}
	kin_forward(m, a->check);
	const struct xform *e = &a->check->site_xf[a->palm];
	double dp[3] = { e->p[0] - tg->xf.p[0], e->p[1] - tg->xf.p[1], e->p[2] - tg->xf.p[2] };
	double pos = sqrt(mathx_dot(dp, dp)), ang = mathx_rot_angle_between(e->r, tg->xf.r);
	int reached = pos < SUCCESS_POS && ang < SUCCESS_ORI;
	t->us[t->n++] = us;
	t->reached += reached;
	t->success += reached && inside;
	t->limit_violations += reached && !inside;
	t->iters += iters;
	t->evals += evals;
	t->restarts += restarts;
}

static void
tally_print(struct tally *t, const char *extra)
{
	qsort(t->us, (size_t)t->n, sizeof *t->us, bench_cmp_double);
	double median = t->n % 2 ? t->us[t->n / 2] : (t->us[t->n / 2 - 1] + t->us[t->n / 2]) / 2;
	int p95 = (int)ceil(0.95 * t->n) - 1;
	char iters[32] = "";
	if (t->has_iters)
		snprintf(iters, sizeof iters, " iters=%.1f", t->iters / t->n);
	printf("BENCH ik.arm6d.%s n=%d success=%.1f median_us=%.1f p95_us=%.1f%s evals=%.1f "
	       "restarts=%.2f limit_violations=%d reached=%.1f%s\n",
	       t->name, t->n, 100.0 * t->success / t->n, median, t->us[p95], iters,
	       t->evals / t->n, t->restarts / t->n, t->limit_violations, 100.0 * t->reached / t->n,
	       extra);
}

/* ---- ours ---------------------------------------------------------------- */

static struct ik_constraint_def
arm_constraint(const struct arm *a)
{
	struct ik_constraint_def d = ik_constraint_default_def();
	d.effector_site = a->palm;
	d.pos = IK_POINT;
	d.ori = IK_FRAME;
	d.pos_weight = 0.5;
	d.weight = 1;
	d.start_joint = a->clavicle;
	return d;
}

static int
bench_ours(struct arm *a, const struct target *tg, int n, int max_iter, struct tally *t)
{
	const struct model *m = a->m;
	struct ik *ik = ik_make(m, 1);
	struct ik_constraint_def def = arm_constraint(a);
	if (!ik || ik_add(ik, m, &def) != 0) {
		fprintf(stderr, "ik_arm: ik_make or ik_add failed\n");
		ik_free(ik);
		return -1;
	}
	struct ik_options opt = ik_default_options();
	opt.step_pos = opt.step_ori = 0;
	opt.restarts = RESTARTS;
	opt.budget_us = BUDGET_US;
	if (max_iter > 0)
		opt.max_iter = max_iter;
	opt.tol_pos = 1e-4;
	opt.tol_ori = 1e-3;
	struct ik_clock clock = { bench_clock_us, NULL };
	int met_but_failed = 0, not_met_but_ok = 0, moved_other = 0;
	/* the first WARMUP solves (of the first targets) warm the caches and are not counted */
	for (int i = 0; i < n + WARMUP; i++) {
		const struct target *g = &tg[i < WARMUP ? i % n : i - WARMUP];
		state_reset(m, a->s);
		kin_update(m, a->s);
		ik_set_goal(ik, 0, &g->xf);
		double t0 = bench_now_us();
		struct ik_result r = ik_solve(ik, m, a->s, &opt, &clock);
		double us = bench_now_us() - t0;
		if (i < WARMUP)
			continue;
		double q[NARM];
		for (int k = 0; k < NARM; k++) {
			q[k] = a->s->q[a->dof[k]];
			a->s->q[a->dof[k]] = 0;
		}
		/* only the arm may move */
		int other = 0;
		for (int d = 0; d < m->ndof; d++)
			other |= a->s->q[d] != 0;
		moved_other += other;
		int ok0 = t->success;
		tally_solve(a, t, q, g, us, r.iterations, r.evaluations, r.restarts);
		int ok = t->success > ok0;
		met_but_failed += r.met && !ok;
		not_met_but_ok += !r.met && ok;
		t->status[r.status]++;
	}
	char extra[160];
	snprintf(extra, sizeof extra, " converged=%d iteration_limit=%d time_limit=%d",
		 t->status[IK_CONVERGED], t->status[IK_ITER_LIMIT], t->status[IK_TIME_LIMIT]);
	tally_print(t, extra);
	printf("ik_arm: %s: max_iter %d, restart_after %d, restarts <= %d, budget %d us; "
	       "met by the solver but failed the test: %d; not met but passed: %d; "
	       "moved a dof outside the arm: %d\n",
	       t->name, opt.max_iter, opt.restart_after, RESTARTS, BUDGET_US, met_but_failed,
	       not_met_but_ok, moved_other);
	ik_free(ik);
	return 0;
}

/* ---- NLopt on our objective ---------------------------------------------- */

struct nl_ctx {
	struct ik *ik;
	const struct model *m;
	struct state *s;
	int evals;
};

static double
nl_energy(unsigned n, const double *x, double *grad, void *data)
{
	struct nl_ctx *c = data;
	(void)n;
	c->evals++;
	return ik_energy(c->ik, c->m, c->s, x, grad);
}

static int
bench_nlopt(struct arm *a, const struct target *tg, int n, nlopt_algorithm alg, struct tally *t)
{
	const struct model *m = a->m;
	struct ik *ik = ik_make(m, 1);
	struct ik_constraint_def def = arm_constraint(a);
	if (!ik || ik_add(ik, m, &def) != 0) {
		fprintf(stderr, "ik_arm: ik_make or ik_add failed\n");
		ik_free(ik);
		return -1;
	}
	state_reset(m, a->s);
	kin_update(m, a->s);
	int nv = ik_prepare(ik, m, a->s, 0);
	int var_arm[NARM];
	for (int i = 0; i < nv && nv == NARM; i++) {
		var_arm[i] = -1;
		for (int k = 0; k < NARM; k++)
			if (a->dof[k] == ik_var_dof(ik, i))
				var_arm[i] = k;
		if (var_arm[i] < 0)
			nv = -1;
	}
	if (nv != NARM) {
		fprintf(stderr, "ik_arm: ik_prepare gave %d variables, not the 9 arm dofs\n", nv);
		ik_free(ik);
		return -1;
	}
	nlopt_opt o = nlopt_create(alg, NARM);
	double lo[NARM], hi[NARM], x[NARM], q[NARM];
	for (int i = 0; i < NARM; i++) {
		lo[i] = m->dof_lo[ik_var_dof(ik, i)];
		hi[i] = m->dof_hi[ik_var_dof(ik, i)];
	}
	struct nl_ctx ctx = { ik, m, a->s, 0 };
	nlopt_set_lower_bounds(o, lo);
	nlopt_set_upper_bounds(o, hi);
	nlopt_set_min_objective(o, nl_energy, &ctx);
	nlopt_set_stopval(o, NLOPT_STOPVAL);
	nlopt_set_ftol_abs(o, 1e-15);
	nlopt_set_xtol_abs1(o, 1e-12);
	nlopt_set_maxeval(o, 1000);
	nlopt_set_maxtime(o, BUDGET_US * 1e-6);
	int codes[8] = { 0 }; /* stopval ftol xtol maxeval maxtime other-success failure */
	for (int i = 0; i < n + WARMUP; i++) {
		const struct target *g = &tg[i < WARMUP ? i % n : i - WARMUP];
		state_reset(m, a->s);
		kin_update(m, a->s);
		ik_set_goal(ik, 0, &g->xf);
		ctx.evals = 0;
		double f = 0, t0 = bench_now_us();
		ik_prepare(ik, m, a->s, 0);
		for (int k = 0; k < NARM; k++)
			x[k] = a->s->q[ik_var_dof(ik, k)];
		nlopt_result res = nlopt_optimize(o, x, &f);
		double us = bench_now_us() - t0;
		if (i < WARMUP)
			continue;
		for (int k = 0; k < NARM; k++)
			q[var_arm[k]] = x[k];
		tally_solve(a, t, q, g, us, 0, ctx.evals, 0);
		switch (res) {
		case NLOPT_STOPVAL_REACHED: codes[0]++; break;
		case NLOPT_FTOL_REACHED: codes[1]++; break;
		case NLOPT_XTOL_REACHED: codes[2]++; break;
		case NLOPT_MAXEVAL_REACHED: codes[3]++; break;
		case NLOPT_MAXTIME_REACHED: codes[4]++; break;
		case NLOPT_SUCCESS: codes[5]++; break;
		case NLOPT_FAILURE: case NLOPT_INVALID_ARGS: case NLOPT_OUT_OF_MEMORY:
		case NLOPT_ROUNDOFF_LIMITED: case NLOPT_FORCED_STOP:
		default: codes[6]++; break;
		}
	}
	char extra[200];
	snprintf(extra, sizeof extra,
		 " stopval=%d ftol=%d xtol=%d maxeval=%d maxtime=%d other=%d failure=%d", codes[0],
		 codes[1], codes[2], codes[3], codes[4], codes[5], codes[6]);
	tally_print(t, extra);
	nlopt_destroy(o);
	ik_free(ik);
	return 0;
}

int
main(int argc, char **argv)
{
	if (argc < 2 || argc > 3) {
		fprintf(stderr, "usage: ik_arm TARGETS_OUT [N]\n");
		return 2;
	}
	int n = argc > 2 ? atoi(argv[2]) : 1000;
	if (n < 1 || n > MAX_TARGETS) {
		fprintf(stderr, "ik_arm: N is 1..%d\n", MAX_TARGETS);
		return 2;
	}
	struct arm a;
	if (arm_make(&a) < 0)
		return 1;
	struct target *tg = calloc((size_t)n, sizeof *tg);
	double *us = calloc((size_t)n * 4, sizeof *us);
	if (!tg || !us)
		return 1;
	make_targets(&a, tg, n);
	if (write_targets(&a, tg, n, argv[1]) < 0)
		return 1;
	struct tally ours = { .name = "posture", .us = us, .has_iters = 1 };
	struct tally lbfgs = { .name = "nlopt_lbfgs", .us = us + 2 * n };
	struct tally slsqp = { .name = "nlopt_slsqp", .us = us + 3 * n };
	/* ik_default_options' iteration limit (per start), the 2 ms budget */
	if (bench_ours(&a, tg, n, 0, &ours) < 0 ||
	    bench_nlopt(&a, tg, n, NLOPT_LD_LBFGS, &lbfgs) < 0 ||
	    bench_nlopt(&a, tg, n, NLOPT_LD_SLSQP, &slsqp) < 0)
		return 1;
	int major, minor, bugfix;
	nlopt_version(&major, &minor, &bugfix);
	printf("ik_arm: %d targets from srand(1); success = 1 mm and 1 deg with every arm dof "
	       "within limits; NLopt %d.%d.%d from neutral without restarts\n",
	       n, major, minor, bugfix);
	free(us);
	free(tg);
	state_free(a.check);
	state_free(a.s);
	model_free(a.m);
	return 0;
}
