/* test_kin.c - forward kinematics, Jacobians, centres of mass, re-rooting */
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

#include "figure/kin.h"
#include "figure/model.h"
#include "figure/state.h"

static const double QID[4] = { 0, 0, 0, 1 };

/* a two-link planar arm: base --R(z)--> link1 (1 m) --R(z)--> link2 (0.5 m) */
static struct model *
planar_arm(void)
{
	struct model_builder *b = model_builder_create("arm");
	struct segment_def sd = segment_default_def();
	sd.name = "base";
	int base = model_builder_segment(b, &sd);
	sd.name = "l1";
	sd.mass = 2;
	sd.com[0] = 0.5;
	int l1 = model_builder_segment(b, &sd);
	sd.name = "l2";
	sd.mass = 1;
	sd.com[0] = 0.25;
	int l2 = model_builder_segment(b, &sd);
	double o[3] = { 0, 0, 0 }, x1[3] = { 1, 0, 0 }, x2[3] = { 0.5, 0, 0 };
	int s_base = model_builder_site(b, base, "origin", o, QID);
	int s_sh = model_builder_site(b, base, "shoulder", o, QID);
	int s_l1a = model_builder_site(b, l1, "proximal", o, QID);
	int s_l1b = model_builder_site(b, l1, "distal", x1, QID);
	int s_l2a = model_builder_site(b, l2, "proximal", o, QID);
	int s_tip = model_builder_site(b, l2, "tip", x2, QID);
	assert_true(s_tip >= 0);
	struct joint_def jd = joint_default_def();
	jd.name = "j1";
	jd.site_from = s_sh;
	jd.site_to = s_l1a;
	jd.ndof = 1;
	jd.dof[0] = (struct dof_def){ DOF_ROTATION, 2, 1, -M_PI, M_PI, 0 };
	assert_true(model_builder_joint(b, &jd) >= 0);
	jd.name = "j2";
	jd.site_from = s_l1b;
	jd.site_to = s_l2a;
	assert_true(model_builder_joint(b, &jd) >= 0);
	assert_int_equal(model_builder_root(b, s_base, o, QID), 0);
	struct model *m = model_builder_finish(b);
	assert_non_null(m);
	model_builder_free(b);
	return m;
}

static void
test_planar_arm_analytic(void **unused)
{
	(void)unused;
	struct model *m = planar_arm();
	struct state *s = state_make(m);
	double a = 0.7, c = -1.1;
	s->q[0] = a;
	s->q[1] = c;
	kin_update(m, s);
	int tip = model_find_site(m, "l2.tip");
	assert_true(tip >= 0);
	double *p = s->site_xf[tip].p;
	assert_near(p[0], cos(a) + 0.5 * cos(a + c), 1e-14);
	assert_near(p[1], sin(a) + 0.5 * sin(a + c), 1e-14);
	assert_near(p[2], 0, 1e-14);
	/* centre of mass: (2 * mid of l1 + 1 * mid of l2) / 3 */
	double cx = (2 * 0.5 * cos(a) + (cos(a) + 0.25 * cos(a + c))) / 3;
	double cy = (2 * 0.5 * sin(a) + (sin(a) + 0.25 * sin(a + c))) / 3;
	assert_near(s->com[0], cx, 1e-14);
	assert_near(s->com[1], cy, 1e-14);
	/* analytic Jacobian of the tip */
	double J[6 * 2];
	kin_site_jacobian(m, s, tip, J);
	assert_near(J[0], -sin(a) - 0.5 * sin(a + c), 1e-14);
	assert_near(J[1], -0.5 * sin(a + c), 1e-14);
	assert_near(J[2], cos(a) + 0.5 * cos(a + c), 1e-14);
	assert_near(J[3], 0.5 * cos(a + c), 1e-14);
	assert_near(J[5 * 2 + 0], 1, 1e-15); /* angular z */
	assert_near(J[5 * 2 + 1], 1, 1e-15);
	state_free(s);
	model_free(m);
}

