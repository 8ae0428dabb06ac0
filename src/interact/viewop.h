/*
 * viewop.h - Appendix C's ways of moving a camera (C.2 sweep, pan, zoom;
 * C.3 the snap's in-betweens), as pure functions on struct camera.
 *
 * The camera is C.1.3's (draw/view.h): camera to world, -z the line of
 * sight, vrd the view reference distance; the view reference point R lies
 * vrd along the line of sight. In the dissertation's notation (row
 * vectors, position in the bottom row):
 *
 *   sweep   C' = T D R, T = C R^-1: the camera turns by D about R, which
 *           stays put (and vrd with it);
 *   pan     C' = R D: the camera turns by D about its own origin, carrying
 *           R with it at the same distance;
 *   zoom    C'p = Cp + theta_v Cz: the camera slides along its z axis and
 *           vrd changes by as much, so R stays put.
 *
 * D is R_y(theta_h), a right-hand turn about the world's vertical, or
 * R_Cx(theta_v), a right-hand turn about the camera's own x axis. Angles
 * are radians, distances metres; mapping pixels to them is viewctl's job.
 *
 * Never a twist (C.1.2): every function leaves the camera's x axis exactly
 * horizontal (its y component 0) and its frame orthonormal, rebuilt from a
 * heading and an elevation each time so that no drift accumulates. The
 * elevation (the angle of the camera's z axis above the horizontal: the
 * camera's height above R as an angle in a sweep) stays within
 * VIEWOP_ELEVATION_MAX, short of the poles where "horizontal x" would lose
 * its meaning. Cameras are assumed upright (y . world y >= 0), as
 * view_camera_aim makes them and as these functions keep them.
 */
#ifndef POSTURE_INTERACT_VIEWOP_H
#define POSTURE_INTERACT_VIEWOP_H

#include <stdint.h>

#include "draw/view.h"

/* how far above or below the horizon the camera may turn: 1 degree short of the poles */
#define VIEWOP_ELEVATION_MAX (89.0 * M_PI / 180)
/* the nearest a zoom brings the camera to its reference point, m */
#define VIEWOP_VRD_MIN 0.01

/* the camera's elevation, radians: atan2 of z's vertical against its horizontal part */
double viewop_elevation(const struct camera *c);

/*
 * Sweep (C.2.1.2) about the world vertical through R by theta_h: R, vrd and
 * the elevation stay. Returns theta_h.
 */
double viewop_sweep_horizontal(struct camera *c, double theta_h);

/*
 * Sweep about the camera's x axis through R by theta_v (a positive angle
 * lowers the camera): R, vrd and the heading stay. theta_v is cut so the
 * elevation ends within +-VIEWOP_ELEVATION_MAX (a camera already beyond it
 * may only turn back towards it). Returns the angle turned.
 */
double viewop_sweep_vertical(struct camera *c, double theta_v);

/*
 * Pan (C.2.2.2) about the world vertical through the camera's origin by
 * theta_h (positive turns the line of sight to the left): the position,
 * vrd and the elevation stay; R circles the camera. Returns theta_h.
 */
double viewop_pan_horizontal(struct camera *c, double theta_h);

/*
 * Pan about the camera's own x axis by theta_v (positive raises the line
 * of sight), cut like viewop_sweep_vertical. Returns the angle turned.
 */
double viewop_pan_vertical(struct camera *c, double theta_v);

/*
 * Zoom (C.2.3.2): the camera moves theta_v metres along its +z axis (back,
 * away from R; negative moves in) and vrd grows by as much, so R stays.
 * The move is cut so vrd stays at least VIEWOP_VRD_MIN (a camera already
 * nearer may only back away). Returns the distance moved.
 */
double viewop_zoom(struct camera *c, double theta_v);

/*
 * The snap (C.3): the camera pivots about its origin, about the world
 * vertical and its own horizontal axis together, until its line of sight
 * passes through the target, which becomes R (vrd the distance to it).
 * In-between views come from an eased progress p in [0, 1]: heading and
 * elevation each advance by ease(p) of their whole turn (the shorter way
 * round) and vrd by the same share of its change.
 */
struct viewop_snap {
	struct camera from;  /* the camera when the snap began */
	double heading0, elev0;   /* of from, radians */
	double dheading, delev;   /* the whole turn, radians; |dheading| <= pi */
	double vrd1;              /* the distance to the target */
	double turn;              /* max(|dheading|, |delev|): what the minimum step is measured on */
	uint64_t begin_us;
	double progress;          /* eased, 0 .. 1, never decreasing */
};

/*
 * Starts a snap of camera c to target at time now_us. Returns 0, or -1
 * (s untouched) when the target is not finite, nearer than VIEWOP_VRD_MIN,
 * or so nearly above or below the camera that aiming at it would take the
 * elevation past VIEWOP_ELEVATION_MAX.
 */
int viewop_snap_begin(struct viewop_snap *s, const struct camera *c, const double target[3],
		      uint64_t now_us);

/*
 * The in-between for time now_us: progress is ease(elapsed / total_us),
 * but at least min_turn radians more than at the previous step (measured
 * on s->turn), so small snaps need not take the whole time; it reaches 1
 * once total_us has passed. dest gets the view at that progress. Returns
 * 1 while more in-betweens follow, 0 when dest is the final view.
 */
int viewop_snap_step(struct viewop_snap *s, uint64_t now_us, uint64_t total_us, double min_turn,
		     struct camera *dest);

/* the view at progress p (0 .. 1, already eased) of snap s */
void viewop_snap_at(const struct viewop_snap *s, double p, struct camera *dest);

/* the ease-in / ease-out of the in-betweens: 3u^2 - 2u^3 on [0, 1] */
double viewop_ease(double u);

#endif
