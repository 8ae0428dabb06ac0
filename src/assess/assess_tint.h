/*
 * assess_tint.h - the colour a body part is drawn in when a view is tinted
 * by an assessment (set view VIEW tint=rula|reba|owas).
 *
 * The rule: a part's colour is the action level the grand score would
 * have if that part alone were as measured and every other part (the
 * add-ons too: muscle use, load, coupling, activity) at its lowest score.
 * The level is looked up through the method's own tables (RULA A, B and C;
 * REBA A, B and C; OWAS's classification), so a part shows orange only
 * when it alone puts the posture in the method's third level: the colours
 * say what the method says of that part, not a share of its score range.
 *
 * The four colours by the methods' own words, the same urgency in each:
 *   green   no action       RULA AL 1, REBA AL 0,    OWAS AC 1
 *   yellow  action may be needed, later
 *                           RULA AL 2, REBA AL 1-2,  OWAS AC 2
 *   orange  action soon     RULA AL 3, REBA AL 3,    OWAS AC 3
 *   red     action now      RULA AL 4, REBA AL 4,    OWAS AC 4
 * (REBA has five levels: "may be necessary" (1) and "necessary" (2) share
 * yellow so that orange and red mean "soon" and "now" in all three.)
 *
 * Nothing allocates; the tables are the scorers' (rula.h, reba.h, owas.h).
 */
#ifndef POSTURE_ASSESS_TINT_H
#define POSTURE_ASSESS_TINT_H

#include "assess/assess.h"

enum assess_colour {
	ASSESS_GREEN,
	ASSESS_YELLOW,
	ASSESS_ORANGE,
	ASSESS_RED,
	ASSESS_NCOLOURS,
};

/*
 * The action level (the method's numbering: RULA 1-4, REBA 0-4, OWAS 1-4)
 * with part index `part` of r alone as measured, the rest at their lowest
 * scores. -1 for a part the method's tables do not take (an unknown name)
 * or an index out of range.
 */
int assess_part_level(const struct assess_result *r, int part);

/* the colour of action level `level` of method (ASSESS_GREEN for a level below the first) */
enum assess_colour assess_level_colour(enum assess_method method, int level);

/*
 * The key of a method's colours, for a legend: the levels each colour
 * stands for ("1", "1-2", ...) and the word for them ("AL", "AC").
 */
const char *assess_colour_levels(enum assess_method method, enum assess_colour c);
const char *assess_level_word(enum assess_method method);

#endif
