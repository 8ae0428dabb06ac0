/* test_human.c - the standard human figure: structure, anthropometry, balance, symmetry */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/human.h"
#include "figure/kin.h"
#include "figure/model.h"
#include "figure/state.h"

static const double DEG = M_PI / 180;

static struct model *
build(double stature, double mass, enum human_sex sex)
{
	struct human_def d = { .stature = stature, .mass = mass, .sex = sex };
	char err[256] = "";
	struct model *m = human_build(&d, err, sizeof err);
	if (!m)
		fail_msg("human_build(%g, %g): %s", stature, mass, err);
	return m;
}

static int
site(const struct model *m, const char *name)
{
	int s = model_find_site(m, name);
	if (s < 0)
		fail_msg("no site %s", name);
	return s;
}

static int
joint(const struct model *m, const char *name)
{
	int j = model_find_joint(m, name);
	if (j < 0)
		fail_msg("no joint %s", name);
	return j;
}

static const double *
site_pos(const struct model *m, const struct state *s, const char *name)
{
	return s->site_xf[site(m, name)].p;
}

/* lowest and highest world y of one geom */
static void
geom_y_range(const struct model *m, const struct state *s, int g, double *lo, double *hi)
{
	const struct xform *sx = &s->seg_xf[m->geom_seg[g]];
	double gr[9], W[9], c[3];
	mathx_quat_to_mat(&m->geom_quat[4 * g], gr);
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			W[3 * i + j] = sx->r[3 * i] * gr[j] + sx->r[3 * i + 1] * gr[3 + j] +
				       sx->r[3 * i + 2] * gr[6 + j];
	xform_apply(sx, &m->geom_pos[3 * g], c);
	const double *sz = &m->geom_size[3 * g];
	double e = 0;
	switch ((enum geom_kind)m->geom_kind[g]) {
	case GEOM_BOX:
		for (int i = 0; i < 3; i++)
			e += fabs(W[3 + i]) * sz[i] / 2;
		break;
	case GEOM_ELLIPSOID:
		for (int i = 0; i < 3; i++)
			e += pow(W[3 + i] * sz[i], 2);
		e = sqrt(e);
		break;
	case GEOM_CAPSULE:
		e = fabs(W[4]) * sz[1] / 2 + sz[0];
		break;
	case GEOM_CYLINDER:
		e = fabs(W[4]) * sz[1] / 2 + sz[0] * sqrt(1 - W[4] * W[4]);
		break;
	case GEOM_MESH:
		fail_msg("the human has no meshes");
		break;
	}
	*lo = c[1] - e;
	*hi = c[1] + e;
}

