/*
 * stance.h - the standing human's natural constraints (§5.4, Appendix D):
 * both feet hold their place, the centre of mass stays over the balance
 * point, the chest stays vertical; hands are solved after the body
 * (§D.1.5). The behaviours build on this set; IK tests and benchmarks use
 * it as the standard whole-body problem.
 */
#ifndef POSTURE_STANCE_H
#define POSTURE_STANCE_H

#include "pose/ik.h"

struct stance {
	int foot_l, foot_r; /* hold global location (§D.1.1) */
	int balance;        /* centre of mass over the balance point (§4.5.2) */
	int torso;          /* keep vertical (§D.1.3) */
	int hand_l, hand_r; /* -1 until stance_hand */
	double balance_point[3];
};

/*
 * Roots the human through the left foot's balance site and adds the
 * standing constraints for its current posture, and the default limit
 * springs. The balance point is the
 * midpoint of the feet's balance sites (x = 0.5, z = 0 of Figure 5.2).
 * Returns 0, or -1 when the solver is full or the figure lacks a site.
 */
int stance_standing(struct ik *ik, const struct model *m, struct state *s, struct stance *dest);

/* default spring angle and weight of the knees and elbows (§D.1.6) */
#define STANCE_SPRING_ANGLE (10 * M_PI / 180)
#define STANCE_SPRING_WEIGHT 1e-4

/*
 * Puts limit springs on both knees and elbows, so that they stay off full
 * extension ("at ease" rather than "attention", §D.1.6). Returns 0 or -1.
 */
int stance_limit_springs(struct ik *ik, const struct model *m, double angle, double weight);

/*
 * Adds a hand constraint (group 1, after the body) on the palm, from the
 * clavicle, holding position and orientation; its goal starts at the
 * palm's current frame. Returns its index or -1.
 */
int stance_hand(struct ik *ik, const struct model *m, const struct state *s, struct stance *st,
		int right);

#endif
