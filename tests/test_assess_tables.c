/*
 * test_assess_tables.c - RULA, REBA and OWAS against their published
 * tables, cell for cell, and their bands at every edge, both sides.
 *
 * The tables below are typed from research human-factors §1.3 (RULA A, B,
 * C), §2.2 (REBA A, B, C) and §3.3 (OWAS, the majority reading) in the
 * layout the research file prints them, apart from the scorers' arrays.
 * Every cell reachable from a posture is reached through the public
 * scorers: synthetic body angles placed in the bands that give the cell's
 * indices, the look-up the derivation records compared with the cell.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "assess/assess.h"
#include "assess/owas.h"
#include "assess/reba.h"
#include "assess/rula.h"

/* ---- the published tables, as research human-factors prints them ---- */

/* RULA Table A: rows (upper arm 1-6, lower arm 1-3); columns W1t1 W1t2 W2t1 ... W4t2 */
static const int rula_a[18][8] = {
	{ 1, 2, 2, 2, 2, 3, 3, 3 }, { 2, 2, 2, 2, 3, 3, 3, 3 }, { 2, 3, 3, 3, 3, 3, 4, 4 },
	{ 2, 3, 3, 3, 3, 4, 4, 4 }, { 3, 3, 3, 3, 3, 4, 4, 4 }, { 3, 4, 4, 4, 4, 4, 5, 5 },
	{ 3, 3, 4, 4, 4, 4, 5, 5 }, { 3, 4, 4, 4, 4, 4, 5, 5 }, { 4, 4, 4, 4, 4, 5, 5, 5 },
	{ 4, 4, 4, 4, 4, 5, 5, 5 }, { 4, 4, 4, 4, 4, 5, 5, 5 }, { 4, 4, 4, 5, 5, 5, 6, 6 },
	{ 5, 5, 5, 5, 5, 6, 6, 7 }, { 5, 6, 6, 6, 6, 7, 7, 7 }, { 6, 6, 6, 7, 7, 7, 7, 8 },
	{ 7, 7, 7, 7, 7, 8, 8, 9 }, { 8, 8, 8, 8, 8, 9, 9, 9 }, { 9, 9, 9, 9, 9, 9, 9, 9 },
};
/* RULA Table B: rows neck 1-6; columns T1L1 T1L2 T2L1 ... T6L2 */
static const int rula_b[6][12] = {
	{ 1, 3, 2, 3, 3, 4, 5, 5, 6, 6, 7, 7 }, { 2, 3, 2, 3, 4, 5, 5, 5, 6, 7, 7, 7 },
	{ 3, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 7 }, { 5, 5, 5, 6, 6, 7, 7, 7, 7, 7, 8, 8 },
	{ 7, 7, 7, 7, 7, 8, 8, 8, 8, 8, 8, 8 }, { 8, 8, 8, 8, 8, 8, 8, 9, 9, 9, 9, 9 },
};
/* RULA Table C: rows score C 1..8+, columns score D 1..7+ */
static const int rula_c[8][7] = {
	{ 1, 2, 3, 3, 4, 5, 5 }, { 2, 2, 3, 4, 4, 5, 5 }, { 3, 3, 3, 4, 4, 5, 6 },
	{ 3, 3, 3, 4, 5, 6, 6 }, { 4, 4, 4, 5, 6, 7, 7 }, { 4, 4, 5, 6, 6, 7, 7 },
	{ 5, 5, 6, 6, 7, 7, 7 }, { 5, 5, 6, 7, 7, 7, 7 },
};
/* REBA Table A: rows trunk 1-5; columns N1L1..N1L4 N2L1..N2L4 N3L1..N3L4 */
static const int reba_a[5][12] = {
	{ 1, 2, 3, 4, 1, 2, 3, 4, 3, 3, 5, 6 }, { 2, 3, 4, 5, 3, 4, 5, 6, 4, 5, 6, 7 },
	{ 2, 4, 5, 6, 4, 5, 6, 7, 5, 6, 7, 8 }, { 3, 5, 6, 7, 5, 6, 7, 8, 6, 7, 8, 9 },
	{ 4, 6, 7, 8, 6, 7, 8, 9, 7, 8, 9, 9 },
};
/* REBA Table B: rows upper arm 1-6; columns LA1W1 LA1W2 LA1W3 LA2W1 LA2W2 LA2W3 */
static const int reba_b[6][6] = {
	{ 1, 2, 2, 1, 2, 3 }, { 1, 2, 3, 2, 3, 4 }, { 3, 4, 5, 4, 5, 5 },
	{ 4, 5, 5, 5, 6, 7 }, { 6, 7, 8, 7, 8, 8 }, { 7, 8, 8, 8, 9, 9 },
};
/* REBA Table C: rows score A 1-12, columns score B 1-12 */
static const int reba_c[12][12] = {
	{ 1, 1, 1, 2, 3, 3, 4, 5, 6, 7, 7, 7 },
	{ 1, 2, 2, 3, 4, 4, 5, 6, 6, 7, 7, 8 },
	{ 2, 3, 3, 3, 4, 5, 6, 7, 7, 8, 8, 8 },
	{ 3, 4, 4, 4, 5, 6, 7, 8, 8, 9, 9, 9 },
	{ 4, 4, 4, 5, 6, 7, 8, 8, 9, 9, 9, 9 },
	{ 6, 6, 6, 7, 8, 8, 9, 9, 10, 10, 10, 10 },
	{ 7, 7, 7, 8, 9, 9, 9, 10, 10, 11, 11, 11 },
	{ 8, 8, 8, 9, 10, 10, 10, 10, 10, 11, 11, 11 },
	{ 9, 9, 9, 10, 10, 10, 11, 11, 11, 12, 12, 12 },
	{ 10, 10, 10, 11, 11, 11, 11, 12, 12, 12, 12, 12 },
	{ 11, 11, 11, 11, 12, 12, 12, 12, 12, 12, 12, 12 },
	{ 12, 12, 12, 12, 12, 12, 12, 12, 12, 12, 12, 12 },
};
/* OWAS: rows (back, arms), each legs 1-7 as "load1/load2/load3" (the majority reading) */
static const char *const owas_rows[12][7] = {
	{ "111", "111", "111", "222", "222", "111", "111" },
	{ "111", "111", "111", "222", "222", "111", "111" },
	{ "111", "111", "111", "223", "223", "111", "112" },
	{ "223", "223", "223", "333", "333", "222", "233" },
	{ "223", "223", "233", "344", "344", "334", "234" },
	{ "334", "223", "333", "344", "444", "444", "234" },
	{ "111", "111", "112", "333", "444", "111", "111" },
	{ "223", "111", "112", "444", "444", "333", "111" },
	{ "223", "111", "233", "444", "444", "444", "111" },
	{ "233", "223", "223", "444", "444", "444", "234" },
	{ "334", "234", "334", "444", "444", "444", "234" },
	{ "444", "234", "334", "444", "444", "444", "234" },
};

