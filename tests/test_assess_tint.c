/*
 * test_assess_tint.c - a body part's tint colour: the action level with
 * that part alone as measured, the rest at their lowest score.
 *
 * The expected levels are worked by hand from the published tables as the
 * research notes transcribe them (human-factors §1.3-1.4 RULA, §2.2-2.3
 * REBA, §3.3 OWAS), not from the scorers: a part alone at score k reads
 * Table A (or B) with every other index 1, then Table C with the other
 * group's score at its lowest, then the method's action levels. The cells
 * used are written beside each row.
 *
 * Then the tint's colours on a human (daemon/tint.h): with the right arm
 * raised past 90 deg and the rest neutral, RULA colours the right upper arm
 * yellow, the scored side's other parts and the trunk, head and legs green,
 * the unscored left arm grey, the eyeballs their own colour; made again and
 * again, the colours allocate nothing.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "alloc_count.h"

#include "assess/assess_tint.h"
#include "assess/body_angles.h"
#include "assess/rula.h"
#include "daemon/tint.h"
#include "figure/human.h"
#include "figure/kin.h"
#include "figure/model.h"
#include "figure/state.h"

static struct assess_result
one_part(enum assess_method m, const char *name, int score, int body)
{
	struct assess_result r;
	memset(&r, 0, sizeof r);
	r.method = m;
	r.nparts = 1;
	r.part[0].name = name;
	r.part[0].score = score;
	r.part[0].body = body;
	return r;
}

struct row {
	const char *part;
	int n;
	int level[7]; /* [score - 1] */
};

static void
check(enum assess_method m, const struct row *rows, size_t nrows)
{
	for (size_t i = 0; i < nrows; i++)
		for (int k = 1; k <= rows[i].n; k++) {
			struct assess_result r = one_part(m, rows[i].part, k, 1);
			int got = assess_part_level(&r, 0);
			if (got != rows[i].level[k - 1])
				fail_msg("method %d %s score %d: level %d, expected %d", m, rows[i].part,
					 k, got, rows[i].level[k - 1]);
		}
}

static void
test_rula_parts_alone_follow_tables_a_b_c(void **unused)
{
	(void)unused;
	/* Table C, column D = 1: C 1..8 -> 1 2 3 3 4 4 5 5; row C = 1: D 1..7 -> 1 2 3 3 4 5 5;
	 * action levels 1-2 -> 1, 3-4 -> 2, 5-6 -> 3, 7 -> 4 */
	static const struct row rows[] = {
		/* Table A (UA k, LA 1, W 1, t 1) = 1 2 3 4 5 7 -> C 1 2 3 3 4 5 */
		{ "upper_arm", 6, { 1, 1, 2, 2, 2, 3 } },
		/* A (1, k, 1, 1) = 1 2 2 */
		{ "lower_arm", 3, { 1, 1, 1 } },
		/* A (1, 1, k, 1) = 1 2 2 3 */
		{ "wrist", 4, { 1, 1, 1, 2 } },
		/* A (1, 1, 1, k) = 1 2 */
		{ "wrist_twist", 2, { 1, 1 } },
		/* Table B (neck k, trunk 1, legs 1) = 1 2 3 5 7 8 -> D (7 at most) -> C 1 2 3 4 5 5 */
		{ "neck", 6, { 1, 1, 2, 2, 3, 3 } },
		/* B (1, k, 1) = 1 2 3 5 6 7 -> C 1 2 3 4 5 5 */
		{ "trunk", 6, { 1, 1, 2, 2, 3, 3 } },
		/* B (1, 1, k) = 1 3 -> C 1 3 */
		{ "legs", 2, { 1, 2 } },
	};
	check(ASSESS_RULA, rows, sizeof rows / sizeof rows[0]);
}

