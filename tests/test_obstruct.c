/*
 * test_obstruct.c - §3.7.1's decision on synthetic visibility maps, whose
 * answers follow from the geometry: a clear map, a wall far behind the
 * camera, a wall covering the camera direction with its edge at a known
 * angle (the answer is just past the edge, towards it), a wall with a hole
 * (the answer is the hole), a map blocked everywhere, and the eye turned
 * by view_adjust_turn_to.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "draw/hemi.h"
#include "figure/human.h"
#include "figure/kin.h"
#include "interact/obstruct.h"
#include "interact/view_adjust.h"
#include "interact/viewop.h"
#include "test_util.h"

#define DEG (M_PI / 180)

/* a map at origin o looking along dir, empty */
static struct hemi_map *
map_make(const double o[3], const double dir[3])
{
	struct hemi_map *m = calloc(1, sizeof *m);
	assert_non_null(m);
	assert_int_equal(hemi_camera(&m->cam, o, dir), 0);
	for (int i = 0; i < HEMI_N * HEMI_N; i++)
		m->dist[i] = INFINITY;
	return m;
}

static double
angle(const double a[3], const double b[3])
{
	double c = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
	return acos(c > 1 ? 1 : c < -1 ? -1 : c);
}

/*
 * Fills every pixel whose ray meets the plane z = zw (world, the map
 * looking down -z from the world origin) at x < edge with id 7 at the
 * ray's distance to it: a wall with a straight vertical edge at x = edge.
 */
static void
wall(struct hemi_map *m, double zw, double edge)
{
	for (int y = 0; y < HEMI_N; y++)
		for (int x = 0; x < HEMI_N; x++) {
			double d[3];
			hemi_pixel_dir(m, x, y, d);
			double t = zw / d[2];
			if (t > 0 && t * d[0] < edge) {
				m->id[y * HEMI_N + x] = 7;
				m->dist[y * HEMI_N + x] = (float)t;
			}
		}
}

static void
test_clear_map(void **state)
{
	(void)state;
	const double o[3] = { 0, 1, 0 }, dir[3] = { 0, 0, -1 };
	struct hemi_map *m = map_make(o, dir);
	double out[3] = { 9, 9, 9 };
	assert_int_equal(obstruct_check(m, 3, OBSTRUCT_CONE, out), 0);
	assert_true(out[0] == 9); /* untouched */
	free(m);
}

/* a wall beyond the camera hides nothing between the object and the eye */
static void
test_wall_behind_camera(void **state)
{
	(void)state;
	const double o[3] = { 0, 0, 0 }, dir[3] = { 0, 0, -1 };
	struct hemi_map *m = map_make(o, dir);
	wall(m, -5, 10);
	double out[3];
	assert_int_equal(obstruct_check(m, 3, OBSTRUCT_CONE, out), 0);
	assert_int_equal(obstruct_check(m, 6, OBSTRUCT_CONE, out), 1);
	free(m);
}

/*
 * A wall 1 m away covering the camera direction, its edge at x = 0.5:
 * from the origin the edge is atan(0.5) = 26.6 deg to the right. The
 * nearest clear direction has its whole cone past the edge: to the right
 * (+x), level, at an angle from the camera direction between
 * 26.6 deg + cone + pad and that plus a pixel or so.
 */
static void
test_wall_edge(void **state)
{
	(void)state;
	const double o[3] = { 0, 0, 0 }, dir[3] = { 0, 0, -1 };
	struct hemi_map *m = map_make(o, dir);
	wall(m, -1, 0.5);
	double out[3];
	assert_int_equal(obstruct_check(m, 3, OBSTRUCT_CONE, out), 1);
	assert_near(out[0] * out[0] + out[1] * out[1] + out[2] * out[2], 1, 1e-9);
	double a_edge = atan(0.5), a = angle(out, dir);
	assert_true(out[0] > 0);
	assert_true(fabs(out[1]) < 2 * HEMI_PITCH); /* level, within a pixel or two */
	/* its horizontal angle past the edge: at least the cone, at most the cone and 2 pixels */
	double h = atan2(out[0], -out[2]);
	assert_true(h - a_edge >= OBSTRUCT_CONE);
	assert_true(h - a_edge <= OBSTRUCT_CONE + OBSTRUCT_PAD + 2 * HEMI_PITCH);
	assert_true(a < 40 * DEG);
	/* and every blocked pixel is at least the cone away from it */
	for (int i = 0; i < HEMI_N * HEMI_N; i++)
		if (m->id[i]) {
			double d[3];
			hemi_pixel_dir(m, i % HEMI_N, i / HEMI_N, d);
			assert_true(angle(d, out) >= OBSTRUCT_CONE);
		}
	free(m);
}

/* the wall with a hole 20 deg up: the hole is nearer than the edge, so that is the answer */
static void
test_wall_hole(void **state)
{
	(void)state;
	const double o[3] = { 0, 0, 0 }, dir[3] = { 0, 0, -1 };
	struct hemi_map *m = map_make(o, dir);
	wall(m, -1, 0.5);
	const double hole[3] = { 0, sin(20 * DEG), -cos(20 * DEG) };
	for (int i = 0; i < HEMI_N * HEMI_N; i++) {
		double d[3];
		hemi_pixel_dir(m, i % HEMI_N, i / HEMI_N, d);
		if (angle(d, hole) < 10 * DEG) {
			m->id[i] = 0;
			m->dist[i] = INFINITY;
		}
	}
	double out[3];
	assert_int_equal(obstruct_check(m, 3, OBSTRUCT_CONE, out), 1);
	assert_true(out[1] > 0);
	assert_true(angle(out, hole) < 10 * DEG - OBSTRUCT_CONE + 1e-9);
	assert_true(angle(out, dir) < 20 * DEG);
	free(m);
}

