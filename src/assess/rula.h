/*
 * rula.h - RULA, the Rapid Upper Limb Assessment (McAtamney & Corlett,
 * Applied Ergonomics 24(2):91-99, 1993), scored from measured body angles
 * with its whole derivation.
 */
#ifndef POSTURE_RULA_H
#define POSTURE_RULA_H

#include "assess/assess.h"
#include "assess/body_angles.h"

/* what the posture cannot show: the observer says it (all "no" by default) */
struct rula_options {
	int side;           /* enum assess_side_choice */
	double load_kg;     /* the load or force the hands work against */
	int static_posture; /* held longer than a minute (muscle use +1, load static) */
	int repeated;       /* repeated more than 4 times a minute (muscle use +1, load repeated) */
	int arm_supported;  /* the arm's weight supported or the person leaning (upper arm -1) */
	int legs_supported; /* seated: legs and feet supported though no foot bears weight */
	int shock;          /* shock or rapid build-up of force (force/load 3) */
};

/* side worse, 0 kg, every flag no */
struct rula_options rula_options_default(void);

/*
 * Scores a (angles as body_angles.h measures them) with the thresholds cfg
 * leaves open into r: parts upper_arm, lower_arm, wrist, wrist_twist, neck,
 * trunk, legs (body) and muscle_use, force_load (add-ons); look-ups A, B, C;
 * the grand score 1-7 and the action level 1-4. Side "worse" scores both
 * arms and keeps the higher grand score (the right arm on ties); r->side
 * says which.
 */
void rula_score(const struct body_angles *a, const struct assess_config *cfg,
		const struct rula_options *o, struct assess_result *r);

#endif
