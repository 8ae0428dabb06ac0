/* test_spine.c - Monheit's spine model: totals, weights, limits, saturation, kinematic sense */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/human.h"
#include "figure/kin.h"
#include "figure/model.h"
#include "pose/spine.h"
#include "figure/state.h"

static const double DEG = M_PI / 180;
static const double TOL = 1e-12;
static const double QID[4] = { 0, 0, 0, 1 };

/* cmocka's float comparison works in single precision; this one in double */
#define assert_near(a, b, tol) near_at((a), (b), (tol), #a, __FILE__, __LINE__)

static void
near_at(double a, double b, double tol, const char *what, const char *file, int line)
{
	if (!(fabs(a - b) <= tol))
		fail_msg("%s:%d: %s = %.17g, want %.17g (tolerance %g)", file, line, what, a, b,
			 tol);
}

static struct model *
build_human(void)
{
	struct human_def d = human_default_def(HUMAN_MALE);
	char err[256] = "";
	struct model *m = human_build(&d, err, sizeof err);
	if (!m)
		fail_msg("human_build: %s", err);
	return m;
}

/* first dof of spine_k */
static int
spine_dof(const struct model *m, int k)
{
	char name[16];
	snprintf(name, sizeof name, "spine_%d", k);
	int j = model_find_joint(m, name);
	if (j < 0)
		fail_msg("no joint %s", name);
	return m->jnt_dof0[j];
}

/* the limit of spine_k in direction dir on the side of sign */
static double
spine_cap(const struct model *m, int k, int dir, double sign)
{
	int d = spine_dof(m, k) + dir;
	return sign >= 0 ? m->dof_hi[d] : m->dof_lo[d];
}

/* the largest bend of the range in direction dir on the side of sign */
static double
range_capacity(const struct model *m, const struct spine_flavor *f, int dir, double sign)
{
	double c = 0;
	for (int k = f->bottom; k <= f->top; k++)
		c += spine_cap(m, k, dir, sign);
	return c;
}

static int
at_limit(const struct model *m, int k, int dir, double v)
{
	int d = spine_dof(m, k) + dir;
	return v == m->dof_lo[d] || v == m->dof_hi[d];
}

/* the facts every distribution must satisfy, whatever the total */
static void
check_distribution(const struct model *m, const struct spine_flavor *f, const double total[3],
		   const double *q, const double shortfall[3])
{
	double w[SPINE_NJNT];
	assert_int_equal(spine_weights(f, w), 0);
	for (int dir = 0; dir < 3; dir++) {
		double sum = 0;
		for (int k = 0; k < SPINE_NJNT; k++) {
			double v = q[3 * k + dir];
			int d = spine_dof(m, k) + dir;
			/* within limits; outside the range exactly straight */
			assert_true(v >= m->dof_lo[d] && v <= m->dof_hi[d]);
			if (k < f->bottom || k > f->top)
				assert_true(v == 0);
			/* never against the requested direction */
			assert_true(v * total[dir] >= 0);
			sum += v;
		}
		/* achieved + shortfall = requested */
		assert_near(sum + shortfall[dir], total[dir], TOL);
		/* unclamped joints share one ratio to their weights; clamped ones hold less */
		double ratio = NAN;
		for (int k = f->bottom; k <= f->top; k++)
			if (!at_limit(m, k, dir, q[3 * k + dir]) && total[dir] != 0) {
				double r = q[3 * k + dir] / w[k];
				if (isnan(ratio))
					ratio = r;
				assert_near(r, ratio, TOL);
			}
		if (!isnan(ratio))
			for (int k = f->bottom; k <= f->top; k++) {
				double v = q[3 * k + dir];
				if (at_limit(m, k, dir, v))
					assert_true(fabs(v) <= fabs(ratio * w[k]) + TOL);
			}
		/* a shortfall only when every joint of the range is at its limit */
		if (shortfall[dir] != 0)
			for (int k = f->bottom; k <= f->top; k++)
				assert_true(q[3 * k + dir] == spine_cap(m, k, dir, total[dir]));
	}
}

