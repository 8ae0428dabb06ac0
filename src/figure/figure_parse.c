/* figure_parse.c - values, lists and transforms of the figure language (see figure_read.c) */
#include "figure/figure_parse.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* the current token of parser p */
#define TOK (p->lx.tok)

static const double parse_qid[4] = { 0, 0, 0, 1 };

static const struct {
	const char *word;
	unsigned bit;
} parse_once[] = {
	{ "mass", ONCE_MASS },
	{ "com", ONCE_COM },
	{ "inertia", ONCE_INERTIA },
	{ "color", ONCE_COLOR },
	{ "psurf", ONCE_PSURF },
	{ "connect", ONCE_CONNECT },
	{ "type", ONCE_TYPE },
	{ "limits", ONCE_LIMITS },
	{ "displacement", ONCE_DISPLACEMENT },
	{ "root", ONCE_ROOT },
	{ "location", ONCE_LOCATION },
};

int
figure_parse_error_at(struct figure_parser *p, struct figure_pos at, const char *fmt, ...)
{
	char msg[1024];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	return figure_lex_error(&p->lx, at.line, at.col, "%s", msg);
}

/* "expected WHAT, found TOKEN" at the current token */
int
figure_parse_expected(struct figure_parser *p, const char *what)
{
	char found[80];
	return figure_parse_error_at(p, figure_parse_here(p), "expected %s, found %s", what,
				     figure_lex_describe(&TOK, found, sizeof found));
}

int
figure_parse_expect(struct figure_parser *p, enum figure_tok kind, const char *what)
{
	if (TOK.kind != kind)
		return figure_parse_expected(p, what);
	return figure_parse_next(p);
}

int
figure_parse_expect_word(struct figure_parser *p, const char *word, const char *what)
{
	if (!figure_parse_is_word(p, word))
		return figure_parse_expected(p, what);
	return figure_parse_next(p);
}

int
figure_parse_name(struct figure_parser *p, const char *what, char dest[MODEL_NAME_MAX],
		  struct figure_pos *at)
{
	if (TOK.kind != FTOK_IDENT)
		return figure_parse_expected(p, what);
	*at = figure_parse_here(p);
	memcpy(dest, TOK.text, MODEL_NAME_MAX);
	return figure_parse_next(p);
}

/* the keyword starting a statement; checks "at most once" and skips it */
int
figure_parse_keyword(struct figure_parser *p, unsigned *given, const char *block)
{
	for (size_t i = 0; i < sizeof parse_once / sizeof parse_once[0]; i++) {
		if (strcmp(TOK.text, parse_once[i].word))
			continue;
		if (*given & parse_once[i].bit)
			return figure_parse_error_at(p, figure_parse_here(p),
						     "'%s' is given twice in %s", TOK.text, block);
		*given |= parse_once[i].bit;
	}
	return figure_parse_next(p);
}

/* a number of the given kind; a bare number is in base units */
int
figure_parse_number(struct figure_parser *p, enum figure_unit kind, const char *ctx, double *dest)
{
	char what[160];
	snprintf(what, sizeof what, "%s %s", figure_lex_unit_noun(kind), ctx);
	if (TOK.kind != FTOK_NUMBER)
		return figure_parse_expected(p, what);
	if (TOK.unit != FUNIT_NONE && TOK.unit != kind)
		return figure_parse_error_at(
			p, figure_parse_here(p), "expected %s, found %s '%.*s'", what,
			figure_lex_unit_noun(TOK.unit), (int)TOK.len, TOK.start);
	*dest = TOK.value;
	return figure_parse_next(p);
}

/* a number whose kind is checked later */
int
figure_parse_raw_number(struct figure_parser *p, const char *what, struct figure_num *dest)
{
	if (TOK.kind != FTOK_NUMBER)
		return figure_parse_expected(p, what);
	dest->v = TOK.value;
	dest->unit = TOK.unit;
	dest->at = figure_parse_here(p);
	return figure_parse_next(p);
}

/* "(" v "," v ... ")" with n values of the given kinds */
int
figure_parse_list(struct figure_parser *p, const enum figure_unit *kinds, int n, const char *ctx,
		  double *dest)
{
	char what[160];
	snprintf(what, sizeof what, "'(' to start %s", ctx);
	if (figure_parse_expect(p, FTOK_LPAREN, what) < 0)
		return -1;
	for (int i = 0; i < n; i++) {
		snprintf(what, sizeof what, "',' (%s takes %d values)", ctx, n);
		if (i > 0 && figure_parse_expect(p, FTOK_COMMA, what) < 0)
			return -1;
		snprintf(what, sizeof what, "in %s", ctx);
		if (figure_parse_number(p, kinds[i], what, &dest[i]) < 0)
			return -1;
	}
	snprintf(what, sizeof what, "')' after the %d values of %s", n, ctx);
	return figure_parse_expect(p, FTOK_RPAREN, what);
}

const enum figure_unit figure_parse_len3[3] = { FUNIT_LENGTH, FUNIT_LENGTH, FUNIT_LENGTH };

