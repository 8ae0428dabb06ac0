/* jbuf.c - JSON into a fixed buffer */
#include "daemon/jbuf.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int
jbuf_init(struct jbuf *j, size_t cap)
{
	j->buf = malloc(cap);
	j->cap = j->buf ? cap : 0;
	j->len = 0;
	j->overflow = 0;
	return j->buf ? 0 : -1;
}

void
jbuf_free(struct jbuf *j)
{
	free(j->buf);
	j->buf = NULL;
	j->cap = j->len = 0;
}

void
jbuf_reset(struct jbuf *j)
{
	j->len = 0;
	j->overflow = 0;
}

static void
put(struct jbuf *j, const char *s, size_t n)
{
	if (j->len + n + 1 > j->cap) {
		j->overflow = 1;
		return;
	}
	memcpy(j->buf + j->len, s, n);
	j->len += n;
	j->buf[j->len] = 0;
}

void
jbuf_raw(struct jbuf *j, const char *s)
{
	put(j, s, strlen(s));
}

void
jbuf_str(struct jbuf *j, const char *s)
{
	put(j, "\"", 1);
	for (; *s; s++) {
		unsigned char c = (unsigned char)*s;
		char esc[8];
		if (c == '"' || c == '\\') {
			esc[0] = '\\';
			esc[1] = (char)c;
			put(j, esc, 2);
		} else if (c < 0x20) {
			snprintf(esc, sizeof esc, "\\u%04x", c);
			put(j, esc, 6);
		} else {
			put(j, (const char *)&c, 1);
		}
	}
	put(j, "\"", 1);
}

void
jbuf_num(struct jbuf *j, double v)
{
	char b[32];
	if (!isfinite(v)) {
		put(j, "null", 4);
		return;
	}
	int n = snprintf(b, sizeof b, "%.17g", v);
	/* JSON numbers: "1" is fine, but keep reals recognisable as jansson writes them */
	if (!strpbrk(b, ".eE"))
		n += snprintf(b + n, sizeof b - (size_t)n, ".0");
	put(j, b, (size_t)n);
}

void
jbuf_int(struct jbuf *j, long long v)
{
	char b[32];
	int n = snprintf(b, sizeof b, "%lld", v);
	put(j, b, (size_t)n);
}

void
jbuf_bool(struct jbuf *j, int v)
{
	jbuf_raw(j, v ? "true" : "false");
}

void
jbuf_vec(struct jbuf *j, const double *v, int n)
{
	put(j, "[", 1);
	for (int i = 0; i < n; i++) {
		if (i)
			put(j, ",", 1);
		jbuf_num(j, v[i]);
	}
	put(j, "]", 1);
}

void
jbuf_key(struct jbuf *j, const char *key, int first)
{
	if (!first)
		put(j, ",", 1);
	jbuf_str(j, key);
	put(j, ":", 1);
}

void
jbuf_base64(struct jbuf *j, const unsigned char *p, size_t n)
{
	static const char a[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
	if (j->len + 4 * ((n + 2) / 3) + 3 > j->cap) {
		j->overflow = 1;
		return;
	}
	char *o = j->buf + j->len;
	*o++ = '"';
	for (size_t i = 0; i < n; i += 3) {
		unsigned v = (unsigned)p[i] << 16 | (i + 1 < n ? (unsigned)p[i + 1] << 8 : 0) |
			     (i + 2 < n ? p[i + 2] : 0);
		*o++ = a[v >> 18 & 63];
		*o++ = a[v >> 12 & 63];
		*o++ = i + 1 < n ? a[v >> 6 & 63] : '=';
		*o++ = i + 2 < n ? a[v & 63] : '=';
	}
	*o++ = '"';
	*o = 0;
	j->len = (size_t)(o - j->buf);
}
