/*
 * figure_read.c - the peabody figure language (Phillips 1991, Appendix A,
 * Figure A.1) read into a struct model through the model builder.
 *
 * GRAMMAR (EBNF; tokens are separated by white space and comments)
 *
 *   file       = figure EOF                      exactly one figure
 *   figure     = "figure" NAME "{" { fig_stmt } "}"
 *   fig_stmt   = segment | joint
 *              | "root" "=" NAME "." NAME ";"    SEGMENT.SITE, required
 *              | "location" "=" transform ";"    global frame of the root site
 *   segment    = "segment" NAME "{" { seg_stmt } "}"
 *   seg_stmt   = "mass" "=" number ";"           mass; default 0
 *              | "com" "=" "(" len "," len "," len ")" ";"
 *              | "inertia" "=" "(" num "," num "," num "," num "," num "," num ")" ";"
 *                                                ixx iyy izz ixy ixz iyz, kg m^2 about the com
 *              | "color" "=" "(" num "," num "," num [ "," num ] ")" ";"   rgb[a] in [0, 1]
 *              | "psurf" "=" STRING ";"          OBJ mesh at identity, scale 1
 *              | "geometry" "=" shape [ "at" transform ] ";"   any number of these
 *              | "site" NAME "->" "location" "=" transform ";"
 *   shape      = "box" "(" len "," len "," len ")"           full extents
 *              | "cylinder" "(" len "," len ")"               radius, length along y
 *              | "capsule" "(" len "," len ")"                radius, straight length
 *              | "ellipsoid" "(" len "," len "," len ")"     semi-axes
 *              | "mesh" "(" STRING [ "," num "," num "," num ] ")"   path, scale
 *   joint      = "joint" NAME "{" { jnt_stmt } "}"
 *   jnt_stmt   = "connect" NAME "." NAME "to" NAME "." NAME ";"   required
 *              | "type" "=" dof { "," dof } ";"   none: a rigid joint
 *              | "limits" "=" pair { "," pair } ";"   one pair per dof
 *              | "displacement" "=" "(" number { "," number } ")" ";"   one per dof
 *   dof        = ( "R" | "T" ) "(" axis ")"       rotation about / translation along
 *   axis       = [ "+" | "-" ] ( "x" | "y" | "z" )
 *   pair       = "(" number "," number ")"        lo, hi with lo <= hi
 *   transform  = factor { factor }                applied left to right, each in the
 *                                                 frame made by the ones before it
 *   factor     = "trans" "(" len "," len "," len ")"
 *              | "rot" "(" axis "," angle ")"
 *              | "rot" "(" num "," num "," num "," angle ")"   axis need not be unit
 *              | "quat" "(" num "," num "," num "," num ")"   x y z w, |q|^2 within 1e-12 of 1
 *
 * Tokens. NAME = [A-Za-z_][A-Za-z0-9_]*, at most MODEL_NAME_MAX - 1 bytes;
 * keywords are only keywords where the grammar expects them. STRING = "..."
 * on one line, no escapes. A number is C-style decimal with an optional
 * exponent, followed directly by an optional unit: m cm mm in (lengths), deg
 * rad (angles), kg g (masses). A bare number is in base units (m, rad, kg);
 * `len`, `angle` accept a bare number or the matching unit, `num` only a
 * bare number. Comments: '#' or '//' to the end of the line, and block
 * comments between slash-star and star-slash.
 *
 * Semantics. Statements inside a block may come in any order; mass, com,
 * inertia, color, psurf, connect, type, limits, displacement, root and
 * location at most once each. A connect may only name segments (and their
 * sites) defined earlier in the file; the root is looked up at the end.
 * Limits default to (-180deg, 180deg) for R and (-1m, 1m) for T;
 * displacements default to 0, and a displacement outside the limits is an
 * error. The joints must make the segments a single tree. Mesh paths are
 * kept as written and read relative to the figure file's directory; the same
 * path used twice shares one mesh.
 *
 * Errors are all-or-nothing: the first one stops the reading, nothing is
 * returned, and the message reads "ORIGIN:LINE:COL: expected X, found Y" or
 * names what is wrong. The text may not exceed 16 MiB, a line 4096 bytes,
 * and it may hold no control bytes other than tab, CR, LF, FF and VT.
 */
