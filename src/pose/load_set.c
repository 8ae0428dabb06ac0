/* load_set.c - the loads on a figure now: its own, and its hands' shares of what they carry */
#include "pose/load_set.h"

#include <string.h>

#include "pose/attach.h"

/* is figure obj carried: grabbed by some hand? */
static int
carried(const struct env *e, int obj)
{
	for (int i = 0; i < ENV_MAX_ATTACH; i++) {
		const struct env_attach *a = &e->att[i];
		if (a->used && a->obj == obj && a->kind == ATTACH_GRAB)
			return 1;
	}
	return 0;
}

/* the world position of the palm of a hand held to something */
static const double *
palm_of(const struct env *e, int fig, int side)
{
	const struct env_figure *f = &e->fig[fig];
	return f->state->site_xf[f->behave->s_palm[side]].p;
}

int
load_set_hands(const struct env *e, int obj, int fig[], int side[], double share[], double mid[3])
{
	memset(mid, 0, 3 * sizeof *mid);
	if (obj < 0 || obj >= ENV_MAX_FIGURES || !e->fig[obj].gen || !carried(e, obj))
		return 0;
	int n = 0;
	for (int i = 0; i < ENV_MAX_ATTACH && n < LOAD_SET_HANDS; i++) {
		const struct env_attach *a = &e->att[i];
		if (!a->used || a->obj != obj || a->limb != ATTACH_HAND || !e->fig[a->fig].gen ||
		    !e->fig[a->fig].behave)
			continue;
		fig[n] = a->fig;
		side[n] = a->side;
		n++;
	}
	for (int k = 0; k < n; k++)
		share[k] = 1.0 / n;
	if (n == 2) { /* the lever rule on the floor plane */
		const double *p1 = palm_of(e, fig[0], side[0]), *p2 = palm_of(e, fig[1], side[1]);
		const double *c = e->fig[obj].state->com;
		double dx = p2[0] - p1[0], dz = p2[2] - p1[2], span2 = dx * dx + dz * dz;
		if (span2 >= LOAD_SET_SPAN_MIN * LOAD_SET_SPAN_MIN) {
			double t = ((c[0] - p1[0]) * dx + (c[2] - p1[2]) * dz) / span2;
			t = t < 0 ? 0 : t > 1 ? 1 : t;
			share[0] = 1 - t;
			share[1] = t;
		}
	}
	for (int k = 0; k < n; k++) {
		const double *p = palm_of(e, fig[k], side[k]);
		for (int i = 0; i < 3; i++)
			mid[i] += share[k] * p[i];
	}
	return n;
}

/* one load into the set; 0, or -1 when it is full */
static int
put(struct ext_load *out, struct load_origin *origin, int *n, int max, const struct ext_load *l,
    const struct load_origin *o)
{
	if (*n >= max)
		return -1;
	out[*n] = *l;
	if (origin)
		origin[*n] = *o;
	(*n)++;
	return 0;
}

/* env load slot k as it acts on its own figure */
static struct ext_load
own_load(const struct env *e, int k)
{
	const struct env_load *l = &e->load[k];
	const struct model *m = e->fig[l->fig].model;
	struct ext_load x = { .seg = m->site_seg[l->site], .mass = l->mass };
	memcpy(x.local, m->site_loc[l->site].p, sizeof x.local);
	memcpy(x.force, l->force, sizeof x.force);
	memcpy(x.torque, l->torque, sizeof x.torque);
	return x;
}

/*
 * A share s of a force (and torque, and mass) acting at world point at,
 * moved by shift, carried by the hand of figure f on side: in that hand's
 * segment's frame.
 */
static struct ext_load
share_on_hand(const struct env_figure *f, int side, double s, const double at[3],
	      const double shift[3], const double force[3], const double torque[3], double mass)
{
	int palm = f->behave->s_palm[side];
	struct ext_load x = { .seg = f->model->site_seg[palm], .mass = s * mass };
	double w[3];
	for (int i = 0; i < 3; i++) {
		w[i] = at[i] + shift[i];
		x.force[i] = s * force[i];
		x.torque[i] = s * torque[i];
	}
	struct xform inv;
	xform_inv(&f->state->seg_xf[x.seg], &inv);
	xform_apply(&inv, w, x.local);
	return x;
}

