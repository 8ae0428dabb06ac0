/*
 * mesh_export.h - closed triangle meshes (an analysis's surfaces: reach
 * envelopes) written for other tools: binary STL, which every CAD and
 * slicing tool opens, and glTF 2.0, binary (.glb) or text with its buffer
 * inside as base64 (.gltf).
 *
 * Vertices at the same position are welded into one and the triangles that
 * then repeat a corner (no area) left out, so the file is the closed surface
 * a reader welding by position (every STL reader) sees as closed.
 *
 * STL holds one surface and no colour: the first mesh given alone. glTF
 * holds each mesh as a node of that name with a material of its colour
 * (alpha below 1: blended), vertex normals, and 32-bit indices. Units
 * metres in both; axes ours (y up), as glTF's are.
 */
#ifndef POSTURE_MESH_EXPORT_H
#define POSTURE_MESH_EXPORT_H

#include <stddef.h>

struct mesh_export {
	const char *name;
	int nvert, ntri;
	const float *vert;   /* 3 nvert */
	const float *normal; /* 3 nvert, unit (STL's facet normals are the faces' own) */
	const int *tri;      /* 3 ntri, counter-clockwise seen from outside */
	float rgba[4];
};

/*
 * Writes the n meshes to path, its format by its ending (".stl" the first
 * mesh alone, ".glb", ".gltf"), through a temporary file and a rename.
 * Returns 0, or -1 with why in err and nothing written (another ending, a
 * vertex index out of range, an empty mesh, I/O).
 */
int mesh_export_write(const struct mesh_export *m, int n, const char *path, char *err,
		      size_t errlen);

#endif
