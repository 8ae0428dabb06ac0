/*
 * cmd_load.c - the loads on the figures as the environment's objects: a
 * force (and torque) or a weight at a site (add load), listed with what
 * the hands carry (list loads), removed (delete load). What they do to the
 * body is cmd_loads.c's.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "pose/load_set.h"

static const char *const add_keys[] = { "force", "torque", "mass", NULL };

/* "mass=KG": a bare number or one ending in "kg"; 0, or -1 */
static int
kilograms(const char *v, double *kg)
{
	char num[64];
	size_t n = strlen(v);
	if (n > 2 && !strcmp(v + n - 2, "kg"))
		n -= 2;
	if (n >= sizeof num)
		return -1;
	memcpy(num, v, n);
	num[n] = '\0';
	return words_number(num, UNIT_NONE, kg);
}

static double
norm3(const double v[3])
{
	return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* the arguments after FIG SEG.SITE: key=value of add_keys, "as NAME"; else the error set */
static int
only_known(struct cmd_ctx *c)
{
	for (int i = 2; i < c->argc; i++) {
		if (!strcmp(c->argv[i], "as")) {
			i++; /* its name is checked by cmd_as_name */
			continue;
		}
		int ok = 0;
		for (const char *const *k = add_keys; *k && !ok; k++)
			ok = words_is_key(c->argv[i], *k);
		if (!ok)
			return cmd_fail(c, "bad-argument",
					"unexpected '%.60s' (add load takes force=, torque=, mass=, as NAME)",
					c->argv[i]);
	}
	return 0;
}

/* the load the arguments describe, into l (fig and site set); 0, or -1 with the error set */
static int
load_of_args(struct cmd_ctx *c, struct env_load *l)
{
	const char *force = cmd_key(c, "force"), *torque = cmd_key(c, "torque"),
		   *mass = cmd_key(c, "mass");
	if (!force == !mass)
		return cmd_fail(c, "arity", "a load is force=FX,FY,FZ [torque=TX,TY,TZ] (N, N m) or "
				"mass=KG (a weight), one of the two");
	if (mass && torque)
		return cmd_fail(c, "bad-argument", "a weight (mass=) pulls straight down: no torque=");
	if (mass) {
		if (kilograms(mass, &l->mass) < 0 || !(l->mass > 0 && l->mass <= ENV_LOAD_MASS_MAX))
			return cmd_fail(c, "bad-number", "mass: a weight in kg above 0 and at most %g, "
					"not '%.30s'", ENV_LOAD_MASS_MAX, mass);
		l->force[1] = -l->mass * LOAD_GRAVITY;
		return 0;
	}
	if (words_list(force, UNIT_NONE, 3, l->force) < 0)
		return cmd_fail(c, "bad-number", "force=FX,FY,FZ: three finite numbers of newtons "
				"(world frame, y up), not '%.40s'", force);
	if (torque && words_list(torque, UNIT_NONE, 3, l->torque) < 0)
		return cmd_fail(c, "bad-number", "torque=TX,TY,TZ: three finite numbers of newton "
				"metres (world frame, y up), not '%.40s'", torque);
	if (!(norm3(l->force) <= ENV_LOAD_FORCE_MAX))
		return cmd_fail(c, "bad-number", "force: at most %g N (a body gives way long before)",
				ENV_LOAD_FORCE_MAX);
	if (!(norm3(l->torque) <= ENV_LOAD_TORQUE_MAX))
		return cmd_fail(c, "bad-number", "torque: at most %g N m", ENV_LOAD_TORQUE_MAX);
	return 0;
}

int
cmd_add_load(struct cmd_ctx *c)
{
	struct env *e = &c->d->env;
	int fig = cmd_figure(c, c->argv[0]), bad;
	if (fig < 0 || only_known(c) < 0)
		return -1;
	const char *name = cmd_as_name(c, &bad);
	if (bad)
		return -1;
	const struct model *m = e->fig[fig].model;
	struct env_load l = { .fig = fig, .site = model_find_site(m, c->argv[1]) };
	if (l.site < 0)
		return cmd_fail(c, "not-found", "%s has no site '%.60s' (SEG.SITE: show figure %s lists "
				"them)", e->fig[fig].name, c->argv[1], e->fig[fig].name);
	if (load_of_args(c, &l) < 0)
		return -1;
	if (name && env_find_load(e, name) >= 0)
		return cmd_fail(c, "exists", "a load named '%s' exists", name);
	int slot = env_add_load(e, name, &l);
	if (slot == ENV_FULL)
		return cmd_fail(c, "limit", "%d loads at most", ENV_MAX_LOADS);
	if (slot < 0) /* the arguments were checked: only a name clash or a bug is left */
		return cmd_fail(c, slot == ENV_EXISTS ? "exists" : "internal", "the load was not added");
	char id[32];
	env_load_id(e, slot, id);
	json_object_set_new(c->result, "load", json_string(id));
	json_object_set_new(c->result, "name", json_string(e->load[slot].name));
	return 0;
}

int
cmd_delete_load(struct cmd_ctx *c)
{
	struct env *e = &c->d->env;
	int slot = cmd_load_ref(c, c->argv[0]);
	if (slot < 0)
		return -1;
	env_remove_load(e, slot);
	return 0;
}

/* a load's point in the world now */
static void
world_point(const struct env_figure *f, const struct ext_load *x, double w[3])
{
	xform_apply(&f->state->seg_xf[x->seg], x->local, w);
}

static json_t *
env_load_json(const struct env *e, int k)
{
	const struct env_load *l = &e->load[k];
	const struct env_figure *f = &e->fig[l->fig];
	char id[32], site[2 * MODEL_NAME_MAX];
	env_load_id(e, k, id);
	json_t *o = json_object();
	json_object_set_new(o, "load", json_string(id));
	json_object_set_new(o, "name", json_string(l->name));
	json_object_set_new(o, "figure", json_string(f->name));
	json_object_set_new(o, "site", json_string(model_site_fullname(f->model, l->site, site,
									sizeof site)));
	json_object_set_new(o, "force", cmd_vec(l->force, 3));
	json_object_set_new(o, "torque", cmd_vec(l->torque, 3));
	json_object_set_new(o, "mass", l->mass > 0 ? json_real(l->mass) : json_null());
	json_object_set_new(o, "position", cmd_vec(f->state->site_xf[l->site].p, 3));
	return o;
}

/* what the hands of figure slot fig carry now: each share of a carried object's weight and loads */
static int
carried_json(struct cmd_ctx *c, int fig, json_t *list)
{
	static struct ext_load set[LOAD_SET_MAX];
	static struct load_origin from[LOAD_SET_MAX];
	const struct env *e = &c->d->env;
	int n = load_set_of(e, fig, set, from, LOAD_SET_MAX);
	if (n < 0)
		return cmd_fail(c, "internal", "the loads on %s did not fit", e->fig[fig].name);
	for (int k = 0; k < n; k++) {
		if (from[k].carried < 0)
			continue;
		double at[3];
		world_point(&e->fig[fig], &set[k], at);
		char id[32];
		json_t *o = json_object();
		json_object_set_new(o, "figure", json_string(e->fig[fig].name));
		json_object_set_new(o, "hand", json_string(from[k].side ? "right" : "left"));
		json_object_set_new(o, "object", json_string(e->fig[from[k].carried].name));
		if (from[k].load >= 0)
			env_load_id(e, from[k].load, id);
		json_object_set_new(o, "load", from[k].load >= 0 ? json_string(id) : json_null());
		json_object_set_new(o, "share", json_real(from[k].share));
		json_object_set_new(o, "force", cmd_vec(set[k].force, 3));
		json_object_set_new(o, "torque", cmd_vec(set[k].torque, 3));
		int weight = from[k].load < 0 || e->load[from[k].load].mass > 0; /* its share may be 0 */
		json_object_set_new(o, "mass", weight ? json_real(set[k].mass) : json_null());
		json_object_set_new(o, "position", cmd_vec(at, 3));
		json_array_append_new(list, o);
	}
	return 0;
}

int
cmd_list_loads(struct cmd_ctx *c)
{
	struct env *e = &c->d->env;
	int only = -1;
	if (c->argc == 1 && (only = cmd_figure(c, c->argv[0])) < 0)
		return -1;
	json_t *loads = json_array(), *carried = json_array();
	for (int k = 0; k < ENV_MAX_LOADS; k++)
		if (e->load[k].gen && (only < 0 || e->load[k].fig == only))
			json_array_append_new(loads, env_load_json(e, k));
	for (int i = 0; i < ENV_MAX_FIGURES; i++)
		if (e->fig[i].gen && (only < 0 || i == only) && carried_json(c, i, carried) < 0) {
			json_decref(loads);
			json_decref(carried);
			return -1;
		}
	json_object_set_new(c->result, "loads", loads);
	json_object_set_new(c->result, "carried", carried);
	return 0;
}
