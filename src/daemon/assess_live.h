/*
 * assess_live.h - a figure's assessment as it stands now: its body angles
 * and its RULA, REBA and OWAS results under the daemon's settings (set
 * assess), each figure's computed at most once a frame and only when asked
 * (a subscriber, the status line, a tinted view, a command), and again only
 * when its posture, its behaviour's support or the settings changed.
 * Nothing allocates after assess_live_init.
 *
 * The live options: each method's defaults (rula_options_default,
 * reba_options_default), the side the worse of the two, the load the mass
 * the figure's hands carry (assess_live_held_kg), seated as its behaviour
 * says (behave_params.seated; a figure without behaviours stands).
 */
#ifndef POSTURE_ASSESS_LIVE_H
#define POSTURE_ASSESS_LIVE_H

#include <stddef.h>
#include <stdint.h>

#include "assess/assess.h"
#include "assess/body_angles.h"
#include "pose/env.h"

struct daemon;

struct assess_live_fig {
	int valid;                 /* 0: not a human (no angles), or not computed */
	uint64_t key;              /* what it was computed from (posture hash, settings) */
	struct body_angles angles;
	struct assess_result res[ASSESS_NMETHODS]; /* enum assess_method */
	double load_kg;            /* the load counted (held objects), kg */
};

/* the live assessment of figure slot fig now; NULL for a figure that is not a human */
const struct assess_live_fig *assess_live_of(struct daemon *d, int fig);

/*
 * Why assess_live_of gave NULL for figure slot fig: "no figure", "X is not
 * a human figure", or what body_angles_measure said. "" when it did not.
 */
const char *assess_live_why(struct daemon *d, int fig);

/*
 * The cache made (once, before the frame loop runs; assess_live_of makes it
 * when asked first otherwise): 0, or -1 when out of memory.
 */
int assess_live_init(struct daemon *d);
void assess_live_free(struct daemon *d);

/* how many assessments were computed since assess_live_init (a cached answer counts none) */
uint64_t assess_live_computed(const struct daemon *d);

/*
 * The load the hands of figure slot fig carry, kg: the total mass of every
 * figure it grabbed (grab: the object follows the hand, its weight in the
 * hand), each once. A place held on another figure (hold hand: the hand
 * follows a steering wheel, a handle) carries none of that figure's weight.
 */
double assess_live_held_kg(const struct env *e, int fig);

/* seated as figure slot fig's behaviour says (0: standing, or no behaviours) */
int assess_live_seated(const struct env *e, int fig);

#endif
