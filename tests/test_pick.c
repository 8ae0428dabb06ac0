/*
 * test_pick.c - the mouse line and picking against analytic answers: a ray
 * and a triangle (Möller-Trumbore's barycentric weights by hand), boxes,
 * spheres and capsules whose first surface point along a ray is known, the
 * hit's normal, distance, face, edge, vertex and nearest site; the
 * bounding boxes never reject a hit that testing every triangle finds
 * (random rays at the posed human); a pick allocates nothing; and how far
 * a turned box reaches along directions (pick_extent).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "draw/demo_scene.h"
#include "draw/render.h"
#include "draw/tess.h"
#include "draw/view.h"
#include "figure/human.h"
#include "figure/kin.h"
#include "figure/model.h"
#include "figure/state.h"
#include "interact/mouse_line.h"
#include "interact/pick.h"

#include "alloc_count.h"
#include "test_util.h"

#define DEG (M_PI / 180)
static const double QID[4] = { 0, 0, 0, 1 };

/* ---- one segment, one geom, placed by its root ------------------------------ */

struct one {
	struct model *m;
	struct state *s;
	struct pick_model *pm;
};

/* a segment "body" with geom g and sites "a" at site_a and "b" at site_b, its frame at root */
static void
one_make(struct one *o, const struct geom_def *g, const double site_a[3], const double site_b[3],
	 const struct xform *root)
{
	struct model_builder *b = model_builder_create("one");
	struct segment_def sd = segment_default_def();
	sd.name = "body";
	int seg = model_builder_segment(b, &sd);
	int sa = model_builder_site(b, seg, "a", site_a, QID);
	assert_true(model_builder_site(b, seg, "b", site_b, QID) >= 0);
	assert_true(model_builder_geom(b, seg, g) >= 0);
	double zero[3] = { 0, 0, 0 };
	assert_int_equal(model_builder_root(b, sa, zero, QID), 0);
	o->m = model_builder_finish(b);
	assert_non_null(o->m);
	model_builder_free(b);
	o->s = state_make(o->m);
	assert_non_null(o->s);
	/* the root site is "a": put the segment's frame (not the site) at root */
	struct xform at = *root;
	xform_apply(root, site_a, at.p);
	assert_int_equal(state_root_at(o->m, o->s, sa, &at), 0);
	kin_update(o->m, o->s);
	o->pm = pick_model_make(o->m);
	assert_non_null(o->pm);
}

static void
one_free(struct one *o)
{
	pick_model_free(o->pm);
	state_free(o->s);
	model_free(o->m);
}

static struct ray
ray_of(double ox, double oy, double oz, double dx, double dy, double dz)
{
	struct ray r = { { ox, oy, oz }, { dx, dy, dz } };
	double n = sqrt(dx * dx + dy * dy + dz * dz);
	for (int k = 0; k < 3; k++)
		r.d[k] /= n;
	return r;
}

/* a rotation of angle about unit axis (ax, ay, az), then a translation */
static struct xform
place(double ax, double ay, double az, double angle, double px, double py, double pz)
{
	struct xform x;
	double s = sin(angle / 2), q[4] = { ax * s, ay * s, az * s, cos(angle / 2) };
	mathx_quat_to_mat(q, x.r);
	x.p[0] = px;
	x.p[1] = py;
	x.p[2] = pz;
	return x;
}

/* the shapes' common stand: site "a" at the frame's origin, "b" 0.3 m up, the frame at (0, 1, 0) */
static void
one_make_upright(struct one *o, const struct geom_def *g)
{
	double sa[3] = { 0, 0, 0 }, sb[3] = { 0, 0.3, 0 };
	struct xform root = place(0, 1, 0, 0, 0, 1, 0);
	one_make(o, g, sa, sb, &root);
}

static void
assert_vec_near(const double a[3], double x, double y, double z, double tol)
{
	assert_near(a[0], x, tol);
	assert_near(a[1], y, tol);
	assert_near(a[2], z, tol);
}

