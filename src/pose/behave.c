/* behave.c - the human figure's behaviours (Chapter 5, Appendix D) */
#include "pose/behave.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "pose/behave_internal.h"
#include "figure/human.h"
#include "figure/kin.h"
#include "pose/stance.h"

#define W_FOOT 10.0    /* the feet and balance outweigh the rest: they carry the body */
#define W_BALANCE 10.0
#define W_HEEL_RISE (W_BALANCE / 1000)
#define W_PELVIS 2.0
#define W_TORSO 2.0
#define STEP_LIFT 0.08 /* m: how high a stepping foot rises */

struct behave_params
behave_default_params(void)
{
	struct behave_params p = { 0 };
	p.foot[0] = p.foot[1] = FOOT_HOLD_GLOBAL;
	p.heel[0] = p.heel[1] = HEEL_KEEP_ON_FLOOR;
	p.torso = TORSO_KEEP_VERTICAL;
	p.hand[0] = p.hand[1] = HAND_FREE;
	p.hand_site[0] = p.hand_site[1] = -1;
	p.spring_angle = STANCE_SPRING_ANGLE;
	p.balance_follows_feet = 1;
	p.pelvis_follows_feet = 1;
	p.auto_root = 1;
	p.step_when_losing_balance = 1;
	p.step_when_twisted = 1;
	p.twist_limit = 45 * M_PI / 180;
	p.step_frames = 20;
	p.stability_threshold = 0.02;
	return p;
}

/* the heading of a foot: from its heel to its toe tip, about the vertical */
static double
foot_heading(const struct behave *b, const struct state *s, int side)
{
	const double *h = s->site_xf[b->s_heel[side]].p, *t = s->site_xf[b->s_tip[side]].p;
	return atan2(t[0] - h[0], t[2] - h[2]);
}

/* the mean heading of the feet (a circular mean) */
static double
feet_heading(const struct behave *b, const struct state *s)
{
	double a = foot_heading(b, s, 0), c = foot_heading(b, s, 1);
	return atan2(sin(a) + sin(c), cos(a) + cos(c));
}

/* balance as the behaviours see it: feet whose heels may rise stand on tiptoe, but not mid-step */
static int
measure(struct behave *b, const struct model *m, const struct state *s)
{
	unsigned tiptoe = 0;
	for (int k = 0; k < 2; k++)
		if (b->p.heel[k] == HEEL_ALLOW_RISE && !b->p.seated && !b->step.active)
			tiptoe |= 1u << k;
	double com[3];
	behave_com(b, s, com);
	int rc = balance_measure_com(m, s, BALANCE_CONTACT, tiptoe, com, &b->bal);
	/* the truth follows every measure (a restored figure too); the alert's edge is the solve's */
	b->stability_low = b->bal.margin < b->p.stability_threshold; /* no support: a margin of -1e9 */
	return rc;
}

void
behave_com(const struct behave *b, const struct state *s, double dest[3])
{
	point_mass_com(s, b->mass, b->nmass, dest);
}

/* two lists of masses the same, field by field (their padding is no part of them) */
static int
same_masses(const struct point_mass *a, int na, const struct point_mass *c, int nc)
{
	if (na != nc)
		return 0;
	for (int i = 0; i < na; i++)
		if (a[i].seg != c[i].seg || a[i].mass != c[i].mass || a[i].local[0] != c[i].local[0] ||
		    a[i].local[1] != c[i].local[1] || a[i].local[2] != c[i].local[2])
			return 0;
	return 1;
}

int
behave_set_masses(struct behave *b, const struct model *m, const struct state *s,
		  const struct point_mass *pm, int n)
{
	if (point_mass_check(m, pm, n) < 0)
		return -1;
	if (!same_masses(b->mass, b->nmass, pm, n)) {
		double before[3], after[3];
		behave_com(b, s, before);
		if (n > 0)
			memcpy(b->mass, pm, sizeof *pm * (size_t)n);
		b->nmass = n;
		behave_com(b, s, after);
		/* the body stays where it stands: what is held moves with the centre of mass's jump */
		if (!b->masses_adopt) {
			b->elevation += after[1] - before[1];
			for (int i = 0; i < 3; i++)
				b->com_fixed[i] += after[i] - before[i];
		} else { /* restored: measured again with its weights, telling no alert */
			behave_measure(b, m, s);
		}
	}
	b->masses_adopt = 0;
	return 0;
}

void
behave_measure(struct behave *b, const struct model *m, const struct state *s)
{
	measure(b, m, s);
	b->alert_low = b->stability_low;
}

/* ---- the constraints ----------------------------------------------------------- */

