/*
 * envelope_grid.h - the reachability field of an envelope on a regular grid
 * and its surface, for any solver that sends an effector toward a point
 * (envelope.c gives the human's reach and a plain figure's chain).
 *
 * The field at a grid point is the distance from the point to where the
 * effector ends up: 0 (within tol) inside, the distance to the reachable
 * set outside, which is 1-Lipschitz: a point at distance d proves every
 * point closer than d - tol to it outside, without a solve. Coarse to fine:
 * a coarse lattice is solved in waves outwards from the seed, and a cell is
 * refined unless a corner's distance proves the whole cell outside, or, at
 * or below the trusted cell size, all its corners and its neighbours' are
 * inside; within a refined cell, a point its corners prove outside is not
 * solved either. Then
 * every point next to a change of sign that was filled rather than solved is
 * solved, until none is left (the boundary is traced). Each vertex is put on
 * its edge where the plane tangent to the reachable set at the outside
 * point's nearest reachable point, a millimetre inside (at most a twentieth
 * of a step), crosses it, and then sent to the solver:
 * unless reached there, it moves to where the effector ended, so every
 * vertex is a reached point.
 */
#ifndef POSTURE_ENVELOPE_GRID_H
#define POSTURE_ENVELOPE_GRID_H

#include <stddef.h>

#include "assess/mcubes.h"

#define ENVELOPE_THREADS_MAX 16

struct env_oracle {
	int nthreads;
	void *thr[ENVELOPE_THREADS_MAX]; /* one solver's context per thread */
	/* sends the effector toward p from the starting posture, or, with q0, from
	 * that posture of the moved dofs; dest gets where it ended (a reached
	 * point) and q_out (nq floats, when nq > 0) the posture; 0, or -1 when the
	 * solver refused */
	int (*solve)(void *thr, const double p[3], const float *q0, double dest[3], float *q_out);
	int nq;         /* the moved dofs a posture holds (0: no warm starts) */
	int warm_field; /* 1: the field's points start from a neighbour's posture, 0: from the
			   starting posture (the vertices always start from a neighbour's) */
	double tol;     /* the effector within this of p has reached it */
};

struct env_stats {
	int grid[3];
	long solves;
};

/*
 * A box holding the reachable set: the effector sent far away along 26
 * directions from centre, the box of where it ended, grown by a margin.
 */
int env_bounds(const struct env_oracle *o, const double centre[3], double step, double lo[3],
	       double hi[3]);

/*
 * The surface of the reachable set within [lo, hi] at grid step `step`, the
 * field solved outwards from seed (a reachable point); 0, or -1 with err.
 */
int env_surface(const struct env_oracle *o, const double lo[3], const double hi[3],
		const double seed[3], double step, struct mc_mesh *dest, struct env_stats *st,
		char *err, size_t errlen);

#endif