static void
test_counts(void **unused)
{
	(void)unused;
	struct model *m = build(1.75, 75, HUMAN_MALE);
	assert_int_equal(m->nseg, 37);
	assert_int_equal(m->nseg, HUMAN_NSEG);
	assert_int_equal(m->njnt, HUMAN_NJNT);
	assert_int_equal(m->njnt, 36);
	assert_int_equal(m->ndof, HUMAN_NDOF);
	assert_int_equal(m->ndof, 92);
	/* the eyes' dofs come last; the body has 88 as §D.1.3 */
	int body = 0;
	for (int d = 0; d < m->ndof; d++)
		if (strncmp(m->jnt_name[m->dof_jnt[d]], "eye_", 4) != 0)
			body++;
	assert_int_equal(body, HUMAN_BODY_NDOF);
	assert_int_equal(body, 88);
	assert_int_equal(m->jnt_dof0[joint(m, "eye_l")], 88);
	char name[32];
	for (int k = 0; k < HUMAN_NSPINE; k++) {
		snprintf(name, sizeof name, "spine_%d", k);
		assert_int_equal(m->jnt_ndof[joint(m, name)], 3);
	}
	assert_int_equal(HUMAN_NSPINE, 18);
	static const struct {
		const char *name;
		int ndof;
	} limb[] = { { "hip", 3 }, { "knee", 1 }, { "ankle", 3 }, { "toe", 1 }, { "clavicle", 2 },
		     { "shoulder", 3 }, { "elbow", 1 }, { "wrist", 3 }, { "eye", 2 } };
	for (size_t i = 0; i < sizeof limb / sizeof limb[0]; i++)
		for (int s = 0; s < 2; s++) {
			snprintf(name, sizeof name, "%s_%c", limb[i].name, s ? 'r' : 'l');
			assert_int_equal(m->jnt_ndof[joint(m, name)], limb[i].ndof);
		}
	static const char *const segs[] = {
		"pelvis", "L5", "L4", "L3", "L2", "L1", "T12", "T11", "T10", "T9", "T8", "T7",
		"T6", "T5", "T4", "T3", "T2", "T1", "head", "eyeball_l", "eyeball_r", "thigh_l",
		"thigh_r", "shank_l", "shank_r", "foot_l", "foot_r", "toes_l", "toes_r",
		"clavicle_l", "clavicle_r", "upperarm_l", "upperarm_r", "forearm_l", "forearm_r",
		"hand_l", "hand_r",
	};
	for (size_t i = 0; i < sizeof segs / sizeof segs[0]; i++)
		assert_true(model_find_segment(m, segs[i]) >= 0);
	static const char *const sites[] = {
		"pelvis.root", "pelvis.lower_torso", "pelvis.center", "pelvis.hip_l", "pelvis.hip_r",
		HUMAN_SITE_CHEST, "foot_l.heel", "foot_l.ankle", "foot_l.balance", "toes_l.tip",
		"toes_l.toe", "shank_l.knee", "forearm_l.wrist_ref", "hand_l.palm",
		"hand_l.fingertip", "upperarm_l.elbow", "head.between_eyes", "eyeball_l.gaze",
		"foot_r.heel", "foot_r.ankle", "foot_r.balance", "toes_r.tip", "toes_r.toe",
		"shank_r.knee", "forearm_r.wrist_ref", "hand_r.palm", "hand_r.fingertip",
		"upperarm_r.elbow", "eyeball_r.gaze",
	};
	for (size_t i = 0; i < sizeof sites / sizeof sites[0]; i++)
		site(m, sites[i]);
	assert_int_equal(m->root_site, site(m, HUMAN_SITE_ROOT));
	/* the clavicles hang from the upper thoracic segment */
	int cl = joint(m, "clavicle_l");
	assert_string_equal(m->seg_name[m->site_seg[m->jnt_site_from[cl]]], "T1");
	/* every joint runs proximal -> distal onto the distal segment's origin */
	for (int j = 0; j < m->njnt; j++)
		assert_string_equal(m->site_name[m->jnt_site_to[j]], "origin");
	model_free(m);
}

/* mass, limits and height for a range of figures */
static void
test_mass_limits_extent(void **unused)
{
	(void)unused;
	struct human_def defs[4] = { human_default_def(HUMAN_MALE), human_default_def(HUMAN_FEMALE),
				     { .stature = 1.5, .mass = 50, .sex = HUMAN_FEMALE },
				     { .stature = 1.95, .mass = 110, .sex = HUMAN_MALE } };
	for (int f = 0; f < 4; f++) {
		struct model *m = build(defs[f].stature, defs[f].mass, defs[f].sex);
		struct state *s = state_make(m);
		kin_update(m, s);
		double sum = 0;
		for (int i = 0; i < m->nseg; i++) {
			assert_true(m->seg_mass[i] > 0);
			sum += m->seg_mass[i];
		}
		assert_near(sum, defs[f].mass, 1e-9);
		for (int d = 0; d < m->ndof; d++) {
			const char *jn = m->jnt_name[m->dof_jnt[d]];
			assert_near(m->dof_init[d], 0, 0);
			assert_true(m->dof_lo[d] <= 0 && m->dof_hi[d] >= 0);
			if (strncmp(jn, "knee", 4) == 0 || strncmp(jn, "elbow", 5) == 0) {
				/* 0 = full extension, a bound */
				assert_near(m->dof_lo[d], 0, 0);
				assert_true(m->dof_hi[d] > 120 * DEG);
			} else {
				assert_true(m->dof_lo[d] < 0 && m->dof_hi[d] > 0);
			}
		}
		double lo = 1e9, hi = -1e9, foot_lo = 1e9;
		for (int g = 0; g < m->ngeom; g++) {
			double a, b;
			geom_y_range(m, s, g, &a, &b);
			lo = fmin(lo, a);
			hi = fmax(hi, b);
			if (strncmp(m->seg_name[m->geom_seg[g]], "foot", 4) == 0)
				foot_lo = fmin(foot_lo, a);
		}
		assert_near(lo, 0, 1e-3);
		assert_near(foot_lo, 0, 1e-3);
		assert_near(hi, defs[f].stature, 1e-3);
		assert_near(site_pos(m, s, "head.vertex")[1], defs[f].stature, 1e-9);
		/* every segment has geometry */
		for (int i = 0; i < m->nseg; i++)
			assert_true(m->seg_ngeom[i] > 0);
		state_free(s);
		model_free(m);
	}
}

