/*
 * geom.c - closest points, ray and plane, spoke angles (Appendix B).
 */
#include "interact/geom.h"

#include <math.h>

#include "figure/mathx.h"

/* sin^2 of the angle below which two lines count as parallel (about 1e-6 rad) */
#define PARALLEL_SIN2 1e-12
/* |d . n| / |n| below which a unit ray runs along a plane */
#define PARALLEL_COS 1e-9
/* squared length (m^2) below which a spoke has no direction */
#define SPOKE_MIN2 1e-24

static void
sub(const double a[3], const double b[3], double dest[3])
{
	for (int i = 0; i < 3; i++)
		dest[i] = a[i] - b[i];
}

int
geom_normalize(const double a[3], double dest[3])
{
	double n = sqrt(mathx_dot(a, a));
	if (!(n > 0) || !isfinite(n))
		return -1;
	for (int i = 0; i < 3; i++)
		dest[i] = a[i] / n;
	return 0;
}

int
geom_lines_closest(const double pa[3], const double da[3], const double pb[3],
		   const double db[3], double dest[2])
{
	double w[3];
	sub(pa, pb, w);
	double a = mathx_dot(da, da), b = mathx_dot(da, db), c = mathx_dot(db, db);
	double d = mathx_dot(da, w), e = mathx_dot(db, w);
	if (!(a > 0) || !(c > 0))
		return GEOM_DEGENERATE;
	/* den = |da|^2 |db|^2 sin^2 of the angle between them */
	double den = a * c - b * b;
	if (den <= PARALLEL_SIN2 * a * c) {
		dest[0] = 0;
		dest[1] = e / c;
		return GEOM_PARALLEL;
	}
	/* the normal equations of min |w + s da - t db|^2 */
	dest[0] = (b * e - c * d) / den;
	dest[1] = (a * e - b * d) / den;
	return GEOM_HIT;
}

int
geom_axis_nearest_ray(const double p[3], const double a[3], const struct ray *r, double *s,
		      double dest[3])
{
	double st[2];
	int rc = geom_lines_closest(p, a, r->o, r->d, st);
	if (rc != GEOM_HIT)
		return rc;
	if (st[1] < 0)
		return GEOM_BEHIND;
	if (s)
		*s = st[0];
	if (dest)
		for (int i = 0; i < 3; i++)
			dest[i] = p[i] + st[0] * a[i];
	return GEOM_HIT;
}

int
geom_ray_plane(const struct ray *r, const double p0[3], const double n[3], double *t,
	       double dest[3])
{
	double nn = sqrt(mathx_dot(n, n)), dd = sqrt(mathx_dot(r->d, r->d));
	if (!(nn > 0) || !(dd > 0))
		return GEOM_DEGENERATE;
	double dn = mathx_dot(r->d, n);
	if (fabs(dn) <= PARALLEL_COS * nn * dd)
		return GEOM_PARALLEL;
	double w[3];
	sub(p0, r->o, w);
	double tt = mathx_dot(w, n) / dn;
	if (tt < 0)
		return GEOM_BEHIND;
	if (t)
		*t = tt;
	if (dest)
		for (int i = 0; i < 3; i++)
			dest[i] = r->o[i] + tt * r->d[i];
	return GEOM_HIT;
}

int
geom_spoke_angle(const double axis[3], const double s0[3], const double s1[3], double *dest)
{
	double u[3];
	if (geom_normalize(axis, u))
		return GEOM_DEGENERATE;
	/* project both spokes into the wheel's plane */
	double p0[3], p1[3], k0 = mathx_dot(s0, u), k1 = mathx_dot(s1, u);
	for (int i = 0; i < 3; i++) {
		p0[i] = s0[i] - k0 * u[i];
		p1[i] = s1[i] - k1 * u[i];
	}
	if (mathx_dot(p0, p0) < SPOKE_MIN2 || mathx_dot(p1, p1) < SPOKE_MIN2)
		return GEOM_DEGENERATE;
	/* atan2 keeps full precision near 0 and pi, where acos of a dot does not */
	double c[3];
	mathx_cross(p0, p1, c);
	*dest = atan2(mathx_dot(c, u), mathx_dot(p0, p1));
	return GEOM_HIT;
}

double
geom_line_angle(const double a[3], const double b[3])
{
	double c[3];
	mathx_cross(a, b, c);
	double sn = sqrt(mathx_dot(c, c)), cs = fabs(mathx_dot(a, b));
	if (sn == 0 && cs == 0)
		return 0;
	return atan2(sn, cs);
}

void
geom_rotation(const double axis[3], double angle, double dest[9])
{
	/* Rodrigues: R = I cos + (1 - cos) a a^T + sin [a]x */
	double c = cos(angle), s = sin(angle), k = 1 - c;
	double x = axis[0], y = axis[1], z = axis[2];
	dest[0] = c + k * x * x;
	dest[1] = k * x * y - s * z;
	dest[2] = k * x * z + s * y;
	dest[3] = k * x * y + s * z;
	dest[4] = c + k * y * y;
	dest[5] = k * y * z - s * x;
	dest[6] = k * x * z - s * y;
	dest[7] = k * y * z + s * x;
	dest[8] = c + k * z * z;
}
