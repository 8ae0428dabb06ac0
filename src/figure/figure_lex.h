/*
 * figure_lex.h - the tokens of the peabody figure language, for
 * figure_read.c (the grammar is documented there).
 *
 * The lexer works on a byte buffer that need not end in NUL. Before the
 * first token it checks the whole text once: size, line lengths and binary
 * bytes. Numbers carry their unit: the value is already converted to base
 * units (m, rad, kg) and `unit` says which kind of unit was written, so the
 * parser can reject a length where an angle belongs.
 */
#ifndef POSTURE_FIGURE_LEX_H
#define POSTURE_FIGURE_LEX_H

#include <stddef.h>

#include "figure/model.h"

#define FIGURE_TEXT_MAX (16u << 20) /* bytes of a figure file */
#define FIGURE_LINE_MAX 4096	    /* bytes of a line, without its end */

enum figure_tok {
	FTOK_EOF,
	FTOK_IDENT,
	FTOK_NUMBER,
	FTOK_STRING,
	FTOK_LBRACE,
	FTOK_RBRACE,
	FTOK_LPAREN,
	FTOK_RPAREN,
	FTOK_SEMI,
	FTOK_COMMA,
	FTOK_EQUALS,
	FTOK_DOT,
	FTOK_ARROW,
	FTOK_MINUS,
	FTOK_PLUS,
};

enum figure_unit {
	FUNIT_NONE, /* a bare number */
	FUNIT_LENGTH,
	FUNIT_ANGLE,
	FUNIT_MASS,
};

struct figure_token {
	enum figure_tok kind;
	int line, col;		   /* 1-based; columns count bytes */
	const char *start;	   /* the token's text in the buffer */
	size_t len;		   /* its length in bytes */
	double value;		   /* FTOK_NUMBER: in base units */
	enum figure_unit unit;	   /* FTOK_NUMBER: the kind of unit written */
	char text[MODEL_PATH_MAX]; /* FTOK_IDENT: the name; FTOK_STRING: the contents */
};

struct figure_lex {
	const char *text;
	size_t len, pos;
	int line, col; /* of text[pos] */
	const char *origin;
	char *err;
	size_t errlen;
	struct figure_token tok; /* the current token */
};

/*
 * Checks the text (size, binary bytes, line lengths) and reads the first
 * token. Returns 0, or -1 with "origin:line:col: message" in err.
 */
int figure_lex_init(struct figure_lex *lx, const char *text, size_t len, const char *origin,
		    char *err, size_t errlen);

/* reads the next token into lx->tok; returns 0, or -1 with the message in err */
int figure_lex_next(struct figure_lex *lx);

/* formats "origin:line:col: message" into the error buffer; returns -1 */
int figure_lex_error(struct figure_lex *lx, int line, int col, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));

/* describes a token for messages ("'joint'", "end of file"); returns dest */
const char *figure_lex_describe(const struct figure_token *t, char *dest, size_t len);

/* "a length", "an angle", "a mass" or "a plain number" */
const char *figure_lex_unit_noun(enum figure_unit u);

#endif
