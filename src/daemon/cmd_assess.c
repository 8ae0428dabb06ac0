/*
 * cmd_assess.c - a human's posture assessed: its body angles (get angles),
 * RULA, REBA and OWAS with their whole derivation (assess rula|reba|owas,
 * of one figure or of each member of a family), and the thresholds the
 * methods leave open (set assess, get assess). The lifting equation is
 * cmd_niosh.c's.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assess/owas.h"
#include "assess/reba.h"
#include "assess/rula.h"
#include "daemon/assess_json.h"
#include "daemon/assess_live.h"
#include "daemon/cmd_ctx.h"
#include "daemon/family.h"

#define ASSESS_LOAD_MAX_KG 1000.0 /* a load a person's hands could hold, and then some */
#define REPLY_BUF (1024 * 1024)   /* a family's replies: up to 40 figures of a few KB */

/* the slot of a human named by ref, or -1 with the error set */
static int
human_of(struct cmd_ctx *c, const char *ref, const struct assess_live_fig **live)
{
	int fig = cmd_figure(c, ref);
	if (fig < 0)
		return -1;
	if (!(*live = assess_live_of(c->d, fig)))
		return cmd_fail(c, "bad-argument", "%s", assess_live_why(c->d, fig));
	return fig;
}

/*
 * The figures words[0] names: a figure, or "family=PREFIX" each member of
 * that family. n of them into slot; returns the prefix for a family (NULL
 * for a figure), with *n -1 and the error set when they do not resolve.
 */
static const char *
figures_of(struct cmd_ctx *c, const char *word, int slot[ENV_MAX_FIGURES], int *n)
{
	*n = -1;
	if (words_is_key(word, "family")) {
		const char *prefix = word + strlen("family=");
		int k = prefix[0] ? family_members(&c->d->env, prefix, slot) : 0;
		if (!k) {
			cmd_fail(c, "not-found", "no family '%.60s' (load family PREFIX sex=... makes one)",
				 prefix);
			return NULL;
		}
		*n = k;
		return prefix;
	}
	const struct assess_live_fig *live;
	if ((slot[0] = human_of(c, word, &live)) < 0)
		return NULL;
	*n = 1;
	return NULL;
}

/* "KEY=yes|no" when given: 0 (dest set, or left alone when absent), or -1 with the error set */
static int
yes_no(struct cmd_ctx *c, const char *key, int *dest)
{
	const char *v = cmd_key(c, key);
	if (!v)
		return 0;
	if (!strcmp(v, "yes") || !strcmp(v, "no")) {
		*dest = !strcmp(v, "yes");
		return 0;
	}
	return cmd_fail(c, "bad-argument", "%s: yes or no, not '%.20s'", key, v);
}

/* "side=left|right|worse" when given, into *dest (enum assess_side_choice) */
static int
side_of(struct cmd_ctx *c, int *dest)
{
	const char *v = cmd_key(c, "side");
	static const char *const names[] = { "left", "right", "worse" };
	if (!v)
		return 0;
	for (int i = 0; i < 3; i++)
		if (!strcmp(v, names[i])) {
			*dest = i;
			return 0;
		}
	return cmd_fail(c, "bad-argument", "side: left, right or worse, not '%.20s'", v);
}

/*
 * "load=KG" when given (a bare number, or with "kg"): 0 with *given set
 * and *kg the load, or -1 with the error set for anything but a mass from
 * 0 to ASSESS_LOAD_MAX_KG.
 */
static int
load_of(struct cmd_ctx *c, double *kg, int *given)
{
	const char *v = cmd_key(c, "load");
	*given = v != NULL;
	if (!v)
		return 0;
	char num[64];
	size_t n = strlen(v);
	if (n > 2 && !strcmp(v + n - 2, "kg"))
		n -= 2;
	if (n >= sizeof num)
		return cmd_fail(c, "bad-number", "load: a mass in kg");
	memcpy(num, v, n);
	num[n] = '\0';
	double m;
	if (words_number(num, UNIT_NONE, &m) < 0 || !(m >= 0 && m <= ASSESS_LOAD_MAX_KG))
		return cmd_fail(c, "bad-number", "load: a mass in kg from 0 to %.0f, not '%.30s'",
				ASSESS_LOAD_MAX_KG, v);
	*kg = m;
	return 0;
}

