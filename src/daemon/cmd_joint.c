/* cmd_joint.c - joint values, sites, the root and the figure's place */
#include <stdio.h>
#include <math.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "pose/balance.h"
#include "pose/load_balance.h"
#include "figure/kin.h"

static int
joint_of(struct cmd_ctx *c, int fig, const char *name)
{
	int j = model_find_joint(c->d->env.fig[fig].model, name);
	if (j < 0)
		cmd_fail(c, "not-found", "figure %s has no joint '%.60s'", c->d->env.fig[fig].name, name);
	return j;
}

static int
site_of(struct cmd_ctx *c, int fig, const char *name)
{
	int k = model_find_site(c->d->env.fig[fig].model, name);
	if (k < 0)
		cmd_fail(c, "not-found", "figure %s has no site '%.60s' (give SEGMENT.SITE)",
			 c->d->env.fig[fig].name, name);
	return k;
}

int
cmd_get_joint(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]), j;
	if (fig < 0 || (j = joint_of(c, fig, c->argv[1])) < 0)
		return -1;
	const struct env_figure *f = &c->d->env.fig[fig];
	int d0 = f->model->jnt_dof0[j], n = f->model->jnt_ndof[j];
	json_object_set_new(c->result, "joint", json_string(f->model->jnt_name[j]));
	json_object_set_new(c->result, "values", cmd_vec(&f->state->q[d0], n));
	json_object_set_new(c->result, "lower", cmd_vec(&f->model->dof_lo[d0], n));
	json_object_set_new(c->result, "upper", cmd_vec(&f->model->dof_hi[d0], n));
	json_t *types = json_array();
	for (int d = d0; d < d0 + n; d++) {
		char t[8];
		snprintf(t, sizeof t, "%c(%s%c)", f->model->dof_kind[d] == DOF_ROTATION ? 'R' : 'T',
			 f->model->dof_sign[d] < 0 ? "-" : "", "xyz"[f->model->dof_axis[d]]);
		json_array_append_new(types, json_string(t));
	}
	json_object_set_new(c->result, "types", types);
	return 0;
}

int
cmd_set_joint(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]), j;
	if (fig < 0 || (j = joint_of(c, fig, c->argv[1])) < 0)
		return -1;
	struct env_figure *f = &c->d->env.fig[fig];
	const struct model *m = f->model;
	int d0 = m->jnt_dof0[j], n = m->jnt_ndof[j];
	if (c->argc - 2 != n)
		return cmd_fail(c, "arity", "joint %s has %d dofs, got %d values", m->jnt_name[j], n,
				c->argc - 2);
	double v[MODEL_JOINT_DOF_MAX];
	for (int k = 0; k < n; k++) {
		int d = d0 + k;
		enum unit_kind kind = m->dof_kind[d] == DOF_ROTATION ? UNIT_ANGLE : UNIT_LENGTH;
		if (words_number(c->argv[2 + k], kind, &v[k]) < 0)
			return cmd_fail(c, "bad-number", "value %d: '%.40s' is not a finite %s", k + 1,
					c->argv[2 + k], kind == UNIT_ANGLE ? "angle" : "length");
		if (v[k] < m->dof_lo[d] || v[k] > m->dof_hi[d])
			return cmd_fail(c, "bad-argument", "value %d (%.6g) lies outside [%.6g, %.6g]",
					k + 1, v[k], m->dof_lo[d], m->dof_hi[d]);
	}
	memcpy(&f->state->q[d0], v, sizeof *v * (size_t)n);
	kin_update(m, f->state);
	json_object_set_new(c->result, "values", cmd_vec(v, n));
	return 0;
}

int
cmd_get_posture(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]);
	if (fig < 0)
		return -1;
	const struct env_figure *f = &c->d->env.fig[fig];
	const struct model *m = f->model;
	json_t *p = json_object();
	for (int j = 0; j < m->njnt; j++)
		if (m->jnt_ndof[j])
			json_object_set_new(p, m->jnt_name[j],
					    cmd_vec(&f->state->q[m->jnt_dof0[j]], m->jnt_ndof[j]));
	char root[2 * MODEL_NAME_MAX];
	json_object_set_new(c->result, "posture", p);
	json_object_set_new(c->result, "root", json_string(model_site_fullname(m, f->state->root_site,
		root, sizeof root)));
	json_object_set_new(c->result, "root_position", cmd_vec(f->state->root_xf.p, 3));
	json_object_set_new(c->result, "root_rotation", cmd_vec(f->state->root_xf.r, 9));
	json_object_set_new(c->result, "com", cmd_vec(f->state->com, 3));
	return 0;
}

