/*
 * visibility.h - what `analyze visibility FIG TARGET` works out, apart from
 * the rendering: where a target lies from a manikin's line of sight, which
 * of its cones it falls in, how far the eyes and then the head must turn to
 * look at it, and how much of it two id maps (hemi.h) show. Pure: no GL;
 * the daemon renders the maps (render_hemicube) and calls these.
 *
 * Angles follow the human's eye joints (figure/human_data.c: "eye", Fick
 * order): yaw about the head's y axis, positive towards its +x (the
 * figure's left), then pitch about the turned x axis, positive up. With
 * both at 0 the eye looks along the head's +z.
 *
 * The fraction visible is by solid angle: the target's pixels in a map of
 * it alone (its silhouette from the eye) and, of those, the ones where the
 * map of every figure still shows it, each pixel weighted by the solid
 * angle it subtends (cos^3 of its angle off the map's axis, a pinhole's
 * law). A pixel counts by its centre's ray, so the answer is exact to the
 * pixels along the target's and the occluders' edges.
 */
#ifndef POSTURE_INTERACT_VISIBILITY_H
#define POSTURE_INTERACT_VISIBILITY_H

#include <stdint.h>

#include "draw/hemi.h"

#define VIS_MAX_OCCLUDERS 16 /* occluders named one by one; the rest counted together */
#define VIS_MAP_MARGIN 1.02  /* the map's field: the target's bounding sphere and 2 % more */
#define VIS_MAP_FOV_MAX (150.0 * M_PI / 180) /* a wider map would spread pixels too thin */

/* the eyes' range about the head (radians): from the eye joints' limits */
struct vis_limits {
	double yaw_lo, yaw_hi, pitch_lo, pitch_hi;
};

/*
 * Looking at a point: its angle from the line of sight now, the eyes'
 * turn in the head that looks at it (within their limits), and the head's
 * turn about the eye for the rest (0 when the eyes reach): the head turned
 * by yaw about its y axis, then by pitch about its turned x axis, the eyes
 * by their angles in it, the line of sight passes through the point
 * exactly. Degrees.
 */
struct vis_fixation {
	double angle;               /* between the line of sight and the point */
	double eye_yaw, eye_pitch;  /* the eyes' angles in the head that fixate */
	double head_yaw, head_pitch; /* the head's turn, yaw then pitch, about the eye */
};

/*
 * For the eye at eye looking along dir (unit), the head's rotation head_r
 * (row-major, world from head; +z ahead, +y up) and the eyes' range lim:
 * the fixation of point p (not at the eye). Returns 0, or -1 when p is at
 * the eye (dest untouched).
 */
int vis_fixate(const double eye[3], const double dir[3], const double head_r[9],
	       const struct vis_limits *lim, const double p[3], struct vis_fixation *dest);

/*
 * The narrowest of the n cones (full angles, degrees) that holds a point
 * angle degrees off the line of sight (on its rim counts): its index, or
 * -1 when none does.
 */
int vis_cone(double angle, const double *cones, int n);

/*
 * An id map's camera (hemi.h's near and far planes) at eye aimed at the
 * centre c of a sphere of radius r, its field just covering the sphere
 * (VIS_MAP_MARGIN). Returns 0, or -1 when the eye is inside the sphere or
 * the field would be wider than VIS_MAP_FOV_MAX (cam untouched).
 */
int vis_map_camera(struct camera *cam, const double eye[3], const double c[3], double r);

struct vis_occluder {
	uint32_t id;     /* view_id() of what hides part of the target */
	double fraction; /* of the target's solid angle it hides */
};

struct vis_coverage {
	double fraction;    /* of the target's solid angle seen; 0 when it shows no pixel */
	int pixels;         /* the target's pixels in the map of it alone */
	int edge_pixels;    /* of those, the ones with a neighbour that differs (seen or not) */
	double edge_share;  /* their share of the target's solid angle: the fraction's resolution */
	double solid_angle; /* the target's, steradians */
	int nocc;           /* occluders, the largest share first */
	struct vis_occluder occ[VIS_MAX_OCCLUDERS];
	double others;      /* the share hidden by occluders beyond the table */
};

/*
 * The target's share seen: alone is the map with only the target drawn
 * (view id target), all the map with every figure, both through the same
 * camera. Fills dest; allocates nothing.
 */
void vis_coverage(const struct hemi_map *alone, const struct hemi_map *all, uint32_t target,
		  struct vis_coverage *dest);

#endif
