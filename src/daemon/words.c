/* words.c - splitting request lines and reading numbers with units */
#include "daemon/words.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum words_status
words_split(const char *line, size_t len, struct words *dest, const char **msg)
{
	size_t i = 0, o = 0;
	dest->n = 0;
	dest->tag[0] = 0;
	*msg = "";
	while (i < len && (line[i] == ' ' || line[i] == '\t'))
		i++;
	if (i == len || line[i] == '%')
		return WORDS_EMPTY;
	if (line[i] == '#') { /* a tag for the reply */
		size_t t = 0;
		for (i++; i < len && line[i] != ' ' && line[i] != '\t'; i++) {
			if (t + 1 >= sizeof dest->tag) {
				*msg = "tag longer than 47 bytes";
				return WORDS_PARSE;
			}
			dest->tag[t++] = line[i];
		}
		dest->tag[t] = 0;
		if (!t) {
			*msg = "empty tag after '#'";
			return WORDS_PARSE;
		}
	}
	while (i < len) {
		while (i < len && (line[i] == ' ' || line[i] == '\t'))
			i++;
		if (i == len)
			break;
		if (dest->n == WORDS_MAX) {
			*msg = "more than 64 words";
			return WORDS_TOO_MANY;
		}
		dest->w[dest->n++] = &dest->buf[o];
		int quoted = 0;
		while (i < len && (quoted || (line[i] != ' ' && line[i] != '\t'))) {
			char c = line[i++];
			if (c == '"') {
				quoted = !quoted;
				continue;
			}
			if (quoted && c == '\\') {
				if (i == len || (line[i] != '"' && line[i] != '\\')) {
					*msg = "only \\\" and \\\\ may be escaped";
					return WORDS_PARSE;
				}
				c = line[i++];
			}
			dest->buf[o++] = c;
		}
		if (quoted) {
			*msg = "unbalanced quote";
			return WORDS_PARSE;
		}
		dest->buf[o++] = 0;
	}
	if (!dest->n)
		return WORDS_EMPTY;
	return WORDS_OK;
}

struct unit {
	const char *name;
	enum unit_kind kind;
	double scale;
};

static const struct unit units[] = {
	{ "m", UNIT_LENGTH, 1 },	 { "cm", UNIT_LENGTH, 0.01 },
	{ "mm", UNIT_LENGTH, 0.001 },	 { "deg", UNIT_ANGLE, M_PI / 180 },
	{ "rad", UNIT_ANGLE, 1 },
};

int
words_number(const char *s, enum unit_kind kind, double *dest)
{
	char *end;
	/* strtod also reads "nan", "inf" and hex: refuse them before it does */
	const char *p = s + (*s == '+' || *s == '-');
	if (!isdigit((unsigned char)*p) && *p != '.')
		return -1;
	if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X'))
		return -1;
	errno = 0;
	double v = strtod(s, &end);
	if (end == s || errno == ERANGE || !isfinite(v))
		return -1;
	if (!*end) {
		*dest = v;
		return 0;
	}
	for (size_t i = 0; i < sizeof units / sizeof *units; i++) {
		if (strcmp(end, units[i].name))
			continue;
		if (units[i].kind != kind)
			return -1;
		*dest = v * units[i].scale;
		return 0;
	}
	return -1;
}

int
words_list(const char *s, enum unit_kind kind, int n, double *dest)
{
	char item[128];
	if (!s)
		return -1;
	for (int k = 0; k < n; k++) {
		const char *comma = strchr(s, ',');
		size_t len = comma ? (size_t)(comma - s) : strlen(s);
		if (len == 0 || len >= sizeof item || (k < n - 1) != (comma != NULL))
			return -1;
		memcpy(item, s, len);
		item[len] = 0;
		if (words_number(item, kind, &dest[k]) < 0)
			return -1;
		s = comma ? comma + 1 : s + len;
	}
	return 0;
}

const char *
words_value(const char *word, size_t *klen)
{
	const char *eq = strchr(word, '=');
	if (!eq || eq == word)
		return NULL;
	*klen = (size_t)(eq - word);
	return eq + 1;
}

int
words_is_key(const char *word, const char *key)
{
	size_t n = strlen(key);
	return !strncmp(word, key, n) && word[n] == '=';
}

int
words_is_name(const char *s)
{
	if (!(isalpha((unsigned char)*s) || *s == '_'))
		return 0;
	size_t n = 0;
	for (; s[n]; n++)
		if (!(isalnum((unsigned char)s[n]) || s[n] == '_'))
			return 0;
	return n < 48;
}
