/*
 * owas.h - OWAS, the Ovako Working posture Analysing System (Karhu, Kansi &
 * Kuorinka, Applied Ergonomics 8(4):199-201, 1977): a posture's four-digit
 * code from measured body angles and its action category.
 */
#ifndef POSTURE_OWAS_H
#define POSTURE_OWAS_H

#include "assess/assess.h"
#include "assess/body_angles.h"

struct owas_options {
	double load_kg; /* the load or force: digit 1 up to 10 kg, 2 up to 20 kg, 3 beyond */
};

/*
 * Codes a with the thresholds cfg leaves open into r: parts back 1-4, arms
 * 1-3, legs 1-6 (body; each part's score is its code digit) and load 1-3;
 * r->code the four digits ("2131"); the look-up "AC" and the action
 * category 1-4 as score and action level. Legs code 7 (walking) is never
 * produced: one posture does not show walking. Each part's adjustments
 * (value 0) list the criteria its digit was chosen by.
 */
void owas_score(const struct body_angles *a, const struct assess_config *cfg,
		const struct owas_options *o, struct assess_result *r);

/*
 * The action category 1-4 of a code (back 1-4, arms 1-3, legs 1-7, load
 * 1-3), or 0 for a digit out of range.
 */
int owas_category(int back, int arms, int legs, int load);

#endif