#include "figure/figure.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/figure_lex.h"
#include "figure/figure_parse.h"

/* the current token of parser p */
#define TOK (p->lx.tok)

/* a joint block, handed to the builder at its closing brace */
struct read_joint {
	struct joint_def def;
	char name[MODEL_NAME_MAX];
	char seg_name[2][MODEL_NAME_MAX]; /* segments of site_from and site_to */
	int seg[2];
	struct figure_pos at, limits_at, disp_at;
	struct figure_num lim[2 * MODEL_JOINT_DOF_MAX];
	struct figure_num disp[MODEL_JOINT_DOF_MAX];
	int nlim, ndisp; /* numbers read */
};

/* looks up SEGMENT.SITE among what the builder holds so far */
static int
read_resolve_site(struct figure_parser *p, const char *seg, struct figure_pos seg_at,
		  const char *site, struct figure_pos site_at, const char *hint, int *seg_dest,
		  int *site_dest)
{
	*seg_dest = model_builder_find_segment(p->b, seg);
	if (*seg_dest < 0)
		return figure_parse_error_at(p, seg_at, "unknown segment '%s' (%s)", seg, hint);
	*site_dest = model_builder_find_site(p->b, *seg_dest, site);
	if (*site_dest < 0)
		return figure_parse_error_at(p, site_at, "segment '%s' has no site '%s'", seg,
					     site);
	return 0;
}

/* NAME "." NAME, read into seg and site with their positions */
static int
read_site_name(struct figure_parser *p, const char *ctx, char seg[MODEL_NAME_MAX],
	       struct figure_pos *seg_at, char site[MODEL_NAME_MAX], struct figure_pos *site_at)
{
	char what[160];
	snprintf(what, sizeof what, "a segment name (SEGMENT.SITE) %s", ctx);
	if (figure_parse_name(p, what, seg, seg_at) < 0)
		return -1;
	snprintf(what, sizeof what, "'.' after '%s' (SEGMENT.SITE)", seg);
	if (figure_parse_expect(p, FTOK_DOT, what) < 0)
		return -1;
	snprintf(what, sizeof what, "a site name after '%s.'", seg);
	return figure_parse_name(p, what, site, site_at);
}

/* one side of "connect A.a to B.b"; k is 0 for the from-site, 1 for the to-site */
static int
read_connect_side(struct figure_parser *p, struct read_joint *j, int k, const char *ctx)
{
	char site[MODEL_NAME_MAX];
	struct figure_pos seg_at, site_at;
	if (read_site_name(p, ctx, j->seg_name[k], &seg_at, site, &site_at) < 0)
		return -1;
	return read_resolve_site(p, j->seg_name[k], seg_at, site, site_at,
				 "a joint may only connect segments defined earlier in the file",
				 &j->seg[k], k == 0 ? &j->def.site_from : &j->def.site_to);
}

/* dof { "," dof }, after "type =" */
static int
read_dofs(struct figure_parser *p, struct read_joint *j)
{
	struct joint_def *d = &j->def;
	for (;;) {
		enum dof_kind kind;
		if (d->ndof == MODEL_JOINT_DOF_MAX)
			return figure_parse_error_at(p, figure_parse_here(p),
						     "a joint has at most %d degrees of freedom",
						     MODEL_JOINT_DOF_MAX);
		if (figure_parse_is_word(p, "R"))
			kind = DOF_ROTATION;
		else if (figure_parse_is_word(p, "T"))
			kind = DOF_TRANSLATION;
		else
			return figure_parse_expected(p, "a degree of freedom R(axis) or T(axis)");
		struct dof_def *f = &d->dof[d->ndof];
		if (figure_parse_next(p) < 0 ||
		    figure_parse_expect(p, FTOK_LPAREN, "'(' after R or T") < 0 ||
		    figure_parse_axis(p, &f->axis, &f->sign) < 0 ||
		    figure_parse_expect(p, FTOK_RPAREN, "')' after the axis") < 0)
			return -1;
		f->kind = kind;
		d->ndof++;
		if (TOK.kind != FTOK_COMMA)
			return 0;
		if (figure_parse_next(p) < 0)
			return -1;
	}
}

