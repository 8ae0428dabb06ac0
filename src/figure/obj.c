/* obj.c - Wavefront OBJ reader (see obj.h) */
#include "figure/obj.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define OBJ_COUNT_MAX (INT_MAX / 3) /* vertices or triangles of one mesh */

struct obj_parse {
	const char *origin;
	char *err;
	size_t errlen;
	int line;		/* 1-based number of the line being parsed */
	const char *line_start; /* its first byte, for columns */
	struct obj_mesh m;
	int capvert, capface;
};

/* formats "origin:line:col: message" for the byte `at` of the current line */
static int obj_fail(struct obj_parse *p, const char *at, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

static int
obj_fail(struct obj_parse *p, const char *at, const char *fmt, ...)
{
	char msg[256];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	int col = at ? (int)(at - p->line_start) + 1 : 1;
	if (p->err && p->errlen)
		snprintf(p->err, p->errlen, "%s:%d:%d: %s", p->origin, p->line, col, msg);
	return -1;
}

static int
obj_is_blank(char c)
{
	return c == ' ' || c == '\t';
}

static char *
obj_skip_blank(char *s)
{
	while (obj_is_blank(*s))
		s++;
	return s;
}

/* length of the word at s, for messages */
static int
obj_word_len(const char *s)
{
	int n = 0;
	while (s[n] && !obj_is_blank(s[n]) && n < 40)
		n++;
	return n;
}

/* doubles the capacity of *arr (elements of elem bytes) when n reaches it */
static int
obj_grow(void **arr, int *cap, int n, size_t elem)
{
	if (n < *cap)
		return 0;
	int ncap = *cap ? *cap * 2 : 64;
	if (*cap > OBJ_COUNT_MAX / 2)
		ncap = OBJ_COUNT_MAX;
	void *q = realloc(*arr, (size_t)ncap * elem);
	if (!q)
		return -1;
	*arr = q;
	*cap = ncap;
	return 0;
}

/* `v x y z [more numbers]`: the first three are the position */
static int
obj_vertex(struct obj_parse *p, char *s)
{
	double v[3] = { 0, 0, 0 };
	int n = 0;
	for (s = obj_skip_blank(s); *s; s = obj_skip_blank(s)) {
		char *end;
		double x = strtod(s, &end);
		if (end == s || (*end && !obj_is_blank(*end)))
			return obj_fail(p, s, "expected a number, found '%.*s'", obj_word_len(s),
					s);
		if (!isfinite(x) || !isfinite((float)x))
			return obj_fail(
				p, s,
				"vertex coordinate '%.*s' is not a finite single-precision number",
				obj_word_len(s), s);
		if (n < 3)
			v[n] = x;
		n++;
		s = end;
	}
	if (n < 3)
		return obj_fail(p, s, "a vertex needs 3 coordinates, found %d", n);
	if (p->m.nvert >= OBJ_COUNT_MAX)
		return obj_fail(p, NULL, "more than %d vertices", OBJ_COUNT_MAX);
	if (obj_grow((void **)&p->m.vert, &p->capvert, p->m.nvert, 3 * sizeof(float)) < 0)
		return obj_fail(p, NULL, "out of memory");
	for (int i = 0; i < 3; i++)
		p->m.vert[3 * p->m.nvert + i] = (float)v[i];
	p->m.nvert++;
	return 0;
}

/*
 * parses an optionally signed decimal integer at s; returns the number of
 * bytes read (0 when there is none) and sets *overflow beyond int range
 */
static int
obj_int(const char *s, long long *dest, int *overflow)
{
	int i = 0, neg = 0;
	long long v = 0;
	if (s[i] == '-' || s[i] == '+')
		neg = s[i++] == '-';
	if (s[i] < '0' || s[i] > '9')
		return 0;
	*overflow = 0;
	for (; s[i] >= '0' && s[i] <= '9'; i++) {
		v = v * 10 + (s[i] - '0');
		if (v > INT_MAX) {
			*overflow = 1;
			v = INT_MAX;
		}
	}
	*dest = neg ? -v : v;
	return i;
}

static int
obj_add_triangle(struct obj_parse *p, int a, int b, int c)
{
	if (p->m.nface >= OBJ_COUNT_MAX)
		return obj_fail(p, NULL, "more than %d triangles", OBJ_COUNT_MAX);
	if (obj_grow((void **)&p->m.face, &p->capface, p->m.nface, 3 * sizeof(int)) < 0)
		return obj_fail(p, NULL, "out of memory");
	int *f = &p->m.face[3 * p->m.nface++];
	f[0] = a;
	f[1] = b;
	f[2] = c;
	return 0;
}

/* `f a b c ...` with corners v, v/t, v//n or v/t/n; fan-triangulated */
static int
obj_face(struct obj_parse *p, char *s)
{
	int ncorner = 0, first = -1, prev = -1;
	for (s = obj_skip_blank(s); *s; s = obj_skip_blank(s)) {
		char *corner = s;
		long long v, t;
		int overflow = 0;
		int n = obj_int(s, &v, &overflow);
		if (n == 0)
			return obj_fail(p, s, "expected a vertex index, found '%.*s'",
					obj_word_len(s), s);
		if (overflow)
			return obj_fail(p, s, "vertex index '%.*s' is out of range", n, s);
		s += n;
		/* texture and normal indices are read and dropped */
		for (int k = 0; k < 2 && *s == '/'; k++) {
			s++;
			s += obj_int(s, &t, &overflow);
		}
		if (*s && !obj_is_blank(*s))
			return obj_fail(p, corner,
					"expected a face corner 'v', 'v/t', 'v//n' or 'v/t/n', "
					"found '%.*s'",
					obj_word_len(corner), corner);
		if (v == 0)
			return obj_fail(p, corner, "vertex index 0 (OBJ indices start at 1)");
		long long i = v > 0 ? v - 1 : p->m.nvert + v;
		if (i < 0 || i >= p->m.nvert)
			return obj_fail(p, corner,
					"face refers to vertex %lld, but only %d vertices are "
					"defined so far",
					v, p->m.nvert);
		if (ncorner == 0)
			first = (int)i;
		else if (ncorner >= 2 && obj_add_triangle(p, first, prev, (int)i) < 0)
			return -1;
		prev = (int)i;
		ncorner++;
	}
	if (ncorner < 3)
		return obj_fail(p, s, "a face needs at least 3 corners, found %d", ncorner);
	return 0;
}

/* one line, already cut at its end (NUL) */
static int
obj_line(struct obj_parse *p, char *s, size_t n)
{
	for (size_t i = 0; i < n; i++) {
		unsigned char c = (unsigned char)s[i];
		if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7f)
			return obj_fail(p, s + i, "binary data (byte 0x%02x) in a text file", c);
	}
	if (n > 0 && s[n - 1] == '\r')
		s[n - 1] = 0;
	s = obj_skip_blank(s);
	if (s[0] == 'v' && (obj_is_blank(s[1]) || !s[1]))
		return obj_vertex(p, s + 1);
	if (s[0] == 'f' && (obj_is_blank(s[1]) || !s[1]))
		return obj_face(p, s + 1);
	return 0; /* comments, blank lines and other statements */
}

