/* cmd_constraint.c - creating, moving, switching and listing constraints */
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "figure/kin.h"

static const char *const pos_names[] = { "none", "point", "line", "plane" };
static const char *const ori_names[] = { "none", "frame", "direction", "aim" };

static int
pick(const char *const *names, int n, const char *s)
{
	for (int i = 0; i < n; i++)
		if (!strcmp(names[i], s))
			return i;
	return -1;
}

static int
unit_vector(struct cmd_ctx *c, const char *key, double v[3])
{
	const char *s = cmd_key(c, key);
	if (!s)
		return 0;
	if (words_list(s, UNIT_NONE, 3, v) < 0)
		return cmd_fail(c, "bad-number", "%s=X,Y,Z: three finite numbers", key);
	double n = sqrt(mathx_dot(v, v));
	if (!(n > 1e-12))
		return cmd_fail(c, "bad-argument", "%s: the vector has no length", key);
	for (int i = 0; i < 3; i++)
		v[i] /= n;
	return 0;
}

static const char *const add_keys[] = { "effector", "goal", "goalsite", "pos", "ori", "weight",
					"posweight", "start", "axis", "effaxis", "group", "com",
					"rot" };

/*
 * Applies the key=value arguments (from index `from`) to d: what add and
 * set constraint share. `fresh` chooses defaults that depend on pos and ori.
 */
static int
apply_keys(struct cmd_ctx *c, int from, const struct env_figure *f, struct ik_constraint_def *d,
	   int fresh)
{
	const struct model *m = f->model;
	for (int i = from; i < c->argc; i++) {
		if (!strcmp(c->argv[i], "as") && fresh && i + 1 < c->argc) {
			if (!words_is_name(c->argv[++i]))
				return cmd_fail(c, "bad-argument", "'as' takes a name: letters, digits, '_'");
			continue;
		}
		size_t known = 0;
		for (size_t k = 0; k < sizeof add_keys / sizeof *add_keys; k++)
			known |= words_is_key(c->argv[i], add_keys[k]);
		if (!known || (!fresh && (words_is_key(c->argv[i], "effector") ||
					  words_is_key(c->argv[i], "com"))))
			return cmd_fail(c, "bad-argument", "unexpected '%.60s'", c->argv[i]);
	}
	const char *eff = cmd_key(c, "effector");
	if (fresh && (!eff || (d->effector_site = model_find_site(m, eff)) < 0))
		return cmd_fail(c, eff ? "not-found" : "arity", "effector=SEG.SITE: a site of %s", f->name);
	const char *pos = cmd_key(c, "pos"), *ori = cmd_key(c, "ori");
	int p = pos ? pick(pos_names, 4, pos) : (int)d->pos, o = ori ? pick(ori_names, 4, ori) : (int)d->ori;
	if (p < 0 || o < 0)
		return cmd_fail(c, "bad-argument", "pos=point|line|plane|none, ori=frame|direction|aim|none");
	if (p == IK_POS_NONE && o == IK_ORI_NONE)
		return cmd_fail(c, "bad-argument", "a constraint needs pos= or ori=");
	if (fresh || pos || ori) /* the blend follows the parts present */
		d->pos_weight = o == IK_ORI_NONE ? 1 : p == IK_POS_NONE ? 0 : 0.5;
	d->pos = (enum ik_pos)p;
	d->ori = (enum ik_ori)o;
	const char *w = cmd_key(c, "weight"), *pw = cmd_key(c, "posweight"), *g = cmd_key(c, "group");
	double gv = d->group;
	if ((w && words_number(w, UNIT_NONE, &d->weight) < 0) ||
	    (pw && words_number(pw, UNIT_NONE, &d->pos_weight) < 0) ||
	    (g && words_number(g, UNIT_NONE, &gv) < 0))
		return cmd_fail(c, "bad-number", "weight, posweight and group are numbers");
	if (d->weight < 0)
		return cmd_fail(c, "bad-argument", "weight: a number >= 0");
	if (d->pos_weight < 0 || d->pos_weight > 1)
		return cmd_fail(c, "bad-argument", "posweight: a number from 0 to 1");
	if (gv < 0 || gv > 3 || gv != (int)gv)
		return cmd_fail(c, "bad-argument", "group: 0, 1, 2 or 3");
	d->group = (int)gv;
	const char *start = cmd_key(c, "start"), *com = cmd_key(c, "com");
	if (start && (d->start_joint = !strcmp(start, "-") ? -1 : model_find_joint(m, start)) < 0 &&
	    strcmp(start, "-"))
		return cmd_fail(c, "not-found", "start=%.60s: no such joint", start);
	if (com && strcmp(com, "0") && strcmp(com, "1"))
		return cmd_fail(c, "bad-argument", "com=0|1");
	if (com)
		d->com_effector = !strcmp(com, "1");
	if (unit_vector(c, "axis", d->goal_axis) < 0 || unit_vector(c, "effaxis", d->effector_axis) < 0)
		return -1;
	/* the goal: a site of the figure, a given point, or (new) where the effector is now */
	const char *gs = cmd_key(c, "goalsite"), *gp = cmd_key(c, "goal");
	double r[9];
	int turned;
	if (cmd_rotation(c, r, &turned) < 0)
		return -1;
	if (gs && gp)
		return cmd_fail(c, "bad-argument", "goal= or goalsite=, not both");
	if (fresh)
		d->goal_xf = f->state->site_xf[d->effector_site];
	if (gs) {
		if ((d->goal_site = model_find_site(m, gs)) < 0)
			return cmd_fail(c, "not-found", "goalsite=%.60s: no such site", gs);
		xform_identity(&d->goal_xf);
	} else if (gp) {
		if (words_list(gp, UNIT_LENGTH, 3, d->goal_xf.p) < 0)
			return cmd_fail(c, "bad-number", "goal=X,Y,Z: three lengths");
		d->goal_site = -1;
	}
	if (turned)
		memcpy(d->goal_xf.r, r, sizeof r);
	/* the solver has the last word on what is valid */
	struct ik *probe = f->ik;
	if (ik_add(probe, m, d) < 0)
		return cmd_fail(c, "bad-argument", "not a valid constraint for %s", f->name);
	return 0;
}

