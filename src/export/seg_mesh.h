/*
 * seg_mesh.h - a segment's geometry as one triangle mesh in the segment's
 * frame, tessellated as the renderer draws it (the same primitives at the
 * fine level, the figure's own meshes with the same crease rule), so what
 * another tool shows of an export is what the kiosk shows.
 */
#ifndef POSTURE_SEG_MESH_H
#define POSTURE_SEG_MESH_H

#include <stdio.h>

#include "figure/model.h"

struct seg_mesh {
	int nvert, ntri;
	float *pos;    /* nvert x 3: metres, segment frame */
	float *nrm;    /* nvert x 3: unit normals */
	unsigned *idx; /* ntri x 3: counter-clockwise seen from outside */
	float lo[3], hi[3]; /* bounding box of pos (zero when empty) */
};

/*
 * Builds segment seg's mesh (every geom of it). A segment without geoms
 * gives an empty mesh. Returns 0, or -1 when out of memory (dest then
 * holds nothing).
 */
int seg_mesh_build(const struct model *m, int seg, struct seg_mesh *dest);

void seg_mesh_free(struct seg_mesh *mesh);

/* the mesh as binary STL (little-endian, one normal a facet); 0, or -1 on an I/O error */
int seg_mesh_write_stl(const struct seg_mesh *mesh, const char *name, FILE *f);

#endif
