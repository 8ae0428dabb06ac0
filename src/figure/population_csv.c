/* population_csv.c - reading a population from a CSV file in ANSUR II's layout */
#include "figure/population_csv.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "figure/population_internal.h"

/* what a header's column is */
enum column_kind { COL_IGNORED = -1, COL_SEX = -2 }; /* else a measure's index */

/* the running sums of one sex (Welford's update: no row is kept) */
struct accum {
	int n;
	double mean[POPULATION_NCOL];
	double comoment[POPULATION_NTRI]; /* sum of (x - mean)(x - mean)^T over the rows */
	double *stature;
	int cap;
};

struct reader {
	const char *file;
	int line;
	char *err;
	size_t errlen;
	/* the current line's fields, decoded, each NUL-terminated in buf */
	char *buf;
	char **field;
	int nfield;
	/* the header */
	int ncol;
	int *kind;
	int measures[POPULATION_NCOL]; /* the measure columns, by index, in the header's order */
	int nmeasure;
	struct accum acc[2];
};

static int
fail(struct reader *r, const char *fmt, ...)
{
	int n = snprintf(r->err, r->errlen, "%s:%d: ", r->file, r->line);
	if (n >= 0 && (size_t)n < r->errlen) {
		va_list ap;
		va_start(ap, fmt);
		vsnprintf(r->err + n, r->errlen - (size_t)n, fmt, ap);
		va_end(ap);
	}
	return -1;
}

/* a cell quoted in a message: printable ASCII, at most 24 bytes */
static const char *
shown(const char *s, char dest[32])
{
	size_t i = 0;
	for (; s[i] && i < 24; i++)
		dest[i] = s[i] >= 0x20 && s[i] < 0x7f ? s[i] : '?';
	if (s[i])
		dest[i++] = '.', dest[i++] = '.', dest[i++] = '.';
	dest[i] = 0;
	return dest;
}

/* the line's fields into r->field (decoded into r->buf); -1 on a bad quote or too many */
static int
split(struct reader *r, const char *s, size_t len)
{
	char *out = r->buf;
	size_t i = 0;
	r->nfield = 0;
	for (;;) {
		if (r->nfield >= POPULATION_MAX_FIELDS)
			return fail(r, "more than %d fields", POPULATION_MAX_FIELDS);
		r->field[r->nfield++] = out;
		while (i < len && (s[i] == ' ' || s[i] == '\t'))
			i++;
		if (i < len && s[i] == '"') {
			/* a quoted field: "" is a quote; it must close on this line */
			for (i++;; i++) {
				if (i >= len)
					return fail(r, "a quoted field does not close on its line");
				if (s[i] == '"' && i + 1 < len && s[i + 1] == '"')
					*out++ = s[i++];
				else if (s[i] == '"')
					break;
				else
					*out++ = s[i];
			}
			for (i++; i < len && (s[i] == ' ' || s[i] == '\t'); i++)
				;
			if (i < len && s[i] != ',')
				return fail(r, "text after a quoted field's closing quote");
		} else {
			while (i < len && s[i] != ',')
				*out++ = s[i++];
			while (out > r->field[r->nfield - 1] && (out[-1] == ' ' || out[-1] == '\t'))
				out--;
		}
		*out++ = 0;
		if (i >= len)
			return 0;
		i++; /* the comma */
	}
}

/* a plain decimal number, the whole cell: [+-]digits[.digits][e[+-]digits]; -1 otherwise */
static int
decimal(const char *s, double *dest)
{
	const char *p = s;
	int digits = 0;
	if (*p == '+' || *p == '-')
		p++;
	for (; isdigit((unsigned char)*p); p++)
		digits++;
	if (*p == '.')
		for (p++; isdigit((unsigned char)*p); p++)
			digits++;
	if (!digits)
		return -1;
	if (*p == 'e' || *p == 'E') {
		p++;
		if (*p == '+' || *p == '-')
			p++;
		if (!isdigit((unsigned char)*p))
			return -1;
		while (isdigit((unsigned char)*p))
			p++;
	}
	if (*p)
		return -1;
	*dest = strtod(s, NULL);
	return isfinite(*dest) ? 0 : -1;
}

