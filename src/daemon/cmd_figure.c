/* cmd_figure.c - loading, listing and inspecting figures */
#include <stdio.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/manikin.h"
#include "figure/figure.h"
#include "figure/kin.h"

int
cmd_load_figure(struct cmd_ctx *c)
{
	int bad;
	const char *name = cmd_as_name(c, &bad);
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
	return cmd_added(c, slot, name);
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
		if (f->is_human)
			manikin_json(f, o);
		if (daemon_is_ghost(c->d, i)) /* a family overlaid: drawn translucent, never picked */
			json_object_set_new(o, "ghost", json_true());
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