static void
toe_def(const struct behave *b, const struct state *s, int side, struct ik_constraint_def *d)
{
	*d = ik_constraint_default_def();
	d->effector_site = b->s_toe[side];
	d->goal_xf = s->site_xf[b->s_toe[side]];
	d->weight = W_FOOT;
	d->pos_weight = 0.5;
	if (b->p.foot[side] == FOOT_PIVOT) { /* flat, free to turn about the vertical */
		d->ori = IK_DIRECTION;
		d->effector_axis[2] = 0, d->effector_axis[1] = 1;
		d->goal_axis[0] = 0, d->goal_axis[1] = 1, d->goal_axis[2] = 0;
		xform_identity(&d->goal_xf);
		memcpy(d->goal_xf.p, s->site_xf[b->s_toe[side]].p, sizeof d->goal_xf.p);
	} else {
		d->ori = IK_FRAME;
	}
	d->enabled = !b->p.seated; /* seated, the heel holds the foot */
}

static void
heel_def(const struct behave *b, const struct state *s, int side, struct ik_constraint_def *d)
{
	*d = ik_constraint_default_def();
	d->effector_site = b->s_heel[side];
	d->pos = IK_PLANE; /* the floor: the heel's height, nothing else */
	d->goal_axis[0] = 0, d->goal_axis[1] = 1, d->goal_axis[2] = 0;
	d->goal_xf.p[1] = 0;
	d->goal_xf.p[0] = s->site_xf[b->s_heel[side]].p[0];
	d->goal_xf.p[2] = s->site_xf[b->s_heel[side]].p[2];
	/* keep: metres against the radians of the torso, heels stay down; allow
	 * to rise: down only while nothing else needs it up (a thousandth of
	 * balance's pull), so a rise on tiptoe costs the centre of mass < 0.1 % */
	d->weight = b->p.heel[side] == HEEL_KEEP_ON_FLOOR ? 10 * W_FOOT : W_HEEL_RISE;
	if (b->p.seated) { /* the heel's whole frame where it is: pivot and heel rules rest */
		d->pos = IK_POINT;
		d->ori = IK_FRAME;
		d->pos_weight = 0.5;
		d->weight = W_FOOT;
		d->goal_xf = s->site_xf[b->s_heel[side]];
		d->enabled = 1;
	}
}

static void
torso_def(const struct behave *b, const struct state *s, struct ik_constraint_def *d)
{
	*d = ik_constraint_default_def();
	d->effector_site = b->s_chest;
	d->start_joint = b->j_spine0;
	d->pos = IK_POS_NONE;
	d->pos_weight = 0;
	d->weight = W_TORSO;
	d->goal_xf = s->site_xf[b->s_chest];
	if (b->p.torso == TORSO_HOLD_GLOBAL) {
		d->ori = IK_FRAME;
	} else {
		d->ori = IK_DIRECTION;
		d->effector_axis[2] = 0, d->effector_axis[1] = 1;
		d->goal_axis[0] = 0, d->goal_axis[1] = 1, d->goal_axis[2] = 0;
		xform_identity(&d->goal_xf);
	}
	d->enabled = b->p.torso != TORSO_FREE;
}

static void
aim_def(int site, int start, const double point[3], int on, struct ik_constraint_def *d)
{
	*d = ik_constraint_default_def();
	d->effector_site = site;
	d->start_joint = start;
	d->pos = IK_POS_NONE;
	d->ori = IK_AIM;
	d->pos_weight = 0;
	d->effector_axis[0] = d->effector_axis[1] = 0, d->effector_axis[2] = 1;
	memcpy(d->goal_xf.p, point, sizeof d->goal_xf.p);
	d->enabled = on;
}

static void
hand_def(const struct behave *b, const struct model *m, const struct state *s, int side,
	 struct ik_constraint_def *d)
{
	*d = ik_constraint_default_def();
	d->effector_site = b->s_palm[side];
	d->start_joint = b->j_clav[side];
	d->group = 1; /* after the body (§D.1.5) */
	d->goal_xf = s->site_xf[b->s_palm[side]];
	d->enabled = b->p.hand[side] != HAND_FREE;
	switch (b->p.hand[side]) {
	case HAND_FREE:
	case HAND_HOLD_GLOBAL:
		d->ori = IK_FRAME;
		d->pos_weight = 0.5;
		break;
	case HAND_ON_HIPS: /* the palm on the side of the hip, elbows out: arms akimbo */
		d->goal_site = b->s_hip[side];
		xform_identity(&d->goal_xf);
		d->goal_xf.p[0] = (side ? -1 : 1) * 0.07;
		d->goal_xf.p[1] = 0.06;
		break;
	case HAND_ON_KNEES:
		d->goal_site = b->s_knee[side];
		xform_identity(&d->goal_xf);
		d->goal_xf.p[1] = 0.05;
		break;
	case HAND_ON_SITE:
		d->goal_site = b->p.hand_site[side] >= 0 && b->p.hand_site[side] < m->nsite
				       ? b->p.hand_site[side]
				       : -1;
		xform_identity(&d->goal_xf);
		d->ori = IK_FRAME;
		d->pos_weight = 0.5;
		d->enabled = d->goal_site >= 0;
		break;
	}
}

