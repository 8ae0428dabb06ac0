/*
 * joint_manip.h - manipulating a joint (§3.8): the left, middle and right
 * buttons select the joint's first three DOFs, CONTROL with them the next
 * three; a rotational DOF turns by the rotation wheel's spoke angle about
 * its axis (B.3), a translational one slides by the change of the axis's
 * point nearest the mouse line (B.1); the value is clamped to the limits.
 *
 * The caller gives each DOF as it is now in the world (joint_dof_view):
 * its axis already carried through the DOFs before it (forward
 * kinematics does that), and turned the way the child segment moves, so
 * a joint that points up the current rooting (the child moves by -q)
 * gets its axis negated and moves as defined. Like the manipulation
 * operator, a press never moves anything: every change of the chord
 * re-anchors, and later mouse lines change the value by the change of the
 * angle or the nearest point since.
 */
#ifndef POSTURE_INTERACT_JOINT_MANIP_H
#define POSTURE_INTERACT_JOINT_MANIP_H

#include "devices/event.h"
#include "interact/ray.h"

/* a DOF of the joint as the mouse sees it now */
struct joint_dof_view {
	int rotation;     /* 1: an angle (radians), 0: a length (metres) */
	double axis[3];   /* world, unit: the way the child moves for a growing value */
	double pivot[3];  /* world: a point of the axis */
	double lo, hi;    /* the limits of the value */
	double value;     /* the value now */
};

struct joint_manip {
	int ndof;         /* the joint's DOFs, 1..6 */
	unsigned buttons; /* left 1, middle 2, right 4 */
	unsigned ctrl;    /* left key 1, right key 2 */
	int dof;          /* the DOF selected, -1: none */
	/* the anchor: the value and the reference when the chord last changed */
	int anchored;
	double value0;
	double s0;           /* translation: the axis parameter of the nearest point */
	double spoke0[3];    /* rotation: the first spoke */
	double spoke[3];     /* ... and the latest */
	double angle;        /* the spokes' summed turn since the anchor */
};

void joint_manip_init(struct joint_manip *j, int ndof);

/*
 * A button or CONTROL record: returns 1 when the selection changed (the
 * next mouse line re-anchors), 0 otherwise. One button selects DOF 0, 1
 * or 2 (left, middle, right), with CONTROL 3, 4 or 5; a DOF the joint does
 * not have, two or three buttons, or none select nothing.
 */
int joint_manip_event(struct joint_manip *j, const struct input_event_rec *e);

/*
 * A new mouse line, with the selected DOF as it is now: returns 1 with
 * the DOF's new value (clamped to its limits) in *value, 0 when nothing
 * changes (no DOF selected, the line anchors, or it misses the wheel's
 * plane or runs parallel to the axis).
 */
int joint_manip_ray(struct joint_manip *j, const struct joint_dof_view *dv, const struct ray *r,
		    double *value);

/*
 * A value typed for the selected DOF: its value when it was selected (or
 * now, before any motion) plus typed, clamped, into *value. Returns 1, or
 * 0 when no DOF is selected. The mouse goes on from the typed value.
 */
int joint_manip_type(struct joint_manip *j, const struct joint_dof_view *dv, double typed,
		     double *value);

#endif
