/*
 * ik_energy.h - the energy a solve minimises (§4.3): the constraints'
 * weighted residuals and the limit springs over one group's variables,
 * with its gradient and Gauss-Newton metric, and the step factor that
 * shortens each goal before a solve (§4.7.1). The solver (ik.c) fills a
 * struct ik_terms when it prepares a group and minimises what it returns.
 */
#ifndef POSTURE_IK_ENERGY_H
#define POSTURE_IK_ENERGY_H

#include "figure/state.h"
#include "pose/ik_constraint.h"

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

/* one group's energy: what it sums, over which variables */
struct ik_terms {
	int n, ndof;        /* constraints in use, the figure's dofs */
	struct ik_con *con; /* cap */

	/* limit springs, per dof */
	double *spring_angle, *spring_weight;
	signed char *spring_side;
	double spring_f; /* spring energy at the last evaluation */

	/* the prepared group: pointers into the solver's chain for it */
	int nvar;
	int *var_dof;             /* ndof */
	double *lo, *hi;          /* ndof */
	int ndyn;
	int *dyn_seg;             /* nseg: segments that move, top-down */
	unsigned char *moves_eff; /* cap x ndof: variable k moves constraint c's effector */
	unsigned char *moves_goal; /* cap x ndof: ... and its goal site */
	unsigned char *in_group;  /* cap */

	double *jr; /* ndof x IK_RESIDUAL_MAX: residual derivatives of one constraint */
};

/*
 * The energy at x (written into the state's joint values); grad (nvar) and
 * the Gauss-Newton metric (nvar x nvar) too when not NULL.
 */
double ik_energy_eval(struct ik_terms *e, const struct model *m, struct state *s, const double *x,
		      double *grad, double *metric);
/* 1 when every constraint of the group is within the tolerances and no spring is stretched */
int ik_energy_met(const struct ik_terms *e, double tol_pos, double tol_ori);
/* shortens every goal to the step factor's reach (§4.7.1); returns 1 when one was shortened */
int ik_energy_step_factor(struct ik_terms *e, const struct model *m, const struct state *s,
			  double step_pos, double step_ori);
/* sets c->pos_err and c->ori_err for the given frames */
void ik_con_errors(struct ik_con *c, const struct xform *E, const struct xform *Gp,
		   const struct xform *Go);
/* the effector's frame and the goal frames of the position and orientation parts */
void ik_con_frames(const struct ik_con *c, const struct model *m, const struct state *s,
		   struct xform *eff, struct xform *gpos, struct xform *gori);

#endif
