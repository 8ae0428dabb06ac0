/*
 * state.h - everything about a figure that changes: joint values, the root,
 * and the hierarchy and global frames derived from them.
 *
 * The tree fields are peabody's "root fields" (§A.4.2): each segment knows
 * the site at its top (seg_root_site) and the joint above it
 * (seg_root_joint); each joint knows whether the model's from -> to
 * direction runs down the tree (jnt_dir = +1) or up it (-1). They are
 * rebuilt whenever the root changes, so the model's joint directions stay
 * what the figure file says whatever the root (§A.3: both knees alike).
 *
 * Every array is sized when the state is made; nothing here allocates after.
 */
#ifndef POSTURE_STATE_H
#define POSTURE_STATE_H

#include <stdint.h>
#include "figure/model.h"

struct state {
	double *q; /* ndof: joint values, radians or metres */

	/* the root: a site and its global frame */
	int root_site;
	struct xform root_xf;

	/* hierarchy derived from the root (state_root_at, kin_set_root) */
	int *seg_order;      /* nseg: top-down order, root segment first */
	int *seg_parent;     /* nseg: parent segment, -1 at the root */
	int *seg_root_site;  /* nseg: site at the top of the segment */
	int *seg_root_joint; /* nseg: joint to the parent, -1 at the root */
	int *jnt_child_seg;  /* njnt: segment below the joint */
	signed char *jnt_dir; /* njnt: +1 from-site above to-site, -1 inverted */

	/* global quantities (kin_forward) */
	struct xform *seg_xf;  /* nseg */
	struct xform *site_xf; /* nsite */
	double *dof_axis_w;    /* ndof x 3: world axis of each dof */
	double *dof_pivot_w;   /* ndof x 3: world point the axis passes through */

	/* mass distribution (kin_com) */
	double *seg_com_w;    /* nseg x 3 */
	double *subtree_mass; /* nseg: mass of the segment and all below it */
	double *subtree_com;  /* nseg x 3 */
	double com[3];        /* whole figure */
};

/*
 * Makes a state for m in its initial posture (the model's displacements and
 * root) with its hierarchy built. Global frames are not computed yet:
 * kin_update does that. Returns NULL when out of memory.
 */
struct state *state_make(const struct model *m);
void state_free(struct state *s);

/* puts the initial posture and root back; the global frames are stale until kin_update */
void state_reset(const struct model *m, struct state *s);

/* copies every mutable value of src into dest (same model); no allocation */
void state_copy(const struct model *m, const struct state *src, struct state *dest);

/*
 * Makes `site` the root with the global frame root_xf and rebuilds the
 * hierarchy from it; the global frames are stale until kin_update
 * (kin_set_root re-roots without moving anything). Returns 0, or -1 for a
 * bad site.
 */
int state_root_at(const struct model *m, struct state *s, int site, const struct xform *root_xf);

/* clamps every joint value into its limits; returns how many were moved */
int state_clamp(const struct model *m, struct state *s);

/* FNV-1a hash of the joint values and root, for determinism checks */
uint64_t state_hash(const struct model *m, const struct state *s);

#endif
