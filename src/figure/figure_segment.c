/* figure_segment.c - segment blocks of the figure language (grammar in figure_read.c) */
#include "figure/figure_parse.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/obj.h"

/* the current token of parser p */
#define TOK (p->lx.tok)

static const enum figure_unit seg_num6[6] = { FUNIT_NONE, FUNIT_NONE, FUNIT_NONE,
					      FUNIT_NONE, FUNIT_NONE, FUNIT_NONE };

/* loads an OBJ once per path and returns its builder index in *dest */
static int
seg_mesh(struct figure_parser *p, const char *path, struct figure_pos at, int *dest)
{
	if (!path[0])
		return figure_parse_error_at(p, at, "empty mesh path");
	for (int i = 0; i < p->nmesh; i++) {
		if (!strcmp(p->mesh[i].path, path)) {
			*dest = p->mesh[i].index;
			return 0;
		}
	}
	char full[PATH_MAX];
	int n;
	if (path[0] == '/' || !p->base_dir || !p->base_dir[0])
		n = snprintf(full, sizeof full, "%s", path);
	else
		n = snprintf(full, sizeof full, "%s/%s", p->base_dir, path);
	if (n < 0 || (size_t)n >= sizeof full)
		return figure_parse_error_at(p, at, "mesh path \"%s\" is too long", path);
	struct obj_mesh om;
	char oerr[512];
	if (obj_read_file(full, &om, oerr, sizeof oerr) < 0)
		return figure_parse_error_at(p, at, "cannot load mesh \"%s\": %s", path, oerr);
	int idx = model_builder_mesh(p->b, path, om.vert, om.nvert, om.face, om.nface);
	obj_mesh_free(&om);
	if (idx < 0)
		return figure_parse_error_at(p, at, "%s", model_builder_error(p->b));
	if (p->nmesh == p->capmesh) {
		int ncap = p->capmesh ? 2 * p->capmesh : 8;
		struct figure_mesh_ref *q = realloc(p->mesh, sizeof *q * (size_t)ncap);
		if (!q)
			return figure_parse_error_at(p, at, "out of memory");
		p->mesh = q;
		p->capmesh = ncap;
	}
	snprintf(p->mesh[p->nmesh].path, MODEL_PATH_MAX, "%s", path);
	p->mesh[p->nmesh++].index = idx;
	*dest = idx;
	return 0;
}

static int
seg_add_geom(struct figure_parser *p, const struct figure_geom *g)
{
	struct figure_seg *s = &p->seg;
	if (s->ngeom == s->capgeom) {
		int ncap = s->capgeom ? 2 * s->capgeom : 8;
		struct figure_geom *q = realloc(s->geom, sizeof *q * (size_t)ncap);
		if (!q)
			return figure_parse_error_at(p, g->at, "out of memory");
		s->geom = q;
		s->capgeom = ncap;
	}
	s->geom[s->ngeom++] = *g;
	return 0;
}

/* shape [ "at" transform ], after "geometry =" */
static int
seg_geometry(struct figure_parser *p)
{
	static const enum figure_unit len2[2] = { FUNIT_LENGTH, FUNIT_LENGTH };
	struct figure_geom g = { .def = geom_default_def(), .at = figure_parse_here(p) };
	const char *what = "a shape: box, cylinder, capsule, ellipsoid or mesh";
	if (TOK.kind != FTOK_IDENT)
		return figure_parse_expected(p, what);
	char kind[MODEL_NAME_MAX];
	memcpy(kind, TOK.text, sizeof kind);
	if (!strcmp(kind, "box"))
		g.def.kind = GEOM_BOX;
	else if (!strcmp(kind, "cylinder"))
		g.def.kind = GEOM_CYLINDER;
	else if (!strcmp(kind, "capsule"))
		g.def.kind = GEOM_CAPSULE;
	else if (!strcmp(kind, "ellipsoid"))
		g.def.kind = GEOM_ELLIPSOID;
	else if (!strcmp(kind, "mesh"))
		g.def.kind = GEOM_MESH;
	else
		return figure_parse_expected(p, what);
	if (figure_parse_next(p) < 0)
		return -1;
	char ctx[64];
	snprintf(ctx, sizeof ctx, "%s()", kind);
	int rc = 0;
	switch (g.def.kind) {
	case GEOM_BOX:
	case GEOM_ELLIPSOID:
		rc = figure_parse_list(p, figure_parse_len3, 3, ctx, g.def.size);
		break;
	case GEOM_CYLINDER:
	case GEOM_CAPSULE:
		rc = figure_parse_list(p, len2, 2, ctx, g.def.size);
		break;
	case GEOM_MESH:
		g.def.size[0] = g.def.size[1] = g.def.size[2] = 1;
		if (figure_parse_expect(p, FTOK_LPAREN, "'(' after 'mesh'") < 0)
			return -1;
		if (TOK.kind != FTOK_STRING)
			return figure_parse_expected(p, "a file name string in mesh()");
		if (seg_mesh(p, TOK.text, figure_parse_here(p), &g.def.mesh) < 0 ||
		    figure_parse_next(p) < 0)
			return -1;
		for (int i = 0; i < 3 && (i > 0 || TOK.kind == FTOK_COMMA); i++) {
			if (figure_parse_expect(p, FTOK_COMMA,
						"',' (mesh() takes a path and 3 scales)") < 0 ||
			    figure_parse_number(p, FUNIT_NONE, "for a scale in mesh()",
						&g.def.size[i]) < 0)
				return -1;
		}
		rc = figure_parse_expect(p, FTOK_RPAREN, "')' after the arguments of mesh()");
		break;
	}
	if (rc < 0)
		return -1;
	if (figure_parse_is_word(p, "at")) {
		if (figure_parse_next(p) < 0 ||
		    figure_parse_transform(p, "the geometry placement", g.def.pos, g.def.quat) < 0)
			return -1;
	}
	if (figure_parse_expect(p, FTOK_SEMI, "';' after the geometry") < 0)
		return -1;
	return seg_add_geom(p, &g);
}

