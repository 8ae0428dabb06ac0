/* history.c - the undo checkpoints as environments, for exports over time */
#include "daemon/history.h"

#include <stdio.h>
#include <stdlib.h>

#include "daemon/session.h"
#include "figure/kin.h"

int
history_read(const struct daemon *d, struct history *h, char *err, size_t errlen)
{
	h->n = 0;
	h->env = d->undo.n ? malloc(sizeof *h->env * (size_t)d->undo.n) : NULL;
	if (d->undo.n && !h->env) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	for (int k = 0; k < d->undo.n; k++) {
		struct env *e = &h->env[k];
		env_init(e);
		char why[300];
		if (session_read(d->undo.text[k], d->undo.len[k], d->state_dir, d->library_dir, e, why,
				 sizeof why) < 0) {
			snprintf(err, errlen, "undo checkpoint %d: %s", k + 1, why);
			history_free(h);
			return -1;
		}
		h->n++;
		for (int f = 0; f < ENV_MAX_FIGURES; f++)
			if (e->fig[f].gen)
				kin_update(e->fig[f].model, e->fig[f].state);
	}
	return 0;
}

void
history_free(struct history *h)
{
	for (int k = 0; k < h->n; k++)
		env_clear(&h->env[k]);
	free(h->env);
	h->env = NULL;
	h->n = 0;
}

void
history_motion(const struct daemon *d, const struct history *h, int fig,
	       const struct state **frames, struct motion *dest)
{
	const struct env_figure *now = &d->env.fig[fig];
	dest->name = now->name;
	dest->m = now->model;
	dest->now = now->state;
	dest->frames = NULL;
	dest->nframes = 0;
	if (!h)
		return;
	for (int k = 0; k < h->n; k++) {
		int then = env_find_figure(&h->env[k], now->name);
		frames[k] = then >= 0 && model_equal(h->env[k].fig[then].model, now->model)
				    ? h->env[k].fig[then].state
				    : NULL;
	}
	frames[h->n] = now->state;
	dest->frames = frames;
	dest->nframes = h->n + 1;
}