/* random tree figure with mixed dofs, some joints pointing "up" the tree */
static struct model *
random_tree(unsigned seed, int nseg)
{
	srand(seed);
	struct model_builder *b = model_builder_create("tree");
	char name[32];
	int top[64], any[64];
	for (int i = 0; i < nseg; i++) {
		struct segment_def sd = segment_default_def();
		snprintf(name, sizeof name, "s%d", i);
		sd.name = name;
		sd.mass = 0.5 + (double)rand() / RAND_MAX;
		for (int r = 0; r < 3; r++)
			sd.com[r] = (double)rand() / RAND_MAX - 0.5;
		int seg = model_builder_segment(b, &sd);
		double pos[3], q[4], axis[3];
		for (int r = 0; r < 3; r++) {
			pos[r] = (double)rand() / RAND_MAX - 0.5;
			axis[r] = (double)rand() / RAND_MAX - 0.5;
		}
		double n = sqrt(mathx_dot(axis, axis));
		for (int r = 0; r < 3; r++)
			axis[r] /= n;
		mathx_quat_axis_angle(axis, 2.0 * rand() / RAND_MAX, q);
		top[i] = model_builder_site(b, seg, "top", pos, q);
		for (int r = 0; r < 3; r++)
			pos[r] = (double)rand() / RAND_MAX - 0.5;
		mathx_quat_axis_angle(axis, -1.0 * rand() / RAND_MAX, q);
		any[i] = model_builder_site(b, seg, "bottom", pos, q);
	}
	for (int i = 1; i < nseg; i++) {
		int parent = rand() % i;
		struct joint_def jd = joint_default_def();
		snprintf(name, sizeof name, "j%d", i);
		jd.name = name;
		/* half the joints are written child -> parent */
		if (rand() % 2) {
			jd.site_from = any[parent];
			jd.site_to = top[i];
		} else {
			jd.site_from = top[i];
			jd.site_to = any[parent];
		}
		jd.ndof = 1 + rand() % 4;
		for (int k = 0; k < jd.ndof; k++) {
			jd.dof[k].kind = rand() % 5 == 0 ? DOF_TRANSLATION : DOF_ROTATION;
			jd.dof[k].axis = rand() % 3;
			jd.dof[k].sign = rand() % 2 ? 1 : -1;
			jd.dof[k].lo = -1;
			jd.dof[k].hi = 1;
		}
		assert_true(model_builder_joint(b, &jd) >= 0);
	}
	double o[3] = { 0.1, 0.2, 0.3 };
	assert_int_equal(model_builder_root(b, top[0], o, QID), 0);
	struct model *m = model_builder_finish(b);
	assert_non_null(m);
	model_builder_free(b);
	return m;
}

static void
random_posture(const struct model *m, struct state *s)
{
	for (int d = 0; d < m->ndof; d++)
		s->q[d] = m->dof_lo[d] + (m->dof_hi[d] - m->dof_lo[d]) * rand() / RAND_MAX;
}