/* the balance constraint's goal from b->bal_point and the elevation */
static void
balance_goal(const struct behave *b, struct ik_constraint_def *d)
{
	d->pos = b->p.hold_elevation ? IK_POINT : IK_LINE;
	xform_identity(&d->goal_xf);
	d->goal_xf.p[0] = b->bal_point[0];
	d->goal_xf.p[1] = b->elevation;
	d->goal_xf.p[2] = b->bal_point[1];
}

int
behave_find_sites(struct behave *b, const struct model *m)
{
	static const char *const sfx[2] = { "l", "r" };
	char name[64];
	int bad = 0;
#define SITE(dst, fmt, side)                                                   \
	do {                                                                   \
		snprintf(name, sizeof name, fmt, sfx[side], sfx[side]);        \
		bad |= ((dst) = model_find_site(m, name)) < 0;                 \
	} while (0)
	for (int k = 0; k < 2; k++) {
		SITE(b->s_toe[k], "toes_%s.toe%.0s", k);
		SITE(b->s_heel[k], "foot_%s.heel%.0s", k);
		SITE(b->s_tip[k], "toes_%s.tip%.0s", k);
		SITE(b->s_eye[k], "eyeball_%s.gaze%.0s", k);
		SITE(b->s_palm[k], "hand_%s.palm%.0s", k);
		SITE(b->s_hip[k], "pelvis.hip_%s%.0s", k);
		SITE(b->s_knee[k], "shank_%s.knee%.0s", k);
		SITE(b->s_shoulder[k], "clavicle_%s.shoulder_%s", k);
		snprintf(name, sizeof name, "clavicle_%s", sfx[k]);
		bad |= (b->j_clav[k] = model_find_joint(m, name)) < 0;
		snprintf(name, sizeof name, "eye_%s", sfx[k]);
		bad |= (b->j_eye[k] = model_find_joint(m, name)) < 0;
	}
#undef SITE
	bad |= (b->s_pelvis = model_find_site(m, HUMAN_SITE_PELVIS)) < 0;
	bad |= (b->s_lower = model_find_site(m, HUMAN_SITE_LOWER_TORSO)) < 0;
	bad |= (b->s_chest = model_find_site(m, HUMAN_SITE_CHEST)) < 0;
	bad |= (b->s_head = model_find_site(m, HUMAN_SITE_HEAD)) < 0;
	bad |= (b->j_spine0 = model_find_joint(m, "spine_0")) < 0;
	bad |= (b->j_neck = model_find_joint(m, "spine_17")) < 0;
	return bad ? -1 : 0;
}

static int
root_site_of(const struct behave *b, enum balance_root r)
{
	return r == BALANCE_ROOT_LEFT_FOOT ? b->s_toe[0]
	       : r == BALANCE_ROOT_RIGHT_FOOT ? b->s_toe[1]
					      : b->s_lower;
}

/* roots the figure anew; the foot that was the root holds where it is */
static void
set_root(struct behave *b, const struct model *m, struct state *s, struct ik *ik,
	 enum balance_root r)
{
	if (r == b->root)
		return;
	kin_set_root(m, s, root_site_of(b, r));
	for (int k = 0; k < 2; k++) {
		struct ik_constraint_def d = *ik_get(ik, b->c_toe[k]);
		if (b->p.foot[k] == FOOT_PIVOT)
			memcpy(d.goal_xf.p, s->site_xf[b->s_toe[k]].p, sizeof d.goal_xf.p);
		else
			d.goal_xf = s->site_xf[b->s_toe[k]];
		ik_set_goal(ik, b->c_toe[k], &d.goal_xf);
	}
	b->root = r;
}

