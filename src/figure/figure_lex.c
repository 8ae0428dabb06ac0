/* figure_lex.c - tokens of the peabody figure language (the grammar is in figure_read.c) */
#include "figure/figure_lex.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* value in base units = written value / div * mul; 1 leaves a value exact */
/* clang-format off */
static const struct {
	const char *name;
	enum figure_unit unit;
	double div, mul;
} figure_units[] = {
	{ "m",   FUNIT_LENGTH,    1, 1 },
	{ "cm",  FUNIT_LENGTH,  100, 1 },
	{ "mm",  FUNIT_LENGTH, 1000, 1 },
	{ "in",  FUNIT_LENGTH,    1, 0.0254 }, /* exactly 25.4 mm */
	{ "deg", FUNIT_ANGLE,   180, M_PI },   /* so 90deg is M_PI / 2 to the bit */
	{ "rad", FUNIT_ANGLE,     1, 1 },
	{ "kg",  FUNIT_MASS,      1, 1 },
	{ "g",   FUNIT_MASS,   1000, 1 },
};
/* clang-format on */

int
figure_lex_error(struct figure_lex *lx, int line, int col, const char *fmt, ...)
{
	char msg[1024];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	if (lx->err && lx->errlen)
		snprintf(lx->err, lx->errlen, "%s:%d:%d: %s", lx->origin, line, col, msg);
	return -1;
}

const char *
figure_lex_describe(const struct figure_token *t, char *dest, size_t len)
{
	int n = t->len > 40 ? 40 : (int)t->len;
	switch (t->kind) {
	case FTOK_EOF:
		snprintf(dest, len, "end of file");
		break;
	case FTOK_STRING:
		snprintf(dest, len, "string \"%.40s\"", t->text);
		break;
	case FTOK_IDENT:
	case FTOK_NUMBER:
	case FTOK_LBRACE:
	case FTOK_RBRACE:
	case FTOK_LPAREN:
	case FTOK_RPAREN:
	case FTOK_SEMI:
	case FTOK_COMMA:
	case FTOK_EQUALS:
	case FTOK_DOT:
	case FTOK_ARROW:
	case FTOK_MINUS:
	case FTOK_PLUS:
		snprintf(dest, len, "'%.*s%s'", n, t->start, t->len > 40 ? "..." : "");
		break;
	}
	return dest;
}

const char *
figure_lex_unit_noun(enum figure_unit u)
{
	switch (u) {
	case FUNIT_NONE:
		return "a plain number";
	case FUNIT_LENGTH:
		return "a length";
	case FUNIT_ANGLE:
		return "an angle";
	case FUNIT_MASS:
		return "a mass";
	}
	return "a number";
}

/* the byte at index i, or 0 past the end (the text need not end in NUL) */
static unsigned char
lex_at(const struct figure_lex *lx, size_t i)
{
	return i < lx->len ? (unsigned char)lx->text[i] : 0;
}

static int
lex_is_digit(unsigned char c)
{
	return c >= '0' && c <= '9';
}

static int
lex_is_alpha(unsigned char c)
{
	return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}

static void
lex_advance(struct figure_lex *lx, size_t n)
{
	for (; n > 0 && lx->pos < lx->len; n--) {
		if (lx->text[lx->pos++] == '\n') {
			lx->line++;
			lx->col = 1;
		} else {
			lx->col++;
		}
	}
}

/* one pass over the whole text: size, binary bytes, line lengths */
static int
lex_check_text(struct figure_lex *lx)
{
	if (lx->len > FIGURE_TEXT_MAX)
		return figure_lex_error(lx, 1, 1, "the text is larger than %u MiB",
					FIGURE_TEXT_MAX >> 20);
	int line = 1;
	size_t col = 0;
	for (size_t i = 0; i < lx->len; i++) {
		unsigned char c = (unsigned char)lx->text[i];
		if (c == '\n') {
			line++;
			col = 0;
			continue;
		}
		col++;
		if ((c < 0x20 && c != '\t' && c != '\r' && c != '\f' && c != '\v') || c == 0x7f)
			return figure_lex_error(lx, line, (int)col,
						"binary data (byte 0x%02x) in a text file", c);
		int line_end = c == '\r' && (i + 1 == lx->len || lx->text[i + 1] == '\n');
		if (col > FIGURE_LINE_MAX && !line_end)
			return figure_lex_error(lx, line, (int)col, "line is longer than %d bytes",
						FIGURE_LINE_MAX);
	}
	return 0;
}