/* pair { "," pair }, after "limits =" */
static int
read_limits(struct figure_parser *p, struct read_joint *j)
{
	for (;;) {
		if (j->nlim == 2 * MODEL_JOINT_DOF_MAX)
			return figure_parse_error_at(p, figure_parse_here(p),
						     "more than %d limit pairs",
						     MODEL_JOINT_DOF_MAX);
		if (figure_parse_expect(p, FTOK_LPAREN,
					"'(' to start a (lower, upper) limit pair") < 0 ||
		    figure_parse_raw_number(p, "a lower limit", &j->lim[j->nlim]) < 0 ||
		    figure_parse_expect(p, FTOK_COMMA, "',' between the lower and upper limit") <
			    0 ||
		    figure_parse_raw_number(p, "an upper limit", &j->lim[j->nlim + 1]) < 0 ||
		    figure_parse_expect(p, FTOK_RPAREN, "')' after the upper limit") < 0)
			return -1;
		j->nlim += 2;
		if (TOK.kind != FTOK_COMMA)
			return 0;
		if (figure_parse_next(p) < 0)
			return -1;
	}
}

/* "(" number { "," number } ")", after "displacement =" */
static int
read_displacement(struct figure_parser *p, struct read_joint *j)
{
	if (figure_parse_expect(p, FTOK_LPAREN, "'(' to start the displacement values") < 0)
		return -1;
	for (;;) {
		if (j->ndisp == MODEL_JOINT_DOF_MAX)
			return figure_parse_error_at(p, figure_parse_here(p),
						     "more than %d displacement values",
						     MODEL_JOINT_DOF_MAX);
		if (figure_parse_raw_number(p, "a displacement value", &j->disp[j->ndisp++]) < 0)
			return -1;
		if (TOK.kind != FTOK_COMMA)
			return figure_parse_expect(p, FTOK_RPAREN,
						   "',' or ')' in the displacement");
		if (figure_parse_next(p) < 0)
			return -1;
	}
}

/* one statement of a joint block */
static int
read_joint_statement(struct figure_parser *p, struct read_joint *j, unsigned *given)
{
	char block[96], word[MODEL_NAME_MAX], what[96];
	snprintf(block, sizeof block, "joint '%s'", j->name);
	if (TOK.kind != FTOK_IDENT)
		return figure_parse_expected(p, "a joint statement (connect, type, limits, "
						"displacement) or '}'");
	struct figure_pos at = figure_parse_here(p);
	memcpy(word, TOK.text, sizeof word);
	if (!strcmp(word, "connect")) {
		if (figure_parse_keyword(p, given, block) < 0 ||
		    read_connect_side(p, j, 0, "after 'connect'") < 0 ||
		    figure_parse_expect_word(p, "to", "'to' between the two sites of 'connect'") <
			    0 ||
		    read_connect_side(p, j, 1, "after 'to'") < 0)
			return -1;
		return figure_parse_expect(p, FTOK_SEMI, "';' after the connect statement");
	}
	if (strcmp(word, "type") && strcmp(word, "limits") && strcmp(word, "displacement"))
		return figure_parse_error_at(
			p, at,
			"unknown statement '%s' in %s (expected connect, type, "
			"limits or displacement)",
			word, block);
	snprintf(what, sizeof what, "'=' after '%s'", word);
	if (figure_parse_keyword(p, given, block) < 0 ||
	    figure_parse_expect(p, FTOK_EQUALS, what) < 0)
		return -1;
	int rc;
	if (!strcmp(word, "type")) {
		rc = read_dofs(p, j);
	} else if (!strcmp(word, "limits")) {
		j->limits_at = at;
		rc = read_limits(p, j);
	} else {
		j->disp_at = at;
		rc = read_displacement(p, j);
	}
	if (rc < 0)
		return -1;
	snprintf(what, sizeof what, "';' after the %s", word);
	return figure_parse_expect(p, FTOK_SEMI, what);
}

