/*
 * collide.h - distance and contact between triangle meshes: the Flexible
 * Collision Library (FCL) behind a small C interface, its C++ confined to
 * collide_fcl.cc.
 *
 * A collide_mesh is one rigid triangle mesh with its bounding volume
 * hierarchy (FCL's OBBRSS: oriented boxes for the overlap tests, rectangle
 * swept spheres for the distance bounds), built once in the mesh's own frame
 * and placed by a transform at each query, so a segment's mesh is built
 * once per model and moved with the segment's frame.
 *
 * A query between two placed meshes gives their separation: the minimum
 * distance and the two closest points when they are apart; when they
 * interpenetrate, the penetration depth of their deepest contact as a
 * negative distance, with the contact point as both points. FCL computes
 * mesh-mesh penetration per pair of intersecting triangles, not the
 * translation that would separate the two volumes: two 10 cm spheres
 * overlapping by 5 cm read as 1.2 cm. That is the depth reported; it says
 * how deep surfaces cross, and understates how deep volumes overlap.
 *
 * Once their scratch is warm, queries allocate nothing.
 */
#ifndef POSTURE_FIT_COLLIDE_H
#define POSTURE_FIT_COLLIDE_H

#include <stddef.h>

#include "figure/mathx.h"

#ifdef __cplusplus
extern "C" {
#endif

struct collide_mesh;

/*
 * A mesh of nvert vertices (pos: 3 floats each, metres, the mesh's frame)
 * and ntri triangles (idx: 3 vertex indices each), its hierarchy built.
 * Returns NULL with a message in err for an empty or malformed mesh (an
 * index out of range, a coordinate not finite) or when memory runs out.
 */
struct collide_mesh *collide_mesh_make(const float *pos, int nvert, const unsigned *idx, int ntri,
				       char *err, size_t errlen);
void collide_mesh_free(struct collide_mesh *m);

/* the mesh's triangles */
int collide_mesh_triangles(const struct collide_mesh *m);

/* the mesh's bounding box in its own frame */
void collide_mesh_bounds(const struct collide_mesh *m, double lo[3], double hi[3]);

struct collide_result {
	double distance; /* m: > 0 apart, 0 touching, < 0 interpenetrating by that depth */
	double pa[3];    /* world: the point of a nearest to b (apart), or the deepest contact */
	double pb[3];    /* world: the point of b nearest to a, or the deepest contact */
};

/*
 * What a query keeps between calls: the contacts' storage, so that once
 * warm a query allocates nothing (FCL's distance between meshes apart
 * allocates nothing of its own; its contact list would, each time). One a
 * thread; NULL when out of memory.
 */
struct collide_scratch;
struct collide_scratch *collide_scratch_make(void);
void collide_scratch_free(struct collide_scratch *sc);

/*
 * The separation of mesh a placed by xa (mesh frame to world) and mesh b
 * placed by xb, with scratch sc. Returns 0 with *out filled, or -1 when
 * FCL fails (out untouched).
 */
int collide_distance(struct collide_scratch *sc, const struct collide_mesh *a,
		     const struct xform *xa, const struct collide_mesh *b, const struct xform *xb,
		     struct collide_result *out);

/*
 * 1 when a and b placed so overlap (any pair of triangles intersects),
 * else 0: cheaper than a distance when only contact matters.
 */
int collide_overlap(struct collide_scratch *sc, const struct collide_mesh *a,
		    const struct xform *xa, const struct collide_mesh *b, const struct xform *xb);

#ifdef __cplusplus
}
#endif

#endif