/* behave_attach's work on a zeroed b that may already carry its weights */
static int
attach(struct behave *b, const struct model *m, struct state *s, struct ik *ik,
       const struct behave_params *p)
{
	b->p = p ? *p : behave_default_params();
	if (behave_find_sites(b, m) < 0)
		return -1;
	kin_update(m, s);
	b->leg_length = s->site_xf[b->s_hip[0]].p[1];
	kin_set_root(m, s, b->s_toe[0]);
	b->root = BALANCE_ROOT_LEFT_FOOT;
	struct ik_constraint_def d;
	for (int k = 0; k < 2; k++) {
		toe_def(b, s, k, &d);
		b->c_toe[k] = ik_add(ik, m, &d);
		heel_def(b, s, k, &d);
		b->c_heel[k] = ik_add(ik, m, &d);
	}
	/* balance: the centre of mass, carried by the lower torso, over the balance point */
	if (measure(b, m, s) < 0)
		return -1;
	b->bal_x = b->bal.x;
	b->bal_z = b->bal.z;
	memcpy(b->bal_point, b->bal.point, sizeof b->bal_point);
	double com[3];
	behave_com(b, s, com); /* with the weights carried */
	b->elevation = com[1];
	d = ik_constraint_default_def();
	d.effector_site = b->s_lower;
	d.com_effector = 1;
	d.weight = W_BALANCE;
	balance_goal(b, &d);
	b->c_balance = ik_add(ik, m, &d);
	/* the pelvis: its orientation relative to the feet's heading */
	double head[9];
	mathx_rot_y(feet_heading(b, s), head);
	mathx_mat3_tmul(head, s->site_xf[b->s_pelvis].r, b->pelvis_turn);
	d = ik_constraint_default_def();
	d.effector_site = b->s_pelvis;
	d.pos = IK_POS_NONE;
	d.ori = IK_FRAME;
	d.pos_weight = 0;
	d.weight = W_PELVIS;
	d.goal_xf = s->site_xf[b->s_pelvis];
	b->c_pelvis = ik_add(ik, m, &d);
	torso_def(b, s, &d);
	b->c_torso = ik_add(ik, m, &d);
	aim_def(b->s_head, b->j_neck, b->p.head_point, b->p.fixate_head, &d);
	b->c_head = ik_add(ik, m, &d);
	for (int k = 0; k < 2; k++) {
		aim_def(b->s_eye[k], b->j_eye[k], b->p.eyes_point, b->p.fixate_eyes, &d);
		b->c_eye[k] = ik_add(ik, m, &d);
		hand_def(b, m, s, k, &d);
		b->c_hand[k] = ik_add(ik, m, &d);
	}
	memcpy(b->com_fixed, com, sizeof b->com_fixed);
	if (b->c_hand[1] < 0 || stance_limit_springs(ik, m, b->p.spring_angle, STANCE_SPRING_WEIGHT) < 0)
		return -1;
	behave_keep_constraints(b, ik);
	return 0;
}

int
behave_attach(struct behave *b, const struct model *m, struct state *s, struct ik *ik,
	      const struct behave_params *p)
{
	memset(b, 0, sizeof *b);
	return attach(b, m, s, ik, p);
}

int
behave_hold_posture(struct behave *b, const struct model *m, struct state *s, struct ik *ik)
{
	struct behave_params p = b->p;
	struct point_mass pm[POINT_MASS_MAX];
	int n = b->nmass, steps = b->steps_taken;
	memcpy(pm, b->mass, sizeof pm);
	memset(b, 0, sizeof *b);
	memcpy(b->mass, pm, sizeof pm);
	b->nmass = n;
	if (attach(b, m, s, ik, &p) < 0)
		return -1;
	b->steps_taken = steps;
	behave_set_params(b, m, s, ik, &p); /* seated: the root and the seat's balance */
	return 0;
}

void
behave_set_params(struct behave *b, const struct model *m, struct state *s, struct ik *ik,
		  const struct behave_params *p)
{
	b->p = *p;
	struct ik_constraint_def d;
	for (int k = 0; k < 2; k++) {
		toe_def(b, s, k, &d);
		ik_set(ik, m, b->c_toe[k], &d);
		heel_def(b, s, k, &d);
		ik_set(ik, m, b->c_heel[k], &d);
		aim_def(b->s_eye[k], b->j_eye[k], p->eyes_point, p->fixate_eyes, &d);
		ik_set(ik, m, b->c_eye[k], &d);
		hand_def(b, m, s, k, &d);
		ik_set(ik, m, b->c_hand[k], &d);
	}
	torso_def(b, s, &d);
	ik_set(ik, m, b->c_torso, &d);
	aim_def(b->s_head, b->j_neck, p->head_point, p->fixate_head, &d);
	ik_set(ik, m, b->c_head, &d);
	d = *ik_get(ik, b->c_balance);
	double com[3];
	behave_com(b, s, com);
	if (p->hold_elevation && d.pos != IK_POINT)
		b->elevation = com[1];
	balance_goal(b, &d);
	d.enabled = !p->seated; /* the seat bears the weight */
	ik_set(ik, m, b->c_balance, &d);
	if (p->seated)
		set_root(b, m, s, ik, BALANCE_ROOT_LOWER_TORSO);
	stance_limit_springs(ik, m, p->spring_angle, STANCE_SPRING_WEIGHT);
	if (p->root_through_com)
		memcpy(b->com_fixed, com, sizeof b->com_fixed);
}

static void step_start(struct behave *b, struct state *s, struct ik *ik, int side,
		       const struct xform *to);

/* ---- active behaviours ------------------------------------------------------ */

