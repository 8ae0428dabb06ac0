/*
 * model.h - the immutable description of one figure (peabody, Appendix A).
 *
 * A figure is a set of segments (rigid parts with mass and geometry), sites
 * (frames fixed to a segment), and joints that connect two sites of the same
 * figure through an ordered list of degrees of freedom. The model has no
 * hierarchy of its own: which site is the root, and so which way each joint
 * points in the tree, is state (struct state), so re-rooting never touches
 * the model. Arrays are structure-of-arrays with their shapes in comments,
 * allocated once by model_builder_finish and never resized.
 *
 * Units: metres, radians, kilograms. Quaternions are (x, y, z, w).
 */
#ifndef POSTURE_MODEL_H
#define POSTURE_MODEL_H

#include <stddef.h>
#include "figure/mathx.h"

#define MODEL_NAME_MAX 48  /* bytes of a name, with its NUL */
#define MODEL_PATH_MAX 256 /* bytes of a mesh path, with its NUL */
#define MODEL_JOINT_DOF_MAX 6

enum dof_kind {
	DOF_ROTATION,
	DOF_TRANSLATION,
};

enum geom_kind {
	GEOM_BOX,       /* size: full extents x, y, z */
	GEOM_CYLINDER,  /* size: radius, length (along local y) */
	GEOM_CAPSULE,   /* size: radius, length of the straight part (along local y) */
	GEOM_ELLIPSOID, /* size: semi-axes x, y, z */
	GEOM_MESH,      /* size: scale x, y, z applied to the mesh vertices */
};

struct model {
	char name[MODEL_NAME_MAX];
	int nseg, nsite, njnt, ndof, ngeom, nmesh;
	int nvert, nface; /* all meshes together */

	/* segments */
	char (*seg_name)[MODEL_NAME_MAX]; /* nseg */
	double *seg_mass;                 /* nseg: kg */
	double *seg_com;                  /* nseg x 3: centre of mass, segment frame */
	double *seg_inertia;              /* nseg x 6: ixx iyy izz ixy ixz iyz about com, kg m^2 */
	float *seg_rgba;                  /* nseg x 4 */
	int *seg_site0, *seg_nsite;       /* nseg: sites of a segment are contiguous */
	int *seg_geom0, *seg_ngeom;       /* nseg: geoms of a segment are contiguous */

	/* sites: location relative to the segment frame */
	char (*site_name)[MODEL_NAME_MAX]; /* nsite */
	int *site_seg;                     /* nsite */
	double *site_pos;                  /* nsite x 3 */
	double *site_quat;                 /* nsite x 4: as read, so save -> load is exact */
	struct xform *site_loc;            /* nsite: pos + quat as a transform */
	struct xform *site_loc_inv;        /* nsite: its inverse */
	unsigned char *site_pure;          /* nsite: 1 when the location is a pure translation */
	unsigned char *site_moved;         /* nsite: 1 when model_set_site moved it since the build */

	/* joints: connect site_from to site_to; transform = dof_0 * dof_1 * ... */
	char (*jnt_name)[MODEL_NAME_MAX]; /* njnt */
	int *jnt_site_from, *jnt_site_to; /* njnt */
	int *jnt_dof0, *jnt_ndof;         /* njnt: dofs of a joint are contiguous */

	/* degrees of freedom, about / along sign * axis of the frame so far */
	int *dof_jnt;             /* ndof */
	unsigned char *dof_kind;  /* ndof: enum dof_kind */
	unsigned char *dof_axis;  /* ndof: 0 x, 1 y, 2 z */
	signed char *dof_sign;    /* ndof: +1 or -1 */
	double *dof_lo, *dof_hi;  /* ndof: limits, lo <= hi */
	double *dof_init;         /* ndof: initial value (the figure file's displacement) */

	/* geometry: primitives or meshes, placed in the segment frame */
	int *geom_seg;           /* ngeom */
	unsigned char *geom_kind; /* ngeom: enum geom_kind */
	double *geom_size;       /* ngeom x 3 */
	double *geom_pos;        /* ngeom x 3 */
	double *geom_quat;       /* ngeom x 4 */
	int *geom_mesh;          /* ngeom: mesh index for GEOM_MESH, else -1 */