static void
test_reba_parts_alone_follow_tables_a_b_c(void **unused)
{
	(void)unused;
	/* Table C column B = 1: A 1..7 -> 1 1 2 3 4 6 7; row A = 1: B 1..7 -> 1 1 1 2 3 3 4;
	 * no activity; levels 1 -> 0, 2-3 -> 1, 4-7 -> 2, 8-10 -> 3, 11-15 -> 4 */
	static const struct row rows[] = {
		/* Table A (trunk k, neck 1, legs 1) = 1 2 2 3 4 -> C 1 1 1 2 3 */
		{ "trunk", 5, { 0, 0, 0, 1, 1 } },
		/* A (1, k, 1) = 1 1 3 -> C 1 1 2 */
		{ "neck", 3, { 0, 0, 1 } },
		/* A (1, 1, k) = 1 2 3 4 -> C 1 1 2 3 */
		{ "legs", 4, { 0, 0, 1, 1 } },
		/* Table B (UA k, LA 1, W 1) = 1 1 3 4 6 7 -> C 1 1 1 2 3 4 */
		{ "upper_arm", 6, { 0, 0, 0, 1, 1, 2 } },
		/* B (1, k, 1) = 1 1 */
		{ "lower_arm", 2, { 0, 0 } },
		/* B (1, 1, k) = 1 2 2 -> C 1 1 1 */
		{ "wrist", 3, { 0, 0, 0 } },
	};
	check(ASSESS_REBA, rows, sizeof rows / sizeof rows[0]);
}

static void
test_owas_digits_alone_follow_the_classification(void **unused)
{
	(void)unused;
	static const struct row rows[] = {
		/* back k, arms 1, legs 1, load 1: 1 2 1 2 */
		{ "back", 4, { 1, 2, 1, 2 } },
		/* back 1, arms k, legs 1: 1 1 1 */
		{ "arms", 3, { 1, 1, 1 } },
		/* back 1, arms 1, legs k: 1 1 1 2 2 1 1 */
		{ "legs", 7, { 1, 1, 1, 2, 2, 1, 1 } },
	};
	check(ASSESS_OWAS, rows, sizeof rows / sizeof rows[0]);
}

static void
test_add_ons_unknown_parts_and_bad_indices_have_no_level(void **unused)
{
	(void)unused;
	struct assess_result r = one_part(ASSESS_RULA, "force_load", 3, 0);
	assert_int_equal(assess_part_level(&r, 0), -1);
	r = one_part(ASSESS_REBA, "elbow", 1, 1);
	assert_int_equal(assess_part_level(&r, 0), -1);
	r = one_part(ASSESS_OWAS, "load", 3, 1);
	assert_int_equal(assess_part_level(&r, 0), -1);
	r = one_part(ASSESS_RULA, "upper_arm", 7, 1); /* beyond the part's range */
	assert_int_equal(assess_part_level(&r, 0), -1);
	r = one_part(ASSESS_RULA, "upper_arm", 2, 1);
	assert_int_equal(assess_part_level(&r, 1), -1);
	assert_int_equal(assess_part_level(&r, -1), -1);
}

static void
test_colours_mean_the_same_urgency_in_each_method(void **unused)
{
	(void)unused;
	/* RULA and OWAS: levels 1 2 3 4; REBA: 0, 1-2, 3, 4 */
	static const enum assess_colour four[5] = { ASSESS_GREEN, ASSESS_GREEN, ASSESS_YELLOW,
						    ASSESS_ORANGE, ASSESS_RED };
	static const enum assess_colour reba[5] = { ASSESS_GREEN, ASSESS_YELLOW, ASSESS_YELLOW,
						    ASSESS_ORANGE, ASSESS_RED };
	for (int lv = 1; lv <= 4; lv++) {
		assert_int_equal(assess_level_colour(ASSESS_RULA, lv), four[lv]);
		assert_int_equal(assess_level_colour(ASSESS_OWAS, lv), four[lv]);
	}
	for (int lv = 0; lv <= 4; lv++)
		assert_int_equal(assess_level_colour(ASSESS_REBA, lv), reba[lv]);
	assert_string_equal(assess_colour_levels(ASSESS_REBA, ASSESS_YELLOW), "1-2");
	assert_string_equal(assess_colour_levels(ASSESS_RULA, ASSESS_RED), "4");
	assert_string_equal(assess_level_word(ASSESS_OWAS), "AC");
}