/* "site" NAME "->" "location" "=" transform ";" */
static int
seg_site(struct figure_parser *p)
{
	struct figure_seg *s = &p->seg;
	struct figure_site st;
	if (figure_parse_next(p) < 0 ||
	    figure_parse_name(p, "a site name after 'site'", st.name, &st.at) < 0)
		return -1;
	for (int i = 0; i < s->nsite; i++)
		if (!strcmp(s->site[i].name, st.name))
			return figure_parse_error_at(p, st.at,
						     "site '%s' is defined twice in segment '%s'",
						     st.name, s->name);
	if (figure_parse_expect(p, FTOK_ARROW,
				"'->' after the site name (site NAME->location = ...)") < 0 ||
	    figure_parse_expect_word(p, "location", "'location' after '->'") < 0 ||
	    figure_parse_expect(p, FTOK_EQUALS, "'=' after 'location'") < 0 ||
	    figure_parse_transform(p, "the site location", st.pos, st.quat) < 0 ||
	    figure_parse_expect(p, FTOK_SEMI, "';' after the site location") < 0)
		return -1;
	if (s->nsite == s->capsite) {
		int ncap = s->capsite ? 2 * s->capsite : 8;
		struct figure_site *q = realloc(s->site, sizeof *q * (size_t)ncap);
		if (!q)
			return figure_parse_error_at(p, st.at, "out of memory");
		s->site = q;
		s->capsite = ncap;
	}
	s->site[s->nsite++] = st;
	return 0;
}

/* "color" "=" "(" r "," g "," b [ "," a ] ")" */
static int
seg_color(struct figure_parser *p)
{
	struct figure_seg *s = &p->seg;
	if (figure_parse_expect(p, FTOK_LPAREN, "'(' to start the color") < 0)
		return -1;
	for (int i = 0; i < 4; i++) {
		if (i == 3 && TOK.kind == FTOK_RPAREN)
			break;
		if (i > 0 && figure_parse_expect(p, FTOK_COMMA,
						 i < 3 ? "',' (color takes 3 or 4 values)"
						       : "',' or ')' after the blue value") < 0)
			return -1;
		struct figure_pos at = figure_parse_here(p);
		double v;
		if (figure_parse_number(p, FUNIT_NONE, "for a color component", &v) < 0)
			return -1;
		if (!(v >= 0 && v <= 1))
			return figure_parse_error_at(p, at,
						     "color components lie in [0, 1], found %g", v);
		s->def.rgba[i] = (float)v;
	}
	return figure_parse_expect(p, FTOK_RPAREN, "')' after the color");
}