/* every argument after the figure is one of keys (NULL-terminated); else the error set */
static int
only_keys(struct cmd_ctx *c, const char *const *keys)
{
	for (int i = 1; i < c->argc; i++) {
		int ok = 0;
		for (const char *const *k = keys; *k && !ok; k++)
			ok = words_is_key(c->argv[i], *k);
		if (!ok) {
			char list[256] = "";
			for (const char *const *k = keys; *k; k++)
				snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s=", k == keys ? "" : ", ", *k);
			return cmd_fail(c, "bad-argument", "unexpected '%.60s' (this takes %s)", c->argv[i],
					list);
		}
	}
	return 0;
}

/* the options of a method read from the arguments, and what they were */
struct method_opts {
	enum assess_method method;
	struct rula_options rula;
	struct reba_options reba;
	struct owas_options owas;
	int load_given;
	double load_kg;
};

static const char *const rula_keys[] = { "side", "load", "static", "repeated", "arm_supported",
					 "legs_supported", "shock", NULL };
static const char *const reba_keys[] = { "side", "load", "coupling", "activity", "shock",
					 "arm_supported", NULL };
static const char *const owas_keys[] = { "load", NULL };

static int
read_opts(struct cmd_ctx *c, struct method_opts *o)
{
	static const char *const *keys[] = { rula_keys, reba_keys, owas_keys };
	if (only_keys(c, keys[o->method]) < 0 || load_of(c, &o->load_kg, &o->load_given) < 0)
		return -1;
	o->rula = rula_options_default();
	o->reba = reba_options_default();
	o->owas = (struct owas_options){ 0 };
	o->rula.side = o->reba.side = ASSESS_SIDE_WORSE;
	switch (o->method) {
	case ASSESS_RULA:
		return side_of(c, &o->rula.side) < 0 || yes_no(c, "static", &o->rula.static_posture) < 0 ||
				       yes_no(c, "repeated", &o->rula.repeated) < 0 ||
				       yes_no(c, "arm_supported", &o->rula.arm_supported) < 0 ||
				       yes_no(c, "legs_supported", &o->rula.legs_supported) < 0 ||
				       yes_no(c, "shock", &o->rula.shock) < 0
			       ? -1
			       : 0;
	case ASSESS_REBA: {
		static const char *const couplings[] = { "good", "fair", "poor", "unacceptable" };
		const char *cp = cmd_key(c, "coupling"), *act = cmd_key(c, "activity");
		if (side_of(c, &o->reba.side) < 0 || yes_no(c, "shock", &o->reba.shock) < 0 ||
		    yes_no(c, "arm_supported", &o->reba.arm_supported) < 0)
			return -1;
		if (cp) {
			int k = 0;
			while (k < 4 && strcmp(cp, couplings[k]))
				k++;
			if (k == 4)
				return cmd_fail(c, "bad-argument",
						"coupling: good, fair, poor or unacceptable, not '%.20s'", cp);
			o->reba.coupling = k;
		}
		double a;
		if (act && (words_number(act, UNIT_NONE, &a) < 0 || a != floor(a) || a < 0 || a > 3))
			return cmd_fail(c, "bad-number",
					"activity: 0 to 3, one for each of static, repeated, rapid change");
		if (act)
			o->reba.activity = (int)a;
		return 0;
	}
	case ASSESS_OWAS:
	case ASSESS_NMETHODS:
		break;
	}
	return 0;
}

/* the options as used for one figure (its held load unless load= was given), as JSON keys */
static void
inputs_json(struct jbuf *j, const struct method_opts *o, double load, int held)
{
	static const char *const sides[] = { "left", "right", "worse" };
	jbuf_key(j, "inputs", 0);
	jbuf_raw(j, "{");
	jbuf_key(j, "load_kg", 1);
	jbuf_num(j, load);
	jbuf_key(j, "load_from", 0);
	jbuf_str(j, o->load_given ? "load=" : held ? "held" : "none");
	switch (o->method) {
	case ASSESS_RULA:
		jbuf_key(j, "side", 0);
		jbuf_str(j, sides[o->rula.side]);
		jbuf_key(j, "static", 0);
		jbuf_bool(j, o->rula.static_posture);
		jbuf_key(j, "repeated", 0);
		jbuf_bool(j, o->rula.repeated);
		jbuf_key(j, "arm_supported", 0);
		jbuf_bool(j, o->rula.arm_supported);
		jbuf_key(j, "legs_supported", 0);
		jbuf_bool(j, o->rula.legs_supported);
		jbuf_key(j, "shock", 0);
		jbuf_bool(j, o->rula.shock);
		break;
	case ASSESS_REBA: {
		static const char *const couplings[] = { "good", "fair", "poor", "unacceptable" };
		jbuf_key(j, "side", 0);
		jbuf_str(j, sides[o->reba.side]);
		jbuf_key(j, "coupling", 0);
		jbuf_str(j, couplings[o->reba.coupling & 3]);
		jbuf_key(j, "activity", 0);
		jbuf_int(j, o->reba.activity);
		jbuf_key(j, "shock", 0);
		jbuf_bool(j, o->reba.shock);
		jbuf_key(j, "arm_supported", 0);
		jbuf_bool(j, o->reba.arm_supported);
		break;
	}
	case ASSESS_OWAS:
	case ASSESS_NMETHODS:
		break;
	}
	jbuf_raw(j, "}");
}

