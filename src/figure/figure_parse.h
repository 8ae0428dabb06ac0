/*
 * figure_parse.h - shared parts of the figure reader (figure_read.c,
 * figure_segment.c, figure_parse.c): the parser state and the helpers that
 * read values, lists and transforms. Internal to the figure reader.
 *
 * Every helper returns 0, or -1 with "origin:line:col: message" already in
 * the caller's error buffer; the parser stops at the first -1.
 */
#ifndef POSTURE_FIGURE_PARSE_H
#define POSTURE_FIGURE_PARSE_H

#include <string.h>

#include "figure/figure_lex.h"
#include "figure/model.h"

/* statements allowed once per block */
enum {
	ONCE_MASS = 1 << 0,
	ONCE_COM = 1 << 1,
	ONCE_INERTIA = 1 << 2,
	ONCE_COLOR = 1 << 3,
	ONCE_PSURF = 1 << 4,
	ONCE_CONNECT = 1 << 5,
	ONCE_TYPE = 1 << 6,
	ONCE_LIMITS = 1 << 7,
	ONCE_DISPLACEMENT = 1 << 8,
	ONCE_ROOT = 1 << 9,
	ONCE_LOCATION = 1 << 10,
};

struct figure_pos {
	int line, col;
};

struct figure_site {
	char name[MODEL_NAME_MAX];
	double pos[3], quat[4];
	struct figure_pos at;
};

struct figure_geom {
	struct geom_def def;
	struct figure_pos at;
};

/* a number kept with its unit, for values whose kind depends on later statements */
struct figure_num {
	double v;
	enum figure_unit unit;
	struct figure_pos at;
};

/* the segment being read; it goes to the builder at its closing brace */
struct figure_seg {
	struct segment_def def;
	char name[MODEL_NAME_MAX];
	struct figure_pos at;
	struct figure_site *site;
	struct figure_geom *geom;
	int nsite, capsite, ngeom, capgeom;
};

struct figure_mesh_ref {
	char path[MODEL_PATH_MAX];
	int index;
};

struct figure_parser {
	struct figure_lex lx;
	struct model_builder *b;
	const char *base_dir;
	char name[MODEL_NAME_MAX];
	unsigned given; /* figure-level ONCE_ bits */
	struct figure_seg seg;
	struct figure_mesh_ref *mesh;
	int nmesh, capmesh;
	int *uf; /* union-find over segments, to name the joint closing a loop */
	int capuf;
	char root_seg[MODEL_NAME_MAX], root_site[MODEL_NAME_MAX];
	struct figure_pos root_seg_at, root_site_at;
	double loc_pos[3], loc_quat[4];
};

/* a position in the text, for messages about things checked after they were read */
static inline struct figure_pos
figure_parse_here(const struct figure_parser *p)
{
	return (struct figure_pos){ p->lx.tok.line, p->lx.tok.col };
}

/* reads the next token */
static inline int
figure_parse_next(struct figure_parser *p)
{
	return figure_lex_next(&p->lx);
}

/* 1 when the current token is the name `word` */
static inline int
figure_parse_is_word(const struct figure_parser *p, const char *word)
{
	return p->lx.tok.kind == FTOK_IDENT && !strcmp(p->lx.tok.text, word);
}

extern const enum figure_unit figure_parse_len3[3]; /* three lengths */

/* formats a message at a position; returns -1 */
int figure_parse_error_at(struct figure_parser *p, struct figure_pos at, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* "expected WHAT, found TOKEN" at the current token; returns -1 */
int figure_parse_expected(struct figure_parser *p, const char *what);

/* skips a token of the given kind, or fails with "expected WHAT" */
int figure_parse_expect(struct figure_parser *p, enum figure_tok kind, const char *what);

/* skips the name `word`, or fails with "expected WHAT" */
int figure_parse_expect_word(struct figure_parser *p, const char *word, const char *what);

/* a name into dest, with its position in *at */
int figure_parse_name(struct figure_parser *p, const char *what, char dest[MODEL_NAME_MAX],
		      struct figure_pos *at);

/* the keyword opening a statement of `block`: fails when given twice, then skips it */
int figure_parse_keyword(struct figure_parser *p, unsigned *given, const char *block);

/* a number of the given kind (a bare number is in base units); ctx ends the message */
int figure_parse_number(struct figure_parser *p, enum figure_unit kind, const char *ctx,
			double *dest);

/* a number of any kind, kept with its unit and position for a later check */
int figure_parse_raw_number(struct figure_parser *p, const char *what, struct figure_num *dest);

/* "(" v "," v ... ")" with n values of the given kinds */
int figure_parse_list(struct figure_parser *p, const enum figure_unit *kinds, int n,
		      const char *ctx, double *dest);

/* [+|-] x|y|z: axis 0..2 and sign +1/-1 */
int figure_parse_axis(struct figure_parser *p, int *axis, int *sign);

/* transform = factor { factor }, composed into a position and a quaternion */
int figure_parse_transform(struct figure_parser *p, const char *ctx, double pos[3], double quat[4]);

/* "segment" NAME "{" ... "}": reads the block and adds it to the builder */
int figure_segment_parse(struct figure_parser *p);

#endif
