/*
 * attach.h - a human's hands and feet held to other figures (Table D.4,
 * §D.1.1): "grab object", after which the object follows the hand, and
 * "hold local location", after which the hand or foot follows a place on
 * an object's segment (a pedal, a steering wheel, a handle). Both are
 * kept in env->att and applied by the frame loop around the human's solve.
 */
#ifndef POSTURE_ATTACH_H
#define POSTURE_ATTACH_H

#include <stddef.h>

#include "pose/env.h"

/*
 * The hand of behaving human fig grabs figure obj where they are now.
 * Returns 0, or -1 with a reason in err (not a behaving human, the object
 * is the figure itself, behaves, or holds on to the human).
 */
int attach_grab(struct env *e, int fig, int side, int obj, char *err, size_t errlen);

/*
 * The hand or foot of behaving human fig holds its place relative to
 * segment seg of figure obj and follows it. Returns 0, or -1 with err.
 */
int attach_local(struct env *e, int fig, enum attach_limb limb, int side, int obj, int seg,
		 char *err, size_t errlen);

/* lets go of whatever the limb holds; 1 when it held something, else 0 */
int attach_release(struct env *e, int fig, enum attach_limb limb, int side);

/* every attachment of fig (switching its behaviours off) */
void attach_release_all(struct env *e, int fig);

/* the slot in env->att of the limb's attachment, or -1 */
int attach_find(const struct env *e, int fig, enum attach_limb limb, int side);

/* before fig solves: limbs holding local locations get goals from their objects */
void attach_before_solve(struct env *e, int fig);

/* after fig solved: objects its hands grabbed follow them; 1 when one moved */
int attach_after_solve(struct env *e, int fig);

/* an attachment the caller built (a session being read); 0, or -1 when invalid */
int attach_add(struct env *e, const struct env_attach *a);

#endif
