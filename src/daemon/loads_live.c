/* loads_live.c - each figure's loads analysis now, computed when asked and kept while it holds */
#include "daemon/loads_live.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/assess_live.h"
#include "daemon/daemon.h"
#include "daemon/posture_hash.h"

struct loads_live {
	struct loads_live_fig fig[ENV_MAX_FIGURES];
	int known[ENV_MAX_FIGURES]; /* key holds what fig[] (valid or not) was made from */
	char why[ENV_MAX_FIGURES][192];
	uint64_t computed;
	/* the load set of the figure being asked about, before it is known to have changed */
	struct ext_load probe[LOAD_SET_MAX];
	struct load_origin probe_origin[LOAD_SET_MAX];
};

int
loads_live_init(struct daemon *d)
{
	if (d->loads_live)
		return 0;
	d->loads_live = calloc(1, sizeof *d->loads_live);
	return d->loads_live ? 0 : -1;
}

void
loads_live_free(struct daemon *d)
{
	free(d->loads_live);
	d->loads_live = NULL;
}

uint64_t
loads_live_computed(const struct daemon *d)
{
	return d->loads_live ? d->loads_live->computed : 0;
}

int
loads_live_lowback_input(const struct model *m, const struct state *s,
			 const struct statics_result *st, int j, struct lowback_input *dest)
{
	if (j < 0 || j >= st->njoint || j >= m->njnt)
		return -1;
	const double *r = s->seg_xf[st->distal_seg[j]].r; /* row-major: column k is local axis k */
	for (int i = 0; i < 3; i++) {
		/* what the part above puts on the disc: the negative of what holds it up */
		dest->load_force[i] = -st->force[j][i];
		dest->load_moment[i] = -st->moment[j][i];
		dest->disc_normal[i] = r[3 * i + 1];
		dest->anterior[i] = r[3 * i + 2];
	}
	return 0;
}

void
loads_live_strength_input(const struct model *m, const struct state *s,
			  const struct statics_result *st, enum strength_sex sex,
			  struct strength_input *dest, int joint[STRENGTH_NJOINTS])
{
	memset(dest, 0, sizeof *dest);
	dest->sex = sex;
	for (int k = 0; k < STRENGTH_NJOINTS; k++) {
		const char *name = strength_joint_name((enum strength_joint)k);
		int j = model_find_joint(m, !strcmp(name, "l5s1") ? "spine_0" : name);
		if (j < 0 || j >= st->njoint || !st->anatomical[j]) {
			joint[k] = -1;
			continue;
		}
		joint[k] = j;
		for (int a = 0; a < STRENGTH_NAXES; a++) {
			dest->moment[k][a] = st->anat[j][a];
			dest->angle[k][a] = a < m->jnt_ndof[j] ? s->q[m->jnt_dof0[j] + a] * 180 / M_PI : 0;
		}
	}
}

/* a load set's numbers into the hash, field by field (a struct's padding is not hashed) */
static uint64_t
hash_loads(uint64_t h, const struct ext_load *l, const struct load_origin *o, int n)
{
	h = posture_fnv(h, &n, sizeof n);
	for (int k = 0; k < n; k++) {
		h = posture_fnv(h, &l[k].seg, sizeof l[k].seg);
		h = posture_fnv(h, l[k].local, sizeof l[k].local);
		h = posture_fnv(h, l[k].force, sizeof l[k].force);
		h = posture_fnv(h, l[k].torque, sizeof l[k].torque);
		h = posture_fnv(h, &l[k].mass, sizeof l[k].mass);
		h = posture_fnv(h, &o[k].load, sizeof o[k].load);
		h = posture_fnv(h, &o[k].carried, sizeof o[k].carried);
		h = posture_fnv(h, &o[k].side, sizeof o[k].side);
	}
	return h;
}

/* what an analysis of the figure is made from: posture, support, loads, the environment */
static uint64_t
key_of(const struct daemon *d, int fig, int seated, const struct ext_load *l,
       const struct load_origin *o, int n)
{
	const struct env_figure *f = &d->env.fig[fig];
	uint64_t h = state_hash(f->model, f->state);
	h = posture_fnv(h, &f->gen, sizeof f->gen);
	h = posture_fnv(h, &f->model, sizeof f->model);
	h = posture_fnv(h, &seated, sizeof seated);
	/* a command's change that no number above shows (a site moved on its segment) */
	h = posture_fnv(h, &d->mutations, sizeof d->mutations);
	return hash_loads(h, l, o, n);
}

