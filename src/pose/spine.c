/* spine.c - Monheit's spine model: total bends distributed over the vertebrae (see spine.h) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/kin.h"
#include "figure/model.h"
#include "pose/spine.h"
#include "figure/state.h"

struct spine_flavor
spine_bend_from_waist(void)
{
	struct spine_flavor f = { .bottom = 0, .top = 11, .initiator = 0, .resistor = 11 };
	return f;
}

struct spine_flavor
spine_curl_from_neck(void)
{
	struct spine_flavor f = { .bottom = 0, .top = 17, .initiator = 17, .resistor = 0 };
	return f;
}

int
spine_flavor_named(const char *name, struct spine_flavor *dest)
{
	if (!name)
		return -1;
	if (strcmp(name, "waist") == 0 || strcmp(name, "bend from waist") == 0) {
		*dest = spine_bend_from_waist();
		return 0;
	}
	if (strcmp(name, "neck") == 0 || strcmp(name, "curl from neck") == 0) {
		*dest = spine_curl_from_neck();
		return 0;
	}
	return -1;
}

int
spine_flavor_check(const struct spine_flavor *f)
{
	if (!f || f->bottom < 0 || f->top >= SPINE_NJNT || f->bottom > f->top)
		return -1;
	if (f->initiator < f->bottom || f->initiator > f->top)
		return -1;
	if (f->resistor < f->bottom || f->resistor > f->top)
		return -1;
	return 0;
}

int
spine_weights(const struct spine_flavor *f, double *dest)
{
	if (spine_flavor_check(f) != 0)
		return -1;
	/* linear ramp from 1 at the initiator to 1/(D+1) at the resistor, flat beyond */
	int D = abs(f->resistor - f->initiator);
	for (int k = 0; k < SPINE_NJNT; k++) {
		int d = abs(k - f->initiator);
		if (d > D)
			d = D;
		dest[k] = k < f->bottom || k > f->top ? 0 : (double)(D + 1 - d) / (D + 1);
	}
	return 0;
}

/* first dof of joint spine_k, or -1 when m lacks it or it has not 3 rotation dofs */
static int
spine_joint_dof0(const struct model *m, int k)
{
	char name[16];
	snprintf(name, sizeof name, "spine_%d", k);
	int j = model_find_joint(m, name);
	if (j < 0 || m->jnt_ndof[j] != 3)
		return -1;
	int d0 = m->jnt_dof0[j];
	for (int d = d0; d < d0 + 3; d++)
		if (m->dof_kind[d] != DOF_ROTATION)
			return -1;
	return d0;
}

/* dest (18): the first dof of every spine joint; -1 unless all exist and can rest at 0 */
static int
spine_find(const struct model *m, int *dest)
{
	for (int k = 0; k < SPINE_NJNT; k++) {
		int d0 = spine_joint_dof0(m, k);
		if (d0 < 0)
			return -1;
		for (int d = d0; d < d0 + 3; d++)
			if (!(m->dof_lo[d] <= 0 && m->dof_hi[d] >= 0))
				return -1;
		dest[k] = d0;
	}
	return 0;
}

/*
 * Shares total over the joints in proportion to w, clamping at cap (the
 * limit on total's side), and re-sharing the rest over the unclamped joints
 * until none passes its cap. dest (18) gets the values; returns the part of
 * total left when every joint with a weight is clamped (else 0).
 */
static double
spine_share(const double *w, const double *cap, double total, double *dest)
{
	unsigned char done[SPINE_NJNT];
	double rest = total;
	for (int k = 0; k < SPINE_NJNT; k++) {
		dest[k] = 0;
		done[k] = !(w[k] > 0);
	}
	/* each pass clamps at least one joint or finishes, so at most 19 passes */
	for (;;) {
		double wsum = 0;
		for (int k = 0; k < SPINE_NJNT; k++)
			if (!done[k])
				wsum += w[k];
		if (!(wsum > 0))
			return rest;
		/* clamp every joint whose share passes its cap; they stay clamped */
		double ratio = rest / wsum;
		int nclamped = 0;
		for (int k = 0; k < SPINE_NJNT; k++)
			if (!done[k] && fabs(ratio * w[k]) > fabs(cap[k])) {
				dest[k] = cap[k];
				done[k] = 1;
				rest -= cap[k];
				nclamped++;
			}
		if (nclamped == 0) {
			for (int k = 0; k < SPINE_NJNT; k++)
				if (!done[k])
					dest[k] = ratio * w[k];
			return 0;
		}
	}
}

/* as spine_distribute, with the spine's dofs already found */
static void
spine_distribute_found(const struct model *m, const int *dof0, const double *w,
		       const double total[3], double *q_spine, double shortfall[3])
{
	for (int dir = 0; dir < 3; dir++) {
		double cap[SPINE_NJNT], val[SPINE_NJNT];
		for (int k = 0; k < SPINE_NJNT; k++) {
			int d = dof0[k] + dir;
			cap[k] = total[dir] >= 0 ? m->dof_hi[d] : m->dof_lo[d];
		}
		double rest = spine_share(w, cap, total[dir], val);
		for (int k = 0; k < SPINE_NJNT; k++)
			q_spine[3 * k + dir] = val[k];
		if (shortfall)
			shortfall[dir] = rest;
	}
}

/* 0 when f is valid, total finite and m has the spine; fills dof0 and w */
static int
spine_prepare(const struct model *m, const struct spine_flavor *f, const double total[3],
	      int *dof0, double *w)
{
	if (!m || !total || spine_weights(f, w) != 0)
		return -1;
	for (int dir = 0; dir < 3; dir++)
		if (!isfinite(total[dir]))
			return -1;
	return spine_find(m, dof0);
}

int
spine_distribute(const struct model *m, const struct spine_flavor *f, const double total[3],
		 double *q_spine, double shortfall[3])
{
	int dof0[SPINE_NJNT];
	double w[SPINE_NJNT];
	if (spine_prepare(m, f, total, dof0, w) != 0)
		return -1;
	spine_distribute_found(m, dof0, w, total, q_spine, shortfall);
	return 0;
}

int
spine_apply(const struct model *m, struct state *s, const struct spine_flavor *f,
	    const double total[3], double shortfall[3])
{
	int dof0[SPINE_NJNT];
	double w[SPINE_NJNT], q[SPINE_NDOF];
	if (spine_prepare(m, f, total, dof0, w) != 0)
		return -1;
	spine_distribute_found(m, dof0, w, total, q, shortfall);
	/* every spine dof, then global frames and centres of mass */
	for (int k = 0; k < SPINE_NJNT; k++)
		for (int dir = 0; dir < 3; dir++)
			s->q[dof0[k] + dir] = q[3 * k + dir];
	kin_update(m, s);
	return 0;
}

void
spine_totals(const struct model *m, const struct state *s, double dest[3])
{
	dest[0] = dest[1] = dest[2] = 0;
	for (int k = 0; k < SPINE_NJNT; k++) {
		int d0 = spine_joint_dof0(m, k);
		if (d0 < 0)
			continue;
		for (int dir = 0; dir < 3; dir++)
			dest[dir] += s->q[d0 + dir];
	}
}