int
cmd_get_site(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]), k;
	if (fig < 0 || (k = site_of(c, fig, c->argv[1])) < 0)
		return -1;
	const struct xform *x = &c->d->env.fig[fig].state->site_xf[k];
	json_object_set_new(c->result, "position", cmd_vec(x->p, 3));
	json_object_set_new(c->result, "rotation", cmd_vec(x->r, 9));
	return 0;
}

int
cmd_set_root(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]), k;
	if (fig < 0 || (k = site_of(c, fig, c->argv[1])) < 0)
		return -1;
	struct env_figure *f = &c->d->env.fig[fig];
	kin_set_root(f->model, f->state, k);
	f->ik_stale = 1; /* chains run to the new root */
	json_object_set_new(c->result, "root", json_string(c->argv[1]));
	return 0;
}

int
cmd_set_location(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]);
	if (fig < 0)
		return -1;
	double p[3], r[9];
	int given;
	for (int i = 0; i < 3; i++)
		if (words_number(c->argv[1 + i], UNIT_LENGTH, &p[i]) < 0)
			return cmd_fail(c, "bad-number", "X Y Z: lengths such as 1.2 or 30cm");
	for (int i = 4; i < c->argc; i++)
		if (!words_is_key(c->argv[i], "rot") && !words_is_key(c->argv[i], "yaw"))
			return cmd_fail(c, "bad-argument", "unexpected '%.60s'", c->argv[i]);
	if (cmd_rotation(c, r, &given) < 0)
		return -1;
	struct env_figure *f = &c->d->env.fig[fig];
	memcpy(f->state->root_xf.p, p, sizeof p);
	if (given)
		memcpy(f->state->root_xf.r, r, sizeof f->state->root_xf.r);
	kin_update(f->model, f->state);
	return 0;
}

/* set site FIG SEG.SITE X Y Z [rot=AXIS,ANGLE]: a site moved on its segment */
int
cmd_set_site(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]);
	if (fig < 0)
		return -1;
	struct env_figure *f = &c->d->env.fig[fig];
	int site = model_find_site(f->model, c->argv[1]);
	if (site < 0)
		return cmd_fail(c, "not-found", "no site '%.60s' on %s", c->argv[1], f->name);
	struct xform loc = f->model->site_loc[site];
	for (int i = 0; i < 3; i++)
		if (words_number(c->argv[2 + i], UNIT_LENGTH, &loc.p[i]) < 0 || !(fabs(loc.p[i]) < 1e3))
			return cmd_fail(c, "bad-number", "X Y Z: lengths within 1 km, such as 0.1 or 3cm");
	for (int i = 5; i < c->argc; i++)
		if (!words_is_key(c->argv[i], "rot"))
			return cmd_fail(c, "bad-argument", "unexpected '%.60s'", c->argv[i]);
	int given;
	if (cmd_rotation(c, loc.r, &given) < 0)
		return -1;
	env_place_site(&c->d->env, fig, site, &loc);
	json_object_set_new(c->result, "position", cmd_vec(f->state->site_xf[site].p, 3));
	return 0;
}

int
cmd_get_balance(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]);
	if (fig < 0)
		return -1;
	const struct env_figure *f = &c->d->env.fig[fig];
	struct balance b;
	struct point_mass pm[POINT_MASS_MAX];
	int npm = load_balance_masses(&c->d->env, fig, pm);
	double com[3]; /* the body's with the weights it carries */
	point_mass_com(f->state, pm, npm > 0 ? npm : 0, com);
	if (balance_measure_com(f->model, f->state, BALANCE_CONTACT, 0, com, &b) < 0)
		return cmd_fail(c, "bad-argument", "figure %s has no feet to balance on", f->name);
	json_t *poly = json_array();
	for (int i = 0; i < b.npoly; i++)
		json_array_append_new(poly, cmd_vec(b.poly[i], 2));
	json_t *line = json_array();
	json_array_append_new(line, cmd_vec(b.ref_l, 2));
	json_array_append_new(line, cmd_vec(b.ref_r, 2));
	json_object_set_new(c->result, "polygon", poly);
	json_object_set_new(c->result, "balance_line", line);
	json_object_set_new(c->result, "point", cmd_vec(b.point, 2));
	json_object_set_new(c->result, "x", json_real(b.x));
	json_object_set_new(c->result, "z", json_real(b.z));
	json_object_set_new(c->result, "margin", json_real(b.margin));
	json_object_set_new(c->result, "weight_left", json_real(b.weight_l));
	json_object_set_new(c->result, "com", cmd_vec(b.com, 3));
	double carried = 0; /* kg of weights on the feet besides the body's */
	for (int i = 0; i < npm; i++)
		carried += pm[i].mass;
	json_object_set_new(c->result, "carried", json_real(carried));
	return 0;
}