static int
header(struct reader *r, char *ignored, size_t ignored_len)
{
	int sex_col = -1;
	size_t used = 0;
	r->ncol = r->nfield;
	if (!(r->kind = malloc(sizeof *r->kind * (size_t)r->ncol)))
		return fail(r, "out of memory");
	if (ignored && ignored_len)
		ignored[0] = 0;
	for (int i = 0; i < r->ncol; i++) {
		const char *name = r->field[i];
		char buf[32];
		int m = population_column(name);
		r->kind[i] = m >= 0 ? m : COL_IGNORED;
		if (!strcasecmp(name, "gender") || !strcasecmp(name, "sex")) {
			if (sex_col >= 0)
				return fail(r, "two sex columns (%s and %s)", r->field[sex_col], name);
			sex_col = i;
			r->kind[i] = COL_SEX;
		} else if (m >= 0) {
			for (int j = 0; j < r->nmeasure; j++)
				if (r->measures[j] == m)
					return fail(r, "the column %s appears twice", shown(name, buf));
			r->measures[r->nmeasure++] = m;
		} else if (ignored && used + 1 < ignored_len) {
			/* name the ignored column, ASCII only, as far as there is room */
			if (used)
				ignored[used++] = ',';
			for (const char *c = name; *c && used + 1 < ignored_len; c++)
				ignored[used++] = *c >= 0x20 && *c < 0x7f && *c != ',' ? *c : '?';
			ignored[used] = 0;
		}
	}
	if (sex_col < 0)
		return fail(r, "no sex column (Gender or sex)");
	if (!r->nmeasure)
		return fail(r, "no column is one of ANSUR II's measured dimensions (stature, weightkg, ...)");
	return 0;
}

/* adds one person's measures (and stature) to the sums of their sex */
static int
accumulate(struct accum *a, const int *cols, int k, const double *x)
{
	double delta[POPULATION_NCOL];
	a->n++;
	for (int i = 0; i < k; i++) {
		int c = cols[i];
		delta[i] = x[i] - a->mean[c];
		a->mean[c] += delta[i] / a->n;
	}
	for (int i = 0; i < k; i++)
		for (int j = 0; j < k; j++) {
			int ci = cols[i], cj = cols[j];
			if (cj <= ci)
				a->comoment[ci * (ci + 1) / 2 + cj] += delta[i] * (x[j] - a->mean[cj]);
		}
	return 0;
}

static int
row(struct reader *r)
{
	double x[POPULATION_NCOL];
	int sex = -1, k = 0, stature_col = population_column("stature");
	double stature = NAN;
	char buf[32];
	if (r->nfield != r->ncol)
		return fail(r, "%d fields where the header has %d", r->nfield, r->ncol);
	for (int i = 0; i < r->ncol; i++) {
		const char *cell = r->field[i];
		if (r->kind[i] == COL_IGNORED)
			continue;
		if (r->kind[i] == COL_SEX) {
			if (!cell[0])
				return fail(r, "no sex (the sex column is empty)");
			if (!strcasecmp(cell, "male") || !strcasecmp(cell, "m"))
				sex = HUMAN_MALE;
			else if (!strcasecmp(cell, "female") || !strcasecmp(cell, "f"))
				sex = HUMAN_FEMALE;
			else
				return fail(r, "sex '%s' is neither Male nor Female", shown(cell, buf));
			continue;
		}
		int m = r->kind[i];
		const char *name = population_column_name(m);
		double v, lo, hi, unit = !strcmp(name, "weightkg") ? 10 : 1;
		if (!cell[0])
			return fail(r, "%s is empty", name);
		if (decimal(cell, &v) < 0)
			return fail(r, "%s '%s' is not a number", name, shown(cell, buf));
		population_bounds(m, &lo, &hi);
		if (!(v >= lo * unit && v <= hi * unit))
			return fail(r, "%s %s is outside %g to %g %s (half ANSUR II's smallest to "
				    "twice its largest)", name, shown(cell, buf), lo * unit, hi * unit,
				    unit == 10 ? "tenths of a kilogram, as in ANSUR II" : "mm");
		x[k++] = v / unit;
		if (m == stature_col)
			stature = v;
	}
	if (r->acc[0].n + r->acc[1].n >= POPULATION_MAX_PEOPLE)
		return fail(r, "more than %d people", POPULATION_MAX_PEOPLE);
	struct accum *a = &r->acc[sex];
	if (!isnan(stature)) {
		if (a->n >= a->cap) {
			int cap = a->cap ? 2 * a->cap : 256;
			double *s = realloc(a->stature, sizeof *s * (size_t)cap);
			if (!s)
				return fail(r, "out of memory");
			a->stature = s;
			a->cap = cap;
		}
		a->stature[a->n] = stature;
	}
	/* the measures arrive in the header's order: the same as r->measures */
	return accumulate(a, r->measures, k, x);
}

