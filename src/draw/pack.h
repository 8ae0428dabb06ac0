/*
 * pack.h - a frame's instances baked into one world-space vertex and index
 * array, by class: opaque shadow casters, other opaque, transparent (back
 * to front), and the casters again in their coarse versions for the
 * shadow map. The renderer uploads the arrays and draws each class with
 * one call: on llvmpipe each draw call costs tens of microseconds, far
 * more than transforming a few tens of thousands of vertices on the CPU.
 * No GL here; nothing allocates after pack_init.
 */
#ifndef POSTURE_PACK_H
#define POSTURE_PACK_H

#include <stdint.h>

#include "draw/tess.h"
#include "draw/view.h"

#define PACK_MAX_VERT (1 << 18) /* vertices of all instances of a frame */
#define PACK_MAX_IDX (1 << 20)  /* their indices */

struct pack_vertex {
	float p[3], n[3];
	uint8_t c[4];
};

/* PACK_SHADOW: the casters again, in their coarse versions (shadows need no detail) */
enum pack_class { PACK_CAST, PACK_OPAQUE, PACK_CLEAR, PACK_SHADOW, PACK_N };

struct pack {
	struct pack_vertex *pv; /* PACK_MAX_VERT */
	unsigned *pi;           /* PACK_MAX_IDX */
	int nv, ni;             /* filled by the last pack_drawlist */
	int range[PACK_N][2];   /* first index and count of each class */
	int instances, triangles; /* packed for drawing (the shadow copies not counted) */
	int order[VIEW_MAX_INST]; /* instances front to back (early depth rejection) */
	float key[VIEW_MAX_INST];
};

/* allocates the arrays; 0, or -1 when out of memory (pack_free cleans up either way) */
int pack_init(struct pack *p);
void pack_free(struct pack *p);

/*
 * Packs dl's instances as seen through view (column-major, world to eye):
 * mesh[i] is mesh id i, lod[i] the id of its coarse version, nmesh how
 * many there are. Instances with an unknown mesh are skipped; when the
 * arrays are full the class ends there.
 */
void pack_drawlist(struct pack *p, const struct drawlist *dl, const float view[16],
		   const struct tess_mesh *mesh, const int *lod, int nmesh);

#endif