/* ---- postures placed in the bands ---- */

/* standing straight, arms hanging with the elbows at 80 deg: every part in its first band */
static struct body_angles
neutral(void)
{
	struct body_angles a;
	memset(&a, 0, sizeof a);
	a.hip_trunk_angle = 180;
	for (int s = 0; s < 2; s++) {
		a.arm[s].elbow_flexion = 80;
		a.arm[s].wrist_twist_fraction = 0.1;
		a.arm[s].hand_across_midline = -0.2;
		a.arm[s].hand_out_to_side = -0.05;
		a.arm[s].elbow_above_shoulder = -0.3;
		a.arm[s].hand_above_shoulder = -0.5;
		a.leg[s].weight_share = 0.5;
		a.leg[s].foot_on_floor = 1;
	}
	a.legs_on_floor = 2;
	return a;
}

/* the upper arm (both methods' bands) to score s: the band, then raised and abducted */
static void
place_upper_arm(struct body_arm *arm, int s)
{
	static const double band_angle[5] = { 0, 0, 30, 60, 100 };
	int base = s > 4 ? 4 : s;
	arm->upper_arm_flexion = band_angle[base];
	arm->shoulder_elevation = s - base >= 1 ? 20 : 0;
	arm->upper_arm_abduction = s - base >= 2 ? 50 : 0;
}

static void
place_rula(struct body_angles *a, int ua, int la, int w, int wt, int neck, int trunk, int legs)
{
	struct body_arm *arm = &a->arm[BODY_RIGHT];
	place_upper_arm(arm, ua);
	arm->elbow_flexion = la == 1 ? 80 : 120;
	arm->hand_across_midline = la == 3 ? 0.1 : -0.2;
	static const double wrist_angle[5] = { 0, 0, 10, 20, 20 };
	arm->wrist_flexion = wrist_angle[w];
	arm->wrist_deviation = w == 4 ? -20 : 0;
	arm->wrist_twist_fraction = wt == 2 ? 0.9 : 0.1;
	static const double neck_angle[7] = { 0, 5, 15, 25, -15, -15, -15 };
	a->neck_flexion = neck_angle[neck];
	a->neck_twist = neck >= 5 ? 30 : 0;
	a->neck_side_bend = neck == 6 ? -20 : 0;
	static const double trunk_angle[7] = { 0, 0, 10, 30, 70, 70, 70 };
	a->trunk_flexion = trunk_angle[trunk];
	a->trunk_twist = trunk >= 5 ? -30 : 0;
	a->trunk_side_bend = trunk == 6 ? 20 : 0;
	a->leg[BODY_LEFT].weight_share = legs == 2 ? 0.8 : 0.5;
	a->leg[BODY_RIGHT].weight_share = legs == 2 ? 0.2 : 0.5;
}

static const struct assess_part *
part(const struct assess_result *r, const char *name)
{
	for (int i = 0; i < r->nparts; i++)
		if (!strcmp(r->part[i].name, name))
			return &r->part[i];
	fail_msg("no part %s", name);
	return NULL;
}

static const struct assess_lookup *
lookup(const struct assess_result *r, const char *table)
{
	for (int i = 0; i < r->nlookups; i++)
		if (!strcmp(r->lookup[i].table, table))
			return &r->lookup[i];
	fail_msg("no look-up %s", table);
	return NULL;
}

static struct rula_options
rula_right(void)
{
	struct rula_options o = rula_options_default();
	o.side = ASSESS_SIDE_RIGHT;
	return o;
}

/* ---- RULA ---- */

static void
test_rula_table_a(void **state)
{
	(void)state;
	struct assess_config cfg = assess_config_default();
	struct rula_options o = rula_right();
	struct assess_result r;
	static const char *const names[4] = { "upper_arm", "lower_arm", "wrist", "wrist_twist" };
	for (int ua = 1; ua <= 6; ua++)
		for (int la = 1; la <= 3; la++)
			for (int w = 1; w <= 4; w++)
				for (int wt = 1; wt <= 2; wt++) {
					struct body_angles a = neutral();
					place_rula(&a, ua, la, w, wt, 1, 1, 1);
					rula_score(&a, &cfg, &o, &r);
					const int want[4] = { ua, la, w, wt };
					for (int i = 0; i < 4; i++)
						assert_int_equal(part(&r, names[i])->score, want[i]);
					const struct assess_lookup *l = lookup(&r, "A");
					assert_int_equal(l->nidx, 4);
					for (int i = 0; i < 4; i++) {
						assert_int_equal(l->idx[i], want[i]);
						assert_string_equal(l->idx_name[i], names[i]);
					}
					assert_int_equal(l->value, rula_a[(ua - 1) * 3 + la - 1][(w - 1) * 2 + wt - 1]);
				}
}

