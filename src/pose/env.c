/* env.c - figures, constraints and their ids */
#include "pose/env.h"

#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "figure/kin.h"

void
env_init(struct env *e)
{
	memset(e, 0, sizeof *e);
	e->next_gen = 1;
}

static void
free_figure(struct env_figure *f)
{
	free(f->behave);
	ik_free(f->ik);
	state_free(f->state);
	model_free(f->model);
	memset(f, 0, sizeof *f);
}

void
env_clear(struct env *e)
{
	for (int i = 0; i < ENV_MAX_FIGURES; i++)
		if (e->fig[i].gen)
			free_figure(&e->fig[i]);
	memset(e->con, 0, sizeof e->con);
	memset(e->load, 0, sizeof e->load);
	memset(e->view, 0, sizeof e->view);
	memset(e->att, 0, sizeof e->att);
	memset(&e->show, 0, sizeof e->show);
}

static int
figure_named(const struct env *e, const char *name)
{
	for (int i = 0; i < ENV_MAX_FIGURES; i++)
		if (e->fig[i].gen && !strcmp(e->fig[i].name, name))
			return i;
	return -1;
}

static int
constraint_named(const struct env *e, const char *name)
{
	for (int i = 0; i < ENV_MAX_CONSTRAINTS; i++)
		if (e->con[i].gen && !strcmp(e->con[i].name, name))
			return i;
	return -1;
}

int
env_add_figure(struct env *e, struct model *model, const char *name, int is_human,
	       const struct human_def *human, const char *path)
{
	char auto_name[MODEL_NAME_MAX];
	if (!name) { /* the model's name, made unique with a number */
		snprintf(auto_name, sizeof auto_name, "%s", model->name);
		for (int k = 2; figure_named(e, auto_name) >= 0; k++)
			snprintf(auto_name, sizeof auto_name, "%.40s%u", model->name, (unsigned)k % 1000u);
		name = auto_name;
	}
	int slot = -1;
	for (int i = 0; i < ENV_MAX_FIGURES && slot < 0; i++)
		if (!e->fig[i].gen)
			slot = i;
	int err = figure_named(e, name) >= 0 ? ENV_EXISTS : slot < 0 ? ENV_FULL : ENV_OK;
	if (err) {
		model_free(model);
		return err;
	}
	struct env_figure *f = &e->fig[slot];
	f->state = state_make(model);
	f->ik = ik_make(model, ENV_MAX_CONSTRAINTS + BEHAVE_NCON);
	if (!f->state || !f->ik) {
		state_free(f->state);
		ik_free(f->ik);
		model_free(model);
		memset(f, 0, sizeof *f);
		return ENV_FULL;
	}
	kin_update(model, f->state);
	f->model = model;
	f->gen = e->next_gen++;
	snprintf(f->name, sizeof f->name, "%s", name);
	f->is_human = is_human;
	if (human)
		f->human = *human;
	snprintf(f->path, sizeof f->path, "%s", path ? path : "");
	f->manikin = (struct env_manikin){ .percentile = NAN, .coverage = NAN };
	return slot;
}

void
env_remove_figure(struct env *e, int slot)
{
	for (int i = 0; i < ENV_MAX_CONSTRAINTS; i++)
		if (e->con[i].gen && e->con[i].fig == slot)
			memset(&e->con[i], 0, sizeof e->con[i]);
	for (int i = 0; i < ENV_MAX_LOADS; i++)
		if (e->load[i].gen && e->load[i].fig == slot)
			memset(&e->load[i], 0, sizeof e->load[i]);
	for (int i = 0; i < ENV_MAX_ATTACH; i++) /* what held it or it held lets go */
		if (e->att[i].used && (e->att[i].fig == slot || e->att[i].obj == slot))
			memset(&e->att[i], 0, sizeof e->att[i]);
	free_figure(&e->fig[slot]);
}

