/*
 * ik_constraint.h - what a constraint is (§4.2, §4.3): an end effector (a
 * site of the figure, with an optional offset frame) tied to a goal (a
 * fixed global frame, or a site of the same figure) through a position
 * objective and/or an orientation objective, blended by a
 * position/orientation weight and scaled by a weight. The solver (ik.h)
 * holds sets of them; its energy (ik_energy.h) measures them.
 */
#ifndef POSTURE_IK_CONSTRAINT_H
#define POSTURE_IK_CONSTRAINT_H

#include "figure/model.h"

#define IK_MAX_GROUPS 4 /* solve groups: 0 the body, 1 the hands, ... (§D.1.5) */

enum ik_pos {
	IK_POS_NONE,
	IK_POINT, /* effector origin at the goal origin */
	IK_LINE,  /* effector origin on the line through the goal origin along goal_axis */
	IK_PLANE, /* effector origin on the plane through the goal origin, normal goal_axis */
};

enum ik_ori {
	IK_ORI_NONE,
	IK_FRAME,     /* effector axes parallel to the goal axes (3 dofs) */
	IK_DIRECTION, /* effector_axis (effector frame) parallel to goal_axis (goal frame) */
	IK_AIM,       /* effector_axis points from the effector origin at the goal origin */
};

/* a constraint's definition; fill from ik_constraint_default_def() */
struct ik_constraint_def {
	int effector_site;
	struct xform effector_offset; /* effector frame relative to the site */
	int goal_site;                /* -1: goal_xf is global; else goal_xf is relative to this site */
	struct xform goal_xf;
	enum ik_pos pos;
	enum ik_ori ori;
	double goal_axis[3];     /* line direction, plane normal, or direction, in the goal frame */
	double effector_axis[3]; /* direction or aim vector, in the effector frame */
	double pos_weight;       /* share of the position objective, 0..1 */
	double weight;
	int start_joint;         /* the chain runs from the effector up to this joint; -1: to the root */
	int group;               /* solved in order of group, 0..3: 0 the body, 1 the hands (§D.1.5) */
	int com_effector;        /* 1: the effector is the figure's centre of mass (§4.5.2) */
	int enabled;
};

struct ik_constraint_def ik_constraint_default_def(void);

/*
 * 1 when d is a definition the solver can take for figure m: sites and
 * joints in range, objectives known, finite frames, unit axes where an
 * objective needs one, weights in range, a group below IK_MAX_GROUPS.
 */
int ik_constraint_valid(const struct model *m, const struct ik_constraint_def *d);

#endif
