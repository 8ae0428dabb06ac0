/*
 * mcubes.h - the closed surface of a sampled field: marching cubes with each
 * cube split into the six tetrahedra of its Kuhn (Freudenthal)
 * triangulation, all along the diagonal from its lowest corner to its
 * highest. Every cube is split the same way, so neighbours split a shared
 * face along the same diagonal and the surface has no cracks: each
 * tetrahedron's case (which of its four corners are inside) has one
 * triangle or one quad, the whole table. A vertex on a grid edge is shared
 * by every triangle that meets the edge (welded), so the mesh is watertight
 * and consistently oriented: every edge in exactly two triangles, once each
 * way, triangles counter-clockwise seen from outside.
 *
 * The grid's outermost layer should be outside: the surface is then closed.
 */
#ifndef POSTURE_MCUBES_H
#define POSTURE_MCUBES_H

#include <stddef.h>

struct mc_grid {
	int n[3];          /* points each way */
	double origin[3];  /* where point (0, 0, 0) is */
	double step;       /* between neighbouring points */
	const float *val;  /* n[0] n[1] n[2] values, x fastest; inside where <= 0 */
};

/* a triangle mesh: the same layout as struct envelope_mesh */
struct mc_mesh {
	int nvert, ntri;
	float *vert;   /* 3 nvert */
	float *normal; /* 3 nvert, unit, outward */
	int *tri;      /* 3 ntri, counter-clockwise seen from outside */
	double volume;
	double lo[3], hi[3]; /* bounds; both 0 when empty */
};

/* the grid index of point (i, j, k) */
static inline long
mc_index(const struct mc_grid *g, int i, int j, int k)
{
	return ((long)k * g->n[1] + j) * g->n[0] + i;
}

/*
 * The surface where val crosses 0. Each vertex lies on the grid edge from
 * an inside point to an outside one (a cube edge or one of its diagonals),
 * placed by linear interpolation; when edges is not NULL, *edges gets
 * 2 nvert indices: the inside point and the outside point of each vertex's
 * edge, so the caller may place them better and call mc_mesh_finish again.
 * Returns 0 with normals, volume and bounds done (mc_mesh_finish), or -1
 * when out of memory (dest empty).
 */
int mc_extract(const struct mc_grid *g, struct mc_mesh *dest, long **edges);

/* normals (area-weighted, outward), volume (divergence theorem) and bounds from vert and tri */
void mc_mesh_finish(struct mc_mesh *mesh);

void mc_mesh_free(struct mc_mesh *mesh);

/* 1 when p lies inside the closed mesh: a ray's crossings are odd */
int mc_mesh_contains(const struct mc_mesh *mesh, const double p[3]);

#endif
