/*
 * view.h - cameras and the abstract draw list (no GL), like MuJoCo's mjv_.
 *
 * A view is a camera, an image size and a draw list. view_begin() starts a
 * draw list for a camera and size; the view_add_*() builders append the
 * figures (mesh instances), the icons of the dissertation (lines and
 * triangles with colour and alpha) and text placed in pixels; render.c
 * turns the list into pixels. A draw list has a fixed capacity, allocated
 * once by view_drawlist_make(); building never allocates. What does not
 * fit is dropped and counted (dl->dropped), never overflowed.
 *
 * The camera is Appendix C.1.3's: a transform from camera to world whose
 * -z axis is the line of sight, +x points right and +y up, plus a view
 * reference distance (the view reference point lies that far along the
 * line of sight) and a perspective projection (vertical field of view).
 * view_camera_aim() keeps the camera's x axis horizontal (no twist).
 *
 * World units are metres, y up, the floor at y = 0. Pixel coordinates have
 * their origin at the top left corner of the image, x right, y down.
 */
#ifndef POSTURE_VIEW_H
#define POSTURE_VIEW_H

#include <stdint.h>

#include "pose/env.h"
#include "pose/ik.h"
#include "figure/mathx.h"
#include "figure/model.h"
#include "figure/state.h"

/* capacities of one draw list */
#define VIEW_MAX_INST 2048   /* mesh instances */
#define VIEW_MAX_VERT 32768  /* line and triangle vertices */
#define VIEW_MAX_BATCH 512   /* runs of vertices drawn the same way */
#define VIEW_MAX_TEXT 64     /* text items */
#define VIEW_TEXT_LEN 160    /* bytes of one text item, with its NUL */

/* text metrics the overlay builders assume; render loads the font at this size */
#define VIEW_FONT_PX 14
#define VIEW_CHAR_PX 9 /* at least a character's advance: DejaVu Sans Mono's 0.6 em at 14 px */
#define VIEW_LINE_PX 20      /* height of a status or message band */

struct camera {
	struct xform xf; /* camera to world: columns of xf.r are the x, y, z axes in world */
	double vrd;      /* view reference distance, m (> 0) */
	double fovy;     /* vertical field of view, radians */
	double znear, zfar;
};

/* the built-in unit meshes (tess.h); a model's own meshes get ids from render_add_model */
enum view_mesh {
	VIEW_MESH_SPHERE,     /* radius 1 */
	VIEW_MESH_HEMISPHERE, /* radius 1, y >= 0 */
	VIEW_MESH_TUBE,       /* radius 1, y in [-0.5, 0.5], open */
	VIEW_MESH_CYLINDER,   /* the same, closed */
	VIEW_MESH_CONE,       /* radius 1 at y = 0, apex at y = 1 */
	VIEW_MESH_BOX,        /* [-0.5, 0.5]^3 */
	VIEW_MESH_BUILTIN,    /* count */
};

struct view_instance {
	int mesh;           /* enum view_mesh, or a model mesh id from render_add_model */
	float mat[16];      /* mesh to world, column-major (cglm mat4) */
	float rgba[4];      /* alpha < 1 draws it transparent, after the opaque ones */
	unsigned char shadow; /* 1: casts a shadow on the floor */
};

struct view_vertex {
	float p[3];         /* world metres, or pixels (z ignored) for VIEW_SCREEN */
	uint8_t c[4];       /* rgba */
};

enum view_prim {
	VIEW_LINES,     /* pairs of vertices */
	VIEW_TRIANGLES, /* triples */
};

enum view_space {
	VIEW_WORLD,  /* depth-tested in the scene */
	VIEW_SCREEN, /* pixels over everything */
};

/*
 * A run of vertices drawn alike. Icons are overlays (§3.3.2: transparent,
 * so they do not intrude): with xray set, the parts behind geometry are
 * drawn too, faintly, so an icon inside a body still reads.
 */
struct view_batch {
	uint8_t prim;  /* enum view_prim */
	uint8_t space; /* enum view_space */
	uint8_t xray;
	float width;   /* line width, pixels */
	int first, count;
};

enum view_align {
	VIEW_ALIGN_LEFT,   /* x is the left end of the text */
	VIEW_ALIGN_CENTER, /* x is the middle of the text */
};

struct view_text {
	float x, y;       /* pixels: the baseline's left end or middle */
	uint8_t c[4];
	uint8_t align;    /* enum view_align */
	char s[VIEW_TEXT_LEN];
};

