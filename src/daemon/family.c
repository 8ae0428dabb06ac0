/* family.c - a family of manikins shown at the kiosk (see family.h) */
#include "daemon/family.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "figure/kin.h"

int
family_is_member(const struct env *e, const char *prefix, int fig)
{
	const struct env_figure *f = &e->fig[fig];
	return f->gen && f->is_human && prefix[0] && !strcmp(f->manikin.family, prefix);
}

/* the family's order: women first, then the member number, then the slot */
static int
before(const struct env *e, int a, int b)
{
	const struct env_figure *x = &e->fig[a], *y = &e->fig[b];
	if (x->human.sex != y->human.sex)
		return x->human.sex == HUMAN_FEMALE;
	if (x->manikin.member != y->manikin.member)
		return x->manikin.member < y->manikin.member;
	return a < b;
}

int
family_members(const struct env *e, const char *prefix, int dest[ENV_MAX_FIGURES])
{
	int n = 0;
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		if (!family_is_member(e, prefix, i))
			continue;
		int j = n++;
		for (; j > 0 && before(e, i, dest[j - 1]); j--) /* insertion: a few dozen at most */
			dest[j] = dest[j - 1];
		dest[j] = i;
	}
	return n;
}

int
family_selected(const struct env *e)
{
	const struct env_show *sh = &e->show;
	if (sh->arrange == ENV_SHOW_OFF)
		return -1;
	int slot[ENV_MAX_FIGURES], n = family_members(e, sh->family, slot);
	for (int i = 0; i < n; i++)
		if (!strcmp(e->fig[slot[i]].name, sh->selected))
			return slot[i];
	return n ? slot[0] : -1;
}

int
family_is_ghost(const struct env *e, int fig, int mode_fig)
{
	if (e->show.arrange != ENV_SHOW_OVERLAY || fig == mode_fig ||
	    !family_is_member(e, e->show.family, fig))
		return 0;
	return fig != family_selected(e);
}

double
family_sole_height(const struct model *m, const struct state *s)
{
	double y = INFINITY;
	for (int k = 0; k < m->nsite; k++) {
		const char *seg = m->seg_name[m->site_seg[k]];
		if (!strncmp(seg, "foot_", 5) || !strncmp(seg, "toes_", 5))
			y = fmin(y, s->site_xf[k].p[1]);
	}
	return y;
}

int
family_place(const struct model *m, const struct state *s, double dest[3])
{
	int l = model_find_site(m, "foot_l.balance"), r = model_find_site(m, "foot_r.balance");
	if (l < 0 || r < 0)
		return -1;
	for (int i = 0; i < 3; i++)
		dest[i] = 0.5 * (s->site_xf[l].p[i] + s->site_xf[r].p[i]);
	return 0;
}

/* the heading of a human: its pelvis's forward (+z) axis about the vertical, radians */
static double
heading(const struct model *m, const struct state *s)
{
	const double *r = s->seg_xf[model_find_segment(m, "pelvis")].r;
	return atan2(r[2], r[8]);
}

/*
 * Turns the figure by turn about the vertical through `from` (world) and
 * carries that point to `to`, horizontally; then stands it on the floor.
 */
static void
move_figure(struct env_figure *f, const double from[3], const double to[3], double turn)
{
	struct xform *x = &f->state->root_xf;
	if (turn != 0 || from[0] != to[0] || from[2] != to[2]) {
		double c = cos(turn), s = sin(turn);
		const double ry[9] = { c, 0, s, 0, 1, 0, -s, 0, c };
		double d[3] = { x->p[0] - from[0], x->p[1], x->p[2] - from[2] }, r[9];
		x->p[0] = c * d[0] + s * d[2] + to[0];
		x->p[2] = -s * d[0] + c * d[2] + to[2];
		for (int i = 0; i < 3; i++)
			for (int j = 0; j < 3; j++)
				r[3 * i + j] = ry[3 * i] * x->r[j] + ry[3 * i + 1] * x->r[3 + j] +
					       ry[3 * i + 2] * x->r[6 + j];
		memcpy(x->r, r, sizeof r);
		kin_update(f->model, f->state);
	}
	double sole = family_sole_height(f->model, f->state);
	if (sole != 0 && isfinite(sole)) {
		x->p[1] -= sole;
		kin_update(f->model, f->state);
	}
}

