/*
 * loads_live.h - what the loads do to a figure now: the loads acting on it
 * (load_set.h: its own and its hands' shares of what they carry), the
 * static equilibrium with its supports and every joint's force and moment
 * (statics.h), and for a human the low back (lowback.h) and the percent of
 * the population strong enough (strength.h). Each figure's is computed at
 * most once a frame and only when asked (a subscriber, the status line, a
 * command), and again only when its posture, its support, its loads or the
 * environment (any change a command made) changed. Nothing allocates after
 * loads_live_init.
 */
#ifndef POSTURE_LOADS_LIVE_H
#define POSTURE_LOADS_LIVE_H

#include <stdint.h>

#include "assess/lowback.h"
#include "assess/statics.h"
#include "assess/strength.h"
#include "pose/env.h"
#include "pose/load_set.h"

struct daemon;

struct loads_live_fig {
	int valid;    /* 0: not computed, or the statics refused (loads_live_why) */
	uint64_t key; /* what it was computed from */
	int seated;   /* as its behaviour says */
	int nloads;
	struct ext_load loads[LOAD_SET_MAX];
	struct load_origin origin[LOAD_SET_MAX];
	struct statics_result st;
	int human;                /* 1: a human figure: low back and strength below */
	int spine0;               /* the L5/S1 joint (spine_0), -1: none */
	struct lowback_input lbin; /* what the low back model was given */
	int low_back;             /* 1: lb holds the L5/S1 disc's loads */
	struct lowback_result lb;
	char lb_why[160];         /* why not, when low_back is 0 for a human */
	int strength;             /* 1: sr holds the percent capable */
	struct strength_input sin; /* what strength was given: moments and angles */
	int sin_joint[STRENGTH_NJOINTS]; /* each strength joint's joint of the model, -1: none */
	struct strength_result sr;
	char sr_why[160];
};

/* the loads analysis of figure slot fig now; NULL when it cannot be made (loads_live_why) */
const struct loads_live_fig *loads_live_of(struct daemon *d, int fig);

/* why loads_live_of gave NULL: "no figure", the statics' reason; "" when it did not */
const char *loads_live_why(struct daemon *d, int fig);

/* the cache made (once, before the frame loop): 0, or -1 when out of memory */
int loads_live_init(struct daemon *d);
void loads_live_free(struct daemon *d);

/* how many analyses were computed since loads_live_init (a cached answer counts none) */
uint64_t loads_live_computed(const struct daemon *d);

/*
 * The low back model's input from a solved statics: the resultant of
 * everything above joint j (the L5/S1 joint, spine_0, of a human; its
 * distal part) about its centre, the disc's cranial normal and the
 * figure's forward, both L5's own axes (y and z of its segment frame, the
 * human's conventions). 0, or -1 when j is no joint of the result.
 */
int loads_live_lowback_input(const struct model *m, const struct state *s,
			     const struct statics_result *st, int j, struct lowback_input *dest);

/*
 * The strength model's input from a solved statics of a human: each
 * strength joint's anatomical moments (statics' anat: the same axes and
 * signs) and its angles, the joint's dof values in degrees (flexion,
 * abduction, rotation in the human's ISB order; the elbow and the knee
 * have flexion alone). joint[k]: the model's joint of strength joint k,
 * -1 where the figure has none or the statics give no anatomical moment.
 */
void loads_live_strength_input(const struct model *m, const struct state *s,
			       const struct statics_result *st, enum strength_sex sex,
			       struct strength_input *dest, int joint[STRENGTH_NJOINTS]);

#endif
