/*
 * point_mass.h - the weights a figure carries as point masses: a mass at a
 * point fixed in one of its segments, moving with it (a box in the hands, a
 * tool on the belt). The centre of mass that balance keeps over the support
 * (Chapter 5) is the figure's own with these added:
 *
 *     c = (M c_body + sum m_i p_i) / (M + sum m_i)
 *
 * M and c_body the figure's mass and centre of mass (kin_com), p_i the
 * masses' world positions. A pure force (a push, a pull on the hand) has no
 * mass and moves no centre of mass; only weights become point masses.
 */
#ifndef POSTURE_POINT_MASS_H
#define POSTURE_POINT_MASS_H

#include "figure/model.h"
#include "figure/state.h"
#include "pose/load.h"

/* point masses on one figure: weights on one segment are one point mass (point_mass_of_loads),
 * so a figure's every own load on a segment of its own and both hands fit */
#define POINT_MASS_MAX 72

struct point_mass {
	int seg;         /* the segment carrying it */
	double local[3]; /* where, in the segment's frame (m) */
	double mass;     /* kg, > 0 */
};

/* 0 when pm[0..n) are masses figure m can carry: n within 0..POINT_MASS_MAX, segments
 * in range, finite points, finite masses > 0; else -1 */
int point_mass_check(const struct model *m, const struct point_mass *pm, int n);

/*
 * The weights among loads (mass > 0) as point masses, into dest (room for
 * max); forces without mass are left out. The weights on one segment become
 * one point mass, their sum at their centre (exact: they move together), in
 * the order their segments first come. Returns how many, or -1 when more
 * than max segments carry weights.
 */
int point_mass_of_loads(const struct ext_load *loads, int n, struct point_mass *dest, int max);

/*
 * The centre of mass of the figure with the masses (the formula above);
 * needs kin_com. With n == 0 it is s->com exactly, so a figure without
 * weights balances as it always did.
 */
void point_mass_com(const struct state *s, const struct point_mass *pm, int n, double dest[3]);

#endif
