/*
 * geom.h - the analytic pieces of Appendix B: the point of an axis nearest
 * the mouse line (B.1), the mouse line through a plane (B.2), the angle
 * between two spokes of a wheel (B.3), and the angle between an axis and
 * the line of sight that the 20 degree rule of section 3.7 tests.
 *
 * World metres and radians, right-handed. Directions need not have unit
 * length unless a function says so.
 */
#ifndef POSTURE_INTERACT_GEOM_H
#define POSTURE_INTERACT_GEOM_H

#include "interact/ray.h"

enum geom_hit {
	GEOM_HIT = 0,       /* an answer */
	GEOM_PARALLEL = -1, /* the lines are parallel, or the ray runs along the plane */
	GEOM_BEHIND = -2,   /* the answer lies behind the ray's origin */
	GEOM_DEGENERATE = -3, /* a zero vector where a direction was needed */
};

/*
 * The closest points of line a (pa + s da) and line b (pb + t db):
 * dest[0] = s, dest[1] = t. Returns GEOM_HIT, or GEOM_PARALLEL when the
 * directions are within about 1e-6 rad of each other (then s = 0 and t is
 * the foot of pa on b, one of the many closest pairs), or GEOM_DEGENERATE
 * when a direction is zero (dest untouched).
 */
int geom_lines_closest(const double pa[3], const double da[3], const double pb[3],
		       const double db[3], double dest[2]);

/*
 * The parameter s of the point of the axis (p + s a) nearest the ray, and
 * that point in dest (B.1). Returns GEOM_HIT, GEOM_PARALLEL (the ray runs
 * along the axis, no unique point), GEOM_BEHIND (the nearest point of the
 * ray's line lies behind its origin: the mouse points away from the axis)
 * or GEOM_DEGENERATE (a zero direction). s and dest are set on GEOM_HIT
 * only; either may be NULL.
 */
int geom_axis_nearest_ray(const double p[3], const double a[3], const struct ray *r, double *s,
			  double dest[3]);

/*
 * Where the ray meets the plane through p0 with normal n (B.2): the ray
 * parameter in *t and the point in dest, either may be NULL. Returns
 * GEOM_HIT, GEOM_PARALLEL (the ray runs along the plane, within about
 * 1e-9 of the normal's length), GEOM_BEHIND (the plane is met behind the
 * ray's origin; nothing set) or GEOM_DEGENERATE (n is zero).
 */
int geom_ray_plane(const struct ray *r, const double p0[3], const double n[3], double *t,
		   double dest[3]);

/*
 * The signed angle (-pi, pi] that turns spoke s0 into spoke s1 about axis,
 * both spokes first projected into the wheel's plane (perpendicular to the
 * axis); positive counterclockwise seen from the axis' tip (right-hand
 * rule). Returns GEOM_HIT, or GEOM_DEGENERATE when the axis or a projected
 * spoke has (almost) no length (dest untouched).
 */
int geom_spoke_angle(const double axis[3], const double s0[3], const double s1[3], double *dest);

/*
 * The angle between two lines with directions a and b, in [0, pi/2]:
 * the sign of a direction does not matter (an axis is as degenerate
 * pointing at the eye as away from it). 0 when either is zero.
 */
double geom_line_angle(const double a[3], const double b[3]);

/* the rotation matrix (row-major) turning by angle about a unit axis, right-handed */
void geom_rotation(const double axis[3], double angle, double dest[9]);

/* dest = a / |a|; returns 0, or -1 when a is zero or not finite (dest untouched) */
int geom_normalize(const double a[3], double dest[3]);

#endif
