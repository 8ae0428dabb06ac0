/*
 * manikin.h - a human's measures and where they came from, as a session
 * line's words and as JSON: what `load human` with measures and `load
 * family` make, what sessions, undo and the journal keep, and what `list
 * figures` says.
 */
#ifndef POSTURE_MANIKIN_H
#define POSTURE_MANIKIN_H

#include <jansson.h>
#include <stddef.h>
#include <stdio.h>

#include "daemon/words.h"
#include "pose/env.h"

/*
 * The words a session's human figure line carries after "sex=...": its
 * measures (measures=20 numbers in measures.h's order, measure_given=MASK)
 * when it has any, and its provenance (population=, given=, percentile=,
 * mahalanobis=, family=, member=, coverage=) when it is a manikin of a
 * population; nothing for a human from stature and mass alone.
 */
void manikin_write_words(const struct env_figure *f, FILE *dest);

/*
 * Reads those words among w's from word `from` on into hd (its measures)
 * and mk (reset first). 0, or -1 with err for a malformed one.
 */
int manikin_read_words(const struct words *w, int from, struct human_def *hd,
		       struct env_manikin *mk, char *err, size_t errlen);

/*
 * What list figures says of a human: sex, stature, mass, and for one with
 * measures its measures (mm, weightkg kg), and for a manikin of a
 * population its population, the measures it was conditioned on, its
 * Mahalanobis distance and the share of the population nearer the mean
 * (percent), its percentile and its family. Added to o.
 */
void manikin_json(const struct env_figure *f, json_t *o);

/* measures.h's measures of a definition as {name: value}, those given */
json_t *manikin_measures_json(const struct human_def *hd);

#endif