/* [+|-] x|y|z */
int
figure_parse_axis(struct figure_parser *p, int *axis, int *sign)
{
	*sign = 1;
	if (TOK.kind == FTOK_MINUS || TOK.kind == FTOK_PLUS) {
		*sign = TOK.kind == FTOK_MINUS ? -1 : 1;
		if (figure_parse_next(p) < 0)
			return -1;
	}
	const char *t = TOK.text;
	if (TOK.kind != FTOK_IDENT || t[1] || t[0] < 'x' || t[0] > 'z')
		return figure_parse_expected(p, "an axis x, y, z, -x, -y or -z");
	*axis = t[0] - 'x';
	return figure_parse_next(p);
}

/*
 * A transform being composed. The first factor is taken as written and an
 * identity rotation is never multiplied, so trans(p) quat(q) keeps p and q
 * bit for bit (what figure_write relies on).
 */
struct parse_xf {
	double p[3], q[4];
	int any;
};

static void
xf_translate(struct parse_xf *x, const double t[3])
{
	if (!x->any) {
		memcpy(x->p, t, sizeof x->p);
		memcpy(x->q, parse_qid, sizeof x->q);
		x->any = 1;
		return;
	}
	double v[3], r[9];
	if (!memcmp(x->q, parse_qid, sizeof x->q)) {
		memcpy(v, t, sizeof v);
	} else {
		mathx_quat_to_mat(x->q, r);
		for (int i = 0; i < 3; i++)
			v[i] = r[3 * i] * t[0] + r[3 * i + 1] * t[1] + r[3 * i + 2] * t[2];
	}
	for (int i = 0; i < 3; i++)
		x->p[i] += v[i];
}

static void
xf_rotate(struct parse_xf *x, const double q[4])
{
	if (!x->any) {
		memset(x->p, 0, sizeof x->p);
		x->any = 1;
		memcpy(x->q, q, sizeof x->q);
	} else if (!memcmp(x->q, parse_qid, sizeof x->q)) {
		memcpy(x->q, q, sizeof x->q);
	} else {
		mathx_quat_mul(x->q, q, x->q);
	}
}

/* rot(axis, angle) or rot(ux, uy, uz, angle), after "rot" */
static int
parse_rot(struct figure_parser *p, struct figure_pos at, double dest[4])
{
	double u[3] = { 0, 0, 0 }, angle;
	if (figure_parse_expect(p, FTOK_LPAREN, "'(' after 'rot'") < 0)
		return -1;
	if (TOK.kind == FTOK_NUMBER) {
		for (int i = 0; i < 3; i++) {
			if (i > 0 &&
			    figure_parse_expect(p, FTOK_COMMA,
						"',' between the axis components of rot()") < 0)
				return -1;
			if (figure_parse_number(p, FUNIT_NONE, "for an axis component in rot()",
						&u[i]) < 0)
				return -1;
		}
		double n = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
		if (!(n > 0) || !isfinite(n))
			return figure_parse_error_at(
				p, at, "rot() needs a non-zero axis of finite length");
		for (int i = 0; i < 3; i++)
			u[i] /= n;
	} else {
		int axis, sign;
		if (figure_parse_axis(p, &axis, &sign) < 0)
			return -1;
		u[axis] = sign;
	}
	if (figure_parse_expect(p, FTOK_COMMA, "',' before the angle of rot()") < 0 ||
	    figure_parse_number(p, FUNIT_ANGLE, "as the angle of rot()", &angle) < 0 ||
	    figure_parse_expect(p, FTOK_RPAREN, "')' after the angle of rot()") < 0)
		return -1;
	mathx_quat_axis_angle(u, angle, dest);
	for (int i = 0; i < 3; i++)
		if (u[i] == 0)
			dest[i] = 0; /* +0, not the -0 of 0 * -sin */
	return 0;
}

/* transform = factor { factor } */
int
figure_parse_transform(struct figure_parser *p, const char *ctx, double pos[3], double quat[4])
{
	static const enum figure_unit num4[4] = { FUNIT_NONE, FUNIT_NONE, FUNIT_NONE, FUNIT_NONE };
	struct parse_xf x = { .any = 0 };
	for (;;) {
		struct figure_pos at = figure_parse_here(p);
		double v[4];
		if (figure_parse_is_word(p, "trans")) {
			if (figure_parse_next(p) < 0 ||
			    figure_parse_list(p, figure_parse_len3, 3, "trans()", v) < 0)
				return -1;
			xf_translate(&x, v);
		} else if (figure_parse_is_word(p, "rot")) {
			if (figure_parse_next(p) < 0 || parse_rot(p, at, v) < 0)
				return -1;
			xf_rotate(&x, v);
		} else if (figure_parse_is_word(p, "quat")) {
			if (figure_parse_next(p) < 0 ||
			    figure_parse_list(p, num4, 4, "quat()", v) < 0)
				return -1;
			double n2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3];
			if (!(fabs(n2 - 1) <= 1e-12))
				return figure_parse_error_at(
					p, at,
					"quat() is not of unit length (|q|^2 = %.17g); give "
					"17 significant digits or use rot()",
					n2);
			xf_rotate(&x, v);
		} else {
			break;
		}
	}
	if (!x.any) {
		char what[160];
		snprintf(what, sizeof what, "a transform (trans, rot or quat) for %s", ctx);
		return figure_parse_expected(p, what);
	}
	memcpy(pos, x.p, sizeof x.p);
	memcpy(quat, x.q, sizeof x.q);
	return 0;
}