static void
test_flavors(void **unused)
{
	(void)unused;
	struct spine_flavor w = spine_bend_from_waist(), n = spine_curl_from_neck(), f;
	assert_int_equal(w.bottom, 0);
	assert_int_equal(w.top, 11);
	assert_int_equal(w.initiator, 0);
	assert_int_equal(w.resistor, 11);
	assert_int_equal(n.bottom, 0);
	assert_int_equal(n.top, 17);
	assert_int_equal(n.initiator, 17);
	assert_int_equal(n.resistor, 0);
	assert_int_equal(spine_flavor_check(&w), 0);
	assert_int_equal(spine_flavor_check(&n), 0);
	assert_int_equal(spine_flavor_named("waist", &f), 0);
	assert_memory_equal(&f, &w, sizeof f);
	assert_int_equal(spine_flavor_named("bend from waist", &f), 0);
	assert_memory_equal(&f, &w, sizeof f);
	assert_int_equal(spine_flavor_named("neck", &f), 0);
	assert_memory_equal(&f, &n, sizeof f);
	assert_int_equal(spine_flavor_named("curl from neck", &f), 0);
	assert_memory_equal(&f, &n, sizeof f);
	/* unknown names leave dest alone */
	struct spine_flavor keep = { 1, 2, 1, 2 };
	f = keep;
	assert_int_equal(spine_flavor_named("hips", &f), -1);
	assert_int_equal(spine_flavor_named("", &f), -1);
	assert_int_equal(spine_flavor_named(NULL, &f), -1);
	assert_memory_equal(&f, &keep, sizeof f);
}

static void
test_weights(void **unused)
{
	(void)unused;
	double w[SPINE_NJNT];
	/* waist: 12/12 .. 1/12 over spine_0 .. spine_11, then 0 */
	struct spine_flavor f = spine_bend_from_waist();
	assert_int_equal(spine_weights(&f, w), 0);
	for (int k = 0; k < SPINE_NJNT; k++)
		assert_near(w[k], k <= 11 ? (12.0 - k) / 12 : 0, 1e-15);
	/* neck: 18/18 at spine_17 down to 1/18 at spine_0 */
	f = spine_curl_from_neck();
	assert_int_equal(spine_weights(&f, w), 0);
	for (int k = 0; k < SPINE_NJNT; k++)
		assert_near(w[k], (k + 1.0) / 18, 1e-15);
	/* initiator inside the range: the far side falls with distance, floored as the resistor */
	f = (struct spine_flavor){ .bottom = 2, .top = 12, .initiator = 5, .resistor = 8 };
	assert_int_equal(spine_weights(&f, w), 0);
	static const double want[SPINE_NJNT] = {
		0, 0, 1.0 / 4, 2.0 / 4, 3.0 / 4, 1, 3.0 / 4, 2.0 / 4, 1.0 / 4,
		1.0 / 4, 1.0 / 4, 1.0 / 4, 1.0 / 4, 0, 0, 0, 0, 0,
	};
	for (int k = 0; k < SPINE_NJNT; k++)
		assert_near(w[k], want[k], 1e-15);
	/* initiator = resistor: uniform over the range */
	f = (struct spine_flavor){ .bottom = 3, .top = 6, .initiator = 4, .resistor = 4 };
	assert_int_equal(spine_weights(&f, w), 0);
	for (int k = 0; k < SPINE_NJNT; k++)
		assert_true(w[k] == (k >= 3 && k <= 6 ? 1 : 0));
}

/* one direction's achievable total: met exactly, the other directions straight */
static void
check_one_direction(const struct model *m, const struct spine_flavor *f, int dir, double t)
{
	double total[3] = { 0, 0, 0 }, q[SPINE_NDOF], sf[3] = { 9, 9, 9 };
	total[dir] = t;
	assert_int_equal(spine_distribute(m, f, total, q, sf), 0);
	check_distribution(m, f, total, q, sf);
	double sum = 0;
	for (int k = 0; k < SPINE_NJNT; k++) {
		sum += q[3 * k + dir];
		for (int o = 0; o < 3; o++)
			if (o != dir)
				assert_true(q[3 * k + o] == 0);
	}
	assert_near(sum, t, TOL);
	for (int o = 0; o < 3; o++)
		assert_true(sf[o] == 0);
}