/* inertia tensors are physical: positive definite, triangle inequality */
static void
test_inertia(void **unused)
{
	(void)unused;
	struct model *m = build(1.75, 75, HUMAN_MALE);
	for (int i = 0; i < m->nseg; i++) {
		const double *I = &m->seg_inertia[6 * i];
		double a = I[0], b = I[1], c = I[2], xy = I[3], xz = I[4], yz = I[5];
		assert_true(a > 0);
		assert_true(a * b - xy * xy > 0);
		double det = a * (b * c - yz * yz) - xy * (xy * c - yz * xz) + xz * (xy * yz - b * xz);
		assert_true(det > 0);
		assert_true(a + b >= c * (1 - 1e-12) && a + c >= b * (1 - 1e-12) &&
			    b + c >= a * (1 - 1e-12));
	}
	/* the thigh's long axis is vertical: its smallest moment is about y */
	const double *It = &m->seg_inertia[6 * model_find_segment(m, "thigh_l")];
	assert_true(It[1] < It[0] && It[1] < It[2]);
	model_free(m);
}

static void
test_standing_balance(void **unused)
{
	(void)unused;
	struct model *m = build(1.75, 75, HUMAN_MALE);
	struct state *s = state_make(m);
	kin_update(m, s);
	const double *bl = site_pos(m, s, "foot_l.balance"), *br = site_pos(m, s, "foot_r.balance");
	double H = 1.75, ratio = s->com[1] / H;
	print_message("CoM height / stature %.4f\n", ratio);
	assert_true(ratio > 0.54 && ratio < 0.58);
	double mid[3] = { (bl[0] + br[0]) / 2, 0, (bl[2] + br[2]) / 2 };
	double off = hypot(s->com[0] - mid[0], s->com[2] - mid[2]);
	print_message("CoM horizontal offset from the balance line's midpoint %.3g m\n", off);
	assert_true(off < 0.02);
	for (int k = 0; k < 2; k++) {
		const double *b = site_pos(m, s, k ? "foot_r.balance" : "foot_l.balance");
		const double *a = site_pos(m, s, k ? "foot_r.ankle" : "foot_l.ankle");
		assert_near(b[1], 0, 1e-9);
		assert_near(b[0], a[0], 1e-9);
		assert_true(b[2] - a[2] >= 0.02 && b[2] - a[2] <= 0.05);
		/* heel and toes on the floor, heel behind the ankle, tip in front */
		const double *heel = site_pos(m, s, k ? "foot_r.heel" : "foot_l.heel");
		const double *tip = site_pos(m, s, k ? "toes_r.tip" : "toes_l.tip");
		assert_near(heel[1], 0, 1e-9);
		assert_near(tip[1], 0, 1e-9);
		assert_near(site_pos(m, s, k ? "toes_r.toe" : "toes_l.toe")[1], 0, 1e-9);
		assert_true(heel[2] < a[2] && tip[2] > b[2]);
		assert_near(tip[2] - heel[2], 0.152 * H, 1e-9);
	}
	/* the shanks lean forward a few degrees, the line of gravity in front of the knee */
	const double *knee = site_pos(m, s, "thigh_l.knee_l"), *ank = site_pos(m, s, "foot_l.ankle");
	double lean = atan2(knee[2] - ank[2], knee[1] - ank[1]) / DEG;
	print_message("shank lean %.2f deg\n", lean);
	assert_true(lean > 0 && lean < 8);
	assert_true(s->com[2] > knee[2]);
	/* the lower torso site sits at the standing centre of mass */
	const double *lt = site_pos(m, s, HUMAN_SITE_LOWER_TORSO);
	for (int r = 0; r < 3; r++)
		assert_near(lt[r], s->com[r], 1e-9);
	/* the female figure balances as well */
	struct model *f = build(1.628, 67.7, HUMAN_FEMALE);
	struct state *t = state_make(f);
	kin_update(f, t);
	double rf = t->com[1] / 1.628;
	print_message("female CoM height / stature %.4f\n", rf);
	assert_true(rf > 0.53 && rf < 0.58);
	bl = site_pos(f, t, "foot_l.balance");
	br = site_pos(f, t, "foot_r.balance");
	assert_true(hypot(t->com[0] - (bl[0] + br[0]) / 2, t->com[2] - (bl[2] + br[2]) / 2) < 0.02);
	state_free(t);
	model_free(f);
	state_free(s);
	model_free(m);
}

