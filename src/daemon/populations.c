/* populations.c - the daemon's populations: the built-in one and those loaded */
#include "daemon/populations.h"

#include <stdlib.h>
#include <string.h>

const struct population *
populations_find(const struct populations *ps, const char *name)
{
	if (!strcmp(name, POPULATIONS_BUILTIN))
		return population_ansur2();
	for (int i = 0; i < POPULATIONS_MAX; i++)
		if (ps->pop[i] && !strcmp(ps->name[i], name))
			return ps->pop[i];
	return NULL;
}

int
populations_add(struct populations *ps, const char *name, struct population *p)
{
	int slot = -1;
	if (!strcmp(name, POPULATIONS_BUILTIN) || strlen(name) >= sizeof ps->name[0]) {
		population_free(p);
		return -1;
	}
	for (int i = 0; i < POPULATIONS_MAX && slot < 0; i++)
		if (ps->pop[i] && !strcmp(ps->name[i], name))
			slot = i;
	for (int i = 0; i < POPULATIONS_MAX && slot < 0; i++)
		if (!ps->pop[i])
			slot = i;
	if (slot < 0) {
		population_free(p);
		return -1;
	}
	population_free(ps->pop[slot]);
	ps->pop[slot] = p;
	snprintf(ps->name[slot], sizeof ps->name[slot], "%s", name);
	return 0;
}

void
populations_clear(struct populations *ps)
{
	for (int i = 0; i < POPULATIONS_MAX; i++)
		population_free(ps->pop[i]);
	memset(ps, 0, sizeof *ps);
}

int
populations_write(const struct populations *ps, FILE *f)
{
	int n = 0;
	for (int i = 0; i < POPULATIONS_MAX; i++)
		n += ps->pop[i] != NULL;
	fprintf(f, "populations %d\n", n);
	for (int i = 0; i < POPULATIONS_MAX; i++) {
		if (!ps->pop[i])
			continue;
		char *text = NULL;
		size_t len = 0;
		FILE *m = open_memstream(&text, &len);
		if (!m)
			return -1;
		int bad = population_stats_write(ps->pop[i], m);
		if (fclose(m) != 0 || bad) {
			free(text);
			return -1;
		}
		fprintf(f, "population %s %zu\n", ps->name[i], len);
		fwrite(text, 1, len, f);
		free(text);
	}
	return ferror(f) ? -1 : 0;
}

int
populations_read(struct populations *ps, const char *text, size_t len, size_t *used, char *err,
		 size_t errlen)
{
	struct populations fresh = { 0 };
	const char *p = text, *end = text + len;
	int n;
	char head[32];
	snprintf(head, sizeof head, "%.*s", (int)(len < 31 ? len : 31), text);
	if (sscanf(head, "populations %d", &n) != 1 || n < 0 || n > POPULATIONS_MAX ||
	    !(p = memchr(p, '\n', len))) {
		snprintf(err, errlen, "expected 'populations N'");
		return -1;
	}
	p++;
	for (int i = 0; i < n; i++) {
		char name[64], line[128];
		size_t plen;
		const char *nl = memchr(p, '\n', (size_t)(end - p));
		if (!nl || nl - p >= (long)sizeof line)
			goto bad;
		memcpy(line, p, (size_t)(nl - p));
		line[nl - p] = 0;
		if (sscanf(line, "population %47s %zu", name, &plen) != 2 || plen > (size_t)(end - nl - 1))
			goto bad;
		struct population *pop = population_stats_read(nl + 1, plen, err, errlen);
		if (!pop || populations_add(&fresh, name, pop) < 0)
			goto bad;
		p = nl + 1 + plen;
	}
	populations_clear(ps);
	*ps = fresh;
	*used = (size_t)(p - text);
	return 0;
bad:
	populations_clear(&fresh);
	snprintf(err, errlen, "a bad population in the saved state");
	return -1;
}
