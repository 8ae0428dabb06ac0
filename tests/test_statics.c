/*
 * test_statics.c - the static equilibrium against analytic answers: a
 * horizontal arm holding a weight (the shoulder's moment is the sum of
 * weights times lever arms), the standing knees (the body above them and
 * its centre of mass), the weight shared between the feet as balance.h
 * shares it and between seat and feet by the lever rule, the whole body's
 * equilibrium on random postures and loads, the same figure re-rooted or
 * mirrored, a figure that tips or is lifted, one that is not a human, and
 * the errors.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "alloc_count.h"
#include "test_util.h"
#include "test_human.h"
#include "test_random.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assess/statics.h"
#include "figure/kin.h"
#include "figure/mathx.h"
#include "figure/state.h"
#include "pose/balance.h"
#include "pose/load.h"

#define RAD(d) ((d) * M_PI / 180)
#define G LOAD_GRAVITY
#define EXACT 1e-9 /* N m, N, or relative: what is exact up to rounding */

struct fx {
	struct model *m;
	struct state *s;
	struct statics_result r;
};

static int
setup(void **st)
{
	struct fx *f = calloc(1, sizeof *f);
	f->m = test_human();
	f->s = state_make(f->m);
	kin_update(f->m, f->s);
	*st = f;
	return 0;
}

static int
teardown(void **st)
{
	struct fx *f = *st;
	state_free(f->s);
	model_free(f->m);
	free(f);
	return 0;
}

static void
set_deg(struct fx *f, const char *joint, int k, double deg)
{
	int j = model_find_joint(f->m, joint);
	assert_true(j >= 0 && k < f->m->jnt_ndof[j]);
	f->s->q[f->m->jnt_dof0[j] + k] = RAD(deg);
}

static int
joint(const struct fx *f, const char *name)
{
	int j = model_find_joint(f->m, name);
	assert_true(j >= 0);
	return j;
}

static void
solve(struct fx *f, const struct ext_load *loads, int n, int seated)
{
	char err[256] = "";
	kin_update(f->m, f->s);
	if (statics_solve(f->m, f->s, loads, n, seated, &f->r, err, sizeof err) < 0)
		fail_msg("statics_solve: %s", err);
}

/* a weight of kg at a site */
static struct ext_load
weight_at(const struct model *m, const char *site, double kg)
{
	struct ext_load l = { 0 };
	int k = test_site(m, site);
	l.seg = m->site_seg[k];
	memcpy(l.local, m->site_loc[k].p, sizeof l.local);
	l.mass = kg;
	l.force[1] = -kg * G;
	return l;
}

/* the segments at and below seg in the tree rooted at the pelvis, by the joints' sites */
static int
below(const struct model *m, int top, int seg)
{
	for (int guard = 0; guard < m->nseg; guard++) {
		if (seg == top)
			return 1;
		int up = -1;
		for (int j = 0; j < m->njnt; j++) /* the human's joints run from proximal to distal */
			if (m->site_seg[m->jnt_site_to[j]] == seg)
				up = m->site_seg[m->jnt_site_from[j]];
		if (up < 0)
			return 0;
		seg = up;
	}
	return 0;
}

/*
 * The arm held straight forward, a weight in the hand: the shoulder's
 * flexion moment is g times each mass's lever arm in front of the joint,
 * its moment about the vertical none, about the arm's long axis g times
 * the masses' sideways offsets; the force the arm's and the weight's.
 */
