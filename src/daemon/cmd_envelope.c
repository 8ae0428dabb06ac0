/*
 * cmd_envelope.c - analyze reach: a hand's reach envelope (assess/envelope.h)
 * computed from a figure's posture now and kept by name (envelopes.h), and
 * targets checked by reach_solve on a copy of the figure, for one figure
 * or each manikin of a family. Nothing the person's figures hold changes:
 * an envelope is a derived result, kept beside the environment, not in it.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/envelopes.h"
#include "daemon/words.h"
#include "figure/model.h"
#include "pose/reach.h"

#define TARGETS_MAX 32

static const char *const side_names[] = { "left", "right" };

struct analyze {
	struct envelope_request req;
	int ntarget;
	double target[TARGETS_MAX][3];
	int want_envelope; /* no targets, or envelope=yes */
	const char *name;  /* name=, or NULL: FIG.hand.mode */
};

/* the store, made when first needed; NULL with the error set */
static struct envelopes *
store(struct cmd_ctx *c)
{
	if (!c->d->envelopes && !(c->d->envelopes = calloc(1, sizeof *c->d->envelopes)))
		cmd_fail(c, "internal", "out of memory");
	return c->d->envelopes;
}

/* a name the store keeps: letters, digits, '_', '.', '-', not too long */
static int
envelope_name_ok(const char *s)
{
	size_t n = strlen(s);
	if (!n || n >= ENVELOPE_NAME_MAX)
		return 0;
	for (; *s; s++)
		if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9') ||
		      *s == '_' || *s == '.' || *s == '-'))
			return 0;
	return 1;
}

/* "X,Y,Z;X,Y,Z;..." into a: 0, or -1 with the error set */
static int
read_targets(struct cmd_ctx *c, const char *list, struct analyze *a)
{
	char buf[4096];
	if (snprintf(buf, sizeof buf, "%s", list) >= (int)sizeof buf)
		return cmd_fail(c, "bad-argument", "targets= is too long");
	a->ntarget = 0;
	for (char *t = buf, *end; t; t = end) {
		if ((end = strchr(t, ';')))
			*end++ = '\0';
		if (a->ntarget == TARGETS_MAX)
			return cmd_fail(c, "bad-argument", "at most %d targets", TARGETS_MAX);
		if (words_list(t, UNIT_LENGTH, 3, a->target[a->ntarget]) < 0)
			return cmd_fail(c, "bad-argument",
					"target '%.60s': X,Y,Z (three lengths), targets separated by ';'",
					t);
		a->ntarget++;
	}
	if (!a->ntarget)
		return cmd_fail(c, "bad-argument", "targets=X,Y,Z;X,Y,Z;... (none given)");
	return 0;
}

/* the request's words after the figure; 0, or -1 with the error set */
static int
read_analyze(struct cmd_ctx *c, struct analyze *a)
{
	memset(a, 0, sizeof *a);
	a->req.mode = REACH_BODY;
	a->req.balance = 1;
	a->req.resolution = ENVELOPE_RES_DEFAULT;
	envelope_comfort_default(&a->req.comfort_ranges);
	static const char *const keys[] = { "hand", "mode", "balance", "resolution", "comfort",
					    "ranges", "targets", "name", "envelope" };
	for (int i = 1; i < c->argc; i++) {
		const char *w = c->argv[i];
		size_t k = 0;
		while (k < sizeof keys / sizeof *keys && !words_is_key(w, keys[k]))
			k++;
		if (k < sizeof keys / sizeof *keys)
			continue;
		return cmd_fail(c, "bad-argument", "unexpected '%.60s'", w);
	}
	int side, mode = (int)a->req.mode, balance;
	if (cmd_reach_words(c, &side, &mode, &balance) < 0)
		return -1;
	a->req.side = side;
	a->req.mode = (enum reach_mode)mode;
	a->req.balance = balance;
	const char *res = cmd_key(c, "resolution");
	if (res && (words_number(res, UNIT_LENGTH, &a->req.resolution) < 0 ||
		    !(a->req.resolution >= ENVELOPE_RES_MIN && a->req.resolution <= ENVELOPE_RES_MAX)))
		return cmd_fail(c, "bad-argument", "resolution=LEN from %g to %g m, not '%.30s'",
				ENVELOPE_RES_MIN, ENVELOPE_RES_MAX, res);
	const char *comfort = cmd_key(c, "comfort");
	if (comfort && strcmp(comfort, "on") && strcmp(comfort, "off"))
		return cmd_fail(c, "bad-argument", "comfort=on|off");
	a->req.comfort = comfort && !strcmp(comfort, "on");
	const char *ranges = cmd_key(c, "ranges");
	char err[256];
	if (ranges && !a->req.comfort)
		return cmd_fail(c, "bad-argument", "ranges= are the comfort zone's: for comfort=on");
	if (ranges && envelope_comfort_parse(ranges, &a->req.comfort_ranges, err, sizeof err) < 0)
		return cmd_fail(c, "bad-argument", "ranges=JOINT.DOF=LO,HI;... (degrees): %s", err);
	const char *targets = cmd_key(c, "targets");
	if (targets && read_targets(c, targets, a) < 0)
		return -1;
	const char *env = cmd_key(c, "envelope");
	if (env && strcmp(env, "yes") && strcmp(env, "no"))
		return cmd_fail(c, "bad-argument", "envelope=yes|no");
	if (env && !strcmp(env, "no") && !targets)
		return cmd_fail(c, "bad-argument", "envelope=no asks for targets=");
	a->want_envelope = !targets || (env && !strcmp(env, "yes"));
	a->name = cmd_key(c, "name");
	if (a->name && !envelope_name_ok(a->name))
		return cmd_fail(c, "bad-argument", "name=NAME: letters, digits, '_', '.', '-', "
				"shorter than %d bytes", ENVELOPE_NAME_MAX);
	if (a->name && !a->want_envelope)
		return cmd_fail(c, "bad-argument", "name= names an envelope: none is computed");
	return 0;
}

