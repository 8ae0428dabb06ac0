/*
 * history.h - the session's history read back for exports: the environment
 * at each undo checkpoint, oldest first, then the one now, so a figure's
 * postures over the session become an animation's frames.
 */
#ifndef POSTURE_HISTORY_H
#define POSTURE_HISTORY_H

#include <stddef.h>

#include "daemon/daemon.h"
#include "export/motion.h"

struct history {
	struct env *env; /* n environments read from the undo checkpoints, oldest first */
	int n;
};

/* reads every undo checkpoint of d; 0, or -1 with why in err (h then holds nothing) */
int history_read(const struct daemon *d, struct history *h, char *err, size_t errlen);
void history_free(struct history *h);

/*
 * Figure slot fig of d's environment as an export takes it: its posture now
 * and, with h, its frames: at each checkpoint the posture of the figure of
 * that name when it had the same model then (else NULL: it did not exist,
 * or was another figure), then the posture now. frames must hold h->n + 1.
 */
void history_motion(const struct daemon *d, const struct history *h, int fig,
		    const struct state **frames, struct motion *dest);

#endif
