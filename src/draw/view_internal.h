/*
 * view_internal.h - what view.c and view_icons.c share: colours, small
 * vector helpers, and the drawing helpers of the icons. Not for other files.
 */
#ifndef POSTURE_VIEW_INTERNAL_H
#define POSTURE_VIEW_INTERNAL_H

#include <math.h>
#include <string.h>

#include "draw/view.h"

/* icon colours */
static const uint8_t C_AXIS[3][4] = { { 230, 60, 50, 255 }, { 40, 185, 70, 255 },
				      { 50, 110, 240, 255 } };
static const uint8_t C_AXIS_NEG[3][4] = { { 240, 150, 140, 255 }, { 140, 215, 150, 255 },
					  { 140, 170, 245, 255 } };
static const uint8_t C_WHEEL[4] = { 250, 200, 40, 255 };
static const uint8_t C_GREEN[4] = { 40, 200, 70, 255 };
static const uint8_t C_RED[4] = { 225, 45, 40, 255 };
static const uint8_t C_GOAL[4] = { 235, 120, 20, 255 };
static const uint8_t C_BAND[4] = { 255, 255, 255, 100 };
static const uint8_t C_WHITE[4] = { 255, 255, 255, 255 };
static const uint8_t C_BLACK[4] = { 0, 0, 0, 255 };

#define ICON_WIDTH 2.0f  /* line width of icons, pixels before icon_scale */
#define THICK_WIDTH 3.5f /* their emphasised lines */

static inline uint8_t *
with_alpha(const uint8_t c[4], uint8_t a, uint8_t dest[4])
{
	memcpy(dest, c, 3);
	dest[3] = a;
	return dest;
}

/* ---- small vector helpers ------------------------------------------------ */

static inline void
v_set(double d[3], double x, double y, double z)
{
	d[0] = x, d[1] = y, d[2] = z;
}

static inline double
v_dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void
v_cross(const double a[3], const double b[3], double d[3])
{
	double t[3] = { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
			a[0] * b[1] - a[1] * b[0] };
	memcpy(d, t, sizeof t);
}

static inline double
v_norm(const double a[3])
{
	return sqrt(v_dot(a, a));
}

/* d = a / |a|; returns |a| (d untouched when 0) */
static inline double
v_unit(const double a[3], double d[3])
{
	double l = v_norm(a);
	if (l > 0)
		v_set(d, a[0] / l, a[1] / l, a[2] / l);
	return l;
}

/* d = a + s * b */
static inline void
v_madd(const double a[3], double s, const double b[3], double d[3])
{
	v_set(d, a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]);
}

/* a unit vector perpendicular to unit a */
static inline void
v_perp(const double a[3], double d[3])
{
	double t[3] = { 1, 0, 0 };
	if (fabs(a[0]) > 0.8)
		v_set(t, 0, 1, 0);
	v_cross(a, t, d);
	v_unit(d, d);
}

/* column j of a row-major rotation */
static inline void
r_col(const double r[9], int j, double d[3])
{
	v_set(d, r[j], r[3 + j], r[6 + j]);
}

/* column-major matrix of x scaled by s along its own axes */
void view_mat_from_xform(const struct xform *x, const double s[3], float dest[16]);
void view_world_label(struct drawlist *dl, const double p[3], const char *text, const uint8_t c[4]);
void view_circle(struct drawlist *dl, const double c[3], const double a[3], const double u[3],
		 double r, int n, const uint8_t col[4]);

#endif