static void
test_rula_table_b(void **state)
{
	(void)state;
	struct assess_config cfg = assess_config_default();
	struct rula_options o = rula_right();
	struct assess_result r;
	for (int n = 1; n <= 6; n++)
		for (int t = 1; t <= 6; t++)
			for (int l = 1; l <= 2; l++) {
				struct body_angles a = neutral();
				place_rula(&a, 1, 1, 1, 1, n, t, l);
				rula_score(&a, &cfg, &o, &r);
				assert_int_equal(part(&r, "neck")->score, n);
				assert_int_equal(part(&r, "trunk")->score, t);
				assert_int_equal(part(&r, "legs")->score, l);
				const struct assess_lookup *lk = lookup(&r, "B");
				assert_int_equal(lk->idx[0], n);
				assert_int_equal(lk->idx[1], t);
				assert_int_equal(lk->idx[2], l);
				assert_int_equal(lk->value, rula_b[n - 1][(t - 1) * 2 + l - 1]);
			}
}

/* Table C through Table A and B cells of each value (muscle use and force/load 0) */
static void
test_rula_table_c(void **state)
{
	(void)state;
	struct assess_config cfg = assess_config_default();
	struct rula_options o = rula_right();
	struct assess_result r;
	for (int c = 1; c <= 9; c++)
		for (int d = 1; d <= 9; d++) {
			/* a Table A cell worth c and a Table B cell worth d, from the tables above */
			int ai = -1, aj = -1, bi = -1, bj = -1;
			for (int i = 0; i < 18 && ai < 0; i++)
				for (int j = 0; j < 8; j++)
					if (rula_a[i][j] == c) {
						ai = i;
						aj = j;
						break;
					}
			for (int i = 0; i < 6 && bi < 0; i++)
				for (int j = 0; j < 12; j++)
					if (rula_b[i][j] == d) {
						bi = i;
						bj = j;
						break;
					}
			assert_true(ai >= 0 && bi >= 0);
			struct body_angles a = neutral();
			place_rula(&a, ai / 3 + 1, ai % 3 + 1, aj / 2 + 1, aj % 2 + 1, bi + 1, bj / 2 + 1,
				   bj % 2 + 1);
			rula_score(&a, &cfg, &o, &r);
			const struct assess_lookup *l = lookup(&r, "C");
			/* scores of 8 (C) and 7 (D) or more read the last row and column */
			int row = c < 8 ? c : 8, col = d < 7 ? d : 7;
			assert_int_equal(l->idx[0], row);
			assert_int_equal(l->idx[1], col);
			assert_int_equal(l->value, rula_c[row - 1][col - 1]);
			assert_int_equal(r.score, rula_c[row - 1][col - 1]);
			/* action levels (§1.4): 1-2 -> 1, 3-4 -> 2, 5-6 -> 3, 7 -> 4 */
			assert_int_equal(r.action_level, (r.score + 1) / 2);
			assert_non_null(r.action);
			assert_true(strlen(r.action) > 10);
		}
}

/* muscle use and force/load (§1.2) enter both scores C and D */
static void
test_rula_addons(void **state)
{
	(void)state;
	struct assess_config cfg = assess_config_default();
	struct assess_result r;
	struct body_angles a = neutral();
	const struct {
		double kg;
		int held, shock, force;
	} cases[] = {
		{ 1.99, 0, 0, 0 }, { 2, 0, 0, 1 }, { 10, 0, 0, 1 }, { 10.01, 0, 0, 2 },
		{ 1.99, 1, 0, 0 }, { 2, 1, 0, 2 }, { 10, 1, 0, 2 }, { 10.01, 1, 0, 3 },
		{ 0, 0, 1, 3 },
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		struct rula_options o = rula_right();
		o.load_kg = cases[i].kg;
		o.repeated = cases[i].held;
		o.shock = cases[i].shock;
		rula_score(&a, &cfg, &o, &r);
		assert_int_equal(part(&r, "force_load")->score, cases[i].force);
		assert_int_equal(part(&r, "muscle_use")->score, cases[i].held);
		int extra = cases[i].force + cases[i].held;
		/* scores C and D: the neutral posture's Table A and B cells plus both add-ons */
		int sa = lookup(&r, "A")->value, sb = lookup(&r, "B")->value;
		assert_int_equal(lookup(&r, "C")->idx[0], sa + extra);
		assert_int_equal(lookup(&r, "C")->idx[1], sb + extra);
	}
}

/* one scorer run with an angle moved: the part's score */
static int
rula_part_at(struct body_angles a, const char *name, struct assess_config cfg)
{
	struct rula_options o = rula_right();
	struct assess_result r;
	rula_score(&a, &cfg, &o, &r);
	return part(&r, name)->score;
}

