/* balance.c - the support polygon, the balance point and its parameters, rooting */
#include "pose/balance.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static double
cross2(const double o[2], const double a[2], const double b[2])
{
	return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

static double
dot2(const double a[2], const double b[2])
{
	return a[0] * b[0] + a[1] * b[1];
}

/* sorts points by x then z; insertion sort, n is small */
static void
sort2(double (*p)[2], int n)
{
	for (int i = 1; i < n; i++)
		for (int j = i; j > 0 && (p[j][0] < p[j - 1][0] ||
					  (p[j][0] == p[j - 1][0] && p[j][1] < p[j - 1][1]));
		     j--) {
			double t[2] = { p[j][0], p[j][1] };
			memcpy(p[j], p[j - 1], sizeof t);
			memcpy(p[j - 1], t, sizeof t);
		}
}

int
balance_hull(double (*p)[2], int n, double (*h)[2])
{
	/* Andrew's monotone chain; h needs room for n + 1 points */
	int k = 0;
	sort2(p, n);
	for (int i = 0; i < n; i++) {
		while (k >= 2 && cross2(h[k - 2], h[k - 1], p[i]) <= 0)
			k--;
		memcpy(h[k++], p[i], sizeof p[i]);
	}
	for (int i = n - 2, t = k + 1; i >= 0; i--) {
		while (k >= t && cross2(h[k - 2], h[k - 1], p[i]) <= 0)
			k--;
		memcpy(h[k++], p[i], sizeof p[i]);
	}
	return n > 1 ? k - 1 : n;
}

/* the half extents of geom g's bounding box in its own frame; 0 for a kind without one */
static int
geom_half(const struct model *m, int g, double half[3])
{
	const double *sz = &m->geom_size[3 * g];
	switch ((enum geom_kind)m->geom_kind[g]) {
	case GEOM_BOX:
	case GEOM_MESH:
		half[0] = sz[0] / 2, half[1] = sz[1] / 2, half[2] = sz[2] / 2;
		break;
	case GEOM_ELLIPSOID:
		half[0] = sz[0], half[1] = sz[1], half[2] = sz[2];
		break;
	case GEOM_CYLINDER:
	case GEOM_CAPSULE:
		half[0] = half[2] = sz[0];
		half[1] = sz[1] / 2 + (m->geom_kind[g] == GEOM_CAPSULE ? sz[0] : 0);
		break;
	default:
		return 0;
	}
	return 1;
}

/* corners of a geom's bounding box in the world */
static int
geom_corners(const struct model *m, const struct state *s, int g, double (*dest)[3])
{
	double half[3];
	if (!geom_half(m, g, half))
		return 0;
	struct xform loc, x;
	mathx_quat_to_mat(&m->geom_quat[4 * g], loc.r);
	memcpy(loc.p, &m->geom_pos[3 * g], sizeof loc.p);
	xform_mul(&s->seg_xf[m->geom_seg[g]], &loc, &x);
	for (int c = 0; c < 8; c++) {
		double l[3] = { c & 1 ? half[0] : -half[0], c & 2 ? half[1] : -half[1],
				c & 4 ? half[2] : -half[2] };
		xform_apply(&x, l, dest[c]);
	}
	return 8;
}

/* how far from p along unit d the polygon ends (0 when p is outside it that way) */
static double
reach_along(const struct balance *b, const double p[2], const double d[2])
{
	double best = 0;
	int hit = 0;
	for (int i = 0; i < b->npoly; i++) {
		const double *a = b->poly[i], *c = b->poly[(i + 1) % b->npoly];
		double e[2] = { c[0] - a[0], c[1] - a[1] }, w[2] = { a[0] - p[0], a[1] - p[1] };
		double den = d[0] * e[1] - d[1] * e[0];
		if (fabs(den) < 1e-15)
			continue;
		/* p + t d = a + u e */
		double t = (w[0] * e[1] - w[1] * e[0]) / den, u = (w[0] * d[1] - w[1] * d[0]) / den;
		if (u >= -1e-12 && u <= 1 + 1e-12 && t >= 0 && (!hit || t > best)) {
			best = t;
			hit = 1;
		}
	}
	return best;
}

/*
 * A foot's end of the balance line: its balance site, moving to the ball
 * of the foot (halfway from the toe joint to the toe tip) as the heel,
 * once off the floor (contact_height above the toes), rises by another
 * contact_height, so that on tiptoe the weight goes over what still
 * touches the floor.
 */
static void
foot_ref(const struct model *m, const struct state *s, int balance_site, const char *side,
	 double contact_height, double dest[2])
{
	const double *c = s->site_xf[balance_site].p;
	double t = 0;
	int toe = -1, tip = -1;
	if (contact_height > 0) { /* only a foot that may stand on tiptoe: no lookups otherwise */
		char name[32];
		snprintf(name, sizeof name, "foot_%s.heel", side);
		int heel = model_find_site(m, name);
		snprintf(name, sizeof name, "toes_%s.toe", side);
		toe = model_find_site(m, name);
		snprintf(name, sizeof name, "toes_%s.tip", side);
		tip = model_find_site(m, name);
		if (heel >= 0 && toe >= 0 && tip >= 0) {
			t = (s->site_xf[heel].p[1] - s->site_xf[toe].p[1]) / contact_height - 1;
			t = t < 0 ? 0 : t > 1 ? 1 : t;
		}
	}
	for (int i = 0; i < 2; i++) {
		int k = i ? 2 : 0;
		double ball = t > 0 ? (s->site_xf[toe].p[k] + s->site_xf[tip].p[k]) / 2 : c[k];
		dest[i] = (1 - t) * c[k] + t * ball;
	}
}

int
balance_touches_floor(const struct model *m, const struct state *s, int seg, double h)
{
	if (seg < 0)
		return 0;
	const struct xform *x = &s->seg_xf[seg];
	for (int g = m->seg_geom0[seg]; g < m->seg_geom0[seg] + m->seg_ngeom[seg]; g++) {
		double half[3];
		if (!geom_half(m, g, half))
			continue;
		double gr[9], w[9], c[3];
		mathx_quat_to_mat(&m->geom_quat[4 * g], gr);
		mathx_mat3_mul(x->r, gr, w);
		xform_apply(x, &m->geom_pos[3 * g], c);
		double low = c[1];
		for (int k = 0; k < 3; k++)
			low -= fabs(w[3 + k]) * half[k];
		if (low < h)
			return 1;
	}
	return 0;
}

int
balance_measure(const struct model *m, const struct state *s, double contact_height,
		struct balance *dest)
{
	return balance_measure_feet(m, s, contact_height, 0, dest);
}

int
balance_measure_feet(const struct model *m, const struct state *s, double contact_height,
		     unsigned tiptoe, struct balance *dest)
{
	return balance_measure_com(m, s, contact_height, tiptoe, s->com, dest);
}

int
balance_measure_com(const struct model *m, const struct state *s, double contact_height,
		    unsigned tiptoe, const double com[3], struct balance *dest)
{
	static const char *const feet[4] = { "foot_l", "foot_r", "toes_l", "toes_r" };
	int bl = model_find_site(m, "foot_l.balance"), br = model_find_site(m, "foot_r.balance");
	if (bl < 0 || br < 0)
		return -1;
	double pts[4 * 8 * 8][2], corner[8][3];
	int n = 0;
	for (int f = 0; f < 4; f++) {
		int seg = model_find_segment(m, feet[f]);
		if (seg < 0)
			continue;
		for (int g = m->seg_geom0[seg]; g < m->seg_geom0[seg] + m->seg_ngeom[seg]; g++) {
			int k = geom_corners(m, s, g, corner);
			for (int i = 0; i < k && n < (int)(sizeof pts / sizeof *pts); i++)
				if (corner[i][1] < contact_height) {
					pts[n][0] = corner[i][0];
					pts[n][1] = corner[i][2];
					n++;
				}
		}
	}
	double hull[sizeof pts / sizeof *pts + 1][2];
	int nh = balance_hull(pts, n, hull);
	dest->npoly = nh < BALANCE_POLY_MAX ? nh : BALANCE_POLY_MAX;
	memcpy(dest->poly, hull, sizeof *hull * (size_t)dest->npoly);
	foot_ref(m, s, bl, "l", tiptoe & 1 ? contact_height : 0, dest->ref_l);
	foot_ref(m, s, br, "r", tiptoe & 2 ? contact_height : 0, dest->ref_r);
	memmove(dest->com, com, sizeof dest->com);
	dest->point[0] = com[0], dest->point[1] = com[2];
	/* forward: across the line from left to right, turned as the feet face (up x line) */
	double d[2] = { dest->ref_r[0] - dest->ref_l[0], dest->ref_r[1] - dest->ref_l[1] };
	if (dot2(d, d) < 1e-18) { /* feet together: forward is where the left foot points */
		int toe = model_find_site(m, "toes_l.tip");
		double f[2] = { toe >= 0 ? s->site_xf[toe].p[0] - dest->ref_l[0] : 0,
				toe >= 0 ? s->site_xf[toe].p[2] - dest->ref_l[1] : 1 };
		double fl = sqrt(dot2(f, f));
		d[0] = -f[1] / fl, d[1] = f[0] / fl; /* so that forward below comes out as f */
	}
	double u[2] = { d[0] / sqrt(dot2(d, d)), d[1] / sqrt(dot2(d, d)) };
	dest->forward[0] = u[1], dest->forward[1] = -u[0];
	balance_params_of(dest, dest->point, &dest->x, &dest->z);
	dest->margin = balance_margin(dest, dest->point);
	dest->weight_l = dest->x < 0 ? 1 : dest->x > 1 ? 0 : 1 - dest->x;
	return 0;
}

#define BALANCE_NOMINAL_EDGE 0.10 /* m: z's unit where the polygon gives none (feet in the air) */

/*
 * z's unit the way dir (sign of z) goes: how far the polygon reaches from
 * the balance line at x, clamped to the line's ends so that points out past
 * a foot's side keep finite parameters that map back to the same point.
 */
static double
edge_at(const struct balance *b, double x, double z)
{
	double d[2] = { b->ref_r[0] - b->ref_l[0], b->ref_r[1] - b->ref_l[1] };
	double xc = x < 0 ? 0 : x > 1 ? 1 : x;
	double p[2] = { b->ref_l[0] + xc * d[0], b->ref_l[1] + xc * d[1] };
	double dir[2] = { z >= 0 ? b->forward[0] : -b->forward[0], z >= 0 ? b->forward[1] : -b->forward[1] };
	double edge = reach_along(b, p, dir);
	return edge > 1e-6 ? edge : BALANCE_NOMINAL_EDGE;
}

void
balance_params_of(const struct balance *b, const double pt[2], double *x, double *z)
{
	/* Figure 5.2: p the nearest point of the line, x its place, z the way forward */
	double d[2] = { b->ref_r[0] - b->ref_l[0], b->ref_r[1] - b->ref_l[1] };
	double len2 = dot2(d, d);
	double w[2] = { pt[0] - b->ref_l[0], pt[1] - b->ref_l[1] };
	*x = len2 > 1e-18 ? dot2(w, d) / len2 : 0.5;
	double p[2] = { b->ref_l[0] + *x * d[0], b->ref_l[1] + *x * d[1] };
	double off[2] = { pt[0] - p[0], pt[1] - p[1] };
	double zraw = dot2(off, b->forward);
	*z = zraw / edge_at(b, *x, zraw);
}

void
balance_point_of(const struct balance *b, double x, double z, double dest[2])
{
	double d[2] = { b->ref_r[0] - b->ref_l[0], b->ref_r[1] - b->ref_l[1] };
	double p[2] = { b->ref_l[0] + x * d[0], b->ref_l[1] + x * d[1] };
	double edge = edge_at(b, x, z);
	dest[0] = p[0] + z * edge * b->forward[0];
	dest[1] = p[1] + z * edge * b->forward[1];
}

double
balance_margin(const struct balance *b, const double p[2])
{
	if (b->npoly < 3)
		return -1e9;
	double best = 1e300;
	int inside = 1;
	for (int i = 0; i < b->npoly; i++) {
		const double *a = b->poly[i], *c = b->poly[(i + 1) % b->npoly];
		double e[2] = { c[0] - a[0], c[1] - a[1] }, w[2] = { p[0] - a[0], p[1] - a[1] };
		double t = dot2(w, e) / dot2(e, e);
		t = t < 0 ? 0 : t > 1 ? 1 : t;
		double q[2] = { a[0] + t * e[0] - p[0], a[1] + t * e[1] - p[1] };
		best = fmin(best, sqrt(dot2(q, q)));
		if (cross2(a, c, p) < 0)
			inside = 0;
	}
	return inside ? best : -best;
}

enum balance_root
balance_choose_root(const struct balance *b, double com_height, double leg_length,
		    enum balance_root current)
{
	if (com_height < 0.7 * leg_length)
		return BALANCE_ROOT_LOWER_TORSO;
	if (b->weight_l > 0.6)
		return BALANCE_ROOT_LEFT_FOOT;
	if (b->weight_l < 0.4)
		return BALANCE_ROOT_RIGHT_FOOT;
	if (current == BALANCE_ROOT_LOWER_TORSO) /* standing up again: the heavier foot */
		return b->weight_l >= 0.5 ? BALANCE_ROOT_LEFT_FOOT : BALANCE_ROOT_RIGHT_FOOT;
	return current;
}
