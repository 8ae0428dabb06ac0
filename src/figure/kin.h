/*
 * kin.h - forward kinematics, Jacobians and centres of mass.
 *
 * All functions take the immutable model and the state; none allocates,
 * reads a clock or does I/O. Jacobians are row-major with one column per
 * dof of the figure; columns of dofs that do not move the point are zero.
 */
#ifndef POSTURE_KIN_H
#define POSTURE_KIN_H

#include "figure/model.h"
#include "figure/state.h"

/* global frames of every segment and site and the world axis of every dof */
void kin_forward(const struct model *m, struct state *s);

/*
 * the same for a subset: segs in top-down order, each one's parent current
 * (used by IK to recompute only the chains that move)
 */
void kin_forward_segments(const struct model *m, struct state *s, const int *segs, int n);

/* segment and sub-tree centres of mass and the figure's; needs kin_forward */
void kin_com(const struct model *m, struct state *s);

/* forward kinematics followed by centres of mass */
void kin_update(const struct model *m, struct state *s);

/*
 * Makes `site` the root without moving anything (§A.4.2): its current
 * global frame becomes the root frame, the hierarchy is rebuilt and the
 * frames recomputed. Needs current global frames. Returns 0, or -1 for a
 * bad site.
 */
int kin_set_root(const struct model *m, struct state *s, int site);

/*
 * dest (3 x ndof): d(point)/dq for a point fixed to segment seg, given in
 * world coordinates. Needs kin_forward.
 */
void kin_point_jacobian(const struct model *m, const struct state *s, int seg,
			const double point_w[3], double *dest);

/*
 * dest (6 x ndof): rows 0-2 linear velocity of the site origin, rows 3-5
 * angular velocity of its frame, both in world axes. Needs kin_forward.
 */
void kin_site_jacobian(const struct model *m, const struct state *s, int site, double *dest);

/* dest (3 x ndof): Jacobian of the whole figure's centre of mass; needs kin_com */
void kin_com_jacobian(const struct model *m, const struct state *s, double *dest);

/* 1 when dof moves segment seg in the current hierarchy */
int kin_dof_moves(const struct model *m, const struct state *s, int dof, int seg);

/* global transform across joint j from its from-site to its to-site */
void kin_joint_xform(const struct model *m, const struct state *s, int j, struct xform *dest);

#endif
