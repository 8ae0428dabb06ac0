/*
 * ik.h - inverse kinematics for postural control (Chapter 4, Zhao's method).
 *
 * A constraint ties an end effector (a site of the figure, with an optional
 * offset frame) to a goal (a fixed global frame, or a site of the same
 * figure, followed live during the solve) through a position objective
 * (point, line, plane) and/or an orientation objective (frame, direction,
 * aim), blended by a position/orientation weight and scaled by a weight
 * (§4.3.2, §4.3.3). The variables are the joint values of the chains from
 * each effector up to a start joint or to the figure root; the root never
 * moves (§4.4). The potential energy is the weighted sum of all enabled
 * constraints plus limit springs (§D.1.6); overconstrained sets settle at
 * its minimum.
 *
 * The minimiser is a variable-metric (BFGS) method with the joint limits
 * as bounds, handled by projection and an active set, analytic gradients
 * and a backtracking line search that only accepts decrease, so every
 * iteration is at least as good as the last (§4.7.2). It stops at
 * convergence, at an iteration limit or at a deadline read from a clock the
 * caller passes in, and the posture it leaves is the best one found. The
 * result records where the deadline cut it (struct ik_work), and a solve
 * given that record as opt->replay stops at the same place without a
 * clock, so a recorded session replays bit for bit (ik_work.h).
 *
 * Everything is allocated by ik_make for a figure and a constraint
 * capacity; setting goals, enabling constraints and solving allocate
 * nothing.
 */
#ifndef POSTURE_IK_H
#define POSTURE_IK_H

#include <stdint.h>

#include "figure/model.h"
#include "figure/state.h"
#include "pose/ik_constraint.h"
#include "pose/ik_work.h"
#include "pose/point_mass.h"

/* why a solve stopped */
enum ik_status {
	IK_CONVERGED,  /* every objective met its tolerance, or no further decrease is possible */
	IK_ITER_LIMIT, /* the iteration limit cut it */
	IK_TIME_LIMIT, /* the deadline cut it */
};

const char *ik_status_to_str(enum ik_status st);

/* the clock: microseconds, monotonic; a virtual one makes solves reproducible */
struct ik_clock {
	uint64_t (*now_us)(void *ctx);
	void *ctx;
};

struct ik_options {
	double step_pos;    /* step factor: metres per solve (§4.7.1), 0 = off */
	double step_ori;    /* step factor: radians per solve, 0 = off */
	int max_iter;       /* per start of a group in a balance round */
	uint64_t budget_us; /* wall-clock limit of the whole solve (needs a clock), 0 = none */
	double tol_pos;     /* metres: a position objective is met below this */
	double tol_ori;     /* radians: an orientation objective is met below this */
	double settle_rel;  /* a start whose energy fell by less than this fraction over its
			     last 4 iterations has settled: a goal out of reach gains nothing
			     from polishing (0 = run on to a stationary point) */
	int balance_rounds; /* at most this many centre-of-mass rounds (§4.5.2) */
	double balance_tol; /* metres: the centre of mass has settled when it moves less */
	int restarts;       /* random restarts allowed when stuck away from the goals */
	int restart_after;  /* with restarts left: iterations from one start before the next,
			     once the energy halves no more in 8 iterations */
	unsigned restart_groups; /* bit g set: group g may restart (default all) */
	uint32_t seed;      /* for restarts */
	double *trace;      /* optional: the energy after every iteration, for tests */
	int trace_cap;
	/* replay (ik_work.h): non-NULL, the solve is cut where this record of a
	 * live solve was cut, and the clock and budget_us are not looked at; a
	 * record of a solve that ended on its own is never cut */
	const struct ik_work *replay;
};

struct ik_options ik_default_options(void);