static struct geom_def
geom(enum geom_kind kind, double s0, double s1, double s2)
{
	struct geom_def g = geom_default_def();
	g.kind = kind;
	g.size[0] = s0;
	g.size[1] = s1;
	g.size[2] = s2;
	return g;
}

/* ---- one triangle ---------------------------------------------------------- */

static void
test_triangle_by_hand(void **unused)
{
	(void)unused;
	/* counter-clockwise seen from +z: the front faces +z */
	const double a[3] = { -1, -1, 0 }, b[3] = { 1, -1, 0 }, c[3] = { 0, 1, 0 };
	double t, u, v;
	struct ray r = ray_of(0, 0, 5, 0, 0, -1);
	/* (0, 0) = a + u (b - a) + v (c - a): v = 1/2, u = 1/4 */
	assert_int_equal(pick_triangle(&r, a, b, c, 0, &t, &u, &v), 1);
	assert_near(t, 5, 1e-15);
	assert_near(u, 0.25, 1e-15);
	assert_near(v, 0.5, 1e-15);
	r = ray_of(0.5, -0.5, 2, 0, 0, -1);
	assert_int_equal(pick_triangle(&r, a, b, c, 0, &t, &u, &v), 1);
	assert_near(t, 2, 1e-15);
	assert_near(u, 0.625, 1e-15);
	assert_near(v, 0.25, 1e-15);
	/* slanted: meets z = 0 at (0.25, 0.25) after 5 sqrt(1.005) */
	r = ray_of(0, 0, 5, 0.05, 0.05, -1);
	assert_int_equal(pick_triangle(&r, a, b, c, 0, &t, &u, &v), 1);
	assert_near(t, 5 * sqrt(1.005), 1e-14);
	assert_near(u, 0.3125, 1e-14);
	assert_near(v, 0.625, 1e-14);
	/* from behind (a back face, culled as drawn), outside, parallel, nearer than tmin */
	r = ray_of(0, 0, -5, 0, 0, 1);
	assert_int_equal(pick_triangle(&r, a, b, c, 0, &t, &u, &v), 0);
	r = ray_of(2, 2, 5, 0, 0, -1);
	assert_int_equal(pick_triangle(&r, a, b, c, 0, &t, &u, &v), 0);
	r = ray_of(0, 0, 1, 1, 0, 0);
	assert_int_equal(pick_triangle(&r, a, b, c, 0, &t, &u, &v), 0);
	r = ray_of(0, 0, 5, 0, 0, -1);
	assert_int_equal(pick_triangle(&r, a, b, c, 6, &t, &u, &v), 0);
	/* pointing away */
	r = ray_of(0, 0, 5, 0, 0, 1);
	assert_int_equal(pick_triangle(&r, a, b, c, 0, &t, &u, &v), 0);
}

/* ---- primitives whose surface is known ----------------------------------------- */