int
cmd_add_constraint(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]);
	if (fig < 0)
		return -1;
	struct env *e = &c->d->env;
	struct env_figure *f = &e->fig[fig];
	const char *name = NULL;
	for (int i = 1; i + 1 < c->argc; i++)
		if (!strcmp(c->argv[i], "as"))
			name = c->argv[i + 1];
	struct ik_constraint_def d = ik_constraint_default_def();
	env_sync_solver(e, fig);
	int rc = apply_keys(c, 1, f, &d, 1);
	f->ik_stale = 1; /* the probe's trial constraint goes at the next sync */
	if (rc < 0)
		return -1;
	int slot = env_add_constraint(e, fig, name, &d);
	if (slot == ENV_EXISTS)
		return cmd_fail(c, "exists", "a constraint named '%s' exists", name);
	if (slot < 0)
		return cmd_fail(c, "limit", "%d constraints at most", ENV_MAX_CONSTRAINTS);
	char id[32];
	env_constraint_id(e, slot, id);
	json_object_set_new(c->result, "constraint", json_string(id));
	json_object_set_new(c->result, "name", json_string(e->con[slot].name));
	return 0;
}

int
cmd_set_constraint(struct cmd_ctx *c)
{
	int slot = cmd_constraint(c, c->argv[0]);
	if (slot < 0)
		return -1;
	struct env *e = &c->d->env;
	struct env_figure *f = &e->fig[e->con[slot].fig];
	struct ik_constraint_def d = e->con[slot].def;
	env_sync_solver(e, e->con[slot].fig);
	int rc = apply_keys(c, 1, f, &d, 0);
	f->ik_stale = 1;
	if (rc < 0)
		return -1;
	env_set_constraint(e, slot, &d);
	return 0;
}

