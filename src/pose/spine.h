/*
 * spine.h - Monheit's spine model (§5.5.3, §D.1.3): total bending angles in
 * the forward, lateral and axial directions distributed over the vertebral
 * joints of the standard human (human.h) by weighting factors.
 *
 * The spine is the 18 joints spine_0 (pelvis-L5) .. spine_17 (T1-head),
 * found by name, each with 3 rotation dofs in the order flexion
 * (+ forward), lateral bend (+ to the left), axial rotation (+ turn left).
 * A bend is three totals (radians), one per direction; each direction is
 * distributed on its own, and the joint values of a direction sum to its
 * total. Spine arrays of 54 values hold joint k's three dofs at 3k .. 3k+2.
 *
 * The weighting. A flavour is a range of joints [bottom, top] with an
 * initiator and a resistor joint inside it. With D = |resistor - initiator|
 * and d_k = |k - initiator|, joint k in the range has the weight
 *
 *	w_k = (D + 1 - min(d_k, D)) / (D + 1)
 *
 * and every joint outside the range has 0. This is a linear ramp from 1 at
 * the initiator down to 1/(D+1) at the resistor, the ramp that would reach
 * zero one joint past the resistor; joints beyond the resistor, or on the
 * far side of the initiator at least D joints away, keep the resistor's
 * weight. When the initiator is the resistor, D = 0 and the range is
 * uniform. Why this ramp: it is the simplest profile that is largest at the
 * initiator, strictly decreasing towards the resistor and smallest there,
 * as §D.1.3 describes; and it gives every joint of the range a positive
 * weight, so the whole range takes part and a bend that is too large can
 * use every joint up to its limit.
 *
 * The limits. A direction's total T is shared in proportion to the weights;
 * the joints whose share passes their limit on T's side (dof_hi for T > 0,
 * dof_lo for T < 0) are set to that limit, and what is left of T is shared
 * again over the others in proportion to their weights, until no share
 * passes a limit. The unclamped joints of a direction then hold T' w_k for
 * one common T', and each clamped joint holds less than T' w_k would be.
 * When every joint of the range is clamped and T is still not reached, the
 * rest is the shortfall (signed like T: requested minus achieved).
 *
 * The model must have the 18 spine joints, each with 3 rotation dofs whose
 * limits contain 0 (human_build's figure does); otherwise the functions that
 * distribute return -1.
 */
#ifndef POSTURE_SPINE_H
#define POSTURE_SPINE_H

#include "figure/model.h"
#include "figure/state.h"

#define SPINE_NJNT 18             /* spine_0 .. spine_17, as HUMAN_NSPINE */
#define SPINE_NDOF (3 * SPINE_NJNT) /* 54 */

/* direction index within a spine joint and within the totals */
#define SPINE_FLEX 0 /* flexion, + forward */
#define SPINE_LAT 1  /* lateral bend, + to the left */
#define SPINE_AXIAL 2 /* axial rotation, + turn left */

/* joint indices 0 .. 17 into spine_0 .. spine_17 */
struct spine_flavor {
	int bottom, top;   /* the range of joints that move, bottom <= top */
	int initiator;     /* the largest weight; in [bottom, top] */
	int resistor;      /* the smallest weight; in [bottom, top] */
};

/*
 * "Bend from waist": spine_0 (L5/S1) .. spine_11 (T6/T7), initiated at
 * spine_0 and resisted at spine_11. The lumbar and lower thoracic joints
 * are where trunk flexion happens (White and Panjabi's segment ranges are
 * largest there); the upper thoracic joints and the neck stay straight, so
 * the chest and head are carried along rigidly, as a bend that is confined
 * to the lower back should look.
 */
struct spine_flavor spine_bend_from_waist(void);

/*
 * "Curl from neck": the whole spine, spine_0 .. spine_17, initiated at the
 * neck (spine_17) and resisted at the pelvis (spine_0): the head leads and
 * the curl rolls down the back with decreasing weight.
 */
struct spine_flavor spine_curl_from_neck(void);

/*
 * Fills dest with a standard flavour by name: "waist" or "bend from waist",
 * "neck" or "curl from neck". Returns 0, or -1 (dest untouched) for any
 * other name.
 */
int spine_flavor_named(const char *name, struct spine_flavor *dest);

/*
 * Returns 0 when f is a valid flavour (0 <= bottom <= top < 18, initiator
 * and resistor in [bottom, top]), else -1.
 */
int spine_flavor_check(const struct spine_flavor *f);

/*
 * dest (18): the weight w_k of every joint for f (formula above; 0 outside
 * the range). Returns 0, or -1 for a bad flavour (dest untouched).
 */
int spine_weights(const struct spine_flavor *f, double *dest);

/*
 * Distributes total (flexion, lateral, axial; radians) over the spine of m
 * for flavour f. q_spine (54) receives every spine dof value, 0 for the
 * joints outside the range; shortfall (3, may be NULL) receives per
 * direction the part of the total that the joints' limits could not take
 * (0 when achievable). Returns 0, or -1 (nothing written) for a bad
 * flavour, a non-finite total, or a model without the standard spine.
 */
int spine_distribute(const struct model *m, const struct spine_flavor *f, const double total[3],
		     double *q_spine, double shortfall[3]);

/*
 * spine_distribute, then writes the 54 values into s->q (every spine dof,
 * so the joints outside the range are straightened) and updates the global
 * frames and centres of mass (kin_update). Other dofs are not touched.
 * Returns 0, or -1 with s unchanged, as spine_distribute.
 */
int spine_apply(const struct model *m, struct state *s, const struct spine_flavor *f,
		const double total[3], double shortfall[3]);

/*
 * dest (3): the current total bend per direction, the sum of the flexion,
 * lateral and axial values of spine_0 .. spine_17 in s. Spine joints that m
 * lacks, or that lack 3 dofs, count 0.
 */
void spine_totals(const struct model *m, const struct state *s, double dest[3]);

#endif
