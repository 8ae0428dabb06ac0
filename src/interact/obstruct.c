/* obstruct.c - §3.7.1's obstruction check on the visibility map (see obstruct.h) */
#include "interact/obstruct.h"

#include <math.h>

#include "interact/viewop.h"

/* pixel i hides what lies at eye_dist along its ray */
static int
blocked(const struct hemi_map *m, int i, double eye_dist)
{
	return m->id[i] && m->dist[i] < eye_dist;
}

/* the unit direction of pixel (x, y)'s centre in the map camera's frame (-z: the camera) */
static void
pixel_dir(int x, int y, double dest[3])
{
	double t = tan(HEMI_FOV / 2);
	double v[3] = { (2 * (x + 0.5) / HEMI_N - 1) * t, (1 - 2 * (y + 0.5) / HEMI_N) * t, -1 };
	double n = sqrt(v[0] * v[0] + v[1] * v[1] + 1);
	for (int k = 0; k < 3; k++)
		dest[k] = v[k] / n;
}

static double
angle(const double a[3], const double b[3])
{
	double c = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
	return acos(c > 1 ? 1 : c < -1 ? -1 : c);
}

/*
 * 1 when no blocked pixel lies within reach (radians) of u (map frame),
 * the pixel (cx, cy). Only a window of pixels can: a pixel's angular size
 * shrinks away from the centre as 1 / (1 + r^2) at most (r: tan of the
 * angle off the axis), so the window is sized by the pitch found a reach
 * further out than u.
 */
static int
cone_clear(const struct hemi_map *m, const double u[3], int cx, int cy, double reach,
	   double eye_dist)
{
	double off = acos(-u[2]) + reach, rr = off < M_PI / 2 - 0.01 ? tan(off) : 100;
	int r = (int)ceil(reach * (1 + rr * rr) / HEMI_PITCH) + 1;
	double c = cos(reach);
	for (int y = cy - r; y <= cy + r; y++) {
		if (y < 0 || y >= HEMI_N)
			continue;
		for (int x = cx - r; x <= cx + r; x++) {
			if (x < 0 || x >= HEMI_N || !blocked(m, y * HEMI_N + x, eye_dist))
				continue;
			double v[3];
			pixel_dir(x, y, v);
			if (u[0] * v[0] + u[1] * v[1] + u[2] * v[2] > c)
				return 0;
		}
	}
	return 1;
}

int
obstruct_check(const struct hemi_map *m, double eye_dist, double cone, double dest[3])
{
	const double ahead[3] = { 0, 0, -1 }, reach = cone + OBSTRUCT_PAD;
	if (cone_clear(m, ahead, HEMI_N / 2, HEMI_N / 2, reach, eye_dist))
		return 0;
	/* the inscribed cone of the map: a direction's own cone must stay inside it */
	const double inside = HEMI_FOV / 2 - reach;
	const double *R = m->cam.xf.r;
	double best = INFINITY;
	int bx = -1, by = -1;
	for (int y = 0; y < HEMI_N; y++)
		for (int x = 0; x < HEMI_N; x++) {
			double u[3];
			pixel_dir(x, y, u);
			double a = angle(u, ahead);
			if (a >= best || a > inside)
				continue;
			/* its elevation in the world: never past the camera's limit */
			double wy = R[3] * u[0] + R[4] * u[1] + R[5] * u[2];
			if (fabs(wy) > sin(VIEWOP_ELEVATION_MAX))
				continue;
			if (cone_clear(m, u, x, y, reach, eye_dist)) {
				best = a;
				bx = x;
				by = y;
			}
		}
	if (bx < 0)
		return -1;
	hemi_pixel_dir(m, bx, by, dest);
	return 1;
}

int
obstruct_own_parts(const struct model *m, const struct state *s, int seg, unsigned char *skip,
		   int cap)
{
	if (m->nseg > cap || seg < 0 || seg >= m->nseg)
		return -1;
	int n = 0;
	for (int k = 0; k < m->nseg; k++) {
		skip[k] = k == seg || s->seg_parent[k] == seg || s->seg_parent[seg] == k;
		n += skip[k];
	}
	return n;
}