/* achievable totals, positive and negative, in every direction, for both flavours */
static void
test_totals_met(void **unused)
{
	(void)unused;
	struct model *m = build_human();
	struct spine_flavor fl[3] = { spine_bend_from_waist(), spine_curl_from_neck(),
				      { .bottom = 4, .top = 15, .initiator = 9, .resistor = 15 } };
	static const double frac[] = { 0.01, 0.2, 0.5, 0.8, 0.95, 0.999999 };
	for (int i = 0; i < 3; i++)
		for (int dir = 0; dir < 3; dir++)
			for (int sign = -1; sign <= 1; sign += 2)
				for (size_t j = 0; j < sizeof frac / sizeof frac[0]; j++) {
					double t = frac[j] * range_capacity(m, &fl[i], dir, sign);
					assert_true(t * sign > 0);
					check_one_direction(m, &fl[i], dir, t);
				}
	/* some of these clamp joints: 95% of the waist's axial range cannot be proportional */
	double total[3] = { 0, 0, 0.95 * range_capacity(m, &fl[0], SPINE_AXIAL, 1) }, q[SPINE_NDOF];
	assert_int_equal(spine_distribute(m, &fl[0], total, q, NULL), 0);
	assert_true(at_limit(m, 0, SPINE_AXIAL, q[3 * 0 + SPINE_AXIAL]));
	assert_false(at_limit(m, 11, SPINE_AXIAL, q[3 * 11 + SPINE_AXIAL]));
	model_free(m);
}

/* unsaturated bends: shares fall from the initiator to the resistor */
static void
test_monotone(void **unused)
{
	(void)unused;
	struct model *m = build_human();
	static const struct {
		int neck;
		double total[3];
	} c[] = {
		{ 0, { 30 * DEG, 15 * DEG, 5 * DEG } },  { 0, { -15 * DEG, -15 * DEG, -5 * DEG } },
		{ 1, { 20 * DEG, 20 * DEG, 20 * DEG } }, { 1, { -10 * DEG, -20 * DEG, -20 * DEG } },
	};
	for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
		struct spine_flavor f =
			c[i].neck ? spine_curl_from_neck() : spine_bend_from_waist();
		double q[SPINE_NDOF], sf[3];
		assert_int_equal(spine_distribute(m, &f, c[i].total, q, sf), 0);
		check_distribution(m, &f, c[i].total, q, sf);
		int step = f.resistor > f.initiator ? 1 : -1;
		for (int dir = 0; dir < 3; dir++) {
			/* the case is unsaturated: no joint reaches its limit */
			for (int k = f.bottom; k <= f.top; k++) {
				double v = q[3 * k + dir];
				assert_true(fabs(v) < fabs(spine_cap(m, k, dir, c[i].total[dir])));
				assert_true(v * c[i].total[dir] > 0);
			}
			/* strictly decreasing share from the initiator to the resistor */
			for (int k = f.initiator; k != f.resistor; k += step)
				assert_true(fabs(q[3 * k + dir]) > fabs(q[3 * (k + step) + dir]));
		}
	}
	model_free(m);
}

/* the three directions are distributed independently */
static void
test_independent(void **unused)
{
	(void)unused;
	struct model *m = build_human();
	struct spine_flavor f = spine_bend_from_waist();
	double all[3] = { 60 * DEG, -40 * DEG, 30 * DEG }, q[SPINE_NDOF], sf[3];
	assert_int_equal(spine_distribute(m, &f, all, q, sf), 0);
	for (int dir = 0; dir < 3; dir++) {
		double one[3] = { 0, 0, 0 }, q1[SPINE_NDOF], sf1[3];
		one[dir] = all[dir];
		assert_int_equal(spine_distribute(m, &f, one, q1, sf1), 0);
		for (int k = 0; k < SPINE_NJNT; k++)
			assert_true(q[3 * k + dir] == q1[3 * k + dir]);
		assert_true(sf[dir] == sf1[dir]);
	}
	model_free(m);
}

