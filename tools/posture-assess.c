/*
 * posture-assess - RULA, REBA and OWAS of observed postures, outside the
 * daemon: a video study's angle sets in, each method's whole derivation
 * out, one JSON line for each line in. The peer tests feed it the angle
 * sets they give ergonomics-metrics.
 */
#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assess/assess.h"
#include "assess/body_angles.h"
#include "assess/owas.h"
#include "assess/reba.h"
#include "assess/rula.h"

static const char usage[] =
	"usage: posture-assess [--set KEY=VALUE]... [rula] [reba] [owas]\n"
	"\n"
	"Reads JSON lines from standard input, each an observed posture:\n"
	"  {\"id\": ANY, \"angles\": {NAME: VALUE, ...}, \"options\": {KEY: VALUE, ...}}\n"
	"and writes one JSON line for each: {\"id\": ..., \"rula\": {...}, \"reba\": {...},\n"
	"\"owas\": {...}}, each method's score, action level and derivation (the parts with\n"
	"their angle, band and adjustments; the table look-ups). A line it cannot read is\n"
	"answered {\"id\": ..., \"error\": WHY}; the exit status is then 1.\n"
	"\n"
	"angles (degrees; metres; fractions; flags 0/1), named as `get angles` names them;\n"
	"missing ones are those of a person standing straight with the arms hanging:\n"
	"  trunk_flexion trunk_side_bend trunk_twist hip_trunk_angle (180)\n"
	"  neck_flexion neck_side_bend neck_twist seated (flag)\n"
	"  each arm, _l and _r: upper_arm_flexion upper_arm_abduction upper_arm_rotation\n"
	"    shoulder_elevation elbow_flexion wrist_flexion wrist_deviation wrist_twist\n"
	"    wrist_twist_fraction hand_across_midline (-0.2) hand_out_to_side\n"
	"    elbow_above_shoulder (-0.3) hand_above_shoulder (-0.6)\n"
	"  each leg, _l and _r: hip_flexion knee_flexion weight_share (0.5)\n"
	"    foot_on_floor (flag, 1) kneeling (flag)\n"
	"options: side left|right|worse, load KG, static, repeated, arm_supported,\n"
	"  legs_supported, shock (true|false), coupling good|fair|poor|unacceptable,\n"
	"  activity 0..3\n"
	"--set KEY=VALUE  one of the thresholds the methods leave open (`set assess`);\n"
	"  --set help lists them with their units, ranges and sources\n";

static struct body_angles
standing(void)
{
	struct body_angles a;
	memset(&a, 0, sizeof a);
	a.hip_trunk_angle = 180;
	for (int s = 0; s < 2; s++) {
		a.arm[s].hand_across_midline = -0.2;
		a.arm[s].elbow_above_shoulder = -0.3;
		a.arm[s].hand_above_shoulder = -0.6;
		a.leg[s].weight_share = 0.5;
		a.leg[s].foot_on_floor = 1;
	}
	return a;
}

struct options {
	struct rula_options rula;
	struct reba_options reba;
	struct owas_options owas;
};

static int
read_angles(json_t *obj, struct body_angles *a, char *err, size_t errlen)
{
	const char *key;
	json_t *v;
	json_object_foreach(obj, key, v) {
		int i = body_angle_find(key);
		if (i < 0) {
			snprintf(err, errlen, "unknown angle '%s'", key);
			return -1;
		}
		const struct body_angle_name *f = &body_angle_names[i];
		if (!json_is_number(v) && !(f->integer && json_is_boolean(v))) {
			snprintf(err, errlen, "angle '%s' is not a number", key);
			return -1;
		}
		double x = json_is_boolean(v) ? json_is_true(v) : json_number_value(v);
		if (!isfinite(x)) {
			snprintf(err, errlen, "angle '%s' is not finite", key);
			return -1;
		}
		if (f->integer)
			*(int *)((char *)a + f->offset) = x != 0;
		else
			*(double *)((char *)a + f->offset) = x;
	}
	a->legs_on_floor = a->leg[BODY_LEFT].foot_on_floor + a->leg[BODY_RIGHT].foot_on_floor;
	return 0;
}

static int
read_flag(json_t *v, const char *key, int *dest, char *err, size_t errlen)
{
	if (!json_is_boolean(v)) {
		snprintf(err, errlen, "option '%s' takes true or false", key);
		return -1;
	}
	*dest = json_is_true(v);
	return 0;
}

