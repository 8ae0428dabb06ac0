/* assess_json.c - an assessment as JSON, written without allocating (see assess_json.h) */
#include "daemon/assess_json.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

const char *
assess_json_method(enum assess_method m)
{
	switch (m) {
	case ASSESS_RULA:
		return "rula";
	case ASSESS_REBA:
		return "reba";
	case ASSESS_OWAS:
		return "owas";
	case ASSESS_NMETHODS:
		break;
	}
	return "?";
}

static void
str_or_null(struct jbuf *j, const char *s)
{
	if (s)
		jbuf_str(j, s);
	else
		jbuf_raw(j, "null");
}

static void
side(struct jbuf *j, int s)
{
	str_or_null(j, s == ASSESS_SIDE_LEFT ? "left" : s == ASSESS_SIDE_RIGHT ? "right" : NULL);
}

/* the part's name, or "part_N" for one without (never a duplicate key then) */
static void
part_key(struct jbuf *j, const struct assess_result *r, int i, int first)
{
	if (r->part[i].name) {
		jbuf_key(j, r->part[i].name, first);
		return;
	}
	char k[16];
	snprintf(k, sizeof k, "part_%d", i);
	jbuf_key(j, k, first);
}

static void
worst(struct jbuf *j, const struct assess_result *r)
{
	jbuf_key(j, "worst", 0);
	str_or_null(j, r->worst >= 0 && r->worst < r->nparts ? r->part[r->worst].name : NULL);
}

static void
part(struct jbuf *j, const struct assess_part *p)
{
	jbuf_key(j, "angle", 1);
	jbuf_num(j, p->angle); /* NAN (no angle): null */
	jbuf_key(j, "angle_name", 0);
	str_or_null(j, p->angle_name);
	jbuf_key(j, "band", 0);
	jbuf_str(j, p->band);
	jbuf_key(j, "base", 0);
	jbuf_int(j, p->base);
	jbuf_key(j, "adjust", 0);
	jbuf_raw(j, "[");
	for (int k = 0; k < p->nadj && k < ASSESS_MAX_ADJ; k++) {
		jbuf_raw(j, k ? ",{" : "{");
		jbuf_key(j, "value", 1);
		jbuf_int(j, p->adj[k].value);
		jbuf_key(j, "reason", 0);
		jbuf_str(j, p->adj[k].reason);
		jbuf_raw(j, "}");
	}
	jbuf_raw(j, "]");
	jbuf_key(j, "score", 0);
	jbuf_int(j, p->score);
	jbuf_key(j, "max", 0);
	jbuf_int(j, p->max);
}

void
assess_json_result_keys(struct jbuf *j, const struct assess_result *r, int first)
{
	int nparts = r->nparts < ASSESS_MAX_PARTS ? r->nparts : ASSESS_MAX_PARTS;
	int nlook = r->nlookups < ASSESS_MAX_LOOKUPS ? r->nlookups : ASSESS_MAX_LOOKUPS;
	jbuf_key(j, "score", first);
	jbuf_int(j, r->score);
	jbuf_key(j, "action_level", 0);
	jbuf_int(j, r->action_level);
	jbuf_key(j, "action", 0);
	str_or_null(j, r->action);
	jbuf_key(j, "side", 0);
	side(j, r->side);
	jbuf_key(j, "parts", 0);
	jbuf_raw(j, "{");
	for (int i = 0; i < nparts; i++) {
		part_key(j, r, i, i == 0);
		jbuf_raw(j, "{");
		part(j, &r->part[i]);
		jbuf_raw(j, "}");
	}
	jbuf_raw(j, "}");
	/* each table once, its cell: a table looked up twice keeps the first (none is, today) */
	jbuf_key(j, "tables", 0);
	jbuf_raw(j, "{");
	int written = 0;
	for (int i = 0; i < nlook; i++) {
		const char *t = r->lookup[i].table ? r->lookup[i].table : "?";
		int seen = 0;
		for (int k = 0; k < i && !seen; k++)
			seen = r->lookup[k].table && !strcmp(r->lookup[k].table, t);
		if (seen)
			continue;
		jbuf_key(j, t, !written++);
		jbuf_int(j, r->lookup[i].value);
	}
	jbuf_raw(j, "}");
	jbuf_key(j, "lookups", 0);
	jbuf_raw(j, "[");
	for (int i = 0; i < nlook; i++) {
		const struct assess_lookup *l = &r->lookup[i];
		jbuf_raw(j, i ? ",{" : "{");
		jbuf_key(j, "table", 1);
		str_or_null(j, l->table);
		jbuf_key(j, "idx", 0);
		jbuf_raw(j, "{");
		for (int k = 0; k < l->nidx && k < ASSESS_MAX_IDX; k++) {
			jbuf_key(j, l->idx_name[k] ? l->idx_name[k] : "?", k == 0);
			jbuf_int(j, l->idx[k]);
		}
		jbuf_raw(j, "}");
		jbuf_key(j, "value", 0);
		jbuf_int(j, l->value);
		jbuf_raw(j, "}");
	}
	jbuf_raw(j, "]");
	worst(j, r);
	if (r->method == ASSESS_OWAS) {
		jbuf_key(j, "code", 0);
		jbuf_str(j, r->code);
	}
}

void
assess_json_summary(struct jbuf *j, const struct assess_result *r)
{
	int nparts = r->nparts < ASSESS_MAX_PARTS ? r->nparts : ASSESS_MAX_PARTS;
	jbuf_raw(j, "{");
	jbuf_key(j, "score", 1);
	jbuf_int(j, r->score);
	jbuf_key(j, "action_level", 0);
	jbuf_int(j, r->action_level);
	jbuf_key(j, "side", 0);
	side(j, r->side);
	worst(j, r);
	jbuf_key(j, "parts", 0);
	jbuf_raw(j, "{");
	for (int i = 0; i < nparts; i++) {
		part_key(j, r, i, i == 0);
		jbuf_int(j, r->part[i].score);
	}
	jbuf_raw(j, "}");
	if (r->method == ASSESS_OWAS) {
		jbuf_key(j, "code", 0);
		jbuf_str(j, r->code);
	}
	jbuf_raw(j, "}");
}

void
assess_json_angles(struct jbuf *j, const struct body_angles *a)
{
	jbuf_raw(j, "{");
	for (size_t i = 0; i < body_angle_count; i++) {
		double v = body_angle_value(a, i);
		jbuf_key(j, body_angle_names[i].name, i == 0);
		if (!strcmp(body_angle_names[i].unit, "flag") && isfinite(v))
			jbuf_int(j, (long long)(v != 0)); /* 0 or 1 */
		else if (!strcmp(body_angle_names[i].unit, "count") && isfinite(v))
			jbuf_int(j, (long long)v);
		else
			jbuf_num(j, v);
	}
	jbuf_raw(j, "}");
}