static void
test_jacobians_match_finite_differences(void **unused)
{
	(void)unused;
	for (unsigned seed = 1; seed <= 5; seed++) {
		struct model *m = random_tree(seed, 12);
		struct state *s = state_make(m), *t = state_make(m);
		kin_update(m, s);
		kin_update(m, t);
		random_posture(m, s);
		/* root somewhere in the middle, so joints point both ways */
		kin_update(m, s);
		kin_set_root(m, s, m->seg_site0[5] + 1);
		int n = m->ndof;
		double *J = calloc((size_t)(6 * n), sizeof *J), *Jc = calloc((size_t)(3 * n), sizeof *Jc);
		for (int site = 0; site < m->nsite; site++) {
			kin_site_jacobian(m, s, site, J);
			for (int d = 0; d < n; d++) {
				const double h = 1e-6;
				double pp[3], pm[3], Rp[9], Rm[9];
				state_copy(m, s, t);
				t->q[d] += h;
				kin_update(m, t);
				memcpy(pp, t->site_xf[site].p, sizeof pp);
				memcpy(Rp, t->site_xf[site].r, sizeof Rp);
				t->q[d] -= 2 * h;
				kin_update(m, t);
				memcpy(pm, t->site_xf[site].p, sizeof pm);
				memcpy(Rm, t->site_xf[site].r, sizeof Rm);
				for (int r = 0; r < 3; r++)
					assert_near(J[r * n + d], (pp[r] - pm[r]) / (2 * h), 1e-7);
				/* angular: skew(w) = dR/dq R^T */
				const double *R = s->site_xf[site].r;
				double W[9] = { 0 };
				for (int i = 0; i < 3; i++)
					for (int j = 0; j < 3; j++)
						for (int k = 0; k < 3; k++)
							W[3 * i + j] += (Rp[3 * i + k] - Rm[3 * i + k]) /
									(2 * h) * R[3 * j + k];
				assert_near(J[3 * n + d], W[7], 1e-7);
				assert_near(J[4 * n + d], W[2], 1e-7);
				assert_near(J[5 * n + d], W[3], 1e-7);
			}
		}
		kin_com_jacobian(m, s, Jc);
		for (int d = 0; d < n; d++) {
			const double h = 1e-6;
			double cp[3];
			state_copy(m, s, t);
			t->q[d] += h;
			kin_update(m, t);
			memcpy(cp, t->com, sizeof cp);
			t->q[d] -= 2 * h;
			kin_update(m, t);
			for (int r = 0; r < 3; r++)
				assert_near(Jc[r * n + d], (cp[r] - t->com[r]) / (2 * h), 1e-7);
		}
		free(J);
		free(Jc);
		state_free(s);
		state_free(t);
		model_free(m);
	}
}

static void
test_reroot_moves_nothing(void **unused)
{
	(void)unused;
	struct model *m = random_tree(42, 20);
	struct state *s = state_make(m);
	struct xform *before = calloc((size_t)m->nsite, sizeof *before);
	random_posture(m, s);
	kin_update(m, s);
	memcpy(before, s->site_xf, sizeof *before * (size_t)m->nsite);
	double com[3];
	memcpy(com, s->com, sizeof com);
	for (int site = 0; site < m->nsite; site += 3) {
		assert_int_equal(kin_set_root(m, s, site), 0);
		for (int k = 0; k < m->nsite; k++) {
			for (int r = 0; r < 3; r++)
				assert_near(s->site_xf[k].p[r], before[k].p[r], 1e-12);
			for (int r = 0; r < 9; r++)
				assert_near(s->site_xf[k].r[r], before[k].r[r], 1e-12);
		}
		for (int r = 0; r < 3; r++)
			assert_near(s->com[r], com[r], 1e-12);
	}
	assert_int_equal(kin_set_root(m, s, -1), -1);
	assert_int_equal(kin_set_root(m, s, m->nsite), -1);
	free(before);
	state_free(s);
	model_free(m);
}

/* the joint transform is the same whichever way the joint lies in the tree */
static void
test_joint_direction_independent_of_root(void **unused)
{
	(void)unused;
	struct model *m = random_tree(7, 10);
	struct state *s = state_make(m);
	random_posture(m, s);
	kin_update(m, s);
	for (int root = 0; root < m->nsite; root += 4) {
		kin_set_root(m, s, root);
		for (int j = 0; j < m->njnt; j++) {
			struct xform rel, expect;
			/* global from-site * joint transform == global to-site */
			kin_joint_xform(m, s, j, &rel);
			xform_mul(&s->site_xf[m->jnt_site_from[j]], &rel, &expect);
			for (int r = 0; r < 3; r++)
				assert_near(expect.p[r], s->site_xf[m->jnt_site_to[j]].p[r], 1e-12);
			for (int r = 0; r < 9; r++)
				assert_near(expect.r[r], s->site_xf[m->jnt_site_to[j]].r[r], 1e-12);
		}
	}
	state_free(s);
	model_free(m);
}