/* a limit or displacement must be an angle for R and a length for T */
static int
read_check_unit(struct figure_parser *p, const struct figure_num *n, const struct dof_def *f,
		int dof, const char *what)
{
	enum figure_unit want = f->kind == DOF_ROTATION ? FUNIT_ANGLE : FUNIT_LENGTH;
	if (n->unit == FUNIT_NONE || n->unit == want)
		return 0;
	return figure_parse_error_at(p, n->at, "%s of dof %d (%s) must be %s, found %s", what,
				     dof + 1,
				     f->kind == DOF_ROTATION ? "a rotation" : "a translation",
				     figure_lex_unit_noun(want), figure_lex_unit_noun(n->unit));
}

static int
read_uf_find(int *parent, int i)
{
	while (parent[i] != i) {
		parent[i] = parent[parent[i]];
		i = parent[i];
	}
	return i;
}

/* checks a finished joint block against its dofs and hands it to the builder */
static int
read_joint_add(struct figure_parser *p, struct read_joint *j, unsigned given)
{
	struct joint_def *d = &j->def;
	const char *unit[2] = { "rad", "m" };
	if (!(given & ONCE_CONNECT))
		return figure_parse_error_at(p, j->at,
					     "joint '%s' has no 'connect SEGMENT.SITE to "
					     "SEGMENT.SITE;' statement",
					     j->name);
	if ((given & ONCE_LIMITS) && j->nlim / 2 != d->ndof)
		return figure_parse_error_at(p, j->limits_at,
					     "joint '%s' has %d degrees of freedom "
					     "but its limits give %d pair%s",
					     j->name, d->ndof, j->nlim / 2,
					     j->nlim == 2 ? "" : "s");
	if ((given & ONCE_DISPLACEMENT) && j->ndisp != d->ndof)
		return figure_parse_error_at(p, j->disp_at,
					     "joint '%s' has %d degrees of freedom "
					     "but its displacement gives %d value%s",
					     j->name, d->ndof, j->ndisp, j->ndisp == 1 ? "" : "s");
	for (int k = 0; k < d->ndof; k++) {
		struct dof_def *f = &d->dof[k];
		int rot = f->kind == DOF_ROTATION;
		f->lo = rot ? -M_PI : -1;
		f->hi = rot ? M_PI : 1;
		f->init = 0;
		if (given & ONCE_LIMITS) {
			const struct figure_num *lo = &j->lim[2 * k], *hi = &j->lim[2 * k + 1];
			if (read_check_unit(p, lo, f, k, "the lower limit") < 0 ||
			    read_check_unit(p, hi, f, k, "the upper limit") < 0)
				return -1;
			if (lo->v > hi->v)
				return figure_parse_error_at(p, lo->at,
							     "lower limit %.17g %s of dof %d "
							     "is above its upper limit %.17g %s",
							     lo->v, unit[!rot], k + 1, hi->v,
							     unit[!rot]);
			f->lo = lo->v;
			f->hi = hi->v;
		}
		if (given & ONCE_DISPLACEMENT) {
			const struct figure_num *v = &j->disp[k];
			if (read_check_unit(p, v, f, k, "the displacement") < 0)
				return -1;
			if (v->v < f->lo || v->v > f->hi)
				return figure_parse_error_at(
					p, v->at,
					"displacement %.17g %s of dof %d "
					"lies outside its limits [%.17g, %.17g]",
					v->v, unit[!rot], k + 1, f->lo, f->hi);
			f->init = v->v;
		} else if (f->lo > 0 || f->hi < 0) {
			return figure_parse_error_at(p, j->limits_at,
						     "the default displacement 0 of "
						     "dof %d lies outside its limits; give a "
						     "displacement",
						     k + 1);
		}
	}

	/* name the joint that would close a loop, before the builder sees it */
	int a = read_uf_find(p->uf, j->seg[0]), c = read_uf_find(p->uf, j->seg[1]);
	if (j->seg[0] != j->seg[1] && a == c)
		return figure_parse_error_at(p, j->at,
					     "joint '%s' closes a loop: segments '%s' and "
					     "'%s' are already connected (a figure must be a tree)",
					     j->name, j->seg_name[0], j->seg_name[1]);
	d->name = j->name;
	if (model_builder_joint(p->b, d) < 0)
		return figure_parse_error_at(p, j->at, "%s", model_builder_error(p->b));
	p->uf[a] = c;
	return 0;
}