static void
test_arm_held_forward_with_a_weight(void **st)
{
	struct fx *f = *st;
	for (int side = 0; side < 2; side++) {
		const char *sh = side ? "shoulder_r" : "shoulder_l";
		state_reset(f->m, f->s);
		set_deg(f, sh, 0, 90);
		struct ext_load w = weight_at(f->m, side ? "hand_r.palm" : "hand_l.palm", 7.5);
		solve(f, &w, 1, 0);
		int j = joint(f, sh), arm = f->m->site_seg[f->m->jnt_site_to[j]];
		const double *c = f->s->site_xf[f->m->jnt_site_to[j]].p;
		double flex = 0, rot = 0, mass = 0;
		for (int seg = 0; seg < f->m->nseg; seg++)
			if (below(f->m, arm, seg)) {
				const double *p = &f->s->seg_com_w[3 * seg];
				flex += f->m->seg_mass[seg] * G * (p[2] - c[2]);
				rot += f->m->seg_mass[seg] * G * (p[0] - c[0]);
				mass += f->m->seg_mass[seg];
			}
		double palm[3];
		xform_apply(&f->s->seg_xf[w.seg], w.local, palm);
		flex += 7.5 * G * (palm[2] - c[2]);
		rot += 7.5 * G * (palm[0] - c[0]);
		assert_true(flex > 30); /* the arm and 7.5 kg some 0.3 m out */
		assert_near(f->r.anat[j][0], flex, EXACT);
		assert_near(f->r.anat[j][1], 0, EXACT); /* abduction's axis is vertical now */
		/* internal rotation about the arm's long axis, now forward (+z); mirrored */
		assert_near(f->r.anat[j][2], side ? -rot : rot, EXACT);
		assert_near(f->r.force[j][1], (mass + 7.5) * G, EXACT);
		assert_near(f->r.force[j][0], 0, EXACT);
		assert_near(f->r.force[j][2], 0, EXACT);
	}
}

/*
 * Standing at rest: the two knees carry what lies above them; taking
 * moments about the line through both knee centres, each knee's flexion
 * moment is half the upper body's weight times its centre of mass's
 * forward offset from that line.
 */
static void
test_standing_knees_carry_the_centre_of_mass_offset(void **st)
{
	struct fx *f = *st;
	solve(f, NULL, 0, 0);
	int kl = joint(f, "knee_l"), kr = joint(f, "knee_r");
	int shank[2] = { f->m->site_seg[f->m->jnt_site_to[kl]], f->m->site_seg[f->m->jnt_site_to[kr]] };
	double mass = 0, z = 0;
	for (int seg = 0; seg < f->m->nseg; seg++)
		if (!below(f->m, shank[0], seg) && !below(f->m, shank[1], seg)) {
			mass += f->m->seg_mass[seg];
			z += f->m->seg_mass[seg] * f->s->seg_com_w[3 * seg + 2];
		}
	z /= mass;
	double zk = f->r.point[kl][2];
	assert_near(f->r.point[kr][2], zk, 1e-12);
	assert_near(f->r.point[kr][1], f->r.point[kl][1], 1e-12);
	double want = mass * G * (z - zk) / 2;
	assert_true(fabs(want) > 0.1); /* the rest posture's centre of mass is not over the knees */
	assert_near(f->r.anat[kl][0], want, EXACT);
	assert_near(f->r.anat[kr][0], want, EXACT);
	assert_near(f->r.moment[kl][0], want, EXACT); /* the knee's axis is x at rest */
	/* the feet share the weight equally, each straight up at its balance site */
	assert_int_equal(f->r.nsupport, 2);
	assert_int_equal(f->r.contacts, 2);
	assert_false(f->r.tips);
	for (int k = 0; k < 2; k++) {
		assert_near(f->r.support[k].force[1], f->m->total_mass * G / 2, EXACT);
		assert_near(f->r.support[k].share, 0.5, 1e-12);
	}
}

