/* load_balance.c - the weights a figure feels, given to its balance */
#include "pose/load_balance.h"

#include <string.h>

#include "pose/load_set.h"
#include "pose/point_mass.h"

/* every own load on a segment of its own and both hands' shares fit as point masses */
_Static_assert(POINT_MASS_MAX >= ENV_MAX_LOADS + 2, "point masses for every weight a figure feels");

int
load_balance_masses(const struct env *e, int fig, struct point_mass *dest)
{
	struct ext_load loads[LOAD_SET_MAX]; /* on the stack: nothing allocates in a frame */
	int n = load_set_of(e, fig, loads, NULL, LOAD_SET_MAX);
	if (n < 0)
		return -1;
	return point_mass_of_loads(loads, n, dest, POINT_MASS_MAX);
}

int
load_balance_update(struct env *e, int fig)
{
	struct point_mass pm[POINT_MASS_MAX];
	int n = load_balance_masses(e, fig, pm);
	if (n < 0)
		return -1;
	struct env_figure *f = &e->fig[fig];
	if (f->behave)
		return behave_set_masses(f->behave, f->model, f->state, pm, n);
	return ik_set_point_masses(f->ik, f->model, pm, n);
}

void
load_balance_com(const struct env *e, int fig, double dest[3])
{
	struct point_mass pm[POINT_MASS_MAX];
	int n = load_balance_masses(e, fig, pm);
	if (n < 0) { /* no figure there */
		memset(dest, 0, 3 * sizeof *dest);
		return;
	}
	point_mass_com(e->fig[fig].state, pm, n, dest);
}