struct drawlist {
	struct camera cam;
	int width, height;         /* of the image, pixels */
	float bg_top[3], bg_bottom[3]; /* background gradient */
	int floor;                 /* 1: draw the floor (y = 0) with its grid */
	float floor_rgb[3];
	float grid;                /* spacing of the grid lines, m */
	float light[3];            /* direction towards the key light (world), also the shadows' */
	float icon_scale;          /* line widths in pixels are multiplied by this */
	int ninst, nvert, nbatch, ntext;
	int dropped;               /* items that did not fit since view_begin */
	struct view_instance inst[VIEW_MAX_INST];
	struct view_vertex vert[VIEW_MAX_VERT];
	struct view_batch batch[VIEW_MAX_BATCH];
	struct view_text text[VIEW_MAX_TEXT];
};

/* ---- cameras ---------------------------------------------------------- */

/* 40 deg field of view, 5 cm to 200 m, looking down -z from (0, 1, 4) */
void view_camera_default(struct camera *dest);

/*
 * Places the camera at eye looking at target: -z along target - eye, x
 * horizontal (no twist: x . world y = 0), y up (y . world y >= 0), vrd =
 * |target - eye|. Looking straight up or down, x keeps the camera's
 * previous heading made horizontal (world x if it had none). Returns 0, or
 * -1 (camera unchanged) when eye and target coincide or are not finite.
 */
int view_camera_aim(struct camera *c, const double eye[3], const double target[3]);

/*
 * The camera of a named view: the default one aimed from its eye at its
 * target with its field of view (fovy_deg; 0 or less: the default 40 deg).
 */
void view_camera_of_view(const struct env_view *v, struct camera *dest);

/* the view reference point: vrd along the line of sight */
void view_camera_vrp(const struct camera *c, double dest[3]);

/* world to camera (the inverse of the camera transform), column-major */
void view_camera_view_matrix(const struct camera *c, float dest[16]);

/* the perspective projection for width / height = aspect, column-major (GL clip space) */
void view_camera_proj_matrix(const struct camera *c, double aspect, float dest[16]);

/*
 * Projects a world point into an image of w x h pixels (origin top left).
 * dest gets pixel x, y; returns 1 when the point lies in front of the
 * camera (beyond znear), 0 otherwise (dest then meaningless).
 */
int view_project(const struct camera *c, int w, int h, const double p[3], double dest[2]);

/*
 * The mouse line (§3.3.3): the ray through pixel (px, py) of a w x h image,
 * from the camera origin; dir is a unit vector.
 */
void view_mouse_line(const struct camera *c, int w, int h, double px, double py, double origin[3],
		     double dir[3]);

/* ---- what a figure is drawn with ---------------------------------------- */

/*
 * How a geom is drawn: one to three unit meshes, each placed in the
 * segment's frame by xf and scaled along its own axes by scale (a capsule
 * is a tube and two hemispheres). Picking tests exactly these meshes.
 */
#define VIEW_GEOM_PARTS_MAX 3
struct view_part {
	int mesh;           /* enum view_mesh, or VIEW_MESH_BUILTIN for a model mesh */
	int model_mesh;     /* the model's mesh index for a model mesh, else -1 */
	struct xform xf;    /* part to segment */
	double scale[3];
};

/* the parts of geom g of m; returns how many (1 .. VIEW_GEOM_PARTS_MAX) */
int view_geom_parts(const struct model *m, int g, struct view_part dest[VIEW_GEOM_PARTS_MAX]);

struct tess_mesh;
/*
 * Tessellates built-in mesh k as the renderer draws it: fine (1) for the
 * pictures, coarse (0) for shadows. Returns 0, or -1 when out of memory.
 */
int view_mesh_tess(enum view_mesh k, int fine, struct tess_mesh *dest);

/* ---- the draw list ------------------------------------------------------ */

/* a draw list with every array in place; NULL when out of memory */
struct drawlist *view_drawlist_make(void);
void view_drawlist_free(struct drawlist *dl);

/*
 * Empties dl and starts a picture of w x h pixels through cam, with the
 * default look: a pale blue-grey gradient, a floor with a 0.5 m grid, the
 * key light from above front left.
 */
void view_begin(struct drawlist *dl, const struct camera *cam, int w, int h);

/*
 * Every geom of a figure in its current posture (kin_forward done),
 * coloured by segment. mesh_base is what render_add_model returned for m
 * (the id of m's mesh 0); figures without meshes may pass 0. Returns the
 * instances added.
 */
int view_add_figure(struct drawlist *dl, const struct model *m, const struct state *s,
		    int mesh_base);

/*
 * The same with each segment in a colour of the caller's: seg_rgba holds
 * 4 floats (r, g, b, alpha) for each of m's segments, in place of the
 * model's seg_rgba (an assessment's tint, say: draw knows no more than
 * the colours). Returns the instances added.
 */
