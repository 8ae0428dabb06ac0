/*
 * test_pack.c - the draw list packed by class, without GL: class order and
 * depth order, the coarse meshes of the shadow copies, positions through
 * the instance's matrix and normals through its inverse transpose (an
 * analytic answer for a sheared box), full arrays, unknown meshes.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "draw/pack.h"

/* column-major translation by (x, y, z) */
static void
translate(float x, float y, float z, float dest[16])
{
	memset(dest, 0, 16 * sizeof *dest);
	dest[0] = dest[5] = dest[10] = dest[15] = 1;
	dest[12] = x;
	dest[13] = y;
	dest[14] = z;
}

struct fixture {
	struct pack p;
	struct tess_mesh mesh[2]; /* 0: a fine box stand-in, 1: its coarse version */
	int lod[2];
	struct drawlist *dl;
	float view[16]; /* looking down -z from the origin: depth is -z */
};

static int
setup(void **state)
{
	static struct fixture f;
	memset(&f, 0, sizeof f);
	if (pack_init(&f.p) < 0 || tess_box(&f.mesh[0]) < 0 || tess_box(&f.mesh[1]) < 0)
		return -1;
	/* the coarse version: one triangle of the box, so it is told apart */
	f.mesh[1].nidx = 3;
	f.lod[0] = 1;
	f.lod[1] = 1;
	f.dl = view_drawlist_make();
	translate(0, 0, 0, f.view);
	*state = &f;
	return f.dl ? 0 : -1;
}

static int
teardown(void **state)
{
	struct fixture *f = *state;
	pack_free(&f->p);
	tess_free(&f->mesh[0]);
	tess_free(&f->mesh[1]);
	view_drawlist_free(f->dl);
	return 0;
}

static void
add(struct fixture *f, int mesh, float z, float alpha, int shadow)
{
	float m[16], rgba[4] = { 1, 1, 1, alpha };
	translate(0, 0, z, m);
	assert_true(view_add_instance(f->dl, mesh, m, rgba, shadow) >= 0);
}

/* the z of the first vertex packed at index position k */
static float
z_at(const struct pack *p, int k)
{
	return p->pv[p->pi[k]].p[2];
}

static void
test_classes_in_order_and_depth(void **state)
{
	struct fixture *f = *state;
	f->dl->ninst = 0;
	int box = f->mesh[0].nidx;
	add(f, 0, -5, 1, 1);    /* a caster */
	add(f, 0, -2, 1, 0);    /* opaque, near */
	add(f, 0, -9, 1, 0);    /* opaque, far */
	add(f, 0, -3, 0.5f, 0); /* transparent, near */
	add(f, 0, -8, 0.5f, 0); /* transparent, far */
	pack_drawlist(&f->p, f->dl, f->view, f->mesh, f->lod, 2);
	const struct pack *p = &f->p;
	assert_int_equal(p->range[PACK_CAST][1], box);
	assert_int_equal(p->range[PACK_OPAQUE][1], 2 * box);
	assert_int_equal(p->range[PACK_CLEAR][1], 2 * box);
	assert_int_equal(p->range[PACK_SHADOW][1], 3); /* the caster's coarse version */
	/* classes follow each other in the index array */
	assert_int_equal(p->range[PACK_CAST][0], 0);
	assert_int_equal(p->range[PACK_OPAQUE][0], box);
	assert_int_equal(p->range[PACK_CLEAR][0], 3 * box);
	assert_int_equal(p->range[PACK_SHADOW][0], 5 * box);
	/* opaque near to far (early depth rejection), transparent far to near (blending) */
	assert_true(z_at(p, p->range[PACK_OPAQUE][0]) > -2.6f);
	assert_true(z_at(p, p->range[PACK_OPAQUE][0] + box) < -8.4f);
	assert_true(z_at(p, p->range[PACK_CLEAR][0]) < -7.4f);
	assert_true(z_at(p, p->range[PACK_CLEAR][0] + box) > -3.6f);
	assert_true(z_at(p, p->range[PACK_SHADOW][0]) < -4.4f && z_at(p, p->range[PACK_SHADOW][0]) > -5.6f);
	/* the shadow copies are not counted as drawn */
	assert_int_equal(p->instances, 5);
	assert_int_equal(p->triangles, 5 * box / 3);
}