/* the balance point the figure holds: by its parameters when it follows the feet, else fixed */
static void
held_balance_point(const struct behave *b, double dest[2])
{
	if (b->p.balance_follows_feet)
		balance_point_of(&b->bal, b->bal_x, b->bal_z, dest);
	else
		memmove(dest, b->bal_point, sizeof b->bal_point);
}

/* the stepping foot on its way: a straight line, lifted in the middle */
static void
step_advance(struct behave *b, const struct model *m, struct state *s, struct ik *ik)
{
	struct behave_step *st = &b->step;
	st->frame++;
	double t = (double)st->frame / st->frames;
	if (t > 1)
		t = 1;
	struct xform g = st->to;
	for (int i = 0; i < 3; i++)
		g.p[i] = st->from.p[i] + t * (st->to.p[i] - st->from.p[i]);
	g.p[1] += STEP_LIFT * sin(M_PI * t);
	ik_set_goal(ik, b->c_toe[st->side], &g);
	if (st->frame < st->frames)
		return;
	/* down: the heel goes back to the floor, and the balance point, held still
	 * during the step, gets its parameters in the new support polygon */
	st->active = 0;
	b->steps_taken++;
	kin_update(m, s);
	measure(b, m, s);
	balance_params_of(&b->bal, b->bal_point, &b->bal_x, &b->bal_z);
	struct ik_constraint_def d;
	heel_def(b, s, st->side, &d);
	d.goal_xf.p[0] = s->site_xf[b->s_heel[st->side]].p[0];
	d.goal_xf.p[2] = s->site_xf[b->s_heel[st->side]].p[2];
	ik_set(ik, m, b->c_heel[st->side], &d);
}

/*
 * Take step when losing balance (§D.3.1): when the balance point leaves the
 * support polygon to the front or back, the foot bearing less weight steps
 * so that the balance point ends midway between the feet.
 */
static void
step_trigger(struct behave *b, const struct model *m, struct state *s, struct ik *ik)
{
	const struct balance *bal = &b->bal;
	if (b->root == BALANCE_ROOT_LOWER_TORSO || bal->npoly < 3 || bal->margin >= 0)
		return;
	/* a heel left the floor and the polygon shrank to the toes under the
	 * centre of mass: with the balance point still inside, this frame's
	 * solve carries the weight over the balls of the feet (tiptoe), no step */
	double goal[2];
	held_balance_point(b, goal);
	int heel_up = s->site_xf[b->s_heel[0]].p[1] > BALANCE_CONTACT ||
		      s->site_xf[b->s_heel[1]].p[1] > BALANCE_CONTACT;
	if (heel_up && balance_margin(bal, goal) >= 0)
		return;
	/* out past a foot's outer edge rather than the front or back */
	int to_side = (bal->x < 0 || bal->x > 1) && fabs(bal->z) <= 1;
	if (!to_side && fabs(bal->z) <= 1)
		return;
	/* going down into a squat is no loss of balance: the feet stay (§5.5.2) */
	double standing = 0.75 * b->leg_length;
	if (s->com[1] < standing || /* the body's own height, as for rooting */ (b->p.hold_elevation && b->elevation < standing))
		return;
	/* to the front or back the foot bearing less weight steps; to the side
	 * only the support foot, the one the balance point went past, can */
	int side = to_side ? (bal->x < 0 ? 0 : 1) : bal->weight_l > 0.5 ? 1 : 0;
	const double *support = side ? bal->ref_l : bal->ref_r, *moving = side ? bal->ref_r : bal->ref_l;
	double target[2] = { 2 * bal->point[0] - support[0], 2 * bal->point[1] - support[1] };
	struct xform to = s->site_xf[b->s_toe[side]];
	to.p[0] += target[0] - moving[0];
	to.p[2] += target[1] - moving[1];
	/* the figure stands on the other foot while this one is in the air */
	set_root(b, m, s, ik, side ? BALANCE_ROOT_LEFT_FOOT : BALANCE_ROOT_RIGHT_FOOT);
	step_start(b, s, ik, side, &to);
}

static void
step_start(struct behave *b, struct state *s, struct ik *ik, int side, const struct xform *to)
{
	struct behave_step *st = &b->step;
	st->active = 1;
	st->side = side;
	st->frame = 0;
	st->frames = b->p.step_frames > 0 ? b->p.step_frames : 20;
	st->from = s->site_xf[b->s_toe[side]];
	st->to = *to;
	ik_enable(ik, b->c_heel[side], 0); /* the heel lifts with the foot */
}

/*
 * Take step when pelvis is twisted (§D.3.2): past the limit the legs can
 * turn no further, so the foot not rooted steps round the other, turned by
 * the twist, and the feet's heading catches up with the pelvis.
 */