/* the sums over the whole body: supports + loads + weights, force and moment about the origin */
static void
residual(const struct fx *f, const struct ext_load *loads, int n, double dest[6], double *scale)
{
	memset(dest, 0, 6 * sizeof *dest);
	*scale = 0;
	for (int seg = 0; seg < f->m->nseg; seg++) {
		double w[3] = { 0, -f->m->seg_mass[seg] * G, 0 }, c[3];
		mathx_cross(&f->s->seg_com_w[3 * seg], w, c);
		dest[1] += w[1];
		for (int i = 0; i < 3; i++)
			dest[3 + i] += c[i];
		*scale += -w[1];
	}
	for (int k = 0; k < n; k++) {
		double x[3], c[3];
		xform_apply(&f->s->seg_xf[loads[k].seg], loads[k].local, x);
		mathx_cross(x, loads[k].force, c);
		for (int i = 0; i < 3; i++) {
			dest[i] += loads[k].force[i];
			dest[3 + i] += c[i] + loads[k].torque[i];
			*scale += fabs(loads[k].force[i]) + fabs(loads[k].torque[i]);
		}
	}
	for (int k = 0; k < f->r.nsupport; k++) {
		const struct statics_support *u = &f->r.support[k];
		double c[3];
		mathx_cross(u->point, u->force, c);
		for (int i = 0; i < 3; i++) {
			dest[i] += u->force[i];
			dest[3 + i] += c[i] + u->moment[i];
		}
	}
}

static void
random_posture(struct fx *f)
{
	for (int d = 0; d < f->m->ndof; d++)
		f->s->q[d] = span(f->m->dof_lo[d], f->m->dof_hi[d]);
}

/* n loads on random segments at random points: forces, torques and weights */
static int
random_loads(const struct model *m, struct ext_load *dest, int n)
{
	for (int k = 0; k < n; k++) {
		struct ext_load *l = &dest[k];
		memset(l, 0, sizeof *l);
		l->seg = (int)(urand() * m->nseg);
		for (int i = 0; i < 3; i++)
			l->local[i] = span(-0.2, 0.2);
		if (urand() < 0.3) {
			l->mass = span(0.5, 20);
			l->force[1] = -l->mass * G;
			continue;
		}
		for (int i = 0; i < 3; i++) {
			l->force[i] = span(-300, 300);
			l->torque[i] = urand() < 0.5 ? span(-20, 20) : 0;
		}
	}
	return n;
}

/*
 * On random postures and loads, seated or standing, whether the figure
 * would tip or not, the supports, loads and weights sum to zero force and
 * moment (1e-9 of the forces' sum, the moments taken about the world's
 * origin with 1 m as the length scale: the figure stands near it).
 */
static void
test_whole_body_equilibrium_closes(void **st)
{
	struct fx *f = *st;
	rng_state = 26;
	struct ext_load loads[6];
	for (int trial = 0; trial < 500; trial++) {
		random_posture(f);
		int n = random_loads(f->m, loads, (int)(urand() * 7));
		int seated = trial % 3 == 0;
		solve(f, loads, n, seated);
		double res[6], scale;
		residual(f, loads, n, res, &scale);
		for (int i = 0; i < 6; i++)
			if (!(fabs(res[i]) <= 1e-9 * scale))
				fail_msg("trial %d: residual %d = %.3g of %.3g", trial, i, res[i], scale);
		double shares = 0;
		for (int k = 0; k < f->r.nsupport; k++) {
			assert_true(f->r.support[k].share >= 0);
			shares += f->r.support[k].share;
		}
		assert_near(shares, 1, 1e-12);
		assert_near(f->r.weight_n, f->m->total_mass * G, 1e-9);
	}
}

/*
 * The feet share the weight as balance.h's weight_l says (the lever rule
 * along the line between their balance sites): the upper body bent and
 * twisted at random over feet that stay on the floor.
 */