static void
test_box(void **unused)
{
	(void)unused;
	/*
	 * A 2 x 1 x 0.5 box at (0.1, 0.2, 0.3) in a segment turned 90 deg about
	 * y and moved to (1, 2, 3): local x is world -z, local z world +x, so
	 * its centre is at (1.3, 2.2, 2.9) with half extents 0.25, 0.5, 1 along
	 * world x, y, z. Sites: a at the segment's origin (1, 2, 3), b at local
	 * (0.1, 0.2, 1), world (2, 2.2, 2.9).
	 */
	struct geom_def g = geom(GEOM_BOX, 2, 1, 0.5);
	g.pos[0] = 0.1;
	g.pos[1] = 0.2;
	g.pos[2] = 0.3;
	double sa[3] = { 0, 0, 0 }, sb[3] = { 0.1, 0.2, 1 };
	struct xform root = place(0, 1, 0, 90 * DEG, 1, 2, 3);
	struct one o;
	one_make(&o, &g, sa, sb, &root);
	struct pick_hit h;

	struct ray r = ray_of(1.3, 2.2, 10, 0, 0, -1);
	assert_int_equal(pick_figure(o.pm, o.m, o.s, &r, 0, &h), 1);
	assert_near(h.distance, 10 - 3.9, 1e-6);
	assert_vec_near(h.point, 1.3, 2.2, 3.9, 1e-6);
	assert_vec_near(h.normal, 0, 0, 1, 1e-6);
	assert_int_equal(h.segment, 0);
	assert_int_equal(h.geom, 0);
	assert_string_equal(o.m->site_name[h.site], "a"); /* 0.97 m from a, 1.22 from b */

	r = ray_of(10, 2.2, 2.9, -1, 0, 0);
	assert_int_equal(pick_figure(o.pm, o.m, o.s, &r, 0, &h), 1);
	assert_near(h.distance, 10 - 1.55, 1e-6);
	assert_vec_near(h.normal, 1, 0, 0, 1e-6);
	assert_string_equal(o.m->site_name[h.site], "b"); /* 0.45 m from b, 0.59 from a */

	r = ray_of(1.3, -10, 2.9, 0, 1, 0);
	assert_int_equal(pick_figure(o.pm, o.m, o.s, &r, 0, &h), 1);
	assert_near(h.distance, 10 + 1.7, 1e-6);
	assert_vec_near(h.normal, 0, -1, 0, 1e-6);

	/* just past the side at x = 1.55; from inside (back faces); beyond tmin */
	r = ray_of(1.56, 2.2, 10, 0, 0, -1);
	assert_int_equal(pick_figure(o.pm, o.m, o.s, &r, 0, &h), 0);
	r = ray_of(1.3, 2.2, 2.9, 0, 0, 1);
	assert_int_equal(pick_figure(o.pm, o.m, o.s, &r, 0, &h), 0);
	r = ray_of(1.3, 2.2, 10, 0, 0, -1);
	assert_int_equal(pick_figure(o.pm, o.m, o.s, &r, 6.2, &h), 0);

	/*
	 * Near the corner (1.55, 2.7, 3.9) of the face facing +z: the nearest
	 * edge is the face's side at x = 1.55 (5 mm away; each diagonal is
	 * farther), the nearest vertex that corner. Vertex numbers name the
	 * drawn box mesh's vertices: placed as drawn, they must be there.
	 */
	r = ray_of(1.545, 2.6, 10, 0, 0, -1);
	assert_int_equal(pick_figure(o.pm, o.m, o.s, &r, 0, &h), 1);
	struct tess_mesh box;
	assert_int_equal(view_mesh_tess(VIEW_MESH_BOX, 1, &box), 0);
	double w[3][3];
	int ids[3] = { h.vertex, h.edge[0], h.edge[1] };
	for (int k = 0; k < 3; k++) {
		const float *q = box.vn + 6 * ids[k];
		double local[3] = { q[0] * 2 + 0.1, q[1] * 1 + 0.2, q[2] * 0.5 + 0.3 };
		xform_apply(&o.s->seg_xf[0], local, w[k]);
	}
	assert_vec_near(w[0], 1.55, 2.7, 3.9, 1e-6);
	assert_near(w[1][0], 1.55, 1e-6);
	assert_near(w[1][2], 3.9, 1e-6);
	assert_near(w[2][0], 1.55, 1e-6);
	assert_near(w[2][2], 3.9, 1e-6);
	assert_true(fabs(w[1][1] - w[2][1]) > 0.9); /* the whole side, 1 m long */
	assert_true(h.face >= 0 && h.face < box.nidx / 3);
	tess_free(&box);
	one_free(&o);
}

/*
 * How far a figure reaches along a direction: the box of test_box, whose
 * world half extents are 0.25, 0.5 and 1 along x, y and z about (1.3,
 * 2.2, 2.9), reaches c.d +- (0.25 |dx| + 0.5 |dy| + |dz|) along unit d.
 */