/* "joint" NAME "{" { jnt_stmt } "}" */
static int
read_joint(struct figure_parser *p)
{
	struct read_joint j;
	unsigned given = 0;
	char what[96];
	memset(&j, 0, sizeof j);
	j.def = joint_default_def();
	if (figure_parse_next(p) < 0 ||
	    figure_parse_name(p, "a joint name after 'joint'", j.name, &j.at) < 0)
		return -1;
	snprintf(what, sizeof what, "'{' to open joint '%s'", j.name);
	if (figure_parse_expect(p, FTOK_LBRACE, what) < 0)
		return -1;
	while (TOK.kind != FTOK_RBRACE) {
		if (TOK.kind == FTOK_EOF) {
			snprintf(what, sizeof what, "'}' to close joint '%s'", j.name);
			return figure_parse_expected(p, what);
		}
		if (read_joint_statement(p, &j, &given) < 0)
			return -1;
	}
	if (figure_parse_next(p) < 0)
		return -1;
	return read_joint_add(p, &j, given);
}

/* one statement of the figure block */
static int
read_figure_statement(struct figure_parser *p)
{
	char block[96];
	snprintf(block, sizeof block, "figure '%s'", p->name);
	if (TOK.kind != FTOK_IDENT)
		return figure_parse_expected(p,
					     "a figure statement (segment, joint, root, location) "
					     "or '}'");
	if (figure_parse_is_word(p, "segment"))
		return figure_segment_parse(p);
	if (figure_parse_is_word(p, "joint"))
		return read_joint(p);
	if (figure_parse_is_word(p, "root")) {
		if (figure_parse_keyword(p, &p->given, block) < 0 ||
		    figure_parse_expect(p, FTOK_EQUALS, "'=' after 'root'") < 0 ||
		    read_site_name(p, "after 'root ='", p->root_seg, &p->root_seg_at, p->root_site,
				   &p->root_site_at) < 0)
			return -1;
		return figure_parse_expect(p, FTOK_SEMI, "';' after the root");
	}
	if (figure_parse_is_word(p, "location")) {
		if (figure_parse_keyword(p, &p->given, block) < 0 ||
		    figure_parse_expect(p, FTOK_EQUALS, "'=' after 'location'") < 0 ||
		    figure_parse_transform(p, "the figure location", p->loc_pos, p->loc_quat) < 0)
			return -1;
		return figure_parse_expect(p, FTOK_SEMI, "';' after the figure location");
	}
	return figure_parse_error_at(p, figure_parse_here(p),
				     "unknown statement '%s' in %s (expected segment, joint, root "
				     "or location)",
				     TOK.text, block);
}

