/* ik_internal.h - the solver's data: the constraint set, the chains, the minimiser's workspace */
#ifndef POSTURE_IK_INTERNAL_H
#define POSTURE_IK_INTERNAL_H

#include "pose/ik.h"
#include "pose/ik_energy.h"

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
};

#endif
