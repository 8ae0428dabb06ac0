/* view_adjust.c - §3.7's automatic viewing adjustment (see view_adjust.h) */
#include "interact/view_adjust.h"

#include <math.h>
#include <string.h>

#include "interact/viewop.h"

static double
dot3(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* a / |a| into dest; its length, 0 (dest untouched) for a zero or non-finite vector */
static double
unit3(const double a[3], double dest[3])
{
	double n = sqrt(dot3(a, a));
	if (!(n > 1e-12) || !isfinite(n))
		return 0;
	for (int k = 0; k < 3; k++)
		dest[k] = a[k] / n;
	return n;
}

double
view_adjust_sight_angle(const struct camera *cam, const double p[3], const double axis[3])
{
	double d[3] = { p[0] - cam->xf.p[0], p[1] - cam->xf.p[1], p[2] - cam->xf.p[2] }, u[3];
	if (!unit3(d, u)) /* the eye on the point: the camera's own line of sight */
		for (int k = 0; k < 3; k++)
			u[k] = -cam->xf.r[3 * k + 2];
	double c = fabs(dot3(u, axis));
	return acos(c > 1 ? 1 : c);
}

/* the eye's direction from the origin as heading (about y, from +z) and elevation */
static void
heading_elevation(const double u[3], double *h, double *e)
{
	*h = atan2(u[0], u[2]);
	*e = asin(u[1] > 1 ? 1 : u[1] < -1 ? -1 : u[1]);
}

static double
wrap_pi(double a)
{
	while (a > M_PI)
		a -= 2 * M_PI;
	while (a <= -M_PI)
		a += 2 * M_PI;
	return a;
}

/*
 * u (the eye's direction from the origin, unit) turned in the plane of u
 * and the axis until its angle to the axis line is want; w is the turn's
 * direction away from the axis when u lies on it.
 */
static void
turn_to_angle(const double u[3], const double axis[3], const double w_fallback[3], double want,
	      double dest[3])
{
	double c = dot3(u, axis), s = c < 0 ? -1 : 1, perp[3], w[3];
	for (int k = 0; k < 3; k++)
		perp[k] = u[k] - c * axis[k];
	if (!unit3(perp, w)) {
		double pf[3], cf = dot3(w_fallback, axis);
		for (int k = 0; k < 3; k++)
			pf[k] = w_fallback[k] - cf * axis[k];
		if (!unit3(pf, w)) { /* any direction off the axis */
			double t[3] = { axis[1], axis[2], axis[0] };
			double ct = dot3(t, axis);
			for (int k = 0; k < 3; k++)
				pf[k] = t[k] - ct * axis[k];
			unit3(pf, w);
		}
	}
	for (int k = 0; k < 3; k++)
		dest[k] = s * cos(want) * axis[k] + sin(want) * w[k];
}

/* the camera at progress p: eye on the sphere about the origin, aimed between r0 and the origin */
static void
view_adjust_at(const struct view_adjust *va, double p, struct camera *dest)
{
	double h = va->h0 + p * va->dh, e = va->e0 + p * va->de, d = va->d0 + p * (va->d1 - va->d0);
	double eye[3] = { va->origin[0] + d * cos(e) * sin(h), va->origin[1] + d * sin(e),
			  va->origin[2] + d * cos(e) * cos(h) };
	double r[3];
	for (int k = 0; k < 3; k++)
		r[k] = va->r0[k] + p * (va->origin[k] - va->r0[k]);
	*dest = va->from;
	if (view_camera_aim(dest, eye, r) < 0) /* the eye on the moving reference point */
		view_camera_aim(dest, eye, va->origin);
}

/* the eye's direction from origin (unit, into u) and its distance; 0 when the eye is on it */
static double
eye_from(const struct camera *cam, const double origin[3], double u[3])
{
	double d[3];
	for (int k = 0; k < 3; k++)
		d[k] = cam->xf.p[k] - origin[k];
	return unit3(d, u);
}

/* the rest of va for a turn of cam about origin at distance dist (h0, e0, dh, de set), started */
static int
adjust_start(struct view_adjust *va, const struct camera *cam, const double origin[3], double dist,
	     uint64_t now_us)
{
	va->d0 = va->d1 = dist;
	va->from = *cam;
	memcpy(va->origin, origin, sizeof va->origin);
	view_camera_vrp(cam, va->r0);
	va->turn = fmax(fabs(va->dh), fabs(va->de));
	va->begin_us = now_us;
	va->active = 1;
	view_adjust_at(va, 1, &va->to);
	return 1;
}

int
view_adjust_begin(struct view_adjust *va, const struct camera *cam, const double origin[3],
		  const double axis[3], enum view_adjust_kind kind, double limit, uint64_t now_us)
{
	memset(va, 0, sizeof *va);
	double a[3], u[3], dist = eye_from(cam, origin, u);
	if (!unit3(axis, a) || !dist || !isfinite(limit))
		return -1;
	double angle = acos(fmin(1, fabs(dot3(u, a)))); /* the line of sight to the axis line */
	double want;
	if (kind == VIEW_ADJUST_ALONG) {
		if (angle >= limit)
			return 0;
		want = limit + VIEW_ADJUST_MARGIN;
	} else {
		if (angle <= M_PI / 2 - limit)
			return 0;
		want = M_PI / 2 - limit - VIEW_ADJUST_MARGIN;
	}
	/* away from (or towards) the axis in their plane; on the axis, towards the camera's up */
	double up[3] = { cam->xf.r[1], cam->xf.r[4], cam->xf.r[7] }, u1[3];
	turn_to_angle(u, a, up, want, u1);
	double h1, e1;
	heading_elevation(u, &va->h0, &va->e0);
	heading_elevation(u1, &h1, &e1);
	if (e1 > VIEWOP_ELEVATION_MAX) /* never over the poles: as close as the camera may go */
		e1 = VIEWOP_ELEVATION_MAX;
	if (e1 < -VIEWOP_ELEVATION_MAX)
		e1 = -VIEWOP_ELEVATION_MAX;
	va->dh = wrap_pi(h1 - va->h0);
	va->de = e1 - va->e0;
	return adjust_start(va, cam, origin, dist, now_us);
}

int
view_adjust_step(struct view_adjust *va, uint64_t now_us, uint64_t total_us, double min_turn,
		 struct camera *dest)
{
	if (!va->active) {
		*dest = va->to;
		return 0;
	}
	double u = total_us ? (double)(now_us - va->begin_us) / (double)total_us : 1;
	double p = viewop_ease(u < 0 ? 0 : u > 1 ? 1 : u);
	if (va->turn > 0 && p < va->progress + min_turn / va->turn)
		p = va->progress + min_turn / va->turn; /* a slow display still gets there */
	if (p >= 1 || now_us - va->begin_us >= total_us) {
		va->progress = 1;
		va->active = 0;
		*dest = va->to;
		return 0;
	}
	va->progress = p;
	view_adjust_at(va, p, dest);
	return 1;
}

int
view_adjust_focus(struct view_adjust *va, const struct camera *cam, const double origin[3],
		  uint64_t now_us)
{
	memset(va, 0, sizeof *va);
	double u[3], dist = eye_from(cam, origin, u);
	if (!dist)
		return -1;
	heading_elevation(u, &va->h0, &va->e0); /* the eye stays: no turn about the origin */
	return adjust_start(va, cam, origin, dist, now_us);
}

int
view_adjust_turn_to(struct view_adjust *va, const struct camera *cam, const double origin[3],
		    const double dir[3], uint64_t now_us)
{
	memset(va, 0, sizeof *va);
	double u[3], u1[3], dist = eye_from(cam, origin, u);
	if (!dist || !unit3(dir, u1))
		return -1;
	double h1, e1;
	heading_elevation(u, &va->h0, &va->e0);
	heading_elevation(u1, &h1, &e1);
	e1 = fmax(-VIEWOP_ELEVATION_MAX, fmin(VIEWOP_ELEVATION_MAX, e1));
	va->dh = wrap_pi(h1 - va->h0);
	va->de = e1 - va->e0;
	if (fmax(fabs(va->dh), fabs(va->de)) < VIEW_ADJUST_MIN_TURN)
		return 0;
	return adjust_start(va, cam, origin, dist, now_us);
}

int
view_adjust_visible(const struct camera *cam, int w, int h, const double p[3])
{
	return view_adjust_inside(cam, w, h, p, 0);
}

int
view_adjust_inside(const struct camera *cam, int w, int h, const double p[3], double margin)
{
	double d[3] = { p[0] - cam->xf.p[0], p[1] - cam->xf.p[1], p[2] - cam->xf.p[2] }, c[3];
	for (int k = 0; k < 3; k++) /* into the camera's frame: columns of r are its axes */
		c[k] = d[0] * cam->xf.r[k] + d[1] * cam->xf.r[3 + k] + d[2] * cam->xf.r[6 + k];
	if (!(-c[2] > cam->znear) || w <= 0 || h <= 0)
		return 0;
	double t = tan(cam->fovy / 2), aspect = (double)w / h;
	double x = c[0] / (-c[2] * t * aspect), y = c[1] / (-c[2] * t);
	return fabs(x) <= 1 - margin && fabs(y) <= 1 - margin;
}