/* file = figure EOF */
static struct model *
read_figure(struct figure_parser *p)
{
	char what[96];
	struct figure_pos at;
	if (!figure_parse_is_word(p, "figure")) {
		figure_parse_expected(p, "'figure' to start the file");
		return NULL;
	}
	if (figure_parse_next(p) < 0 ||
	    figure_parse_name(p, "a figure name after 'figure'", p->name, &at) < 0)
		return NULL;
	p->b = model_builder_create(p->name);
	if (!p->b) {
		figure_parse_error_at(p, at, "out of memory");
		return NULL;
	}
	snprintf(what, sizeof what, "'{' to open figure '%s'", p->name);
	if (figure_parse_expect(p, FTOK_LBRACE, what) < 0)
		return NULL;
	while (TOK.kind != FTOK_RBRACE) {
		if (TOK.kind == FTOK_EOF) {
			snprintf(what, sizeof what, "'}' to close figure '%s'", p->name);
			figure_parse_expected(p, what);
			return NULL;
		}
		if (read_figure_statement(p) < 0)
			return NULL;
	}
	struct figure_pos close = figure_parse_here(p);
	if (figure_parse_next(p) < 0)
		return NULL;
	if (TOK.kind != FTOK_EOF) {
		figure_parse_expected(p, "the end of the file after the figure (a file holds "
					 "exactly one figure)");
		return NULL;
	}

	/* the root, then the builder's checks of the whole tree */
	if (!(p->given & ONCE_ROOT)) {
		figure_parse_error_at(
			p, close, "figure '%s' has no 'root = SEGMENT.SITE;' statement", p->name);
		return NULL;
	}
	int seg, site;
	char hint[96];
	snprintf(hint, sizeof hint, "the root must name a segment of figure '%s'", p->name);
	if (read_resolve_site(p, p->root_seg, p->root_seg_at, p->root_site, p->root_site_at, hint,
			      &seg, &site) < 0)
		return NULL;
	if (model_builder_root(p->b, site, p->loc_pos, p->loc_quat) < 0) {
		figure_parse_error_at(p, p->root_seg_at, "%s", model_builder_error(p->b));
		return NULL;
	}
	struct model *m = model_builder_finish(p->b);
	if (!m)
		figure_parse_error_at(p, close, "%s", model_builder_error(p->b));
	return m;
}

struct model *
figure_read_string(const char *text, size_t len, const char *origin, const char *base_dir,
		   char *err, size_t errlen)
{
	if (err && errlen)
		err[0] = 0;
	if (!origin)
		origin = "<figure>";
	struct figure_parser *p = calloc(1, sizeof *p);
	if (!p) {
		if (err && errlen)
			snprintf(err, errlen, "%s:1:1: out of memory", origin);
		return NULL;
	}
	p->base_dir = base_dir;
	p->loc_quat[3] = 1;
	struct model *m = NULL;
	if (figure_lex_init(&p->lx, text, len, origin, err, errlen) == 0)
		m = read_figure(p);
	model_builder_free(p->b);
	free(p->seg.site);
	free(p->seg.geom);
	free(p->mesh);
	free(p->uf);
	free(p);
	return m;
}

/* reads up to max + 1 bytes of a file into a new buffer; -1 with errno */
static int
read_whole_file(FILE *f, size_t max, char **dest, size_t *len)
{
	size_t cap = 1 << 16, n = 0;
	char *buf = malloc(cap);
	if (!buf)
		return -1;
	for (;;) {
		if (n == cap) {
			if (cap >
			    max) /* holds max + 1 bytes already: too big, the caller says so */
				break;
			size_t ncap = cap * 2 > max + 1 ? max + 1 : cap * 2;
			char *q = realloc(buf, ncap);
			if (!q) {
				free(buf);
				return -1;
			}
			buf = q;
			cap = ncap;
		}
		size_t got = fread(buf + n, 1, cap - n, f);
		n += got;
		if (got == 0)
			break;
	}
	if (ferror(f)) {
		free(buf);
		errno = EIO;
		return -1;
	}
	*dest = buf;
	*len = n;
	return 0;
}

struct model *
figure_read_file(const char *path, char *err, size_t errlen)
{
	if (err && errlen)
		err[0] = 0;
	FILE *f = fopen(path, "rb");
	if (!f) {
		if (err && errlen)
			snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
		return NULL;
	}
	char *text = NULL;
	size_t len = 0;
	int rc = read_whole_file(f, FIGURE_TEXT_MAX, &text, &len);
	int saved = errno;
	fclose(f);
	if (rc < 0) {
		if (err && errlen)
			snprintf(err, errlen, "%s: cannot read: %s", path, strerror(saved));
		return NULL;
	}

	/* meshes are found next to the figure file */
	char *dir = strdup(path);
	char *slash = dir ? strrchr(dir, '/') : NULL;
	if (slash)
		slash[slash == dir ? 1 : 0] = 0;
	struct model *m = NULL;
	if (!dir) {
		if (err && errlen)
			snprintf(err, errlen, "%s: out of memory", path);
	} else {
		m = figure_read_string(text, len, path, slash ? dir : NULL, err, errlen);
	}
	free(dir);
	free(text);
	return m;
}