/* every band edge from both sides; an edge scores the worse band */
static void
test_rula_edges(void **state)
{
	(void)state;
	struct assess_config cfg = assess_config_default();
	const struct {
		double v;
		int want;
	} ua[] = { { -20.01, 2 }, { -20, 2 }, { -19.99, 1 }, { 19.99, 1 }, { 20, 2 }, { 44.99, 2 },
		   { 45, 3 }, { 89.99, 3 }, { 90, 4 } },
	  la[] = { { 59.99, 2 }, { 60, 2 }, { 60.01, 1 }, { 99.99, 1 }, { 100, 2 } },
	  wr[] = { { -5, 1 }, { 5, 1 }, { 5.01, 2 }, { -5.01, 2 }, { 14.99, 2 }, { 15, 3 }, { -15, 3 } },
	  nk[] = { { -5, 1 }, { -5.01, 4 }, { 9.99, 1 }, { 10, 2 }, { 19.99, 2 }, { 20, 3 } },
	  tr[] = { { -5, 1 }, { 5, 1 }, { 5.01, 2 }, { -5.01, 2 }, { 19.99, 2 }, { 20, 3 },
		   { 59.99, 3 }, { 60, 4 } };
	for (size_t i = 0; i < sizeof ua / sizeof ua[0]; i++) {
		struct body_angles a = neutral();
		a.arm[BODY_RIGHT].upper_arm_flexion = ua[i].v;
		assert_int_equal(rula_part_at(a, "upper_arm", cfg), ua[i].want);
	}
	for (size_t i = 0; i < sizeof la / sizeof la[0]; i++) {
		struct body_angles a = neutral();
		a.arm[BODY_RIGHT].elbow_flexion = la[i].v;
		assert_int_equal(rula_part_at(a, "lower_arm", cfg), la[i].want);
	}
	for (size_t i = 0; i < sizeof wr / sizeof wr[0]; i++) {
		struct body_angles a = neutral();
		a.arm[BODY_RIGHT].wrist_flexion = wr[i].v;
		assert_int_equal(rula_part_at(a, "wrist", cfg), wr[i].want);
	}
	for (size_t i = 0; i < sizeof nk / sizeof nk[0]; i++) {
		struct body_angles a = neutral();
		a.neck_flexion = nk[i].v;
		assert_int_equal(rula_part_at(a, "neck", cfg), nk[i].want);
	}
	for (size_t i = 0; i < sizeof tr / sizeof tr[0]; i++) {
		struct body_angles a = neutral();
		a.trunk_flexion = tr[i].v;
		assert_int_equal(rula_part_at(a, "trunk", cfg), tr[i].want);
	}
	/* seated: band 1 while the hip-trunk angle is 90 deg or more, whatever the lean */
	struct body_angles a = neutral();
	a.seated = 1;
	a.trunk_flexion = 30;
	a.hip_trunk_angle = 90;
	assert_int_equal(rula_part_at(a, "trunk", cfg), 1);
	a.hip_trunk_angle = 89.99;
	assert_int_equal(rula_part_at(a, "trunk", cfg), 3);
	/* the open thresholds count when exceeded */
	const struct {
		double *field;
		double at;
		const char *part;
	} th[] = {
		{ &a.arm[BODY_RIGHT].shoulder_elevation, cfg.shoulder_raised, "upper_arm" },
		{ &a.arm[BODY_RIGHT].upper_arm_abduction, cfg.arm_abducted, "upper_arm" },
		{ &a.arm[BODY_RIGHT].hand_across_midline, cfg.across_midline, "lower_arm" },
		{ &a.arm[BODY_RIGHT].hand_out_to_side, cfg.out_to_side, "lower_arm" },
		{ &a.arm[BODY_RIGHT].wrist_deviation, cfg.wrist_deviated, "wrist" },
		{ &a.arm[BODY_RIGHT].wrist_twist_fraction, cfg.wrist_twist_end, "wrist_twist" },
		{ &a.neck_twist, cfg.neck_twist, "neck" },
		{ &a.neck_side_bend, cfg.neck_side_bend, "neck" },
		{ &a.trunk_twist, cfg.trunk_twist, "trunk" },
		{ &a.trunk_side_bend, cfg.trunk_side_bend, "trunk" },
	};
	for (size_t i = 0; i < sizeof th / sizeof th[0]; i++) {
		a = neutral();
		*th[i].field = th[i].at;
		int at = rula_part_at(a, th[i].part, cfg);
		*th[i].field = th[i].at + 0.001;
		assert_int_equal(rula_part_at(a, th[i].part, cfg), at + 1);
	}
	/* legs: even weight within uneven_weight, standing on both feet */
	a = neutral();
	a.leg[BODY_LEFT].weight_share = 0.6;
	a.leg[BODY_RIGHT].weight_share = 0.4;
	assert_int_equal(rula_part_at(a, "legs", cfg), 1);
	a.leg[BODY_LEFT].weight_share = 0.61;
	a.leg[BODY_RIGHT].weight_share = 0.39;
	assert_int_equal(rula_part_at(a, "legs", cfg), 2);
	a = neutral();
	a.leg[BODY_LEFT].foot_on_floor = 0;
	a.legs_on_floor = 1;
	assert_int_equal(rula_part_at(a, "legs", cfg), 2);
	a.seated = 1;
	assert_int_equal(rula_part_at(a, "legs", cfg), 2);
	a.legs_on_floor = 2;
	assert_int_equal(rula_part_at(a, "legs", cfg), 1);
}

/* the derivation says what was measured and against what */
static void
test_rula_derivation(void **state)
{
	(void)state;
	struct assess_config cfg = assess_config_default();
	struct rula_options o = rula_right();
	struct assess_result r;
	struct body_angles a = neutral();
	a.arm[BODY_RIGHT].upper_arm_flexion = 50;
	a.arm[BODY_RIGHT].shoulder_elevation = 14.2;
	rula_score(&a, &cfg, &o, &r);
	const struct assess_part *p = part(&r, "upper_arm");
	assert_string_equal(p->band, "45-90 deg flexion");
	assert_string_equal(p->angle_name, "upper_arm_flexion_r");
	assert_near(p->angle, 50, 0);
	assert_int_equal(p->base, 3);
	assert_int_equal(p->nadj, 1);
	assert_int_equal(p->adj[0].value, 1);
	assert_string_equal(p->adj[0].reason, "shoulder raised: clavicle elevation 14.2 > 10 deg");
	assert_int_equal(p->score, 4);
	assert_int_equal(p->max, 6);
	assert_true(p->body);
	assert_true(isnan(part(&r, "legs")->angle));
	assert_false(part(&r, "force_load")->body);
	/* the worst part: the upper arm at 4 of 1..6 against everything else at 1 */
	assert_string_equal(r.part[r.worst].name, "upper_arm");
	assert_int_equal(r.side, ASSESS_SIDE_RIGHT);
	assert_string_equal(r.code, "");
	/* support takes one off, not below 1 */
	o.arm_supported = 1;
	a = neutral();
	rula_score(&a, &cfg, &o, &r);
	assert_int_equal(part(&r, "upper_arm")->base, 1);
	assert_int_equal(part(&r, "upper_arm")->score, 1);
}

