/*
 * test_visibility.c - analyze visibility's geometry (interact/visibility.h)
 * against analytic answers: the angle of a point placed at a known angle
 * from the line of sight; within the eyes' range the eyes' Fick angles
 * alone, read off the construction; beyond it, for points all round, the
 * head's turn and the eyes' composed put the line of sight through the
 * point, the eyes within their limits; the narrowest cone; the map's
 * field just covering a sphere (its tangent cone); and the share seen on
 * synthetic id maps: a disc half covered is half seen, by symmetry, and
 * an occluder's share is its pixels' solid angle.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "interact/visibility.h"

#include "test_util.h"

#define DEG (M_PI / 180)

/* the human's eye joints: +-45 abduction, 45 down and 35 up (human_data.c) */
static const struct vis_limits LIM = { -45 * DEG, 45 * DEG, -45 * DEG, 35 * DEG };

/* a head turned by yaw about world y then pitch up (its columns: x left, y up, z ahead) */
static void
head_turned(double yaw, double pitch, double r[9])
{
	double cy = cos(yaw), sy = sin(yaw), cp = cos(pitch), sp = sin(pitch);
	/* R = Ry(yaw) * Rx(-pitch), row-major */
	double a[9] = { cy, 0, sy, 0, 1, 0, -sy, 0, cy };
	double b[9] = { 1, 0, 0, 0, cp, sp, 0, -sp, cp };
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++) {
			r[3 * i + j] = 0;
			for (int k = 0; k < 3; k++)
				r[3 * i + j] += a[3 * i + k] * b[3 * k + j];
		}
}

/* the direction of Fick angles in a frame r (row-major, its columns the axes) */
static void
fick_world(const double r[9], double yaw, double pitch, double dest[3])
{
	double l[3] = { sin(yaw) * cos(pitch), sin(pitch), cos(yaw) * cos(pitch) };
	for (int i = 0; i < 3; i++)
		dest[i] = r[3 * i] * l[0] + r[3 * i + 1] * l[1] + r[3 * i + 2] * l[2];
}

static void
test_angle_of_a_point_at_a_known_angle(void **st)
{
	(void)st;
	static const double eye[3] = { 0.1, 1.6, 0.2 };
	double head[9], dir[3], p[3];
	head_turned(0.3, 0.1, head);
	fick_world(head, 0, 0, dir); /* the eyes straight ahead in the head */
	for (double a = 0.5; a < 180; a += 7.25) {
		/* a point a degrees off the line of sight, 1.3 m away, turned about it by 40 deg */
		double off[3];
		fick_world(head, 0, 0, off);
		double side[3] = { head[0], head[3], head[6] }, up[3] = { head[1], head[4], head[7] };
		for (int k = 0; k < 3; k++)
			p[k] = eye[k] + 1.3 * (cos(a * DEG) * dir[k] +
					       sin(a * DEG) * (cos(40 * DEG) * side[k] +
							       sin(40 * DEG) * up[k]));
		struct vis_fixation fx;
		assert_int_equal(vis_fixate(eye, dir, head, &LIM, p, &fx), 0);
		assert_near(fx.angle, a, 1e-9);
	}
	assert_int_equal(vis_fixate(eye, dir, head, &LIM, eye, &(struct vis_fixation){ 0 }), -1);
}

static void
test_within_the_eyes_range_the_eyes_alone(void **st)
{
	(void)st;
	static const double eye[3] = { 0, 1.5, 0 };
	double head[9], dir[3];
	head_turned(-0.7, 0.2, head);
	fick_world(head, 0.1, -0.05, dir); /* looking somewhere: the fixation is in the head */
	static const double cases[][2] = { { 0, 0 }, { 30, 10 }, { -44, -44 }, { 45, 35 },
					   { 12.5, -30 } };
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		double u[3], p[3];
		fick_world(head, cases[i][0] * DEG, cases[i][1] * DEG, u);
		for (int k = 0; k < 3; k++)
			p[k] = eye[k] + 2.0 * u[k];
		struct vis_fixation fx;
		vis_fixate(eye, dir, head, &LIM, p, &fx);
		assert_near(fx.eye_yaw, cases[i][0], 1e-9);
		assert_near(fx.eye_pitch, cases[i][1], 1e-9);
		assert_near(fx.head_yaw, 0, 0);
		assert_near(fx.head_pitch, 0, 0);
	}
}

