/*
 * urdf.h - export of a figure to URDF that robotics tools load as it is:
 * Pinocchio, MuJoCo, PyBullet, urdfdom (check_urdf), RViz.
 */
#ifndef POSTURE_URDF_H
#define POSTURE_URDF_H

#include <stddef.h>
#include <stdio.h>

#include "figure/model.h"
#include "figure/state.h"

/*
 * The mass and inertia of the links between the dofs of one joint, and of
 * "world". They have none in the figure, but MuJoCo refuses a moving body
 * without mass (its limit, mjMINVAL, is 1e-15), and PyBullet, merging the
 * fixed links into a massless "world", drops the root segment's mass.
 * 1e-9 kg a link, 1e-12 kg m^2 about each axis: the human's 93 such links
 * add 9.3e-8 kg to 75 kg and move its centre of mass by under 1e-9 m, far
 * inside what any comparison resolves, while staying well above the
 * simulators' thresholds.
 */
#define URDF_NEGLIGIBLE_MASS 1e-9
#define URDF_NEGLIGIBLE_INERTIA 1e-12

/*
 * Writes the figure as URDF, with the hierarchy of the state's current root
 * fixed to a "world" link at the root's frame now. A joint with n dofs
 * becomes n single-dof URDF joints named "<joint>__<k>" (k = 0..n-1, in
 * dof order), joined by links "<joint>__<k>_link" of URDF_NEGLIGIBLE_MASS;
 * each site becomes a fixed joint to a massless link "<segment>__<site>".
 * Joint values are ours (radians, metres), limits ours; URDF has no place
 * for a default posture, so the state's values are given in a comment.
 * mesh_stem: NULL writes no geometry; else each segment with geoms gets a
 * <visual> and a <collision> of the mesh file "<mesh_stem><segment>.stl"
 * (seg_mesh.h), a path relative to the URDF. A <mujoco> element keeps
 * MuJoCo from merging the fixed links away, so every segment and site
 * stays a body there. Returns 0, or -1 on an I/O error.
 */
int urdf_write(const struct model *m, const struct state *s, const char *mesh_stem, FILE *f);

/*
 * Writes path (the URDF) and, beside it, one binary STL a segment with
 * geometry, named "<stem>_<segment>.stl" where stem is path's file name
 * without ".urdf". The URDF goes through a temporary file and a rename,
 * so it never exists half written. Returns the number of files written,
 * or -1 with why in err and none left (the meshes written are removed).
 */
int urdf_export(const struct model *m, const struct state *s, const char *path, char *err,
		size_t errlen);

#endif