static void
test_positions_and_normals_of_a_sheared_box(void **state)
{
	struct fixture *f = *state;
	f->dl->ninst = 0;
	/* A = [[1, 1, 0], [0, 2, 0], [0, 0, 1]] (row-major), then translated by (1, 2, 3) */
	float m[16] = { 1, 0, 0, 0, /* column 0 */
			1, 2, 0, 0, /* column 1 */
			0, 0, 1, 0, /* column 2 */
			1, 2, 3, 1 };
	float rgba[4] = { 1, 0, 0, 1 };
	assert_true(view_add_instance(f->dl, 0, m, rgba, 0) >= 0);
	pack_drawlist(&f->p, f->dl, f->view, f->mesh, f->lod, 2);
	const struct tess_mesh *b = &f->mesh[0];
	assert_int_equal(f->p.nv, b->nvert);
	for (int k = 0; k < b->nvert; k++) {
		const float *s = b->vn + 6 * k;
		const struct pack_vertex *v = &f->p.pv[k];
		/* x' = A x + t */
		assert_float_equal(v->p[0], s[0] + s[1] + 1, 1e-6);
		assert_float_equal(v->p[1], 2 * s[1] + 2, 1e-6);
		assert_float_equal(v->p[2], s[2] + 3, 1e-6);
		/* n' = A^-T n, A^-T = [[1, 0, 0], [-1/2, 1/2, 0], [0, 0, 1]]: it stays normal to
		 * every edge of its face, which A carries to A e */
		double nx = s[3], ny = -0.5 * s[3] + 0.5 * s[4], nz = s[5];
		assert_float_equal(v->n[0], nx, 1e-6);
		assert_float_equal(v->n[1], ny, 1e-6);
		assert_float_equal(v->n[2], nz, 1e-6);
		assert_int_equal(v->c[0], 255);
		assert_int_equal(v->c[1], 0);
		assert_int_equal(v->c[3], 255);
	}
	/* indices point at this instance's vertices */
	for (int k = 0; k < f->p.ni; k++)
		assert_true(f->p.pi[k] < (unsigned)b->nvert);
}

static void
test_unknown_and_degenerate_instances_are_skipped(void **state)
{
	struct fixture *f = *state;
	f->dl->ninst = 0;
	add(f, 7, -1, 1, 1); /* no such mesh */
	float flat[16];
	translate(0, 0, -1, flat);
	flat[0] = 0; /* a matrix with no inverse: no normals */
	float rgba[4] = { 1, 1, 1, 1 };
	assert_true(view_add_instance(f->dl, 0, flat, rgba, 1) >= 0);
	pack_drawlist(&f->p, f->dl, f->view, f->mesh, f->lod, 2);
	assert_int_equal(f->p.nv, 0);
	assert_int_equal(f->p.ni, 0);
	assert_int_equal(f->p.instances, 0);
	assert_int_equal(f->p.triangles, 0);
}

static void
test_full_arrays_end_the_class(void **state)
{
	struct fixture *f = *state;
	struct tess_mesh ball[2];
	assert_int_equal(tess_sphere(64, 34, &ball[0]), 0);
	ball[1] = ball[0];
	/* spheres whose vertices and indices fit */
	int fit_v = PACK_MAX_VERT / ball[0].nvert, fit_i = PACK_MAX_IDX / ball[0].nidx;
	int fit = fit_v < fit_i ? fit_v : fit_i;
	assert_true(fit + 20 < VIEW_MAX_INST);
	f->dl->ninst = 0;
	for (int i = 0; i < fit + 20; i++)
		add(f, 0, -1 - 0.001f * (float)i, 1, 0);
	add(f, 1, -0.5f, 0.5f, 0); /* a transparent one: its class still has room */
	pack_drawlist(&f->p, f->dl, f->view, ball, f->lod, 2);
	assert_true(f->p.nv <= PACK_MAX_VERT && f->p.ni <= PACK_MAX_IDX);
	assert_int_equal(f->p.range[PACK_OPAQUE][1], fit * ball[0].nidx);
	assert_int_equal(f->p.instances, fit);
	assert_int_equal(f->p.range[PACK_CLEAR][1], 0); /* no room left for its sphere either */
	tess_free(&ball[0]);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_classes_in_order_and_depth),
		cmocka_unit_test(test_positions_and_normals_of_a_sheared_box),
		cmocka_unit_test(test_unknown_and_degenerate_instances_are_skipped),
		cmocka_unit_test(test_full_arrays_end_the_class),
	};
	return cmocka_run_group_tests(tests, setup, teardown);
}
