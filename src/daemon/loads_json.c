/* loads_json.c - a loads analysis as JSON, written without allocating (see loads_json.h) */
#include "daemon/loads_json.h"

#include <math.h>
#include <stdio.h>

static const char *const support_kinds[] = { "foot", "seat", "root" };

/* a load of the set: its point in the world now, its numbers and where it comes from */
static void
load_json(struct jbuf *j, const struct env *e, const struct env_figure *f, const struct ext_load *l,
	  const struct load_origin *o)
{
	double at[3];
	xform_apply(&f->state->seg_xf[l->seg], l->local, at);
	jbuf_raw(j, "{");
	jbuf_key(j, "segment", 1);
	jbuf_str(j, f->model->seg_name[l->seg]);
	jbuf_key(j, "point", 0);
	jbuf_vec(j, at, 3);
	jbuf_key(j, "force", 0);
	jbuf_vec(j, l->force, 3);
	jbuf_key(j, "torque", 0);
	jbuf_vec(j, l->torque, 3);
	jbuf_key(j, "mass", 0);
	int weight = o->load < 0 || e->load[o->load].mass > 0;
	if (weight)
		jbuf_num(j, l->mass);
	else
		jbuf_raw(j, "null");
	jbuf_key(j, "load", 0);
	if (o->load >= 0) {
		char id[32];
		env_load_id(e, o->load, id);
		jbuf_str(j, id);
	} else {
		jbuf_raw(j, "null");
	}
	jbuf_key(j, "carried", 0);
	if (o->carried >= 0)
		jbuf_str(j, e->fig[o->carried].name);
	else
		jbuf_raw(j, "null");
	jbuf_key(j, "hand", 0);
	if (o->side >= 0)
		jbuf_str(j, o->side ? "right" : "left");
	else
		jbuf_raw(j, "null");
	jbuf_key(j, "share", 0);
	jbuf_num(j, o->share);
	jbuf_raw(j, "}");
}

static void
joints_json(struct jbuf *j, const struct model *m, const struct statics_result *st)
{
	jbuf_raw(j, "{");
	for (int k = 0; k < st->njoint; k++) {
		jbuf_key(j, m->jnt_name[k], k == 0);
		jbuf_raw(j, "{");
		jbuf_key(j, "point", 1);
		jbuf_vec(j, st->point[k], 3);
		jbuf_key(j, "force", 0);
		jbuf_vec(j, st->force[k], 3);
		jbuf_key(j, "moment", 0);
		jbuf_vec(j, st->moment[k], 3);
		jbuf_key(j, "torque", 0);
		jbuf_vec(j, &st->dof_torque[m->jnt_dof0[k]], m->jnt_ndof[k]);
		const char *const *axes = st->anatomical[k] ? statics_axis_names(m, k) : NULL;
		if (axes) {
			jbuf_key(j, "anatomical", 0);
			jbuf_raw(j, "{");
			for (int a = 0; a < 3; a++) {
				jbuf_key(j, axes[a], a == 0);
				jbuf_num(j, st->anat[k][a]);
			}
			jbuf_raw(j, "}");
		}
		jbuf_raw(j, "}");
	}
	jbuf_raw(j, "}");
}

static void
supports_json(struct jbuf *j, const struct model *m, const struct statics_result *st, int full)
{
	char site[2 * MODEL_NAME_MAX];
	jbuf_raw(j, "[");
	for (int k = 0; k < st->nsupport; k++) {
		const struct statics_support *s = &st->support[k];
		jbuf_raw(j, k ? ",{" : "{");
		jbuf_key(j, "site", 1);
		jbuf_str(j, model_site_fullname(m, s->site, site, sizeof site));
		jbuf_key(j, "force", 0);
		jbuf_vec(j, s->force, 3);
		if (full) {
			jbuf_key(j, "kind", 0);
			jbuf_str(j, (unsigned)s->kind < 3 ? support_kinds[s->kind] : "?");
			jbuf_key(j, "point", 0);
			jbuf_vec(j, s->point, 3);
			jbuf_key(j, "moment", 0);
			jbuf_vec(j, s->moment, 3);
			jbuf_key(j, "share", 0);
			jbuf_num(j, s->share);
		}
		jbuf_raw(j, "}");
	}
	jbuf_raw(j, "]");
}

