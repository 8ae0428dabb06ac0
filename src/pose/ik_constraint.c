/* ik_constraint.c - a constraint's defaults and the checks a definition must pass */
#include "pose/ik_constraint.h"

#include <math.h>

struct ik_constraint_def
ik_constraint_default_def(void)
{
	struct ik_constraint_def d = { 0 };
	d.effector_site = -1;
	d.goal_site = -1;
	xform_identity(&d.effector_offset);
	xform_identity(&d.goal_xf);
	d.pos = IK_POINT;
	d.ori = IK_ORI_NONE;
	d.goal_axis[1] = 1;
	d.effector_axis[2] = 1;
	d.pos_weight = 1;
	d.weight = 1;
	d.start_joint = -1;
	d.enabled = 1;
	return d;
}

static int
unit_axis(const double v[3])
{
	double n = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
	return isfinite(n) && fabs(n - 1) < 1e-9;
}

int
ik_constraint_valid(const struct model *m, const struct ik_constraint_def *d)
{
	if (d->effector_site < 0 || d->effector_site >= m->nsite)
		return 0;
	if (d->goal_site < -1 || d->goal_site >= m->nsite)
		return 0;
	if (d->start_joint < -1 || d->start_joint >= m->njnt)
		return 0;
	if ((int)d->pos < IK_POS_NONE || d->pos > IK_PLANE || (int)d->ori < IK_ORI_NONE ||
	    d->ori > IK_AIM)
		return 0;
	if (!xform_finite(&d->goal_xf) || !xform_finite(&d->effector_offset))
		return 0;
	if (!(d->pos_weight >= 0 && d->pos_weight <= 1) || !(d->weight >= 0) || !isfinite(d->weight))
		return 0;
	if ((d->pos == IK_LINE || d->pos == IK_PLANE || d->ori == IK_DIRECTION) &&
	    !unit_axis(d->goal_axis))
		return 0;
	if ((d->ori == IK_DIRECTION || d->ori == IK_AIM) && !unit_axis(d->effector_axis))
		return 0;
	return d->group >= 0 && d->group < IK_MAX_GROUPS;
}
