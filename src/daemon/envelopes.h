/*
 * envelopes.h - the reach envelopes the daemon keeps (analyze reach): each
 * under its name, with the figure it was computed for, drawn in every view
 * unless hidden, until replaced, removed, or its figure goes.
 *
 * An envelope is a derived result, like a reply: it is not part of the
 * environment, so sessions, undo checkpoints and the journal do not hold
 * it (recomputing takes seconds and gives the same surface). An undo or a
 * session load that takes its figure away takes it too (envelopes_prune).
 */
#ifndef POSTURE_ENVELOPES_H
#define POSTURE_ENVELOPES_H

#include <stdint.h>

#include "assess/envelope.h"
#include "pose/env.h"

#define ENVELOPES_MAX 64  /* a family of 40 and a few more */
#define ENVELOPE_NAME_MAX 96

/* how the views draw an envelope and the exports colour it: see-through blue, the comfort
 * zone green */
extern const float ENVELOPE_REACH_RGBA[4];
extern const float ENVELOPE_COMFORT_RGBA[4];

struct envelope_entry {
	int used;
	char name[ENVELOPE_NAME_MAX];
	int fig;                      /* the figure's slot, its generation and name when computed */
	uint32_t gen;
	char fig_name[MODEL_NAME_MAX];
	int hidden;                   /* 1: not drawn */
	uint64_t serial;              /* new with each envelope put here (what the views uploaded) */
	struct envelope e;
};

struct envelopes {
	struct envelope_entry slot[ENVELOPES_MAX];
	uint64_t serial; /* counts every change: a put, a hide, a removal */
};

/* the slot named name, or -1 */
int envelopes_find(const struct envelopes *s, const char *name);

/*
 * Keeps e (taken over: the caller must not free it) under name for figure
 * slot fig of env, replacing an envelope of that name. Returns the slot,
 * or -1 when every slot holds another name (e is then freed).
 */
int envelopes_put(struct envelopes *s, const char *name, const struct env *env, int fig,
		  struct envelope *e);

/* the envelope in slot k freed, the slot emptied */
void envelopes_remove(struct envelopes *s, int k);

/* shows (hidden 0) or hides envelope k */
void envelopes_set_hidden(struct envelopes *s, int k, int hidden);

/*
 * Removes the envelopes whose figure is gone from env: its slot empty or
 * holding another generation or name. Returns how many went.
 */
int envelopes_prune(struct envelopes *s, const struct env *env);

/* how many are kept */
int envelopes_count(const struct envelopes *s);

/* every envelope freed (s itself is the caller's) */
void envelopes_clear(struct envelopes *s);

#endif