/* the name with every "_l" turned into "_r" */
static int
mirror_name(const char *in, char *out, size_t len)
{
	int n = 0;
	snprintf(out, len, "%s", in);
	for (char *p = out; (p = strstr(p, "_l")) != NULL; p += 2) {
		p[1] = 'r';
		n++;
	}
	return n;
}

static void
test_symmetry(void **unused)
{
	(void)unused;
	struct model *m = build(1.75, 75, HUMAN_MALE);
	struct state *s = state_make(m);
	kin_update(m, s);
	char full[128], other[128];
	int pairs = 0;
	for (int k = 0; k < m->nsite; k++) {
		model_site_fullname(m, k, full, sizeof full);
		if (!mirror_name(full, other, sizeof other))
			continue;
		const double *a = s->site_xf[k].p, *b = site_pos(m, s, other);
		assert_near(-a[0], b[0], 1e-12);
		assert_near(a[1], b[1], 1e-12);
		assert_near(a[2], b[2], 1e-12);
		pairs++;
	}
	assert_int_equal(pairs, 29);
	/* the same hip value on both sides gives mirror-image feet, dof by dof */
	int hl = m->jnt_dof0[joint(m, "hip_l")], hr = m->jnt_dof0[joint(m, "hip_r")];
	for (int d = 0; d < 3; d++) {
		state_reset(m, s);
		s->q[hl + d] = 0.4;
		s->q[hr + d] = 0.4;
		kin_update(m, s);
		const double *fl = site_pos(m, s, "toes_l.tip"), *fr = site_pos(m, s, "toes_r.tip");
		assert_near(-fl[0], fr[0], 1e-12);
		assert_near(fl[1], fr[1], 1e-12);
		assert_near(fl[2], fr[2], 1e-12);
		/* and the value moved the foot */
		assert_true(fabs(fl[0] - 0.089) + fabs(fl[1]) + fabs(fl[2] - 0.1645) > 0.01);
	}
	/* the mass distribution is symmetric: the centre of mass on the mid-plane */
	state_reset(m, s);
	kin_update(m, s);
	assert_near(s->com[0], 0, 1e-12);
	state_free(s);
	model_free(m);
}

