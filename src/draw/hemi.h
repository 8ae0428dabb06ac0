/*
 * hemi.h - the visibility map of §3.7.1: what the environment looks like
 * from the manipulated object's origin towards the camera, one object id
 * and one distance per pixel. render_hemicube (render.h) fills it; the
 * obstruction check (interact/obstruct.h) reads it.
 *
 * The dissertation borrows radiosity's hemicube (five faces of a cube, a
 * whole hemisphere). This map is one square perspective frustum of
 * HEMI_FOV instead: §3.7.1 only looks "in the neighbourhood of the
 * direction of the camera", and a turn of more than 60 degrees would not
 * be the slight change the adjustments are meant to be (§3.9), so the
 * four side faces would only be searched to be rejected. One frustum is
 * one pass over the instances instead of five, and its pixels are
 * directions the search can walk without seams between faces. At
 * HEMI_N = 64 a pixel is about 2.6 degrees at the centre (1.3 at the
 * corners), finer than the cone the check keeps clear.
 */
#ifndef POSTURE_HEMI_H
#define POSTURE_HEMI_H

#include <stdint.h>

#include "draw/view.h"

#define HEMI_N 96                        /* pixels a side */
#define HEMI_FOV (120.0 * M_PI / 180)    /* the frustum's full angle, both ways */
#define HEMI_PITCH (2 * tan(HEMI_FOV / 2) / HEMI_N) /* a pixel at the centre, radians */
#define HEMI_ZNEAR 0.01                  /* m: nearer geometry is not seen */
#define HEMI_ZFAR 200.0

struct hemi_map {
	/* eye at the origin, looking towards the camera (view_camera_aim: no twist) */
	struct camera cam;
	/* rows top to bottom: view_id() of what the pixel's ray hits first, 0 for nothing */
	uint32_t id[HEMI_N * HEMI_N];
	/* the distance from the origin to that hit along the pixel's ray, m (INFINITY: nothing) */
	float dist[HEMI_N * HEMI_N];
};

/*
 * The map's camera at origin looking along dir (any length): returns 0, or
 * -1 (cam unchanged) when dir is zero or not finite.
 */
int hemi_camera(struct camera *cam, const double origin[3], const double dir[3]);

/* the unit world direction of the ray through the centre of pixel (px, py) */
void hemi_pixel_dir(const struct hemi_map *m, int px, int py, double dest[3]);

#endif
