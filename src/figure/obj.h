/*
 * obj.h - a small Wavefront OBJ reader: vertices and polygonal faces.
 *
 * Reads `v x y z [w ...]` and `f a b c ...` lines; face corners may be
 * written `v`, `v/t`, `v//n` or `v/t/n`, and negative indices count back
 * from the last vertex defined so far (-1 is the latest). Polygons are split
 * into triangles as a fan around their first corner. Every other statement
 * (vt, vn, g, o, s, usemtl, mtllib, l, ...) is ignored. Errors name the
 * file, line and column: "path:LINE:COL: message".
 */
#ifndef POSTURE_OBJ_H
#define POSTURE_OBJ_H

#include <stddef.h>

#define OBJ_TEXT_MAX (64u << 20) /* bytes of an OBJ file */

struct obj_mesh {
	float *vert; /* nvert x 3 */
	int *face;   /* nface x 3: triangles, 0-based vertex indices */
	int nvert, nface;
};

/*
 * Parses len bytes of OBJ text; `origin` names it in messages. Returns 0
 * with the mesh in dest (free it with obj_mesh_free), or -1 with the
 * message in err and dest empty. A mesh without faces is an error.
 */
int obj_read_string(const char *text, size_t len, const char *origin, struct obj_mesh *dest,
		    char *err, size_t errlen);

/* reads and parses a file; the same contract as obj_read_string */
int obj_read_file(const char *path, struct obj_mesh *dest, char *err, size_t errlen);

/* frees the arrays of a mesh and empties it; NULL and empty meshes are fine */
void obj_mesh_free(struct obj_mesh *mesh);

#endif
