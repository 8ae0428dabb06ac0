/*
 * family.h - a family of manikins (load family) shown at the kiosk: its
 * members in order, the selected one, which of them are ghosts, their
 * places in a row or overlaid, and what the status line says of a manikin.
 *
 * The shown family is the environment's (env.h, struct env_show), so
 * sessions, undo and the journal keep it; this reads it and moves the
 * members' roots. Nothing here reads a clock, a device or the pictures.
 */
#ifndef POSTURE_DAEMON_FAMILY_H
#define POSTURE_DAEMON_FAMILY_H

#include <stddef.h>

#include "interact/pick.h"
#include "pose/env.h"

/*
 * A ghost's opacity: its own colours at a quarter, so the body it stands
 * in reads through it and its outline still shows against the background.
 */
#define FAMILY_GHOST_ALPHA 0.25f
/* the clearance a row's default spacing leaves between neighbours' widest reaches, m */
#define FAMILY_ROW_MARGIN 0.2

/*
 * The members of family prefix (humans whose manikin.family is prefix):
 * into dest in the family's order, women first in a family of both sexes,
 * then by member number (0 the centre). Returns how many.
 */
int family_members(const struct env *e, const char *prefix, int dest[ENV_MAX_FIGURES]);

/* 1 when figure slot fig is a member of family prefix */
int family_is_member(const struct env *e, const char *prefix, int fig);

/*
 * The shown family's selected member: the one env->show names while it is
 * a member, else its first member. -1 when no family is shown or none of
 * its members is left.
 */
int family_selected(const struct env *e);

/*
 * 1 when figure slot fig is drawn as a ghost: a member of the family shown
 * overlaid, not the selected one and not mode_fig (the figure a mode is
 * on, which is drawn as it is moved; -1: none).
 */
int family_is_ghost(const struct env *e, int fig, int mode_fig);

/* the height of a human's soles: the lowest site of its feet and toes (+inf: none) */
double family_sole_height(const struct model *m, const struct state *s);

/*
 * Arranges the n members slot[0..n-1] (family_members' order) about the
 * member slot[sel], which stays where it stands: each is turned about the
 * vertical to face as the selected one faces and stood on the floor (its
 * soles at y = 0), keeping its root site and posture; overlaid (row 0) its
 * feet's balance sites' midpoint goes where the selected one's is; in a
 * row, member i's goes (i - sel) * spacing along the unit horizontal h.
 * spacing <= 0 asks for the default: the widest reaches of the members
 * from their feet's midpoint along h (pm[i]: slot[i]'s pick model, the
 * geometry as drawn), to either side, plus FAMILY_ROW_MARGIN, so that no
 * two neighbours touch in their postures now; *used says the spacing. A
 * behaving member is refused (its behaviours hold its feet where they
 * stand). Returns 0, or -1 with err and nothing moved.
 */
int family_arrange(struct env *e, const int *slot, const struct pick_model *const *pm, int n,
		   int sel, int row, const double h[3], double spacing, double *used, char *err,
		   size_t errlen);

/*
 * The family posed alike: each of the n members slot[0..n-1] but slot
 * `from` takes from's joint values, joint by joint by name, and stands
 * where it stood (its feet's midpoint), facing as it faced, on the floor.
 * A behaving member, or one without a joint of from's, is refused.
 * Returns 0, or -1 with err and nothing changed.
 */
int family_pose_alike(struct env *e, const int *slot, int n, int from, char *err, size_t errlen);

/* a human's feet's balance sites' midpoint (world) into dest: 0, or -1 without those sites */
int family_place(const struct model *m, const struct state *s, double dest[3]);

/*
 * What the status line says of figure slot fig: its name and, for a human,
 * where its size comes from: "f_3: family f, Mahalanobis 2.15 (90%
 * coverage)", "f_0: family f centre (90% coverage)", "f5: P5 stature
 * (ansur2 female)", "w: ansur2 female, Mahalanobis 1.23 on 3 measures",
 * "jack: 1.75 m, 75 kg". Printable ASCII, as the screen's font draws it.
 */
void family_describe(const struct env *e, int fig, char *dest, size_t len);

#endif
