/*
 * view_adjust.h - the automatic viewing adjustment of §3.7: when the user
 * selects again an axis the 20 degree rule refused, the camera turns about
 * a vertical and a horizontal axis through the object's origin, both at
 * once, until the line of sight is clear of the axis, and focuses on the
 * origin; eased in and out over about a second of real time whatever the
 * frame rate, with a least turn per frame so a slow display still ends.
 *
 * "Clear": translating along an axis wants the line of sight at least
 * `limit` from it; turning about an axis (or moving in a plane, given by
 * its normal) wants the axis at least `limit` from perpendicular to the
 * line of sight, so the wheel (or plane) is not seen edge-on. The turn is
 * the least that gets there, plus a degree of margin so the operator's
 * strict check passes. Pure: cameras and times in, cameras out; never a
 * twist (every in-between is aimed with view_camera_aim).
 */
#ifndef POSTURE_INTERACT_VIEW_ADJUST_H
#define POSTURE_INTERACT_VIEW_ADJUST_H

#include <stdint.h>

#include "draw/view.h"

enum view_adjust_kind {
	VIEW_ADJUST_ALONG,  /* translating along the axis: keep the line of sight off it */
	VIEW_ADJUST_ACROSS, /* a wheel or a plane with this normal: keep it off edge-on */
};

#define VIEW_ADJUST_MARGIN (1.0 * M_PI / 180) /* past the limit, so the strict check passes */
#define VIEW_ADJUST_US 1000000                /* about a second of real time (§3.7) */
#define VIEW_ADJUST_MIN_TURN (0.1 * M_PI / 180) /* the least turn a frame, for slow displays */

struct view_adjust {
	int active;
	struct camera from, to; /* the camera before, and the one it ends as */
	double origin[3];       /* the object's origin: the pivot, and the last reference point */
	double r0[3];           /* the reference point before */
	double h0, e0, dh, de;  /* heading and elevation of the eye about the origin, and the turn */
	double d0, d1;          /* the eye's distance from the origin, before and after */
	double turn;            /* max(|dh|, |de|): what the least step is measured on */
	uint64_t begin_us;
	double progress;        /* eased, 0 .. 1, never decreasing */
};

/*
 * Plans the adjustment of camera cam for an axis (world, unit) at origin:
 * returns 1 and fills va when the camera must turn, 0 when the line of
 * sight is already clear (va->active 0), -1 when nothing can be done (the
 * eye on the origin, non-finite input).
 */
int view_adjust_begin(struct view_adjust *va, const struct camera *cam, const double origin[3],
		      const double axis[3], enum view_adjust_kind kind, double limit,
		      uint64_t now_us);

/*
 * The in-between for now_us (total_us the whole time, min_turn the least
 * turn a step makes, radians), into dest. Returns 1 while more follow, 0
 * for the last (dest is va->to, va->active 0).
 */
int view_adjust_step(struct view_adjust *va, uint64_t now_us, uint64_t total_us, double min_turn,
		     struct camera *dest);

/*
 * §3.7 also focuses the view on an object whose origin is not visible: the
 * camera stays where it is and turns (eased, VIEW_ADJUST_US) until its
 * reference point is the origin. Returns 1, or -1 when the eye is on it.
 */
int view_adjust_focus(struct view_adjust *va, const struct camera *cam, const double origin[3],
		      uint64_t now_us);

/*
 * §3.7.1: the eye turned about the origin until it lies along dir (world,
 * any length) from it, at the same distance, and aimed at the origin;
 * eased like the others, heading and elevation at once (elevation kept
 * within +-VIEWOP_ELEVATION_MAX). Returns 1, 0 when the eye is already
 * there (within VIEW_ADJUST_MIN_TURN; va->active 0), -1 for the eye on
 * the origin or a zero direction.
 */
int view_adjust_turn_to(struct view_adjust *va, const struct camera *cam, const double origin[3],
			const double dir[3], uint64_t now_us);

/* 1 when p is in front of the camera and inside its w x h picture, 0 when not */
int view_adjust_visible(const struct camera *cam, int w, int h, const double p[3]);

/*
 * 1 when p is in front of the camera and at least `margin` (a fraction of
 * the picture's half width and half height) inside its edges: where a
 * dragged object may go before the view follows it.
 */
int view_adjust_inside(const struct camera *cam, int w, int h, const double p[3], double margin);

/* the angle between the line of sight from cam's eye to p and the axis, folded to 0..90 degrees */
double view_adjust_sight_angle(const struct camera *cam, const double p[3], const double axis[3]);

#endif