static void
test_extent(void **unused)
{
	(void)unused;
	struct geom_def g = geom(GEOM_BOX, 2, 1, 0.5);
	g.pos[0] = 0.1;
	g.pos[1] = 0.2;
	g.pos[2] = 0.3;
	double sa[3] = { 0, 0, 0 }, sb[3] = { 0.1, 0.2, 1 };
	struct xform root = place(0, 1, 0, 90 * DEG, 1, 2, 3);
	struct one o;
	one_make(&o, &g, sa, sb, &root);
	const double c[3] = { 1.3, 2.2, 2.9 }, half[3] = { 0.25, 0.5, 1 };
	const double dirs[][3] = { { 1, 0, 0 }, { 0, 0, -1 }, { 0.6, 0, 0.8 }, { -0.48, 0.6, 0.64 } };
	for (size_t k = 0; k < sizeof dirs / sizeof *dirs; k++) {
		const double *d = dirs[k];
		double mid = c[0] * d[0] + c[1] * d[1] + c[2] * d[2];
		double reach = half[0] * fabs(d[0]) + half[1] * fabs(d[1]) + half[2] * fabs(d[2]);
		double lo = 0, hi = 0;
		assert_int_equal(pick_extent(o.pm, o.s, d, &lo, &hi), 1);
		assert_near(lo, mid - reach, 1e-6);
		assert_near(hi, mid + reach, 1e-6);
	}
	one_free(&o);
}

static void
test_sphere(void **unused)
{
	(void)unused;
	/* a ball of radius 0.3 at (0, 1, 0); its mesh has vertices on the sphere, faces inside */
	struct geom_def g = geom(GEOM_ELLIPSOID, 0.3, 0.3, 0.3);
	struct one o;
	one_make_upright(&o, &g);
	struct pick_hit h;

	/* through the centre: the equator's vertex at +z */
	struct ray r = ray_of(0, 1, 5, 0, 0, -1);
	assert_int_equal(pick_figure(o.pm, o.m, o.s, &r, 0, &h), 1);
	assert_near(h.distance, 4.7, 1e-6);
	assert_true(h.normal[2] > cos(15 * DEG));

	/* off centre: on or just inside the sphere, never outside */
	r = ray_of(0.1, 1.15, 5, 0, 0, -1);
	double z = sqrt(0.09 - 0.01 - 0.0225);
	assert_int_equal(pick_figure(o.pm, o.m, o.s, &r, 0, &h), 1);
	assert_true(h.distance >= 5 - z - 1e-6);
	assert_true(h.distance <= 5 - z + 0.02);
	/* the normal points out, within a facet's angle of the sphere's */
	double n[3] = { 0.1 / 0.3, 0.15 / 0.3, z / 0.3 };
	assert_true(mathx_dot(n, h.normal) > cos(20 * DEG));
	assert_near(mathx_dot(h.normal, h.normal), 1, 1e-12);

	/* a line that passes the sphere by 1 cm */
	r = ray_of(0.31, 1, 5, 0, 0, -1);
	assert_int_equal(pick_figure(o.pm, o.m, o.s, &r, 0, &h), 0);
	one_free(&o);
}