/* moves dof `j`.`d` by v from the built posture; returns the world site position */
static void
moved(const struct model *m, struct state *s, const char *jn, int d, double v, const char *sn,
      double before[3], double after[3])
{
	state_reset(m, s);
	kin_update(m, s);
	memcpy(before, site_pos(m, s, sn), 3 * sizeof(double));
	s->q[m->jnt_dof0[joint(m, jn)] + d] = v;
	kin_update(m, s);
	memcpy(after, site_pos(m, s, sn), 3 * sizeof(double));
}

static void
test_anatomical_sense(void **unused)
{
	(void)unused;
	struct model *m = build(1.75, 75, HUMAN_MALE);
	struct state *s = state_make(m);
	kin_update(m, s);
	double a[3], b[3];
	for (int k = 0; k < 2; k++) {
		const char *sfx = k ? "_r" : "_l";
		double out = k ? -1 : 1; /* away from the midline */
		char jn[32], sn[32];
		/* hip flexion: foot forward and up */
		snprintf(jn, sizeof jn, "hip%s", sfx);
		snprintf(sn, sizeof sn, "foot%s.ankle", sfx);
		moved(m, s, jn, HUMAN_DOF_FLEX, 0.5, sn, a, b);
		assert_true(b[2] > a[2] + 0.1 && b[1] > a[1] + 0.05);
		/* hip abduction: foot away from the midline */
		moved(m, s, jn, HUMAN_DOF_ABD, 0.3, sn, a, b);
		assert_true(out * (b[0] - a[0]) > 0.1);
		/* hip internal rotation: toes turn towards the midline */
		snprintf(sn, sizeof sn, "toes%s.tip", sfx);
		moved(m, s, jn, HUMAN_DOF_ROT, 0.5, sn, a, b);
		assert_true(out * (b[0] - a[0]) < -0.03);
		/* knee flexion: ankle backwards */
		snprintf(jn, sizeof jn, "knee%s", sfx);
		snprintf(sn, sizeof sn, "foot%s.ankle", sfx);
		moved(m, s, jn, 0, 0.5, sn, a, b);
		assert_true(b[2] < a[2] - 0.1);
		/* ankle dorsiflexion: toes up; toe flexion: tip down */
		snprintf(jn, sizeof jn, "ankle%s", sfx);
		snprintf(sn, sizeof sn, "toes%s.tip", sfx);
		moved(m, s, jn, HUMAN_DOF_FLEX, 0.3, sn, a, b);
		assert_true(b[1] > a[1] + 0.02);
		snprintf(jn, sizeof jn, "toe%s", sfx);
		moved(m, s, jn, 0, 0.5, sn, a, b);
		assert_true(b[1] < a[1] - 0.01);
		/* shoulder flexion and abduction */
		snprintf(jn, sizeof jn, "shoulder%s", sfx);
		snprintf(sn, sizeof sn, "upperarm%s.elbow", sfx);
		moved(m, s, jn, HUMAN_DOF_FLEX, 0.5, sn, a, b);
		assert_true(b[2] > a[2] + 0.1);
		moved(m, s, jn, HUMAN_DOF_ABD, 0.5, sn, a, b);
		assert_true(out * (b[0] - a[0]) > 0.1);
		/* elbow flexion: wrist forward */
		snprintf(jn, sizeof jn, "elbow%s", sfx);
		snprintf(sn, sizeof sn, "forearm%s.wrist_ref", sfx);
		moved(m, s, jn, 0, 0.5, sn, a, b);
		assert_true(b[2] > a[2] + 0.1);
		/* wrist flexion: fingers towards the palm, i.e. the thigh */
		snprintf(jn, sizeof jn, "wrist%s", sfx);
		snprintf(sn, sizeof sn, "hand%s.fingertip", sfx);
		moved(m, s, jn, HUMAN_DOF_FLEX, 0.5, sn, a, b);
		assert_true(out * (b[0] - a[0]) < -0.05);
		/* radial deviation: fingers forward (thumb side) */
		moved(m, s, jn, HUMAN_DOF_ABD, 0.3, sn, a, b);
		assert_true(b[2] > a[2] + 0.03);
		/* clavicle: elevation raises, protraction brings forward the shoulder */
		snprintf(jn, sizeof jn, "clavicle%s", sfx);
		snprintf(sn, sizeof sn, "upperarm%s.origin", sfx);
		moved(m, s, jn, HUMAN_DOF_CLAV_ELEVATE, 0.3, sn, a, b);
		assert_true(b[1] > a[1] + 0.02);
		moved(m, s, jn, HUMAN_DOF_CLAV_PROTRACT, 0.3, sn, a, b);
		assert_true(b[2] > a[2] + 0.02);
		/* eyes: abduction turns the gaze outwards, elevation up */
		snprintf(jn, sizeof jn, "eye%s", sfx);
		snprintf(sn, sizeof sn, "eyeball%s.gaze", sfx);
		state_reset(m, s);
		int eye = m->jnt_dof0[joint(m, jn)], g = site(m, sn);
		s->q[eye + HUMAN_DOF_EYE_YAW] = 0.3;
		kin_update(m, s);
		assert_true(out * s->site_xf[g].r[2] > 0.25); /* world x of the gaze's +z */
		s->q[eye + HUMAN_DOF_EYE_YAW] = 0;
		s->q[eye + HUMAN_DOF_EYE_PITCH] = 0.3;
		kin_update(m, s);
		assert_true(s->site_xf[g].r[5] > 0.25); /* world y of the gaze's +z */
	}
	/* spine: flexion moves the head forward, left bend and turn go left */
	for (int k = 0; k < HUMAN_NSPINE; k++) {
		char jn[32];
		snprintf(jn, sizeof jn, "spine_%d", k);
		moved(m, s, jn, HUMAN_DOF_FLEX, 0.1, "head.vertex", a, b);
		assert_true(b[2] > a[2] + 0.005);
		moved(m, s, jn, HUMAN_DOF_ABD, 0.05, "head.vertex", a, b);
		assert_true(b[0] > a[0] + 0.002);
		moved(m, s, jn, HUMAN_DOF_ROT, 0.1, "head.between_eyes", a, b);
		assert_true(b[0] > a[0] + 0.002);
	}
	state_free(s);
	model_free(m);
}

