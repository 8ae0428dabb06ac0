/*
 * urdf.h - export of a figure to URDF, so robotics tools (Pinocchio, ROS)
 * can load our figures and check our kinematics independently.
 */
#ifndef POSTURE_URDF_H
#define POSTURE_URDF_H

#include <stdio.h>

#include "figure/model.h"
#include "figure/state.h"

/*
 * Writes the figure as URDF, with the hierarchy of the state's current root
 * fixed to a "world" link at the root frame. A joint with n dofs becomes n
 * single-dof URDF joints named "<joint>__<k>" (k = 0..n-1, in dof order),
 * joined by massless links; each site becomes a fixed joint to a massless
 * link named "<segment>__<site>". Returns 0, or -1 on an I/O error.
 */
int urdf_write(const struct model *m, const struct state *s, FILE *f);

#endif
