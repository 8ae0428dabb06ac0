/* pick.c - the mouse line against the figures' drawn meshes (see pick.h) */
#include "interact/pick.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "draw/tess.h"
#include "draw/view.h"

/* ---- the model ------------------------------------------------------------ */

void
pick_model_free(struct pick_model *pm)
{
	if (!pm)
		return;
	free(pm->seg_part0);
	free(pm->seg_npart);
	free(pm->seg_lo);
	free(pm->seg_hi);
	free(pm->part);
	free(pm->tri);
	free(pm->tri_vert);
	free(pm);
}

/* the triangles of one drawn mesh: its corners and their vertex numbers */
struct mesh_ref {
	const float *pos; /* vertex positions */
	int stride;       /* floats from one vertex to the next */
	const unsigned *uidx; /* a tessellated mesh's indices, or */
	const int *iidx;      /* a model mesh's faces */
	int ntri;
};

static struct mesh_ref
mesh_of_part(const struct view_part *p, const struct model *m, const struct tess_mesh *builtin)
{
	struct mesh_ref r = { 0 };
	if (p->model_mesh >= 0) {
		int k = p->model_mesh;
		r.pos = m->mesh_vert + 3 * m->mesh_vert0[k];
		r.stride = 3;
		r.iidx = m->mesh_face + 3 * m->mesh_face0[k];
		r.ntri = m->mesh_nface[k];
	} else {
		const struct tess_mesh *t = &builtin[p->mesh];
		r.pos = t->vn;
		r.stride = 6;
		r.uidx = t->idx;
		r.ntri = t->nidx / 3;
	}
	return r;
}

static int
corner(const struct mesh_ref *r, int tri, int k)
{
	return r->uidx ? (int)r->uidx[3 * tri + k] : r->iidx[3 * tri + k];
}

static void
box_grow(double lo[3], double hi[3], const double p[3])
{
	for (int k = 0; k < 3; k++) {
		lo[k] = p[k] < lo[k] ? p[k] : lo[k];
		hi[k] = p[k] > hi[k] ? p[k] : hi[k];
	}
}

/* a hair of slack, so rounding in the box test never loses a grazing hit */
static void
box_pad(double lo[3], double hi[3])
{
	for (int k = 0; k < 3; k++) {
		double e = 1e-9 + 1e-6 * (fabs(lo[k]) + fabs(hi[k]));
		lo[k] -= e;
		hi[k] += e;
	}
}

/* one part's triangles into the arrays from pm->ntri on, its box into *pp */
static void
add_part(struct pick_model *pm, const struct view_part *p, const struct mesh_ref *r,
	 struct pick_part *pp)
{
	/* a mirroring scale turns the winding over: swap two corners to keep the front */
	int mirror = p->scale[0] * p->scale[1] * p->scale[2] < 0;
	pp->tri0 = pm->ntri;
	pp->ntri = r->ntri;
	for (int k = 0; k < 3; k++) {
		pp->lo[k] = INFINITY;
		pp->hi[k] = -INFINITY;
	}
	for (int t = 0; t < r->ntri; t++) {
		float *dst = pm->tri + 9 * (size_t)pm->ntri;
		int *vn = pm->tri_vert + 3 * (size_t)pm->ntri;
		for (int k = 0; k < 3; k++) {
			int kk = mirror && k ? 3 - k : k;
			int v = corner(r, t, kk);
			const float *q = r->pos + (size_t)r->stride * v;
			double s[3] = { q[0] * p->scale[0], q[1] * p->scale[1], q[2] * p->scale[2] }, w[3];
			xform_apply(&p->xf, s, w);
			for (int i = 0; i < 3; i++)
				dst[3 * k + i] = (float)w[i];
			/* the box of the stored (float) corners, so it holds them exactly */
			double f[3] = { dst[3 * k], dst[3 * k + 1], dst[3 * k + 2] };
			box_grow(pp->lo, pp->hi, f);
			vn[k] = v;
		}
		pm->ntri++;
	}
	box_pad(pp->lo, pp->hi);
}