static void
test_capsule(void **unused)
{
	(void)unused;
	/* radius 0.1, straight part 0.4 along y, centred at (0, 1, 0): poles at y = 1.3 and 0.7 */
	struct geom_def g = geom(GEOM_CAPSULE, 0.1, 0.4, 0);
	struct one o;
	one_make_upright(&o, &g);
	struct pick_hit h;

	struct ray r = ray_of(0, 6, 0, 0, -1, 0);
	assert_int_equal(pick_figure(o.pm, o.m, o.s, &r, 0, &h), 1);
	assert_near(h.distance, 6 - 1.3, 1e-6);
	assert_true(h.normal[1] > cos(25 * DEG));
	assert_int_equal(h.part, 1); /* the upper cap */
	assert_string_equal(o.m->site_name[h.site], "b");

	/* the lower cap is the upper one turned over: its outside still faces out */
	r = ray_of(0, -4, 0, 0, 1, 0);
	assert_int_equal(pick_figure(o.pm, o.m, o.s, &r, 0, &h), 1);
	assert_near(h.distance, 4 + 0.7, 1e-6);
	assert_true(h.normal[1] < -cos(25 * DEG));
	assert_int_equal(h.part, 2);
	assert_string_equal(o.m->site_name[h.site], "a");

	/* the tube's side, at a vertex column (x = r, z = 0) */
	r = ray_of(5, 1.1, 0, -1, 0, 0);
	assert_int_equal(pick_figure(o.pm, o.m, o.s, &r, 0, &h), 1);
	assert_near(h.distance, 5 - 0.1, 1e-6);
	assert_true(h.normal[0] > cos(10 * DEG));
	assert_int_equal(h.part, 0); /* the tube */
	assert_near(h.normal[1], 0, 1e-6);
	one_free(&o);
}

static void
test_nearest_figure_wins(void **unused)
{
	(void)unused;
	struct geom_def ball = geom(GEOM_ELLIPSOID, 0.3, 0.3, 0.3), box = geom(GEOM_BOX, 0.2, 0.2, 0.2);
	double sa[3] = { 0, 0, 0 };
	struct xform at0 = place(0, 1, 0, 0, 0, 1, 0), at1 = place(0, 1, 0, 0, 0, 1, 1);
	struct one a, b;
	one_make(&a, &ball, sa, sa, &at0);
	one_make(&b, &box, sa, sa, &at1);
	struct pick_target t[2] = { { a.pm, a.m, a.s }, { b.pm, b.m, b.s } };
	struct pick_hit h;
	/* from +z the box (its face at z = 1.1) is in front of the ball (z = 0.3) */
	struct ray r = ray_of(0, 1, 5, 0, 0, -1);
	assert_int_equal(pick_scene(t, 2, &r, 0, &h), 1);
	assert_int_equal(h.figure, 1);
	assert_near(h.distance, 3.9, 1e-6);
	/* from -z the ball is first */
	r = ray_of(0, 1, -5, 0, 0, 1);
	assert_int_equal(pick_scene(t, 2, &r, 0, &h), 1);
	assert_int_equal(h.figure, 0);
	assert_near(h.distance, 4.7, 1e-6);
	r = ray_of(0, 3, -5, 0, 0, 1);
	assert_int_equal(pick_scene(t, 2, &r, 0, &h), 0);
	one_free(&a);
	one_free(&b);
}

/* ---- the human: boxes against every triangle ----------------------------------- */

static double
lcg(uint32_t *s)
{
	*s = *s * 1664525u + 1013904223u;
	return (*s >> 8) / 16777216.0;
}

struct posed {
	struct model *m;
	struct state *s;
	struct pick_model *pm;
};

static void
posed_make(struct posed *p)
{
	char err[256];
	struct human_def hd = human_default_def(HUMAN_MALE);
	p->m = human_build(&hd, err, sizeof err);
	assert_non_null(p->m);
	p->s = state_make(p->m);
	/* a posture drawn within the limits, a third of the way out at most */
	uint32_t seed = 11;
	for (int d = 0; d < p->m->ndof; d++) {
		double lo = p->m->dof_lo[d], hi = p->m->dof_hi[d], mid = p->m->dof_init[d];
		p->s->q[d] = mid + (lcg(&seed) - 0.5) * 0.66 * (hi - lo) / 2;
		if (p->s->q[d] < lo || p->s->q[d] > hi)
			p->s->q[d] = mid;
	}
	kin_update(p->m, p->s);
	p->pm = pick_model_make(p->m);
	assert_non_null(p->pm);
}

static void
posed_free(struct posed *p)
{
	pick_model_free(p->pm);
	state_free(p->s);
	model_free(p->m);
}

