/*
 * behave_store.c - a behaviour's parameters and state packed as numbers,
 * for sessions and the journal, and rebuilt from them.
 */
#include "pose/behave.h"

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

int
behave_unpack(struct behave *b, const struct model *m, const double *v, int nv)
{
	struct behave fresh;
	memset(&fresh, 0, sizeof fresh);
	if (nv != behave_pack(&fresh, NULL, 0) || behave_find_sites(&fresh, m) < 0)
		return -1;
	int n = 0;
	struct behave_params *p = &fresh.p;
	for (int k = 0; k < 2; k++) {
		p->foot[k] = (enum foot_behavior)PACK_GET();
		p->heel[k] = (enum heel_behavior)PACK_GET();
		p->hand[k] = (enum hand_behavior)PACK_GET();
		p->hand_site[k] = (int)PACK_GET();
	}
	p->hold_elevation = (int)PACK_GET();
	p->torso = (enum torso_behavior)PACK_GET();
	p->fixate_head = (int)PACK_GET();
	p->fixate_eyes = (int)PACK_GET();
	for (int i = 0; i < 3; i++) {
		p->head_point[i] = PACK_GET();
		p->eyes_point[i] = PACK_GET();
	}
	p->spring_angle = PACK_GET();
	p->balance_follows_feet = (int)PACK_GET();
	p->pelvis_follows_feet = (int)PACK_GET();
	p->auto_root = (int)PACK_GET();
	p->root_through_com = (int)PACK_GET();
	p->step_when_losing_balance = (int)PACK_GET();
	p->step_when_twisted = (int)PACK_GET();
	p->twist_limit = PACK_GET();
	p->step_frames = (int)PACK_GET();
	p->foot_follows_line = (int)PACK_GET();
	p->hands_laban = (int)PACK_GET();
	p->seated = (int)PACK_GET();
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
	fresh.root = (enum balance_root)PACK_GET();
	fresh.steps_taken = (int)PACK_GET();
	fresh.step.active = (int)PACK_GET();
	fresh.step.side = (int)PACK_GET();
	fresh.step.frame = (int)PACK_GET();
	fresh.step.frames = (int)PACK_GET();
	for (int i = 0; i < 3; i++) {
		fresh.step.from.p[i] = PACK_GET();
		fresh.step.to.p[i] = PACK_GET();
	}
	for (int i = 0; i < 9; i++) {
		fresh.step.from.r[i] = PACK_GET();
		fresh.step.to.r[i] = PACK_GET();
	}
	/* enumerations and sides within their ranges, or the numbers were not ours */
	for (int k = 0; k < 2; k++)
		if ((unsigned)p->foot[k] > FOOT_HOLD_GLOBAL || (unsigned)p->heel[k] > HEEL_ALLOW_RISE ||
		    (unsigned)p->hand[k] > HAND_ON_SITE || p->hand_site[k] >= m->nsite)
			return -1;
	if ((unsigned)p->torso > TORSO_FREE || (unsigned)fresh.root > BALANCE_ROOT_LOWER_TORSO ||
	    (unsigned)fresh.step.side > 1)
		return -1;
	memcpy(fresh.def, b->def, sizeof fresh.def);
	*b = fresh;
	b->detached = 1;
	for (int k = 0; k < BEHAVE_NCON; k++)
		*behave_slot(b, k) = -1;
	return 0;
}
