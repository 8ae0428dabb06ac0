/* daemon.c - undo and redo checkpoints, the kiosk's steps and figure, the pick models */
#include "daemon/daemon.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/envelopes.h"
#include "daemon/family.h"
#include "daemon/session.h"

void
daemon_checkpoints_clear(struct checkpoints *c)
{
	for (int i = 0; i < c->n; i++)
		free(c->text[i]);
	c->n = 0;
}

void
daemon_checkpoints_push(struct checkpoints *c, char *text, size_t len)
{
	if (c->n == DAEMON_UNDO_MAX) { /* forget the oldest */
		free(c->text[0]);
		memmove(c->text, c->text + 1, sizeof *c->text * (DAEMON_UNDO_MAX - 1));
		memmove(c->len, c->len + 1, sizeof *c->len * (DAEMON_UNDO_MAX - 1));
		c->n--;
	}
	c->text[c->n] = text;
	c->len[c->n] = len;
	c->n++;
}

int
daemon_kiosk_view(const struct daemon *d)
{
	const struct interact *ia = d->interact;
	if (ia && ia->mode != INTERACT_NONE && ia->view >= 0)
		return ia->view;
	if (d->pointer_view >= 0 && d->env.view[d->pointer_view].used)
		return d->pointer_view;
	for (int v = 0; v < ENV_MAX_VIEWS; v++)
		if (d->env.view[v].used)
			return v;
	return -1;
}

int
daemon_kiosk_figure(const struct daemon *d)
{
	const struct interact *ia = d->interact;
	if (ia && ia->mode != INTERACT_NONE && ia->fig >= 0)
		return ia->fig;
	int sel = family_selected(&d->env);
	if (sel >= 0)
		return sel;
	int k = d->kiosk_fig.fig;
	if (k >= 0 && k < ENV_MAX_FIGURES && d->env.fig[k].gen && d->env.fig[k].gen == d->kiosk_fig.gen)
		return k;
	return -1;
}

int
daemon_is_ghost(const struct daemon *d, int fig)
{
	const struct interact *ia = d->interact;
	return family_is_ghost(&d->env, fig, ia && ia->mode != INTERACT_NONE ? ia->fig : -1);
}

int
daemon_replace_env(struct daemon *d, const char *text, size_t len, char *err, size_t errlen)
{
	struct env *fresh = malloc(sizeof *fresh);
	if (!fresh) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	env_init(fresh);
	struct assess_config cfg;
	if (session_read_with(text, len, d->state_dir, d->library_dir, fresh, &cfg, err, errlen) < 0) {
		free(fresh);
		return -1;
	}
	env_clear(&d->env);
	d->env = *fresh;
	free(fresh);
	if (d->envelopes) /* those of the figures the new environment lacks */
		envelopes_prune(d->envelopes, &d->env);
	daemon_set_assess_config(d, &cfg);
	return 0;
}

struct assess_config
daemon_assess_config(const struct daemon *d)
{
	return d->assess_cfg_set ? d->assess_cfg : assess_config_default();
}

void
daemon_set_assess_config(struct daemon *d, const struct assess_config *cfg)
{
	d->assess_cfg = *cfg;
	d->assess_cfg_set = 1;
	d->assess_serial++;
}

char *
daemon_session_text(const struct daemon *d, size_t *len)
{
	struct assess_config cfg = daemon_assess_config(d);
	return session_to_string_with(&d->env, &cfg, len);
}

int
daemon_step_begin(struct daemon *d, int fig, const char *mode)
{
	struct daemon_step *st = &d->step;
	if (st->open)
		return 0;
	if (!(st->before = daemon_session_text(d, &st->len)))
		return -1;
	st->open = 1;
	st->fig = fig;
	st->gen = fig >= 0 && fig < ENV_MAX_FIGURES ? d->env.fig[fig].gen : 0;
	snprintf(st->mode, sizeof st->mode, "%s", mode);
	return 0;
}

void
daemon_step_moves(struct daemon *d, int fig)
{
	struct daemon_step *st = &d->step;
	if (!st->open || st->fig >= 0 || fig < 0 || fig >= ENV_MAX_FIGURES)
		return;
	st->fig = fig;
	st->gen = d->env.fig[fig].gen;
}

