/*
 * niosh_measure.h - the task geometry of the revised NIOSH lifting equation
 * measured on a human figure in one posture (the origin or the destination
 * of a lift): H, V and A as the Applications Manual defines them (Waters,
 * Putz-Anderson & Garg, DHHS (NIOSH) Publication 94-110, 1994, revised
 * 2021, §1.3.1, §1.3.2, §1.3.4; Waters et al., Ergonomics 36:749, 1993).
 *
 * - H: "from the mid-point of the line joining the inner ankle bones to a
 *   point projected on the floor directly below the mid-point of the hand
 *   grasps". The inner ankle bones are the medial malleoli; the human has
 *   the lateral ones (shank_*.lateral_malleolus) and the ankle joint centre
 *   (the foot's origin), which the ISB places midway between the two
 *   malleoli (Wu et al. 2002, J Biomech 35:543), so each medial malleolus
 *   is the lateral one reflected through the ankle joint centre. The hand
 *   grasp is the palm site (hand_*.palm), where the figure's hands hold
 *   what they grab and the load's centre lies; the manual marks it on the
 *   large middle knuckle, which lies over the palm a few cm towards the
 *   fingers (it moves V by that much when the hands hang, hardly H).
 * - V: the hands' midpoint above the floor (y = 0).
 * - A: the angle between the asymmetry line (the ankles' midpoint to the
 *   point below the hands' midpoint) and the mid-sagittal line, 0..180 deg.
 *   The manual fixes the mid-sagittal plane by the "neutral body posture",
 *   not by torso twist; here its line runs the way the feet point (the
 *   bisector of the two feet's heel-to-toe directions on the floor), which
 *   twisting at the legs, trunk or shoulders leaves alone while the feet
 *   stay planted, as the manual's lift without pivoting or stepping does.
 *   With the hands straight above the ankles' midpoint A is 0.
 *
 * D is |V at the destination - V at the origin| (niosh_travel_cm). Lengths
 * in cm as the metric equation takes them, and in inches (2.54 cm each) for
 * the U.S. customary one. Nothing allocates.
 */
#ifndef POSTURE_NIOSH_MEASURE_H
#define POSTURE_NIOSH_MEASURE_H

#include <stddef.h>

#include "figure/model.h"
#include "figure/state.h"

#define NIOSH_CM_PER_IN 2.54 /* exact, by the international inch (1959) */

struct niosh_geometry {
	double h_cm, v_cm;    /* horizontal and vertical location */
	double h_in, v_in;    /* the same in inches */
	double a_deg;         /* asymmetry angle, 0..180 */
	double hands_mid[3];  /* m, world: the midpoint of the palms */
	double ankles_mid[3]; /* m, world: the midpoint of the medial malleoli */
	double forward[3];    /* unit, horizontal: the mid-sagittal line's direction */
};

/*
 * Measures H, V and A on human m in state s (frames current: kin_update).
 * Returns 0, or -1 with why in err (dest untouched) for a figure without
 * the human's feet, shanks' lateral malleoli and palms.
 */
int niosh_measure(const struct model *m, const struct state *s, struct niosh_geometry *dest,
		  char *err, size_t errlen);

/* D, the vertical travel distance between the two ends of a lift, cm */
double niosh_travel_cm(const struct niosh_geometry *origin, const struct niosh_geometry *dest);

#endif
