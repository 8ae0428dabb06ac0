/*
 * reba.h - REBA, the Rapid Entire Body Assessment (Hignett & McAtamney,
 * Applied Ergonomics 31(2):201-205, 2000), scored from measured body angles
 * with its whole derivation.
 */
#ifndef POSTURE_REBA_H
#define POSTURE_REBA_H

#include "assess/assess.h"
#include "assess/body_angles.h"

/* what the posture cannot show: the observer says it */
struct reba_options {
	int side;       /* enum assess_side_choice */
	double load_kg; /* load or force */
	int coupling;   /* 0 good, 1 fair, 2 poor, 3 unacceptable */
	int activity;   /* 0..3: how many of static > 1 min, repeated > 4/min, rapid large changes */
	int shock;      /* shock or rapid build-up of force (load +1) */
	int arm_supported; /* the arm supported, the person leaning, or gravity-assisted (upper arm -1) */
};

/* side worse, 0 kg, good coupling, no activity, no shock, arm not supported */
struct reba_options reba_options_default(void);

/*
 * Scores a with the thresholds cfg leaves open into r: parts trunk, neck,
 * legs, upper_arm, lower_arm, wrist (body) and load, coupling, activity
 * (add-ons); look-ups A, B, C; the REBA score 1-15 and the action level
 * 0-4. Side "worse" scores both arms and keeps the higher score (the right
 * arm on ties).
 */
void reba_score(const struct body_angles *a, const struct assess_config *cfg,
		const struct reba_options *o, struct assess_result *r);

#endif