static void
step_close(struct daemon_step *st)
{
	free(st->before);
	st->before = NULL;
	st->open = 0;
}

int
daemon_step_end(struct daemon *d)
{
	struct daemon_step *st = &d->step;
	if (!st->open)
		return 0;
	size_t len;
	char *now = daemon_session_text(d, &len);
	/* a click that moved nothing is no step to undo */
	int changed = !now || len != st->len || memcmp(now, st->before, len);
	free(now);
	if (changed) {
		daemon_checkpoints_push(&d->undo, st->before, st->len);
		daemon_checkpoints_clear(&d->redo);
		st->before = NULL;
	}
	step_close(st);
	return changed;
}

int
daemon_step_abandon(struct daemon *d, char *err, size_t errlen)
{
	struct daemon_step *st = &d->step;
	if (!st->open)
		return 0;
	/* the views stay as they are: a camera turned during the step was journaled on its own */
	struct env_view views[ENV_MAX_VIEWS];
	memcpy(views, d->env.view, sizeof views);
	int rc = daemon_replace_env(d, st->before, st->len, err, errlen);
	if (rc == 0)
		memcpy(d->env.view, views, sizeof views);
	step_close(st);
	return rc;
}

static uint64_t
fnv(uint64_t h, const void *p, size_t n)
{
	const unsigned char *b = p;
	for (size_t i = 0; i < n; i++)
		h = (h ^ b[i]) * 0x100000001b3ull;
	return h;
}

/* the geoms and the sizes of the meshes: cheap, and what a pick model is made of */
static uint64_t
model_print(const struct model *m)
{
	size_t g = (size_t)m->ngeom;
	uint64_t h = fnv(0xcbf29ce484222325ull, &m->nseg, sizeof m->nseg);
	h = fnv(h, &m->ngeom, sizeof m->ngeom);
	h = fnv(h, &m->nvert, sizeof m->nvert);
	h = fnv(h, &m->nface, sizeof m->nface);
	h = fnv(h, m->geom_seg, g * sizeof *m->geom_seg);
	h = fnv(h, m->geom_kind, g * sizeof *m->geom_kind);
	h = fnv(h, m->geom_size, 3 * g * sizeof *m->geom_size);
	h = fnv(h, m->geom_pos, 3 * g * sizeof *m->geom_pos);
	h = fnv(h, m->geom_quat, 4 * g * sizeof *m->geom_quat);
	return fnv(h, m->geom_mesh, g * sizeof *m->geom_mesh);
}

const struct pick_model *
daemon_pick_model(struct daemon *d, int fig)
{
	struct pick_cache *pc = &d->picks;
	const struct env_figure *f = &d->env.fig[fig];
	uint64_t print = model_print(f->model);
	if (pc->pm[fig] && pc->gen[fig] == f->gen && pc->model[fig] == f->model &&
	    pc->print[fig] == print)
		return pc->pm[fig];
	pick_model_free(pc->pm[fig]);
	pc->pm[fig] = pick_model_make(f->model);
	pc->gen[fig] = f->gen;
	pc->model[fig] = f->model;
	pc->print[fig] = print;
	return pc->pm[fig];
}

int
daemon_pick(struct daemon *d, const struct ray *r, double tmin, int skip, struct pick_hit *dest,
	    int *fig)
{
	struct pick_target t[ENV_MAX_FIGURES];
	int slot[ENV_MAX_FIGURES], n = 0;
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		if (!d->env.fig[i].gen || i == skip || daemon_is_ghost(d, i))
			continue;
		const struct pick_model *pm = daemon_pick_model(d, i);
		if (!pm)
			return -1;
		t[n] = (struct pick_target){ pm, d->env.fig[i].model, d->env.fig[i].state };
		slot[n++] = i;
	}
	if (!pick_scene(t, n, r, tmin, dest))
		return 0;
	*fig = slot[dest->figure];
	return 1;
}

void
daemon_picks_free(struct daemon *d)
{
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		pick_model_free(d->picks.pm[i]);
		d->picks.pm[i] = NULL;
	}
}

void
daemon_text_clear(struct daemon_text *t)
{
	free(t->text);
	t->text = NULL;
	t->len = 0;
}