/* figure slot fig (a human) scored under o, its whole reply object into j */
static void
score_one(struct cmd_ctx *c, int fig, struct method_opts *o, struct jbuf *j)
{
	struct daemon *d = c->d;
	const struct assess_live_fig *live = assess_live_of(d, fig);
	struct assess_config cfg = daemon_assess_config(d);
	double load = o->load_given ? o->load_kg : live->load_kg;
	static struct assess_result r; /* 8 KB of derivation: kept off the stack */
	memset(&r, 0, sizeof r);
	switch (o->method) {
	case ASSESS_RULA:
		o->rula.load_kg = load;
		rula_score(&live->angles, &cfg, &o->rula, &r);
		break;
	case ASSESS_REBA:
		o->reba.load_kg = load;
		reba_score(&live->angles, &cfg, &o->reba, &r);
		break;
	case ASSESS_OWAS:
	case ASSESS_NMETHODS:
		o->owas.load_kg = load;
		owas_score(&live->angles, &cfg, &o->owas, &r);
		break;
	}
	jbuf_raw(j, "{");
	jbuf_key(j, "figure", 1);
	jbuf_str(j, d->env.fig[fig].name);
	jbuf_key(j, "method", 0);
	jbuf_str(j, assess_json_method(o->method));
	jbuf_key(j, "frame", 0);
	jbuf_int(j, (long long)d->stats.frame);
	assess_json_result_keys(j, &r, 0);
	inputs_json(j, o, load, live->load_kg > 0);
	jbuf_raw(j, "}");
}

static int
assess_method(struct cmd_ctx *c, enum assess_method m)
{
	struct method_opts o = { .method = m };
	int slot[ENV_MAX_FIGURES], n;
	const char *family = figures_of(c, c->argv[0], slot, &n);
	if (n < 0 || read_opts(c, &o) < 0)
		return -1;
	for (int i = 0; i < n; i++) /* a family's members are humans; checked all the same */
		if (!assess_live_of(c->d, slot[i]))
			return cmd_fail(c, "bad-argument", "%s", assess_live_why(c->d, slot[i]));
	struct jbuf j;
	if (jbuf_init(&j, REPLY_BUF) < 0)
		return cmd_fail(c, "internal", "out of memory");
	if (family) {
		jbuf_raw(&j, "{");
		jbuf_key(&j, "family", 1);
		jbuf_str(&j, family);
		jbuf_key(&j, "figures", 0);
		jbuf_raw(&j, "[");
		for (int i = 0; i < n; i++) {
			if (i)
				jbuf_raw(&j, ",");
			score_one(c, slot[i], &o, &j);
		}
		jbuf_raw(&j, "]}");
	} else {
		score_one(c, slot[0], &o, &j);
	}
	int rc = cmd_merge_json(c, c->result, &j);
	jbuf_free(&j);
	return rc;
}

int
cmd_assess_rula(struct cmd_ctx *c)
{
	return assess_method(c, ASSESS_RULA);
}

int
cmd_assess_reba(struct cmd_ctx *c)
{
	return assess_method(c, ASSESS_REBA);
}

int
cmd_assess_owas(struct cmd_ctx *c)
{
	return assess_method(c, ASSESS_OWAS);
}