static int
read_options(json_t *obj, struct options *o, char *err, size_t errlen)
{
	static const char *const sides[3] = { "left", "right", "worse" };
	static const char *const couplings[4] = { "good", "fair", "poor", "unacceptable" };
	const char *key;
	json_t *v;
	json_object_foreach(obj, key, v) {
		int flag;
		if (!strcmp(key, "side")) {
			int s = -1;
			for (int i = 0; i < 3; i++)
				if (json_is_string(v) && !strcmp(json_string_value(v), sides[i]))
					s = i;
			if (s < 0) {
				snprintf(err, errlen, "side is left, right or worse");
				return -1;
			}
			o->rula.side = o->reba.side = s;
		} else if (!strcmp(key, "load")) {
			double kg = json_is_number(v) ? json_number_value(v) : -1;
			if (!(kg >= 0 && kg < 1e6)) {
				snprintf(err, errlen, "load is a number of kg >= 0");
				return -1;
			}
			o->rula.load_kg = o->reba.load_kg = o->owas.load_kg = kg;
		} else if (!strcmp(key, "coupling")) {
			int c = -1;
			for (int i = 0; i < 4; i++)
				if (json_is_string(v) && !strcmp(json_string_value(v), couplings[i]))
					c = i;
			if (c < 0) {
				snprintf(err, errlen, "coupling is good, fair, poor or unacceptable");
				return -1;
			}
			o->reba.coupling = c;
		} else if (!strcmp(key, "activity")) {
			json_int_t n = json_is_integer(v) ? json_integer_value(v) : -1;
			if (n < 0 || n > 3) {
				snprintf(err, errlen, "activity is 0 to 3");
				return -1;
			}
			o->reba.activity = (int)n;
		} else if (!strcmp(key, "static")) {
			if (read_flag(v, key, &o->rula.static_posture, err, errlen) < 0)
				return -1;
		} else if (!strcmp(key, "repeated")) {
			if (read_flag(v, key, &o->rula.repeated, err, errlen) < 0)
				return -1;
		} else if (!strcmp(key, "arm_supported")) {
			if (read_flag(v, key, &flag, err, errlen) < 0)
				return -1;
			o->rula.arm_supported = o->reba.arm_supported = flag;
		} else if (!strcmp(key, "legs_supported")) {
			if (read_flag(v, key, &o->rula.legs_supported, err, errlen) < 0)
				return -1;
		} else if (!strcmp(key, "shock")) {
			if (read_flag(v, key, &flag, err, errlen) < 0)
				return -1;
			o->rula.shock = o->reba.shock = flag;
		} else {
			snprintf(err, errlen, "unknown option '%s'", key);
			return -1;
		}
	}
	return 0;
}

static json_t *
number_or_null(double x)
{
	return isfinite(x) ? json_real(x) : json_null();
}

/* a result as the derivation a person checks by hand */
static json_t *
derivation(const struct assess_result *r)
{
	static const char *const sides[2] = { "left", "right" };
	json_t *d = json_object(), *parts = json_object(), *tables = json_object();
	json_t *lookups = json_object();
	json_object_set_new(d, "score", json_integer(r->score));
	json_object_set_new(d, "action_level", json_integer(r->action_level));
	json_object_set_new(d, "action", json_string(r->action));
	json_object_set_new(d, "side", r->side == ASSESS_SIDE_LEFT || r->side == ASSESS_SIDE_RIGHT ?
					       json_string(sides[r->side]) : json_null());
	if (r->code[0])
		json_object_set_new(d, "code", json_string(r->code));
	json_object_set_new(d, "worst", r->worst >= 0 ? json_string(r->part[r->worst].name) :
							json_null());
	for (int i = 0; i < r->nparts; i++) {
		const struct assess_part *p = &r->part[i];
		json_t *jp = json_object(), *adj = json_array();
		json_object_set_new(jp, "angle", number_or_null(p->angle));
		json_object_set_new(jp, "angle_name", p->angle_name ? json_string(p->angle_name) :
								    json_null());
		json_object_set_new(jp, "band", json_string(p->band));
		json_object_set_new(jp, "base", json_integer(p->base));
		for (int k = 0; k < p->nadj; k++)
			json_array_append_new(adj, json_pack("{s:i,s:s}", "value", p->adj[k].value,
							     "reason", p->adj[k].reason));
		json_object_set_new(jp, "adjustments", adj);
		json_object_set_new(jp, "score", json_integer(p->score));
		json_object_set_new(jp, "max", json_integer(p->max));
		json_object_set_new(jp, "body", json_boolean(p->body));
		json_object_set_new(parts, p->name, jp);
	}
	for (int i = 0; i < r->nlookups; i++) {
		const struct assess_lookup *l = &r->lookup[i];
		json_t *idx = json_object();
		for (int k = 0; k < l->nidx; k++)
			json_object_set_new(idx, l->idx_name[k], json_integer(l->idx[k]));
		json_object_set_new(tables, l->table, json_integer(l->value));
		json_object_set_new(lookups, l->table, json_pack("{s:i,s:o}", "value", l->value,
								  "index", idx));
	}
	json_object_set_new(d, "parts", parts);
	json_object_set_new(d, "tables", tables);
	json_object_set_new(d, "lookups", lookups);
	return d;
}