struct pick_model *
pick_model_make(const struct model *m)
{
	struct tess_mesh builtin[VIEW_MESH_BUILTIN];
	struct pick_model *pm = calloc(1, sizeof *pm);
	int ok = pm != NULL, nbuilt = 0;
	for (; ok && nbuilt < VIEW_MESH_BUILTIN; nbuilt++)
		ok = !view_mesh_tess((enum view_mesh)nbuilt, 1, &builtin[nbuilt]);
	if (!ok)
		nbuilt--;

	/* count parts and triangles */
	int npart = 0, ntri = 0;
	for (int g = 0; ok && g < m->ngeom; g++) {
		struct view_part part[VIEW_GEOM_PARTS_MAX];
		int n = view_geom_parts(m, g, part);
		for (int k = 0; k < n; k++) {
			struct mesh_ref r = mesh_of_part(&part[k], m, builtin);
			npart++;
			ntri += r.ntri;
		}
	}
	if (ok) {
		pm->nseg = m->nseg;
		pm->seg_part0 = calloc((size_t)m->nseg + 1, sizeof(int));
		pm->seg_npart = calloc((size_t)m->nseg + 1, sizeof(int));
		pm->seg_lo = calloc(3 * (size_t)m->nseg + 1, sizeof(double));
		pm->seg_hi = calloc(3 * (size_t)m->nseg + 1, sizeof(double));
		pm->part = calloc((size_t)npart + 1, sizeof *pm->part);
		pm->tri = malloc(sizeof(float) * 9 * ((size_t)ntri + 1));
		pm->tri_vert = malloc(sizeof(int) * 3 * ((size_t)ntri + 1));
		ok = pm->seg_part0 && pm->seg_npart && pm->seg_lo && pm->seg_hi && pm->part &&
		     pm->tri && pm->tri_vert;
	}

	/* segment by segment (a segment's geoms are contiguous), part by part */
	for (int seg = 0; ok && seg < m->nseg; seg++) {
		double *lo = pm->seg_lo + 3 * seg, *hi = pm->seg_hi + 3 * seg;
		pm->seg_part0[seg] = pm->npart;
		for (int k = 0; k < 3; k++) {
			lo[k] = INFINITY;
			hi[k] = -INFINITY;
		}
		for (int g = m->seg_geom0[seg]; g < m->seg_geom0[seg] + m->seg_ngeom[seg]; g++) {
			struct view_part part[VIEW_GEOM_PARTS_MAX];
			int n = view_geom_parts(m, g, part);
			for (int k = 0; k < n; k++) {
				struct mesh_ref r = mesh_of_part(&part[k], m, builtin);
				struct pick_part *pp = &pm->part[pm->npart++];
				pp->geom = g;
				pp->index = k;
				add_part(pm, &part[k], &r, pp);
				if (pp->ntri) {
					box_grow(lo, hi, pp->lo);
					box_grow(lo, hi, pp->hi);
				}
			}
		}
		pm->seg_npart[seg] = pm->npart - pm->seg_part0[seg];
	}
	for (int k = 0; k < nbuilt; k++)
		tess_free(&builtin[k]);
	if (!ok) {
		pick_model_free(pm);
		return NULL;
	}
	return pm;
}

/* ---- rays ----------------------------------------------------------------- */

int
pick_triangle(const struct ray *r, const double a[3], const double b[3], const double c[3],
	      double tmin, double *t, double *u, double *v)
{
	double e1[3], e2[3], pv[3], tv[3], qv[3];
	for (int k = 0; k < 3; k++) {
		e1[k] = b[k] - a[k];
		e2[k] = c[k] - a[k];
		tv[k] = r->o[k] - a[k];
	}
	mathx_cross(r->d, e2, pv);
	/* det = -d . (e1 x e2): positive when the ray meets the front (outward) face */
	double det = mathx_dot(e1, pv);
	if (!(det > 0))
		return 0;
	double inv = 1 / det;
	double uu = mathx_dot(tv, pv) * inv;
	if (uu < 0 || uu > 1)
		return 0;
	mathx_cross(tv, e1, qv);
	double vv = mathx_dot(r->d, qv) * inv;
	if (vv < 0 || uu + vv > 1)
		return 0;
	double tt = mathx_dot(e2, qv) * inv;
	if (!(tt >= tmin) || !isfinite(tt))
		return 0;
	*t = tt;
	*u = uu;
	*v = vv;
	return 1;
}