/* the figures argv[0] names: one human, or a family's members; their count, or -1 */
static int
figures_of(struct cmd_ctx *c, int slot[ENV_MAX_FIGURES], const char **family)
{
	int n = cmd_figures(c, c->argv[0], slot, family);
	if (n < 0)
		return -1;
	for (int i = 0; i < n; i++)
		if (!c->d->env.fig[slot[i]].is_human)
			return cmd_fail(c, "bad-argument", "%s is not a human figure",
					c->d->env.fig[slot[i]].name);
	return n;
}

/* the name figure fig's envelope is kept under */
static void
envelope_name(const struct cmd_ctx *c, const struct analyze *a, int fig, const char *family,
	      char *dest, size_t len)
{
	const char *fname = c->d->env.fig[fig].name;
	if (a->name && family)
		snprintf(dest, len, "%s.%s", a->name, fname);
	else if (a->name)
		snprintf(dest, len, "%s", a->name);
	else
		snprintf(dest, len, "%s.%s.%s", fname, side_names[a->req.side],
			 cmd_reach_mode_name(a->req.mode));
}

static json_t *
bounds_json(const struct envelope_mesh *m)
{
	return json_pack("[o,o]", cmd_vec(m->lo, 3), cmd_vec(m->hi, 3));
}

static void
mesh_json(json_t *o, const struct envelope_mesh *m)
{
	json_object_set_new(o, "volume", json_real(m->volume));
	json_object_set_new(o, "bounds", bounds_json(m));
	json_object_set_new(o, "vertices", json_integer(m->nvert));
	json_object_set_new(o, "triangles", json_integer(m->ntri));
}

/* an envelope's reply: what was asked, the surface, the comfort zone, the work done */
static json_t *
envelope_json(const char *name, const char *fig, const struct envelope *e)
{
	json_t *o = json_object();
	json_object_set_new(o, "name", json_string(name));
	json_object_set_new(o, "figure", json_string(fig));
	json_object_set_new(o, "hand", json_string(side_names[e->req.side]));
	json_object_set_new(o, "mode", json_string(cmd_reach_mode_name(e->req.mode)));
	if (e->req.mode == REACH_BODY)
		json_object_set_new(o, "balance", json_boolean(e->req.balance));
	mesh_json(o, &e->reach);
	json_object_set_new(o, "resolution", json_real(e->req.resolution));
	json_object_set_new(o, "grid", json_pack("[i,i,i]", e->grid[0], e->grid[1], e->grid[2]));
	json_object_set_new(o, "solves", json_integer(e->solves));
	json_object_set_new(o, "seconds", json_real(e->seconds));
	if (e->req.comfort) {
		json_t *z = json_object(), *ranges = json_array();
		mesh_json(z, &e->comfort);
		const struct envelope_comfort *cr = &e->req.comfort_ranges;
		struct envelope_comfort def;
		envelope_comfort_default(&def);
		for (int i = 0; i < cr->n; i++) {
			json_t *r = json_pack("{s:s, s:i, s:f, s:f}", "joint", cr->r[i].joint, "dof",
					      cr->r[i].dof, "lo", cr->r[i].lo, "hi", cr->r[i].hi);
			/* a range left at its default says where the default comes from */
			int dflt = i < def.n && !strcmp(def.r[i].joint, cr->r[i].joint) &&
				   def.r[i].dof == cr->r[i].dof && def.r[i].lo == cr->r[i].lo &&
				   def.r[i].hi == cr->r[i].hi;
			const char *src = dflt ? envelope_comfort_source(i) : NULL;
			json_object_set_new(r, "source", src ? json_string(src) : json_string("set"));
			json_array_append_new(ranges, r);
		}
		json_object_set_new(z, "ranges", ranges);
		json_object_set_new(o, "comfort", z);
	}
	return o;
}

