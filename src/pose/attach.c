/* attach.c - grab object and hold local location (Table D.4) */
#include "pose/attach.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "figure/kin.h"

/* the limb's effector: the palm, or the toes (the heel when seated) */
static int
effector_site(const struct behave *b, enum attach_limb limb, int side)
{
	return limb == ATTACH_HAND ? b->s_palm[side] : behave_foot_site(b, side);
}

int
attach_find(const struct env *e, int fig, enum attach_limb limb, int side)
{
	for (int i = 0; i < ENV_MAX_ATTACH; i++) {
		const struct env_attach *a = &e->att[i];
		if (a->used && a->fig == fig && a->limb == limb && a->side == side)
			return i;
	}
	return -1;
}

/* does figure holder hold on to figure held by any limb? (the other way round is a loop) */
static int
linked(const struct env *e, int holder, int held)
{
	for (int i = 0; i < ENV_MAX_ATTACH; i++) {
		const struct env_attach *a = &e->att[i];
		if (a->used && a->fig == holder && a->obj == held)
			return 1;
	}
	return 0;
}

/* a figure grabbed by someone is moved by that hand alone */
static int
grabbed(const struct env *e, int obj)
{
	for (int i = 0; i < ENV_MAX_ATTACH; i++)
		if (e->att[i].used && e->att[i].kind == ATTACH_GRAB && e->att[i].obj == obj)
			return 1;
	return 0;
}

int
attach_add(struct env *e, const struct env_attach *a)
{
	if (a->fig < 0 || a->fig >= ENV_MAX_FIGURES || a->obj < 0 || a->obj >= ENV_MAX_FIGURES ||
	    !e->fig[a->fig].gen || !e->fig[a->obj].gen || !e->fig[a->fig].behave || a->fig == a->obj ||
	    (unsigned)a->side > 1 || (unsigned)a->limb > ATTACH_FOOT || (unsigned)a->kind > ATTACH_LOCAL ||
	    (a->kind == ATTACH_GRAB && a->limb != ATTACH_HAND) || a->seg < 0 ||
	    a->seg >= e->fig[a->obj].model->nseg || attach_find(e, a->fig, a->limb, a->side) >= 0)
		return -1;
	for (int i = 0; i < ENV_MAX_ATTACH; i++)
		if (!e->att[i].used) {
			e->att[i] = *a;
			e->att[i].used = 1;
			return 0;
		}
	return -1;
}

/* checks common to both kinds; 0, or -1 with err */
static int
check(struct env *e, int fig, int obj, char *err, size_t errlen)
{
	struct env_figure *f = &e->fig[fig], *o = &e->fig[obj];
	if (!f->behave) {
		snprintf(err, errlen, "behaviours are off for %s (behave %s on)", f->name, f->name);
		return -1;
	}
	if (fig == obj) {
		snprintf(err, errlen, "%s cannot hold on to itself", f->name);
		return -1;
	}
	if (o->behave) {
		snprintf(err, errlen, "%s behaves on its own: it cannot be held", o->name);
		return -1;
	}
	if (linked(e, obj, fig)) {
		snprintf(err, errlen, "%s already holds on to %s", o->name, f->name);
		return -1;
	}
	return 0;
}

int
attach_grab(struct env *e, int fig, int side, int obj, char *err, size_t errlen)
{
	if (check(e, fig, obj, err, errlen) < 0)
		return -1;
	if (grabbed(e, obj) || attach_find(e, fig, ATTACH_HAND, side) >= 0) {
		snprintf(err, errlen, "%s is held already, or the hand holds something (release it)",
			 e->fig[obj].name);
		return -1;
	}
	struct env_figure *f = &e->fig[fig], *o = &e->fig[obj];
	kin_update(f->model, f->state);
	kin_update(o->model, o->state);
	struct env_attach a = { .kind = ATTACH_GRAB, .limb = ATTACH_HAND, .fig = fig, .side = side,
				.obj = obj, .seg = 0 };
	struct xform palm_inv;
	xform_inv(&f->state->site_xf[effector_site(f->behave, ATTACH_HAND, side)], &palm_inv);
	xform_mul(&palm_inv, &o->state->seg_xf[0], &a.rel);
	return attach_add(e, &a) < 0 ? (snprintf(err, errlen, "too many attachments"), -1) : 0;
}