int
family_arrange(struct env *e, const int *slot, const struct pick_model *const *pm, int n,
	       int sel, int row, const double h[3], double spacing, double *used, char *err,
	       size_t errlen)
{
	/* everything checked before anything moves */
	for (int i = 0; i < n; i++) {
		const struct env_figure *f = &e->fig[slot[i]];
		double p[3];
		if (f->behave) {
			snprintf(err, errlen, "%s behaves: its behaviours hold its feet where they stand "
				 "(behave %s off, arrange, then on again)", f->name, f->name);
			return -1;
		}
		if (family_place(f->model, f->state, p) < 0 || model_find_segment(f->model, "pelvis") < 0) {
			snprintf(err, errlen, "%s has no feet's balance sites or pelvis to stand it by",
				 f->name);
			return -1;
		}
	}
	/* overlaid: each turned as the selected one faces, its feet where the selected one's are */
	const struct env_figure *s0 = &e->fig[slot[sel]];
	double at[3], face = heading(s0->model, s0->state);
	family_place(s0->model, s0->state, at);
	for (int i = 0; i < n; i++) {
		struct env_figure *f = &e->fig[slot[i]];
		double from[3];
		family_place(f->model, f->state, from);
		move_figure(f, from, i == sel ? from : at, i == sel ? 0 : face - heading(f->model, f->state));
	}
	*used = 0;
	if (!row)
		return 0;
	/* a row: the widest reaches to either side of the feet, so neighbours never touch */
	if (spacing <= 0) {
		double left = 0, right = 0, mid = at[0] * h[0] + at[2] * h[2];
		for (int i = 0; i < n; i++) {
			double lo, hi;
			if (!pick_extent(pm[i], e->fig[slot[i]].state, h, &lo, &hi))
				continue;
			left = fmax(left, mid - lo);
			right = fmax(right, hi - mid);
		}
		spacing = left + right + FAMILY_ROW_MARGIN;
	}
	for (int i = 0; i < n; i++) {
		if (i == sel)
			continue;
		double to[3] = { at[0] + (i - sel) * spacing * h[0], 0, at[2] + (i - sel) * spacing * h[2] };
		move_figure(&e->fig[slot[i]], at, to, 0);
	}
	*used = spacing;
	return 0;
}

int
family_pose_alike(struct env *e, const int *slot, int n, int from, char *err, size_t errlen)
{
	const struct model *fm = e->fig[from].model;
	const double *q = e->fig[from].state->q;
	/* everything checked before anything moves */
	for (int i = 0; i < n; i++) {
		const struct env_figure *f = &e->fig[slot[i]];
		double p[3];
		if (f->behave) {
			snprintf(err, errlen, "%s behaves: its behaviours hold its posture (behave %s off "
				 "first)", f->name, f->name);
			return -1;
		}
		if (family_place(f->model, f->state, p) < 0 || model_find_segment(f->model, "pelvis") < 0) {
			snprintf(err, errlen, "%s has no feet's balance sites or pelvis to stand it by",
				 f->name);
			return -1;
		}
		for (int j = 0; j < fm->njnt; j++) {
			int k = model_find_joint(f->model, fm->jnt_name[j]);
			if (k < 0 || f->model->jnt_ndof[k] != fm->jnt_ndof[j]) {
				snprintf(err, errlen, "%s has no joint %s like %s's", f->name, fm->jnt_name[j],
					 e->fig[from].name);
				return -1;
			}
		}
	}
	for (int i = 0; i < n; i++) {
		if (slot[i] == from)
			continue;
		struct env_figure *f = &e->fig[slot[i]];
		double was[3], now[3], face = heading(f->model, f->state);
		family_place(f->model, f->state, was);
		for (int j = 0; j < fm->njnt; j++) {
			int k = model_find_joint(f->model, fm->jnt_name[j]);
			memcpy(&f->state->q[f->model->jnt_dof0[k]], &q[fm->jnt_dof0[j]],
			       sizeof *q * (size_t)fm->jnt_ndof[j]);
		}
		kin_update(f->model, f->state);
		family_place(f->model, f->state, now);
		move_figure(f, now, was, face - heading(f->model, f->state));
	}
	return 0;
}

void
family_describe(const struct env *e, int fig, char *dest, size_t len)
{
	const struct env_figure *f = &e->fig[fig];
	const struct env_manikin *mk = &f->manikin;
	const char *sex = f->human.sex == HUMAN_FEMALE ? "female" : "male";
	if (!f->is_human) {
		snprintf(dest, len, "%s", f->name);
	} else if (mk->family[0] && mk->member == 0) {
		snprintf(dest, len, "%s: family %s centre (%.4g%% coverage)", f->name, mk->family,
			 100 * mk->coverage);
	} else if (mk->family[0]) {
		snprintf(dest, len, "%s: family %s, Mahalanobis %.2f (%.4g%% coverage)", f->name,
			 mk->family, mk->mahalanobis, 100 * mk->coverage);
	} else if (!isnan(mk->percentile)) {
		snprintf(dest, len, "%s: P%.4g stature (%s %s)", f->name, mk->percentile, mk->population,
			 sex);
	} else if (mk->population[0]) {
		int k = 0;
		for (int c = 0; c < POPULATION_NCOL; c++)
			k += mk->given[c] != 0;
		snprintf(dest, len, "%s: %s %s, Mahalanobis %.2f on %d measure%s", f->name,
			 mk->population, sex, mk->mahalanobis, k, k == 1 ? "" : "s");
	} else {
		snprintf(dest, len, "%s: %.2f m, %.0f kg %s", f->name, f->human.stature, f->human.mass,
			 sex);
	}
}