static int
config_arg(struct assess_config *cfg, const char *arg)
{
	char key[64], err[256];
	const char *eq = strchr(arg, '=');
	if (!strcmp(arg, "help")) {
		for (size_t i = 0; i < assess_config_nkeys; i++) {
			const struct assess_config_key *k = &assess_config_keys[i];
			printf("%s=%g %s (%g..%g): %s\n", k->key,
			       *(const double *)((const char *)cfg + k->offset), k->unit, k->min, k->max,
			       k->source);
		}
		exit(0);
	}
	if (!eq || (size_t)(eq - arg) >= sizeof key) {
		fprintf(stderr, "posture-assess: --set takes KEY=VALUE\n");
		return -1;
	}
	memcpy(key, arg, (size_t)(eq - arg));
	key[eq - arg] = 0;
	char *end;
	errno = 0;
	double v = strtod(eq + 1, &end);
	if (end == eq + 1 || *end || errno) {
		fprintf(stderr, "posture-assess: --set %s: '%s' is not a number\n", key, eq + 1);
		return -1;
	}
	if (assess_config_set(cfg, key, v, err, sizeof err) < 0) {
		fprintf(stderr, "posture-assess: --set: %s\n", err);
		return -1;
	}
	return 0;
}

int
main(int argc, char **argv)
{
	struct assess_config cfg = assess_config_default();
	int want[3] = { 0, 0, 0 }, any = 0;
	for (int i = 1; i < argc; i++) {
		if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
			fputs(usage, stdout);
			return 0;
		} else if (!strcmp(argv[i], "--set") && i + 1 < argc) {
			if (config_arg(&cfg, argv[++i]) < 0)
				return 2;
		} else if (!strcmp(argv[i], "rula") || !strcmp(argv[i], "reba") ||
			   !strcmp(argv[i], "owas")) {
			want[argv[i][1] == 'u' ? 0 : argv[i][1] == 'e' ? 1 : 2] = any = 1;
		} else {
			fprintf(stderr, "posture-assess: bad argument '%s'\n%s", argv[i], usage);
			return 2;
		}
	}
	if (!any)
		want[0] = want[1] = want[2] = 1;
	char *line = NULL;
	size_t cap = 0;
	long lineno = 0;
	int rc = 0;
	struct assess_result r;
	while (getline(&line, &cap, stdin) > 0) {
		lineno++;
		char err[256] = "";
		json_error_t jerr;
		json_t *in = json_loads(line, 0, &jerr), *out = json_object();
		json_t *id = json_is_object(in) ? json_object_get(in, "id") : NULL;
		if (id)
			json_object_set(out, "id", id);
		struct body_angles a = standing();
		struct options o = { rula_options_default(), reba_options_default(), { 0 } };
		json_t *angles = json_is_object(in) ? json_object_get(in, "angles") : NULL;
		json_t *opts = json_is_object(in) ? json_object_get(in, "options") : NULL;
		if (!in)
			snprintf(err, sizeof err, "not JSON: %s", jerr.text);
		else if (!json_is_object(in))
			snprintf(err, sizeof err, "a line is a JSON object");
		else if (angles && !json_is_object(angles))
			snprintf(err, sizeof err, "angles is an object");
		else if (opts && !json_is_object(opts))
			snprintf(err, sizeof err, "options is an object");
		else if (angles && read_angles(angles, &a, err, sizeof err) < 0)
			;
		else if (opts && read_options(opts, &o, err, sizeof err) < 0)
			;
		else
			a.legs_on_floor = a.leg[BODY_LEFT].foot_on_floor + a.leg[BODY_RIGHT].foot_on_floor;
		if (err[0]) {
			fprintf(stderr, "posture-assess: line %ld: %s\n", lineno, err);
			json_object_set_new(out, "error", json_string(err));
			rc = 1;
		} else {
			if (want[0]) {
				rula_score(&a, &cfg, &o.rula, &r);
				json_object_set_new(out, "rula", derivation(&r));
			}
			if (want[1]) {
				reba_score(&a, &cfg, &o.reba, &r);
				json_object_set_new(out, "reba", derivation(&r));
			}
			if (want[2]) {
				owas_score(&a, &cfg, &o.owas, &r);
				json_object_set_new(out, "owas", derivation(&r));
			}
		}
		char *text = json_dumps(out, JSON_COMPACT);
		if (text)
			puts(text);
		free(text);
		json_decref(out);
		json_decref(in);
	}
	free(line);
	return rc;
}