static void
test_beyond_it_the_head_turns_and_the_gaze_goes_through(void **st)
{
	(void)st;
	static const double eye[3] = { 0.3, 1.7, -0.4 };
	double head[9], dir[3];
	head_turned(1.1, -0.15, head);
	fick_world(head, 0, 0, dir);
	srand(7);
	int beyond = 0;
	for (int i = 0; i < 4000; i++) {
		/* directions all round (uniform on the sphere), 0.3 to 5 m away */
		double z = 2.0 * rand() / RAND_MAX - 1, t = 2 * M_PI * rand() / RAND_MAX;
		double u[3] = { sqrt(1 - z * z) * cos(t), z, sqrt(1 - z * z) * sin(t) }, p[3];
		double dist = 0.3 + 4.7 * rand() / RAND_MAX;
		for (int k = 0; k < 3; k++)
			p[k] = eye[k] + dist * u[k];
		struct vis_fixation fx;
		vis_fixate(eye, dir, head, &LIM, p, &fx);
		assert_true(fx.eye_yaw >= -45 - 1e-9 && fx.eye_yaw <= 45 + 1e-9);
		assert_true(fx.eye_pitch >= -45 - 1e-9 && fx.eye_pitch <= 35 + 1e-9);
		beyond += fx.head_yaw != 0 || fx.head_pitch != 0;
		/* the head turned: yaw about its y, then pitch about its turned x */
		double turned[9], hr[9], g[3];
		head_turned(fx.head_yaw * DEG, fx.head_pitch * DEG, hr);
		for (int a = 0; a < 3; a++)
			for (int b = 0; b < 3; b++) {
				turned[3 * a + b] = 0;
				for (int k = 0; k < 3; k++)
					turned[3 * a + b] += head[3 * a + k] * hr[3 * k + b];
			}
		fick_world(turned, fx.eye_yaw * DEG, fx.eye_pitch * DEG, g);
		double cosang = g[0] * u[0] + g[1] * u[1] + g[2] * u[2];
		assert_true(cosang > cos(1e-6));
	}
	assert_true(beyond > 2000); /* most of the sphere is beyond the eyes */
}

static void
test_the_narrowest_cone(void **st)
{
	(void)st;
	static const double c[4] = { 3, 20, 40, 60 }, d[2] = { 50, 10 };
	assert_int_equal(vis_cone(0, c, 4), 0);
	assert_int_equal(vis_cone(1.5, c, 4), 0); /* on the rim */
	assert_int_equal(vis_cone(1.51, c, 4), 1);
	assert_int_equal(vis_cone(10, c, 4), 1);
	assert_int_equal(vis_cone(19.9, c, 4), 2);
	assert_int_equal(vis_cone(29.9, c, 4), 3);
	assert_int_equal(vis_cone(30.1, c, 4), -1);
	assert_int_equal(vis_cone(4, d, 2), 1); /* in any order */
	assert_int_equal(vis_cone(6, d, 2), 0);
	assert_int_equal(vis_cone(1, d, 0), -1);
}

static void
test_the_map_covers_the_sphere(void **st)
{
	(void)st;
	static const double eye[3] = { 0, 1.6, 0 }, c[3] = { 0.3, 1.2, 1.5 };
	double r = 0.2, dx = 0.3, dy = -0.4, dz = 1.5, n = sqrt(dx * dx + dy * dy + dz * dz);
	struct camera cam;
	assert_int_equal(vis_map_camera(&cam, eye, c, r), 0);
	/* the sphere's tangent cone, 2 % wider: half angle asin(1.02 r / n) */
	assert_near(cam.fovy, 2 * asin(VIS_MAP_MARGIN * r / n), 1e-12);
	/* aimed at the centre: -z of the camera along c - eye */
	for (int k = 0; k < 3; k++)
		assert_near(-cam.xf.r[3 * k + 2], (c[k] - eye[k]) / n, 1e-12);
	assert_near(cam.znear, HEMI_ZNEAR, 0);
	/* the eye inside the sphere, or a field beyond the widest: refused */
	assert_int_equal(vis_map_camera(&cam, eye, c, n), -1);
	assert_int_equal(vis_map_camera(&cam, eye, c, 0.99 * n), -1);
}