static void
test_feet_share_as_balance_does(void **st)
{
	struct fx *f = *st;
	rng_state = 5;
	int tested = 0;
	for (int trial = 0; trial < 200; trial++) {
		state_reset(f->m, f->s);
		for (int d = 0; d < f->m->ndof; d++) {
			const char *name = f->m->jnt_name[f->m->dof_jnt[d]];
			if (strncmp(name, "hip", 3) && strncmp(name, "knee", 4) &&
			    strncmp(name, "ankle", 5) && strncmp(name, "toe", 3))
				f->s->q[d] = span(f->m->dof_lo[d], f->m->dof_hi[d]) / 3;
		}
		solve(f, NULL, 0, 0);
		struct balance b;
		assert_int_equal(balance_measure(f->m, f->s, BALANCE_CONTACT, &b), 0);
		assert_int_equal(f->r.nsupport, 2);
		assert_near(f->r.support[0].share, b.weight_l, 1e-12);
		assert_near(f->r.support[1].share, 1 - b.weight_l, 1e-12);
		/* no loads: the centre of pressure is under the centre of mass */
		assert_near(f->r.cop[0], f->s->com[0], 1e-12);
		assert_near(f->r.cop[2], f->s->com[2], 1e-12);
		assert_int_equal(f->r.tips, b.margin < 0);
		tested += b.weight_l > 0 && b.weight_l < 1;
	}
	assert_true(tested > 100); /* mostly between the feet, not all on one */
}

/*
 * Seated with thighs level and shanks upright, the feet flat on the floor:
 * the seat (two ischial tuberosities) and the feet share the weight by the
 * lever rule of the centre of mass between the seat's line and the feet's,
 * each pair evenly.
 */
static void
test_seated_lever_between_seat_and_feet(void **st)
{
	struct fx *f = *st;
	for (int side = 0; side < 2; side++) {
		set_deg(f, side ? "hip_r" : "hip_l", 0, 90);
		set_deg(f, side ? "knee_r" : "knee_l", 0, 90);
	}
	kin_update(f->m, f->s);
	int bal = test_site(f->m, "foot_l.balance");
	struct xform root = f->s->root_xf;
	root.p[1] -= f->s->site_xf[bal].p[1];
	state_root_at(f->m, f->s, f->s->root_site, &root);
	solve(f, NULL, 0, 1);
	assert_int_equal(f->r.nsupport, 4);
	assert_int_equal(f->r.contacts, 4);
	assert_false(f->r.tips);
	double zs = 0, zf = 0, seat = 0, feet = 0;
	for (int k = 0; k < 4; k++) {
		const struct statics_support *u = &f->r.support[k];
		double z = f->s->site_xf[u->site].p[2];
		if (u->kind == STATICS_SEAT) {
			zs += z / 2, seat += u->force[1];
			assert_int_equal(u->seg, model_find_segment(f->m, "pelvis"));
		} else {
			assert_int_equal(u->kind, STATICS_FOOT);
			zf += z / 2, feet += u->force[1];
		}
	}
	double w = f->m->total_mass * G, zc = f->s->com[2];
	assert_true(zc > zs && zc < zf);
	assert_near(feet, w * (zc - zs) / (zf - zs), EXACT);
	assert_near(seat, w * (zf - zc) / (zf - zs), EXACT);
	assert_near(f->r.support[0].force[1], f->r.support[1].force[1], EXACT);
	assert_near(f->r.support[2].force[1], f->r.support[3].force[1], EXACT);
	/* the feet bear the lower legs and some of the thighs, the seat the rest */
	assert_true(feet > 0.05 * w && feet < 0.4 * w);
}

/* every number of two results, to tol of its magnitude */
static void
assert_same_result(const struct statics_result *a, const struct statics_result *b, int njnt,
		   int ndof)
{
	for (int j = 0; j < njnt; j++)
		for (int i = 0; i < 3; i++) {
			assert_near(a->force[j][i], b->force[j][i], EXACT * (1 + fabs(a->force[j][i])));
			assert_near(a->moment[j][i], b->moment[j][i], EXACT * (1 + fabs(a->moment[j][i])));
			assert_near(a->anat[j][i], b->anat[j][i], EXACT * (1 + fabs(a->anat[j][i])));
			assert_near(a->point[j][i], b->point[j][i], 1e-12);
		}
	for (int d = 0; d < ndof; d++)
		assert_near(a->dof_torque[d], b->dof_torque[d], EXACT * (1 + fabs(a->dof_torque[d])));
	assert_int_equal(a->nsupport, b->nsupport);
	for (int k = 0; k < a->nsupport; k++)
		for (int i = 0; i < 3; i++) {
			assert_near(a->support[k].force[i], b->support[k].force[i], EXACT);
			assert_near(a->support[k].moment[i], b->support[k].moment[i], EXACT);
			assert_near(a->support[k].point[i], b->support[k].point[i], 1e-12);
		}
	assert_int_equal(a->tips, b->tips);
	assert_int_equal(a->root_seg, b->root_seg);
}

