/*
 * assess_live.h - a figure's assessment as it stands now: its body angles
 * and its RULA, REBA and OWAS results under the daemon's settings (set
 * assess), each figure's computed at most once a frame and only when asked
 * (a subscriber, the status line, a tinted view, a command), and again only
 * when its posture, its behaviour's support or the settings changed.
 * Nothing allocates after assess_live_init.
 */
#ifndef POSTURE_ASSESS_LIVE_H
#define POSTURE_ASSESS_LIVE_H

#include <stdint.h>

#include "assess/assess.h"
#include "assess/body_angles.h"

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

#endif
