/*
 * statics.h - the static equilibrium of a figure under gravity and external
 * loads: the forces its supports (the feet, or the seat and the feet) must
 * supply, and the net force and moment every joint carries.
 *
 * Conventions (world frame, y up, N and N m):
 *
 * - Gravity is -y at LOAD_GRAVITY (pose/load.h) on every segment's centre
 *   of mass; loads are struct ext_load (a force and torque at a point fixed
 *   in a segment; a weight's force is (0, -mass g, 0) and must be given so).
 * - The tree is rooted at the segment of the model's default root site
 *   (the human's pelvis), whatever the state's current root: re-rooting a
 *   figure does not change a single result. A joint's distal part is the
 *   subtree below it from that root.
 * - force[j], moment[j]: what the proximal side applies to the distal part
 *   at the joint centre point[j] (the distal side's joint site), so that
 *   the distal part is in equilibrium: force + its gravity + its loads + its
 *   supports = 0, and likewise the moments about point[j]. A joint holding
 *   up a hanging arm has force[1] > 0.
 * - dof_torque[d]: the generalised force of dof d, the wrench above
 *   projected on the dof's axis about its pivot, positive in the sense of
 *   the dof's positive motion (N m for a rotation, N for a translation):
 *   what the muscles must supply, what Pinocchio's RNEA returns.
 * - anat[j]: for the human's wrists, elbows, shoulders, L5/S1 (spine_0),
 *   hips, knees and ankles, moment[j] about the joint's anatomical axes
 *   (the ISB joint coordinate systems the dofs follow, figure/human.h):
 *   [0] flexion (ankle: dorsiflexion), [1] abduction (ankle: inversion,
 *   wrist: radial deviation, spine: bending to the left), [2] internal
 *   rotation (wrist: pronation, spine: turning to the left). + is a moment
 *   the muscles must supply in that sense; the right side is mirrored as
 *   the dofs are, so one number means one anatomical thing on both sides.
 *   For the 3-dof joints these are the dofs' generalised torques: the
 *   moment's orthogonal projections on the joint coordinate system's axes
 *   (the proximal segment's flexion axis, the floating axis, the distal
 *   segment's long axis), the "motor torques" of Desroches, Cheze & Dumas
 *   2010 (J Biomech Eng 132:114503), power-conjugate to the joint angles'
 *   rates; they differ from the axes' non-orthogonal components where the
 *   axes are far from perpendicular (the shoulder near 90 deg abduction).
 *   Knees and elbows (one dof) get their ab/adduction about the floating
 *   axis (the distal segment's forward axis) and rotation about its long
 *   axis, with the hip's and shoulder's signs on the same side: three
 *   perpendicular axes, where both readings agree.
 *
 * Supports: standing, each foot on the floor (geometry within
 * BALANCE_CONTACT, pose/balance.h) at its balance site; seated (the caller
 * says), the seat under the ischial tuberosities and the feet on the floor.
 * The rule that shares the support wrench between them is in statics.c and
 * the manual: every support's force is its share of the total support
 * force, the shares of the vertical force placing the centre of pressure
 * (between two feet, balance.h's lever rule), each support's free moment
 * closing the equilibrium. A figure without feet is held at its root.
 *
 * Nothing allocates; no clock, no I/O.
 */
#ifndef POSTURE_STATICS_H
#define POSTURE_STATICS_H

#include <stddef.h>

#include "figure/model.h"
#include "figure/state.h"
#include "pose/load.h"

#define STATICS_MAX_SEG 64 /* segments of a figure solved (the human has 37) */
#define STATICS_MAX_JNT (STATICS_MAX_SEG - 1)
#define STATICS_MAX_DOF 256
#define STATICS_MAX_SUPPORT 4 /* two feet, two ischial tuberosities */
#define STATICS_MAX_LOADS 64

enum statics_support_kind {
	STATICS_FOOT,  /* a foot's balance site (foot_l.balance, foot_r.balance) */
	STATICS_SEAT,  /* an ischial tuberosity (pelvis.ischial_tuberosity_l/_r) */
	STATICS_ROOT,  /* a figure without feet, held at its root site */
};

struct statics_support {
	int kind;         /* enum statics_support_kind */
	int site;         /* the site it stands for */
	int seg;          /* the segment it pushes on */
	double point[3];  /* where the force acts, world */
	double force[3];  /* N, world: what the support applies to the figure */
	double moment[3]; /* N m, world: the free moment about point */
	double share;     /* its fraction of the total support force, 0..1 */
};

struct statics_result {
	int njoint, ndof;          /* the model's */
	int root_seg;              /* the segment the tree is rooted at */
	double point[STATICS_MAX_JNT][3];  /* joint centre, world */
	double force[STATICS_MAX_JNT][3];  /* N: proximal onto distal */
	double moment[STATICS_MAX_JNT][3]; /* N m about point, proximal onto distal */
	int distal_seg[STATICS_MAX_JNT];   /* the segment just below the joint */
	int anatomical[STATICS_MAX_JNT];   /* 1 when anat[j] is given */
	double anat[STATICS_MAX_JNT][3];   /* N m: flexion, abduction, rotation (see above) */
	double dof_torque[STATICS_MAX_DOF];

	int nsupport;
	struct statics_support support[STATICS_MAX_SUPPORT];

	double weight_n;     /* the figure's weight, N */
	double load_mass;    /* kg of the weights among the loads */
	double cop[3];       /* the centre of pressure the supports need, on their plane */
	double margin;       /* m from cop to the support polygon's edge, > 0 inside */
	int seated;          /* as asked */
	int contacts;        /* supports that touch (feet on the floor, the seat) */
	int lifts;           /* 1: the loads lift the figure (the supports would have to pull) */
	int tips;            /* 1: cop outside the support polygon, or lifts: it would fall */
};

/*
 * Solves the statics of figure m in state s (frames and centres of mass
 * current: kin_update) under gravity and loads[0..nloads-1], seated or
 * standing. Returns 0 with dest filled, or -1 with why in err (dest
 * untouched) for a figure larger than STATICS_MAX_*, too many loads, a
 * load on a bad segment or not finite, a weight whose force is not
 * (0, -mass g, 0), seated on a figure without ischial tuberosities, or a
 * posture whose frames are not finite. A figure that would tip is solved
 * all the same, with tips set. A few microseconds for the human.
 */
int statics_solve(const struct model *m, const struct state *s, const struct ext_load *loads,
		  int nloads, int seated, struct statics_result *dest, char *err, size_t errlen);

/*
 * 1 when joint j of m is one of the human's joints given anatomical
 * moments (wrist, elbow, shoulder, spine_0, hip, knee, ankle), else 0.
 */
int statics_anatomical_joint(const struct model *m, int j);

/*
 * The names of joint j's three anatomical components ("flexion",
 * "abduction", "rotation"; the ankle's "dorsiflexion", "inversion",
 * "rotation"; the wrist's "flexion", "radial_deviation", "pronation";
 * spine_0's "flexion", "lateral_bend", "axial_rotation"), or NULL when
 * the joint has none.
 */
const char *const *statics_axis_names(const struct model *m, int j);

#endif
