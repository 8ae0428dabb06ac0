/*
 * reach.c - a hand sent to a target on a copy of the figure's state (reach.h).
 *
 * The copy gets the behaviours' constraint set (behave_attach: the natural
 * constraints, their indices and the limit springs), then the mode decides
 * which stay on and how far down the hand's chain runs; one solve, to
 * convergence or to where the energy stops falling, without a clock, so a
 * verdict does not depend on the machine's speed.
 */
#include "pose/reach.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "figure/kin.h"
#include "figure/mathx.h"
#include "pose/stance.h"

struct reach {
	struct ik *ik;
	struct state *copy;
	struct behave b;
	int dof_limit[REACH_LIMITING_MAX * 3];
};

struct reach *
reach_make(const struct model *m)
{
	struct reach *r = calloc(1, sizeof *r);
	if (!r)
		return NULL;
	r->ik = ik_make(m, BEHAVE_NCON);
	r->copy = state_make(m);
	if (!r->ik || !r->copy) {
		reach_free(r);
		return NULL;
	}
	/* a figure the behaviours cannot drive (no hands or feet) cannot be asked */
	kin_update(m, r->copy);
	struct behave_params p = behave_default_params();
	if (behave_attach(&r->b, m, r->copy, r->ik, &p) < 0) {
		reach_free(r);
		return NULL;
	}
	return r;
}

void
reach_free(struct reach *r)
{
	if (!r)
		return;
	ik_free(r->ik);
	state_free(r->copy);
	free(r);
}

const struct state *
reach_posture(const struct reach *r)
{
	return r->copy;
}

static int
finite3(const double *v, int n)
{
	for (int i = 0; i < n; i++)
		if (!isfinite(v[i]))
			return 0;
	return 1;
}

/* the behaviours' constraints this mode keeps: the hand, and for the body its support */
static void
keep_for_mode(struct reach *r, const struct reach_request *q)
{
	struct behave *b = &r->b;
	int body = q->mode == REACH_BODY;
	for (int k = 0; k < 2; k++) {
		ik_enable(r->ik, b->c_toe[k], body);
		ik_enable(r->ik, b->c_heel[k], body);
		ik_enable(r->ik, b->c_eye[k], 0);
		if (k != q->side) /* the other hand stays as it is: its chain is not moved */
			ik_enable(r->ik, b->c_hand[k], 0);
	}
	ik_enable(r->ik, b->c_balance, body && q->balance);
	ik_enable(r->ik, b->c_pelvis, 0);
	ik_enable(r->ik, b->c_torso, 0);
	ik_enable(r->ik, b->c_head, 0);
}

/* the joints of the dofs the solve left on a limit, each once */
static void
limiting_joints(struct reach *r, const struct model *m, struct reach_result *res)
{
	int n = ik_active_limits(r->ik, m, r->copy, r->dof_limit,
				 (int)(sizeof r->dof_limit / sizeof r->dof_limit[0]));
	res->nlimiting = 0;
	for (int i = 0; i < n; i++) {
		int d = r->dof_limit[i], j = 0;
		while (j < m->njnt && !(d >= m->jnt_dof0[j] && d < m->jnt_dof0[j] + m->jnt_ndof[j]))
			j++;
		if (j == m->njnt || (res->nlimiting && res->limiting[res->nlimiting - 1] == j))
			continue; /* dofs come in order: a joint's are together */
		if (res->nlimiting < REACH_LIMITING_MAX)
			res->limiting[res->nlimiting++] = j;
	}
}