static void
same_hit(const struct posed *p, const struct ray *r, int *hits)
{
	struct pick_hit a, b;
	int ha = pick_figure(p->pm, p->m, p->s, r, 0, &a);
	int hb = pick_figure_exhaustive(p->pm, p->m, p->s, r, 0, &b);
	assert_int_equal(ha, hb);
	if (!ha)
		return;
	(*hits)++;
	assert_true(a.distance == b.distance);
	assert_int_equal(a.segment, b.segment);
	assert_int_equal(a.geom, b.geom);
	assert_int_equal(a.face, b.face);
}

static void
test_boxes_never_reject_a_hit(void **unused)
{
	(void)unused;
	struct posed p;
	posed_make(&p);
	uint32_t seed = 5;
	int hits = 0;
	/* random lines from 2.5 m away towards points within 8 cm of the segments' origins */
	for (int i = 0; i < 600; i++) {
		double th = 2 * M_PI * lcg(&seed), ph = acos(2 * lcg(&seed) - 1);
		double o[3] = { 2.5 * sin(ph) * cos(th), 1 + 2.5 * cos(ph), 2.5 * sin(ph) * sin(th) };
		const double *c = p.s->seg_xf[(int)(lcg(&seed) * p.m->nseg)].p;
		double aim[3] = { c[0] + 0.16 * (lcg(&seed) - 0.5), c[1] + 0.16 * (lcg(&seed) - 0.5),
				  c[2] + 0.16 * (lcg(&seed) - 0.5) };
		struct ray r = ray_of(o[0], o[1], o[2], aim[0] - o[0], aim[1] - o[1], aim[2] - o[2]);
		same_hit(&p, &r, &hits);
	}
	assert_true(hits > 200);
	/* grazing lines: aimed at corners and edge midpoints of the triangles themselves */
	for (int i = 0; i < 600; i++) {
		int seg = (int)(lcg(&seed) * p.pm->nseg);
		int tri = (int)(lcg(&seed) * p.pm->ntri);
		for (int s = 0; s < p.pm->nseg; s++) {
			int first = p.pm->part[p.pm->seg_part0[s]].tri0;
			const struct pick_part *last = &p.pm->part[p.pm->seg_part0[s] + p.pm->seg_npart[s] - 1];
			if (p.pm->seg_npart[s] && tri >= first && tri < last->tri0 + last->ntri)
				seg = s;
		}
		const float *f = p.pm->tri + 9 * tri;
		int k = i % 3;
		double local[3], aim[3];
		for (int j = 0; j < 3; j++)
			local[j] = i % 2 ? f[3 * k + j] : (f[3 * k + j] + f[3 * ((k + 1) % 3) + j]) / 2;
		xform_apply(&p.s->seg_xf[seg], local, aim);
		double th = 2 * M_PI * lcg(&seed), ph = acos(2 * lcg(&seed) - 1);
		double o[3] = { aim[0] + 2.5 * sin(ph) * cos(th), aim[1] + 2.5 * cos(ph),
				aim[2] + 2.5 * sin(ph) * sin(th) };
		struct ray r = ray_of(o[0], o[1], o[2], aim[0] - o[0], aim[1] - o[1], aim[2] - o[2]);
		same_hit(&p, &r, &hits);
	}
	posed_free(&p);
}

static void
test_pick_allocates_nothing(void **unused)
{
	(void)unused;
	struct posed p;
	posed_make(&p);
	struct pick_hit h;
	struct ray r = ray_of(0, 1, 3, 0, 0, -1);
#if COUNT_ALLOCS
	long before = allocs;
#endif
	int n = 0;
	for (int i = 0; i < 100; i++) {
		r.o[0] = -0.5 + i / 100.0;
		n += pick_figure(p.pm, p.m, p.s, &r, 0, &h);
	}
#if COUNT_ALLOCS
	assert_int_equal(allocs, before);
#endif
	assert_true(n > 10);
	posed_free(&p);
}

/* ---- picking hits what is drawn ------------------------------------------------ */

#define PW 320
#define PH 240