int
attach_local(struct env *e, int fig, enum attach_limb limb, int side, int obj, int seg, char *err,
	     size_t errlen)
{
	if (check(e, fig, obj, err, errlen) < 0)
		return -1;
	struct env_figure *f = &e->fig[fig], *o = &e->fig[obj];
	if (seg < 0 || seg >= o->model->nseg) {
		snprintf(err, errlen, "%s has no such segment", o->name);
		return -1;
	}
	attach_release(e, fig, limb, side);
	kin_update(f->model, f->state);
	kin_update(o->model, o->state);
	const struct xform *now = &f->state->site_xf[effector_site(f->behave, limb, side)];
	struct env_attach a = { .kind = ATTACH_LOCAL, .limb = limb, .fig = fig, .side = side,
				.obj = obj, .seg = seg };
	struct xform seg_inv;
	xform_inv(&o->state->seg_xf[seg], &seg_inv);
	xform_mul(&seg_inv, now, &a.rel);
	/* the limb holds where it is now; from the next frame on, where the object takes it */
	if (limb == ATTACH_HAND)
		behave_move_hand(f->behave, f->model, f->state, f->ik, side, now, 0);
	else
		behave_move_foot(f->behave, f->model, f->state, f->ik, side, now);
	return attach_add(e, &a) < 0 ? (snprintf(err, errlen, "too many attachments"), -1) : 0;
}

int
attach_release(struct env *e, int fig, enum attach_limb limb, int side)
{
	int i = attach_find(e, fig, limb, side);
	if (i < 0)
		return 0;
	memset(&e->att[i], 0, sizeof e->att[i]);
	return 1;
}

void
attach_release_all(struct env *e, int fig)
{
	for (int i = 0; i < ENV_MAX_ATTACH; i++)
		if (e->att[i].used && e->att[i].fig == fig)
			memset(&e->att[i], 0, sizeof e->att[i]);
}

/*
 * Moves a whole figure rigidly so that the frame now (one of its own) lands
 * on goal. Returns 1 when it moved; a figure already there (to rounding) is
 * left alone, so a still hand lets the frames settle.
 */
static int
carry(const struct model *m, struct state *s, const struct xform *now, const struct xform *goal)
{
	double off = 0;
	for (int i = 0; i < 3; i++)
		off = fmax(off, fabs(goal->p[i] - now->p[i]));
	for (int i = 0; i < 9; i++)
		off = fmax(off, fabs(goal->r[i] - now->r[i]));
	if (off < 1e-12)
		return 0;
	struct xform delta, root;
	xform_mul_inv(goal, now, &delta);
	xform_mul(&delta, &s->root_xf, &root);
	/* a rotation again: the inverse above is the transpose, so a root off by e comes out
	 * off by 2e, and a figure carried frame after frame would double it each time */
	double q[4];
	mathx_mat_to_quat(root.r, q);
	double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
	for (int i = 0; i < 4; i++)
		q[i] /= n;
	mathx_quat_to_mat(q, root.r);
	s->root_xf = root;
	kin_update(m, s);
	return 1;
}

void
attach_before_solve(struct env *e, int fig)
{
	struct env_figure *f = &e->fig[fig];
	struct behave *b = f->behave;
	for (int i = 0; i < ENV_MAX_ATTACH; i++) {
		const struct env_attach *a = &e->att[i];
		if (!a->used || a->fig != fig || a->kind != ATTACH_LOCAL || !b)
			continue;
		struct xform goal;
		xform_mul(&e->fig[a->obj].state->seg_xf[a->seg], &a->rel, &goal);
		if (a->limb == ATTACH_HAND) {
			ik_set_goal(f->ik, b->c_hand[a->side], &goal);
			continue;
		}
		/* a foot the figure stands on rides along with the object, body and all */
		enum balance_root on = a->side ? BALANCE_ROOT_RIGHT_FOOT : BALANCE_ROOT_LEFT_FOOT;
		if (b->root == on)
			carry(f->model, f->state, &f->state->site_xf[b->s_toe[a->side]], &goal);
		behave_set_foot_goal(b, f->ik, a->side, &goal);
	}
}

int
attach_after_solve(struct env *e, int fig)
{
	const struct env_figure *f = &e->fig[fig];
	int moved = 0;
	for (int i = 0; i < ENV_MAX_ATTACH; i++) {
		const struct env_attach *a = &e->att[i];
		if (!a->used || a->fig != fig || a->kind != ATTACH_GRAB || !f->behave)
			continue;
		struct env_figure *o = &e->fig[a->obj];
		struct xform goal;
		xform_mul(&f->state->site_xf[effector_site(f->behave, ATTACH_HAND, a->side)], &a->rel, &goal);
		moved |= carry(o->model, o->state, &o->state->seg_xf[a->seg], &goal);
	}
	return moved;
}
