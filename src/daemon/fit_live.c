/* fit_live.c - the figures' collision models and the caches of their pairs */
#include "daemon/fit_live.h"

#include <stdio.h>
#include <stdlib.h>

#include "daemon/daemon.h"

struct fit_entry {
	uint32_t gen;              /* the figure slot's generation it was built for */
	const struct model *model; /* and its model */
	struct fit_model *fit;
};

struct fit_live {
	struct fit_entry fig[ENV_MAX_FIGURES];
	/* cache[a][b]: figure a against figure b (a == b: itself), made when first asked */
	struct clearance_cache *cache[ENV_MAX_FIGURES][ENV_MAX_FIGURES];
	struct clearance_work *work;
	unsigned long built;
};

#define FIT_MAX_SEG 256 /* segments of a figure the work is made for */

int
fit_live_init(struct daemon *d)
{
	if (d->fit_live)
		return 0;
	struct fit_live *f = calloc(1, sizeof *f);
	if (!f || !(f->work = clearance_work_make(FIT_MAX_SEG))) {
		free(f);
		return -1;
	}
	d->fit_live = f;
	return 0;
}

/* forgets figure slot i's model and every cache that involves it */
static void
drop(struct fit_live *f, int i)
{
	fit_model_free(f->fig[i].fit);
	f->fig[i] = (struct fit_entry){ 0 };
	for (int k = 0; k < ENV_MAX_FIGURES; k++) {
		clearance_cache_free(f->cache[i][k]);
		f->cache[i][k] = NULL;
		if (k != i) {
			clearance_cache_free(f->cache[k][i]);
			f->cache[k][i] = NULL;
		}
	}
}

void
fit_live_free(struct daemon *d)
{
	struct fit_live *f = d->fit_live;
	if (!f)
		return;
	for (int i = 0; i < ENV_MAX_FIGURES; i++)
		drop(f, i);
	clearance_work_free(f->work);
	free(f);
	d->fit_live = NULL;
}

unsigned long
fit_live_built(const struct daemon *d)
{
	return d->fit_live ? d->fit_live->built : 0;
}

const struct fit_model *
fit_live_model(struct daemon *d, int fig, char *why, size_t len)
{
	struct fit_live *f = d->fit_live;
	const struct env_figure *ef = fig >= 0 && fig < ENV_MAX_FIGURES ? &d->env.fig[fig] : NULL;
	if (!f || !ef || !ef->gen) {
		snprintf(why, len, "no figure");
		return NULL;
	}
	struct fit_entry *e = &f->fig[fig];
	if (e->fit && e->gen == ef->gen && e->model == ef->model)
		return e->fit;
	drop(f, fig);
	if (ef->model->nseg > FIT_MAX_SEG) {
		snprintf(why, len, "%s has %d segments; the fit analysis takes up to %d", ef->name,
			 ef->model->nseg, FIT_MAX_SEG);
		return NULL;
	}
	char err[160];
	if (!(e->fit = fit_model_make(ef->model, err, sizeof err))) {
		snprintf(why, len, "%s: %s", ef->name, err);
		return NULL;
	}
	e->gen = ef->gen;
	e->model = ef->model;
	f->built++;
	return e->fit;
}

static struct clearance_cache *
cache_of(struct fit_live *f, int a, int b)
{
	if (!f->cache[a][b])
		f->cache[a][b] = clearance_cache_make(f->fig[a].fit, f->fig[b].fit);
	return f->cache[a][b];
}

int
fit_live_clearance(struct daemon *d, int fig, const int *with, int n, int self,
		   struct clearance_result *res, char *why, size_t len)
{
	struct fit_live *f = d->fit_live;
	const struct fit_model *fa = fit_live_model(d, fig, why, len);
	if (!fa)
		return -1;
	for (int k = 0; k < n; k++)
		if (!fit_live_model(d, with[k], why, len))
			return -1;
	const struct state *sa = d->env.fig[fig].state;
	for (int k = 0; k < n; k++) {
		int b = with[k];
		struct clearance_cache *c = cache_of(f, fig, b);
		if (!c) {
			snprintf(why, len, "out of memory");
			return -1;
		}
		if (clearance_between(f->work, c, fig, fa, sa, b, f->fig[b].fit, d->env.fig[b].state,
				      res) < 0) {
			snprintf(why, len, "the collision library failed");
			return -1;
		}
	}
	if (self) {
		struct clearance_cache *c = cache_of(f, fig, fig);
		if (!c) {
			snprintf(why, len, "out of memory");
			return -1;
		}
		if (clearance_self(f->work, c, fig, fa, sa, res) < 0) {
			snprintf(why, len, "the collision library failed");
			return -1;
		}
	}
	clearance_sort(res);
	return 0;
}