/* the picture of the seated scene (no floor, no icons), or of nothing, packed RGBA */
static void
picture(struct render *r, struct drawlist *dl, const struct demo_scene *sc,
	const struct camera *cam, const int base[2], int figures, uint8_t *dest)
{
	view_begin(dl, cam, PW, PH);
	dl->floor = 0;
	if (figures) {
		view_add_figure(dl, sc->human, sc->hs, base[0]);
		view_add_figure(dl, sc->seat, sc->ss, base[1]);
	}
	struct frame f;
	assert_int_equal(render_frame(r, dl, 0, &f), 0);
	for (int y = 0; y < PH; y++)
		memcpy(dest + 4 * PW * y, f.rgba + (size_t)f.stride * y, 4 * PW);
}

static void
test_pick_hits_what_is_drawn(void **unused)
{
	(void)unused;
	/*
	 * Every pixel of the driver scene: the mouse line through its centre
	 * hits a figure exactly when the renderer drew one there (the picture
	 * differs from the empty one). Only silhouette pixels, where a
	 * neighbour disagrees, may go either way.
	 */
	char err[256];
	struct demo_scene sc;
	assert_int_equal(demo_scene_make(&sc, "seated", "src/figure/library/vehicle_seat.fig", err,
					 sizeof err), 0);
	struct render_def d = render_default_def();
	d.max_w = PW;
	d.max_h = PH;
	d.samples = 0;
	d.shadows = 0;
	struct render *r = render_make(&d, err, sizeof err);
	if (!r) {
		demo_scene_free(&sc);
		skip();
	}
	struct drawlist *dl = view_drawlist_make();
	int base[2] = { render_add_model(r, sc.human, err, sizeof err),
			render_add_model(r, sc.seat, err, sizeof err) };
	struct camera cam;
	demo_scene_camera(&sc, &cam);
	uint8_t *full = malloc(4 * PW * PH), *empty = malloc(4 * PW * PH);
	unsigned char *drawn = malloc(PW * PH), *hit = malloc(PW * PH);
	picture(r, dl, &sc, &cam, base, 1, full);
	picture(r, dl, &sc, &cam, base, 0, empty);

	struct pick_model *ph = pick_model_make(sc.human), *ps = pick_model_make(sc.seat);
	struct pick_target t[2] = { { ph, sc.human, sc.hs }, { ps, sc.seat, sc.ss } };
	int covered = 0;
	for (int y = 0; y < PH; y++)
		for (int x = 0; x < PW; x++) {
			struct ray ray;
			struct pick_hit h;
			size_t i = (size_t)y * PW + x;
			drawn[i] = memcmp(full + 4 * i, empty + 4 * i, 3) != 0;
			assert_int_equal(mouse_line(&cam, PW, PH, x + 0.5, y + 0.5, &ray), 0);
			hit[i] = (unsigned char)pick_scene(t, 2, &ray, 0, &h);
			covered += drawn[i];
		}
	int inside = 0, wrong = 0;
	for (int y = 1; y < PH - 1; y++)
		for (int x = 1; x < PW - 1; x++) {
			size_t i = (size_t)y * PW + x;
			int edge = 0;
			for (int dy = -1; dy <= 1; dy++)
				for (int dx = -1; dx <= 1; dx++)
					edge |= drawn[i + dy * PW + dx] != drawn[i];
			if (edge)
				continue;
			inside++;
			if (hit[i] != drawn[i]) {
				if (wrong < 5)
					print_message("pixel (%d, %d): drawn %d, hit %d\n", x, y, drawn[i],
						      hit[i]);
				wrong++;
			}
		}
	assert_true(covered > PW * PH / 10); /* the scene fills a good part of the picture */
	assert_true(inside > PW * PH / 2);
	assert_int_equal(wrong, 0);
	free(full);
	free(empty);
	free(drawn);
	free(hit);
	pick_model_free(ph);
	pick_model_free(ps);
	view_drawlist_free(dl);
	render_free(r);
	demo_scene_free(&sc);
}

