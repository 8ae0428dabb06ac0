/*
 * tess.h - triangle meshes with per-vertex normals for the geometric
 * primitives (unit sphere, hemisphere, open tube, closed cylinder, cone,
 * box) and for Wavefront meshes, built once when a model is loaded.
 *
 * Primitives are unit shapes, so one mesh serves every geom of a kind:
 * the renderer scales them with the instance matrix and transforms normals
 * by the inverse transpose. A capsule is a tube with two hemispheres, so
 * its caps stay round whatever its radius and length.
 *
 * Vertices are interleaved position + normal (6 floats); triangles are
 * counter-clockwise seen from outside, indexed with unsigned ints. No
 * function here allocates except the builders, which report failure.
 */
#ifndef POSTURE_TESS_H
#define POSTURE_TESS_H

struct tess_mesh {
	int nvert;      /* vertices */
	int nidx;       /* indices, 3 a triangle */
	float *vn;      /* nvert x 6: position x y z, normal x y z */
	unsigned *idx;  /* nidx */
	float lo[3], hi[3]; /* bounding box of the positions */
};

/* the unit sphere (radius 1, centre 0): slices around y, stacks pole to pole */
int tess_sphere(int slices, int stacks, struct tess_mesh *dest);

/* its upper half (y >= 0), open at y = 0 */
int tess_hemisphere(int slices, int stacks, struct tess_mesh *dest);

/* radius 1 along y from -0.5 to 0.5; caps = 1 closes both ends with flat disks */
int tess_cylinder(int slices, int caps, struct tess_mesh *dest);

/* radius 1 at y = 0, apex at y = 1, closed by a base disk */
int tess_cone(int slices, struct tess_mesh *dest);

/* the cube from -0.5 to 0.5, flat faces (4 vertices each) */
int tess_box(struct tess_mesh *dest);

/*
 * A triangle mesh with smooth normals that keep creases: a corner takes the
 * area-weighted mean of the normals of the faces around its vertex that lie
 * within crease_deg of its own face; sharper neighbours do not blend in.
 * vert: nvert x 3, face: nface x 3 (0-based). Degenerate faces are skipped.
 */
int tess_mesh_from_triangles(const float *vert, int nvert, const int *face, int nface,
			     double crease_deg, struct tess_mesh *dest);

/* each builder returns 0, or -1 when out of memory (dest then holds nothing) */
void tess_free(struct tess_mesh *mesh);

#endif
