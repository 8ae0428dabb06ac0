/*
 * fit_model.h - a figure's collision model: one collide_mesh a segment,
 * built once from the meshes the renderer draws (export/seg_mesh.h), placed
 * by the segment frames of any posture; and the pairs of its own segments
 * that self-clearance leaves out, each with its reason.
 *
 * Left out of self-clearance: segments jointed to each other (they share a
 * joint centre, so their meshes meet there in every posture), and for the
 * human the pairs its FIT_TOUCH table names: meshes that overlap in a
 * normal posture (the thighs and the pelvis, the slices of the trunk with
 * their neighbours, the clavicles on the thorax ...), so that only a
 * contact a posture makes is reported.
 */
#ifndef POSTURE_FIT_MODEL_H
#define POSTURE_FIT_MODEL_H

#include <stddef.h>

#include "figure/model.h"
#include "figure/state.h"
#include "fit/collide.h"

enum fit_skip {
	FIT_CHECKED = 0,
	FIT_SAME,      /* a segment and itself */
	FIT_JOINTED,   /* a joint connects them */
	FIT_TOUCHING,  /* the human's table: they touch in a normal posture */
	FIT_NO_MESH,   /* one has no geometry */
};

struct fit_model {
	const struct model *m;
	int nseg;
	struct collide_mesh **mesh; /* nseg: NULL for a segment without geometry */
	double *lo, *hi;            /* nseg x 3: each mesh's bounds in its segment's frame */
	double *radius;             /* nseg: the farthest of its mesh from the segment's origin */
	unsigned char *skip;        /* nseg x nseg: enum fit_skip of each self pair */
	int ntri;                   /* triangles of every mesh */
};

/*
 * The collision model of m (meshes in m's segment frames; the hierarchies built on
 * up to 4 cores). Returns NULL
 * with a message in err when memory runs out or a mesh is malformed.
 */
struct fit_model *fit_model_make(const struct model *m, char *err, size_t errlen);
void fit_model_free(struct fit_model *f);

/* why self pair (a, b) is left out; FIT_CHECKED when it is checked */
enum fit_skip fit_model_skip(const struct fit_model *f, int a, int b);
/* a reason's words for the replies and docs */
const char *fit_skip_str(enum fit_skip k);

/*
 * The world bounding box of segment seg's mesh placed by the frame xf: the
 * mesh's own box turned and moved, enlarged to stay axis-aligned (it holds
 * the mesh, not always tightly).
 */
void fit_model_world_box(const struct fit_model *f, int seg, const struct xform *xf, double lo[3],
			 double hi[3]);

#endif
