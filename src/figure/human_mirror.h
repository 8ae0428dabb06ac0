/*
 * human_mirror.h - a human's posture left for right.
 *
 * The standard human's limb joints are mirrored (human.h): the same value
 * means the same anatomical motion on either side, so the mirror image of
 * a posture swaps the values of each _l joint and its _r twin (hips to
 * eyes); the spine's lateral bend and axial rotation change sign (to the
 * left becomes to the right), its flexion stays. The mirror plane is the
 * pelvis's midsagittal plane: the pelvis stays where it is, and so does
 * every segment on the plane; the root site stays the root.
 */
#ifndef POSTURE_HUMAN_MIRROR_H
#define POSTURE_HUMAN_MIRROR_H

#include <stddef.h>

#include "figure/model.h"
#include "figure/state.h"

/*
 * Mirrors s (its global frames current) in place, global frames updated.
 * Returns 0, or -1 with a message in err when m is not a human figure (a
 * joint _l without its _r twin, no pelvis.root) or a mirrored value falls
 * outside its twin's limits; s is unchanged then.
 */
int human_mirror_posture(const struct model *m, struct state *s, char *err, size_t errlen);

#endif