static void
twist_trigger(struct behave *b, struct state *s, struct ik *ik)
{
	if (b->root == BALANCE_ROOT_LOWER_TORSO)
		return;
	const double *r = s->site_xf[b->s_pelvis].r;
	double twist = atan2(r[2], r[8]) - feet_heading(b, s);
	twist = atan2(sin(twist), cos(twist));
	if (fabs(twist) <= b->p.twist_limit)
		return;
	int side = b->root == BALANCE_ROOT_LEFT_FOOT ? 1 : 0;
	const double *pivot = s->site_xf[b->s_toe[1 - side]].p;
	struct xform to = s->site_xf[b->s_toe[side]];
	double turn[9], rel[3] = { to.p[0] - pivot[0], 0, to.p[2] - pivot[2] };
	mathx_rot_y(twist, turn);
	to.p[0] = pivot[0] + turn[0] * rel[0] + turn[2] * rel[2];
	to.p[2] = pivot[2] + turn[6] * rel[0] + turn[8] * rel[2];
	mathx_mat3_mul(turn, to.r, to.r);
	step_start(b, s, ik, side, &to);
}

/* ---- the frame -------------------------------------------------------------- */

struct ik_result
behave_frame(struct behave *b, const struct model *m, struct state *s, struct ik *ik,
	     const struct ik_options *opt, const struct ik_clock *clock)
{
	measure(b, m, s);
	/* automatic rooting (§5.4.2.4), never in the middle of a step */
	if (b->p.auto_root && !b->step.active && !b->p.root_through_com && !b->p.seated) {
		double com_h = s->com[1]; /* the body's own: how low it is, whatever it carries */
		set_root(b, m, s, ik, balance_choose_root(&b->bal, com_h, b->leg_length, b->root));
	}
	/* active behaviours: advance a step under way, or start one */
	if (b->step.active)
		step_advance(b, m, s, ik);
	if (!b->step.active && b->p.step_when_losing_balance)
		step_trigger(b, m, s, ik);
	if (!b->step.active && b->p.step_when_twisted)
		twist_trigger(b, s, ik);
	/* balance point follows feet (§D.2.1): the same x and z whatever the feet do */
	if (!b->step.active)
		held_balance_point(b, b->bal_point);
	struct ik_constraint_def d = *ik_get(ik, b->c_balance);
	balance_goal(b, &d);
	ik_set_goal(ik, b->c_balance, &d.goal_xf);
	/* pelvis follows feet orientation (§D.2.3) */
	if (b->p.pelvis_follows_feet) {
		struct xform g;
		double head[9];
		xform_identity(&g);
		mathx_rot_y(feet_heading(b, s), head);
		mathx_mat3_mul(head, b->pelvis_turn, g.r);
		ik_set_goal(ik, b->c_pelvis, &g);
	}
	ik_set_point_masses(ik, m, b->mass, b->nmass); /* checked when set */
	struct ik_result r = ik_solve(ik, m, s, opt, clock);
	/* root through the centre of mass (§D.2.5): the whole figure slides back under it */
	if (b->p.root_through_com) {
		double com[3];
		behave_com(b, s, com);
		for (int i = 0; i < 3; i++)
			s->root_xf.p[i] += b->com_fixed[i] - com[i];
		kin_update(m, s);
	}
	measure(b, m, s);
	/* stability as data: the alert's edge since the last solve told one, for the loop to tell */
	b->stability_changed = b->stability_low != b->alert_low;
	b->alert_low = b->stability_low;
	return r;
}

/* ---- manipulation primitives ---------------------------------------------------- */

/*
 * Foot orientation follows balance line (§D.2.2): the foot keeps its angle
 * to the line from the other foot, so a foot stepping forward turns toward
 * the stationary one as a person turning that way would. The turn is about
 * the toes, added to whatever turn the goal already carries.
 */
static void
follow_balance_line(struct behave *b, const struct model *m, struct state *s, int side,
		    struct xform *g)
{
	if (measure(b, m, s) < 0)
		return;
	const double *fixed = side ? b->bal.ref_l : b->bal.ref_r, *moving = side ? b->bal.ref_r : b->bal.ref_l;
	const double *toe = s->site_xf[b->s_toe[side]].p;
	double now[2] = { moving[0] - fixed[0], moving[1] - fixed[1] };
	double then[2] = { now[0] + g->p[0] - toe[0], now[1] + g->p[2] - toe[2] };
	if (hypot(then[0], then[1]) < 1e-6 || hypot(now[0], now[1]) < 1e-6)
		return;
	double turn[9];
	mathx_rot_y(atan2(then[0], then[1]) - atan2(now[0], now[1]), turn);
	mathx_mat3_mul(turn, g->r, g->r);
}

void
behave_move_foot(struct behave *b, const struct model *m, struct state *s, struct ik *ik, int side,
		 const struct xform *goal)
{
	/* the support goes to the other foot (§5.5.1) */
	enum balance_root other = side ? BALANCE_ROOT_LEFT_FOOT : BALANCE_ROOT_RIGHT_FOOT;
	if (b->root != BALANCE_ROOT_LOWER_TORSO)
		set_root(b, m, s, ik, other);
	struct xform g = *goal;
	if (b->p.foot_follows_line && !b->p.seated)
		follow_balance_line(b, m, s, side, &g);
	behave_set_foot_goal(b, ik, side, &g);
}

