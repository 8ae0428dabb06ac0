/*
 * assess_internal.h - what the three scorers (rula.c, reba.c, owas.c) share
 * to write a derivation: parts with their bands and adjustments, table
 * look-ups, the worst part. Nothing allocates; reasons are formatted into
 * the part's fixed buffers.
 */
#ifndef POSTURE_ASSESS_INTERNAL_H
#define POSTURE_ASSESS_INTERNAL_H

#include "assess/assess.h"

/* empties r for method m scored on side (enum assess_side_choice, -1 for none) */
void assess_begin(struct assess_result *r, enum assess_method m, int side);

/*
 * Appends a part (name and angle_name static) measured as angle (NAN when
 * none); body 1 for a body part, 0 for an add-on. The band is set with
 * assess_band, adjustments with assess_adjust, the score with assess_close.
 */
struct assess_part *assess_part(struct assess_result *r, const char *name, const char *angle_name,
				double angle, int body, int max);

/* the band the part fell in: its score and the method's words for it */
void assess_band(struct assess_part *p, int base, const char *band);

/*
 * An adjustment of value with its reason: the measured value and the threshold, in a
 * printf-like format of %s, %d, %.1f, %.2f and %g only (assess.c formats it without the
 * printf family; %g prints a threshold with at most 4 decimals)
 */
void assess_adjust(struct assess_part *p, int value, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* the part's score: base plus its adjustments, clamped to lo..hi; returns it */
int assess_close(struct assess_part *p, int lo, int hi);

/* records a look-up of table with nidx 1-based indices named names; returns value */
int assess_lookup(struct assess_result *r, const char *table, int nidx, const char *const *names,
		  const int *idx, int value);

/* sets r->worst to the body part scoring highest relative to its range, the first on ties */
void assess_set_worst(struct assess_result *r);

/*
 * The arm bands RULA and REBA share (their worksheets print the same
 * edges). A value on an edge scores the worse band (ergoassesspro's "when
 * borderline, score higher"): upper arm -20 and 20 score 2, 45 scores 3,
 * 90 scores 4; elbow 60 and 100 score 2. Each returns the band's score and
 * sets *band to the method's words.
 */
int assess_upper_arm_band(double flexion, const char **band);
int assess_lower_arm_band(double elbow_flexion, const char **band);

#endif