/* "<prefix><slot>.<gen>" -> slot, or an env_err */
static int
parse_id(const char *ref, char prefix, int nslots, const uint32_t *gens, size_t stride)
{
	if (ref[0] != prefix)
		return ENV_NOT_FOUND;
	char *end;
	long slot = strtol(ref + 1, &end, 10);
	if (end == ref + 1 || *end != '.' || slot < 0 || slot >= nslots)
		return ENV_NOT_FOUND;
	const char *g = end + 1;
	unsigned long gen = strtoul(g, &end, 10);
	if (end == g || *end || g[0] == '-')
		return ENV_NOT_FOUND;
	uint32_t have = *(const uint32_t *)((const char *)gens + stride * (size_t)slot);
	if (!have)
		return ENV_NOT_FOUND; /* nothing there now */
	return have == gen ? (int)slot : ENV_STALE; /* the slot holds something newer */
}

int
env_find_figure(const struct env *e, const char *ref)
{
	int slot = figure_named(e, ref);
	if (slot >= 0)
		return slot;
	return parse_id(ref, 'f', ENV_MAX_FIGURES, &e->fig[0].gen, sizeof e->fig[0]);
}

int
env_find_constraint(const struct env *e, const char *ref)
{
	int slot = constraint_named(e, ref);
	if (slot >= 0)
		return slot;
	return parse_id(ref, 'c', ENV_MAX_CONSTRAINTS, &e->con[0].gen, sizeof e->con[0]);
}

static int
load_named(const struct env *e, const char *name)
{
	for (int i = 0; i < ENV_MAX_LOADS; i++)
		if (e->load[i].gen && !strcmp(e->load[i].name, name))
			return i;
	return -1;
}

int
env_find_load(const struct env *e, const char *ref)
{
	int slot = load_named(e, ref);
	if (slot >= 0)
		return slot;
	return parse_id(ref, 'l', ENV_MAX_LOADS, &e->load[0].gen, sizeof e->load[0]);
}

void
env_load_id(const struct env *e, int slot, char dest[32])
{
	snprintf(dest, 32, "l%d.%u", slot, e->load[slot].gen);
}

void
env_figure_id(const struct env *e, int slot, char dest[32])
{
	snprintf(dest, 32, "f%d.%u", slot, e->fig[slot].gen);
}

void
env_constraint_id(const struct env *e, int slot, char dest[32])
{
	snprintf(dest, 32, "c%d.%u", slot, e->con[slot].gen);
}

int
env_add_constraint(struct env *e, int fig, const char *name, const struct ik_constraint_def *def)
{
	char auto_name[MODEL_NAME_MAX];
	if (!name) {
		for (int k = 1;; k++) {
			snprintf(auto_name, sizeof auto_name, "c%d", k);
			if (constraint_named(e, auto_name) < 0)
				break;
		}
		name = auto_name;
	}
	if (constraint_named(e, name) >= 0)
		return ENV_EXISTS;
	for (int i = 0; i < ENV_MAX_CONSTRAINTS; i++) {
		struct env_constraint *c = &e->con[i];
		if (c->gen)
			continue;
		c->gen = e->next_gen++;
		snprintf(c->name, sizeof c->name, "%s", name);
		c->fig = fig;
		c->def = *def;
		e->fig[fig].ik_stale = 1;
		return i;
	}
	return ENV_FULL;
}

