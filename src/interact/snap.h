/*
 * snap.h - snapping the manipulation transform onto a feature of the
 * environment (Appendix B.4): positions onto a site, a node (vertex), an
 * edge or its line, a face, its centre or its plane; orientations onto a
 * site's frame, an edge's direction or a face's normal. Not continuous
 * gravity (B.4: too slow in a complex scene): one snap when asked, onto
 * the feature under the pointer, which the caller picks.
 *
 * An orientation snap onto a frame aligns each axis of G with the target
 * axis nearest to it: the relative rotation is made of 90 degree turns
 * (the hand's +z out of the palm onto a table's -y). Onto an edge or a
 * normal, G turns through the smallest angle that lays one of its axes
 * (either way) along it.
 */
#ifndef POSTURE_INTERACT_SNAP_H
#define POSTURE_INTERACT_SNAP_H

#include "figure/mathx.h"

enum snap_kind {
	SNAP_SITE,             /* position and orientation of a site */
	SNAP_SITE_POSITION,
	SNAP_SITE_ORIENTATION,
	SNAP_NODE_POSITION,    /* a vertex */
	SNAP_EDGE_POSITION,    /* the edge's point nearest G */
	SNAP_EDGE_LINE,        /* the edge's line's point nearest G, maybe beyond its ends */
	SNAP_EDGE_ORIENTATION, /* an axis of G along the edge */
	SNAP_FACE_POSITION,    /* the face's point nearest G */
	SNAP_FACE_CENTER,
	SNAP_FACE_PLANE,       /* the plane's point nearest G, maybe outside the face */
	SNAP_FACE_ORIENTATION, /* an axis of G along the face's normal */
	SNAP_KINDS,
};

/* the feature under the pointer, world */
struct snap_feature {
	struct xform site;   /* the nearest site's frame */
	int has_site;
	double vertex[3];    /* the nearest corner */
	double edge[2][3];   /* the nearest edge's ends */
	double face[3][3];   /* the triangle's corners, counter-clockwise seen from outside */
};

/* the kind a name ("site", "site_position", "edge_line", ...) gives, or -1 */
int snap_kind_named(const char *name);
const char *snap_kind_name(enum snap_kind k);

/* G snapped onto the feature, into dest: 0, or -1 (no site for a site snap, a degenerate edge or face) */
int snap_apply(enum snap_kind kind, const struct snap_feature *f, const struct xform *g,
	       struct xform *dest);

/*
 * The rotation nearest r (columns its axes) among those whose axes are the
 * target's axes tr, each either way: tr times the signed permutation of
 * determinant +1 closest to tr^T r.
 */
void snap_square_up(const double r[9], const double tr[9], double dest[9]);

#endif
