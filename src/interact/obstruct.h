/*
 * obstruct.h - §3.7.1's decision on the visibility map (draw/hemi.h):
 * is the camera hidden from the manipulated object's origin, and if so
 * which direction nearby is clear? Pure: a map and distances in, a world
 * direction out; the daemon renders the map and turns the camera
 * (view_adjust_turn_to).
 *
 * "Obstructed": something in the map nearer to the origin than the camera
 * is, within `cone` of the line from the origin to the eye, so some of
 * the object's surroundings are hidden, not only a single line. A pixel is
 * a small square of directions, not a ray: a blocked pixel counts when
 * its centre is within cone + OBSTRUCT_PAD, so a clear direction found
 * is clear between the pixel centres too.
 *
 * The clear direction is the pixel centre nearest in angle to the camera
 * direction whose whole cone is clear and inside the map, at an elevation
 * within +-VIEWOP_ELEVATION_MAX (the camera never goes over the poles):
 * "the neighbourhood of the direction of the camera" searched outwards.
 */
#ifndef POSTURE_INTERACT_OBSTRUCT_H
#define POSTURE_INTERACT_OBSTRUCT_H

#include "draw/hemi.h"
#include "figure/model.h"
#include "figure/state.h"

#define OBSTRUCT_CONE (3.0 * M_PI / 180) /* half angle kept clear about the line of sight */
/* a pixel's half diagonal at the map's centre: how far a blocked pixel reaches past its centre */
#define OBSTRUCT_PAD (0.71 * HEMI_PITCH)

/*
 * With eye_dist the camera's distance from the origin (m) and cone a half
 * angle (radians): 0 when the camera direction (the map's centre) is
 * clear; 1 when it is obstructed, with dest the nearest clear direction
 * (world, unit, from the origin); -1 when obstructed and nothing in the
 * map is clear (dest untouched).
 */
int obstruct_check(const struct hemi_map *m, double eye_dist, double cone, double dest[3]);

/*
 * The figure's own body is an obstacle too (a hand dragged behind the
 * back is hidden by the torso), except the parts that surround the
 * origin: the segment it is on and the segments jointed to it, from
 * whose inside every direction would look blocked. Sets skip[k] for
 * those segments of m (posture s), clears the others. Returns how many
 * are set, or -1 when m has more than cap segments (skip untouched).
 */
int obstruct_own_parts(const struct model *m, const struct state *s, int seg, unsigned char *skip,
		       int cap);

#endif