static struct hemi_map A, B;

/* maps through a 40 deg camera: the target a disc about the centre, an occluder on the right */
static void
maps(int occluder_from_x)
{
	static const double eye[3] = { 0, 0, 0 }, c[3] = { 0, 0, -2 };
	struct camera cam;
	vis_map_camera(&cam, eye, c, 0.7);
	A.cam = B.cam = cam;
	for (int y = 0; y < HEMI_N; y++)
		for (int x = 0; x < HEMI_N; x++) {
			int i = y * HEMI_N + x;
			double ax = x + 0.5 - HEMI_N / 2.0, ay = y + 0.5 - HEMI_N / 2.0;
			A.id[i] = ax * ax + ay * ay < 30.0 * 30.0 ? 7 : 0;
			B.id[i] = A.id[i] ? (x >= occluder_from_x ? 9 : 7) : 3;
		}
}

static void
test_the_share_seen(void **st)
{
	(void)st;
	struct vis_coverage cv;
	maps(HEMI_N / 2); /* the right half hidden by id 9: half seen, by symmetry */
	vis_coverage(&A, &B, 7, &cv);
	assert_near(cv.fraction, 0.5, 1e-12);
	assert_int_equal(cv.nocc, 1);
	assert_int_equal(cv.occ[0].id, 9);
	assert_near(cv.occ[0].fraction, 0.5, 1e-12);
	assert_true(cv.pixels > 2700 && cv.pixels < 2900); /* pi 30^2 = 2827 */
	/* the edge: the disc's rim and the occluder's edge, a few hundred pixels */
	assert_true(cv.edge_pixels > 200 && cv.edge_pixels < 400);
	assert_true(cv.edge_share > 0.05 && cv.edge_share < 0.15);
	/* the solid angle: the disc's 30 px of the map's 96 wide field about the axis */
	double t = tan(A.cam.fovy / 2), half = atan(t * 30 / (HEMI_N / 2.0));
	assert_near(cv.solid_angle, 2 * M_PI * (1 - cos(half)), 0.02 * cv.solid_angle);
	maps(HEMI_N); /* nothing hides it */
	vis_coverage(&A, &B, 7, &cv);
	assert_near(cv.fraction, 1, 0);
	assert_int_equal(cv.nocc, 0);
	maps(0); /* all hidden */
	vis_coverage(&A, &B, 7, &cv);
	assert_near(cv.fraction, 0, 0);
	assert_near(cv.occ[0].fraction, 1, 1e-12);
	/* a target not in the map */
	vis_coverage(&A, &B, 8, &cv);
	assert_int_equal(cv.pixels, 0);
	assert_near(cv.fraction, 0, 0);
}

static void
test_many_occluders_are_counted(void **st)
{
	(void)st;
	struct vis_coverage cv;
	maps(HEMI_N);
	/* a different occluder in each of 20 columns of the disc's left part */
	int n = 0;
	for (int y = 0; y < HEMI_N; y++)
		for (int x = 20; x < 40; x++)
			if (A.id[y * HEMI_N + x])
				B.id[y * HEMI_N + x] = 100 + (uint32_t)x, n++;
	vis_coverage(&A, &B, 7, &cv);
	assert_int_equal(cv.nocc, VIS_MAX_OCCLUDERS);
	double sum = cv.fraction + cv.others;
	for (int k = 0; k < cv.nocc; k++) {
		sum += cv.occ[k].fraction;
		if (k)
			assert_true(cv.occ[k - 1].fraction >= cv.occ[k].fraction);
	}
	assert_near(sum, 1, 1e-12);
	assert_true(cv.others > 0);
	assert_true(n > 0);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_angle_of_a_point_at_a_known_angle),
		cmocka_unit_test(test_within_the_eyes_range_the_eyes_alone),
		cmocka_unit_test(test_beyond_it_the_head_turns_and_the_gaze_goes_through),
		cmocka_unit_test(test_the_narrowest_cone),
		cmocka_unit_test(test_the_map_covers_the_sphere),
		cmocka_unit_test(test_the_share_seen),
		cmocka_unit_test(test_many_occluders_are_counted),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