static double
norm3(const double v[3])
{
	return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* def a load this environment can hold: its figure and site there, its numbers finite and sane */
static int
load_valid(const struct env *e, const struct env_load *d)
{
	if (d->fig < 0 || d->fig >= ENV_MAX_FIGURES || !e->fig[d->fig].gen || d->site < 0 ||
	    d->site >= e->fig[d->fig].model->nsite)
		return 0;
	for (int k = 0; k < 3; k++)
		if (!isfinite(d->force[k]) || !isfinite(d->torque[k]))
			return 0;
	if (!(norm3(d->force) <= ENV_LOAD_FORCE_MAX) || !(norm3(d->torque) <= ENV_LOAD_TORQUE_MAX) ||
	    !(d->mass >= 0 && d->mass <= ENV_LOAD_MASS_MAX))
		return 0;
	/* a weight is its mass's pull down and nothing else */
	return d->mass == 0 || (d->force[0] == 0 && d->force[1] == -d->mass * LOAD_GRAVITY &&
				d->force[2] == 0 && norm3(d->torque) == 0);
}

int
env_add_load(struct env *e, const char *name, const struct env_load *def)
{
	char auto_name[MODEL_NAME_MAX];
	if (!name) {
		for (int k = 1;; k++) {
			snprintf(auto_name, sizeof auto_name, "l%d", k);
			if (load_named(e, auto_name) < 0)
				break;
		}
		name = auto_name;
	}
	if (!load_valid(e, def))
		return ENV_BAD;
	if (load_named(e, name) >= 0)
		return ENV_EXISTS;
	for (int i = 0; i < ENV_MAX_LOADS; i++) {
		struct env_load *l = &e->load[i];
		if (l->gen)
			continue;
		*l = *def;
		l->gen = e->next_gen++;
		snprintf(l->name, sizeof l->name, "%s", name);
		return i;
	}
	return ENV_FULL;
}

void
env_remove_load(struct env *e, int slot)
{
	memset(&e->load[slot], 0, sizeof e->load[slot]);
}

void
env_remove_constraint(struct env *e, int slot)
{
	e->fig[e->con[slot].fig].ik_stale = 1;
	memset(&e->con[slot], 0, sizeof e->con[slot]);
}

void
env_set_constraint(struct env *e, int slot, const struct ik_constraint_def *def)
{
	struct env_constraint *c = &e->con[slot];
	struct env_figure *f = &e->fig[c->fig];
	int idx = env_solver_index(e, slot);
	int only_goal = !f->ik_stale && idx >= 0 && c->def.enabled == def->enabled;
	c->def = *def;
	if (only_goal) /* a moved goal: no chain is rebuilt */
		ik_set(f->ik, f->model, idx, def);
	else
		f->ik_stale = 1;
}

int
env_solver_index(const struct env *e, int slot)
{
	const struct env_constraint *c = &e->con[slot];
	if (!c->gen || e->fig[c->fig].ik_stale)
		return -1;
	/* the solver holds the figure's constraints in slot order */
	int idx = 0;
	for (int i = 0; i < slot; i++)
		idx += e->con[i].gen && e->con[i].fig == c->fig;
	return idx;
}

void
env_sync_solver(struct env *e, int fig)
{
	struct env_figure *f = &e->fig[fig];
	if (!f->ik_stale)
		return;
	/* the behaviours' own constraints go after the client's */
	if (f->behave)
		behave_keep_constraints(f->behave, f->ik);
	ik_clear(f->ik);
	for (int i = 0; i < ENV_MAX_CONSTRAINTS; i++)
		if (e->con[i].gen && e->con[i].fig == fig)
			ik_add(f->ik, f->model, &e->con[i].def);
	if (f->behave)
		behave_restore_constraints(f->behave, f->model, f->ik);
	f->ik_stale = 0;
}

int
env_count(const struct env *e)
{
	int n = 0;
	for (int i = 0; i < ENV_MAX_FIGURES; i++)
		n += e->fig[i].gen != 0;
	return n;
}

int
env_find_view(const struct env *e, const char *name)
{
	for (int i = 0; i < ENV_MAX_VIEWS; i++)
		if (e->view[i].used && !strcmp(e->view[i].name, name))
			return i;
	return -1;
}

static const char *const tint_names[ENV_TINT_N] = { "off", "rula", "reba", "owas", "strength" };

const char *
env_tint_str(int tint)
{
	return tint >= 0 && tint < ENV_TINT_N ? tint_names[tint] : "?";
}

int
env_tint_find(const char *name)
{
	for (int i = 0; i < ENV_TINT_N; i++)
		if (!strcmp(tint_names[i], name))
			return i;
	return -1;
}

void
env_place_site(struct env *e, int fig, int site, const struct xform *loc)
{
	struct env_figure *f = &e->fig[fig];
	double q[4];
	mathx_mat_to_quat(loc->r, q);
	struct xform seg;
	int root = site == f->state->root_site;
	if (root)
		xform_mul(&f->state->site_xf[site], &f->model->site_loc_inv[site], &seg);
	model_set_site(f->model, site, loc->p, q);
	if (root)
		xform_mul(&seg, &f->model->site_loc[site], &f->state->root_xf);
	f->ik_stale = 1;
	kin_update(f->model, f->state);
}
