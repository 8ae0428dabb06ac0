/* snap.c - the manipulation transform snapped onto features (see snap.h) */
#include "interact/snap.h"

#include <math.h>
#include <string.h>

#include "interact/geom.h"

static const char *const snap_names[SNAP_KINDS] = {
	"site", "site_position", "site_orientation", "node_position", "edge_position",
	"edge_line", "edge_orientation", "face_position", "face_center", "face_plane",
	"face_orientation",
};

int
snap_kind_named(const char *name)
{
	for (int k = 0; k < SNAP_KINDS; k++)
		if (!strcmp(name, snap_names[k]))
			return k;
	return -1;
}

const char *
snap_kind_name(enum snap_kind k)
{
	return k >= 0 && k < SNAP_KINDS ? snap_names[k] : "?";
}

static void
sub3(const double a[3], const double b[3], double dest[3])
{
	for (int k = 0; k < 3; k++)
		dest[k] = a[k] - b[k];
}

/* column c of a row-major 3x3 (the frame's axis c) */
static void
col(const double r[9], int c, double dest[3])
{
	for (int k = 0; k < 3; k++)
		dest[k] = r[3 * k + c];
}

void
snap_square_up(const double r[9], const double tr[9], double dest[9])
{
	/* rel = tr^T r: G's axes in the target's frame; the best signed permutation P
	 * maximises sum P_ij rel_ij over the 24 proper ones */
	double rel[9];
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			rel[3 * i + j] = tr[i] * r[j] + tr[3 + i] * r[3 + j] + tr[6 + i] * r[6 + j];
	static const int perm[6][3] = { { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 },
					{ 1, 2, 0 }, { 2, 0, 1 }, { 2, 1, 0 } };
	static const int parity[6] = { 1, -1, -1, 1, 1, -1 };
	double best = -INFINITY, bp[9] = { 0 };
	for (int p = 0; p < 6; p++)
		for (int signs = 0; signs < 8; signs++) {
			int s[3] = { signs & 1 ? -1 : 1, signs & 2 ? -1 : 1, signs & 4 ? -1 : 1 };
			if (parity[p] * s[0] * s[1] * s[2] != 1)
				continue; /* a reflection, not a rotation */
			/* P has s[j] at row perm[p][j] of column j: G's axis j onto target axis perm[j] */
			double score = 0;
			for (int j = 0; j < 3; j++)
				score += s[j] * rel[3 * perm[p][j] + j];
			if (score > best) {
				best = score;
				memset(bp, 0, sizeof bp);
				for (int j = 0; j < 3; j++)
					bp[3 * perm[p][j] + j] = s[j];
			}
		}
	double out[9];
	for (int i = 0; i < 3; i++) /* dest = tr P */
		for (int j = 0; j < 3; j++)
			out[3 * i + j] = tr[3 * i] * bp[j] + tr[3 * i + 1] * bp[3 + j] +
					 tr[3 * i + 2] * bp[6 + j];
	memcpy(dest, out, sizeof out);
}

/* G turned through the least angle that lays one of its axes, either way, along dir */
static int
lay_axis_along(const double r[9], const double dir[3], double dest[9])
{
	double d[3];
	if (geom_normalize(dir, d) < 0)
		return -1;
	int best = 0;
	double bestc = -1, sign = 1;
	for (int k = 0; k < 3; k++) {
		double a[3];
		col(r, k, a);
		double c = mathx_dot(a, d);
		if (fabs(c) > bestc) {
			bestc = fabs(c);
			best = k;
			sign = c < 0 ? -1 : 1;
		}
	}
	double a[3], axis[3], turn[9];
	col(r, best, a);
	for (int k = 0; k < 3; k++)
		a[k] *= sign;
	mathx_cross(a, d, axis);
	double s = sqrt(mathx_dot(axis, axis)), angle = atan2(s, mathx_dot(a, d));
	if (s < 1e-15) { /* already along it */
		memcpy(dest, r, sizeof turn);
		return 0;
	}
	for (int k = 0; k < 3; k++)
		axis[k] /= s;
	geom_rotation(axis, angle, turn);
	double out[9];
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			out[3 * i + j] = turn[3 * i] * r[j] + turn[3 * i + 1] * r[3 + j] +
					 turn[3 * i + 2] * r[6 + j];
	memcpy(dest, out, sizeof out);
	return 0;
}