int
reach_solve(struct reach *r, const struct model *m, const struct state *s,
	    const struct behave_params *p, const struct point_mass *pm, int n,
	    const struct reach_request *q, struct reach_result *res)
{
	if ((q->side != BEHAVE_LEFT && q->side != BEHAVE_RIGHT) ||
	    (q->mode != REACH_ARM && q->mode != REACH_TORSO && q->mode != REACH_BODY) ||
	    !finite3(q->target, 3) || (q->oriented && !finite3(q->rot, 9)) || q->restarts < 0 ||
	    q->restarts > 64)
		return -1;
	memset(res, 0, sizeof *res);
	state_copy(m, s, r->copy);
	kin_update(m, r->copy);
	struct behave_params bp = p ? *p : behave_default_params();
	/* feet planted where they stand; the body free to bend and squat */
	for (int k = 0; k < 2; k++) {
		bp.foot[k] = FOOT_HOLD_GLOBAL;
		bp.heel[k] = HEEL_KEEP_ON_FLOOR;
	}
	bp.torso = TORSO_FREE;
	bp.hold_elevation = 0;
	bp.root_through_com = 0;
	bp.fixate_head = bp.fixate_eyes = 0;
	ik_clear(r->ik);
	if (behave_attach(&r->b, m, r->copy, r->ik, &bp) < 0 ||
	    ik_set_point_masses(r->ik, m, pm, n) < 0)
		return -1;
	/* the knee and elbow springs are a preference of the behaviours (§D.1.6), not a
	 * limit: a reach goes to the joints' limits */
	if (stance_limit_springs(r->ik, m, bp.spring_angle, 0) < 0)
		return -1;
	kin_update(m, r->copy);
	keep_for_mode(r, q);

	struct ik_constraint_def d = *ik_get(r->ik, r->b.c_hand[q->side]);
	d.effector_site = r->b.s_palm[q->side];
	xform_identity(&d.effector_offset);
	d.goal_site = -1;
	memcpy(d.goal_xf.p, q->target, sizeof q->target);
	if (q->oriented) {
		memcpy(d.goal_xf.r, q->rot, sizeof q->rot);
		d.ori = IK_FRAME;
		d.pos_weight = 0.5;
	} else {
		d.ori = IK_ORI_NONE;
		d.pos_weight = 1;
	}
	d.start_joint = q->mode == REACH_ARM ? r->b.j_clav[q->side]
			: q->mode == REACH_TORSO ? r->b.j_spine0
						 : -1; /* down the legs to the root */
	d.group = 0; /* with the support and balance, so they bound what the hand gets */
	d.enabled = 1;
	if (ik_set(r->ik, m, r->b.c_hand[q->side], &d) < 0)
		return -1;

	struct ik_options opt = ik_default_options();
	opt.step_pos = opt.step_ori = 0; /* the whole way in one solve */
	opt.budget_us = 0;               /* no clock: the verdict does not depend on the machine */
	if (q->restarts > 0) {
		opt.restarts = q->restarts;
		opt.restart_after = 20; /* a start 20 iterations in that no longer halves its
					   distance in 8 has found its basin */
	}
	res->ik = ik_solve(r->ik, m, r->copy, &opt, NULL);

	const struct xform *palm = &r->copy->site_xf[r->b.s_palm[q->side]];
	double dv[3] = { palm->p[0] - q->target[0], palm->p[1] - q->target[1],
			 palm->p[2] - q->target[2] };
	res->distance = sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]);
	memcpy(res->palm, palm->p, sizeof res->palm);
	if (q->oriented) { /* the angle of palm^T goal from its trace */
		double tr = 0;
		for (int i = 0; i < 9; i++)
			tr += palm->r[i] * q->rot[i];
		res->angle = acos(fmax(-1, fmin(1, (tr - 1) / 2)));
	}
	res->reached = res->distance <= REACH_TOL_POS && (!q->oriented || res->angle <= REACH_TOL_ORI);
	double com[3];
	ik_com(r->ik, r->copy, com);
	struct balance bal;
	res->margin = balance_measure_com(m, r->copy, BALANCE_CONTACT, 0, com, &bal) < 0
			      ? -1e9
			      : bal.margin;
	limiting_joints(r, m, res);
	return 0;
}
