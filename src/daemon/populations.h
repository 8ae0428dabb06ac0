/*
 * populations.h - the populations a daemon knows: the built-in ansur2 and
 * those loaded from files (load population).
 *
 * A population is the daemon's data, not part of the environment: a
 * session keeps each manikin's measures, so it loads without the
 * population they came from; load session and undo leave the loaded
 * populations alone. They survive a restart all the same: the journal
 * records each file as read, and snapshots hold their statistics
 * (populations_write), which read back bit for bit.
 */
#ifndef POSTURE_POPULATIONS_H
#define POSTURE_POPULATIONS_H

#include <stddef.h>
#include <stdio.h>

#include "figure/population.h"

#define POPULATIONS_MAX 8                /* loaded ones, besides ansur2 */
#define POPULATIONS_FILE_MAX (4u << 20)  /* the largest file loaded (ANSUR II's is 2 MB) */
#define POPULATIONS_BUILTIN "ansur2"

struct populations {
	char name[POPULATIONS_MAX][48];
	struct population *pop[POPULATIONS_MAX]; /* NULL: a free slot */
};

/* a population by name (ansur2 built in); NULL when none */
const struct population *populations_find(const struct populations *ps, const char *name);

/*
 * Adds p under name, taking ownership, replacing (and freeing) one of the
 * same name. Returns 0, or -1 when every slot is taken (p freed) or the
 * name is the built-in one's (p freed).
 */
int populations_add(struct populations *ps, const char *name, struct population *p);

/* frees every loaded population */
void populations_clear(struct populations *ps);

/*
 * The loaded populations as text: "populations N", then per population
 * "population NAME LEN" and LEN bytes of population_stats_write. 0, or -1
 * on a stream error.
 */
int populations_write(const struct populations *ps, FILE *f);

/*
 * Reads what populations_write wrote (at the start of text) into ps, which
 * it replaces; *used gets the bytes read. Nothing changes on error (-1,
 * with err).
 */
int populations_read(struct populations *ps, const char *text, size_t len, size_t *used,
		     char *err, size_t errlen);

#endif