/* white space and the three kinds of comment */
static int
lex_skip(struct figure_lex *lx)
{
	for (;;) {
		unsigned char c = lex_at(lx, lx->pos), c1 = lex_at(lx, lx->pos + 1);
		if (lx->pos >= lx->len)
			return 0;
		if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') {
			lex_advance(lx, 1);
		} else if (c == '#' || (c == '/' && c1 == '/')) {
			while (lx->pos < lx->len && lx->text[lx->pos] != '\n')
				lex_advance(lx, 1);
		} else if (c == '/' && c1 == '*') {
			int line = lx->line, col = lx->col;
			lex_advance(lx, 2);
			for (;;) {
				if (lx->pos >= lx->len)
					return figure_lex_error(
						lx, line, col,
						"unterminated comment: '/*' without '*/'");
				if (lex_at(lx, lx->pos) == '*' && lex_at(lx, lx->pos + 1) == '/') {
					lex_advance(lx, 2);
					break;
				}
				lex_advance(lx, 1);
			}
		} else {
			return 0;
		}
	}
}

static int
lex_ident(struct figure_lex *lx, struct figure_token *t)
{
	size_t i = lx->pos;
	while (lex_is_alpha(lex_at(lx, i)) || lex_is_digit(lex_at(lx, i)))
		i++;
	size_t n = i - lx->pos;
	if (n >= MODEL_NAME_MAX)
		return figure_lex_error(lx, t->line, t->col,
					"name '%.20s...' is longer than %d bytes", t->start,
					MODEL_NAME_MAX - 1);
	t->kind = FTOK_IDENT;
	t->len = n;
	memcpy(t->text, t->start, n);
	t->text[n] = 0;
	lex_advance(lx, n);
	return 0;
}

/* C-style decimal number, then an optional unit written right after it */
static int
lex_number(struct figure_lex *lx, struct figure_token *t)
{
	size_t i = lx->pos;
	if (lex_at(lx, i) == '-' || lex_at(lx, i) == '+')
		i++;
	while (lex_is_digit(lex_at(lx, i)))
		i++;
	if (lex_at(lx, i) == '.')
		for (i++; lex_is_digit(lex_at(lx, i));)
			i++;
	unsigned char e = lex_at(lx, i), s = lex_at(lx, i + 1);
	if ((e == 'e' || e == 'E') &&
	    (lex_is_digit(s) || ((s == '-' || s == '+') && lex_is_digit(lex_at(lx, i + 2))))) {
		i += lex_is_digit(s) ? 1 : 2;
		while (lex_is_digit(lex_at(lx, i)))
			i++;
	}
	size_t nnum = i - lx->pos, u0 = i;
	while (lex_is_alpha(lex_at(lx, i)) || lex_is_digit(lex_at(lx, i)))
		i++;
	size_t nunit = i - u0;
	t->len = i - lx->pos;

	/* the line check bounds a number by FIGURE_LINE_MAX bytes */
	char num[FIGURE_LINE_MAX + 1];
	memcpy(num, t->start, nnum);
	num[nnum] = 0;
	double v = strtod(num, NULL);
	if (!isfinite(v))
		return figure_lex_error(lx, t->line, t->col, "number '%.40s' is out of range", num);
	t->unit = FUNIT_NONE;
	if (nunit > 0) {
		size_t k, nk = sizeof figure_units / sizeof figure_units[0];
		for (k = 0; k < nk; k++)
			if (strlen(figure_units[k].name) == nunit &&
			    !memcmp(figure_units[k].name, lx->text + u0, nunit))
				break;
		if (k == nk)
			return figure_lex_error(
				lx, t->line, t->col + (int)nnum,
				"unknown unit '%.*s' (use m, cm, mm, in, deg, rad, kg or g)",
				nunit > 20 ? 20 : (int)nunit, lx->text + u0);
		v = v / figure_units[k].div * figure_units[k].mul;
		t->unit = figure_units[k].unit;
		if (!isfinite(v))
			return figure_lex_error(lx, t->line, t->col,
						"number '%.*s' is out of range",
						(int)(t->len > 40 ? 40 : t->len), t->start);
	}
	t->kind = FTOK_NUMBER;
	t->value = v;
	lex_advance(lx, t->len);
	return 0;
}

