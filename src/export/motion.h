/*
 * motion.h - what an export takes of a figure: its model, its posture now,
 * and for an animation its postures over time (a session's history,
 * oldest first, or a file of postures), each a state of that model with
 * its global frames computed (kin_update).
 */
#ifndef POSTURE_MOTION_H
#define POSTURE_MOTION_H

#include "figure/model.h"
#include "figure/state.h"

/* seconds between two postures of an animation when nothing says otherwise */
#define MOTION_FRAME_SECONDS 0.5

struct motion {
	const char *name;                  /* the figure's name in the environment */
	const struct model *m;
	const struct state *now;           /* the posture now */
	const struct state *const *frames; /* nframes postures, oldest first; NULL entries:
					    * the figure did not exist then (hold the nearest) */
	int nframes;                       /* 0: no animation */
};

/*
 * Frame k (k past the last: the last): the nearest frame the figure exists
 * in, the earlier on a tie; its posture now when it is in none.
 */
const struct state *motion_frame(const struct motion *mo, int k);

#endif
