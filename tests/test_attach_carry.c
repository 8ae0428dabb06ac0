/*
 * test_attach_carry.c - a grabbed object carried by a moving hand stays a
 * rigid body where the grab put it: after hundreds of frames of motion its
 * root's rotation is still a rotation (R^T R = I) and its frame still the
 * palm's times the grab's, to rounding. (A carry that inverted the root by
 * its transpose doubled the root's error every frame the hand moved: the
 * object swelled and flew off after some fifty frames of a steady drag.)
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "test_util.h"

#include <stdlib.h>

#include "figure/human.h"
#include "figure/kin.h"
#include "pose/attach.h"
#include "pose/env.h"

static double
off_rotation(const double r[9])
{
	double worst = 0;
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++) {
			double d = 0;
			for (int k = 0; k < 3; k++)
				d += r[3 * k + i] * r[3 * k + j];
			worst = fmax(worst, fabs(d - (i == j)));
		}
	return worst;
}

static void
test_a_carried_object_stays_rigid_where_the_grab_put_it(void **unused)
{
	(void)unused;
	static struct env e;
	env_init(&e);
	char err[300];
	struct human_def hd = human_default_def(HUMAN_MALE);
	int jack = env_add_figure(&e, human_build(&hd, err, sizeof err), "jack", 1, &hd, NULL);
	int crate = env_add_figure(&e, human_build(&hd, err, sizeof err), "crate", 1, &hd, NULL);
	assert_true(jack >= 0 && crate >= 0);
	struct env_figure *f = &e.fig[jack], *o = &e.fig[crate];
	f->behave = calloc(1, sizeof *f->behave);
	assert_non_null(f->behave);
	assert_int_equal(behave_attach(f->behave, f->model, f->state, f->ik, NULL), 0);
	assert_int_equal(attach_grab(&e, jack, 1, crate, err, sizeof err), 0);
	int a = attach_find(&e, jack, ATTACH_HAND, 1), palm = f->behave->s_palm[1];
	assert_true(a >= 0);
	/* the arm swings a little every frame, about every axis of the shoulder */
	int d0 = f->model->jnt_dof0[model_find_joint(f->model, "shoulder_r")];
	for (int k = 0; k < 400; k++) {
		for (int i = 0; i < 3; i++)
			f->state->q[d0 + i] = 0.3 * sin(0.05 * k + i);
		kin_update(f->model, f->state);
		assert_int_equal(attach_after_solve(&e, jack), 1);
	}
	printf("root off a rotation by %.3g\n", off_rotation(o->state->root_xf.r));
	assert_true(off_rotation(o->state->root_xf.r) < 1e-12);
	struct xform want;
	xform_mul(&f->state->site_xf[palm], &e.att[a].rel, &want);
	for (int i = 0; i < 3; i++)
		assert_near(o->state->seg_xf[e.att[a].seg].p[i], want.p[i], 1e-9);
	for (int i = 0; i < 9; i++)
		assert_near(o->state->seg_xf[e.att[a].seg].r[i], want.r[i], 1e-9);
	env_clear(&e);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_a_carried_object_stays_rigid_where_the_grab_put_it),
	};
	return cmocka_run_group_tests_name("attach_carry", tests, NULL, NULL);
}
