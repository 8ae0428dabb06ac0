/* ik_internal.h - the solver's data, shared by ik.c and ik_energy.c only */
#ifndef POSTURE_IK_INTERNAL_H
#define POSTURE_IK_INTERNAL_H

#include "pose/ik.h"

#define IK_RESIDUAL_MAX 12 /* residual components of one constraint */

struct ik_con {
	struct ik_constraint_def def;
	/* goals of this solve after the step factor (§4.7.1): global, or
	 * relative to def.goal_site; one for the position part, one for the
	 * orientation part, so shortening one does not bend the other */
	struct xform goal_pos, goal_ori;
	double com_local[3]; /* com_effector: the centre of mass in the site frame */
	double pos_err, ori_err; /* at the last evaluation */
};

#define IK_MAX_GROUPS 4

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
	int cap, n, ndof;
	struct ik_con *con;
	struct ik_chain chain[IK_MAX_GROUPS];
	unsigned gen;   /* bumped whenever a constraint is added, redefined or switched */
	int rebuilt;    /* chains rebuilt by the current solve */
	int *move_seg;  /* nseg scratch: every segment below a variable */

	/* limit springs, per dof */
	double *spring_angle, *spring_weight;
	signed char *spring_side;

	/* the prepared group: pointers into its chain */
	int group;
	double spring_f; /* spring energy at the last evaluation */
	int nvar;
	int *var_dof;             /* ndof */
	int *dof_var;             /* ndof: variable index or -1 */
	double *lo, *hi;          /* ndof */
	int ndyn;
	int *dyn_seg;             /* nseg: segments that move, top-down */
	unsigned char *moves_eff; /* cap x ndof: variable k moves constraint c's effector */
	unsigned char *moves_goal; /* cap x ndof: ... and its goal site */
	unsigned char *in_group;  /* cap */
	unsigned char *seg_mark;  /* nseg scratch */

	/* minimiser workspace, all ndof (or ndof^2) long */
	double *x, *g, *xt, *gt, *d, *sv, *yv, *hy, *best, *H;
	double *B;  /* ndof^2: Gauss-Newton metric */
	double *jr; /* ndof x IK_RESIDUAL_MAX: residual derivatives of one constraint */
	double *H2; /* ndof^2: Cholesky factor */
	unsigned char *pin; /* ndof: variable pinned at a bound when the metric was made */
	int *free_idx;      /* ndof */
};

/* ik_energy.c */
/*
 * energy at x (written into the state's joint values); grad (nvar) and the
 * Gauss-Newton metric (nvar x nvar) when not NULL
 */
double ik_eval(struct ik *ik, const struct model *m, struct state *s, const double *x,
	       double *grad, double *metric);
int ik_group_met(const struct ik *ik, double tol_pos, double tol_ori);
int ik_apply_step_factor(struct ik *ik, const struct model *m, const struct state *s,
			 double step_pos, double step_ori);
/* sets c->pos_err and c->ori_err for the given frames */
void ik_con_errors(struct ik_con *c, const struct xform *E, const struct xform *Gp,
		   const struct xform *Go);
void ik_con_frames(const struct ik_con *c, const struct model *m, const struct state *s,
		   struct xform *eff, struct xform *gpos, struct xform *gori);

#endif
