/* complete.c - Tab at the kiosk's edit line (see complete.h) */
#include "daemon/complete.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/cmd.h"

struct found {
	const char **dest;
	int n, max;
	const char *prefix;
	size_t plen;
	struct complete *c;
};

static int
already(const struct found *f, const char *w)
{
	for (int i = 0; i < f->n; i++)
		if (!strcmp(f->dest[i], w))
			return 1;
	return 0;
}

/* w (lasting as long as the environment) when it starts with the prefix */
static void
offer(struct found *f, const char *w)
{
	if (f->n < f->max && w[0] && !strncmp(w, f->prefix, f->plen) && !already(f, w))
		f->dest[f->n++] = w;
}

/* a word made here ("hand_r.palm", "start="): kept in the pool */
static void
offer_made(struct found *f, const char *w)
{
	size_t len = strlen(w) + 1;
	if (strncmp(w, f->prefix, f->plen) || f->c->used + len > sizeof f->c->pool)
		return;
	char *at = f->c->pool + f->c->used;
	memcpy(at, w, len);
	f->c->used += len;
	offer(f, at);
}

static void
offer_figure_parts(struct found *f, const struct env_figure *fig)
{
	const struct model *m = fig->model;
	for (int j = 0; j < m->njnt; j++)
		offer(f, m->jnt_name[j]);
	char name[2 * MODEL_NAME_MAX];
	for (int k = 0; k < m->nsite; k++)
		offer_made(f, model_site_fullname(m, k, name, sizeof name));
}

/* the key=... words of the usage of the command the line starts with */
static void
offer_keys(struct found *f, const char *verb, const char *object)
{
	for (int i = 0; cmd_entry_verb(i); i++) {
		if (strcmp(cmd_entry_verb(i), verb) || strcmp(cmd_entry_object(i), object))
			continue;
		const char *u = cmd_entry_usage(i);
		for (const char *eq = strchr(u, '='); eq; eq = strchr(eq + 1, '=')) {
			const char *start = eq;
			while (start > u && (start[-1] == '_' || (start[-1] >= 'a' && start[-1] <= 'z')))
				start--;
			char key[40];
			size_t n = (size_t)(eq - start) + 1;
			if (n < 2 || n >= sizeof key)
				continue;
			memcpy(key, start, n);
			key[n] = '\0';
			offer_made(f, key);
		}
	}
}

static int
by_name(const void *a, const void *b)
{
	return strcmp(*(const char *const *)a, *(const char *const *)b);
}

int
complete_words(void *user, const char *const *words, int nwords, const char *prefix,
	       const char **dest, int max)
{
	struct complete *c = user;
	struct found f = { dest, 0, max, prefix, strlen(prefix), c };
	c->used = 0;
	const struct env *e = &c->d->env;
	if (nwords == 0) {
		for (int i = 0; cmd_entry_verb(i); i++)
			offer(&f, cmd_entry_verb(i));
	} else {
		int objects = 0;
		for (int i = 0; nwords == 1 && cmd_entry_verb(i); i++)
			if (!strcmp(cmd_entry_verb(i), words[0]) && cmd_entry_object(i)[0]) {
				offer(&f, cmd_entry_object(i));
				objects = 1;
			}
		if (!objects) {
			for (int i = 0; i < ENV_MAX_FIGURES; i++)
				if (e->fig[i].gen) {
					offer(&f, e->fig[i].name);
					offer(&f, e->fig[i].manikin.family); /* a family's prefix */
				}
			for (int i = 0; i < ENV_MAX_CONSTRAINTS; i++)
				if (e->con[i].gen)
					offer(&f, e->con[i].name);
			for (int i = 0; i < ENV_MAX_VIEWS; i++)
				if (e->view[i].used)
					offer(&f, e->view[i].name);
			/* the parts of a figure named earlier on the line */
			for (int w = 1; w < nwords; w++) {
				int fig = env_find_figure(e, words[w]);
				if (fig >= 0)
					offer_figure_parts(&f, &e->fig[fig]);
			}
			offer(&f, "left");
			offer(&f, "right");
			offer_keys(&f, words[0], nwords > 1 ? words[1] : "");
			offer_keys(&f, words[0], "");
		}
	}
	qsort(dest, (size_t)f.n, sizeof *dest, by_name);
	return f.n;
}
