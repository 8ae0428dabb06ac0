/*
 * envelope.h - reach envelopes (§6.1's reach): the closed surface of the
 * points a hand's palm can reach, computed by the solver itself (pose/reach.h)
 * so that it includes what the body does to reach: the arm alone, the spine
 * too, or the whole body bending and squatting with its feet planted and
 * balance held.
 *
 * The surface is marching cubes over a reachability field on a regular grid
 * of the request's resolution: at a grid point, the distance from the point
 * to where reach_solve's palm ends up (0 inside: reached). Outside, that is
 * the distance to the reachable set, which prunes the points to solve
 * (assess/envelope_grid.h). Each vertex is placed on its grid edge by the
 * plane tangent to the set there, then sent to the solver: unless reached,
 * it moves to where the palm ended, so every vertex is a reached point. The
 * mesh (assess/mcubes.h) is closed and consistently oriented (outward
 * normals), its volume by the divergence theorem.
 *
 * The comfort zone is the same surface with the moved joints held within
 * their comfort ranges (envelope_comfort_default says which and cites each).
 *
 * Computing allocates; it is an analysis run on request, not in the frame
 * loop. It runs on req.threads threads (0: every core) and changes nothing
 * it is given.
 */
#ifndef POSTURE_ENVELOPE_H
#define POSTURE_ENVELOPE_H

#include <stddef.h>

#include "figure/model.h"
#include "figure/state.h"
#include "pose/behave.h"
#include "pose/point_mass.h"
#include "pose/reach.h"
#include "assess/envelope_comfort.h"

/* m: the grid's step: 2 cm, the resolution the envelopes were specified at; 5 mm to
 * 25 cm allowed (finer grids outgrow memory, coarser ones miss a hand's width) */
#define ENVELOPE_RES_DEFAULT 0.02
#define ENVELOPE_RES_MIN 0.005
#define ENVELOPE_RES_MAX 0.25
/* the arm's solves: "can reach" with this many random restarts when stuck short of a
 * point (pose/reach.h), so that a local minimum does not cut a piece off the envelope */
#define ENVELOPE_ARM_RESTARTS 4

struct envelope_request {
	int side;             /* BEHAVE_LEFT or BEHAVE_RIGHT */
	enum reach_mode mode; /* what may move (pose/reach.h) */
	int balance;          /* REACH_BODY: balance held */
	double resolution;    /* m: grid step, ENVELOPE_RES_MIN .. ENVELOPE_RES_MAX */
	int comfort;          /* 1: the comfort zone as well */
	struct envelope_comfort comfort_ranges; /* used when comfort is set */
	int threads;          /* 0: every core */
};

/* a closed triangle mesh in world coordinates (metres) */
struct envelope_mesh {
	int nvert, ntri;
	float *vert;   /* 3 nvert */
	float *normal; /* 3 nvert, unit, outward */
	int *tri;      /* 3 ntri, counter-clockwise seen from outside */
	double volume; /* m^3 */
	double lo[3], hi[3]; /* bounds; both 0 when empty */
};

struct envelope {
	struct envelope_request req;
	struct envelope_mesh reach;
	struct envelope_mesh comfort; /* empty unless req.comfort */
	int grid[3];                  /* grid points each way */
	long solves;                  /* reach solves made */
	double seconds;               /* wall time */
};

/*
 * The envelope of human model m from the posture s (current frames; the
 * posture the non-moving parts keep, and where the feet stand), with the
 * behaviour parameters p (NULL: the defaults) and carried weights pm, n.
 * Returns 0 with *dest filled (envelope_free it), or -1 with a message in
 * err (not a human, bad request, out of memory).
 */
int envelope_compute(const struct model *m, const struct state *s, const struct behave_params *p,
		     const struct point_mass *pm, int n, const struct envelope_request *req,
		     struct envelope *dest, char *err, size_t errlen);
void envelope_free(struct envelope *e);

/*
 * The envelope of any figure's chain, for figures that are not humans and
 * for checks against analytic reachable sets: site `effector` sent toward
 * each point by the joints from it up to start_joint (-1: to the root),
 * within their limits, from the posture s (current frames). Only req's
 * resolution and threads are used. Returns 0 with *dest filled (free its
 * arrays with free(), or wrap it in a struct envelope for envelope_free) and
 * the solves made in *solves (may be NULL), or -1 with a message in err.
 */
int envelope_compute_chain(const struct model *m, const struct state *s, int effector,
			   int start_joint, const struct envelope_request *req,
			   struct envelope_mesh *dest, long *solves, char *err, size_t errlen);

/* 1 when p lies inside the closed mesh (ray parity), else 0 */
int envelope_mesh_contains(const struct envelope_mesh *mesh, const double p[3]);

#endif
