/*
 * dials.h - the dial panel at work: its bindings
 * (interact/dial_bind.h, the file of --bindings, `bind` at run time) fed
 * every input event, and what they ask for applied: a DOF of the picked
 * joint (Jack's dial box) or of a named joint, a sweep or zoom of the
 * kiosk's view, the elevation or the torso's bend of a behaving human, an
 * axis of the manipulation transform; a panel button's command run as if
 * typed at the kiosk. A turn of the dials is one step (one undo), ended
 * when they have been still for DIALS_STILL_US, or by a key or a button.
 */
#ifndef POSTURE_DIALS_H
#define POSTURE_DIALS_H

#include <stdint.h>

#include "daemon/modes.h"
#include "interact/dial_feed.h"

#define DIALS_STILL_US 500000 /* dials still this long: their step is over */

struct dials {
	struct dial_bind table;
	struct modes *M;
	int stepping;       /* a step the dials began */
	int camera_moved;   /* a view they turned, journaled when the step ends */
	uint64_t last_us;   /* their last move */
	char message[160];  /* why the last move did nothing, for the message line */
};

void dials_init(struct dials *D, struct modes *M);

/* the bindings of a file, named through the panel's map (NULL: later); 0, or -1 with err */
int dials_load(struct dials *D, const char *path, const struct can_map *panel, char *err,
	       size_t errlen);

/* one input event: what the bindings ask for, applied; 1 when something moved or ran */
int dials_input(struct dials *D, const struct input_event_rec *e);

/* once a frame: the dials' step ends when they have been still long enough */
void dials_frame(struct dials *D, uint64_t now_us);

#endif