static void
test_reroot_keeps_frames(void **unused)
{
	(void)unused;
	struct model *m = build(1.75, 75, HUMAN_MALE);
	struct state *s = state_make(m);
	struct xform *before = calloc((size_t)m->nsite, sizeof *before);
	srand(5);
	for (int d = 0; d < m->ndof; d++)
		s->q[d] = m->dof_lo[d] + (m->dof_hi[d] - m->dof_lo[d]) * rand() / RAND_MAX;
	kin_update(m, s);
	memcpy(before, s->site_xf, sizeof *before * (size_t)m->nsite);
	static const char *const roots[] = { "foot_l.balance", "pelvis.lower_torso", "hand_r.palm",
					     "toes_l.toe", "foot_r.heel", HUMAN_SITE_ROOT };
	for (size_t r = 0; r < sizeof roots / sizeof roots[0]; r++) {
		assert_int_equal(kin_set_root(m, s, site(m, roots[r])), 0);
		for (int k = 0; k < m->nsite; k++) {
			for (int i = 0; i < 3; i++)
				assert_near(s->site_xf[k].p[i], before[k].p[i], 1e-9);
			for (int i = 0; i < 9; i++)
				assert_near(s->site_xf[k].r[i], before[k].r[i], 1e-9);
		}
	}
	free(before);
	state_free(s);
	model_free(m);
}