/* side "worse" keeps the arm with the higher grand score, the right on ties */
static void
test_rula_worse_side(void **state)
{
	(void)state;
	struct assess_config cfg = assess_config_default();
	struct rula_options o = rula_options_default();
	struct assess_result r;
	struct body_angles a = neutral();
	assert_int_equal(o.side, ASSESS_SIDE_WORSE);
	rula_score(&a, &cfg, &o, &r);
	assert_int_equal(r.side, ASSESS_SIDE_RIGHT);
	a.arm[BODY_LEFT].upper_arm_flexion = 120;
	a.arm[BODY_LEFT].shoulder_elevation = 30;
	a.arm[BODY_LEFT].upper_arm_abduction = 60;
	rula_score(&a, &cfg, &o, &r);
	assert_int_equal(r.side, ASSESS_SIDE_LEFT);
	assert_int_equal(part(&r, "upper_arm")->score, 6);
	assert_string_equal(part(&r, "upper_arm")->angle_name, "upper_arm_flexion_l");
	o.side = ASSESS_SIDE_RIGHT;
	struct assess_result right;
	rula_score(&a, &cfg, &o, &right);
	assert_true(right.score < r.score);
}

/* ---- REBA ---- */

static struct reba_options
reba_right(void)
{
	struct reba_options o = reba_options_default();
	o.side = ASSESS_SIDE_RIGHT;
	return o;
}

static void
place_reba(struct body_angles *a, int trunk, int neck, int legs, int ua, int la, int w)
{
	static const double trunk_angle[6] = { 0, 0, 10, 30, 70, 70 };
	a->trunk_flexion = trunk_angle[trunk];
	a->trunk_side_bend = trunk == 5 ? 25 : 0;
	a->neck_flexion = neck == 1 ? 10 : 30;
	a->neck_twist = neck == 3 ? 30 : 0;
	/* legs: 1 both feet; 2 knee 45 (+1); 3 knee 70 (+2); 4 on the right foot alone, knee 70 */
	a->leg[BODY_RIGHT].knee_flexion = legs == 1 ? 0 : legs == 2 ? 45 : 70;
	if (legs == 4) {
		a->leg[BODY_LEFT].foot_on_floor = 0;
		a->legs_on_floor = 1;
	}
	struct body_arm *arm = &a->arm[BODY_RIGHT];
	place_upper_arm(arm, ua);
	arm->elbow_flexion = la == 1 ? 80 : 40;
	arm->wrist_flexion = w == 1 ? 5 : w == 2 ? 25 : -25;
	arm->wrist_deviation = w == 3 ? 20 : 0;
}

static void
test_reba_table_a(void **state)
{
	(void)state;
	struct assess_config cfg = assess_config_default();
	struct reba_options o = reba_right();
	struct assess_result r;
	for (int t = 1; t <= 5; t++)
		for (int n = 1; n <= 3; n++)
			for (int l = 1; l <= 4; l++) {
				struct body_angles a = neutral();
				place_reba(&a, t, n, l, 1, 1, 1);
				reba_score(&a, &cfg, &o, &r);
				assert_int_equal(part(&r, "trunk")->score, t);
				assert_int_equal(part(&r, "neck")->score, n);
				assert_int_equal(part(&r, "legs")->score, l);
				const struct assess_lookup *lk = lookup(&r, "A");
				assert_string_equal(lk->idx_name[0], "trunk");
				assert_string_equal(lk->idx_name[1], "neck");
				assert_int_equal(lk->value, reba_a[t - 1][(n - 1) * 4 + l - 1]);
			}
}

static void
test_reba_table_b(void **state)
{
	(void)state;
	struct assess_config cfg = assess_config_default();
	struct reba_options o = reba_right();
	struct assess_result r;
	for (int ua = 1; ua <= 6; ua++)
		for (int la = 1; la <= 2; la++)
			for (int w = 1; w <= 3; w++) {
				struct body_angles a = neutral();
				place_reba(&a, 1, 1, 1, ua, la, w);
				reba_score(&a, &cfg, &o, &r);
				assert_int_equal(part(&r, "upper_arm")->score, ua);
				assert_int_equal(part(&r, "lower_arm")->score, la);
				assert_int_equal(part(&r, "wrist")->score, w);
				assert_int_equal(lookup(&r, "B")->value, reba_b[ua - 1][(la - 1) * 3 + w - 1]);
			}
}

/* Table C through Table A cells plus load and Table B cells plus coupling; then activity */
static void
test_reba_table_c(void **state)
{
	(void)state;
	struct assess_config cfg = assess_config_default();
	struct assess_result r;
	for (int sa = 1; sa <= 12; sa++)
		for (int sb = 1; sb <= 12; sb++) {
			/* the highest load (0..3) and coupling (0..3) that leave a table cell to find */
			int ld = sa - 1 < 3 ? sa - 1 : 3, cp = sb - 1 < 3 ? sb - 1 : 3;
			int ai = -1, aj = -1, bi = -1, bj = -1;
			for (int i = 0; i < 5 && ai < 0; i++)
				for (int j = 0; j < 12; j++)
					if (reba_a[i][j] == sa - ld) {
						ai = i;
						aj = j;
						break;
					}
			for (int i = 0; i < 6 && bi < 0; i++)
				for (int j = 0; j < 6; j++)
					if (reba_b[i][j] == sb - cp) {
						bi = i;
						bj = j;
						break;
					}
			assert_true(ai >= 0 && bi >= 0);
			struct body_angles a = neutral();
			place_reba(&a, ai + 1, aj / 4 + 1, aj % 4 + 1, bi + 1, bj / 3 + 1, bj % 3 + 1);
			struct reba_options o = reba_right();
			static const double kg[4] = { 0, 7, 12, 12 };
			o.load_kg = kg[ld];
			o.shock = ld == 3;
			o.coupling = cp;
			o.activity = (sa + sb) % 4;
			reba_score(&a, &cfg, &o, &r);
			const struct assess_lookup *l = lookup(&r, "C");
			assert_int_equal(l->idx[0], sa);
			assert_int_equal(l->idx[1], sb);
			assert_int_equal(l->value, reba_c[sa - 1][sb - 1]);
			int want = reba_c[sa - 1][sb - 1] + o.activity;
			assert_int_equal(r.score, want);
			/* §2.3: 1 -> 0, 2-3 -> 1, 4-7 -> 2, 8-10 -> 3, 11-15 -> 4 */
			int level = want == 1 ? 0 : want <= 3 ? 1 : want <= 7 ? 2 : want <= 10 ? 3 : 4;
			assert_int_equal(r.action_level, level);
		}
}