static void
test_builder_rejects_bad_trees(void **unused)
{
	(void)unused;
	struct model_builder *b = model_builder_create("bad");
	struct segment_def sd = segment_default_def();
	sd.name = "a";
	int a = model_builder_segment(b, &sd);
	assert_int_equal(model_builder_segment(b, &sd), -1); /* duplicate */
	sd.name = "b";
	int bb = model_builder_segment(b, &sd);
	double o[3] = { 0 };
	int sa = model_builder_site(b, a, "x", o, QID);
	int sb = model_builder_site(b, bb, "x", o, QID);
	assert_int_equal(model_builder_root(b, sa, o, QID), 0);
	assert_null(model_builder_finish(b)); /* two segments, no joint */
	struct joint_def jd = joint_default_def();
	jd.name = "j";
	jd.site_from = sa;
	jd.site_to = sa;
	assert_int_equal(model_builder_joint(b, &jd), -1); /* same segment */
	jd.site_to = sb;
	jd.ndof = 1;
	jd.dof[0] = (struct dof_def){ DOF_ROTATION, 0, 1, 1, -1, 0 };
	assert_int_equal(model_builder_joint(b, &jd), -1); /* lo > hi */
	jd.dof[0] = (struct dof_def){ DOF_ROTATION, 0, 1, -1, 1, 0 };
	assert_true(model_builder_joint(b, &jd) >= 0);
	struct model *m = model_builder_finish(b);
	assert_non_null(m);
	struct model *c = model_copy(m);
	assert_true(model_equal(m, c));
	c->dof_hi[0] = 2;
	assert_false(model_equal(m, c));
	model_free(c);
	model_free(m);
	model_builder_free(b);
}

/* the same figure built twice is the same model, bit for bit */
static void
test_builder_is_deterministic(void **unused)
{
	(void)unused;
	struct model *a = random_tree(11, 15), *b = random_tree(11, 15);
	assert_true(model_equal(a, b));
	model_free(a);
	model_free(b);
}

/*
 * The rotation vector recovers axis times angle from a matrix built by
 * Rodrigues' formula written out here, over the whole range of angles,
 * those next to 0 and to pi included (where the antisymmetric part of the
 * matrix fades and a naive log map loses its digits).
 */
static void
test_rotation_vector_inverts_rodrigues(void **unused)
{
	(void)unused;
	srand(11);
	const double angles[] = { 1e-14, 1e-7, 0.3, 1.5, 3.0, M_PI - 1e-7, M_PI - 1e-12 };
	for (int n = 0; n < 200; n++) {
		double a[3], len = 0;
		for (int i = 0; i < 3; i++) {
			a[i] = 2.0 * rand() / RAND_MAX - 1;
			len += a[i] * a[i];
		}
		len = sqrt(len);
		for (int i = 0; i < 3; i++)
			a[i] /= len;
		double th = n < 7 ? angles[n] : M_PI * rand() / RAND_MAX;
		double c = cos(th), s = sin(th), t = 1 - c, r[9], w[3];
		double x = a[0], y = a[1], z = a[2];
		double m[9] = { t * x * x + c,     t * x * y - s * z, t * x * z + s * y,
				t * x * y + s * z, t * y * y + c,     t * y * z - s * x,
				t * x * z - s * y, t * y * z + s * x, t * z * z + c };
		memcpy(r, m, sizeof r);
		mathx_rotation_vector(r, w);
		/* near pi the axis's sign is free: w and -w are the same turn */
		double sgn = w[0] * a[0] + w[1] * a[1] + w[2] * a[2] < 0 ? -1 : 1;
		for (int i = 0; i < 3; i++)
			assert_true(fabs(sgn * w[i] - a[i] * th) < 1e-9 + 1e-6 * (th > 3.1));
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_planar_arm_analytic),
		cmocka_unit_test(test_jacobians_match_finite_differences),
		cmocka_unit_test(test_reroot_moves_nothing),
		cmocka_unit_test(test_joint_direction_independent_of_root),
		cmocka_unit_test(test_builder_rejects_bad_trees),
		cmocka_unit_test(test_builder_is_deterministic),
		cmocka_unit_test(test_rotation_vector_inverts_rodrigues),
	};
	return cmocka_run_group_tests_name("kin", tests, NULL, NULL);
}
