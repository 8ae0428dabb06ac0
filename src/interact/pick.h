/*
 * pick.h - picking (§3.3.3's probe used to select): the mouse line against
 * the figures' geometry, nearest hit first.
 *
 * A pick model holds a figure's geometry as the renderer draws it (the
 * same unit meshes placed by view_geom_parts, view.h), as triangles in
 * each segment's frame, with a bounding box per segment and per part. It
 * is built once per model (its own allocation) and never changes; a pick
 * allocates nothing: it carries the ray into each segment's frame by the
 * segment's global transform, tests the boxes, then the triangles
 * (Möller-Trumbore). Faces are one-sided as drawn (back faces are culled),
 * so a ray that starts inside a closed mesh does not hit it from within.
 */
#ifndef POSTURE_PICK_H
#define POSTURE_PICK_H

#include "figure/model.h"
#include "figure/state.h"
#include "interact/ray.h"

struct pick_part {
	int geom;           /* the model's geom this part draws */
	int index;          /* which of the geom's parts (view_geom_parts' order) */
	int tri0, ntri;     /* its triangles in the pick model's arrays */
	double lo[3], hi[3]; /* its bounding box, segment frame */
};

struct pick_model {
	int nseg, npart, ntri;
	int *seg_part0, *seg_npart; /* nseg: parts of a segment are contiguous */
	double *seg_lo, *seg_hi;    /* nseg x 3: bounding box of the segment's parts */
	struct pick_part *part;     /* npart */
	float *tri;                 /* ntri x 9: corners a, b, c in the segment frame, counter-
				       clockwise seen from outside */
	int *tri_vert;              /* ntri x 3: the corners' vertex numbers in the part's mesh */
};

/* the meshes of m as drawn; NULL when out of memory */
struct pick_model *pick_model_make(const struct model *m);
void pick_model_free(struct pick_model *pm);

struct pick_hit {
	int figure;       /* which of the targets (pick_scene), else 0 */
	int segment, geom;
	int part;         /* which of the geom's parts: a capsule is tube 0, caps 1 and 2 */
	int face;         /* the triangle's number in the part's mesh (an OBJ mesh's face number) */
	int edge[2];      /* vertex numbers of the triangle's edge nearest the point */
	int vertex;       /* vertex number of the triangle's corner nearest the point */
	int site;         /* the segment's site nearest the point, -1 when it has none */
	double point[3];  /* world, m */
	double normal[3]; /* world, unit: the triangle's outward face normal */
	double distance;  /* along the ray from its origin, m */
	/* the triangle itself, world (for snapping, B.4): its corners counter-clockwise from
	 * outside, and which of them are the nearest edge's ends and the nearest vertex */
	double tri[3][3];
	int edge_corner[2], vertex_corner;
};

/*
 * Ray r against one triangle (a, b, c counter-clockwise seen from the
 * front): 1 when it enters through the front at t >= tmin, with *t and the
 * barycentric weights *u of b and *v of c; 0 otherwise (parallel, behind,
 * back face, outside).
 */
int pick_triangle(const struct ray *r, const double a[3], const double b[3], const double c[3],
		  double tmin, double *t, double *u, double *v);

/*
 * The nearest hit of r on the figure (m in posture s, kin_update done),
 * not nearer than tmin along the ray: 1 with dest filled, 0 on a miss.
 */
int pick_figure(const struct pick_model *pm, const struct model *m, const struct state *s,
		const struct ray *r, double tmin, struct pick_hit *dest);

/* the same without the bounding boxes: every triangle tested (a reference for the tests) */
int pick_figure_exhaustive(const struct pick_model *pm, const struct model *m,
			   const struct state *s, const struct ray *r, double tmin,
			   struct pick_hit *dest);

/* a figure to pick from */
struct pick_target {
	const struct pick_model *pm;
	const struct model *m;
	const struct state *s;
};

/* the nearest hit over n figures (dest->figure says which): 1, or 0 on a miss */
int pick_scene(const struct pick_target *t, int n, const struct ray *r, double tmin,
	       struct pick_hit *dest);

/*
 * How far the figure reaches along the unit direction dir, as drawn (m in
 * posture s, kin_update done): the least and greatest dir . p over its
 * triangles' corners into *lo and *hi. 1, or 0 when it has no geometry.
 */
int pick_extent(const struct pick_model *pm, const struct state *s, const double dir[3], double *lo,
		double *hi);

#endif
