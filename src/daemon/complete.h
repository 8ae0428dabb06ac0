/*
 * complete.h - Tab at the kiosk's edit line: the words a command line may
 * go on with, from the command table and the environment as it is. The
 * first word completes among the verbs, the second among the verb's
 * objects; after them come the names that exist: figures, constraints,
 * views, and the joints and sites (SEG.SITE) of any figure named earlier
 * on the line; `key=` words from the command's usage; left and right.
 */
#ifndef POSTURE_COMPLETE_H
#define POSTURE_COMPLETE_H

#include "daemon/daemon.h"

#define COMPLETE_POOL 16384 /* bytes of candidate words built here (SEG.SITE, key=) */

struct complete {
	const struct daemon *d;
	char pool[COMPLETE_POOL];
	size_t used;
};

/*
 * editline's completion callback (user: a struct complete): writes up to
 * max candidates starting with prefix into dest, sorted, without
 * duplicates; returns their count. They stay valid until the next call.
 */
int complete_words(void *user, const char *const *words, int nwords, const char *prefix,
		   const char **dest, int max);

#endif