/* buf holds len bytes followed by a NUL and is cut into lines in place */
static int
obj_parse_buffer(struct obj_parse *p, char *buf, size_t len)
{
	char *s = buf, *end = buf + len;
	while (s < end) {
		char *nl = memchr(s, '\n', (size_t)(end - s));
		char *le = nl ? nl : end;
		*le = 0;
		p->line++;
		p->line_start = s;
		if (obj_line(p, s, (size_t)(le - s)) < 0)
			return -1;
		s = le + 1;
	}
	if (p->m.nface == 0) {
		p->line_start = NULL;
		if (p->line == 0)
			p->line = 1;
		return obj_fail(p, NULL, "no faces: a mesh needs at least one 'f' line");
	}
	return 0;
}

int
obj_read_string(const char *text, size_t len, const char *origin, struct obj_mesh *dest, char *err,
		size_t errlen)
{
	struct obj_parse p = { .origin = origin ? origin : "<obj>", .err = err, .errlen = errlen };
	memset(dest, 0, sizeof *dest);
	p.line = 1;
	if (len > OBJ_TEXT_MAX)
		return obj_fail(&p, NULL, "larger than %u MiB", OBJ_TEXT_MAX >> 20);
	p.line = 0;
	char *buf = malloc(len + 1);
	if (!buf) {
		p.line = 1;
		return obj_fail(&p, NULL, "out of memory");
	}
	memcpy(buf, text, len);
	buf[len] = 0;
	int rc = obj_parse_buffer(&p, buf, len);
	free(buf);
	if (rc < 0) {
		obj_mesh_free(&p.m);
		return -1;
	}
	*dest = p.m;
	return 0;
}

int
obj_read_file(const char *path, struct obj_mesh *dest, char *err, size_t errlen)
{
	memset(dest, 0, sizeof *dest);
	FILE *f = fopen(path, "rb");
	if (!f) {
		if (err && errlen)
			snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
		return -1;
	}
	/* read at most OBJ_TEXT_MAX + 1 bytes, so that a larger file is caught */
	size_t cap = 1 << 16, len = 0;
	char *buf = malloc(cap);
	int rc = -1;
	while (buf) {
		if (len == cap) {
			size_t ncap = cap * 2 > (size_t)OBJ_TEXT_MAX + 1 ? (size_t)OBJ_TEXT_MAX + 1
									 : cap * 2;
			if (ncap == cap)
				break;
			char *q = realloc(buf, ncap);
			if (!q) {
				free(buf);
				buf = NULL;
				break;
			}
			buf = q;
			cap = ncap;
		}
		size_t n = fread(buf + len, 1, cap - len, f);
		len += n;
		if (n == 0)
			break;
	}
	if (!buf) {
		if (err && errlen)
			snprintf(err, errlen, "%s: out of memory", path);
	} else if (ferror(f)) {
		if (err && errlen)
			snprintf(err, errlen, "%s: read error: %s", path, strerror(errno));
	} else {
		rc = obj_read_string(buf, len, path, dest, err, errlen);
	}
	free(buf);
	fclose(f);
	return rc;
}

void
obj_mesh_free(struct obj_mesh *mesh)
{
	if (!mesh)
		return;
	free(mesh->vert);
	free(mesh->face);
	memset(mesh, 0, sizeof *mesh);
}