/* rooted at a foot or a hand instead of the pelvis, nothing moved: the same answers */
static void
test_rerooted_figure_gives_the_same(void **st)
{
	struct fx *f = *st;
	static const char *const roots[] = { "foot_l.balance", "hand_r.palm", "head.between_eyes",
					     "pelvis.root" };
	static struct statics_result first;
	rng_state = 11;
	struct ext_load loads[4];
	for (int trial = 0; trial < 40; trial++) {
		state_reset(f->m, f->s);
		random_posture(f);
		int n = random_loads(f->m, loads, 4);
		solve(f, loads, n, trial % 2);
		first = f->r;
		for (size_t k = 0; k < sizeof roots / sizeof *roots; k++) {
			assert_int_equal(kin_set_root(f->m, f->s, test_site(f->m, roots[k])), 0);
			solve(f, loads, n, trial % 2);
			assert_same_result(&first, &f->r, f->m->njnt, f->m->ndof);
		}
	}
}

/* the left and right joint of a pair, or spine_0 with itself */
static int
mirror_joint(const struct model *m, int j)
{
	char name[MODEL_NAME_MAX];
	snprintf(name, sizeof name, "%s", m->jnt_name[j]);
	size_t n = strlen(name);
	if (n > 2 && name[n - 2] == '_' && (name[n - 1] == 'l' || name[n - 1] == 'r'))
		name[n - 1] = name[n - 1] == 'l' ? 'r' : 'l';
	return model_find_joint(m, name);
}

/*
 * A posture and its mirror image (the limbs' values swapped side for side,
 * the spine's bending and turning negated), loads mirrored too: each
 * anatomical moment on the left reads as its mirror on the right, the
 * spine's flexion alike and its bending and turning negated.
 */
static void
test_mirrored_posture_reads_the_same_on_the_other_side(void **st)
{
	struct fx *f = *st;
	static struct statics_result first;
	const struct model *m = f->m;
	rng_state = 3;
	double q[HUMAN_NDOF];
	for (int trial = 0; trial < 50; trial++) {
		state_reset(f->m, f->s);
		random_posture(f);
		struct ext_load l[2] = { weight_at(m, "hand_l.palm", 6), weight_at(m, "hand_r.palm", 1) };
		l[1].mass = 0; /* a push and a twist */
		for (int i = 0; i < 3; i++)
			l[1].force[i] = span(-100, 100), l[1].torque[i] = span(-5, 5);
		solve(f, l, 2, 0);
		first = f->r;
		/* the mirror: x negated for points and forces; torques are pseudo-vectors */
		memcpy(q, f->s->q, sizeof q);
		for (int j = 0; j < m->njnt; j++) {
			int mj = mirror_joint(m, j);
			assert_true(mj >= 0);
			for (int k = 0; k < m->jnt_ndof[j]; k++) {
				double v = q[m->jnt_dof0[mj] + k];
				int spine = !strncmp(m->jnt_name[j], "spine_", 6);
				f->s->q[m->jnt_dof0[j] + k] = spine && k > 0 ? -v : v;
			}
		}
		struct ext_load ml[2];
		for (int k = 0; k < 2; k++) {
			ml[k] = l[k];
			ml[k].seg = m->site_seg[test_site(m, k ? "hand_l.palm" : "hand_r.palm")];
			ml[k].local[0] = -l[k].local[0];
			ml[k].force[0] = -l[k].force[0];
			ml[k].torque[1] = -l[k].torque[1];
			ml[k].torque[2] = -l[k].torque[2];
		}
		solve(f, ml, 2, 0);
		for (int j = 0; j < m->njnt; j++) {
			if (!first.anatomical[j])
				continue;
			int mj = mirror_joint(m, j), spine = mj == j;
			for (int k = 0; k < 3; k++) {
				double want = spine && k > 0 ? -first.anat[j][k] : first.anat[j][k];
				assert_near(f->r.anat[mj][k], want, 1e-9 * (1 + fabs(want)));
			}
		}
	}
}