/* figure fig's envelope computed into e; 0, or -1 with the error set */
static int
compute_one(struct cmd_ctx *c, const struct analyze *a, int fig, struct envelope *e)
{
	const struct env_figure *f = &c->d->env.fig[fig];
	const struct behave *b = f->behave;
	char err[256];
	if (envelope_compute(f->model, f->state, b ? &b->p : NULL, b ? b->mass : NULL,
			     b ? b->nmass : 0, &a->req, e, err, sizeof err) < 0)
		return cmd_fail(c, "bad-argument", "%s: %s", f->name, err);
	return 0;
}

/* one target's solve on a copy of figure f's posture; 0, or -1 with the error set */
static int
solve(struct cmd_ctx *c, struct reach *r, const struct model *m, const struct env_figure *f,
      const struct analyze *a, int t, struct reach_result *res)
{
	const struct behave *b = f->behave;
	/* the envelope's own solve: the arm's with its restarts (envelope.h) */
	struct reach_request q = { .side = a->req.side, .mode = a->req.mode,
				   .balance = a->req.balance,
				   .restarts = a->req.mode == REACH_ARM ? ENVELOPE_ARM_RESTARTS : 0 };
	memcpy(q.target, a->target[t], sizeof q.target);
	if (reach_solve(r, m, f->state, b ? &b->p : NULL, b ? b->mass : NULL, b ? b->nmass : 0, &q,
			res) < 0)
		return cmd_fail(c, "bad-number", "the targets must be finite");
	return 0;
}

/*
 * Each target's verdict for figure fig: reach_solve on a copy (the posture
 * now; can reach's solve exactly), reached or the distance the palm stays
 * short by. With comfort=on, the same solve again with the joints held
 * within the comfort ranges (the model's limits narrowed as the comfort
 * zone's are, envelope_comfort_apply): comfortable when that reaches too.
 * NULL with the error set.
 */
static json_t *
verdicts(struct cmd_ctx *c, const struct analyze *a, int fig, int *reached)
{
	const struct env_figure *f = &c->d->env.fig[fig];
	char err[256];
	struct model *cm = a->req.comfort ? model_copy(f->model) : NULL;
	if (a->req.comfort && !cm) {
		cmd_fail(c, "internal", "out of memory");
		return NULL;
	}
	if (cm && envelope_comfort_apply(&a->req.comfort_ranges, cm, a->req.side, err,
					 sizeof err) < 0) {
		model_free(cm);
		cmd_fail(c, "bad-argument", "%s: comfort ranges: %s", f->name, err);
		return NULL;
	}
	struct reach *r = reach_make(f->model), *rc = cm ? reach_make(cm) : NULL;
	json_t *list = json_array();
	if (!r || (cm && !rc)) {
		cmd_fail(c, "bad-argument", "%s has no hands and feet to reach with", f->name);
		goto fail;
	}
	for (int t = 0; t < a->ntarget; t++) {
		struct reach_result res, com;
		if (solve(c, r, f->model, f, a, t, &res) < 0 || (cm && solve(c, rc, cm, f, a, t, &com) < 0))
			goto fail;
		json_t *v = json_object();
		json_object_set_new(v, "target", cmd_vec(a->target[t], 3));
		json_object_set_new(v, "restarts",
				    json_integer(a->req.mode == REACH_ARM ? ENVELOPE_ARM_RESTARTS : 0));
		json_object_set_new(v, "reached", json_boolean(res.reached));
		json_object_set_new(v, "shortfall", json_real(res.reached ? 0.0 : res.distance));
		json_object_set_new(v, "distance", json_real(res.distance));
		if (cm) {
			json_object_set_new(v, "comfortable", json_boolean(com.reached));
			json_object_set_new(v, "comfort_shortfall",
					    json_real(com.reached ? 0.0 : com.distance));
		}
		json_array_append_new(list, v);
		reached[t] = res.reached;
	}
	reach_free(r);
	reach_free(rc);
	model_free(cm);
	return list;
fail:
	reach_free(r);
	reach_free(rc);
	model_free(cm);
	json_decref(list);
	return NULL;
}