static void
test_blocked_everywhere(void **state)
{
	(void)state;
	const double o[3] = { 0, 0, 0 }, dir[3] = { 0, 0, -1 };
	struct hemi_map *m = map_make(o, dir);
	wall(m, -1, 100);
	double out[3] = { 9, 9, 9 };
	assert_int_equal(obstruct_check(m, 3, OBSTRUCT_CONE, out), -1);
	assert_true(out[0] == 9);
	free(m);
}

/* the map's camera and pixels: the centre looks at the camera, rows run top to bottom */
static void
test_map_pixels(void **state)
{
	(void)state;
	const double o[3] = { 1, 2, 3 }, dir[3] = { 3, 0, 4 };
	struct hemi_map *m = map_make(o, dir);
	double a[3], b[3], c[3];
	hemi_pixel_dir(m, HEMI_N / 2, HEMI_N / 2, a);
	hemi_pixel_dir(m, HEMI_N / 2 - 1, HEMI_N / 2 - 1, b);
	const double u[3] = { 0.6, 0, 0.8 };
	assert_near(angle(a, u), M_SQRT1_2 * HEMI_PITCH, 1e-3 * HEMI_PITCH);
	assert_near(angle(b, u), M_SQRT1_2 * HEMI_PITCH, 1e-3 * HEMI_PITCH);
	hemi_pixel_dir(m, HEMI_N / 2, 0, c); /* the top row looks up */
	assert_near(asin(c[1]), HEMI_FOV / 2, HEMI_PITCH);
	free(m);
}

/* the eye about the origin to a direction: same distance, aimed at the origin, eased */
static void
test_turn_to(void **state)
{
	(void)state;
	struct camera cam, c;
	view_camera_default(&cam);
	const double o[3] = { 0, 1, 0 }, eye[3] = { 0, 1, 3 };
	assert_int_equal(view_camera_aim(&cam, eye, o), 0);
	const double d[3] = { sin(30 * DEG), 0, cos(30 * DEG) };
	struct view_adjust va;
	assert_int_equal(view_adjust_turn_to(&va, &cam, o, d, 0), 1);
	assert_int_equal(view_adjust_step(&va, VIEW_ADJUST_US / 2, VIEW_ADJUST_US, 0, &c), 1);
	assert_int_equal(view_adjust_step(&va, VIEW_ADJUST_US, VIEW_ADJUST_US, 0, &c), 0);
	assert_near(c.xf.p[0], 3 * sin(30 * DEG), 1e-9);
	assert_near(c.xf.p[1], 1, 1e-9);
	assert_near(c.xf.p[2], 3 * cos(30 * DEG), 1e-9);
	assert_near(c.xf.r[3], 0, 1e-12); /* x horizontal: no twist */
	double vrp[3];
	view_camera_vrp(&c, vrp);
	for (int k = 0; k < 3; k++)
		assert_near(vrp[k], o[k], 1e-9);
	/* straight up: the elevation stops at the limit */
	const double up[3] = { 0, 1, 0 };
	assert_int_equal(view_adjust_turn_to(&va, &cam, o, up, 0), 1);
	assert_near(asin((va.to.xf.p[1] - 1) / 3), VIEWOP_ELEVATION_MAX, 1e-9);
	/* already there */
	const double here[3] = { 0, 0, 1 };
	assert_int_equal(view_adjust_turn_to(&va, &cam, o, here, 0), 0);
	assert_int_equal(va.active, 0);
}

/*
 * The parts left out around G: the segment and those that share a joint
 * with it, found here from the model's joints (the figure file's pairs of
 * sites), not from the posture's tree the code walks; under any rooting.
 */
static void
test_own_parts_are_the_segment_and_its_joint_neighbours(void **state)
{
	(void)state;
	char err[200];
	struct human_def hd = human_default_def(HUMAN_MALE);
	struct model *m = human_build(&hd, err, sizeof err);
	assert_non_null(m);
	struct state *s = state_make(m);
	kin_update(m, s);
	unsigned char skip[256];
	const char *roots[] = { "foot_l.balance", "hand_r.palm", "head.between_eyes" };
	const char *segs[] = { "hand_r", "pelvis", "forearm_l", "head" };
	for (int r = 0; r < 3; r++) {
		kin_set_root(m, s, model_find_site(m, roots[r]));
		for (int k = 0; k < 4; k++) {
			int seg = model_find_segment(m, segs[k]);
			assert_true(seg >= 0);
			int n = obstruct_own_parts(m, s, seg, skip, 256), want = 1;
			for (int i = 0; i < m->nseg; i++) {
				int near = i == seg;
				for (int j = 0; j < m->njnt; j++) {
					int a = m->site_seg[m->jnt_site_from[j]], b = m->site_seg[m->jnt_site_to[j]];
					near |= (a == seg && b == i) || (b == seg && a == i);
				}
				assert_int_equal(skip[i], near);
				want += near && i != seg;
			}
			assert_int_equal(n, want);
			assert_true(n >= 2);
		}
	}
	/* more segments than the caller has room for: nothing written */
	memset(skip, 7, sizeof skip);
	assert_int_equal(obstruct_own_parts(m, s, 0, skip, m->nseg - 1), -1);
	assert_int_equal(skip[0], 7);
	state_free(s);
	model_free(m);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_clear_map),
		cmocka_unit_test(test_wall_behind_camera),
		cmocka_unit_test(test_wall_edge),
		cmocka_unit_test(test_wall_hole),
		cmocka_unit_test(test_blocked_everywhere),
		cmocka_unit_test(test_map_pixels),
		cmocka_unit_test(test_turn_to),
		cmocka_unit_test(test_own_parts_are_the_segment_and_its_joint_neighbours),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
