/*
 * test_body_angles.c - the body angles and the NIOSH lifting geometry
 * measured on the human against analytic postures: joints set so that the
 * answer follows from the joint conventions of human.h and the built
 * figure's rest geometry by hand (spherical trigonometry, a planar chain),
 * the same posture turned about the vertical and re-rooted, and the weight
 * share against the centre of mass between the feet.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "alloc_count.h"
#include "test_util.h"
#include "test_human.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assess/body_angles.h"
#include "assess/niosh_measure.h"
#include "figure/kin.h"
#include "figure/mathx.h"
#include "figure/state.h"
#include "pose/balance.h"
#include "pose/spine.h"

#define RAD(d) ((d) * M_PI / 180)
#define DEGS(r) ((r) * 180 / M_PI)
#define EXACT 1e-9 /* deg or m: a reading that is exact up to rounding */

struct fx {
	struct model *m;
	struct state *s;
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

static double *
dof(struct fx *f, const char *joint, int k)
{
	int j = model_find_joint(f->m, joint);
	assert_true(j >= 0);
	assert_true(k < f->m->jnt_ndof[j]);
	return &f->s->q[f->m->jnt_dof0[j] + k];
}

static void
set_deg(struct fx *f, const char *joint, int k, double deg)
{
	*dof(f, joint, k) = RAD(deg);
}

static struct body_angles
measure_kneel(struct fx *f, double kneel_height)
{
	char err[256];
	struct body_angles a;
	kin_update(f->m, f->s);
	if (body_angles_measure(f->m, f->s, 0, kneel_height, &a, err, sizeof err) < 0)
		fail_msg("%s", err);
	return a;
}

static struct body_angles
measure(struct fx *f)
{
	return measure_kneel(f, 0.05);
}

/* world position of a site now */
static const double *
at(struct fx *f, const char *site)
{
	return f->s->site_xf[test_site(f->m, site)].p;
}

/* turns the whole figure about the world's vertical by deg and moves it by (dx, dz) */
static void
turn_figure(struct fx *f, double deg, double dx, double dz)
{
	struct xform rot, nx;
	xform_identity(&rot);
	mathx_rot_y(RAD(deg), rot.r);
	rot.p[0] = dx, rot.p[2] = dz;
	xform_mul(&rot, &f->s->root_xf, &nx);
	f->s->root_xf = nx;
	kin_update(f->m, f->s);
}

static void
reroot(struct fx *f, const char *site)
{
	assert_int_equal(kin_set_root(f->m, f->s, test_site(f->m, site)), 0);
	kin_update(f->m, f->s);
}

static const char *const shoulder[2] = { "shoulder_l", "shoulder_r" };

/* the built posture reads neutral everywhere */
static void
test_standing_reads_neutral(void **st)
{
	struct fx *f = *st;
	struct body_angles a = measure(f);
	for (size_t i = 0; i < body_angle_count; i++)
		if (!strcmp(body_angle_names[i].unit, "deg") &&
		    strcmp(body_angle_names[i].name, "hip_trunk_angle"))
			assert_near(body_angle_value(&a, i), 0, EXACT);
	assert_near(a.hip_trunk_angle, 180, EXACT);
	for (int side = 0; side < 2; side++) {
		assert_true(a.leg[side].foot_on_floor);
		assert_false(a.leg[side].kneeling);
		assert_near(a.arm[side].wrist_twist_fraction, 0, EXACT);
	}
	assert_int_equal(a.legs_on_floor, 2);
	assert_int_equal(a.seated, 0);
}

static void
test_upper_arm_in_one_plane_reads_the_joint(void **st)
{
	struct fx *f = *st;
	for (int side = 0; side < 2; side++) {
		set_deg(f, shoulder[side], HUMAN_DOF_FLEX, 50);
		set_deg(f, shoulder[side], HUMAN_DOF_ABD, 0);
	}
	struct body_angles a = measure(f);
	for (int side = 0; side < 2; side++) {
		assert_near(a.arm[side].upper_arm_flexion, 50, EXACT);
		assert_near(a.arm[side].upper_arm_abduction, 0, EXACT);
		assert_near(a.arm[side].upper_arm_rotation, 0, EXACT);
	}
	/* extension reads negative */
	for (int side = 0; side < 2; side++)
		set_deg(f, shoulder[side], HUMAN_DOF_FLEX, -40);
	a = measure(f);
	for (int side = 0; side < 2; side++)
		assert_near(a.arm[side].upper_arm_flexion, -40, EXACT);
	for (int side = 0; side < 2; side++) {
		set_deg(f, shoulder[side], HUMAN_DOF_FLEX, 0);
		set_deg(f, shoulder[side], HUMAN_DOF_ABD, 30);
	}
	a = measure(f);
	for (int side = 0; side < 2; side++) {
		assert_near(a.arm[side].upper_arm_flexion, 0, EXACT);
		assert_near(a.arm[side].upper_arm_abduction, 30, EXACT);
	}
}

/*
 * 50 deg flexion and 30 deg abduction as the swing's components: the arm
 * turned from hanging by the rotation vector 50 deg about -x plus 30 deg
 * about +z, its direction then given to the shoulder's flexion and
 * abduction dofs (abduction asin(u_x), flexion atan2(u_z, -u_y))
 */
static void
test_upper_arm_flexion_and_abduction(void **st)
{
	struct fx *f = *st;
	double w[3] = { -RAD(50), 0, RAD(30) }, e = sqrt(w[0] * w[0] + w[2] * w[2]);
	double axis[3] = { w[0] / e, 0, w[2] / e }, qt[4], r[9], u[3];
	const double down[3] = { 0, -1, 0 };
	mathx_quat_axis_angle(axis, e, qt);
	mathx_quat_to_mat(qt, r);
	for (int i = 0; i < 3; i++)
		u[i] = r[3 * i] * down[0] + r[3 * i + 1] * down[1] + r[3 * i + 2] * down[2];
	for (int side = 0; side < 2; side++) {
		*dof(f, shoulder[side], HUMAN_DOF_FLEX) = atan2(u[2], -u[1]);
		*dof(f, shoulder[side], HUMAN_DOF_ABD) = asin(u[0]);
	}
	struct body_angles a = measure(f);
	for (int side = 0; side < 2; side++) {
		assert_near(a.arm[side].upper_arm_flexion, 50, 1e-6);
		assert_near(a.arm[side].upper_arm_abduction, 30, 1e-6);
	}
	/*
	 * the joint at flexion 50 then abduction 30: the arm's direction is
	 * (sin 30, -cos 30 cos 50, cos 30 sin 50), its elevation from hanging
	 * acos(cos 30 cos 50) = 56.2 deg in the plane atan2(cos 30 sin 50, sin 30)
	 * = 53.0 deg from the coronal: flexion e sin p, abduction e cos p
	 */
	for (int side = 0; side < 2; side++) {
		set_deg(f, shoulder[side], HUMAN_DOF_FLEX, 50);
		set_deg(f, shoulder[side], HUMAN_DOF_ABD, 30);
	}
	double el = acos(cos(RAD(30)) * cos(RAD(50)));
	double pl = atan2(cos(RAD(30)) * sin(RAD(50)), sin(RAD(30)));
	a = measure(f);
	for (int side = 0; side < 2; side++) {
		assert_near(a.arm[side].upper_arm_flexion, DEGS(el * sin(pl)), 1e-6);
		assert_near(a.arm[side].upper_arm_abduction, DEGS(el * cos(pl)), 1e-6);
	}
}

/* raising the arm sideways through the horizontal: no jump in either reading */
static void
test_arm_through_90_abduction_is_continuous(void **st)
{
	struct fx *f = *st;
	static const double flex[] = { 0, 10, -10, 2 };
	for (size_t k = 0; k < sizeof flex / sizeof flex[0]; k++) {
		double prev_f = NAN, prev_a = NAN;
		for (double abd = 80; abd <= 100 + 1e-9; abd += 0.1) {
			for (int side = 0; side < 2; side++) {
				set_deg(f, shoulder[side], HUMAN_DOF_FLEX, flex[k]);
				set_deg(f, shoulder[side], HUMAN_DOF_ABD, abd);
			}
			struct body_angles a = measure(f);
			for (int side = 0; side < 2; side++) {
				const struct body_arm *b = &a.arm[side];
				if (!isnan(prev_f)) {
					assert_true(fabs(b->upper_arm_flexion - prev_f) < 0.2);
					assert_true(fabs(b->upper_arm_abduction - prev_a) < 0.2);
				}
				assert_near(a.arm[side].upper_arm_flexion, a.arm[0].upper_arm_flexion, EXACT);
			}
			prev_f = a.arm[0].upper_arm_flexion;
			prev_a = a.arm[0].upper_arm_abduction;
		}
	}
	/* exactly sideways: abducted 90, not flexed */
	for (int side = 0; side < 2; side++) {
		set_deg(f, shoulder[side], HUMAN_DOF_FLEX, 0);
		set_deg(f, shoulder[side], HUMAN_DOF_ABD, 90);
	}
	struct body_angles a = measure(f);
	assert_near(a.arm[0].upper_arm_flexion, 0, EXACT);
	assert_near(a.arm[0].upper_arm_abduction, 90, EXACT);
}

/* axial rotation after a flexion in the sagittal plane is the swing's exact remainder */
static void
test_upper_arm_rotation(void **st)
{
	struct fx *f = *st;
	for (int side = 0; side < 2; side++)
		set_deg(f, shoulder[side], HUMAN_DOF_ROT, 30);
	struct body_angles a = measure(f);
	for (int side = 0; side < 2; side++)
		assert_near(a.arm[side].upper_arm_rotation, 30, EXACT);
	for (int side = 0; side < 2; side++) {
		set_deg(f, shoulder[side], HUMAN_DOF_FLEX, 50);
		set_deg(f, shoulder[side], HUMAN_DOF_ROT, -25);
	}
	a = measure(f);
	for (int side = 0; side < 2; side++) {
		assert_near(a.arm[side].upper_arm_rotation, -25, EXACT);
		assert_near(a.arm[side].upper_arm_flexion, 50, EXACT);
	}
}

static void
test_shoulder_elevation_is_the_clavicles(void **st)
{
	struct fx *f = *st;
	static const char *const clav[2] = { "clavicle_l", "clavicle_r" };
	for (int side = 0; side < 2; side++) {
		set_deg(f, clav[side], HUMAN_DOF_CLAV_ELEVATE, 20);
		set_deg(f, clav[side], HUMAN_DOF_CLAV_PROTRACT, 15);
	}
	struct body_angles a = measure(f);
	for (int side = 0; side < 2; side++)
		assert_near(a.arm[side].shoulder_elevation, 20, EXACT);
	set_deg(f, clav[1], HUMAN_DOF_CLAV_ELEVATE, -8);
	a = measure(f);
	assert_near(a.arm[1].shoulder_elevation, -8, EXACT);
	/* one shoulder brought forward (reaching) is no trunk twist: the thorax has not turned */
	set_deg(f, clav[0], HUMAN_DOF_CLAV_PROTRACT, 20);
	set_deg(f, clav[1], HUMAN_DOF_CLAV_PROTRACT, 0);
	a = measure(f);
	assert_near(a.trunk_twist, 0, EXACT);
}

static void
test_elbow(void **st)
{
	struct fx *f = *st;
	static const char *const elbow[2] = { "elbow_l", "elbow_r" };
	for (int side = 0; side < 2; side++) {
		set_deg(f, elbow[side], 0, 80);
		set_deg(f, shoulder[side], HUMAN_DOF_FLEX, 40);
		set_deg(f, shoulder[side], HUMAN_DOF_ABD, 20);
	}
	struct body_angles a = measure(f);
	for (int side = 0; side < 2; side++)
		assert_near(a.arm[side].elbow_flexion, 80, EXACT);
}

static void
test_wrist(void **st)
{
	struct fx *f = *st;
	static const char *const wr[2] = { "wrist_l", "wrist_r" };
	/* 20 deg extension and 10 deg ulnar deviation */
	for (int side = 0; side < 2; side++) {
		set_deg(f, wr[side], HUMAN_DOF_FLEX, -20);
		set_deg(f, wr[side], HUMAN_DOF_ABD, -10);
	}
	struct body_angles a = measure(f);
	for (int side = 0; side < 2; side++) {
		assert_near(a.arm[side].wrist_flexion, -20, EXACT);
		assert_near(a.arm[side].wrist_deviation, -10, EXACT);
		assert_near(a.arm[side].wrist_twist, 0, EXACT);
	}
	/* pronation 40 of the 80 the joint allows; supination 60 of 80 */
	for (int side = 0; side < 2; side++) {
		set_deg(f, wr[side], HUMAN_DOF_FLEX, 0);
		set_deg(f, wr[side], HUMAN_DOF_ABD, 0);
	}
	set_deg(f, wr[0], HUMAN_DOF_ROT, 40);
	set_deg(f, wr[1], HUMAN_DOF_ROT, -60);
	a = measure(f);
	assert_near(a.arm[0].wrist_twist, 40, EXACT);
	assert_near(a.arm[0].wrist_twist_fraction, 0.5, 1e-12);
	assert_near(a.arm[1].wrist_twist, -60, EXACT);
	assert_near(a.arm[1].wrist_twist_fraction, 0.75, 1e-12);
	/*
	 * pronated 90 (palm backwards, thumb towards the body), the joint's
	 * flexion dof (applied about the forearm's axis, before the pronation
	 * in the human's order) tips the hand towards the thumb: anatomically a
	 * radial deviation of 20 with no flexion
	 */
	for (int side = 0; side < 2; side++) {
		set_deg(f, wr[side], HUMAN_DOF_ROT, 90);
		set_deg(f, wr[side], HUMAN_DOF_FLEX, 20);
	}
	a = measure(f);
	for (int side = 0; side < 2; side++) {
		assert_near(a.arm[side].wrist_flexion, 0, EXACT);
		assert_near(a.arm[side].wrist_deviation, 20, EXACT);
		assert_near(a.arm[side].wrist_twist, 90, EXACT);
	}
}

static void
test_neck_relative_to_the_thorax(void **st)
{
	struct fx *f = *st;
	set_deg(f, "spine_17", HUMAN_DOF_FLEX, 15);
	set_deg(f, "spine_17", HUMAN_DOF_ROT, 20);
	struct body_angles a = measure(f);
	assert_near(a.neck_flexion, 15, EXACT);
	assert_near(a.neck_twist, 20, EXACT);
	assert_near(a.neck_side_bend, 0, EXACT);
	/* the trunk bending below leaves the neck's reading alone */
	set_deg(f, "spine_5", HUMAN_DOF_FLEX, 25);
	set_deg(f, "spine_9", HUMAN_DOF_ABD, 7);
	a = measure(f);
	assert_near(a.neck_flexion, 15, EXACT);
	assert_near(a.neck_twist, 20, EXACT);
	set_deg(f, "spine_17", HUMAN_DOF_FLEX, -10);
	set_deg(f, "spine_17", HUMAN_DOF_ABD, 12);
	set_deg(f, "spine_17", HUMAN_DOF_ROT, -30);
	a = measure(f);
	assert_near(a.neck_flexion, -10, EXACT);
	assert_near(a.neck_side_bend, 12, EXACT);
	assert_near(a.neck_twist, -30, EXACT);
}

/*
 * All the bend at L5/S1, the trunk axis's foot: the axis turns rigidly
 * from vertical to (sin b, cos b cos f, cos b sin f), flexion f in the
 * sagittal plane and side bend b out of it, untwisted
 */
static void
test_trunk_bent_at_its_base(void **st)
{
	struct fx *f = *st;
	set_deg(f, "spine_0", HUMAN_DOF_FLEX, 30);
	set_deg(f, "spine_0", HUMAN_DOF_ABD, 10);
	struct body_angles a = measure(f);
	assert_near(a.trunk_flexion, 30, EXACT);
	assert_near(a.trunk_side_bend, 10, EXACT);
	assert_near(a.trunk_twist, 0, EXACT);
	/* against the thighs, still vertical: 180 less the axis's angle from vertical */
	assert_near(a.hip_trunk_angle, 180 - DEGS(acos(cos(RAD(10)) * cos(RAD(30)))), EXACT);
	set_deg(f, "spine_0", HUMAN_DOF_ROT, 30);
	set_deg(f, "spine_0", HUMAN_DOF_FLEX, 0);
	set_deg(f, "spine_0", HUMAN_DOF_ABD, 0);
	a = measure(f);
	assert_near(a.trunk_twist, 30, EXACT);
	assert_near(a.trunk_flexion, 0, EXACT);
}

/* rest positions of the 18 spine joints (L5/S1 .. C7/T1) */
static void
spine_rest(struct fx *f, double p[SPINE_NJNT][3])
{
	for (int k = 0; k < SPINE_NJNT; k++) {
		char name[24];
		snprintf(name, sizeof name, "spine_%d", k);
		int j = model_find_joint(f->m, name);
		assert_true(j >= 0);
		memcpy(p[k], f->s->site_xf[f->m->jnt_site_from[j]].p, sizeof p[k]);
	}
}

/*
 * Flexion spread over the lower spine ("bend from waist", 30 deg in all):
 * the chord from L5/S1 to C7/T1 of the planar chain whose link k (joint k
 * to k + 1, rest geometry) is turned by the flexion of joints 0 .. k. A
 * curved spine's chord turns by less than the joints' sum.
 */
static void
test_trunk_flexion_spread_over_the_spine(void **st)
{
	struct fx *f = *st;
	double p[SPINE_NJNT][3], total[3] = { RAD(30), 0, 0 }, sf[3];
	spine_rest(f, p);
	struct spine_flavor waist = spine_bend_from_waist();
	assert_int_equal(spine_apply(f->m, f->s, &waist, total, sf), 0);
	double phi = 0, cy = 0, cz = 0;
	for (int k = 0; k + 1 < SPINE_NJNT; k++) {
		char name[24];
		snprintf(name, sizeof name, "spine_%d", k);
		phi += *dof(f, name, HUMAN_DOF_FLEX);
		double dy = p[k + 1][1] - p[k][1], dz = p[k + 1][2] - p[k][2];
		cy += dy * cos(phi) - dz * sin(phi);
		cz += dy * sin(phi) + dz * cos(phi);
	}
	double want = DEGS(atan2(cz, cy));
	assert_true(fabs(want - 30) > 0.5); /* the chord, not the dofs' sum */
	struct body_angles a = measure(f);
	assert_near(a.trunk_flexion, want, 1e-9);
	assert_near(a.trunk_side_bend, 0, EXACT);

	/* side bend alone, spread the same way: the chord in the coronal plane */
	double lat[3] = { 0, RAD(10), 0 };
	assert_int_equal(spine_apply(f->m, f->s, &waist, lat, sf), 0);
	phi = 0;
	double cx = 0;
	cy = 0;
	for (int k = 0; k + 1 < SPINE_NJNT; k++) {
		char name[24];
		snprintf(name, sizeof name, "spine_%d", k);
		phi += *dof(f, name, HUMAN_DOF_ABD); /* + left: about -z, y turns towards +x */
		double dx = p[k + 1][0] - p[k][0], dy = p[k + 1][1] - p[k][1];
		cx += dx * cos(phi) + dy * sin(phi);
		cy += -dx * sin(phi) + dy * cos(phi);
	}
	a = measure(f);
	assert_near(a.trunk_side_bend, DEGS(atan2(cx, cy)), 1e-9);
	assert_near(a.trunk_flexion, 0, 1e-9);

	/* twist spread over the same joints: their sum, to second order in the chord's small lean */
	double ax[3] = { 0, 0, RAD(30) };
	assert_int_equal(spine_apply(f->m, f->s, &waist, ax, sf), 0);
	a = measure(f);
	assert_near(a.trunk_twist, 30, 0.05);
}

/* the chord's direction (L5/S1 to C7/T1) in the world */
static void
chord(struct fx *f, double dest[3])
{
	kin_update(f->m, f->s);
	const double *b = at(f, "pelvis.spine_0"), *t = at(f, "T1.spine_17");
	double n = 0;
	for (int i = 0; i < 3; i++) {
		dest[i] = t[i] - b[i];
		n += dest[i] * dest[i];
	}
	for (int i = 0; i < 3; i++)
		dest[i] /= sqrt(n);
}

/*
 * 30 deg flexion with 10 deg side bend, both spread over the lower spine:
 * the totals found (Newton's method on the chord's x and z) that point the
 * chord along (sin 10, cos 10 cos 30, cos 10 sin 30) with the figure
 * facing +z; then the figure turned about the vertical and re-rooted at a
 * foot must read 30 and 10
 */
static void
test_trunk_flexion_with_side_bend_spread(void **st)
{
	struct fx *f = *st;
	double want[3] = { sin(RAD(10)), cos(RAD(10)) * cos(RAD(30)), cos(RAD(10)) * sin(RAD(30)) };
	struct spine_flavor waist = spine_bend_from_waist();
	double tot[3] = { RAD(30), RAD(10), 0 }, c[3], sf[3];
	for (int it = 0; it < 30; it++) {
		assert_int_equal(spine_apply(f->m, f->s, &waist, tot, sf), 0);
		chord(f, c);
		double r[2] = { c[0] - want[0], c[2] - want[2] }, jac[2][2];
		if (fabs(r[0]) + fabs(r[1]) < 1e-14)
			break;
		for (int k = 0; k < 2; k++) {
			double t2[3] = { tot[0], tot[1], 0 }, c2[3];
			t2[k == 0 ? 0 : 1] += 1e-7;
			assert_int_equal(spine_apply(f->m, f->s, &waist, t2, sf), 0);
			chord(f, c2);
			jac[0][k] = (c2[0] - c[0]) / 1e-7;
			jac[1][k] = (c2[2] - c[2]) / 1e-7;
		}
		double det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
		tot[0] -= (jac[1][1] * r[0] - jac[0][1] * r[1]) / det;
		tot[1] -= (-jac[1][0] * r[0] + jac[0][0] * r[1]) / det;
	}
	assert_int_equal(spine_apply(f->m, f->s, &waist, tot, sf), 0);
	chord(f, c);
	assert_near(c[0], want[0], 1e-12);
	assert_near(c[2], want[2], 1e-12);
	turn_figure(f, 35, 1.2, -0.7);
	reroot(f, "foot_l.balance");
	struct body_angles a = measure(f);
	assert_near(a.trunk_flexion, 30, 1e-6);
	assert_near(a.trunk_side_bend, 10, 1e-6);
}

/* the hands against the shoulders and the body's midline, from the rest geometry */
static void
test_hand_places(void **st)
{
	struct fx *f = *st;
	/* the palm lies on the hanging arm's axis: its distance from the shoulder joint */
	const double *gh0 = at(f, "upperarm_l.origin"), *pm0 = at(f, "hand_l.palm");
	double len = gh0[1] - pm0[1], ghx = gh0[0];
	assert_near(pm0[0], gh0[0], EXACT);
	/* arms forward, horizontal */
	for (int side = 0; side < 2; side++)
		set_deg(f, shoulder[side], HUMAN_DOF_FLEX, 90);
	struct body_angles a = measure(f);
	for (int side = 0; side < 2; side++) {
		assert_near(a.arm[side].elbow_above_shoulder, 0, EXACT);
		assert_near(a.arm[side].hand_above_shoulder, 0, EXACT);
		assert_near(a.arm[side].hand_out_to_side, 0, EXACT);
		assert_near(a.arm[side].hand_across_midline, -ghx, EXACT);
	}
	/* sideways, horizontal: the palm the arm's length outside the shoulder */
	for (int side = 0; side < 2; side++) {
		set_deg(f, shoulder[side], HUMAN_DOF_FLEX, 0);
		set_deg(f, shoulder[side], HUMAN_DOF_ABD, 90);
	}
	a = measure(f);
	for (int side = 0; side < 2; side++) {
		assert_near(a.arm[side].hand_out_to_side, len, EXACT);
		assert_near(a.arm[side].elbow_above_shoulder, 0, EXACT);
	}
	/* forward and 30 deg across: the palm len sin 30 towards the midline from the shoulder */
	for (int side = 0; side < 2; side++) {
		set_deg(f, shoulder[side], HUMAN_DOF_FLEX, 90);
		set_deg(f, shoulder[side], HUMAN_DOF_ABD, -30);
	}
	a = measure(f);
	for (int side = 0; side < 2; side++) {
		assert_near(a.arm[side].hand_across_midline, len * 0.5 - ghx, EXACT);
		assert_near(a.arm[side].hand_out_to_side, -len * 0.5, EXACT);
	}
	/* overhead */
	for (int side = 0; side < 2; side++) {
		set_deg(f, shoulder[side], HUMAN_DOF_FLEX, 180);
		set_deg(f, shoulder[side], HUMAN_DOF_ABD, 0);
	}
	a = measure(f);
	for (int side = 0; side < 2; side++) {
		assert_near(a.arm[side].hand_above_shoulder, len, EXACT);
		assert_near(a.arm[side].upper_arm_flexion, 180, EXACT);
	}
}

static void
test_legs(void **st)
{
	struct fx *f = *st;
	static const char *const knee[2] = { "knee_l", "knee_r" }, *const hip[2] = { "hip_l", "hip_r" };
	for (int side = 0; side < 2; side++) {
		set_deg(f, knee[side], 0, 45);
		set_deg(f, hip[side], HUMAN_DOF_FLEX, 30);
	}
	struct body_angles a = measure(f);
	for (int side = 0; side < 2; side++) {
		assert_near(a.leg[side].knee_flexion, 45, EXACT);
		assert_near(a.leg[side].hip_flexion, 30, EXACT);
	}
	assert_near(a.hip_trunk_angle, 150, EXACT);
	/* sitting upright: thighs forward, horizontal */
	for (int side = 0; side < 2; side++) {
		set_deg(f, knee[side], 0, 90);
		set_deg(f, hip[side], HUMAN_DOF_FLEX, 90);
	}
	a = measure(f);
	assert_near(a.hip_trunk_angle, 90, EXACT);
	/* kneeling: thighs down, shanks back, the knee's front brought to 2 cm above the floor */
	for (int side = 0; side < 2; side++)
		set_deg(f, hip[side], HUMAN_DOF_FLEX, 0);
	kin_update(f->m, f->s);
	double drop = at(f, "thigh_l.knee_front")[1] - 0.02;
	f->s->root_xf.p[1] -= drop;
	a = measure_kneel(f, 0.05);
	assert_true(a.leg[0].kneeling && a.leg[1].kneeling);
	a = measure_kneel(f, 0.015);
	assert_false(a.leg[0].kneeling || a.leg[1].kneeling);
}

/*
 * the share over each foot from the centre of mass between the feet's
 * balance sites (side by side, so the share is the lever ratio along x)
 */
static void
test_weight_share(void **st)
{
	struct fx *f = *st;
	double total[3] = { 0, RAD(20), 0 }, sf[3];
	struct spine_flavor waist = spine_bend_from_waist();
	assert_int_equal(spine_apply(f->m, f->s, &waist, total, sf), 0);
	struct body_angles a = measure(f);
	const double *l = at(f, "foot_l.balance"), *r = at(f, "foot_r.balance");
	assert_near(l[2], r[2], EXACT);
	double want = (f->s->com[0] - r[0]) / (l[0] - r[0]);
	assert_true(want > 0.55);
	assert_near(a.leg[0].weight_share, want, 1e-12);
	assert_near(a.leg[1].weight_share, 1 - want, 1e-12);
	struct balance b;
	assert_int_equal(balance_measure(f->m, f->s, BALANCE_CONTACT, &b), 0);
	assert_near(a.leg[0].weight_share, b.weight_l, 1e-12);
	/* the right foot lifted: all the weight on the left */
	set_deg(f, "hip_r", HUMAN_DOF_FLEX, 40);
	a = measure(f);
	assert_false(a.leg[1].foot_on_floor);
	assert_true(a.leg[0].foot_on_floor);
	assert_int_equal(a.legs_on_floor, 1);
	assert_near(a.leg[0].weight_share, 1, 0);
	assert_near(a.leg[1].weight_share, 0, 0);
}

/* a posture with every part moved, for the invariance test */
static void
busy_posture(struct fx *f)
{
	double total[3] = { RAD(25), RAD(-8), RAD(12) }, sf[3];
	struct spine_flavor waist = spine_bend_from_waist();
	assert_int_equal(spine_apply(f->m, f->s, &waist, total, sf), 0);
	set_deg(f, "spine_17", HUMAN_DOF_FLEX, 20);
	set_deg(f, "spine_17", HUMAN_DOF_ABD, -6);
	set_deg(f, "spine_17", HUMAN_DOF_ROT, 25);
	set_deg(f, "shoulder_l", HUMAN_DOF_FLEX, 70);
	set_deg(f, "shoulder_l", HUMAN_DOF_ABD, 25);
	set_deg(f, "shoulder_l", HUMAN_DOF_ROT, -15);
	set_deg(f, "shoulder_r", HUMAN_DOF_FLEX, -20);
	set_deg(f, "shoulder_r", HUMAN_DOF_ABD, 95);
	set_deg(f, "clavicle_r", HUMAN_DOF_CLAV_ELEVATE, 12);
	set_deg(f, "elbow_l", 0, 95);
	set_deg(f, "elbow_r", 0, 30);
	set_deg(f, "wrist_l", HUMAN_DOF_FLEX, 25);
	set_deg(f, "wrist_l", HUMAN_DOF_ABD, 8);
	set_deg(f, "wrist_l", HUMAN_DOF_ROT, 50);
	set_deg(f, "wrist_r", HUMAN_DOF_FLEX, -30);
	set_deg(f, "wrist_r", HUMAN_DOF_ROT, -70);
	set_deg(f, "hip_l", HUMAN_DOF_FLEX, 20);
	set_deg(f, "knee_l", 0, 35);
	set_deg(f, "hip_r", HUMAN_DOF_ABD, 10);
	kin_update(f->m, f->s);
}

/* turning the figure about the vertical, moving it and re-rooting it changes no reading */
static void
test_turned_and_rerooted_figure_reads_the_same(void **st)
{
	struct fx *f = *st;
	busy_posture(f);
	reroot(f, "foot_r.balance");
	struct body_angles a = measure(f), b;
	static const char *const roots[] = { "hand_r.palm", "head.between_eyes", "foot_l.balance" };
	for (size_t k = 0; k < sizeof roots / sizeof roots[0]; k++) {
		turn_figure(f, 70 + 100 * (double)k, 0.8, -1.5);
		reroot(f, roots[k]);
		b = measure(f);
		for (size_t i = 0; i < body_angle_count; i++)
			assert_near(body_angle_value(&b, i), body_angle_value(&a, i), 1e-9);
	}
}

/*
 * NIOSH: the arms held straight forward. The medial malleoli, the lateral
 * ones reflected through the ankle centres, have their midpoint where the
 * ankle centres have theirs (the feet side by side); the palms lie an
 * arm's length (shoulder to palm) in front of the shoulders.
 */
static void
test_niosh_geometry(void **st)
{
	struct fx *f = *st;
	char err[256];
	const double *gh = at(f, "upperarm_l.origin"), *pm = at(f, "hand_l.palm");
	const double *ank = at(f, "foot_l.origin"), *t1 = at(f, "T1.origin");
	double len = gh[1] - pm[1], ghy = gh[1], ghz = gh[2], az = ank[2], ay = ank[1], tz = t1[2];
	for (int side = 0; side < 2; side++)
		set_deg(f, shoulder[side], HUMAN_DOF_FLEX, 90);
	kin_update(f->m, f->s);
	struct niosh_geometry g;
	assert_int_equal(niosh_measure(f->m, f->s, &g, err, sizeof err), 0);
	assert_near(g.ankles_mid[0], 0, EXACT);
	assert_near(g.ankles_mid[1], ay, EXACT);
	assert_near(g.ankles_mid[2], az, EXACT);
	assert_near(g.h_cm, 100 * (ghz + len - az), 1e-7);
	assert_near(g.v_cm, 100 * ghy, 1e-7);
	assert_near(g.a_deg, 0, 1e-7);
	assert_near(g.h_in, g.h_cm / 2.54, 1e-12);
	assert_near(g.v_in, g.v_cm / 2.54, 1e-12);

	/*
	 * the left foot turned 20 deg out (about its ankle, which the shank's
	 * malleoli do not follow): the feet's bisector turns 10 deg to the
	 * left while the asymmetry line stays straight ahead
	 */
	set_deg(f, "ankle_l", HUMAN_DOF_ROT, -20);
	kin_update(f->m, f->s);
	assert_int_equal(niosh_measure(f->m, f->s, &g, err, sizeof err), 0);
	assert_near(g.a_deg, 10, 1e-7);
	assert_near(g.forward[0], sin(RAD(10)), 1e-12);
	set_deg(f, "ankle_l", HUMAN_DOF_ROT, 0);

	/* the thorax turned 30 deg left at T1/T2: the hands swing about T1's vertical axis */
	set_deg(f, "spine_16", HUMAN_DOF_ROT, 30);
	kin_update(f->m, f->s);
	assert_int_equal(niosh_measure(f->m, f->s, &g, err, sizeof err), 0);
	double rr = ghz + len - tz, hx = rr * sin(RAD(30)), hz = tz + rr * cos(RAD(30));
	assert_near(g.h_cm, 100 * sqrt(hx * hx + (hz - az) * (hz - az)), 1e-7);
	assert_near(g.a_deg, DEGS(atan2(hx, hz - az)), 1e-7);
	assert_near(g.v_cm, 100 * ghy, 1e-7);
	struct niosh_geometry before = g;

	/* the whole figure turned and moved: nothing changes */
	turn_figure(f, -50, 2.0, 0.3);
	reroot(f, "foot_l.balance");
	assert_int_equal(niosh_measure(f->m, f->s, &g, err, sizeof err), 0);
	assert_near(g.h_cm, before.h_cm, 1e-7);
	assert_near(g.v_cm, before.v_cm, 1e-7);
	assert_near(g.a_deg, before.a_deg, 1e-7);

	/*
	 * the left leg turned 30 deg inwards at the hip, about the vertical
	 * through the hip centre: its medial malleolus (lateral reflected
	 * through the ankle centre, both at rest) swings with it
	 */
	state_reset(f->m, f->s);
	kin_update(f->m, f->s);
	double hip[3], mal[2][3];
	memcpy(hip, at(f, "thigh_l.origin"), sizeof hip);
	for (int side = 0; side < 2; side++) {
		const double *c = at(f, side ? "foot_r.origin" : "foot_l.origin");
		const double *lat = at(f, side ? "shank_r.lateral_malleolus" : "shank_l.lateral_malleolus");
		for (int i = 0; i < 3; i++)
			mal[side][i] = 2 * c[i] - lat[i];
	}
	double dx = mal[0][0] - hip[0], dz = mal[0][2] - hip[2], th = RAD(30);
	mal[0][0] = hip[0] + dx * cos(th) - dz * sin(th);
	mal[0][2] = hip[2] + dx * sin(th) + dz * cos(th);
	set_deg(f, "hip_l", HUMAN_DOF_ROT, 30);
	kin_update(f->m, f->s);
	assert_int_equal(niosh_measure(f->m, f->s, &g, err, sizeof err), 0);
	for (int i = 0; i < 3; i++)
		assert_near(g.ankles_mid[i], (mal[0][i] + mal[1][i]) / 2, 1e-12);

	/* D between two postures */
	struct niosh_geometry lo = before, hi = before;
	lo.v_cm = 20, hi.v_cm = 95;
	assert_near(niosh_travel_cm(&lo, &hi), 75, 0);
	assert_near(niosh_travel_cm(&hi, &lo), 75, 0);
}

static void
test_names(void **st)
{
	struct fx *f = *st;
	set_deg(f, "shoulder_r", HUMAN_DOF_FLEX, 33);
	set_deg(f, "knee_l", 0, 12);
	struct body_angles a = measure(f);
	for (size_t i = 0; i < body_angle_count; i++) {
		const struct body_angle_name *n = &body_angle_names[i];
		assert_int_equal(body_angle_find(n->name), (int)i);
		assert_true(!strcmp(n->unit, "deg") || !strcmp(n->unit, "m") ||
			    !strcmp(n->unit, "fraction") || !strcmp(n->unit, "flag") ||
			    !strcmp(n->unit, "count"));
		assert_true(n->what && strlen(n->what) > 10);
	}
	assert_near(body_angle_value(&a, (size_t)body_angle_find("upper_arm_flexion_r")), 33, EXACT);
	assert_near(body_angle_value(&a, (size_t)body_angle_find("upper_arm_flexion_l")), 0, EXACT);
	assert_near(body_angle_value(&a, (size_t)body_angle_find("knee_flexion_l")), 12, EXACT);
	assert_near(body_angle_value(&a, (size_t)body_angle_find("legs_on_floor")), 2, 0);
	assert_near(body_angle_value(&a, (size_t)body_angle_find("foot_on_floor_r")), 1, 0);
	assert_near(body_angle_value(&a, (size_t)body_angle_find("trunk_flexion")), a.trunk_flexion, 0);
	assert_int_equal(body_angle_find("elbow"), -1);
	assert_true(isnan(body_angle_value(&a, body_angle_count)));
	/* every double and int of the struct is named once */
	assert_int_equal(body_angle_count, 7 + 2 * 13 + 2 * 5 + 2);
}

/* a figure that is not the human: an error, and nothing written */
static void
test_not_a_human(void **st)
{
	(void)st;
	struct model_builder *mb = model_builder_create("box");
	struct segment_def sd = segment_default_def();
	sd.name = "box";
	sd.mass = 1;
	int seg = model_builder_segment(mb, &sd);
	double p[3] = { 0, 0, 0 }, q[4] = { 0, 0, 0, 1 };
	int site = model_builder_site(mb, seg, "root", p, q);
	assert_int_equal(model_builder_root(mb, site, p, q), 0);
	struct model *m = model_builder_finish(mb);
	assert_non_null(m);
	model_builder_free(mb);
	struct state *s = state_make(m);
	kin_update(m, s);
	char err[256] = "";
	struct body_angles a, keep;
	memset(&a, 0x5a, sizeof a);
	keep = a;
	assert_int_equal(body_angles_measure(m, s, 0, 0.05, &a, err, sizeof err), -1);
	assert_non_null(strstr(err, "human"));
	assert_memory_equal(&a, &keep, sizeof a);
	struct niosh_geometry g, gkeep;
	memset(&g, 0x5a, sizeof g);
	gkeep = g;
	err[0] = 0;
	assert_int_equal(niosh_measure(m, s, &g, err, sizeof err), -1);
	assert_non_null(strstr(err, "human"));
	assert_memory_equal(&g, &gkeep, sizeof g);
	state_free(s);
	model_free(m);
}

/* a posture that is not finite: an error naming the first angle it spoils, nothing written */
static void
test_non_finite_posture(void **st)
{
	struct fx *f = *st;
	*dof(f, "elbow_r", 0) = NAN;
	kin_update(f->m, f->s);
	char err[256] = "";
	struct body_angles a, keep;
	memset(&a, 0x5a, sizeof a);
	keep = a;
	assert_int_equal(body_angles_measure(f->m, f->s, 0, 0.05, &a, err, sizeof err), -1);
	assert_non_null(strstr(err, "elbow_flexion_r is not finite"));
	assert_memory_equal(&a, &keep, sizeof a);
}

static void
test_measuring_allocates_nothing(void **st)
{
#if COUNT_ALLOCS
	struct fx *f = *st;
	busy_posture(f);
	char err[256];
	struct body_angles a;
	struct niosh_geometry g;
	long before = allocs;
	for (int i = 0; i < 10; i++) {
		assert_int_equal(body_angles_measure(f->m, f->s, 1, 0.05, &a, err, sizeof err), 0);
		assert_int_equal(niosh_measure(f->m, f->s, &g, err, sizeof err), 0);
	}
	assert_int_equal(allocs, before);
	assert_int_equal(a.seated, 1);
#else
	(void)st;
	skip();
#endif
}

int
main(void)
{
#define T(t) cmocka_unit_test_setup_teardown(t, setup, teardown)
	const struct CMUnitTest tests[] = {
		T(test_standing_reads_neutral),
		T(test_upper_arm_in_one_plane_reads_the_joint),
		T(test_upper_arm_flexion_and_abduction),
		T(test_arm_through_90_abduction_is_continuous),
		T(test_upper_arm_rotation),
		T(test_shoulder_elevation_is_the_clavicles),
		T(test_elbow),
		T(test_wrist),
		T(test_neck_relative_to_the_thorax),
		T(test_trunk_bent_at_its_base),
		T(test_trunk_flexion_spread_over_the_spine),
		T(test_trunk_flexion_with_side_bend_spread),
		T(test_hand_places),
		T(test_legs),
		T(test_weight_share),
		T(test_turned_and_rerooted_figure_reads_the_same),
		T(test_niosh_geometry),
		T(test_names),
		cmocka_unit_test(test_not_a_human),
		T(test_non_finite_posture),
		T(test_measuring_allocates_nothing),
	};
#undef T
	return cmocka_run_group_tests(tests, NULL, NULL);
}