static void
test_bad_inputs(void **unused)
{
	(void)unused;
	struct human_def bad[] = {
		{ .stature = 0, .mass = 75, .sex = HUMAN_MALE },
		{ .stature = NAN, .mass = 75, .sex = HUMAN_MALE },
		{ .stature = 3, .mass = 75, .sex = HUMAN_MALE },
		{ .stature = 0.99, .mass = 75, .sex = HUMAN_MALE },
		{ .stature = 1.75, .mass = -1, .sex = HUMAN_MALE },
		{ .stature = 1.75, .mass = NAN, .sex = HUMAN_FEMALE },
		{ .stature = 1.75, .mass = 301, .sex = HUMAN_MALE },
		{ .stature = 1.75, .mass = 75, .sex = (enum human_sex)7 },
	};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
		char err[256] = "";
		assert_null(human_build(&bad[i], err, sizeof err));
		assert_true(strlen(err) > 10);
	}
	char err[256] = "";
	struct human_def d = { .stature = 3, .mass = 75, .sex = HUMAN_MALE };
	assert_null(human_build(&d, err, sizeof err));
	assert_non_null(strstr(err, "stature"));
	d = (struct human_def){ .stature = 1.75, .mass = -1, .sex = HUMAN_MALE };
	assert_null(human_build(&d, err, sizeof err));
	assert_non_null(strstr(err, "mass"));
	assert_null(human_build(NULL, err, sizeof err));
	/* the bounds themselves are allowed */
	d = (struct human_def){ .stature = 1.0, .mass = 20, .sex = HUMAN_FEMALE };
	struct model *m = human_build(&d, err, sizeof err);
	assert_non_null(m);
	model_free(m);
	d = (struct human_def){ .stature = 2.5, .mass = 300, .sex = HUMAN_MALE };
	m = human_build(&d, err, sizeof err);
	assert_non_null(m);
	model_free(m);
}

static void
test_defaults(void **unused)
{
	(void)unused;
	struct human_def d = human_default_def(HUMAN_MALE);
	assert_near(d.stature, 1.75, 0);
	assert_near(d.mass, 75, 0);
	assert_int_equal(d.sex, HUMAN_MALE);
	d = human_default_def(HUMAN_FEMALE);
	assert_int_equal(d.sex, HUMAN_FEMALE);
	assert_true(d.stature > 1.55 && d.stature < 1.70);
	assert_true(d.mass > 55 && d.mass < 80);
	/* building twice gives the same numbers and names (model_equal also
	 * compares the bytes after each name's NUL, which the builder leaves
	 * unset, so it is not used here) */
	struct model *a = build(1.8, 80, HUMAN_MALE), *b = build(1.8, 80, HUMAN_MALE);
	assert_memory_equal(a->seg_mass, b->seg_mass, sizeof(double) * (size_t)a->nseg);
	assert_memory_equal(a->seg_com, b->seg_com, sizeof(double) * 3 * (size_t)a->nseg);
	assert_memory_equal(a->seg_inertia, b->seg_inertia, sizeof(double) * 6 * (size_t)a->nseg);
	assert_memory_equal(a->site_pos, b->site_pos, sizeof(double) * 3 * (size_t)a->nsite);
	assert_memory_equal(a->geom_size, b->geom_size, sizeof(double) * 3 * (size_t)a->ngeom);
	assert_memory_equal(a->geom_pos, b->geom_pos, sizeof(double) * 3 * (size_t)a->ngeom);
	assert_memory_equal(a->dof_lo, b->dof_lo, sizeof(double) * (size_t)a->ndof);
	assert_memory_equal(a->dof_hi, b->dof_hi, sizeof(double) * (size_t)a->ndof);
	for (int k = 0; k < a->nsite; k++)
		assert_string_equal(a->site_name[k], b->site_name[k]);
	model_free(a);
	model_free(b);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_counts),
		cmocka_unit_test(test_mass_limits_extent),
		cmocka_unit_test(test_inertia),
		cmocka_unit_test(test_standing_balance),
		cmocka_unit_test(test_symmetry),
		cmocka_unit_test(test_anatomical_sense),
		cmocka_unit_test(test_reroot_keeps_frames),
		cmocka_unit_test(test_bad_inputs),
		cmocka_unit_test(test_defaults),
	};
	return cmocka_run_group_tests_name("human", tests, NULL, NULL);
}