static int
goal_update(struct cmd_ctx *c, int relative)
{
	int slot = cmd_constraint(c, c->argv[0]);
	if (slot < 0)
		return -1;
	struct env *e = &c->d->env;
	struct ik_constraint_def d = e->con[slot].def;
	double v[3];
	for (int i = 0; i < 3; i++)
		if (words_number(c->argv[1 + i], UNIT_LENGTH, &v[i]) < 0)
			return cmd_fail(c, "bad-number", "X Y Z: lengths such as 0.3 or 30cm");
	for (int i = 4; i < c->argc; i++)
		if (relative || !words_is_key(c->argv[i], "rot"))
			return cmd_fail(c, "bad-argument", "unexpected '%.60s'", c->argv[i]);
	double r[9];
	int turned;
	if (cmd_rotation(c, r, &turned) < 0)
		return -1;
	for (int i = 0; i < 3; i++)
		d.goal_xf.p[i] = relative ? d.goal_xf.p[i] + v[i] : v[i];
	if (turned)
		memcpy(d.goal_xf.r, r, sizeof r);
	env_set_constraint(e, slot, &d);
	return 0;
}

int
cmd_set_goal(struct cmd_ctx *c)
{
	return goal_update(c, 0);
}

int
cmd_move_goal(struct cmd_ctx *c)
{
	return goal_update(c, 1);
}

static int
switch_constraint(struct cmd_ctx *c, int on)
{
	int slot = cmd_constraint(c, c->argv[0]);
	if (slot < 0)
		return -1;
	struct ik_constraint_def d = c->d->env.con[slot].def;
	d.enabled = on;
	env_set_constraint(&c->d->env, slot, &d);
	return 0;
}

int
cmd_enable_constraint(struct cmd_ctx *c)
{
	return switch_constraint(c, 1);
}

int
cmd_disable_constraint(struct cmd_ctx *c)
{
	return switch_constraint(c, 0);
}

int
cmd_delete_constraint(struct cmd_ctx *c)
{
	int slot = cmd_constraint(c, c->argv[0]);
	if (slot < 0)
		return -1;
	env_remove_constraint(&c->d->env, slot);
	return 0;
}

int
cmd_list_constraints(struct cmd_ctx *c)
{
	struct env *e = &c->d->env;
	int only = -1;
	if (c->argc == 1 && (only = cmd_figure(c, c->argv[0])) < 0)
		return -1;
	json_t *list = json_array();
	for (int i = 0; i < ENV_MAX_CONSTRAINTS; i++) {
		struct env_constraint *k = &e->con[i];
		if (!k->gen || (only >= 0 && k->fig != only))
			continue;
		struct env_figure *f = &e->fig[k->fig];
		const struct ik_constraint_def *d = &k->def;
		env_sync_solver(e, k->fig);
		double pe = 0, oe = 0;
		ik_constraint_error(f->ik, f->model, f->state, env_solver_index(e, i), &pe, &oe);
		char id[32], site[2 * MODEL_NAME_MAX];
		env_constraint_id(e, i, id);
		json_t *o = json_object();
		json_object_set_new(o, "constraint", json_string(id));
		json_object_set_new(o, "name", json_string(k->name));
		json_object_set_new(o, "figure", json_string(f->name));
		json_object_set_new(o, "effector", json_string(model_site_fullname(f->model,
			d->effector_site, site, sizeof site)));
		json_object_set_new(o, "pos", json_string(pos_names[d->pos]));
		json_object_set_new(o, "ori", json_string(ori_names[d->ori]));
		json_object_set_new(o, "enabled", json_boolean(d->enabled));
		json_object_set_new(o, "weight", json_real(d->weight));
		json_object_set_new(o, "posweight", json_real(d->pos_weight));
		json_object_set_new(o, "group", json_integer(d->group));
		json_object_set_new(o, "goal", cmd_vec(d->goal_xf.p, 3));
		json_object_set_new(o, "goal_rotation", cmd_vec(d->goal_xf.r, 9));
		json_object_set_new(o, "pos_error", json_real(pe));
		json_object_set_new(o, "ori_error", json_real(oe));
		json_array_append_new(list, o);
	}
	json_object_set_new(c->result, "constraints", list);
	return 0;
}