/* the low back and strength of a human whose statics are solved */
static void
human_parts(const struct env_figure *f, struct loads_live_fig *a)
{
	char err[160];
	a->spine0 = model_find_joint(f->model, "spine_0");
	a->low_back = 0;
	if (a->spine0 < 0) {
		snprintf(a->lb_why, sizeof a->lb_why, "%s has no spine_0 (L5/S1) joint", f->name);
	} else if (loads_live_lowback_input(f->model, f->state, &a->st, a->spine0, &a->lbin) < 0 ||
		   lowback_compute(&a->lbin, &a->lb, err, sizeof err) < 0) {
		snprintf(a->lb_why, sizeof a->lb_why, "%s", err);
	} else {
		a->low_back = 1;
		a->lb_why[0] = '\0';
	}
	enum strength_sex sex = f->human.sex == HUMAN_FEMALE ? STRENGTH_FEMALE : STRENGTH_MALE;
	loads_live_strength_input(f->model, f->state, &a->st, sex, &a->sin, a->sin_joint);
	a->strength = strength_capable(&a->sin, &a->sr, err, sizeof err) == 0;
	if (a->strength)
		a->sr_why[0] = '\0';
	else
		snprintf(a->sr_why, sizeof a->sr_why, "%s", err);
}

/* figure slot fig (occupied) analysed under the loads in the probe, into L */
static void
compute(struct daemon *d, struct loads_live *L, int fig, uint64_t key, int seated, int n)
{
	const struct env_figure *f = &d->env.fig[fig];
	struct loads_live_fig *a = &L->fig[fig];
	L->known[fig] = 1;
	L->computed++;
	a->key = key;
	a->valid = 0;
	a->seated = seated;
	a->nloads = n;
	memcpy(a->loads, L->probe, sizeof *a->loads * (size_t)n);
	memcpy(a->origin, L->probe_origin, sizeof *a->origin * (size_t)n);
	L->why[fig][0] = '\0';
	char err[160];
	if (statics_solve(f->model, f->state, a->loads, n, seated, &a->st, err, sizeof err) < 0) {
		snprintf(L->why[fig], sizeof L->why[fig], "%s: %s", f->name, err);
		return;
	}
	a->human = f->is_human;
	a->low_back = a->strength = 0;
	a->spine0 = -1;
	if (a->human)
		human_parts(f, a);
	a->valid = 1;
}

/* the cache entry of fig brought up to date; NULL for no figure or out of memory */
static struct loads_live *
update(struct daemon *d, int fig)
{
	if (fig < 0 || fig >= ENV_MAX_FIGURES || !d->env.fig[fig].gen)
		return NULL;
	if (!d->loads_live && loads_live_init(d) < 0)
		return NULL;
	struct loads_live *L = d->loads_live;
	int seated = assess_live_seated(&d->env, fig);
	int n = load_set_of(&d->env, fig, L->probe, L->probe_origin, LOAD_SET_MAX);
	if (n < 0) { /* cannot happen with LOAD_SET_MAX: told all the same */
		L->known[fig] = 0;
		L->fig[fig].valid = 0;
		snprintf(L->why[fig], sizeof L->why[fig], "%s: more loads than %d", d->env.fig[fig].name,
			 LOAD_SET_MAX);
		return L;
	}
	uint64_t key = key_of(d, fig, seated, L->probe, L->probe_origin, n);
	if (!L->known[fig] || L->fig[fig].key != key)
		compute(d, L, fig, key, seated, n);
	return L;
}

const struct loads_live_fig *
loads_live_of(struct daemon *d, int fig)
{
	struct loads_live *L = update(d, fig);
	return L && L->fig[fig].valid ? &L->fig[fig] : NULL;
}

const char *
loads_live_why(struct daemon *d, int fig)
{
	if (fig < 0 || fig >= ENV_MAX_FIGURES || !d->env.fig[fig].gen)
		return "no figure";
	struct loads_live *L = update(d, fig);
	if (!L)
		return "out of memory";
	return L->fig[fig].valid ? "" : L->why[fig];
}
