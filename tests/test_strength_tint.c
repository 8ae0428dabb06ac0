/*
 * test_strength_tint.c - tint=strength (daemon/tint.h): the segment just
 * below each strength joint drawn in the band of the joint's weakest
 * percent capable, by the bands as the research notes give them
 * (human-factors §5.1): >= 99 % green (NIOSH 1981's action limit, men),
 * 75-99 % yellow (UAW-GM's 75 %), 25-75 % orange, < 25 % red (NIOSH's
 * maximum permissible limit, men); a joint without a published curve grey;
 * the segments no strength joint holds up their own colours. Made again
 * and again, the colours allocate nothing.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "alloc_count.h"

#include "daemon/tint.h"
#include "figure/human.h"
#include "figure/model.h"

static void
assert_colour(const struct model *m, const float *rgba, const char *seg, const float want[4])
{
	int s = model_find_segment(m, seg);
	assert_true(s >= 0);
	for (int i = 0; i < 3; i++)
		if (fabsf(rgba[4 * s + i] - want[i]) > 1e-6f)
			fail_msg("%s: channel %d is %g, want %g", seg, i, rgba[4 * s + i], want[i]);
	assert_true(rgba[4 * s + 3] == m->seg_rgba[4 * s + 3]); /* its own opacity */
}

static struct strength_result
no_curves(void)
{
	struct strength_result r;
	memset(&r, 0, sizeof r);
	for (int j = 0; j < STRENGTH_NJOINTS; j++)
		for (int a = 0; a < STRENGTH_NAXES; a++)
			r.percent[j][a] = NAN;
	return r;
}

static const float *const green = tint_rgba[0], *const yellow = tint_rgba[1],
		   *const orange = tint_rgba[2], *const red = tint_rgba[3];

static void
test_each_joint_colours_the_segment_below_it_by_its_weakest_axis(void **unused)
{
	(void)unused;
	char err[200];
	struct human_def hd = human_default_def(HUMAN_MALE);
	struct model *m = human_build(&hd, err, sizeof err);
	assert_non_null(m);
	struct strength_result r = no_curves();
	r.percent[STRENGTH_WRIST_R][STRENGTH_FLEXION] = 99.5;
	r.percent[STRENGTH_ELBOW_R][STRENGTH_FLEXION] = 80;
	r.percent[STRENGTH_SHOULDER_R][STRENGTH_ABDUCTION] = 50;
	r.percent[STRENGTH_L5S1][STRENGTH_FLEXION] = 10;
	/* the weakest axis a curve covers: 60 (orange), not 97 */
	r.percent[STRENGTH_KNEE_L][STRENGTH_ABDUCTION] = 60;
	r.percent[STRENGTH_KNEE_L][STRENGTH_ROTATION] = 97;
	r.percent[STRENGTH_ANKLE_R][STRENGTH_FLEXION] = 20;
	static struct tint_map map;
	static float rgba[4 * TINT_MAX_SEG];
	assert_int_equal(tint_strength_segments(&map, m, 1, &r, rgba), 0);
	assert_colour(m, rgba, "hand_r", green);
	assert_colour(m, rgba, "forearm_r", yellow);
	assert_colour(m, rgba, "upperarm_r", orange);
	static const char *const trunk[] = { "L5", "L3", "L1", "T12", "T6", "T1" };
	for (size_t i = 0; i < sizeof trunk / sizeof trunk[0]; i++)
		assert_colour(m, rgba, trunk[i], red);
	assert_colour(m, rgba, "shank_l", orange);
	assert_colour(m, rgba, "foot_r", red);
	assert_colour(m, rgba, "toes_r", red);
	/* no curve: grey */
	static const char *const grey[] = { "hand_l", "forearm_l", "upperarm_l", "thigh_l", "thigh_r",
					    "shank_r", "foot_l", "toes_l" };
	for (size_t i = 0; i < sizeof grey / sizeof grey[0]; i++)
		assert_colour(m, rgba, grey[i], tint_unscored_rgba);
	/* held up by no strength joint: their own colours */
	static const char *const own[] = { "pelvis", "clavicle_l", "clavicle_r", "head", "eyeball_l" };
	for (size_t i = 0; i < sizeof own / sizeof own[0]; i++)
		assert_colour(m, rgba, own[i], &m->seg_rgba[4 * model_find_segment(m, own[i])]);
#if COUNT_ALLOCS
	long before = allocs;
	for (int i = 0; i < 100; i++)
		assert_int_equal(tint_strength_segments(&map, m, 1, &r, rgba), 0);
	assert_int_equal(allocs, before);
#endif
	/* a figure that is not a human's segments: no colours */
	static struct tint_map other;
	struct model fake = *m;
	fake.nseg = 1;
	assert_int_equal(tint_strength_segments(&other, &fake, 1, &r, rgba), -1);
	model_free(m);
}

/* the bands' edges: 99 and 75 are in the better band, 25 too */
static void
test_the_bands_edges(void **unused)
{
	(void)unused;
	char err[200];
	struct human_def hd = human_default_def(HUMAN_MALE);
	struct model *m = human_build(&hd, err, sizeof err);
	assert_non_null(m);
	static const struct {
		double percent;
		const float *colour;
	} edges[] = { { 100, tint_rgba[0] }, { 99, tint_rgba[0] }, { 98.999, tint_rgba[1] },
		      { 75, tint_rgba[1] },  { 74.999, tint_rgba[2] }, { 25, tint_rgba[2] },
		      { 24.999, tint_rgba[3] }, { 0, tint_rgba[3] } };
	static struct tint_map map;
	static float rgba[4 * TINT_MAX_SEG];
	for (size_t i = 0; i < sizeof edges / sizeof edges[0]; i++) {
		struct strength_result r = no_curves();
		r.percent[STRENGTH_ELBOW_L][STRENGTH_FLEXION] = edges[i].percent;
		assert_int_equal(tint_strength_segments(&map, m, 1, &r, rgba), 0);
		assert_colour(m, rgba, "forearm_l", edges[i].colour);
	}
	model_free(m);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_each_joint_colours_the_segment_below_it_by_its_weakest_axis),
		cmocka_unit_test(test_the_bands_edges),
	};
	return cmocka_run_group_tests_name("strength_tint", tests, NULL, NULL);
}
