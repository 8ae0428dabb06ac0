/*
 * jbuf.h - JSON text written into a buffer made once: the frame loop's
 * events are built without allocating (jansson allocates per value).
 */
#ifndef POSTURE_JBUF_H
#define POSTURE_JBUF_H

#include <stddef.h>

struct jbuf {
	char *buf;
	size_t len, cap;
	int overflow; /* set when something did not fit; the text is then invalid */
};

/* 0, or -1 when out of memory */
int jbuf_init(struct jbuf *j, size_t cap);
void jbuf_free(struct jbuf *j);
void jbuf_reset(struct jbuf *j);

/* raw text, e.g. "{", ",\"key\":" */
void jbuf_raw(struct jbuf *j, const char *s);
/* a JSON string with the escapes JSON needs */
void jbuf_str(struct jbuf *j, const char *s);
/* a number with 17 significant digits (finite numbers only; others become null) */
void jbuf_num(struct jbuf *j, double v);
void jbuf_int(struct jbuf *j, long long v);
void jbuf_bool(struct jbuf *j, int v);
/* [v0,v1,...] */
void jbuf_vec(struct jbuf *j, const double *v, int n);
/* bytes as a base64 JSON string */
void jbuf_base64(struct jbuf *j, const unsigned char *p, size_t n);
/* ,"key": before a value (first = 1 omits the comma) */
void jbuf_key(struct jbuf *j, const char *key, int first);

#endif