static int
reba_part_at(struct body_angles a, const char *name, struct reba_options o)
{
	struct assess_config cfg = assess_config_default();
	struct assess_result r;
	reba_score(&a, &cfg, &o, &r);
	return part(&r, name)->score;
}

static void
test_reba_edges(void **state)
{
	(void)state;
	struct reba_options o = reba_right();
	const struct {
		double v;
		int want;
	} tr[] = { { -5, 1 }, { 5, 1 }, { 5.01, 2 }, { -5.01, 2 }, { 19.99, 2 }, { 20, 3 },
		   { -19.99, 2 }, { -20, 3 }, { 59.99, 3 }, { 60, 4 } },
	  nk[] = { { -5, 1 }, { -5.01, 2 }, { 19.99, 1 }, { 20, 2 } },
	  ua[] = { { -20, 2 }, { -19.99, 1 }, { 19.99, 1 }, { 20, 2 }, { 44.99, 2 }, { 45, 3 },
		   { 89.99, 3 }, { 90, 4 } },
	  la[] = { { 60, 2 }, { 60.01, 1 }, { 99.99, 1 }, { 100, 2 } },
	  wr[] = { { 14.99, 1 }, { 15, 2 }, { -14.99, 1 }, { -15, 2 } },
	  kn[] = { { 29.99, 1 }, { 30, 2 }, { 59.99, 2 }, { 60, 3 } };
	for (size_t i = 0; i < sizeof tr / sizeof tr[0]; i++) {
		struct body_angles a = neutral();
		a.trunk_flexion = tr[i].v;
		assert_int_equal(reba_part_at(a, "trunk", o), tr[i].want);
	}
	for (size_t i = 0; i < sizeof nk / sizeof nk[0]; i++) {
		struct body_angles a = neutral();
		a.neck_flexion = nk[i].v;
		assert_int_equal(reba_part_at(a, "neck", o), nk[i].want);
	}
	for (size_t i = 0; i < sizeof ua / sizeof ua[0]; i++) {
		struct body_angles a = neutral();
		a.arm[BODY_RIGHT].upper_arm_flexion = ua[i].v;
		assert_int_equal(reba_part_at(a, "upper_arm", o), ua[i].want);
	}
	for (size_t i = 0; i < sizeof la / sizeof la[0]; i++) {
		struct body_angles a = neutral();
		a.arm[BODY_RIGHT].elbow_flexion = la[i].v;
		assert_int_equal(reba_part_at(a, "lower_arm", o), la[i].want);
	}
	for (size_t i = 0; i < sizeof wr / sizeof wr[0]; i++) {
		struct body_angles a = neutral();
		a.arm[BODY_RIGHT].wrist_flexion = wr[i].v;
		assert_int_equal(reba_part_at(a, "wrist", o), wr[i].want);
	}
	for (size_t i = 0; i < sizeof kn / sizeof kn[0]; i++) {
		struct body_angles a = neutral();
		a.leg[BODY_LEFT].knee_flexion = kn[i].v;
		assert_int_equal(reba_part_at(a, "legs", o), kn[i].want);
	}
	/* seated: no +2 for the knees beyond 60 deg */
	struct body_angles a = neutral();
	a.seated = 1;
	a.leg[BODY_LEFT].knee_flexion = a.leg[BODY_RIGHT].knee_flexion = 90;
	assert_int_equal(reba_part_at(a, "legs", o), 1);
	/* twisted and side flexed together are one +1 */
	a = neutral();
	a.trunk_twist = 30;
	a.trunk_side_bend = 30;
	assert_int_equal(reba_part_at(a, "trunk", o), 2);
	a.neck_twist = 30;
	a.neck_side_bend = -30;
	assert_int_equal(reba_part_at(a, "neck", o), 2);
	/* loads: < 5, 5-10, > 10 kg, shock +1 */
	const struct {
		double kg;
		int shock, want;
	} ld[] = { { 4.99, 0, 0 }, { 5, 0, 1 }, { 10, 0, 1 }, { 10.01, 0, 2 }, { 10.01, 1, 3 },
		   { 0, 1, 1 } };
	for (size_t i = 0; i < sizeof ld / sizeof ld[0]; i++) {
		o.load_kg = ld[i].kg;
		o.shock = ld[i].shock;
		assert_int_equal(reba_part_at(neutral(), "load", o), ld[i].want);
	}
	/* the upper arm: abducted or rotated one +1, raised +1, supported -1 */
	o = reba_right();
	a = neutral();
	a.arm[BODY_RIGHT].upper_arm_abduction = 40;
	a.arm[BODY_RIGHT].upper_arm_rotation = -60;
	assert_int_equal(reba_part_at(a, "upper_arm", o), 2);
	a.arm[BODY_RIGHT].shoulder_elevation = 15;
	assert_int_equal(reba_part_at(a, "upper_arm", o), 3);
	o.arm_supported = 1;
	assert_int_equal(reba_part_at(a, "upper_arm", o), 2);
}

/* ---- OWAS ---- */

static int
owas_cell(int back, int arms, int legs, int load)
{
	return owas_rows[(back - 1) * 3 + arms - 1][legs - 1][load - 1] - '0';
}

