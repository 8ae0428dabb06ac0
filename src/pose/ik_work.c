/* ik_work.c - the record of a solve's work and its line of text */
#include "pose/ik_work.h"

#include <limits.h>
#include <stdio.h>
#include <string.h>

#include "pose/ik_constraint.h"

struct ik_work
ik_work_none(void)
{
	struct ik_work w = { 0, 0, 0, -1, 0, 0 };
	return w;
}

int
ik_work_equal(const struct ik_work *a, const struct ik_work *b)
{
	return a->cut == b->cut && a->iterations == b->iterations && a->round == b->round &&
	       a->group == b->group && a->start == b->start &&
	       a->start_iterations == b->start_iterations;
}

int
ik_work_write(const struct ik_work *w, char *dest, size_t cap)
{
	int n = snprintf(dest, cap, "ik_work cut=%d iterations=%d round=%d group=%d start=%d "
			 "start_iterations=%d", w->cut, w->iterations, w->round, w->group, w->start,
			 w->start_iterations);
	if (n < 0 || (size_t)n >= cap) {
		if (cap > 0)
			dest[0] = '\0';
		return -1;
	}
	return n;
}

/* the line's fields, in order; -1 allowed only where the field says */
static const struct {
	const char *key;
	size_t offset;
	int may_be_none;
} FIELDS[] = {
	{ "cut", offsetof(struct ik_work, cut), 0 },
	{ "iterations", offsetof(struct ik_work, iterations), 0 },
	{ "round", offsetof(struct ik_work, round), 0 },
	{ "group", offsetof(struct ik_work, group), 1 },
	{ "start", offsetof(struct ik_work, start), 0 },
	{ "start_iterations", offsetof(struct ik_work, start_iterations), 0 },
};

/* a decimal int at *p without sign or leading zeros ("-1" when none_ok); advances *p */
static int
read_count(const char **p, int none_ok, int *dest)
{
	const char *s = *p;
	if (none_ok && s[0] == '-' && s[1] == '1' && (s[2] < '0' || s[2] > '9')) {
		*dest = -1;
		*p = s + 2;
		return 0;
	}
	if (*s < '0' || *s > '9' || (s[0] == '0' && s[1] >= '0' && s[1] <= '9'))
		return -1;
	long v = 0;
	for (; *s >= '0' && *s <= '9'; s++) {
		v = v * 10 + (*s - '0');
		if (v > INT_MAX)
			return -1;
	}
	*dest = (int)v;
	*p = s;
	return 0;
}

/* the fields agree with each other */
static const char *
inconsistency(const struct ik_work *w)
{
	if (w->cut != 0 && w->cut != 1)
		return "cut is neither 0 nor 1";
	if (w->group >= IK_MAX_GROUPS)
		return "group beyond the solver's groups";
	if (w->start_iterations > w->iterations)
		return "start_iterations exceeds iterations";
	if (w->group < 0 && (w->cut || w->iterations || w->round || w->start))
		return "work recorded without a group";
	return NULL;
}

int
ik_work_read(const char *line, struct ik_work *dest, char *err, size_t errlen)
{
	static const char TAG[] = "ik_work";
	struct ik_work w;
	const char *p = line;
	if (strncmp(p, TAG, sizeof TAG - 1) != 0) {
		snprintf(err, errlen, "ik_work: the line does not begin with \"%s\"", TAG);
		return -1;
	}
	p += sizeof TAG - 1;
	for (size_t f = 0; f < sizeof FIELDS / sizeof *FIELDS; f++) {
		size_t klen = strlen(FIELDS[f].key);
		if (p[0] != ' ' || strncmp(p + 1, FIELDS[f].key, klen) != 0 || p[1 + klen] != '=') {
			snprintf(err, errlen, "ik_work: byte %zu: expected \" %s=\"", (size_t)(p - line),
				 FIELDS[f].key);
			return -1;
		}
		p += 2 + klen;
		int *field = (int *)((char *)&w + FIELDS[f].offset);
		if (read_count(&p, FIELDS[f].may_be_none, field) < 0) {
			snprintf(err, errlen, "ik_work: byte %zu: %s is not a count%s", (size_t)(p - line),
				 FIELDS[f].key, FIELDS[f].may_be_none ? " or -1" : "");
			return -1;
		}
	}
	if (p[0] == '\n')
		p++;
	if (*p) {
		snprintf(err, errlen, "ik_work: byte %zu: unexpected text after the last field",
			 (size_t)(p - line));
		return -1;
	}
	const char *why = inconsistency(&w);
	if (why) {
		snprintf(err, errlen, "ik_work: %s", why);
		return -1;
	}
	*dest = w;
	return 0;
}
