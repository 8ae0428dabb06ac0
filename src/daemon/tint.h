/*
 * tint.h - a view's tint (set view VIEW tint=rula|reba|owas): each human's
 * body parts drawn in the colour of their part score (assess_tint.h's
 * rule: the action level with that part alone as measured), so a person
 * dragging sees which joint to fix; and the key in the view's corner.
 *
 * The parts to the human's segments (figure/human.c's names):
 *   upper_arm  clavicle_S, upperarm_S    (RULA/REBA: the scored side S)
 *   lower_arm  forearm_S
 *   wrist      hand_S (RULA: the worse of wrist and wrist_twist)
 *   neck       head
 *   trunk      pelvis, L5 .. L1, T12 .. T1
 *   legs       thigh, shank, foot, toes of both sides
 * OWAS: arms colours both arms whole, back the trunk, legs the legs. A
 * segment a method does not score there (the other side's arm of a
 * one-sided RULA or REBA, the head in OWAS) is drawn grey; the eyeballs
 * and what no part names keep their own colours.
 *
 * tint=strength colours the segment just below each strength joint (the
 * part the joint's muscles hold up) by the joint's percent capable under
 * the posture and its loads (strength.h), its weakest axis, in
 * strength_band's bands: green >= 99 % (NIOSH 1981's action limit, men),
 * yellow 75-99 % (the UAW-GM guideline's 75 %), orange 25-75 %, red < 25 %
 * (below NIOSH's maximum permissible limit, men):
 *   wrist  hand_S         elbow  forearm_S      shoulder  upperarm_S
 *   L5/S1  L5 .. L1, T12 .. T1                  hip       thigh_S
 *   knee   shank_S        ankle  foot_S, toes_S
 * A joint no published curve covers (strength.c: NAN on every axis) is
 * drawn grey; the pelvis, the clavicles, the head and the eyeballs keep
 * their own colours.
 *
 * The colours are made in fixed arrays: nothing allocates in the frame.
 */
#ifndef POSTURE_DAEMON_TINT_H
#define POSTURE_DAEMON_TINT_H

#include <stdint.h>

#include "assess/assess.h"
#include "assess/strength.h"
#include "daemon/daemon.h"
#include "draw/view.h"

#define TINT_MAX_SEG 64 /* segments a tinted figure may have (the human has 37) */

/* the colours of enum assess_colour, and of a segment the method does not score */
extern const float tint_rgba[4][4];
extern const float tint_unscored_rgba[4];

/*
 * What a segment is to the tint: the region of a part (a tint_region),
 * and the side for an arm's; cached per figure slot, made again when the
 * slot holds another model.
 */
struct tint_map {
	const struct model *model;
	uint32_t gen;
	int ok; /* 0: not a human's segments (drawn in its own colours) */
	signed char region[TINT_MAX_SEG]; /* enum tint_region, -1: none */
	signed char side[TINT_MAX_SEG];   /* enum body_side of an arm's segment, else -1 */
	signed char joint[TINT_MAX_SEG];  /* enum strength_joint just above it, -1: none */
};

struct tint {
	struct tint_map map[ENV_MAX_FIGURES];
	float rgba[4 * TINT_MAX_SEG]; /* the figure being drawn's colours */
};

/*
 * The colours of figure slot fig's segments under tint (enum env_tint,
 * not off), 4 floats a segment (view_add_figure_rgba), valid until the
 * next call; NULL when the figure is drawn in its own colours (not a
 * human, or no assessment of it).
 */
const float *tint_figure(struct tint *t, struct daemon *d, int fig, int tint);

/*
 * The segment colours of model m for results res_side[side] (enum
 * body_side; NULL: that side's arm not scored; both the same for a method
 * that scores the whole body), into dest (4 floats a segment). The tint's
 * core, without the daemon: 0, or -1 when m is not a human's.
 */
int tint_segments(struct tint_map *map, const struct model *m, uint32_t gen,
		  const struct assess_result *const res_side[2], float *dest);

/*
 * The segment colours of model m for the percent capable of sr (tint=strength,
 * above), into dest (4 floats a segment): 0, or -1 when m is not a human's.
 */
int tint_strength_segments(struct tint_map *map, const struct model *m, uint32_t gen,
			   const struct strength_result *sr, float *dest);

/*
 * The key of tint's colours in the picture's top left corner: the
 * method's name and its four colours, each labelled with the action
 * levels it stands for (strength: the percents of its bands, and grey for
 * no curve). Nothing for tint off.
 */
void tint_legend(struct drawlist *dl, int tint);

#endif