static int
ascending(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

/* the sums into a population; NULL with the error set */
static struct population *
finish(struct reader *r)
{
	static const char *const people[2] = { "men", "women" };
	if (!r->acc[0].n && !r->acc[1].n) {
		fail(r, "no people: the file holds a header only");
		return NULL;
	}
	for (int s = 0; s < 2; s++)
		if (r->acc[s].n && r->acc[s].n < POPULATION_MIN_PEOPLE) {
			snprintf(r->err, r->errlen, "%s:%d: %d %s: a sex needs at least %d people (or none)",
				 r->file, r->line, r->acc[s].n, people[s], POPULATION_MIN_PEOPLE);
			return NULL;
		}
	struct population *p = population_new_owned();
	if (!p) {
		fail(r, "out of memory");
		return NULL;
	}
	for (int i = 0; i < r->nmeasure; i++)
		p->lacks[r->measures[i]] = 0;
	int has_stature = !p->lacks[population_column("stature")];
	for (int s = 0; s < 2; s++) {
		struct accum *a = &r->acc[s];
		struct population_group *g = &p->sex[s];
		g->n = a->n;
		if (!a->n)
			continue;
		memcpy((double *)g->mean, a->mean, sizeof a->mean);
		for (int i = 0; i < POPULATION_NTRI; i++)
			((double *)g->cov)[i] = a->comoment[i] / (a->n - 1);
		if (has_stature) {
			qsort(a->stature, (size_t)a->n, sizeof *a->stature, ascending);
			g->stature = a->stature;
			a->stature = NULL; /* the population's now */
		}
	}
	return p;
}

struct population *
population_csv_read(const char *text, size_t len, const char *file, char *ignored,
		    size_t ignored_len, char *err, size_t errlen)
{
	struct reader *r = calloc(1, sizeof *r);
	struct population *p = NULL;
	if (!r) {
		snprintf(err, errlen, "%s: out of memory", file);
		return NULL;
	}
	*r = (struct reader){ .file = file, .err = err, .errlen = errlen };
	r->buf = malloc(len + 1);
	r->field = malloc(sizeof *r->field * POPULATION_MAX_FIELDS);
	if (!r->buf || !r->field) {
		fail(r, "out of memory");
		goto out;
	}
	const char *s = text, *end = text + len;
	if (len >= 3 && !memcmp(s, "\xef\xbb\xbf", 3))
		s += 3; /* a UTF-8 byte order mark */
	int have_header = 0;
	while (s < end) {
		const char *nl = memchr(s, '\n', (size_t)(end - s));
		const char *e = nl ? nl : end;
		size_t n = (size_t)(e - s);
		r->line++;
		if (memchr(s, 0, n)) {
			fail(r, "a NUL byte");
			goto out;
		}
		if (n && s[n - 1] == '\r')
			n--;
		if (n && split(r, s, n) < 0)
			goto out;
		if (n && !have_header) {
			if (header(r, ignored, ignored_len) < 0)
				goto out;
			have_header = 1;
		} else if (n && row(r) < 0) {
			goto out;
		}
		s = nl ? nl + 1 : end;
	}
	if (!have_header) {
		r->line = r->line ? r->line : 1;
		fail(r, "empty: no header");
		goto out;
	}
	p = finish(r);
out:
	free(r->acc[0].stature);
	free(r->acc[1].stature);
	free(r->kind);
	free(r->field);
	free(r->buf);
	free(r);
	return p;
}