static void
place_owas(struct body_angles *a, int back, int arms, int legs)
{
	a->trunk_flexion = back == 2 || back == 4 ? -35 : 5;
	a->trunk_twist = back == 3 ? 25 : 0;
	a->trunk_side_bend = back == 4 ? -25 : 0;
	a->arm[BODY_LEFT].elbow_above_shoulder = arms >= 2 ? 0.05 : -0.3;
	a->arm[BODY_RIGHT].elbow_above_shoulder = arms == 3 ? 0 : -0.3;
	switch (legs) {
	case 1:
		a->seated = 1;
		a->leg[BODY_LEFT].knee_flexion = a->leg[BODY_RIGHT].knee_flexion = 90;
		break;
	case 2:
		a->leg[BODY_LEFT].knee_flexion = 25;
		break;
	case 3:
	case 5:
		a->leg[BODY_RIGHT].foot_on_floor = 0;
		a->legs_on_floor = 1;
		a->leg[BODY_RIGHT].knee_flexion = 90; /* the raised leg's knee does not count */
		a->leg[BODY_LEFT].knee_flexion = legs == 5 ? 40 : 10;
		break;
	case 4:
		a->leg[BODY_LEFT].knee_flexion = a->leg[BODY_RIGHT].knee_flexion = 100;
		break;
	case 6:
		a->leg[BODY_RIGHT].kneeling = 1;
		a->leg[BODY_LEFT].knee_flexion = a->leg[BODY_RIGHT].knee_flexion = 90;
		break;
	}
}

static void
test_owas_table(void **state)
{
	(void)state;
	struct assess_config cfg = assess_config_default();
	struct assess_result r;
	static const double kg[4] = { 0, 10, 20, 20.01 };
	int cells = 0;
	for (int b = 1; b <= 4; b++)
		for (int ar = 1; ar <= 3; ar++)
			for (int l = 1; l <= 7; l++)
				for (int ld = 1; ld <= 3; ld++) {
					assert_int_equal(owas_category(b, ar, l, ld), owas_cell(b, ar, l, ld));
					cells++;
					if (l == 7)
						continue; /* walking: no posture shows it */
					struct body_angles a = neutral();
					place_owas(&a, b, ar, l);
					struct owas_options o = { kg[ld] };
					owas_score(&a, &cfg, &o, &r);
					char code[48];
					snprintf(code, sizeof code, "%d%d%d%d", b, ar, l, ld);
					assert_string_equal(r.code, code);
					assert_int_equal(r.score, owas_cell(b, ar, l, ld));
					assert_int_equal(r.action_level, r.score);
					assert_int_equal(lookup(&r, "AC")->value, r.score);
					assert_int_equal(part(&r, "legs")->score, l);
				}
	assert_int_equal(cells, 252);
	/* the contested cells (research §3.3): the majority reading */
	assert_int_equal(owas_category(3, 3, 7, 3), 1);
	assert_int_equal(owas_category(4, 1, 3, 2), 2);
	assert_int_equal(owas_category(0, 1, 1, 1), 0);
	assert_int_equal(owas_category(1, 1, 8, 1), 0);
}

static void
test_owas_edges(void **state)
{
	(void)state;
	struct assess_config cfg = assess_config_default();
	struct assess_result r;
	struct owas_options o = { 0 };
	struct body_angles a = neutral();
	const struct {
		double flex, twist, side;
		char back;
	} bk[] = { { 20, 0, 0, '1' }, { 20.01, 0, 0, '2' }, { -20.01, 0, 0, '2' }, { 0, 20, 0, '1' },
		   { 0, 20.01, 0, '3' }, { 0, 0, -20.01, '3' }, { 25, -25, 0, '4' } };
	for (size_t i = 0; i < sizeof bk / sizeof bk[0]; i++) {
		a = neutral();
		a.trunk_flexion = bk[i].flex;
		a.trunk_twist = bk[i].twist;
		a.trunk_side_bend = bk[i].side;
		owas_score(&a, &cfg, &o, &r);
		assert_int_equal(r.code[0], bk[i].back);
	}
	/* the arm at shoulder level counts; 1 mm below does not */
	a = neutral();
	a.arm[BODY_LEFT].elbow_above_shoulder = 0;
	a.arm[BODY_RIGHT].elbow_above_shoulder = -0.001;
	a.arm[BODY_RIGHT].hand_above_shoulder = 0.3; /* a hand at the face is not a raised arm */
	owas_score(&a, &cfg, &o, &r);
	assert_int_equal(r.code[1], '2');
	/* knees: bent beyond knee_bent */
	a = neutral();
	a.leg[BODY_LEFT].knee_flexion = a.leg[BODY_RIGHT].knee_flexion = cfg.knee_bent;
	owas_score(&a, &cfg, &o, &r);
	assert_int_equal(r.code[2], '2');
	a.leg[BODY_LEFT].knee_flexion = a.leg[BODY_RIGHT].knee_flexion = cfg.knee_bent + 0.01;
	owas_score(&a, &cfg, &o, &r);
	assert_int_equal(r.code[2], '4');
	/* loads: up to 10, up to 20, beyond */
	const struct {
		double kg;
		char digit;
	} ld[] = { { 10, '1' }, { 10.01, '2' }, { 20, '2' }, { 20.01, '3' } };
	for (size_t i = 0; i < sizeof ld / sizeof ld[0]; i++) {
		o.load_kg = ld[i].kg;
		owas_score(&a, &cfg, &o, &r);
		assert_int_equal(r.code[3], ld[i].digit);
	}
	/* the worst part: the one whose neutral code lowers the category most */
	a = neutral();
	place_owas(&a, 2, 1, 4); /* 2141: AC 3; back straight gives 1141 AC 2, legs straight 2121 AC 2 */
	o.load_kg = 0;
	owas_score(&a, &cfg, &o, &r);
	assert_string_equal(r.code, "2141");
	assert_string_equal(r.part[r.worst].name, "back");
	a = neutral();
	place_owas(&a, 1, 1, 5); /* 1151: AC 2; only the legs lower it */
	owas_score(&a, &cfg, &o, &r);
	assert_string_equal(r.part[r.worst].name, "legs");
	assert_string_equal(part(&r, "legs")->angle_name, "knee_flexion_l");
}

