/* envelopes.c - the reach envelopes the daemon keeps (see envelopes.h) */
#include "daemon/envelopes.h"

#include <stdio.h>
#include <string.h>

const float ENVELOPE_REACH_RGBA[4] = { 0.25f, 0.55f, 0.95f, 0.30f };   /* blue */
const float ENVELOPE_COMFORT_RGBA[4] = { 0.30f, 0.85f, 0.35f, 0.40f }; /* green */

int
envelopes_find(const struct envelopes *s, const char *name)
{
	for (int k = 0; k < ENVELOPES_MAX; k++)
		if (s->slot[k].used && !strcmp(s->slot[k].name, name))
			return k;
	return -1;
}

int
envelopes_put(struct envelopes *s, const char *name, const struct env *env, int fig,
	      struct envelope *e)
{
	int k = envelopes_find(s, name);
	for (int i = 0; k < 0 && i < ENVELOPES_MAX; i++)
		if (!s->slot[i].used)
			k = i;
	if (k < 0) {
		envelope_free(e);
		return -1;
	}
	struct envelope_entry *x = &s->slot[k];
	int hidden = x->used && x->hidden; /* a replaced envelope keeps being hidden */
	if (x->used)
		envelope_free(&x->e);
	memset(x, 0, sizeof *x);
	x->used = 1;
	snprintf(x->name, sizeof x->name, "%s", name);
	x->fig = fig;
	x->gen = env->fig[fig].gen;
	snprintf(x->fig_name, sizeof x->fig_name, "%s", env->fig[fig].name);
	x->hidden = hidden;
	x->e = *e;
	memset(e, 0, sizeof *e);
	x->serial = ++s->serial;
	return k;
}

void
envelopes_remove(struct envelopes *s, int k)
{
	if (k < 0 || k >= ENVELOPES_MAX || !s->slot[k].used)
		return;
	envelope_free(&s->slot[k].e);
	memset(&s->slot[k], 0, sizeof s->slot[k]);
	s->serial++;
}

void
envelopes_set_hidden(struct envelopes *s, int k, int hidden)
{
	if (k < 0 || k >= ENVELOPES_MAX || !s->slot[k].used || s->slot[k].hidden == !!hidden)
		return;
	s->slot[k].hidden = !!hidden;
	s->serial++;
}

int
envelopes_prune(struct envelopes *s, const struct env *env)
{
	int n = 0;
	for (int k = 0; k < ENVELOPES_MAX; k++) {
		const struct envelope_entry *x = &s->slot[k];
		if (!x->used)
			continue;
		const struct env_figure *f = &env->fig[x->fig];
		if (f->gen == x->gen && !strcmp(f->name, x->fig_name))
			continue;
		envelopes_remove(s, k);
		n++;
	}
	return n;
}

int
envelopes_count(const struct envelopes *s)
{
	int n = 0;
	for (int k = 0; k < ENVELOPES_MAX; k++)
		n += s->slot[k].used;
	return n;
}

void
envelopes_clear(struct envelopes *s)
{
	for (int k = 0; k < ENVELOPES_MAX; k++)
		envelopes_remove(s, k);
}