/* bends beyond the range: every joint in range at its limit, the rest reported */
static void
test_saturation(void **unused)
{
	(void)unused;
	struct model *m = build_human();
	struct spine_flavor fl[2] = { spine_bend_from_waist(), spine_curl_from_neck() };
	for (int i = 0; i < 2; i++)
		for (int sign = -1; sign <= 1; sign += 2) {
			double total[3], q[SPINE_NDOF], sf[3];
			/* 10 degrees past the range's limit in every direction */
			for (int dir = 0; dir < 3; dir++)
				total[dir] = range_capacity(m, &fl[i], dir, sign) + sign * 10 * DEG;
			assert_int_equal(spine_distribute(m, &fl[i], total, q, sf), 0);
			check_distribution(m, &fl[i], total, q, sf);
			for (int dir = 0; dir < 3; dir++) {
				for (int k = 0; k < SPINE_NJNT; k++) {
					int in = k >= fl[i].bottom && k <= fl[i].top;
					double want = in ? spine_cap(m, k, dir, sign) : 0;
					assert_true(q[3 * k + dir] == want);
				}
				assert_near(sf[dir], sign * 10 * DEG, TOL);
			}
		}
	/* a joint that cannot extend (lo = 0) takes none of an extension; the others make it up */
	struct model *mc = model_copy(m);
	assert_non_null(mc);
	struct spine_flavor f = spine_bend_from_waist();
	mc->dof_lo[spine_dof(mc, 3) + SPINE_FLEX] = 0;
	double total[3] = { -10 * DEG, 0, 0 }, q[SPINE_NDOF], sf[3];
	assert_int_equal(spine_distribute(mc, &f, total, q, sf), 0);
	check_distribution(mc, &f, total, q, sf);
	assert_true(q[3 * 3 + SPINE_FLEX] == 0);
	assert_true(sf[SPINE_FLEX] == 0);
	model_free(mc);
	model_free(m);
}

/* a pseudo-random number in [lo, hi] (deterministic) */
static double
rnd(uint32_t *seed, double lo, double hi)
{
	*seed = *seed * 1664525u + 1013904223u;
	return lo + (hi - lo) * (*seed >> 8) / (double)(1u << 24);
}

/* spine_totals gives back what spine_apply achieved, and nothing else moves */
static void
test_apply_totals(void **unused)
{
	(void)unused;
	struct model *m = build_human();
	struct state *s = state_make(m);
	kin_update(m, s);
	struct state *ref = state_make(m);
	assert_non_null(s);
	assert_non_null(ref);
	kin_update(m, ref);
	uint32_t seed = 12345;
	/* a posture with every dof somewhere within its limits */
	for (int d = 0; d < m->ndof; d++)
		s->q[d] = rnd(&seed, m->dof_lo[d], m->dof_hi[d]);
	kin_update(m, s);
	double t0[3];
	spine_totals(m, s, t0);
	double want0[3] = { 0, 0, 0 };
	for (int k = 0; k < SPINE_NJNT; k++)
		for (int dir = 0; dir < 3; dir++)
			want0[dir] += s->q[spine_dof(m, k) + dir];
	for (int dir = 0; dir < 3; dir++)
		assert_near(t0[dir], want0[dir], TOL);
	for (int it = 0; it < 200; it++) {
		struct spine_flavor f;
		f.bottom = (int)rnd(&seed, 0, 17.999);
		f.top = f.bottom + (int)rnd(&seed, 0, 17.999 - f.bottom);
		f.initiator = f.bottom + (int)rnd(&seed, 0, f.top - f.bottom + 0.999);
		f.resistor = f.bottom + (int)rnd(&seed, 0, f.top - f.bottom + 0.999);
		assert_int_equal(spine_flavor_check(&f), 0);
		double total[3], sf[3], got[3];
		for (int dir = 0; dir < 3; dir++)
			total[dir] = rnd(&seed, -120 * DEG, 120 * DEG);
		state_copy(m, s, ref);
		assert_int_equal(spine_apply(m, s, &f, total, sf), 0);
		spine_totals(m, s, got);
		for (int dir = 0; dir < 3; dir++)
			assert_near(got[dir], total[dir] - sf[dir], TOL);
		/* the values are spine_distribute's; the other dofs are untouched */
		double q[SPINE_NDOF], sf2[3];
		assert_int_equal(spine_distribute(m, &f, total, q, sf2), 0);
		check_distribution(m, &f, total, q, sf2);
		for (int k = 0; k < SPINE_NJNT; k++)
			for (int dir = 0; dir < 3; dir++)
				assert_true(s->q[spine_dof(m, k) + dir] == q[3 * k + dir]);
		for (int d = 0; d < m->ndof; d++)
			if (strncmp(m->jnt_name[m->dof_jnt[d]], "spine_", 6) != 0)
				assert_true(s->q[d] == ref->q[d]);
	}
	/* a rejected call leaves the state as it was */
	state_copy(m, s, ref);
	struct spine_flavor bad = { 5, 3, 4, 4 };
	double total[3] = { 0.1, 0.1, 0.1 };
	assert_int_equal(spine_apply(m, s, &bad, total, NULL), -1);
	assert_true(state_hash(m, s) == state_hash(m, ref));
	state_free(ref);
	state_free(s);
	model_free(m);
}

