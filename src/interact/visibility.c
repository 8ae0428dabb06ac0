/* visibility.c - a target's place in a manikin's sight and its share seen (see visibility.h) */
#include "interact/visibility.h"

#include <math.h>
#include <string.h>

static double
dot3(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double
clamp(double x, double lo, double hi)
{
	return x < lo ? lo : x > hi ? hi : x;
}

/* the direction of Fick angles (yaw, then pitch) in the head's frame */
static void
fick_dir(double yaw, double pitch, double dest[3])
{
	dest[0] = sin(yaw) * cos(pitch);
	dest[1] = sin(pitch);
	dest[2] = cos(yaw) * cos(pitch);
}

int
vis_fixate(const double eye[3], const double dir[3], const double head_r[9],
	   const struct vis_limits *lim, const double p[3], struct vis_fixation *dest)
{
	double w[3] = { p[0] - eye[0], p[1] - eye[1], p[2] - eye[2] }, n = sqrt(dot3(w, w));
	if (!(n > 1e-9))
		return -1;
	double u[3] = { w[0] / n, w[1] / n, w[2] / n }, h[3];
	dest->angle = acos(clamp(dot3(u, dir), -1, 1)) * 180 / M_PI;
	/* the direction in the head's frame: head_r's columns are its axes in the world */
	for (int i = 0; i < 3; i++)
		h[i] = head_r[i] * u[0] + head_r[3 + i] * u[1] + head_r[6 + i] * u[2];
	double yaw = atan2(h[0], h[2]), pitch = asin(clamp(h[1], -1, 1));
	double ey = clamp(yaw, lim->yaw_lo, lim->yaw_hi), ep = clamp(pitch, lim->pitch_lo,
								      lim->pitch_hi);
	double hy = 0, hp = 0;
	if (ey != yaw || ep != pitch) {
		/*
		 * The head turns the eyes' gaze g (at their limits) onto u: a pitch
		 * of the head brings g's height to u's (g_y cos hp + g_z sin hp =
		 * u_y, the smaller turn of the two), then a yaw about the head's
		 * vertical, which keeps heights, brings it round. A pitch keeps
		 * g_x, so u's height is within reach when |g_x| <= cos(pitch): the
		 * eyes' yaw is held to that (towards a point far up or down the
		 * head does the turning).
		 */
		double lim_x = cos(pitch) / cos(ep);
		if (fabs(sin(ey)) > lim_x)
			ey = copysign(asin(clamp(lim_x, 0, 1)), ey);
		double g[3], v[3];
		fick_dir(ey, ep, g);
		double r = hypot(g[1], g[2]), a = atan2(g[2], g[1]), c = h[1] / r;
		double t = acos(clamp(c, -1, 1)), h1 = a - t, h2 = a + t;
		h1 = remainder(h1, 2 * M_PI);
		h2 = remainder(h2, 2 * M_PI);
		hp = fabs(h1) <= fabs(h2) ? h1 : h2;
		v[0] = g[0];
		v[1] = g[1] * cos(hp) + g[2] * sin(hp);
		v[2] = -g[1] * sin(hp) + g[2] * cos(hp);
		hy = remainder(atan2(h[0], h[2]) - atan2(v[0], v[2]), 2 * M_PI);
	}
	dest->eye_yaw = ey * 180 / M_PI;
	dest->eye_pitch = ep * 180 / M_PI;
	dest->head_yaw = hy * 180 / M_PI;
	dest->head_pitch = hp * 180 / M_PI;
	return 0;
}

int
vis_cone(double angle, const double *cones, int n)
{
	int best = -1;
	for (int i = 0; i < n; i++)
		if (angle <= cones[i] / 2 && (best < 0 || cones[i] < cones[best]))
			best = i;
	return best;
}

int
vis_map_camera(struct camera *cam, const double eye[3], const double c[3], double r)
{
	double d[3] = { c[0] - eye[0], c[1] - eye[1], c[2] - eye[2] }, n = sqrt(dot3(d, d));
	if (!(n > r * VIS_MAP_MARGIN))
		return -1;
	double fov = 2 * asin(r * VIS_MAP_MARGIN / n);
	if (fov > VIS_MAP_FOV_MAX)
		return -1;
	struct camera k;
	if (hemi_camera(&k, eye, d) < 0)
		return -1;
	/* a square map: its field both ways covers the sphere's cone */
	k.fovy = fov;
	*cam = k;
	return 0;
}

/* what pixel i of the target's silhouette shows: 0 not the target, 1 seen, 2 hidden */
static int
pixel_class(const struct hemi_map *alone, const struct hemi_map *all, uint32_t target, int i)
{
	if (alone->id[i] != target)
		return 0;
	return all->id[i] == target ? 1 : 2;
}

void
vis_coverage(const struct hemi_map *alone, const struct hemi_map *all, uint32_t target,
	     struct vis_coverage *dest)
{
	memset(dest, 0, sizeof *dest);
	const double t = tan(alone->cam.fovy / 2), pixel = 2 * t / HEMI_N;
	double whole = 0, seen = 0, edge = 0;
	for (int y = 0; y < HEMI_N; y++)
		for (int x = 0; x < HEMI_N; x++) {
			int i = y * HEMI_N + x, k = pixel_class(alone, all, target, i);
			if (!k)
				continue;
			/* the pixel's solid angle: its area on the unit image plane times cos^3 */
			double xn = (2 * (x + 0.5) / HEMI_N - 1) * t, yn = (1 - 2 * (y + 0.5) / HEMI_N) * t;
			double w = pixel * pixel / pow(1 + xn * xn + yn * yn, 1.5);
			whole += w;
			dest->pixels++;
			int differs = 0;
			static const int dx[4] = { 1, -1, 0, 0 }, dy[4] = { 0, 0, 1, -1 };
			for (int q = 0; q < 4; q++) {
				int x2 = x + dx[q], y2 = y + dy[q];
				differs |= x2 < 0 || y2 < 0 || x2 >= HEMI_N || y2 >= HEMI_N ||
					   pixel_class(alone, all, target, y2 * HEMI_N + x2) != k;
			}
			if (differs) {
				dest->edge_pixels++;
				edge += w;
			}
			if (k == 1) {
				seen += w;
				continue;
			}
			/* hidden: by what the map of everything shows there (0: nothing nearer) */
			uint32_t id = all->id[i];
			int j = 0;
			while (j < dest->nocc && dest->occ[j].id != id)
				j++;
			if (j == dest->nocc && j < VIS_MAX_OCCLUDERS)
				dest->occ[dest->nocc++].id = id;
			if (j < VIS_MAX_OCCLUDERS)
				dest->occ[j].fraction += w;
			else
				dest->others += w;
		}
	dest->solid_angle = whole;
	if (!(whole > 0))
		return;
	dest->fraction = seen / whole;
	dest->edge_share = edge / whole;
	dest->others /= whole;
	for (int j = 0; j < dest->nocc; j++)
		dest->occ[j].fraction /= whole;
	/* the largest share first (a handful: insertion) */
	for (int j = 1; j < dest->nocc; j++)
		for (int k = j; k > 0 && dest->occ[k - 1].fraction < dest->occ[k].fraction; k--) {
			struct vis_occluder s = dest->occ[k];
			dest->occ[k] = dest->occ[k - 1];
			dest->occ[k - 1] = s;
		}
}