/* ---- the mouse line ---------------------------------------------------------- */

static double
angle_between(const double a[3], const double b[3])
{
	double c[3];
	mathx_cross(a, b, c);
	return atan2(sqrt(mathx_dot(c, c)), mathx_dot(a, b));
}

static void
test_mouse_line_by_hand(void **unused)
{
	(void)unused;
	struct camera cam;
	view_camera_default(&cam);
	double eye[3] = { 1, 2, 3 }, target[3] = { 0, 1, 0 };
	view_camera_aim(&cam, eye, target);
	cam.fovy = 50 * DEG;
	double sight[3] = { -1, -1, -3 }, xc[3], yc[3];
	for (int k = 0; k < 3; k++)
		sight[k] /= sqrt(11.0);
	for (int k = 0; k < 3; k++) {
		xc[k] = cam.xf.r[3 * k];
		yc[k] = cam.xf.r[3 * k + 1];
	}
	struct ray r;
	const int w = 640, h = 480;
	const double aspect = 640.0 / 480, th = tan(25 * DEG);

	/* the image's centre is on the line of sight */
	assert_int_equal(mouse_line(&cam, w, h, 320, 240, &r), 0);
	assert_vec_near(r.o, 1, 2, 3, 0);
	assert_vec_near(r.d, sight[0], sight[1], sight[2], 1e-15);

	/* the right edge's middle: aspect tan(fovy / 2) to the right, level */
	assert_int_equal(mouse_line(&cam, w, h, 640, 240, &r), 0);
	assert_near(angle_between(r.d, sight), atan(aspect * th), 1e-14);
	assert_near(mathx_dot(r.d, yc), 0, 1e-15);
	assert_true(mathx_dot(r.d, xc) > 0);

	/* the top edge's middle: fovy / 2 up (y runs down the image) */
	assert_int_equal(mouse_line(&cam, w, h, 320, 0, &r), 0);
	assert_near(angle_between(r.d, sight), 25 * DEG, 1e-14);
	assert_true(mathx_dot(r.d, yc) > 0);

	/* the top-left pixel's centre: half a pixel in from each edge */
	assert_int_equal(mouse_line(&cam, w, h, 0.5, 0.5, &r), 0);
	double depth = mathx_dot(r.d, sight);
	assert_near(mathx_dot(r.d, xc) / depth, -(1 - 1.0 / w) * aspect * th, 1e-14);
	assert_near(mathx_dot(r.d, yc) / depth, (1 - 1.0 / h) * th, 1e-14);
	assert_near(mathx_dot(r.d, r.d), 1, 1e-15);

	/* what is not a pixel or an image */
	assert_int_equal(mouse_line(&cam, w, h, NAN, 1, &r), -1);
	assert_int_equal(mouse_line(&cam, w, h, 1, INFINITY, &r), -1);
	assert_int_equal(mouse_line(&cam, 0, h, 1, 1, &r), -1);

	/* a named view: its own field of view */
	struct env_view v = { .used = 1, .width = 320, .height = 240, .fovy_deg = 70,
			      .eye = { 0, 1.2, 3 }, .target = { 0, 1, 0 } };
	assert_int_equal(mouse_line_of_view(&v, 160, 0, &r), 0);
	double s2[3] = { 0, -0.2, -3 };
	for (int k = 0; k < 3; k++)
		s2[k] /= sqrt(9.04);
	assert_near(angle_between(r.d, s2), 35 * DEG, 1e-14);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_triangle_by_hand),
		cmocka_unit_test(test_box),
		cmocka_unit_test(test_extent),
		cmocka_unit_test(test_sphere),
		cmocka_unit_test(test_capsule),
		cmocka_unit_test(test_nearest_figure_wins),
		cmocka_unit_test(test_boxes_never_reject_a_hit),
		cmocka_unit_test(test_pick_allocates_nothing),
		cmocka_unit_test(test_pick_hits_what_is_drawn),
		cmocka_unit_test(test_mouse_line_by_hand),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
