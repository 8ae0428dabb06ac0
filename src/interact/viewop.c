/* viewop.c - sweep, pan, zoom and the snap's in-betweens (see viewop.h) */
#include "interact/viewop.h"

#include <math.h>

/*
 * A camera with no twist is fixed by two angles: the heading of its x axis
 * about the world vertical, x = (cos h, 0, -sin h), and the elevation e of
 * its z axis in the vertical plane through z, z = cos e b + sin e up with
 * b = (sin h, 0, cos h) the horizontal direction across x. A turn about
 * the vertical adds to h; a turn about x by theta takes theta from e.
 */
static double
heading_of(const struct camera *c)
{
	const double *r = c->xf.r;
	return atan2(-r[6], r[0]);
}

double
viewop_elevation(const struct camera *c)
{
	const double *r = c->xf.r;
	double h = heading_of(c);
	double across = r[2] * sin(h) + r[8] * cos(h); /* z . b */
	return atan2(r[5], across);
}

/* the camera's axes from heading and elevation: orthonormal, x horizontal exactly */
static void
frame_set(struct camera *c, double heading, double elev)
{
	double sh = sin(heading), ch = cos(heading), se = sin(elev), ce = cos(elev);
	const double x[3] = { ch, 0, -sh };
	const double z[3] = { ce * sh, se, ce * ch };
	const double y[3] = { -se * sh, ce, -se * ch }; /* z x x */
	for (int i = 0; i < 3; i++) {
		c->xf.r[3 * i + 0] = x[i];
		c->xf.r[3 * i + 1] = y[i];
		c->xf.r[3 * i + 2] = z[i];
	}
}

/* the elevation after taking theta from it, kept within the limit (or not further out) */
static double
elevation_cut(double elev, double theta)
{
	double lo = fmin(-VIEWOP_ELEVATION_MAX, elev), hi = fmax(VIEWOP_ELEVATION_MAX, elev);
	return fmin(fmax(elev - theta, lo), hi);
}

/* the camera vrd along its z axis from point r */
static void
place_from(struct camera *c, const double r[3])
{
	for (int i = 0; i < 3; i++)
		c->xf.p[i] = r[i] + c->vrd * c->xf.r[3 * i + 2];
}

double
viewop_sweep_horizontal(struct camera *c, double theta_h)
{
	if (!isfinite(theta_h))
		return 0;
	double r[3], elev = viewop_elevation(c);
	view_camera_vrp(c, r);
	frame_set(c, heading_of(c) + theta_h, elev);
	place_from(c, r);
	return theta_h;
}

double
viewop_sweep_vertical(struct camera *c, double theta_v)
{
	if (!isfinite(theta_v))
		return 0;
	double r[3], elev = viewop_elevation(c), elev1 = elevation_cut(elev, theta_v);
	view_camera_vrp(c, r);
	frame_set(c, heading_of(c), elev1);
	place_from(c, r);
	return elev - elev1;
}

double
viewop_pan_horizontal(struct camera *c, double theta_h)
{
	if (!isfinite(theta_h))
		return 0;
	frame_set(c, heading_of(c) + theta_h, viewop_elevation(c));
	return theta_h;
}

double
viewop_pan_vertical(struct camera *c, double theta_v)
{
	if (!isfinite(theta_v))
		return 0;
	double elev = viewop_elevation(c), elev1 = elevation_cut(elev, theta_v);
	frame_set(c, heading_of(c), elev1);
	return elev - elev1;
}

double
viewop_zoom(struct camera *c, double theta_v)
{
	if (!isfinite(theta_v))
		return 0;
	/* a camera already nearer than the limit may only back away */
	double vrd1 = fmax(c->vrd + theta_v, fmin(VIEWOP_VRD_MIN, c->vrd));
	double moved = vrd1 - c->vrd;
	for (int i = 0; i < 3; i++)
		c->xf.p[i] += moved * c->xf.r[3 * i + 2];
	c->vrd = vrd1;
	return moved;
}

double
viewop_ease(double u)
{
	if (!(u > 0))
		return 0;
	if (u >= 1)
		return 1;
	return u * u * (3 - 2 * u);
}

int
viewop_snap_begin(struct viewop_snap *s, const struct camera *c, const double target[3],
		  uint64_t now_us)
{
	/* z towards the camera from the target: the final line of sight is -z */
	double z[3] = { c->xf.p[0] - target[0], c->xf.p[1] - target[1], c->xf.p[2] - target[2] };
	double dist = sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
	if (!isfinite(dist) || !(dist >= VIEWOP_VRD_MIN))
		return -1;
	double heading1 = atan2(z[0], z[2]), elev1 = atan2(z[1], hypot(z[0], z[2]));
	if (!(fabs(elev1) <= VIEWOP_ELEVATION_MAX))
		return -1;
	s->from = *c;
	s->heading0 = heading_of(c);
	s->elev0 = viewop_elevation(c);
	/* the shorter way round */
	s->dheading = remainder(heading1 - s->heading0, 2 * M_PI);
	s->delev = elev1 - s->elev0;
	s->vrd1 = dist;
	s->turn = fmax(fabs(s->dheading), fabs(s->delev));
	s->begin_us = now_us;
	s->progress = 0;
	return 0;
}

void
viewop_snap_at(const struct viewop_snap *s, double p, struct camera *dest)
{
	*dest = s->from;
	frame_set(dest, s->heading0 + p * s->dheading, s->elev0 + p * s->delev);
	/* exactly the distance to the target at p = 1 */
	dest->vrd = (1 - p) * s->from.vrd + p * s->vrd1;
}

int
viewop_snap_step(struct viewop_snap *s, uint64_t now_us, uint64_t total_us, double min_turn,
		 struct camera *dest)
{
	uint64_t elapsed = now_us > s->begin_us ? now_us - s->begin_us : 0;
	double p = elapsed >= total_us ? 1 : viewop_ease((double)elapsed / (double)total_us);
	/* no turn to make (the target already on the line of sight): only vrd changes */
	if (!(s->turn > 0))
		p = 1;
	else if (min_turn > 0)
		p = fmax(p, s->progress + min_turn / s->turn);
	/* a sum of minimum steps may fall short of 1 by a rounding: that is the end too */
	if (p > 1 - 1e-9)
		p = 1;
	p = fmax(p, s->progress);
	s->progress = p;
	viewop_snap_at(s, p, dest);
	return p < 1;
}