int view_add_figure_rgba(struct drawlist *dl, const struct model *m, const struct state *s,
			 int mesh_base, const float *seg_rgba);

/*
 * view_add_figure's with every geom translucent, its colour's alpha times alpha
 * (0 < alpha < 1: drawn after the opaque ones, blended), casting no
 * shadow: a ghost beside the figures drawn solid. Returns the instances.
 */
int view_add_figure_ghost(struct drawlist *dl, const struct model *m, const struct state *s,
			  int mesh_base, float alpha);

/*
 * Object ids for a visibility map (render_hemicube): figure slot fig
 * (0 .. 254) and segment seg (0 .. 65534) as one 24 bit number, never 0
 * (0 is "nothing"), and as the flat colour that draws it exactly.
 */
uint32_t view_id(int fig, int seg);
void view_id_rgba(uint32_t id, float dest[4]);
#define VIEW_ID_FIG(id) ((int)((id) >> 16) - 1)
#define VIEW_ID_SEG(id) ((int)((id)&0xffff) - 1)

/* the figure as view_add_figure places it, each geom in its flat id colour, no shadows */
int view_add_figure_ids(struct drawlist *dl, const struct model *m, const struct state *s,
			int mesh_base, int fig);
/* the same with the segments whose skip_seg[seg] is set left out (the parts around a point
 * the map is made from: §3.7.1's own body) */
int view_add_figure_ids_except(struct drawlist *dl, const struct model *m, const struct state *s,
			       int mesh_base, int fig, const unsigned char *skip_seg);

/* one instance; mat is column-major; returns its index or -1 when full */
int view_add_instance(struct drawlist *dl, int mesh, const float mat[16], const float rgba[4],
		      int shadow);

/*
 * Starts a batch of prim in space (merged with the previous batch when
 * alike), then view_vertex() appends vertices to it. Widths are pixels
 * before dl->icon_scale.
 */
void view_batch_begin(struct drawlist *dl, enum view_prim prim, enum view_space space,
		      float width, int xray);
void view_vertex(struct drawlist *dl, const double p[3], const uint8_t c[4]);
/* a line or a triangle in the current batch (kept whole or dropped whole) */
void view_line(struct drawlist *dl, const double a[3], const double b[3], const uint8_t c[4]);
void view_triangle(struct drawlist *dl, const double a[3], const double b[3], const double c[3],
		   const uint8_t rgba[4]);

/* text with its baseline at pixel (x, y); returns 0 or -1 when full (text is cut to fit) */
int view_add_text(struct drawlist *dl, double x, double y, const char *text, const uint8_t c[4],
		  enum view_align align);

/* ---- the icons ---------------------------------------------------------- */

/*
 * The manipulation transform (§3.3.2) as a labelled six-axis frame: lines
 * from -size to +size along each axis of xf, the positive halves coloured
 * (x red, y green, z blue) and labelled "x" "y" "z", the negative halves
 * paler and labelled "-x" "-y" "-z" when labels is set.
 */
void view_add_frame_icon(struct drawlist *dl, const struct xform *xf, double size, int labels);

/*
 * The translation icon (§3.4.1): a transparent double-headed arrow of the
 * given length through origin along dir (any length, not zero).
 */
void view_add_translation_arrow(struct drawlist *dl, const double origin[3], const double dir[3],
				double length);

/*
 * The rotation wheel (§3.5, §3.8.1, Figure 3.4): a rim of radius `radius`
 * about `axis` through center, eight spokes, and the spoke towards `spoke`
 * (projected into the wheel's plane) drawn long and thick. With limited
 * set, the wheel is split into sectors: green where the spoke may turn,
 * from lo - current to hi - current about axis (right hand), red beyond.
 */
struct view_wheel {
	double center[3], axis[3], spoke[3];
	double radius;
	int limited;
	double lo, hi, current; /* radians, for limited wheels */
};
void view_add_rotation_wheel(struct drawlist *dl, const struct view_wheel *w);

/*
 * The wheel of rotational dof `dof` of a figure (kin_forward done): in the
 * plane of its world axis through its pivot, the initial spoke towards the
 * distal segment's centre of mass, sectors from its limits and value.
 * Returns 0, or -1 for a translational or unknown dof.
 */
int view_add_joint_wheel(struct drawlist *dl, const struct model *m, const struct state *s, int dof,
			 double radius);

/*
 * A rotation fan (§4.6.2, Figure 4.1): a translucent sector at origin
 * sweeping from direction `from` to direction `to` (shortest way), radius
 * long, with its two edges drawn as lines. Nothing when they are parallel.
 */
