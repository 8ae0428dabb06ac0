/*
 * load_balance.h - balance feels the load: the weights among the loads a
 * figure feels now (load_set.h: its own weights and its hands' shares of
 * what they carry) given to its balance as point masses (point_mass.h).
 * Pure forces have no mass and are left out: they move no centre of mass
 * (where a push moves the centre of pressure under the feet is not
 * modelled).
 */
#ifndef POSTURE_LOAD_BALANCE_H
#define POSTURE_LOAD_BALANCE_H

#include "pose/env.h"

/*
 * Sets figure fig's weights on its behaviour (behave_set_masses), or on
 * its solver when it has none (ik_set_point_masses), from its loads now.
 * Before each solve. Global frames and centres of mass must be current.
 * Returns 0, or -1 for no figure (nothing changes).
 */
int load_balance_update(struct env *e, int fig);

/*
 * The point masses of figure fig's weights now (room for POINT_MASS_MAX):
 * how many, or -1 for no figure.
 */
int load_balance_masses(const struct env *e, int fig, struct point_mass *dest);

/*
 * The centre of mass balance holds for figure fig, with its weights now:
 * what get balance, the balance icon and move com show. Its own (s->com)
 * with no weights.
 */
void load_balance_com(const struct env *e, int fig, double dest[3]);

#endif
