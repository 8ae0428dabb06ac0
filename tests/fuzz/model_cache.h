/*
 * model_cache.h - for harnesses whose inputs load figures often (sessions,
 * journals): linked with -Wl,--wrap=human_build,--wrap=figure_read_file,
 * each standard human is built once per (stature, mass, sex) and each
 * figure file read once per path, and handed out as copies. Both are
 * deterministic (test_human: built twice, the same model; the files do not
 * change while the harness runs), so the parser under test sees what it
 * would; the figure language has a harness of its own, the human's builder
 * reads no outside bytes, and the two were most of an input's time.
 */
#ifndef POSTURE_FUZZ_MODEL_CACHE_H
#define POSTURE_FUZZ_MODEL_CACHE_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/figure.h"
#include "figure/human.h"

struct model *__real_human_build(const struct human_def *d, char *err, size_t errlen);
struct model *__wrap_human_build(const struct human_def *d, char *err, size_t errlen);
struct model *__real_figure_read_file(const char *path, char *err, size_t errlen);
struct model *__wrap_figure_read_file(const char *path, char *err, size_t errlen);

#define MODEL_CACHE_N 8

static struct model *
model_cache_copy(const struct model *m, char *err, size_t errlen)
{
	struct model *c = model_copy(m);
	if (!c && err && errlen)
		snprintf(err, errlen, "out of memory");
	return c;
}

struct model *
__wrap_human_build(const struct human_def *d, char *err, size_t errlen)
{
	static struct {
		struct human_def def;
		struct model *m;
	} cache[MODEL_CACHE_N];
	static int next;
	for (int i = 0; i < MODEL_CACHE_N; i++)
		if (cache[i].m && cache[i].def.sex == d->sex &&
		    !memcmp(&cache[i].def.stature, &d->stature, sizeof d->stature) &&
		    !memcmp(&cache[i].def.mass, &d->mass, sizeof d->mass))
			return model_cache_copy(cache[i].m, err, errlen);
	struct model *m = __real_human_build(d, err, errlen);
	if (!m)
		return NULL;
	model_free(cache[next].m);
	cache[next].def = *d;
	cache[next].m = m;
	next = (next + 1) % MODEL_CACHE_N;
	return model_cache_copy(m, err, errlen);
}

/* figures read well are kept; a file that fails is read again each time */
struct model *
__wrap_figure_read_file(const char *path, char *err, size_t errlen)
{
	static struct {
		char *path;
		struct model *m;
	} cache[MODEL_CACHE_N];
	static int next;
	for (int i = 0; i < MODEL_CACHE_N; i++)
		if (cache[i].m && !strcmp(cache[i].path, path))
			return model_cache_copy(cache[i].m, err, errlen);
	struct model *m = __real_figure_read_file(path, err, errlen);
	char *kept = m ? strdup(path) : NULL;
	if (!kept)
		return m;
	model_free(cache[next].m);
	free(cache[next].path);
	cache[next].path = kept;
	cache[next].m = m;
	next = (next + 1) % MODEL_CACHE_N;
	return model_cache_copy(m, err, errlen);
}

#endif