/* "..." on one line, without escapes */
static int
lex_string(struct figure_lex *lx, struct figure_token *t)
{
	size_t i = lx->pos + 1;
	while (i < lx->len && lx->text[i] != '"' && lx->text[i] != '\n')
		i++;
	if (i >= lx->len || lx->text[i] != '"')
		return figure_lex_error(
			lx, t->line, t->col,
			"unterminated string: '\"' without a closing '\"' on the same line");
	size_t n = i - lx->pos - 1;
	if (n >= MODEL_PATH_MAX)
		return figure_lex_error(lx, t->line, t->col, "string is longer than %d bytes",
					MODEL_PATH_MAX - 1);
	t->kind = FTOK_STRING;
	t->len = n + 2;
	memcpy(t->text, t->start + 1, n);
	t->text[n] = 0;
	lex_advance(lx, t->len);
	return 0;
}

int
figure_lex_next(struct figure_lex *lx)
{
	if (lex_skip(lx) < 0)
		return -1;
	struct figure_token *t = &lx->tok;
	t->line = lx->line;
	t->col = lx->col;
	t->start = lx->text + lx->pos;
	t->len = 1;
	t->value = 0;
	t->unit = FUNIT_NONE;
	t->text[0] = 0;
	if (lx->pos >= lx->len) {
		t->kind = FTOK_EOF;
		t->len = 0;
		return 0;
	}
	unsigned char c = lex_at(lx, lx->pos), c1 = lex_at(lx, lx->pos + 1);
	unsigned char c2 = lex_at(lx, lx->pos + 2);
	if (lex_is_alpha(c))
		return lex_ident(lx, t);
	if (lex_is_digit(c) || (c == '.' && lex_is_digit(c1)) ||
	    ((c == '-' || c == '+') && (lex_is_digit(c1) || (c1 == '.' && lex_is_digit(c2)))))
		return lex_number(lx, t);
	if (c == '"')
		return lex_string(lx, t);
	if (c == '-' && c1 == '>') {
		t->kind = FTOK_ARROW;
		t->len = 2;
		lex_advance(lx, 2);
		return 0;
	}
	static const char punct[] = "{}();,=.-+";
	static const enum figure_tok kinds[] = { FTOK_LBRACE, FTOK_RBRACE, FTOK_LPAREN, FTOK_RPAREN,
						 FTOK_SEMI,   FTOK_COMMA,  FTOK_EQUALS, FTOK_DOT,
						 FTOK_MINUS,  FTOK_PLUS };
	const char *p = c ? strchr(punct, c) : NULL;
	if (!p) {
		if (c > 0x20 && c < 0x7f)
			return figure_lex_error(lx, t->line, t->col, "unexpected character '%c'",
						c);
		return figure_lex_error(lx, t->line, t->col,
					"unexpected byte 0x%02x outside a string or comment", c);
	}
	t->kind = kinds[p - punct];
	lex_advance(lx, 1);
	return 0;
}

int
figure_lex_init(struct figure_lex *lx, const char *text, size_t len, const char *origin, char *err,
		size_t errlen)
{
	memset(lx, 0, sizeof *lx);
	lx->text = text;
	lx->len = text ? len : 0;
	lx->line = 1;
	lx->col = 1;
	lx->origin = origin ? origin : "<figure>";
	lx->err = err;
	lx->errlen = errlen;
	if (lex_check_text(lx) < 0)
		return -1;
	return figure_lex_next(lx);
}