	/* meshes (Wavefront OBJ), triangles only after loading */
	char (*mesh_path)[MODEL_PATH_MAX]; /* nmesh: as written in the figure file */
	int *mesh_vert0, *mesh_nvert;      /* nmesh */
	int *mesh_face0, *mesh_nface;      /* nmesh */
	float *mesh_vert;                  /* nvert x 3 */
	int *mesh_face;                    /* nface x 3: indices local to the mesh */

	/* the default root: a site and its global location */
	int root_site;
	double root_pos[3], root_quat[4];

	double total_mass;
};

/* definitions filled from a defaults function, as Box2D's b2BodyDef */
struct segment_def {
	const char *name;
	double mass;
	double com[3];
	double inertia[6];
	float rgba[4];
};

struct dof_def {
	enum dof_kind kind;
	int axis; /* 0 x, 1 y, 2 z */
	int sign; /* +1 or -1 */
	double lo, hi, init;
};

struct joint_def {
	const char *name;
	int site_from, site_to;
	int ndof;
	struct dof_def dof[MODEL_JOINT_DOF_MAX];
};

struct geom_def {
	enum geom_kind kind;
	double size[3];
	double pos[3];
	double quat[4];
	int mesh; /* for GEOM_MESH: index returned by model_builder_mesh */
};

struct segment_def segment_default_def(void);
struct joint_def joint_default_def(void);
struct geom_def geom_default_def(void);

struct model_builder;

/* returns a new builder for a figure, or NULL when out of memory */
struct model_builder *model_builder_create(const char *figure_name);
void model_builder_free(struct model_builder *b);

/*
 * Each adder returns the new element's index (>= 0) or -1 with a message
 * available from model_builder_error(): duplicate name, name too long, bad
 * index, non-finite number, limits out of order. A failed add changes nothing.
 */
int model_builder_segment(struct model_builder *b, const struct segment_def *d);
int model_builder_site(struct model_builder *b, int seg, const char *name, const double pos[3],
		       const double quat[4]);
int model_builder_joint(struct model_builder *b, const struct joint_def *d);
int model_builder_geom(struct model_builder *b, int seg, const struct geom_def *d);
/* copies nvert x 3 vertices and nface x 3 triangle indices */
int model_builder_mesh(struct model_builder *b, const char *path, const float *vert, int nvert,
		       const int *face, int nface);
int model_builder_root(struct model_builder *b, int site, const double pos[3], const double quat[4]);

/* lookups while building; -1 when absent */
int model_builder_find_segment(const struct model_builder *b, const char *name);
int model_builder_find_site(const struct model_builder *b, int seg, const char *name);
int model_builder_find_joint(const struct model_builder *b, const char *name);

const char *model_builder_error(const struct model_builder *b);

/*
 * Checks the figure (at least one segment, joints form a spanning tree of the
 * segments: connected, no cycle, no joint within one segment; a root site)
 * and returns the finished model, or NULL with the reason in
 * model_builder_error(). The builder is left intact either way.
 */
struct model *model_builder_finish(struct model_builder *b);

void model_free(struct model *m);

/* deep copy; NULL when out of memory */
struct model *model_copy(const struct model *m);

/* 1 when every field of a and b is identical (bit for bit for numbers) */
int model_equal(const struct model *a, const struct model *b);

/*
 * Moves a site on its segment (pos, unit quaternion x y z w, segment
 * frame): its location, the inverse and the pure flag follow, and the site
 * is marked moved, so a session can write it. The state's global frames
 * are stale until kin_update.
 */
void model_set_site(struct model *m, int site, const double pos[3], const double quat[4]);

/* 1 when joint j has a dof of the kind */
int model_joint_has(const struct model *m, int j, enum dof_kind kind);

/* lookups by name; -1 when absent. model_find_site takes "segment.site". */
int model_find_segment(const struct model *m, const char *name);
int model_find_site(const struct model *m, const char *seg_dot_site);
int model_find_joint(const struct model *m, const char *name);

/* writes "segment.site" into dest; returns dest */
char *model_site_fullname(const struct model *m, int site, char *dest, size_t len);

#endif