/* one statement of a segment block */
static int
seg_statement(struct figure_parser *p, unsigned *given)
{
	struct figure_seg *s = &p->seg;
	char block[96], word[MODEL_NAME_MAX], after[96];
	snprintf(block, sizeof block, "segment '%s'", s->name);
	if (TOK.kind != FTOK_IDENT)
		return figure_parse_expected(
			p, "a segment statement (mass, com, inertia, color, psurf, geometry, "
			   "site) or '}'");
	if (figure_parse_is_word(p, "site"))
		return seg_site(p);
	memcpy(word, TOK.text, sizeof word);
	struct figure_pos at = figure_parse_here(p);
	if (strcmp(word, "mass") && strcmp(word, "com") && strcmp(word, "inertia") &&
	    strcmp(word, "color") && strcmp(word, "psurf") && strcmp(word, "geometry"))
		return figure_parse_error_at(
			p, at,
			"unknown statement '%s' in %s (expected mass, com, inertia, color, "
			"psurf, geometry or site)",
			word, block);
	snprintf(after, sizeof after, "'=' after '%s'", word);
	if (figure_parse_keyword(p, given, block) < 0 ||
	    figure_parse_expect(p, FTOK_EQUALS, after) < 0)
		return -1;
	struct figure_pos vat = figure_parse_here(p);
	int rc = 0;
	if (!strcmp(word, "mass")) {
		rc = figure_parse_number(p, FUNIT_MASS, "after 'mass ='", &s->def.mass);
		if (rc == 0 && !(s->def.mass >= 0))
			return figure_parse_error_at(p, vat, "mass must be >= 0, found %g kg",
						     s->def.mass);
	} else if (!strcmp(word, "com")) {
		rc = figure_parse_list(p, figure_parse_len3, 3, "the centre of mass", s->def.com);
	} else if (!strcmp(word, "inertia")) {
		rc = figure_parse_list(p, seg_num6, 6, "the inertia (ixx, iyy, izz, ixy, ixz, iyz)",
				       s->def.inertia);
		if (rc == 0 &&
		    (s->def.inertia[0] < 0 || s->def.inertia[1] < 0 || s->def.inertia[2] < 0))
			return figure_parse_error_at(
				p, vat, "moments of inertia ixx, iyy, izz must be >= 0");
	} else if (!strcmp(word, "color")) {
		rc = seg_color(p);
	} else if (!strcmp(word, "psurf")) {
		struct figure_geom g = { .def = geom_default_def(), .at = vat };
		g.def.kind = GEOM_MESH;
		g.def.size[0] = g.def.size[1] = g.def.size[2] = 1;
		if (TOK.kind != FTOK_STRING)
			return figure_parse_expected(p, "a file name string after 'psurf ='");
		if (seg_mesh(p, TOK.text, vat, &g.def.mesh) < 0 || figure_parse_next(p) < 0 ||
		    seg_add_geom(p, &g) < 0)
			return -1;
	} else {
		return seg_geometry(p);
	}
	if (rc < 0)
		return -1;
	snprintf(after, sizeof after, "';' after the %s", word);
	return figure_parse_expect(p, FTOK_SEMI, after);
}

/* hands a finished segment block with its sites and geometry to the builder */
static int
seg_add(struct figure_parser *p)
{
	struct figure_seg *s = &p->seg;
	s->def.name = s->name;
	int seg = model_builder_segment(p->b, &s->def);
	if (seg < 0)
		return figure_parse_error_at(p, s->at, "%s", model_builder_error(p->b));
	for (int i = 0; i < s->nsite; i++) {
		const struct figure_site *st = &s->site[i];
		if (model_builder_site(p->b, seg, st->name, st->pos, st->quat) < 0)
			return figure_parse_error_at(p, st->at, "%s", model_builder_error(p->b));
	}
	for (int i = 0; i < s->ngeom; i++)
		if (model_builder_geom(p->b, seg, &s->geom[i].def) < 0)
			return figure_parse_error_at(p, s->geom[i].at, "%s",
						     model_builder_error(p->b));
	if (seg >= p->capuf) {
		int ncap = p->capuf ? 2 * p->capuf : 16;
		int *q = realloc(p->uf, sizeof *q * (size_t)ncap);
		if (!q)
			return figure_parse_error_at(p, s->at, "out of memory");
		p->uf = q;
		p->capuf = ncap;
	}
	p->uf[seg] = seg;
	return 0;
}

/* "segment" NAME "{" { seg_stmt } "}" */
int
figure_segment_parse(struct figure_parser *p)
{
	struct figure_seg *s = &p->seg;
	unsigned given = 0;
	char what[96];
	s->def = segment_default_def();
	s->nsite = s->ngeom = 0;
	if (figure_parse_next(p) < 0 ||
	    figure_parse_name(p, "a segment name after 'segment'", s->name, &s->at) < 0)
		return -1;
	snprintf(what, sizeof what, "'{' to open segment '%s'", s->name);
	if (figure_parse_expect(p, FTOK_LBRACE, what) < 0)
		return -1;
	while (TOK.kind != FTOK_RBRACE) {
		if (TOK.kind == FTOK_EOF) {
			snprintf(what, sizeof what, "'}' to close segment '%s'", s->name);
			return figure_parse_expected(p, what);
		}
		if (seg_statement(p, &given) < 0)
			return -1;
	}
	if (figure_parse_next(p) < 0)
		return -1;
	return seg_add(p);
}
