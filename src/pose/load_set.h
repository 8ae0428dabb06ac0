/*
 * load_set.h - every external load acting on a figure this frame: its own
 * loads (add load) and what its hands carry, as struct ext_load (load.h),
 * for the joint moments, the low back, strength and balance.
 *
 * What a hand carries. An object is carried when some hand grabbed it
 * (grab: it follows that hand). Its weight (its whole mass at its centre
 * of mass) and its own loads then bear on every hand on it: the one that
 * grabbed it and any that hold a place on it (hold hand), of whichever
 * human. An object held by hold hand alone is not carried: it is fixed in
 * the world (a steering wheel, a table, a handle) and a hand on it follows
 * it; what it pushes or pulls there is statically indeterminate and not
 * modelled. Feet carry nothing.
 *
 * The share of each hand on a carried object (a static rule):
 *  - one hand: all of it;
 *  - two hands: the lever rule on the floor plane. With p1, p2 the palms
 *    and c the centre of mass projected on the floor (x, z), t is c's place
 *    along p1 -> p2, clamped to 0..1 (a grasp lifts; it does not push
 *    down), and the hands take 1 - t and t. Palms closer than
 *    LOAD_SET_SPAN_MIN on the floor plane (one above the other) share
 *    equally;
 *  - more hands (two people): equal shares.
 * Hand i's share s_i of the weight acts at its palm moved by c - sum_j s_j
 * p_j (the centre of mass's offset from the hands' weighted middle), so the
 * shares together are exactly the weight at the centre of mass: the whole
 * body's equilibrium and the centre of mass balance keeps are exact. With
 * the centre of mass between the palms and level with them that offset is
 * nought, the textbook lever rule at the grasps; one hand carries the
 * weight at the centre of mass itself. The object's own loads are shared
 * alike, each at its point moved by p_i - sum_j s_j p_j.
 *
 * Nothing allocates; the figures' global frames and centres of mass must
 * be current (kin_update).
 */
#ifndef POSTURE_LOAD_SET_H
#define POSTURE_LOAD_SET_H

#include "pose/env.h"
#include "pose/load.h"

/* palms closer than this on the floor plane (m) share a carried object equally */
#define LOAD_SET_SPAN_MIN 0.01

/* the most loads one figure can feel: its own, and a carried object's share of each of its own per hand */
#define LOAD_SET_MAX (ENV_MAX_LOADS + 2 * (1 + ENV_MAX_LOADS))

/* where a load of the set comes from */
struct load_origin {
	int load;    /* the env load slot it is (or a share of); -1: a carried object's weight */
	int carried; /* the carried figure's slot whose share it is; -1: the figure's own load */
	int side;    /* the hand that carries it (0 left, 1 right); -1: the figure's own load */
	double share; /* the hand's share of the carried object, 0 to 1; 1 for its own */
};

/*
 * The loads on figure slot fig now into out (at most max; origin, when not
 * NULL, beside each): its own env loads in slot order, then for each hand
 * (left, right) on a carried object that object's weight share and its
 * loads' shares. Returns how many; -1 when max is too small (out partly
 * written) or fig is no figure.
 */
int load_set_of(const struct env *e, int fig, struct ext_load *out, struct load_origin *origin,
		int max);

/* the most hands on one object: every human's two */
#define LOAD_SET_HANDS (2 * ENV_MAX_FIGURES)

/*
 * The hands on figure obj when it is carried, and their shares (the rule
 * above): how many (0: not carried), into fig[], side[] and share[] (each
 * LOAD_SET_HANDS long), in the order of env->att, and the hands' weighted
 * middle sum_j s_j p_j into mid.
 */
int load_set_hands(const struct env *e, int obj, int fig[], int side[], double share[],
		   double mid[3]);

/*
 * The weights among n loads of a figure (model m in state s): their total
 * mass (kg), and their centre in the world into com (untouched when none):
 * what balance adds to the body's own centre of mass.
 */
double load_set_weights(const struct model *m, const struct state *s, const struct ext_load *loads,
			int n, double com[3]);

#endif
