/* behave_internal.h - shared between behave.c and behave_store.c */
#ifndef POSTURE_BEHAVE_INTERNAL_H
#define POSTURE_BEHAVE_INTERNAL_H

#include "pose/behave.h"

/* finds the sites and joints the behaviours use; 0, or -1 when the figure lacks one */
int behave_find_sites(struct behave *b, const struct model *m);

/* the index field in b of the behaviour's constraint k, in def[]'s fixed order */
int *behave_slot(struct behave *b, int k);

#endif
