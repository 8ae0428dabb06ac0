/*
 * behave_store.c - a behaviour's parameters and state packed as numbers,
 * for sessions and the journal, and rebuilt from them.
 */
#include "pose/behave.h"

#include <limits.h>
#include <math.h>
#include <string.h>

#include "pose/behave_internal.h"

/* the packed layout: parameters, then state; one list so a count checks it */
#define PACK_PUT(x) (n < max ? (dest[n++] = (double)(x)) : (n++, 0.0))

int
behave_pack(const struct behave *b, double *dest, int max)
{
	int n = 0;
	const struct behave_params *p = &b->p;
	for (int k = 0; k < 2; k++) {
		PACK_PUT(p->foot[k]);
		PACK_PUT(p->heel[k]);
		PACK_PUT(p->hand[k]);
		PACK_PUT(p->hand_site[k]);
	}
	PACK_PUT(p->hold_elevation);
	PACK_PUT(p->torso);
	PACK_PUT(p->fixate_head);
	PACK_PUT(p->fixate_eyes);
	for (int i = 0; i < 3; i++) {
		PACK_PUT(p->head_point[i]);
		PACK_PUT(p->eyes_point[i]);
	}
	PACK_PUT(p->spring_angle);
	PACK_PUT(p->balance_follows_feet);
	PACK_PUT(p->pelvis_follows_feet);
	PACK_PUT(p->auto_root);
	PACK_PUT(p->root_through_com);
	PACK_PUT(p->step_when_losing_balance);
	PACK_PUT(p->step_when_twisted);
	PACK_PUT(p->twist_limit);
	PACK_PUT(p->step_frames);
	PACK_PUT(p->foot_follows_line);
	PACK_PUT(p->hands_laban);
	PACK_PUT(p->seated);
	PACK_PUT(p->stability_threshold);
	PACK_PUT(b->leg_length);
	PACK_PUT(b->bal_x);
	PACK_PUT(b->bal_z);
	PACK_PUT(b->bal_point[0]);
	PACK_PUT(b->bal_point[1]);
	PACK_PUT(b->elevation);
	for (int i = 0; i < 9; i++)
		PACK_PUT(b->pelvis_turn[i]);
	for (int i = 0; i < 3; i++)
		PACK_PUT(b->com_fixed[i]);
	PACK_PUT(b->root);
	PACK_PUT(b->steps_taken);
	PACK_PUT(b->step.active);
	PACK_PUT(b->step.side);
	PACK_PUT(b->step.frame);
	PACK_PUT(b->step.frames);
	for (int i = 0; i < 3; i++) {
		PACK_PUT(b->step.from.p[i]);
		PACK_PUT(b->step.to.p[i]);
	}
	for (int i = 0; i < 9; i++) {
		PACK_PUT(b->step.from.r[i]);
		PACK_PUT(b->step.to.r[i]);
	}
	return n;
}

#define PACK_GET() (v[n++])

/*
 * v as a whole number in [lo, hi]; else lo, with *bad set: the numbers were
 * not ours (a cast of any other double to int is undefined)
 */
static int
whole(double v, int lo, int hi, int *bad)
{
	if (!(v >= lo && v <= hi) || v != floor(v)) {
		*bad = 1;
		return lo;
	}
	return (int)v;
}

#define INT_GET(lo, hi) whole(PACK_GET(), (lo), (hi), &bad)
#define FLAG_GET() INT_GET(0, 1)

int
behave_unpack(struct behave *b, const struct model *m, const double *v, int nv)
{
	struct behave fresh;
	memset(&fresh, 0, sizeof fresh);
	if (nv != behave_pack(&fresh, NULL, 0) || behave_find_sites(&fresh, m) < 0)
		return -1;
	int n = 0, bad = 0;
	struct behave_params *p = &fresh.p;
	for (int k = 0; k < 2; k++) {
		p->foot[k] = (enum foot_behavior)INT_GET(FOOT_PIVOT, FOOT_HOLD_GLOBAL);
		p->heel[k] = (enum heel_behavior)INT_GET(HEEL_KEEP_ON_FLOOR, HEEL_ALLOW_RISE);
		p->hand[k] = (enum hand_behavior)INT_GET(HAND_FREE, HAND_ON_SITE);
		p->hand_site[k] = INT_GET(-1, m->nsite - 1);
	}
	p->hold_elevation = FLAG_GET();
	p->torso = (enum torso_behavior)INT_GET(TORSO_KEEP_VERTICAL, TORSO_FREE);
	p->fixate_head = FLAG_GET();
	p->fixate_eyes = FLAG_GET();
	for (int i = 0; i < 3; i++) {
		p->head_point[i] = PACK_GET();
		p->eyes_point[i] = PACK_GET();
	}
	p->spring_angle = PACK_GET();
	p->balance_follows_feet = FLAG_GET();
	p->pelvis_follows_feet = FLAG_GET();
	p->auto_root = FLAG_GET();
	p->root_through_com = FLAG_GET();
	p->step_when_losing_balance = FLAG_GET();
	p->step_when_twisted = FLAG_GET();
	p->twist_limit = PACK_GET();
	p->step_frames = INT_GET(0, INT_MAX - 1); /* 0: the default's */
	p->foot_follows_line = FLAG_GET();
	p->hands_laban = FLAG_GET();
	p->seated = FLAG_GET();
	p->stability_threshold = PACK_GET();
	fresh.leg_length = PACK_GET();
	fresh.bal_x = PACK_GET();
	fresh.bal_z = PACK_GET();
	fresh.bal_point[0] = PACK_GET();
	fresh.bal_point[1] = PACK_GET();
	fresh.elevation = PACK_GET();
	for (int i = 0; i < 9; i++)
		fresh.pelvis_turn[i] = PACK_GET();
	for (int i = 0; i < 3; i++)
		fresh.com_fixed[i] = PACK_GET();
	fresh.root = (enum balance_root)INT_GET(BALANCE_ROOT_LEFT_FOOT, BALANCE_ROOT_LOWER_TORSO);
	fresh.steps_taken = INT_GET(0, INT_MAX - 1);
	fresh.step.active = FLAG_GET();
	fresh.step.side = INT_GET(0, 1);
	/* a step's frame counts up to its frames: both within int, the count one past too */
	fresh.step.frame = INT_GET(0, INT_MAX - 1);
	fresh.step.frames = INT_GET(0, INT_MAX - 1);
	for (int i = 0; i < 3; i++) {
		fresh.step.from.p[i] = PACK_GET();
		fresh.step.to.p[i] = PACK_GET();
	}
	for (int i = 0; i < 9; i++) {
		fresh.step.from.r[i] = PACK_GET();
		fresh.step.to.r[i] = PACK_GET();
	}
	if (bad || fresh.step.frame > fresh.step.frames || (fresh.step.active && !fresh.step.frames))
		return -1;
	memcpy(fresh.def, b->def, sizeof fresh.def);
	/* the weights are the environment's, not packed: they stay, and the next ones set
	 * are taken as those the numbers were measured with */
	memcpy(fresh.mass, b->mass, sizeof fresh.mass);
	fresh.nmass = b->nmass;
	fresh.masses_adopt = 1;
	*b = fresh;
	b->detached = 1;
	for (int k = 0; k < BEHAVE_NCON; k++)
		*behave_slot(b, k) = -1;
	return 0;
}
