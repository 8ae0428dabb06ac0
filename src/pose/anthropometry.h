/*
 * anthropometry.h - a human figure measured as ANSUR II measured people:
 * the measures of figure/measures.h from the figure's landmark sites
 * (figure/human_data.h), in ANSUR's postures, on a state of its own (the
 * figure's own posture is not touched).
 *
 * Postures, made from the figure's built (all-zero) posture:
 *   standing erect   the built posture: heights above the soles; lengths
 *                    between landmarks (acromion-radiale, radiale-stylion,
 *                    stylion-dactylion), breadths between the two sides'
 *                    landmarks, the foot's length along its axis
 *   sitting erect    the trunk as standing, both hips flexed until the
 *                    thighs (hip to knee joint centre) are horizontal, the
 *                    knees until the shanks (knee to ankle) hang vertical,
 *                    the ankles until the feet are as flat as standing:
 *                    heights above the seat (the lower ischial tuberosity)
 *                    and the footrest (the soles), the buttock-knee length
 *                    from the rearmost buttock to the right knee's front
 *   span             standing, both arms abducted until horizontal: the
 *                    distance between the dactylions (middle finger tips)
 *   thumbtip reach   standing, the right arm flexed forward until
 *                    horizontal: from the wall at the rearmost shoulder
 *                    blade to the right thumb tip in a pinch grip
 * One-sided measures are the right side's, as ANSUR's. Lengths in mm,
 * weightkg in kg (the figure's mass).
 */
#ifndef POSTURE_ANTHROPOMETRY_H
#define POSTURE_ANTHROPOMETRY_H

#include <stddef.h>

#include "figure/human.h"
#include "figure/measures.h"
#include "figure/model.h"

/* a measure's ANSUR II name; its index by name, -1 when unknown */
const char *anthro_name(enum human_measure i);
int anthro_find(const char *name);

/*
 * Measures m into dest (HUMAN_MEASURE_N values, measures.h's order).
 * Returns 0, or -1 with why in err: a figure without the landmarks or
 * joints of the built-in human, or out of memory.
 */
int anthro_measure(const struct model *m, double dest[HUMAN_MEASURE_N], char *err, size_t errlen);

/*
 * The same for a figure that may be the built-in human without measures,
 * whose figure carries no landmark sites (figure/human.h): with d its
 * definition, m is measured on a build of d with them (the same body, bit
 * for bit; sites moved on m since are not seen). NULL d: anthro_measure.
 */
int anthro_measure_figure(const struct model *m, const struct human_def *d,
			  double dest[HUMAN_MEASURE_N], char *err, size_t errlen);

#endif
