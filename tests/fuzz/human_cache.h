/*
 * human_cache.h - for harnesses whose inputs load the standard human often
 * (sessions, journals): linked with -Wl,--wrap=human_build, each human is
 * built once per (stature, mass, sex) and handed out as a copy. Building is
 * deterministic (test_human: twice, the same model), so the parsers see
 * what they would; the builder itself reads no outside bytes, and its
 * 0.5 ms under the sanitizers would otherwise be most of an input's time.
 */
#ifndef POSTURE_FUZZ_HUMAN_CACHE_H
#define POSTURE_FUZZ_HUMAN_CACHE_H

#include <stdio.h>
#include <string.h>

#include "figure/human.h"

struct model *__real_human_build(const struct human_def *d, char *err, size_t errlen);
struct model *__wrap_human_build(const struct human_def *d, char *err, size_t errlen);

static struct model *
copy(const struct model *m, char *err, size_t errlen)
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
	} cache[8];
	static int next;
	for (int i = 0; i < 8; i++)
		if (cache[i].m && cache[i].def.sex == d->sex &&
		    !memcmp(&cache[i].def.stature, &d->stature, sizeof d->stature) &&
		    !memcmp(&cache[i].def.mass, &d->mass, sizeof d->mass))
			return copy(cache[i].m, err, errlen);
	struct model *m = __real_human_build(d, err, errlen);
	if (!m)
		return NULL;
	model_free(cache[next].m);
	cache[next].def = *d;
	cache[next].m = m;
	next = (next + 1) % 8;
	return copy(m, err, errlen);
}

#endif
