/* textfile.c - a whole file into memory (see textfile.h) */
#include "devices/textfile.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

char *
textfile_read(const char *path, size_t *n, char *err, size_t errlen)
{
	FILE *f = fopen(path, "rb");
	if (!f) {
		snprintf(err, errlen, "%s: %s", path, strerror(errno));
		return NULL;
	}
	char *buf = NULL;
	size_t len = 0, cap = 0;
	const char *why = NULL;
	for (;;) {
		if (len + 1 >= cap) { /* room for the terminating NUL too */
			if (cap >= TEXTFILE_MAX) {
				why = "file too large";
				break;
			}
			cap = cap ? 2 * cap : 65536;
			char *grown = realloc(buf, cap);
			if (!grown) {
				why = "out of memory";
				break;
			}
			buf = grown;
		}
		size_t k = fread(buf + len, 1, cap - 1 - len, f);
		len += k;
		if (k == 0)
			break;
	}
	if (!why && ferror(f))
		why = "read error";
	fclose(f);
	if (why) {
		snprintf(err, errlen, "%s: %s", path, why);
		free(buf);
		return NULL;
	}
	buf[len] = 0;
	*n = len;
	return buf;
}

int
textfile_fail(char *err, size_t errlen, const char *name, unsigned line, const char *fmt, ...)
{
	if (!err || !errlen)
		return -1;
	int k = name ? snprintf(err, errlen, "%s:%u: ", name, line) : 0;
	if (k < 0 || (size_t)k >= errlen)
		return -1;
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(err + k, errlen - (size_t)k, fmt, ap);
	va_end(ap);
	return -1;
}

int
textfile_hex_digit(char c)
{
	if (c >= '0' && c <= '9')
		return c - '0';
	if (c >= 'a' && c <= 'f')
		return c - 'a' + 10;
	if (c >= 'A' && c <= 'F')
		return c - 'A' + 10;
	return -1;
}

void
textfile_number_write(char *dest, size_t n, double v)
{
	for (int prec = 15; prec <= 17; prec++) {
		snprintf(dest, n, "%.*g", prec, v);
		if (strtod(dest, NULL) == v)
			return;
	}
}