/* the point of segment ab (clamped: 1) or its line (0) nearest p */
static int
nearest_on_edge(const double a[3], const double b[3], const double p[3], int clamp, double dest[3])
{
	double ab[3], ap[3];
	sub3(b, a, ab);
	sub3(p, a, ap);
	double l2 = mathx_dot(ab, ab);
	if (!(l2 > 1e-24))
		return -1;
	double t = mathx_dot(ap, ab) / l2;
	if (clamp)
		t = t < 0 ? 0 : t > 1 ? 1 : t;
	for (int k = 0; k < 3; k++)
		dest[k] = a[k] + t * ab[k];
	return 0;
}

/* the triangle's unit normal (counter-clockwise from outside) */
static int
face_normal(const double f[3][3], double n[3])
{
	double u[3], v[3];
	sub3(f[1], f[0], u);
	sub3(f[2], f[0], v);
	mathx_cross(u, v, n);
	return geom_normalize(n, n);
}

/* the point of the triangle nearest p: in its plane when inside, else on its nearest edge */
static int
nearest_on_face(const double f[3][3], const double p[3], double dest[3])
{
	double n[3], ap[3];
	if (face_normal(f, n) < 0)
		return -1;
	sub3(p, f[0], ap);
	double h = mathx_dot(ap, n), q[3];
	for (int k = 0; k < 3; k++)
		q[k] = p[k] - h * n[k];
	/* inside when q is on the inner side of all three edges */
	int inside = 1;
	for (int e = 0; e < 3 && inside; e++) {
		double ed[3], eq[3], c[3];
		sub3(f[(e + 1) % 3], f[e], ed);
		sub3(q, f[e], eq);
		mathx_cross(ed, eq, c);
		inside = mathx_dot(c, n) >= 0;
	}
	if (inside) {
		memcpy(dest, q, sizeof q);
		return 0;
	}
	double best = INFINITY;
	for (int e = 0; e < 3; e++) {
		double c[3], d[3];
		nearest_on_edge(f[e], f[(e + 1) % 3], p, 1, c);
		sub3(c, p, d);
		if (mathx_dot(d, d) < best) {
			best = mathx_dot(d, d);
			memcpy(dest, c, sizeof c);
		}
	}
	return 0;
}

int
snap_apply(enum snap_kind kind, const struct snap_feature *f, const struct xform *g,
	   struct xform *dest)
{
	struct xform out = *g;
	int rc = 0;
	double n[3], e[3];
	switch (kind) {
	case SNAP_SITE:
	case SNAP_SITE_POSITION:
	case SNAP_SITE_ORIENTATION:
		if (!f->has_site)
			return -1;
		if (kind != SNAP_SITE_ORIENTATION)
			memcpy(out.p, f->site.p, sizeof out.p);
		if (kind != SNAP_SITE_POSITION)
			snap_square_up(g->r, f->site.r, out.r);
		break;
	case SNAP_NODE_POSITION:
		memcpy(out.p, f->vertex, sizeof out.p);
		break;
	case SNAP_EDGE_POSITION:
	case SNAP_EDGE_LINE:
		rc = nearest_on_edge(f->edge[0], f->edge[1], g->p, kind == SNAP_EDGE_POSITION, out.p);
		break;
	case SNAP_EDGE_ORIENTATION:
		sub3(f->edge[1], f->edge[0], e);
		rc = lay_axis_along(g->r, e, out.r);
		break;
	case SNAP_FACE_POSITION:
		rc = nearest_on_face(f->face, g->p, out.p);
		break;
	case SNAP_FACE_CENTER:
		for (int k = 0; k < 3; k++)
			out.p[k] = (f->face[0][k] + f->face[1][k] + f->face[2][k]) / 3;
		break;
	case SNAP_FACE_PLANE:
		if ((rc = face_normal(f->face, n)) == 0) {
			double ap[3];
			sub3(g->p, f->face[0], ap);
			double h = mathx_dot(ap, n);
			for (int k = 0; k < 3; k++)
				out.p[k] = g->p[k] - h * n[k];
		}
		break;
	case SNAP_FACE_ORIENTATION:
		if ((rc = face_normal(f->face, n)) == 0)
			rc = lay_axis_along(g->r, n, out.r);
		break;
	default:
		return -1;
	}
	if (rc < 0)
		return -1;
	*dest = out;
	return 0;
}
