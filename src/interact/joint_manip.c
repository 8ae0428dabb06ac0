/* joint_manip.c - a joint's DOFs moved with the mouse (see joint_manip.h) */
#include "interact/joint_manip.h"

#include <linux/input-event-codes.h>
#include <string.h>

#include "interact/geom.h"

void
joint_manip_init(struct joint_manip *j, int ndof)
{
	memset(j, 0, sizeof *j);
	j->ndof = ndof;
	j->dof = -1;
}

/* the DOF a chord selects, or -1 */
static int
joint_manip_select(const struct joint_manip *j)
{
	int first;
	switch (j->buttons) {
	case 1:
		first = 0;
		break;
	case 2:
		first = 1;
		break;
	case 4:
		first = 2;
		break;
	default:
		return -1; /* none, or more than one: nothing, as in Table 3.2 */
	}
	int dof = first + (j->ctrl ? 3 : 0);
	return dof < j->ndof ? dof : -1;
}

/* sets or clears bit in *mask for a press or release; 1 when it changed */
static int
joint_manip_bit(unsigned *mask, unsigned bit, int value)
{
	unsigned before = *mask;
	if (value == 1)
		*mask |= bit;
	else if (value == 0)
		*mask &= ~bit;
	return *mask != before;
}

int
joint_manip_event(struct joint_manip *j, const struct input_event_rec *e)
{
	int changed = 0;
	if (e->kind == INPUT_BUTTON) {
		unsigned bit = e->code == BTN_LEFT ? 1 : e->code == BTN_MIDDLE ? 2
						      : e->code == BTN_RIGHT ? 4 : 0;
		changed = bit && joint_manip_bit(&j->buttons, bit, e->value);
	} else if (e->kind == INPUT_KEY) {
		unsigned bit = e->code == KEY_LEFTCTRL ? 1 : e->code == KEY_RIGHTCTRL ? 2 : 0;
		changed = bit && joint_manip_bit(&j->ctrl, bit, e->value);
	}
	if (!changed)
		return 0;
	int dof = joint_manip_select(j);
	j->dof = dof;
	j->anchored = 0; /* the next mouse line anchors: a press moves nothing */
	return 1;
}

static double
joint_manip_clamp(double v, double lo, double hi)
{
	return v < lo ? lo : v > hi ? hi : v;
}

/* the spoke to where the mouse line meets the wheel's plane; 0 when it does not */
static int
joint_manip_spoke(const struct joint_dof_view *dv, const struct ray *r, double spoke[3])
{
	double at[3];
	if (geom_ray_plane(r, dv->pivot, dv->axis, NULL, at) != GEOM_HIT)
		return 0;
	for (int k = 0; k < 3; k++)
		spoke[k] = at[k] - dv->pivot[k];
	return 1;
}

int
joint_manip_ray(struct joint_manip *j, const struct joint_dof_view *dv, const struct ray *r,
		double *value)
{
	if (j->dof < 0)
		return 0;
	if (!dv->rotation) {
		double s;
		if (geom_axis_nearest_ray(dv->pivot, dv->axis, r, &s, NULL) != GEOM_HIT)
			return 0;
		if (!j->anchored) {
			j->anchored = 1;
			j->value0 = dv->value;
			j->s0 = s;
			return 0;
		}
		*value = joint_manip_clamp(j->value0 + (s - j->s0), dv->lo, dv->hi);
		return 1;
	}
	double spoke[3], turn;
	if (!joint_manip_spoke(dv, r, spoke))
		return 0;
	if (!j->anchored) {
		j->anchored = 1;
		j->value0 = dv->value;
		j->angle = 0;
		memcpy(j->spoke0, spoke, sizeof spoke);
		memcpy(j->spoke, spoke, sizeof spoke);
		return 0;
	}
	/* summed step by step, so a crank past half a turn goes on turning */
	if (geom_spoke_angle(dv->axis, j->spoke, spoke, &turn) != GEOM_HIT)
		return 0;
	j->angle += turn;
	memcpy(j->spoke, spoke, sizeof spoke);
	*value = joint_manip_clamp(j->value0 + j->angle, dv->lo, dv->hi);
	return 1;
}

int
joint_manip_type(struct joint_manip *j, const struct joint_dof_view *dv, double typed,
		 double *value)
{
	if (j->dof < 0)
		return 0;
	double base = j->anchored ? j->value0 : dv->value;
	*value = joint_manip_clamp(base + typed, dv->lo, dv->hi);
	j->anchored = 0; /* the next mouse line anchors at the typed value */
	return 1;
}
