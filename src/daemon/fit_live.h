/*
 * fit_live.h - the fit analysis's state in the daemon: each figure's
 * collision model (fit_model.h), built the first time it is asked for and
 * kept while the figure keeps its model, and the caches of the last
 * answers between each pair of figures asked (clearance.h), so that the
 * next frames of a drag ask little.
 */
#ifndef POSTURE_FIT_LIVE_H
#define POSTURE_FIT_LIVE_H

#include <stddef.h>

#include "fit/clearance.h"
#include "fit/fit_model.h"

struct daemon;

/* the state made (once, before the frame loop): 0, or -1 when out of memory */
int fit_live_init(struct daemon *d);
void fit_live_free(struct daemon *d);

/*
 * Figure slot fig's collision model, built now if it has none or its
 * model changed; NULL with the reason in why (no figure, out of memory, a
 * malformed mesh).
 */
const struct fit_model *fit_live_model(struct daemon *d, int fig, char *why, size_t len);

/*
 * Adds to res the clearance of figure slot fig against each of the n
 * figures in with[] and, with self set, with itself (their frames
 * current). Returns 0, or -1 with the reason in why.
 */
int fit_live_clearance(struct daemon *d, int fig, const int *with, int n, int self,
		       struct clearance_result *res, char *why, size_t len);

/* the models built since fit_live_init (one a figure and model) */
unsigned long fit_live_built(const struct daemon *d);

#endif