/* the figures' replies, with each one's envelope (es, or NULL) and verdicts; NULL with the error set */
static json_t *
replies(struct cmd_ctx *c, const struct analyze *a, const int *slot, int n, const char *family,
	const struct envelope *es, int reached[][TARGETS_MAX])
{
	json_t *figs = json_array();
	for (int i = 0; i < n; i++) {
		const char *fname = c->d->env.fig[slot[i]].name;
		json_t *o;
		if (es) {
			char name[ENVELOPE_NAME_MAX + MODEL_NAME_MAX + 2];
			envelope_name(c, a, slot[i], family, name, sizeof name);
			o = envelope_json(name, fname, &es[i]);
		} else {
			o = json_pack("{s:s, s:s, s:s}", "figure", fname, "hand",
				      side_names[a->req.side], "mode", cmd_reach_mode_name(a->req.mode));
		}
		if (a->ntarget) {
			json_t *v = verdicts(c, a, slot[i], reached[i]);
			if (!v) {
				json_decref(o);
				json_decref(figs);
				return NULL;
			}
			json_object_set_new(o, "targets", v);
		}
		json_array_append_new(figs, o);
	}
	return figs;
}

int
cmd_analyze_reach(struct cmd_ctx *c)
{
	struct analyze a;
	int slot[ENV_MAX_FIGURES];
	const char *family;
	int n = figures_of(c, slot, &family);
	if (n < 0 || read_analyze(c, &a) < 0)
		return -1;
	struct envelopes *s = a.want_envelope ? store(c) : NULL;
	if (a.want_envelope && !s)
		return -1;
	/* every name checked before anything is computed; nothing kept until all are made */
	char (*names)[ENVELOPE_NAME_MAX + MODEL_NAME_MAX + 2] = NULL;
	if (a.want_envelope) {
		if (!(names = calloc((size_t)n, sizeof *names)))
			return cmd_fail(c, "internal", "out of memory");
		int fresh = 0;
		for (int i = 0; i < n; i++) {
			envelope_name(c, &a, slot[i], family, names[i], sizeof names[i]);
			fresh += envelopes_find(s, names[i]) < 0;
			if (strlen(names[i]) >= ENVELOPE_NAME_MAX) {
				cmd_fail(c, "bad-argument", "the envelope's name '%.60s...' is too long "
					 "(name=)", names[i]);
				free(names);
				return -1;
			}
		}
		if (envelopes_count(s) + fresh > ENVELOPES_MAX) {
			free(names);
			return cmd_fail(c, "full", "%d envelopes are kept at most (remove envelope NAME)",
					ENVELOPES_MAX);
		}
	}
	struct envelope *es = a.want_envelope ? calloc((size_t)n, sizeof *es) : NULL;
	if (a.want_envelope && !es) {
		free(names);
		return cmd_fail(c, "internal", "out of memory");
	}
	int made = 0;
	while (es && made < n && compute_one(c, &a, slot[made], &es[made]) == 0)
		made++;
	static int reached[ENV_MAX_FIGURES][TARGETS_MAX]; /* the loop is single-threaded */
	json_t *figs = !es || made == n ? replies(c, &a, slot, n, family, es, reached) : NULL;
	if (!figs) {
		for (int i = 0; i < made; i++)
			envelope_free(&es[i]);
		free(es);
		free(names);
		return -1;
	}
	for (int i = 0; es && i < n; i++)
		envelopes_put(s, names[i], &c->d->env, slot[i], &es[i]); /* room checked above */
	free(es);
	free(names);
	if (!family) {
		json_object_update(c->result, json_array_get(figs, 0));
		json_decref(figs);
		return 0;
	}
	/* per target, the manikins that reach it: "which manikins reach the control" */
	json_t *by = json_array();
	for (int t = 0; t < a.ntarget; t++) {
		json_t *who = json_array();
		for (int i = 0; i < n; i++)
			if (reached[i][t])
				json_array_append_new(who, json_string(c->d->env.fig[slot[i]].name));
		json_array_append_new(by, json_pack("{s:o, s:o}", "target", cmd_vec(a.target[t], 3),
						    "reached_by", who));
	}
	json_object_set_new(c->result, "family", json_string(family));
	json_object_set_new(c->result, "figures", figs);
	if (a.ntarget)
		json_object_set_new(c->result, "targets", by);
	else
		json_decref(by);
	return 0;
}