static void
low_back_json(struct jbuf *j, const struct lowback_result *lb, int full)
{
	jbuf_raw(j, "{");
	jbuf_key(j, "level", 1);
	jbuf_str(j, lb->level);
	jbuf_key(j, "compression", 0);
	jbuf_num(j, lb->compression);
	jbuf_key(j, "shear_ap", 0);
	jbuf_num(j, lb->shear_ap);
	jbuf_key(j, "shear_lat", 0);
	jbuf_num(j, lb->shear_lat);
	jbuf_key(j, "limit", 0);
	jbuf_raw(j, "{");
	jbuf_key(j, "action", 1);
	jbuf_num(j, lb->action_limit);
	jbuf_key(j, "max", 0);
	jbuf_num(j, lb->max_limit);
	jbuf_key(j, "zone", 0);
	jbuf_str(j, lowback_zone_name(lb->zone));
	jbuf_raw(j, "}");
	if (full) {
		jbuf_key(j, "model", 0);
		jbuf_str(j, lb->model);
		jbuf_key(j, "muscle_force", 0);
		jbuf_num(j, lb->muscle_force);
		jbuf_key(j, "moment_arm", 0);
		jbuf_num(j, lb->moment_arm);
		jbuf_key(j, "moment_sagittal", 0);
		jbuf_num(j, lb->moment_sagittal);
		jbuf_key(j, "moment_lateral", 0);
		jbuf_num(j, lb->moment_lateral);
		jbuf_key(j, "moment_axial", 0);
		jbuf_num(j, lb->moment_axial);
		jbuf_key(j, "unmodelled", 0);
		jbuf_raw(j, "[");
		for (int k = 0; k < lowback_nunmodelled; k++) {
			if (k)
				jbuf_raw(j, ",");
			jbuf_str(j, lowback_unmodelled[k]);
		}
		if (lb->flags & LOWBACK_FLEXOR_UNMODELLED) {
			if (lowback_nunmodelled)
				jbuf_raw(j, ",");
			jbuf_str(j, "flexors");
		}
		jbuf_raw(j, "]");
	}
	jbuf_raw(j, "}");
}

const char *
loads_json_weakest(const struct env *e, int fig, const struct loads_live_fig *a, const char **axis)
{
	if (!a->strength || isnan(a->sr.capable) || a->sr.weakest_joint < 0 ||
	    a->sr.weakest_joint >= STRENGTH_NJOINTS || a->sin_joint[a->sr.weakest_joint] < 0)
		return NULL;
	*axis = strength_axis_name((enum strength_axis)a->sr.weakest_axis);
	return e->fig[fig].model->jnt_name[a->sin_joint[a->sr.weakest_joint]];
}

static void
strength_json(struct jbuf *j, const struct env *e, int fig, const struct loads_live_fig *a)
{
	const struct strength_result *sr = &a->sr;
	const struct model *m = e->fig[fig].model;
	const char *axis = NULL, *weakest = loads_json_weakest(e, fig, a, &axis);
	jbuf_raw(j, "{");
	jbuf_key(j, "capable", 1);
	jbuf_num(j, sr->capable);
	jbuf_key(j, "weakest", 0);
	if (weakest) {
		jbuf_raw(j, "{");
		jbuf_key(j, "joint", 1);
		jbuf_str(j, weakest);
		jbuf_key(j, "axis", 0);
		jbuf_str(j, axis);
		jbuf_raw(j, "}");
	} else {
		jbuf_raw(j, "null");
	}
	jbuf_key(j, "modelled", 0);
	jbuf_int(j, sr->modelled);
	jbuf_key(j, "joints", 0);
	jbuf_raw(j, "{");
	int first = 1;
	for (int k = 0; k < STRENGTH_NJOINTS; k++) {
		if (a->sin_joint[k] < 0)
			continue;
		jbuf_key(j, m->jnt_name[a->sin_joint[k]], first);
		first = 0;
		jbuf_raw(j, "{");
		for (int x = 0; x < STRENGTH_NAXES; x++) {
			jbuf_key(j, strength_axis_name((enum strength_axis)x), x == 0);
			jbuf_raw(j, "{");
			jbuf_key(j, "percent", 1);
			jbuf_num(j, sr->percent[k][x]); /* NAN: null, no published curve */
			jbuf_key(j, "mean", 0);
			jbuf_num(j, sr->mean[k][x]);
			jbuf_key(j, "sd", 0);
			jbuf_num(j, sr->sd[k][x]);
			jbuf_key(j, "moment", 0);
			jbuf_num(j, a->sin.moment[k][x]);
			jbuf_key(j, "angle", 0);
			jbuf_num(j, a->sin.angle[k][x]);
			jbuf_raw(j, "}");
		}
		jbuf_raw(j, "}");
	}
	jbuf_raw(j, "}}");
}