int
behave_foot_site(const struct behave *b, int side)
{
	return b->p.seated ? b->s_heel[side] : b->s_toe[side];
}

void
behave_set_foot_goal(struct behave *b, struct ik *ik, int side, const struct xform *goal)
{
	if (b->p.seated) {
		ik_set_goal(ik, b->c_heel[side], goal);
		return;
	}
	ik_set_goal(ik, b->c_toe[side], goal);
	struct ik_constraint_def d = *ik_get(ik, b->c_heel[side]);
	d.goal_xf.p[0] = goal->p[0], d.goal_xf.p[2] = goal->p[2];
	ik_set_goal(ik, b->c_heel[side], &d.goal_xf);
}

void
behave_move_com(struct behave *b, const struct model *m, struct state *s, struct ik *ik,
		double dx, double dz, double dy)
{
	measure(b, m, s);
	double target[2] = { b->bal.point[0] + dx, b->bal.point[1] + dz };
	/* the new parameters are held from now on (§5.5.2) */
	balance_params_of(&b->bal, target, &b->bal_x, &b->bal_z);
	memcpy(b->bal_point, target, sizeof b->bal_point);
	if (dy != 0) { /* from now on the elevation is held, at its new height */
		if (!b->p.hold_elevation) {
			struct behave_params p = b->p;
			p.hold_elevation = 1;
			behave_set_params(b, m, s, ik, &p);
		}
		double com[3];
		behave_com(b, s, com);
		b->elevation = com[1] + dy;
	}
}

int
behave_bend_torso(struct behave *b, const struct model *m, struct state *s, struct ik *ik,
		  const double total[3], const struct spine_flavor *flavor)
{
	if (spine_apply(m, s, flavor, total, NULL) < 0)
		return -1;
	/* the bend is the torso's new orientation: hold it while balance moves the hips */
	struct behave_params p = b->p;
	p.torso = TORSO_HOLD_GLOBAL;
	behave_set_params(b, m, s, ik, &p);
	return 0;
}

void
behave_rotate_pelvis(struct behave *b, const struct model *m, struct state *s, struct ik *ik,
		     const double r[9])
{
	(void)m;
	(void)s;
	(void)ik;
	mathx_mat3_mul(r, b->pelvis_turn, b->pelvis_turn);
}

void
behave_move_hand(struct behave *b, const struct model *m, struct state *s, struct ik *ik, int side,
		 const struct xform *goal, int from_wrist)
{
	char name[32];
	snprintf(name, sizeof name, "forearm_%s.wrist_ref", side ? "r" : "l");
	int wrist = model_find_site(m, name);
	int effector = from_wrist && wrist >= 0 ? wrist : b->s_palm[side];
	/* dragging: the same hold, only the goal moves (no chain is rebuilt) */
	if (b->p.hand[side] == HAND_HOLD_GLOBAL && ik_get(ik, b->c_hand[side])->effector_site == effector) {
		ik_set_goal(ik, b->c_hand[side], goal);
		return;
	}
	struct behave_params p = b->p;
	p.hand[side] = HAND_HOLD_GLOBAL;
	behave_set_params(b, m, s, ik, &p);
	struct ik_constraint_def d = *ik_get(ik, b->c_hand[side]);
	if (effector == wrist) { /* position from the lower forearm: the wrist stays out of it (§5.5.5) */
		d.effector_site = wrist;
		d.ori = IK_ORI_NONE;
		d.pos_weight = 1;
	}
	d.goal_xf = *goal;
	ik_set(ik, m, b->c_hand[side], &d);
}

/* v in the chest's frame (x left, y up, z forward) */
static void
in_chest(const struct behave *b, const struct state *s, const double v[3], double dest[3])
{
	const double *r = s->site_xf[b->s_chest].r;
	for (int i = 0; i < 3; i++)
		dest[i] = r[i] * v[0] + r[3 + i] * v[1] + r[6 + i] * v[2];
}

enum hand_region
behave_hand_region(const struct behave *b, const struct state *s, int side, const double p[3])
{
	const double sigma = side ? -1 : 1; /* the arm's outward direction along the chest's x */
	const double *sh = s->site_xf[b->s_shoulder[side]].p, *ch = s->site_xf[b->s_chest].p;
	double w[3] = { p[0] - sh[0], p[1] - sh[1], p[2] - sh[2] }, c[3] = { p[0] - ch[0], p[1] - ch[1], p[2] - ch[2] };
	double d[3], mid[3];
	in_chest(b, s, w, d);
	in_chest(b, s, c, mid);
	double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
	if (sigma * mid[0] < -0.05) /* past the body's midline */
		return REGION_ACROSS;
	if (len < 1e-9 || d[1] / len < -0.7) /* within 45 degrees of straight down */
		return REGION_HANG;
	return sigma * d[0] / len > 0.7 ? REGION_SIDE : REGION_FORWARD_UP;
}