/* a hand pulled forward hard enough: the centre of pressure leaves the feet */
static void
test_a_pull_that_tips_the_figure_is_flagged(void **st)
{
	struct fx *f = *st;
	set_deg(f, "shoulder_r", 0, 90);
	struct ext_load pull = weight_at(f->m, "hand_r.palm", 1);
	pull.mass = 0;
	pull.force[1] = 0;
	pull.force[2] = 20; /* N forward at shoulder height: the centre of pressure 4 cm ahead */
	solve(f, &pull, 1, 0);
	assert_false(f->r.tips);
	assert_false(f->r.lifts);
	assert_true(f->r.margin > 0);
	double small = f->r.cop[2];
	pull.force[2] = 400; /* about 0.8 m ahead: far past the toes */
	solve(f, &pull, 1, 0);
	assert_true(f->r.tips);
	assert_false(f->r.lifts);
	assert_true(f->r.margin < 0);
	/* the centre of pressure moves by the pull's moment over the weight */
	double h = f->s->site_xf[test_site(f->m, "hand_r.palm")].p[1];
	assert_near(f->r.cop[2] - small, 380 * h / (f->m->total_mass * G), 1e-9);
	/* still in equilibrium: the feet push back and the figure would tip, said */
	double res[6], scale;
	residual(f, &pull, 1, res, &scale);
	for (int i = 0; i < 6; i++)
		assert_true(fabs(res[i]) <= 1e-9 * scale);
	/* pulled up harder than it weighs: lifted, so it tips */
	pull.force[2] = 0;
	pull.force[1] = 1.2 * f->m->total_mass * G;
	solve(f, &pull, 1, 0);
	assert_true(f->r.lifts);
	assert_true(f->r.tips);
}

/* one foot raised: the other carries everything, its point under the centre of pressure */
static void
test_standing_on_one_foot(void **st)
{
	struct fx *f = *st;
	set_deg(f, "hip_r", 0, 40);
	set_deg(f, "knee_r", 0, 70);
	solve(f, NULL, 0, 0);
	assert_int_equal(f->r.nsupport, 1);
	assert_int_equal(f->r.contacts, 1);
	const struct statics_support *u = &f->r.support[0];
	assert_int_equal(u->site, test_site(f->m, "foot_l.balance"));
	assert_near(u->share, 1, 0);
	assert_near(u->force[1], f->m->total_mass * G, EXACT);
	assert_near(u->point[0], f->s->com[0], 1e-12);
	assert_near(u->point[2], f->s->com[2], 1e-12);
	assert_true(f->r.tips); /* the centre of mass is over the balance line's middle, not the foot */
	/* the raised leg's knee holds just the shank and foot */
	int kr = joint(f, "knee_r");
	double mass = 0;
	for (int seg = 0; seg < f->m->nseg; seg++)
		if (below(f->m, f->r.distal_seg[kr], seg))
			mass += f->m->seg_mass[seg];
	assert_near(f->r.force[kr][1], mass * G, EXACT);
}

