/*
 * bvh.h - export of a figure's postures over time as BVH (Biovision
 * Hierarchy), the motion format animation tools read (Blender, MotionBuilder).
 *
 * The skeleton follows the joints of the tree of the figure's root now: the
 * ROOT at the root site, a JOINT per joint at its child-side site, named
 * after the joint, each OFFSET from the figure's sites; a segment with no
 * joint below ends in an End Site at its site farthest from its joint.
 * Each joint has three rotation channels, ordered as its rotation dofs are
 * (the axes it lacks after them), plus three position channels where it
 * has a translation dof; the ROOT has three position channels first.
 * Position channels are where the joint sits in its parent, in place of
 * its OFFSET (which is where it sits with its dofs at zero), as readers
 * such as Blender's and bvhio take them. Where
 * a joint's two sites are parallel (the human's are), the rotation
 * channels are the dof values themselves (times the dof's sign).
 */
#ifndef POSTURE_BVH_H
#define POSTURE_BVH_H

#include <stddef.h>
#include <stdio.h>

#include "export/motion.h"

/*
 * Writes mo's frames (every one; NULL entries hold the nearest posture)
 * as the motion, frame_seconds apart. -1 with why in err when there are
 * no frames (nothing would move) or on an I/O error; else 0.
 */
int bvh_write(const struct motion *mo, double frame_seconds, FILE *f, char *err, size_t errlen);

/* bvh_write into path (".bvh"), through a temporary file: 0, or -1 with why in err */
int bvh_export(const struct motion *mo, double frame_seconds, const char *path, char *err,
	       size_t errlen);

#endif