/* the parameter where r enters box lo..hi, or INFINITY when it misses it beyond tmin */
static double
box_entry(const struct ray *r, const double lo[3], const double hi[3], double tmin)
{
	double t0 = tmin, t1 = INFINITY;
	for (int k = 0; k < 3; k++) {
		if (r->d[k] == 0) {
			if (r->o[k] < lo[k] || r->o[k] > hi[k])
				return INFINITY;
			continue;
		}
		double inv = 1 / r->d[k], a = (lo[k] - r->o[k]) * inv, b = (hi[k] - r->o[k]) * inv;
		if (a > b) {
			double x = a;
			a = b;
			b = x;
		}
		t0 = a > t0 ? a : t0;
		t1 = b < t1 ? b : t1;
		if (t0 > t1)
			return INFINITY;
	}
	return t0;
}

/* the nearest triangle of one part nearer than *best: updates *best, *tri, *u, *v */
static void
part_hit(const struct pick_model *pm, const struct pick_part *pp, const struct ray *r,
	 double tmin, double *best, int *tri, double *u, double *v)
{
	for (int i = pp->tri0; i < pp->tri0 + pp->ntri; i++) {
		const float *f = pm->tri + 9 * (size_t)i;
		double a[3] = { f[0], f[1], f[2] }, b[3] = { f[3], f[4], f[5] },
		       c[3] = { f[6], f[7], f[8] }, t, uu, vv;
		if (pick_triangle(r, a, b, c, tmin, &t, &uu, &vv) && t < *best) {
			*best = t;
			*tri = i;
			*u = uu;
			*v = vv;
		}
	}
}

