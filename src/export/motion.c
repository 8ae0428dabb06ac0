/* motion.c - a figure's postures over time, as the exports read them */
#include "export/motion.h"

const struct state *
motion_frame(const struct motion *mo, int k)
{
	if (k >= mo->nframes)
		k = mo->nframes - 1;
	for (int d = 0; d < mo->nframes; d++) {
		if (k - d >= 0 && mo->frames[k - d])
			return mo->frames[k - d];
		if (k + d < mo->nframes && mo->frames[k + d])
			return mo->frames[k + d];
	}
	return mo->now;
}