/* figure fig's hand on side, on carried object obj: its share of the weight and of obj's loads */
static int
carried_shares(const struct env *e, int fig, int side, int obj, struct ext_load *out,
	       struct load_origin *origin, int *n, int max)
{
	int hf[LOAD_SET_HANDS], hs[LOAD_SET_HANDS];
	double share[LOAD_SET_HANDS], mid[3];
	int nh = load_set_hands(e, obj, hf, hs, share, mid);
	int k = 0;
	while (k < nh && !(hf[k] == fig && hs[k] == side))
		k++;
	if (k == nh)
		return 0;
	const struct env_figure *f = &e->fig[fig], *o = &e->fig[obj];
	const double *palm = palm_of(e, fig, side);
	double shift[3], zero[3] = { 0, 0, 0 };
	/* the weight: the palm moved by the centre of mass's offset from the hands' middle */
	double weight[3] = { 0, -o->model->total_mass * LOAD_GRAVITY, 0 }, at[3];
	for (int i = 0; i < 3; i++) {
		shift[i] = palm[i] - mid[i];
		at[i] = o->state->com[i];
	}
	struct ext_load x = share_on_hand(f, side, share[k], at, shift, weight, zero,
					  o->model->total_mass);
	struct load_origin og = { .load = -1, .carried = obj, .side = side, .share = share[k] };
	if (put(out, origin, n, max, &x, &og) < 0)
		return -1;
	for (int j = 0; j < ENV_MAX_LOADS; j++) {
		const struct env_load *l = &e->load[j];
		if (!l->gen || l->fig != obj)
			continue;
		xform_apply(&o->state->seg_xf[o->model->site_seg[l->site]],
			    o->model->site_loc[l->site].p, at);
		x = share_on_hand(f, side, share[k], at, shift, l->force, l->torque, l->mass);
		og.load = j;
		if (put(out, origin, n, max, &x, &og) < 0)
			return -1;
	}
	return 0;
}

int
load_set_of(const struct env *e, int fig, struct ext_load *out, struct load_origin *origin,
	    int max)
{
	if (fig < 0 || fig >= ENV_MAX_FIGURES || !e->fig[fig].gen)
		return -1;
	int n = 0;
	for (int k = 0; k < ENV_MAX_LOADS; k++) {
		if (!e->load[k].gen || e->load[k].fig != fig)
			continue;
		struct ext_load x = own_load(e, k);
		struct load_origin og = { .load = k, .carried = -1, .side = -1, .share = 1 };
		if (put(out, origin, &n, max, &x, &og) < 0)
			return -1;
	}
	if (!e->fig[fig].behave)
		return n; /* only a behaving human's hands hold on to anything */
	for (int side = 0; side < 2; side++) {
		int a = attach_find(e, fig, ATTACH_HAND, side);
		if (a >= 0 && carried_shares(e, fig, side, e->att[a].obj, out, origin, &n, max) < 0)
			return -1;
	}
	return n;
}

double
load_set_weights(const struct model *m, const struct state *s, const struct ext_load *loads, int n,
		 double com[3])
{
	double mass = 0, sum[3] = { 0, 0, 0 };
	for (int k = 0; k < n; k++) {
		const struct ext_load *l = &loads[k];
		if (!(l->mass > 0) || l->seg < 0 || l->seg >= m->nseg)
			continue;
		double w[3];
		xform_apply(&s->seg_xf[l->seg], l->local, w);
		for (int i = 0; i < 3; i++)
			sum[i] += l->mass * w[i];
		mass += l->mass;
	}
	if (mass > 0)
		for (int i = 0; i < 3; i++)
			com[i] = sum[i] / mass;
	return mass;
}
