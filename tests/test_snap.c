/*
 * test_snap.c - each snapping kind of Appendix B.4 on a known box (the
 * unit cube [0,1]^3, its top face, an edge along x, a site on its top
 * turned 90 degrees about y), against answers worked out by hand; the
 * orientation snaps leave G's axes on the target's (each either way) by
 * the least turn.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "interact/geom.h"
#include "interact/snap.h"
#include "test_util.h"

/* the cube's top face (y = 1), counter-clockwise from above; an edge along x at y = z = 1 */
static struct snap_feature
box_feature(void)
{
	struct snap_feature f;
	memset(&f, 0, sizeof f);
	double face[3][3] = { { 0, 1, 0 }, { 0, 1, 1 }, { 1, 1, 1 } };
	memcpy(f.face, face, sizeof face);
	double edge[2][3] = { { 0, 1, 1 }, { 1, 1, 1 } };
	memcpy(f.edge, edge, sizeof edge);
	f.vertex[0] = 1, f.vertex[1] = 1, f.vertex[2] = 1;
	/* a site at the top's centre, turned 90 degrees about y: x -> -z, z -> x */
	xform_identity(&f.site);
	f.site.p[0] = 0.5, f.site.p[1] = 1, f.site.p[2] = 0.5;
	geom_rotation((double[3]){ 0, 1, 0 }, M_PI / 2, f.site.r);
	f.has_site = 1;
	return f;
}

static struct xform
g_at(double x, double y, double z, double turn_y_deg)
{
	struct xform g;
	xform_identity(&g);
	g.p[0] = x, g.p[1] = y, g.p[2] = z;
	geom_rotation((double[3]){ 0, 1, 0 }, turn_y_deg * M_PI / 180, g.r);
	return g;
}

static void
assert_p(const struct xform *x, double a, double b, double c)
{
	assert_near(x->p[0], a, 1e-12);
	assert_near(x->p[1], b, 1e-12);
	assert_near(x->p[2], c, 1e-12);
}

static void
test_positions(void **unused)
{
	(void)unused;
	struct snap_feature f = box_feature();
	struct xform g = g_at(2, 3, -1, 10), s;
	assert_int_equal(snap_apply(SNAP_SITE_POSITION, &f, &g, &s), 0);
	assert_p(&s, 0.5, 1, 0.5);
	assert_true(!memcmp(s.r, g.r, sizeof s.r)); /* orientation untouched */
	assert_int_equal(snap_apply(SNAP_NODE_POSITION, &f, &g, &s), 0);
	assert_p(&s, 1, 1, 1);
	/* G at (2, 3, -1): its nearest edge point is the end (1, 1, 1); on the line, x = 2 */
	assert_int_equal(snap_apply(SNAP_EDGE_POSITION, &f, &g, &s), 0);
	assert_p(&s, 1, 1, 1);
	assert_int_equal(snap_apply(SNAP_EDGE_LINE, &f, &g, &s), 0);
	assert_p(&s, 2, 1, 1);
	/* the face's point nearest (0.2, 5, 0.7): straight below, inside the triangle */
	struct xform above = g_at(0.2, 5, 0.7, 0);
	assert_int_equal(snap_apply(SNAP_FACE_POSITION, &f, &above, &s), 0);
	assert_p(&s, 0.2, 1, 0.7);
	/* outside the triangle (x > z): onto its edge from (0,1,0) to (1,1,1), nearest (0.5,1,0.5) */
	struct xform side = g_at(0.8, 4, 0.2, 0);
	assert_int_equal(snap_apply(SNAP_FACE_POSITION, &f, &side, &s), 0);
	assert_p(&s, 0.5, 1, 0.5);
	assert_int_equal(snap_apply(SNAP_FACE_PLANE, &f, &side, &s), 0);
	assert_p(&s, 0.8, 1, 0.2);
	assert_int_equal(snap_apply(SNAP_FACE_CENTER, &f, &side, &s), 0);
	assert_p(&s, 1.0 / 3, 1, 2.0 / 3);
}

static void
test_orientations(void **unused)
{
	(void)unused;
	struct snap_feature f = box_feature();
	struct xform s, g = g_at(2, 3, -1, 30); /* 30 degrees about y */
	/* site orientation: the site is at 90 about y; nearest squared-up frames are at 0, 90,
	 * 180, 270 about y (plus turns that move y): 30 is nearest 0 */
	assert_int_equal(snap_apply(SNAP_SITE_ORIENTATION, &f, &g, &s), 0);
	assert_p(&s, 2, 3, -1);
	for (int k = 0; k < 9; k++)
		assert_near(s.r[k], k % 4 == 0 ? 1 : 0, 1e-12);
	struct xform g70 = g_at(0, 0, 0, 70), s70;
	assert_int_equal(snap_apply(SNAP_SITE, &f, &g70, &s70), 0);
	assert_p(&s70, 0.5, 1, 0.5);
	for (int k = 0; k < 9; k++)
		assert_near(s70.r[k], f.site.r[k], 1e-12); /* 70 is nearest 90 */
	/* edge orientation: the edge runs along x; G turned 30 about y has x 30 off: back to 0 */
	assert_int_equal(snap_apply(SNAP_EDGE_ORIENTATION, &f, &g, &s), 0);
	assert_near(s.r[0], 1, 1e-12);
	assert_near(fabs(s.r[4]), 1, 1e-12);
	/* face orientation: the top's normal is +y, G's y already along it: nothing moves */
	assert_int_equal(snap_apply(SNAP_FACE_ORIENTATION, &f, &g, &s), 0);
	for (int k = 0; k < 9; k++)
		assert_near(s.r[k], g.r[k], 1e-12);
	/* a G tipped 20 degrees about x: its y turns back onto the normal by the least angle */
	struct xform tip;
	xform_identity(&tip);
	geom_rotation((double[3]){ 1, 0, 0 }, 20 * M_PI / 180, tip.r);
	assert_int_equal(snap_apply(SNAP_FACE_ORIENTATION, &f, &tip, &s), 0);
	assert_near(s.r[4], 1, 1e-12);  /* y axis (column 1) is (0, 1, 0) */
	assert_near(s.r[0], 1, 1e-12);  /* x untouched: the turn was about x */
}

static void
test_names_and_refusals(void **unused)
{
	(void)unused;
	for (int k = 0; k < SNAP_KINDS; k++)
		assert_int_equal(snap_kind_named(snap_kind_name(k)), k);
	assert_int_equal(snap_kind_named("vertex"), -1);
	struct snap_feature f = box_feature();
	f.has_site = 0;
	struct xform g = g_at(0, 0, 0, 0), s;
	assert_int_equal(snap_apply(SNAP_SITE, &f, &g, &s), -1);
	memcpy(f.edge[1], f.edge[0], sizeof f.edge[0]);
	assert_int_equal(snap_apply(SNAP_EDGE_LINE, &f, &g, &s), -1);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_positions),
		cmocka_unit_test(test_orientations),
		cmocka_unit_test(test_names_and_refusals),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