/* angle between a segment's y axis and the world's, in radians */
static double
seg_tilt(const struct model *m, const struct state *s, const char *seg)
{
	int g = model_find_segment(m, seg);
	if (g < 0)
		fail_msg("no segment %s", seg);
	double c = s->seg_xf[g].r[4];
	return acos(c > 1 ? 1 : c);
}

/* forward kinematics of the human: the bends go where the conventions say */
static void
test_kinematic_sense(void **unused)
{
	(void)unused;
	struct model *m = build_human();
	struct state *s = state_make(m);
	assert_non_null(s);
	kin_update(m, s);
	int head = model_find_site(m, HUMAN_SITE_HEAD), hseg = model_find_segment(m, "head");
	assert_true(head >= 0 && hseg >= 0);
	double p0[3];
	memcpy(p0, s->site_xf[head].p, sizeof p0);
	struct spine_flavor f = spine_bend_from_waist();
	/* 45 degrees forward from the waist: head forward (+z) and down */
	double fwd[3] = { 45 * DEG, 0, 0 }, sf[3];
	assert_int_equal(spine_apply(m, s, &f, fwd, sf), 0);
	assert_true(sf[0] == 0);
	const double *p = s->site_xf[head].p;
	assert_true(p[2] - p0[2] > 0.2);
	assert_true(p0[1] - p[1] > 0.05);
	assert_near(p[0], p0[0], 1e-9);
	/* all flexion axes are parallel: the chest and head are pitched by exactly 45 degrees */
	assert_near(seg_tilt(m, s, "T6"), 45 * DEG, 1e-9);
	assert_near(seg_tilt(m, s, "head"), 45 * DEG, 1e-9);
	assert_true(s->seg_xf[hseg].r[7] > 0); /* its up axis leans to +z */
	/* above the range the spine stays straight */
	for (int k = 12; k < SPINE_NJNT; k++)
		for (int dir = 0; dir < 3; dir++)
			assert_true(s->q[spine_dof(m, k) + dir] == 0);
	assert_near(seg_tilt(m, s, "T1"), 45 * DEG, 1e-9);
	/* backwards: head back (-z) */
	double back[3] = { -20 * DEG, 0, 0 };
	assert_int_equal(spine_apply(m, s, &f, back, sf), 0);
	assert_true(s->site_xf[head].p[2] < p0[2] - 0.05);
	/* lateral bend + is to the left, +x */
	double left[3] = { 0, 20 * DEG, 0 };
	assert_int_equal(spine_apply(m, s, &f, left, sf), 0);
	assert_true(s->site_xf[head].p[0] > p0[0] + 0.05);
	assert_near(seg_tilt(m, s, "head"), 20 * DEG, 1e-9);
	/* axial + turns the face left: the head's forward axis (+z) gains +x */
	double turn[3] = { 0, 0, 20 * DEG };
	assert_int_equal(spine_apply(m, s, &f, turn, sf), 0);
	const double *r = s->seg_xf[hseg].r;
	assert_near(atan2(r[2], r[8]), 20 * DEG, 1e-9);
	/* curl from the neck: 30 degrees pitches the head by 30 */
	f = spine_curl_from_neck();
	assert_int_equal(spine_apply(m, s, &f, (double[3]){ 30 * DEG, 0, 0 }, sf), 0);
	assert_near(seg_tilt(m, s, "head"), 30 * DEG, 1e-9);
	state_free(s);
	model_free(m);
}