static double
dist2(const double a[3], const double b[3])
{
	double d[3] = { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
	return mathx_dot(d, d);
}

/* the hit's features from triangle tri of segment seg at (t, u, v) */
static void
describe(const struct pick_model *pm, const struct model *m, const struct state *s,
	 const struct ray *r, int seg, int part, int tri, double t, double u, double v,
	 struct pick_hit *dest)
{
	const struct pick_part *pp = &pm->part[part];
	const float *f = pm->tri + 9 * (size_t)tri;
	const int *vn = pm->tri_vert + 3 * (size_t)tri;
	double c[3][3], e1[3], e2[3], n[3], local[3];
	for (int k = 0; k < 3; k++)
		for (int i = 0; i < 3; i++)
			c[k][i] = f[3 * k + i];
	for (int i = 0; i < 3; i++) {
		e1[i] = c[1][i] - c[0][i];
		e2[i] = c[2][i] - c[0][i];
		local[i] = (1 - u - v) * c[0][i] + u * c[1][i] + v * c[2][i];
	}
	mathx_cross(e1, e2, n);
	double area2 = sqrt(mathx_dot(n, n));
	for (int i = 0; i < 3; i++)
		n[i] /= area2;

	dest->segment = seg;
	dest->geom = pp->geom;
	dest->part = pp->index;
	dest->face = tri - pp->tri0;
	dest->distance = t;
	for (int i = 0; i < 3; i++)
		dest->point[i] = r->o[i] + t * r->d[i];
	xform_rotate(&s->seg_xf[seg], n, dest->normal);

	/* the edge opposite corner k lies bary_k * 2 area / its length away */
	double bary[3] = { 1 - u - v, u, v }, best_e = INFINITY, best_v = INFINITY;
	for (int k = 0; k < 3; k++) {
		int i = (k + 1) % 3, j = (k + 2) % 3;
		double len = sqrt(dist2(c[i], c[j]));
		double de = len > 0 ? bary[k] * area2 / len : INFINITY;
		if (de < best_e) {
			best_e = de;
			dest->edge[0] = vn[i];
			dest->edge[1] = vn[j];
			dest->edge_corner[0] = i;
			dest->edge_corner[1] = j;
		}
		double dv = dist2(local, c[k]);
		if (dv < best_v) {
			best_v = dv;
			dest->vertex = vn[k];
			dest->vertex_corner = k;
		}
		xform_apply(&s->seg_xf[seg], c[k], dest->tri[k]);
	}

	dest->site = -1;
	double best_s = INFINITY;
	for (int k = m->seg_site0[seg]; k < m->seg_site0[seg] + m->seg_nsite[seg]; k++) {
		double d = dist2(s->site_xf[k].p, dest->point);
		if (d < best_s) {
			best_s = d;
			dest->site = k;
		}
	}
}

static int
pick_impl(const struct pick_model *pm, const struct model *m, const struct state *s,
	  const struct ray *r, double tmin, int bounds, struct pick_hit *dest)
{
	double best = INFINITY, bu = 0, bv = 0;
	int bseg = -1, bpart = -1, btri = -1;
	for (int seg = 0; seg < pm->nseg; seg++) {
		/* the ray in the segment's frame: rigid, so t is the same */
		const struct xform *x = &s->seg_xf[seg];
		struct ray lr;
		double d[3] = { r->o[0] - x->p[0], r->o[1] - x->p[1], r->o[2] - x->p[2] };
		for (int j = 0; j < 3; j++) {
			lr.o[j] = x->r[j] * d[0] + x->r[3 + j] * d[1] + x->r[6 + j] * d[2];
			lr.d[j] = x->r[j] * r->d[0] + x->r[3 + j] * r->d[1] + x->r[6 + j] * r->d[2];
		}
		if (bounds && !(box_entry(&lr, pm->seg_lo + 3 * seg, pm->seg_hi + 3 * seg, tmin) < best))
			continue;
		for (int p = pm->seg_part0[seg]; p < pm->seg_part0[seg] + pm->seg_npart[seg]; p++) {
			const struct pick_part *pp = &pm->part[p];
			if (bounds && !(box_entry(&lr, pp->lo, pp->hi, tmin) < best))
				continue;
			int before = btri;
			part_hit(pm, pp, &lr, tmin, &best, &btri, &bu, &bv);
			if (btri != before) {
				bseg = seg;
				bpart = p;
			}
		}
	}
	if (btri < 0)
		return 0;
	dest->figure = 0;
	describe(pm, m, s, r, bseg, bpart, btri, best, bu, bv, dest);
	return 1;
}

int
pick_figure(const struct pick_model *pm, const struct model *m, const struct state *s,
	    const struct ray *r, double tmin, struct pick_hit *dest)
{
	return pick_impl(pm, m, s, r, tmin, 1, dest);
}

int
pick_figure_exhaustive(const struct pick_model *pm, const struct model *m,
		       const struct state *s, const struct ray *r, double tmin,
		       struct pick_hit *dest)
{
	return pick_impl(pm, m, s, r, tmin, 0, dest);
}

int
pick_scene(const struct pick_target *t, int n, const struct ray *r, double tmin,
	   struct pick_hit *dest)
{
	int found = 0;
	for (int i = 0; i < n; i++) {
		struct pick_hit h;
		if (pick_figure(t[i].pm, t[i].m, t[i].s, r, tmin, &h) &&
		    (!found || h.distance < dest->distance)) {
			*dest = h;
			dest->figure = i;
			found = 1;
		}
	}
	return found;
}

int
pick_extent(const struct pick_model *pm, const struct state *s, const double dir[3], double *lo,
	    double *hi)
{
	int any = 0;
	for (int seg = 0; seg < pm->nseg; seg++) {
		/* dir in the segment's frame: a corner's reach is then one dot product */
		const struct xform *x = &s->seg_xf[seg];
		double d[3], off = 0;
		for (int i = 0; i < 3; i++) {
			d[i] = x->r[i] * dir[0] + x->r[3 + i] * dir[1] + x->r[6 + i] * dir[2];
			off += x->p[i] * dir[i];
		}
		for (int k = pm->seg_part0[seg]; k < pm->seg_part0[seg] + pm->seg_npart[seg]; k++) {
			const struct pick_part *p = &pm->part[k];
			const float *t = pm->tri + 9 * (size_t)p->tri0;
			for (int c = 0; c < 3 * p->ntri; c++, t += 3) {
				double v = off + d[0] * t[0] + d[1] * t[1] + d[2] * t[2];
				if (!any || v < *lo)
					*lo = v;
				if (!any || v > *hi)
					*hi = v;
				any = 1;
			}
		}
	}
	return any;
}
