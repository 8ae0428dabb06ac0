/*
 * gltf.h - export of figures to binary glTF 2.0 (.glb), which viewers and
 * DCC tools (Blender, three.js, Babylon, trimesh) open as they are.
 *
 * Each figure is a node tree that follows its joints in the hierarchy of
 * its posture now (struct motion's now):
 *
 *   <figure>            at the root site's global frame
 *     <root segment>    the inverse of the root site's location; its mesh
 *       <joint>         at the parent-side site, turned by the joint's motion
 *         <segment>     the inverse of the child-side site's location; its mesh
 *           <joint> ...
 *
 * so the segment nodes' world transforms are our segment frames, and a
 * viewer poses the figure by turning the joint nodes. Meshes are
 * seg_mesh.h's (as the renderer draws them), in the segment frame, each
 * with a material of the segment's colour. Units metres; glTF's axes are
 * ours (y up, right-handed), and the human faces +z with its left at +x,
 * as glTF's front and left are. Nodes are named after the figure, its
 * segments and joints, as they are: a joint may share its segment's name
 * (glTF allows it; importers such as Blender's add a suffix).
 */
#ifndef POSTURE_GLTF_H
#define POSTURE_GLTF_H

#include <stddef.h>

#include "export/motion.h"

/*
 * Writes the nfig figures to path (which must end in ".glb") through a
 * temporary file and a rename. The nodes hold each figure's posture now;
 * when any figure has frames, one animation holds a keyframe per frame
 * at k * frame_seconds (LINEAR): the translation and rotation of every
 * figure's top node and of the joint nodes that move, a figure absent
 * from a frame held at its nearest frame. Returns 0, or -1 with why in
 * err and nothing written.
 */
int gltf_export(const struct motion *figs, int nfig, double frame_seconds, const char *path,
		char *err, size_t errlen);

#endif