static void
assert_colour(const struct model *m, const float *rgba, const char *seg, const float want[4])
{
	int i = model_find_segment(m, seg);
	assert_true(i >= 0);
	for (int k = 0; k < 4; k++)
		if (rgba[4 * i + k] != want[k])
			fail_msg("%s channel %d: %g, expected %g", seg, k, rgba[4 * i + k], want[k]);
}

static void
test_a_raised_arm_tints_its_segments_and_allocates_nothing(void **unused)
{
	(void)unused;
	char err[256];
	struct human_def hd = human_default_def(HUMAN_MALE);
	struct model *m = human_build(&hd, err, sizeof err);
	assert_non_null(m);
	struct state *s = state_make(m);
	assert_non_null(s);
	s->q[m->jnt_dof0[model_find_joint(m, "shoulder_r")]] = 110 * M_PI / 180;
	kin_update(m, s);
	struct assess_config cfg = assess_config_default();
	struct rula_options o = rula_options_default();
	struct body_angles a;
	static struct assess_result r;
	assert_int_equal(body_angles_measure(m, s, 0, cfg.kneel_height, &a, err, sizeof err), 0);
	rula_score(&a, &cfg, &o, &r);
	assert_int_equal(r.side, ASSESS_SIDE_RIGHT);
	const struct assess_result *side[2] = { NULL, &r }; /* the right arm scored */
	static struct tint_map map;
	static float rgba[4 * TINT_MAX_SEG];
	assert_int_equal(tint_segments(&map, m, 1, side, rgba), 0);
	assert_colour(m, rgba, "upperarm_r", tint_rgba[ASSESS_YELLOW]);
	assert_colour(m, rgba, "clavicle_r", tint_rgba[ASSESS_YELLOW]);
	static const char *const green[] = { "forearm_r", "hand_r", "pelvis", "L3", "T1", "head",
					     "thigh_l", "shank_r", "foot_l", "toes_r" };
	for (size_t i = 0; i < sizeof green / sizeof green[0]; i++)
		assert_colour(m, rgba, green[i], tint_rgba[ASSESS_GREEN]);
	static const char *const grey[] = { "clavicle_l", "upperarm_l", "forearm_l", "hand_l" };
	for (size_t i = 0; i < sizeof grey / sizeof grey[0]; i++)
		assert_colour(m, rgba, grey[i], tint_unscored_rgba);
	int eye = model_find_segment(m, "eyeball_l");
	assert_colour(m, rgba, "eyeball_l", &m->seg_rgba[4 * eye]);
	/* a figure that is not a human's segments: no colours */
	static struct tint_map other;
	struct model fake = *m;
	fake.nseg = 1; /* the pelvis alone: no arms */
	assert_int_equal(tint_segments(&other, &fake, 1, side, rgba), -1);
#if COUNT_ALLOCS
	long before = allocs;
	for (int i = 0; i < 100; i++)
		assert_int_equal(tint_segments(&map, m, 1, side, rgba), 0);
	assert_int_equal(allocs, before);
#endif
	state_free(s);
	model_free(m);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_rula_parts_alone_follow_tables_a_b_c),
		cmocka_unit_test(test_reba_parts_alone_follow_tables_a_b_c),
		cmocka_unit_test(test_owas_digits_alone_follow_the_classification),
		cmocka_unit_test(test_add_ons_unknown_parts_and_bad_indices_have_no_level),
		cmocka_unit_test(test_colours_mean_the_same_urgency_in_each_method),
		cmocka_unit_test(test_a_raised_arm_tints_its_segments_and_allocates_nothing),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