void
behave_predict_hand(const struct behave *b, const struct state *s, int side, struct xform *goal)
{
	const double *palm = s->site_xf[b->s_palm[side]].p;
	enum hand_region to = behave_hand_region(b, s, side, goal->p);
	if (to == behave_hand_region(b, s, side, palm))
		return;
	const double sigma = side ? -1 : 1;
	const double *r = s->site_xf[b->s_chest].r, *sh = s->site_xf[b->s_shoulder[side]].p;
	double X[3] = { r[0], r[3], r[6] }, Z[3] = { r[2], r[5], r[8] };
	/* the fingers carry on the line of the arm, shoulder to hand */
	double f[3] = { goal->p[0] - sh[0], goal->p[1] - sh[1], goal->p[2] - sh[2] };
	double fl = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
	if (fl < 1e-6)
		return;
	double n[3]; /* where the palm should face */
	for (int i = 0; i < 3; i++) {
		f[i] /= fl;
		n[i] = to == REGION_SIDE ? Z[i] : to == REGION_ACROSS ? -Z[i] : -sigma * X[i];
	}
	double along = n[0] * f[0] + n[1] * f[1] + n[2] * f[2];
	for (int i = 0; i < 3; i++)
		n[i] -= along * f[i];
	double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
	if (nl < 1e-6)
		return;
	/* the palm site's axes: fingers -y, palm toward -sigma x, thumb z (human.c) */
	double cx[3], cy[3], cz[3];
	for (int i = 0; i < 3; i++) {
		cx[i] = -sigma * n[i] / nl;
		cy[i] = -f[i];
	}
	cz[0] = cx[1] * cy[2] - cx[2] * cy[1];
	cz[1] = cx[2] * cy[0] - cx[0] * cy[2];
	cz[2] = cx[0] * cy[1] - cx[1] * cy[0];
	for (int i = 0; i < 3; i++) {
		goal->r[3 * i] = cx[i];
		goal->r[3 * i + 1] = cy[i];
		goal->r[3 * i + 2] = cz[i];
	}
}

void
behave_move_head(struct behave *b, struct ik *ik, const double point[3])
{
	memcpy(b->p.head_point, point, sizeof b->p.head_point);
	b->p.fixate_head = 1;
	struct xform g;
	xform_identity(&g);
	memcpy(g.p, point, sizeof g.p);
	ik_set_goal(ik, b->c_head, &g);
	ik_enable(ik, b->c_head, 1);
}

void
behave_move_eyes(struct behave *b, struct ik *ik, const double point[3])
{
	memcpy(b->p.eyes_point, point, sizeof b->p.eyes_point);
	b->p.fixate_eyes = 1;
	struct xform g;
	xform_identity(&g);
	memcpy(g.p, point, sizeof g.p);
	for (int k = 0; k < 2; k++) {
		ik_set_goal(ik, b->c_eye[k], &g);
		ik_enable(ik, b->c_eye[k], 1);
	}
}

/* ---- the natural constraints' table: kept while the solver is refilled ---- */

/* the constraints' index fields in their fixed order */
int *
behave_slot(struct behave *b, int k)
{
	int *slots[BEHAVE_NCON] = { &b->c_toe[0], &b->c_toe[1], &b->c_heel[0], &b->c_heel[1],
				    &b->c_balance, &b->c_pelvis, &b->c_torso, &b->c_head,
				    &b->c_eye[0], &b->c_eye[1], &b->c_hand[0], &b->c_hand[1] };
	return slots[k];
}

void
behave_keep_constraints(struct behave *b, const struct ik *ik)
{
	if (b->detached) /* def[] is already the truth */
		return;
	for (int k = 0; k < BEHAVE_NCON; k++) {
		const struct ik_constraint_def *d = ik_get(ik, *behave_slot(b, k));
		if (d)
			b->def[k] = *d;
	}
}

int
behave_restore_constraints(struct behave *b, const struct model *m, struct ik *ik)
{
	for (int k = 0; k < BEHAVE_NCON; k++)
		if ((*behave_slot(b, k) = ik_add(ik, m, &b->def[k])) < 0)
			return -1;
	b->detached = 0;
	return 0;
}

const struct ik_constraint_def *
behave_def(const struct behave *b, const struct ik *ik, int k)
{
	if (b->detached)
		return &b->def[k];
	const struct ik_constraint_def *d = ik_get(ik, *behave_slot((struct behave *)b, k));
	return d ? d : &b->def[k];
}