/* two segments joined by a one-dof "spine_0": not a standard spine */
static struct model *
not_a_spine(void)
{
	struct model_builder *b = model_builder_create("stick");
	struct segment_def sd = segment_default_def();
	sd.name = "a";
	int a = model_builder_segment(b, &sd);
	sd.name = "b";
	int bs = model_builder_segment(b, &sd);
	double o[3] = { 0, 0, 0 };
	int sa = model_builder_site(b, a, "top", o, QID);
	int sb = model_builder_site(b, bs, "origin", o, QID);
	struct joint_def jd = joint_default_def();
	jd.name = "spine_0";
	jd.site_from = sa;
	jd.site_to = sb;
	jd.ndof = 1;
	jd.dof[0] = (struct dof_def){ DOF_ROTATION, 0, 1, -1, 1, 0 };
	assert_true(model_builder_joint(b, &jd) >= 0);
	assert_int_equal(model_builder_root(b, sa, o, QID), 0);
	struct model *m = model_builder_finish(b);
	assert_non_null(m);
	model_builder_free(b);
	return m;
}

static void
test_rejects(void **unused)
{
	(void)unused;
	struct model *m = build_human();
	static const struct spine_flavor bad[] = {
		{ -1, 5, 0, 5 },  { 0, 18, 0, 17 }, { 6, 5, 5, 6 }, { 2, 8, 1, 8 },
		{ 2, 8, 9, 2 },   { 2, 8, 2, 1 },   { 2, 8, 2, 9 }, { 18, 18, 18, 18 },
		{ -3, -1, -2, -2 },
	};
	double total[3] = { 0.1, 0.1, 0.1 }, q[SPINE_NDOF], sf[3], w[SPINE_NJNT];
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		for (int d = 0; d < SPINE_NDOF; d++)
			q[d] = 7;
		sf[0] = sf[1] = sf[2] = 7;
		w[0] = 7;
		assert_int_equal(spine_flavor_check(&bad[i]), -1);
		assert_int_equal(spine_weights(&bad[i], w), -1);
		assert_int_equal(spine_distribute(m, &bad[i], total, q, sf), -1);
		/* nothing written */
		for (int d = 0; d < SPINE_NDOF; d++)
			assert_true(q[d] == 7);
		assert_true(sf[0] == 7 && sf[1] == 7 && sf[2] == 7 && w[0] == 7);
	}
	struct spine_flavor f = spine_bend_from_waist();
	assert_int_equal(spine_distribute(m, NULL, total, q, sf), -1);
	/* non-finite totals */
	double nan_total[3] = { 0, NAN, 0 }, inf_total[3] = { INFINITY, 0, 0 };
	assert_int_equal(spine_distribute(m, &f, nan_total, q, sf), -1);
	assert_int_equal(spine_distribute(m, &f, inf_total, q, sf), -1);
	/* a spine that cannot rest straight */
	struct model *mc = model_copy(m);
	assert_non_null(mc);
	mc->dof_lo[spine_dof(mc, 14) + SPINE_LAT] = 0.01;
	assert_int_equal(spine_distribute(mc, &f, total, q, sf), -1);
	model_free(mc);
	/* a figure without the standard spine */
	struct model *ns = not_a_spine();
	struct state *s = state_make(ns);
	assert_non_null(s);
	kin_update(ns, s);
	assert_int_equal(spine_distribute(ns, &f, total, q, sf), -1);
	assert_int_equal(spine_apply(ns, s, &f, total, sf), -1);
	s->q[0] = 0.5;
	double t[3] = { 9, 9, 9 };
	spine_totals(ns, s, t);
	assert_true(t[0] == 0 && t[1] == 0 && t[2] == 0);
	state_free(s);
	model_free(ns);
	model_free(m);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_flavors),     cmocka_unit_test(test_weights),
		cmocka_unit_test(test_totals_met),  cmocka_unit_test(test_monotone),
		cmocka_unit_test(test_independent), cmocka_unit_test(test_saturation),
		cmocka_unit_test(test_apply_totals), cmocka_unit_test(test_kinematic_sense),
		cmocka_unit_test(test_rejects),
	};
	return cmocka_run_group_tests_name("spine", tests, NULL, NULL);
}