struct ik_result {
	enum ik_status status;
	int iterations;     /* all groups and rounds */
	int evaluations;    /* objective evaluations */
	int balance_rounds; /* centre-of-mass rounds taken */
	int restarts;       /* restarts taken */
	int stepped;        /* 1 when the step factor shortened a goal */
	int met;            /* 1 when every enabled constraint met its tolerances */
	double f_start, f_end; /* potential energy before and after */
	int active_limits;  /* variables resting on a joint limit at the end */
	int trace_len;      /* entries written to opt->trace */
	int chains_rebuilt; /* groups whose variables had to be worked out again */
	struct ik_work work; /* what decides where the solve stopped, for recording */
};

struct ik;

/* returns a solver for figure m with room for max_constraints, or NULL */
struct ik *ik_make(const struct model *m, int max_constraints);
void ik_free(struct ik *ik);

/*
 * Adds a constraint; returns its index, or -1 when full or the definition
 * is invalid (bad site or joint index, start joint not above the
 * effector, non-finite numbers, zero axis).
 */
int ik_add(struct ik *ik, const struct model *m, const struct ik_constraint_def *def);
/* replaces a constraint's definition; 0 or -1 as ik_add */
int ik_set(struct ik *ik, const struct model *m, int c, const struct ik_constraint_def *def);
const struct ik_constraint_def *ik_get(const struct ik *ik, int c);
int ik_count(const struct ik *ik);
/* removes every constraint */
void ik_clear(struct ik *ik);

/* moves a goal (cheap: no chain is rebuilt); 0, or -1 for a bad index */
int ik_set_goal(struct ik *ik, int c, const struct xform *goal_xf);
int ik_enable(struct ik *ik, int c, int on);

/*
 * A limit spring on a dof (§D.1.6): energy rises as the dof comes within
 * `angle` of its lower (side = -1) or upper (side = +1) limit. weight 0
 * removes it.
 */
int ik_set_spring(struct ik *ik, const struct model *m, int dof, int side, double angle,
		  double weight);

/*
 * The weights the figure carries (point_mass.h): from the next solve on, a
 * constraint whose effector is the centre of mass holds the centre of mass
 * of the figure with them. Copied (at most POINT_MASS_MAX); n = 0 clears
 * them. Returns 0, or -1 for masses the figure cannot carry (nothing changes).
 */
int ik_set_point_masses(struct ik *ik, const struct model *m, const struct point_mass *pm, int n);
/* the weights as set; returns their count */
int ik_point_masses(const struct ik *ik, const struct point_mass **pm);
/* the centre of mass the com effectors hold: the figure's with the weights (needs kin_com) */
void ik_com(const struct ik *ik, const struct state *s, double dest[3]);

/*
 * Solves the enabled constraints from the state's posture (warm start).
 * s must have current global frames and centre of mass (kin_update), and
 * is left so, at the best posture found. clock may be NULL when
 * opt->budget_us is 0 or opt->replay is set. f_start and f_end are the
 * energies of the groups at the start of the first and the end of the last
 * balance round. The result's work, given back as opt->replay with the same
 * starting state, constraints and options, makes the same solve without a
 * clock: the same posture, bit for bit, and the same work.
 */
struct ik_result ik_solve(struct ik *ik, const struct model *m, struct state *s,
			  const struct ik_options *opt, const struct ik_clock *clock);

/*
 * The dofs the last solve moved that rest on a joint limit, in dof order,
 * at most max of them into dest; returns the count.
 */
int ik_active_limits(const struct ik *ik, const struct model *m, const struct state *s, int *dest,
		     int max);

/* error of constraint c in the current state: metres and radians */
void ik_constraint_error(const struct ik *ik, const struct model *m, const struct state *s, int c,
			 double *pos_err, double *ori_err);

/*
 * The potential energy of one group as a function of its variables, for
 * tests and peer benchmarks: ik_prepare fixes the group's variables from
 * the state (returns their count), ik_energy evaluates at x (grad may be
 * NULL) without touching the state's joint values outside the variables.
 */
int ik_prepare(struct ik *ik, const struct model *m, struct state *s, int group);
double ik_energy(struct ik *ik, const struct model *m, struct state *s, const double *x,
		 double *grad);
/* variable i's dof, and the group's bounds */
int ik_var_dof(const struct ik *ik, int i);

#endif