/* a figure that is not a human: held at its root, a lever's moment exactly m g d */
static struct model *
lever(int nseg)
{
	static const double QID[4] = { 0, 0, 0, 1 };
	struct model_builder *b = model_builder_create("lever");
	struct segment_def sd = segment_default_def();
	char name[32];
	int prev_tip = -1;
	for (int i = 0; i < nseg; i++) {
		snprintf(name, sizeof name, "s%d", i);
		sd.name = name;
		sd.mass = i ? 2 : 1;
		sd.com[0] = i ? 0.5 : 0;
		int seg = model_builder_segment(b, &sd);
		double o[3] = { 0, 0, 0 }, tip[3] = { 1, 0, 0 };
		int base = model_builder_site(b, seg, "origin", o, QID);
		int end = model_builder_site(b, seg, "tip", tip, QID);
		if (!i) {
			assert_int_equal(model_builder_root(b, base, o, QID), 0);
		} else {
			struct joint_def jd = joint_default_def();
			snprintf(name, sizeof name, "j%d", i);
			jd.name = name;
			jd.site_from = prev_tip;
			jd.site_to = base;
			jd.ndof = 1;
			jd.dof[0] = (struct dof_def){ DOF_ROTATION, 2, 1, -M_PI, M_PI, 0 };
			assert_true(model_builder_joint(b, &jd) >= 0);
		}
		prev_tip = end;
	}
	struct model *m = model_builder_finish(b);
	assert_non_null(m);
	model_builder_free(b);
	return m;
}

static void
test_a_figure_without_feet_is_held_at_its_root(void **unused)
{
	(void)unused;
	struct model *m = lever(2);
	struct state *s = state_make(m);
	static struct statics_result r;
	char err[256];
	kin_update(m, s);
	assert_int_equal(statics_solve(m, s, NULL, 0, 0, &r, err, sizeof err), 0);
	assert_int_equal(r.nsupport, 1);
	assert_int_equal(r.support[0].kind, STATICS_ROOT);
	assert_near(r.support[0].force[1], 3 * G, EXACT);
	/* the link sticks out along +x with its 2 kg 0.5 m out: about +z the joint holds 2 g 0.5 */
	assert_near(r.dof_torque[0], G, EXACT);
	assert_near(r.moment[0][2], G, EXACT);
	assert_near(r.force[0][1], 2 * G, EXACT);
	assert_false(r.anatomical[0]);
	assert_null(statics_axis_names(m, 0));
	assert_false(r.tips);
	/* seated needs a seat's sites */
	assert_int_equal(statics_solve(m, s, NULL, 0, 1, &r, err, sizeof err), -1);
	assert_non_null(strstr(err, "ischial"));
	state_free(s);
	model_free(m);
	/* too large a figure is refused, said */
	m = lever(STATICS_MAX_SEG + 1);
	s = state_make(m);
	kin_update(m, s);
	assert_int_equal(statics_solve(m, s, NULL, 0, 0, &r, err, sizeof err), -1);
	assert_non_null(strstr(err, "larger"));
	state_free(s);
	model_free(m);
}

/* the anatomical joints and their axes' names */
static void
test_anatomical_joints(void **st)
{
	struct fx *f = *st;
	static const char *const anat[] = { "spine_0", "hip_l", "hip_r", "knee_l", "knee_r",
					    "ankle_l", "ankle_r", "shoulder_l", "shoulder_r",
					    "elbow_l", "elbow_r", "wrist_l", "wrist_r" };
	int n = 0;
	for (int j = 0; j < f->m->njnt; j++) {
		int want = 0;
		for (size_t k = 0; k < sizeof anat / sizeof *anat; k++)
			want |= !strcmp(f->m->jnt_name[j], anat[k]);
		assert_int_equal(statics_anatomical_joint(f->m, j), want);
		assert_int_equal(statics_axis_names(f->m, j) != NULL, want);
		n += want;
	}
	assert_int_equal(n, 13);
	assert_string_equal(statics_axis_names(f->m, joint(f, "ankle_r"))[0], "dorsiflexion");
	assert_string_equal(statics_axis_names(f->m, joint(f, "wrist_l"))[2], "pronation");
	assert_string_equal(statics_axis_names(f->m, joint(f, "spine_0"))[1], "lateral_bend");
	assert_false(statics_anatomical_joint(f->m, -1));
	assert_false(statics_anatomical_joint(f->m, f->m->njnt));
}

