/* stance.c - the standing human's natural constraints */
#include "pose/stance.h"

#include "figure/human.h"
#include "figure/kin.h"

int
stance_standing(struct ik *ik, const struct model *m, struct state *s, struct stance *dest)
{
	int bal_l = model_find_site(m, "foot_l.balance"), bal_r = model_find_site(m, "foot_r.balance");
	int lower = model_find_site(m, HUMAN_SITE_LOWER_TORSO), chest = model_find_site(m, HUMAN_SITE_CHEST);
	int spine = model_find_joint(m, "spine_0");
	if (bal_l < 0 || bal_r < 0 || lower < 0 || chest < 0 || spine < 0)
		return -1;
	dest->hand_l = dest->hand_r = -1;
	kin_set_root(m, s, bal_l);

	/* both feet hold position and orientation; the rooted one trivially */
	struct ik_constraint_def c = ik_constraint_default_def();
	c.ori = IK_FRAME;
	c.pos_weight = 0.5;
	c.weight = 10;
	c.effector_site = bal_l;
	c.goal_xf = s->site_xf[bal_l];
	dest->foot_l = ik_add(ik, m, &c);
	c.effector_site = bal_r;
	c.goal_xf = s->site_xf[bal_r];
	dest->foot_r = ik_add(ik, m, &c);

	/* the centre of mass on the vertical line through the balance point */
	c = ik_constraint_default_def();
	c.effector_site = lower;
	c.com_effector = 1;
	c.pos = IK_LINE;
	for (int i = 0; i < 3; i++)
		dest->balance_point[i] = (s->site_xf[bal_l].p[i] + s->site_xf[bal_r].p[i]) / 2;
	dest->balance_point[1] = 0;
	for (int i = 0; i < 3; i++)
		c.goal_xf.p[i] = dest->balance_point[i];
	c.weight = 10;
	dest->balance = ik_add(ik, m, &c);

	/* the chest's up axis stays vertical, moved by the spine alone */
	c = ik_constraint_default_def();
	c.effector_site = chest;
	c.pos = IK_POS_NONE;
	c.ori = IK_DIRECTION;
	c.pos_weight = 0;
	c.effector_axis[1] = 1;
	c.effector_axis[2] = 0;
	c.start_joint = spine;
	dest->torso = ik_add(ik, m, &c);
	if (stance_limit_springs(ik, m, STANCE_SPRING_ANGLE, STANCE_SPRING_WEIGHT) < 0)
		return -1;
	return dest->foot_l < 0 || dest->foot_r < 0 || dest->balance < 0 || dest->torso < 0 ? -1 : 0;
}

int
stance_hand(struct ik *ik, const struct model *m, const struct state *s, struct stance *st,
	    int right)
{
	int palm = model_find_site(m, right ? "hand_r.palm" : "hand_l.palm");
	int clav = model_find_joint(m, right ? "clavicle_r" : "clavicle_l");
	if (palm < 0 || clav < 0)
		return -1;
	struct ik_constraint_def c = ik_constraint_default_def();
	c.effector_site = palm;
	c.ori = IK_FRAME;
	c.pos_weight = 0.5;
	c.start_joint = clav;
	c.group = 1;
	c.goal_xf = s->site_xf[palm];
	int idx = ik_add(ik, m, &c);
	if (right)
		st->hand_r = idx;
	else
		st->hand_l = idx;
	return idx;
}

int
stance_limit_springs(struct ik *ik, const struct model *m, double angle, double weight)
{
	static const char *const joints[] = { "knee_l", "knee_r", "elbow_l", "elbow_r" };
	for (size_t i = 0; i < sizeof joints / sizeof *joints; i++) {
		int j = model_find_joint(m, joints[i]);
		/* 0 is full extension, the lower limit, for all four */
		if (j < 0 || ik_set_spring(ik, m, m->jnt_dof0[j], -1, angle, weight) < 0)
			return -1;
	}
	return 0;
}
