/* assess_live.c - each figure's assessment now, computed when asked and kept while it holds */
#include "daemon/assess_live.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assess/owas.h"
#include "assess/reba.h"
#include "assess/rula.h"
#include "daemon/daemon.h"
#include "daemon/posture_hash.h"

struct assess_live {
	struct assess_live_fig fig[ENV_MAX_FIGURES];
	int known[ENV_MAX_FIGURES]; /* key holds what fig[] (valid or not) was made from */
	char why[ENV_MAX_FIGURES][192];
	uint64_t computed;
};

int
assess_live_init(struct daemon *d)
{
	if (d->assess_live)
		return 0;
	d->assess_live = calloc(1, sizeof *d->assess_live);
	return d->assess_live ? 0 : -1;
}

void
assess_live_free(struct daemon *d)
{
	free(d->assess_live);
	d->assess_live = NULL;
}

uint64_t
assess_live_computed(const struct daemon *d)
{
	return d->assess_live ? d->assess_live->computed : 0;
}

double
assess_live_held_kg(const struct env *e, int fig)
{
	int counted[ENV_MAX_FIGURES] = { 0 };
	double kg = 0;
	for (int i = 0; i < ENV_MAX_ATTACH; i++) {
		const struct env_attach *a = &e->att[i];
		if (!a->used || a->fig != fig || a->kind != ATTACH_GRAB || a->obj < 0 ||
		    a->obj >= ENV_MAX_FIGURES || !e->fig[a->obj].gen || counted[a->obj])
			continue;
		counted[a->obj] = 1; /* one object in both hands weighs once */
		kg += e->fig[a->obj].model->total_mass;
	}
	return kg;
}

int
assess_live_seated(const struct env *e, int fig)
{
	const struct behave *b = e->fig[fig].behave;
	return b && b->p.seated;
}

/* what an assessment of the figure is made from: posture, support, load, the settings */
static uint64_t
key_of(const struct daemon *d, int fig, int seated, double load)
{
	const struct env_figure *f = &d->env.fig[fig];
	uint64_t h = state_hash(f->model, f->state);
	h = posture_fnv(h, &f->gen, sizeof f->gen);
	h = posture_fnv(h, &f->model, sizeof f->model);
	h = posture_fnv(h, &seated, sizeof seated);
	h = posture_fnv(h, &load, sizeof load);
	return posture_fnv(h, &d->assess_serial, sizeof d->assess_serial);
}

/* the assessment of figure slot fig (occupied) under the settings now, into L */
static void
compute(struct daemon *d, struct assess_live *L, int fig, uint64_t key, int seated, double load)
{
	const struct env_figure *f = &d->env.fig[fig];
	struct assess_live_fig *a = &L->fig[fig];
	struct assess_config cfg = daemon_assess_config(d);
	L->known[fig] = 1;
	L->computed++;
	a->key = key;
	a->valid = 0;
	a->load_kg = load;
	L->why[fig][0] = '\0';
	if (!f->is_human) {
		snprintf(L->why[fig], sizeof L->why[fig], "%s is not a human figure: the assessments "
			 "score a human's posture", f->name);
		return;
	}
	char err[160];
	if (body_angles_measure(f->model, f->state, seated, cfg.kneel_height, &a->angles, err,
				sizeof err) < 0) {
		snprintf(L->why[fig], sizeof L->why[fig], "%s: %s", f->name, err);
		return;
	}
	struct rula_options ro = rula_options_default();
	ro.side = ASSESS_SIDE_WORSE;
	ro.load_kg = load;
	rula_score(&a->angles, &cfg, &ro, &a->res[ASSESS_RULA]);
	struct reba_options eo = reba_options_default();
	eo.side = ASSESS_SIDE_WORSE;
	eo.load_kg = load;
	reba_score(&a->angles, &cfg, &eo, &a->res[ASSESS_REBA]);
	struct owas_options oo = { .load_kg = load };
	owas_score(&a->angles, &cfg, &oo, &a->res[ASSESS_OWAS]);
	a->valid = 1;
}

/* the cache entry of fig brought up to date; NULL for no figure or out of memory */
static struct assess_live *
update(struct daemon *d, int fig)
{
	if (fig < 0 || fig >= ENV_MAX_FIGURES || !d->env.fig[fig].gen)
		return NULL;
	if (!d->assess_live && assess_live_init(d) < 0)
		return NULL;
	struct assess_live *L = d->assess_live;
	int seated = assess_live_seated(&d->env, fig);
	double load = assess_live_held_kg(&d->env, fig);
	uint64_t key = key_of(d, fig, seated, load);
	if (!L->known[fig] || L->fig[fig].key != key)
		compute(d, L, fig, key, seated, load);
	return L;
}

const struct assess_live_fig *
assess_live_of(struct daemon *d, int fig)
{
	struct assess_live *L = update(d, fig);
	return L && L->fig[fig].valid ? &L->fig[fig] : NULL;
}

const char *
assess_live_why(struct daemon *d, int fig)
{
	if (fig < 0 || fig >= ENV_MAX_FIGURES || !d->env.fig[fig].gen)
		return "no figure";
	struct assess_live *L = update(d, fig);
	if (!L)
		return "out of memory";
	return L->fig[fig].valid ? "" : L->why[fig];
}