/* ---- the thresholds ---- */

static void
test_config(void **state)
{
	(void)state;
	struct assess_config cfg = assess_config_default();
	char err[160];
	/* every field of the struct has a key with a unit, a range holding its default, a source */
	assert_int_equal(assess_config_nkeys * sizeof(double), sizeof cfg);
	for (size_t i = 0; i < assess_config_nkeys; i++) {
		const struct assess_config_key *k = &assess_config_keys[i];
		double v = *(const double *)((const char *)&cfg + k->offset);
		assert_true(v >= k->min && v <= k->max);
		assert_true(strlen(k->source) > 10);
		assert_true(!strcmp(k->unit, "deg") || !strcmp(k->unit, "m") ||
			    !strcmp(k->unit, "fraction"));
		for (size_t j = 0; j < i; j++)
			assert_true(k->offset != assess_config_keys[j].offset);
	}
	assert_near(cfg.trunk_twist, 15, 0);
	assert_near(cfg.neck_side_bend, 8, 0);
	assert_near(cfg.arm_abducted, 35, 0);
	assert_near(cfg.owas_back, 20, 0);
	assert_int_equal(assess_config_set(&cfg, "shoulder_raised", 20, err, sizeof err), 0);
	assert_near(cfg.shoulder_raised, 20, 0);
	/* refusals leave the configuration as it was */
	struct assess_config before = cfg;
	assert_int_equal(assess_config_set(&cfg, "shoulder_raised", 46, err, sizeof err), -1);
	assert_non_null(strstr(err, "0..45"));
	assert_int_equal(assess_config_set(&cfg, "shoulder_raised", NAN, err, sizeof err), -1);
	assert_int_equal(assess_config_set(&cfg, "wrist_twist_end", -0.1, err, sizeof err), -1);
	assert_int_equal(assess_config_set(&cfg, "no_such", 1, err, sizeof err), -1);
	assert_non_null(strstr(err, "no_such"));
	assert_memory_equal(&before, &cfg, sizeof cfg);
	/* a threshold moved moves the score */
	struct body_angles a = neutral();
	a.trunk_twist = 12;
	assert_int_equal(rula_part_at(a, "trunk", assess_config_default()), 1);
	struct assess_config c2 = assess_config_default();
	assert_int_equal(assess_config_set(&c2, "trunk_twist", 10, err, sizeof err), 0);
	assert_int_equal(rula_part_at(a, "trunk", c2), 2);
}


/* the reasons' own formatter prints what snprintf prints, for random values and thresholds */
static void
test_reasons_match_printf(void **state)
{
	(void)state;
	uint64_t seed = 7;
	char want[ASSESS_REASON], err[160];
	for (int i = 0; i < 3000; i++) {
		seed = seed * 6364136223846793005ull + 1442695040888963407ull;
		double u1 = (double)(seed >> 11) / 9007199254740992.0;
		seed = seed * 6364136223846793005ull + 1442695040888963407ull;
		double u2 = (double)(seed >> 11) / 9007199254740992.0;
		struct assess_config cfg = assess_config_default();
		/* thresholds of up to 2 decimals, as a person sets them */
		double th = floor(u2 * 9000) / 100, mid = floor(u2 * 30) / 100;
		assert_int_equal(assess_config_set(&cfg, "arm_abducted", th, err, sizeof err), 0);
		assert_int_equal(assess_config_set(&cfg, "out_to_side", mid, err, sizeof err), 0);
		struct body_angles a = neutral();
		a.arm[BODY_RIGHT].upper_arm_abduction = th + 0.01 + u1 * 1000;
		a.arm[BODY_RIGHT].hand_out_to_side = mid + 0.001 + u1 * 3;
		struct rula_options o = rula_right();
		struct assess_result r;
		rula_score(&a, &cfg, &o, &r);
		snprintf(want, sizeof want, "upper arm abducted: %.1f > %g deg",
			 a.arm[BODY_RIGHT].upper_arm_abduction, th);
		assert_string_equal(part(&r, "upper_arm")->adj[0].reason, want);
		snprintf(want, sizeof want, "working out to the side: hand %.2f m outside the shoulder > %g m",
			 a.arm[BODY_RIGHT].hand_out_to_side, mid);
		assert_string_equal(part(&r, "lower_arm")->adj[0].reason, want);
		/* negative values and %d */
		a = neutral();
		a.arm[BODY_RIGHT].wrist_deviation = -(10.01 + u1 * 50);
		a.leg[BODY_LEFT].foot_on_floor = 0;
		a.legs_on_floor = 1;
		rula_score(&a, &cfg, &o, &r);
		snprintf(want, sizeof want, "bent from the midline: ulnar deviation %.1f > 10 deg",
			 -a.arm[BODY_RIGHT].wrist_deviation);
		assert_string_equal(part(&r, "wrist")->adj[0].reason, want);
		assert_string_equal(part(&r, "legs")->adj[0].reason, "1 foot bears weight");
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_rula_table_a),   cmocka_unit_test(test_rula_table_b),
		cmocka_unit_test(test_rula_table_c),   cmocka_unit_test(test_rula_addons),
		cmocka_unit_test(test_rula_edges),     cmocka_unit_test(test_rula_derivation),
		cmocka_unit_test(test_rula_worse_side), cmocka_unit_test(test_reba_table_a),
		cmocka_unit_test(test_reba_table_b),   cmocka_unit_test(test_reba_table_c),
		cmocka_unit_test(test_reba_edges),     cmocka_unit_test(test_owas_table),
		cmocka_unit_test(test_owas_edges),     cmocka_unit_test(test_config),
		cmocka_unit_test(test_reasons_match_printf),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