void view_add_fan(struct drawlist *dl, const double origin[3], const double from[3],
		  const double to[3], double radius, const uint8_t rgba[4]);

/* the three fans that turn the axes of `effector` into those of `goal`, at the effector */
void view_add_orientation_fans(struct drawlist *dl, const struct xform *effector,
			       const struct xform *goal, double radius);

/*
 * The goal icons of the enabled constraints of ik (Chapter 4): a point
 * goal as a small diamond, a line as a long line, a plane as a translucent
 * square, a frame goal as a small unlabelled frame with the fans from
 * the effector's axes, a direction goal as a fan, an aim goal as a sight
 * line; a thin line joins each effector to its goal when they are apart.
 */
void view_add_goals(struct drawlist *dl, const struct ik *ik, const struct model *m,
		    const struct state *s);

/*
 * Balance (§5.4.2.1) of a human figure (segments foot_l, foot_r, toes_l,
 * toes_r, sites foot_l.balance and foot_r.balance; kin_update done): the
 * support polygon (convex hull of the feet's geometry within 2 cm of the
 * floor), the balance line between the feet's balance sites, the centre of
 * mass at its height with a plumb line, and the balance point (its
 * projection to the floor), green inside the support polygon and red
 * outside. com: the centre of mass balanced, the figure's with the weights
 * it carries (load_balance_com); NULL: its own. Returns 0, or -1 when the
 * figure has no feet.
 */
int view_add_balance(struct drawlist *dl, const struct model *m, const struct state *s,
		     const double com[3]);

/*
 * The cones about the line of sight marked on a picture through the eyes
 * (eyeview.h): for each full angle deg[i] (degrees) the circle where that
 * cone about the camera's axis meets the picture, radius
 * (height / 2) tan(deg / 2) / tan(fovy / 2) pixels about its centre, in
 * the colour of its rank (the first red, then yellow, green, blue).
 */
#define VIEW_CONE_SEGMENTS 128 /* straight pieces of a cone's circle */
void view_add_cone_marks(struct drawlist *dl, const double *deg, int n);

/*
 * A manikin's sight in another view (eyeview.h; Process Simulate's vision
 * envelope, research file §6.2): for each full angle deg[i] (degrees) a
 * translucent cone with its apex at eye about the line of sight dir
 * (unit), its sides length long (the rim at that range from the eye, at
 * deg[i] / 2 from dir), filled and its rim drawn, in the colour of its
 * rank as view_add_cone_marks'. Nothing for a zero or non-finite dir.
 */
#define VIEW_SIGHT_SEGMENTS 32 /* triangles of a sight cone's side */
void view_add_sight_cones(struct drawlist *dl, const double eye[3], const double dir[3],
			  const double *deg, int n, double length);

/* an external load's arrow: this long per newton of force, within these lengths (m) */
#define VIEW_LOAD_M_PER_N 0.002 /* 2 mm a newton: a 15 kg weight's 147 N, 29 cm */
#define VIEW_LOAD_LEN_MIN 0.05  /* so that a small force still shows */
#define VIEW_LOAD_LEN_MAX 1.5   /* so that a large one stays in the picture (its label tells) */
#define VIEW_LOAD_HEAD 0.06     /* an arrow's head's length (m), at most 30 % of the arrow */
#define VIEW_LOAD_RING 0.07     /* a torque's ring's radius (m), whatever its size */

/* the arrow's length (m) for a force of this many newtons */
double view_load_length(double newtons);

/*
 * An external load acting at point p (world): its force (NULL or zero:
 * none) as an arrow from p the way it pulls, view_load_length long (a
 * weight's points down), its head turned to the camera; its torque (NULL or
 * zero: none) as a ring about the torque's axis at p with an arrowhead
 * turning the right-hand way; label (NULL: none) beyond the arrow's tip. In
 * the loads' magenta, flat and seen through the body faintly, as the other
 * icons (§3.3.2).
 */
void view_add_load(struct drawlist *dl, const double p[3], const double force[3],
		   const double torque[3], const char *label);

/*
 * The status / edit line at the bottom of the picture and the message line
 * above it (§1.7), on dark translucent bands; either may be NULL. caret >=
 * 0: the edit line's cursor, under that character of status (the font is
 * monospaced, a character a column); -1: none.
 */
void view_add_status(struct drawlist *dl, const char *status, const char *message, int caret);

/* a filled screen rectangle from pixel (x0, y0) to (x1, y1), over the scene */
void view_add_rect(struct drawlist *dl, double x0, double y0, double x1, double y1,
		   const uint8_t rgba[4]);

/* the mouse pointer: an arrow with its tip at pixel (x, y) */
void view_add_pointer(struct drawlist *dl, double x, double y);

#endif