/* bad loads and postures: an error that says why, the result untouched */
static void
test_bad_input_is_refused(void **st)
{
	struct fx *f = *st;
	static struct statics_result before;
	char err[256];
	kin_update(f->m, f->s);
	memset(&f->r, 0x5a, sizeof f->r);
	before = f->r;
	struct ext_load l = weight_at(f->m, "hand_l.palm", 5);
	struct ext_load bad = l;
	bad.seg = f->m->nseg;
	assert_int_equal(statics_solve(f->m, f->s, &bad, 1, 0, &f->r, err, sizeof err), -1);
	assert_non_null(strstr(err, "segment"));
	bad = l;
	bad.force[1] = NAN;
	assert_int_equal(statics_solve(f->m, f->s, &bad, 1, 0, &f->r, err, sizeof err), -1);
	assert_non_null(strstr(err, "finite"));
	bad = l;
	bad.force[1] = -5; /* a weight that does not weigh its mass */
	assert_int_equal(statics_solve(f->m, f->s, &bad, 1, 0, &f->r, err, sizeof err), -1);
	assert_non_null(strstr(err, "weight"));
	bad = l;
	bad.mass = -1;
	assert_int_equal(statics_solve(f->m, f->s, &bad, 1, 0, &f->r, err, sizeof err), -1);
	assert_int_equal(statics_solve(f->m, f->s, &l, STATICS_MAX_LOADS + 1, 0, &f->r, err,
				       sizeof err), -1);
	assert_int_equal(statics_solve(f->m, f->s, NULL, 1, 0, &f->r, err, sizeof err), -1);
	f->s->seg_xf[3].p[1] = INFINITY;
	assert_int_equal(statics_solve(f->m, f->s, NULL, 0, 0, &f->r, err, sizeof err), -1);
	assert_non_null(strstr(err, "finite"));
	assert_memory_equal(&f->r, &before, sizeof before);
}

static void
test_solving_allocates_nothing(void **st)
{
	struct fx *f = *st;
#if COUNT_ALLOCS
	struct ext_load l[2] = { weight_at(f->m, "hand_l.palm", 5),
				 weight_at(f->m, "hand_r.palm", 5) };
	char err[256];
	random_posture(f);
	kin_update(f->m, f->s);
	long a = allocs;
	for (int seated = 0; seated < 2; seated++)
		assert_int_equal(statics_solve(f->m, f->s, l, 2, seated, &f->r, err, sizeof err), 0);
	assert_int_equal(allocs, a);
#else
	(void)f;
	skip();
#endif
}

int
main(void)
{
#define T(t) cmocka_unit_test_setup_teardown(t, setup, teardown)
	const struct CMUnitTest tests[] = {
		T(test_arm_held_forward_with_a_weight),
		T(test_standing_knees_carry_the_centre_of_mass_offset),
		T(test_whole_body_equilibrium_closes),
		T(test_feet_share_as_balance_does),
		T(test_seated_lever_between_seat_and_feet),
		T(test_rerooted_figure_gives_the_same),
		T(test_mirrored_posture_reads_the_same_on_the_other_side),
		T(test_a_pull_that_tips_the_figure_is_flagged),
		T(test_standing_on_one_foot),
		cmocka_unit_test(test_a_figure_without_feet_is_held_at_its_root),
		T(test_anatomical_joints),
		T(test_bad_input_is_refused),
		T(test_solving_allocates_nothing),
	};
#undef T
	return cmocka_run_group_tests(tests, NULL, NULL);
}
