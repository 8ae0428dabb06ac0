/* cmd_figure.c - loading, listing and inspecting figures */
#include <stdio.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "figure/figure.h"
#include "figure/kin.h"

/* "as NAME" among the arguments; returns the name, NULL when absent, or sets an error */
static const char *
as_name(struct cmd_ctx *c, int *bad)
{
	*bad = 0;
	for (int i = 0; i < c->argc; i++) {
		if (strcmp(c->argv[i], "as"))
			continue;
		if (i + 1 >= c->argc || !words_is_name(c->argv[i + 1])) {
			*bad = 1;
			cmd_fail(c, "bad-argument", "'as' takes a name: letters, digits, '_'");
			return NULL;
		}
		return c->argv[i + 1];
	}
	return NULL;
}

static int
added(struct cmd_ctx *c, int slot, const char *name)
{
	if (slot == ENV_EXISTS)
		return cmd_fail(c, "exists", "a figure named '%s' exists", name ? name : "");
	if (slot < 0)
		return cmd_fail(c, "limit", "the environment holds %d figures at most", ENV_MAX_FIGURES);
	char id[32];
	env_figure_id(&c->d->env, slot, id);
	json_object_set_new(c->result, "figure", json_string(id));
	json_object_set_new(c->result, "name", json_string(c->d->env.fig[slot].name));
	return 0;
}

int
cmd_load_human(struct cmd_ctx *c)
{
	int bad;
	const char *name = as_name(c, &bad);
	if (bad)
		return -1;
	struct human_def hd = human_default_def(HUMAN_MALE);
	const char *sex = cmd_key(c, "sex");
	if (sex) {
		if (strcmp(sex, "male") && strcmp(sex, "female"))
			return cmd_fail(c, "bad-argument", "sex is male or female");
		hd = human_default_def(!strcmp(sex, "male") ? HUMAN_MALE : HUMAN_FEMALE);
	}
	const char *st = cmd_key(c, "stature"), *ms = cmd_key(c, "mass");
	if (st && words_number(st, UNIT_LENGTH, &hd.stature) < 0)
		return cmd_fail(c, "bad-number", "stature: a length such as 1.75 or 175cm");
	if (ms && words_number(ms, UNIT_NONE, &hd.mass) < 0)
		return cmd_fail(c, "bad-number", "mass: kilograms, a number");
	/* every argument must be one of ours */
	for (int i = 0; i < c->argc; i++) {
		const char *a = c->argv[i];
		if (!strcmp(a, "as")) {
			i++;
			continue;
		}
		if (!words_is_key(a, "sex") && !words_is_key(a, "stature") && !words_is_key(a, "mass"))
			return cmd_fail(c, "bad-argument", "unexpected '%.60s'", a);
	}
	char err[256];
	struct model *m = human_build(&hd, err, sizeof err);
	if (!m)
		return cmd_fail(c, "bad-argument", "%s", err);
	int slot = env_add_figure(&c->d->env, m, name, 1, &hd, NULL);
	return added(c, slot, name);
}

int
cmd_load_figure(struct cmd_ctx *c)
{
	int bad;
	const char *name = as_name(c, &bad);
	if (bad)
		return -1;
	if (c->argc != 1 && c->argc != 3)
		return cmd_fail(c, "arity", "load figure PATH [as NAME]");
	if (c->argc == 3 && strcmp(c->argv[1], "as"))
		return cmd_fail(c, "bad-argument", "unexpected '%.60s'", c->argv[1]);
	char full[8200], err[512];
	/* a session keeps the path as given, in a field of ENV_PATH_MAX bytes */
	if (strlen(c->argv[0]) >= ENV_PATH_MAX)
		return cmd_fail(c, "bad-argument", "a figure's path is at most %d bytes (a session "
			        "holds no more)", ENV_PATH_MAX - 1);
	const char *lib = !strncmp(c->argv[0], "lib:", 4) ? c->argv[0] + 4 : NULL;
	if (lib) { /* a figure of the shipped library: a plain file name */
		if (!c->d->library_dir[0])
			return cmd_fail(c, "not-found", "this daemon has no figure library (--library)");
		if (!lib[0] || strchr(lib, '/') || lib[0] == '.')
			return cmd_fail(c, "denied", "lib: takes a file name of the library");
		snprintf(full, sizeof full, "%s/%s", c->d->library_dir, lib);
	} else if (cmd_path(c, c->argv[0], 0, full, sizeof full) < 0) {
		return -1;
	}
	struct model *m = figure_read_file(full, err, sizeof err);
	if (!m) {
		/* the message names the file; give the path as the client wrote it */
		const char *rest = strstr(err, c->argv[0]);
		return cmd_fail(c, "bad-file", "%s", rest ? rest : err);
	}
	int slot = env_add_figure(&c->d->env, m, name, 0, NULL, c->argv[0]);
	return added(c, slot, name);
}