int
cmd_get_angles(struct cmd_ctx *c)
{
	const struct assess_live_fig *live;
	int fig = human_of(c, c->argv[0], &live);
	if (fig < 0)
		return -1;
	struct jbuf j;
	if (jbuf_init(&j, 16384) < 0)
		return cmd_fail(c, "internal", "out of memory");
	jbuf_raw(&j, "{");
	jbuf_key(&j, "figure", 1);
	jbuf_str(&j, c->d->env.fig[fig].name);
	jbuf_key(&j, "frame", 0);
	jbuf_int(&j, (long long)c->d->stats.frame);
	jbuf_key(&j, "seated", 0);
	jbuf_bool(&j, live->angles.seated);
	jbuf_key(&j, "angles", 0);
	assess_json_angles(&j, &live->angles);
	jbuf_key(&j, "units", 0);
	jbuf_raw(&j, "{");
	for (size_t i = 0; i < body_angle_count; i++) {
		jbuf_key(&j, body_angle_names[i].name, i == 0);
		jbuf_str(&j, body_angle_names[i].unit);
	}
	jbuf_raw(&j, "}}");
	int rc = cmd_merge_json(c, c->result, &j);
	jbuf_free(&j);
	return rc;
}

/* ---- the settings --------------------------------------------------------------- */

static const struct assess_config_key *
config_key(const char *name, size_t len)
{
	for (size_t k = 0; k < assess_config_nkeys; k++)
		if (strlen(assess_config_keys[k].key) == len && !strncmp(assess_config_keys[k].key, name, len))
			return &assess_config_keys[k];
	return NULL;
}

static double
config_value(const struct assess_config *cfg, const struct assess_config_key *k)
{
	double v;
	memcpy(&v, (const char *)cfg + k->offset, sizeof v);
	return v;
}

/*
 * A value for key k: a bare number in the key's own unit (as get assess
 * lists it), or one with a unit of its kind (deg, rad; m, cm, mm)
 * converted to it. 0, or -1 when it is neither.
 */
static int
config_number(const struct assess_config_key *k, const char *s, double *dest)
{
	if (words_number(s, UNIT_NONE, dest) == 0)
		return 0;
	double v;
	if (!strcmp(k->unit, "deg") && words_number(s, UNIT_ANGLE, &v) == 0) {
		*dest = v * 180 / M_PI;
		return 0;
	}
	if (!strcmp(k->unit, "m") && words_number(s, UNIT_LENGTH, &v) == 0) {
		*dest = v;
		return 0;
	}
	return -1;
}

int
cmd_set_assess(struct cmd_ctx *c)
{
	struct assess_config cfg = daemon_assess_config(c->d);
	json_t *set = json_object();
	for (int i = 0; i < c->argc; i++) {
		size_t klen;
		const char *val = words_value(c->argv[i], &klen);
		const struct assess_config_key *k = val ? config_key(c->argv[i], klen) : NULL;
		char why[200];
		double v;
		int rc = 0;
		if (!val)
			rc = cmd_fail(c, "bad-argument", "KEY=VALUE, not '%.60s' (get assess lists the keys)",
				      c->argv[i]);
		else if (!k)
			rc = cmd_fail(c, "bad-argument", "no setting '%.*s' (get assess lists them)",
				      (int)(klen < 60 ? klen : 60), c->argv[i]);
		else if (config_number(k, val, &v) < 0)
			rc = cmd_fail(c, "bad-number", "%s: a number in %s%s, not '%.30s'", k->key, k->unit,
				      !strcmp(k->unit, "deg") ? " (or with deg, rad)"
				      : !strcmp(k->unit, "m") ? " (or with m, cm, mm)" : "",
				      val);
		else if (assess_config_set(&cfg, k->key, v, why, sizeof why) < 0)
			rc = cmd_fail(c, "bad-argument", "%s", why);
		if (rc < 0) {
			json_decref(set);
			return -1;
		}
		json_object_set_new(set, k->key, json_real(config_value(&cfg, k)));
	}
	daemon_set_assess_config(c->d, &cfg);
	json_object_set_new(c->result, "settings", set);
	return 0;
}

int
cmd_get_assess(struct cmd_ctx *c)
{
	struct assess_config cfg = daemon_assess_config(c->d), def = assess_config_default();
	json_t *all = json_object();
	for (size_t i = 0; i < assess_config_nkeys; i++) {
		const struct assess_config_key *k = &assess_config_keys[i];
		json_t *o = json_object();
		json_object_set_new(o, "value", json_real(config_value(&cfg, k)));
		json_object_set_new(o, "unit", json_string(k->unit));
		json_object_set_new(o, "min", json_real(k->min));
		json_object_set_new(o, "max", json_real(k->max));
		json_object_set_new(o, "default", json_real(config_value(&def, k)));
		json_object_set_new(o, "source", json_string(k->source));
		json_object_set_new(all, k->key, o);
	}
	json_object_set_new(c->result, "settings", all);
	return 0;
}