void
loads_json_keys(struct jbuf *j, const struct env *e, int fig, const struct loads_live_fig *a,
		int first)
{
	const struct env_figure *f = &e->fig[fig];
	const struct statics_result *st = &a->st;
	jbuf_key(j, "seated", first);
	jbuf_bool(j, a->seated);
	jbuf_key(j, "weight", 0);
	jbuf_num(j, st->weight_n);
	jbuf_key(j, "loads", 0);
	jbuf_raw(j, "[");
	for (int k = 0; k < a->nloads; k++) {
		if (k)
			jbuf_raw(j, ",");
		load_json(j, e, f, &a->loads[k], &a->origin[k]);
	}
	jbuf_raw(j, "]");
	jbuf_key(j, "joints", 0);
	joints_json(j, f->model, st);
	jbuf_key(j, "supports", 0);
	supports_json(j, f->model, st, 1);
	jbuf_key(j, "balance", 0);
	jbuf_raw(j, "{");
	jbuf_key(j, "cop", 1);
	jbuf_vec(j, st->cop, 3);
	jbuf_key(j, "margin", 0);
	jbuf_num(j, st->margin);
	jbuf_key(j, "contacts", 0);
	jbuf_int(j, st->contacts);
	jbuf_key(j, "lifts", 0);
	jbuf_bool(j, st->lifts);
	jbuf_key(j, "tips", 0);
	jbuf_bool(j, st->tips);
	jbuf_raw(j, "}");
	jbuf_key(j, "low_back", 0);
	if (a->low_back) {
		low_back_json(j, &a->lb, 1);
	} else {
		jbuf_raw(j, "null");
		jbuf_key(j, "low_back_why", 0);
		jbuf_str(j, a->human ? a->lb_why : "not a human figure: the low back model is a human's");
	}
	jbuf_key(j, "strength", 0);
	if (a->strength) {
		strength_json(j, e, fig, a);
	} else {
		jbuf_raw(j, "null");
		jbuf_key(j, "strength_why", 0);
		jbuf_str(j, a->human ? a->sr_why : "not a human figure: strength is a population's");
	}
}

void
loads_json_summary_keys(struct jbuf *j, const struct env *e, int fig,
			const struct loads_live_fig *a)
{
	jbuf_key(j, "low_back", 0);
	if (a->low_back)
		low_back_json(j, &a->lb, 0);
	else
		jbuf_raw(j, "null");
	const char *axis = NULL, *weakest = loads_json_weakest(e, fig, a, &axis);
	jbuf_key(j, "weakest", 0);
	if (weakest) {
		jbuf_raw(j, "{");
		jbuf_key(j, "joint", 1);
		jbuf_str(j, weakest);
		jbuf_key(j, "axis", 0);
		jbuf_str(j, axis);
		jbuf_key(j, "percent_capable", 0);
		jbuf_num(j, a->sr.capable);
		jbuf_raw(j, "}");
	} else {
		jbuf_raw(j, "null");
	}
	jbuf_key(j, "supports", 0);
	supports_json(j, e->fig[fig].model, &a->st, 0);
	jbuf_key(j, "tips", 0);
	jbuf_bool(j, a->st.tips);
	jbuf_key(j, "loads", 0);
	jbuf_int(j, a->nloads);
}

void
loads_json_status(const struct loads_live_fig *a, char *dest, size_t len)
{
	if (!a || !a->low_back) {
		snprintf(dest, len, "%s", "");
		return;
	}
	/* the font is ASCII's: no thin space, no middle dot */
	int n = snprintf(dest, len, "   %s %.1f kN", a->lb.level, a->lb.compression / 1000);
	if (n >= 0 && (size_t)n < len && a->strength && !isnan(a->sr.capable))
		snprintf(dest + n, len - (size_t)n, ", %.0f %% capable", floor(a->sr.capable));
}