int
cmd_unload_figure(struct cmd_ctx *c)
{
	int slot = cmd_figure(c, c->argv[0]);
	if (slot < 0)
		return -1;
	env_remove_figure(&c->d->env, slot);
	return 0;
}

int
cmd_list_figures(struct cmd_ctx *c)
{
	struct env *e = &c->d->env;
	json_t *list = json_array();
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		struct env_figure *f = &e->fig[i];
		if (!f->gen)
			continue;
		char id[32], root[2 * MODEL_NAME_MAX];
		env_figure_id(e, i, id);
		json_t *o = json_object();
		json_object_set_new(o, "figure", json_string(id));
		json_object_set_new(o, "name", json_string(f->name));
		json_object_set_new(o, "source", json_string(f->is_human ? "human" : f->path));
		json_object_set_new(o, "dofs", json_integer(f->model->ndof));
		json_object_set_new(o, "root", json_string(model_site_fullname(f->model,
			f->state->root_site, root, sizeof root)));
		json_array_append_new(list, o);
	}
	json_object_set_new(c->result, "figures", list);
	return 0;
}

static const char *
dof_type(const struct model *m, int d, char *buf)
{
	snprintf(buf, 8, "%c(%s%c)", m->dof_kind[d] == DOF_ROTATION ? 'R' : 'T',
		 m->dof_sign[d] < 0 ? "-" : "", "xyz"[m->dof_axis[d]]);
	return buf;
}

int
cmd_show_figure(struct cmd_ctx *c)
{
	int slot = cmd_figure(c, c->argv[0]);
	if (slot < 0)
		return -1;
	const struct env_figure *f = &c->d->env.fig[slot];
	const struct model *m = f->model;
	json_t *segs = json_array(), *sites = json_array(), *joints = json_array();
	for (int i = 0; i < m->nseg; i++) {
		json_t *o = json_object();
		json_object_set_new(o, "name", json_string(m->seg_name[i]));
		json_object_set_new(o, "mass", json_real(m->seg_mass[i]));
		json_array_append_new(segs, o);
	}
	for (int k = 0; k < m->nsite; k++) {
		char name[2 * MODEL_NAME_MAX];
		json_array_append_new(sites, json_string(model_site_fullname(m, k, name, sizeof name)));
	}
	for (int j = 0; j < m->njnt; j++) {
		json_t *o = json_object(), *types = json_array();
		int d0 = m->jnt_dof0[j], n = m->jnt_ndof[j];
		char t[8];
		for (int d = d0; d < d0 + n; d++)
			json_array_append_new(types, json_string(dof_type(m, d, t)));
		json_object_set_new(o, "name", json_string(m->jnt_name[j]));
		json_object_set_new(o, "types", types);
		json_object_set_new(o, "lower", cmd_vec(&m->dof_lo[d0], n));
		json_object_set_new(o, "upper", cmd_vec(&m->dof_hi[d0], n));
		json_object_set_new(o, "values", cmd_vec(&f->state->q[d0], n));
		json_array_append_new(joints, o);
	}
	char id[32], root[2 * MODEL_NAME_MAX];
	env_figure_id(&c->d->env, slot, id);
	json_object_set_new(c->result, "figure", json_string(id));
	json_object_set_new(c->result, "name", json_string(f->name));
	json_object_set_new(c->result, "segments", segs);
	json_object_set_new(c->result, "sites", sites);
	json_object_set_new(c->result, "joints", joints);
	json_object_set_new(c->result, "root", json_string(model_site_fullname(m, f->state->root_site,
		root, sizeof root)));
	json_object_set_new(c->result, "com", cmd_vec(f->state->com, 3));
	json_object_set_new(c->result, "mass", json_real(m->total_mass));
	return 0;
}
