/*
 * cmd_niosh.c - the revised NIOSH lifting equation over the protocol: a
 * task given by its numbers, a task measured on a human at two saved
 * postures (origin and destination, on a copy of its state: nothing shown
 * changes), and a job of several tasks (the composite lifting index).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assess/niosh.h"
#include "assess/niosh_measure.h"
#include "daemon/assess_live.h"
#include "daemon/cmd_ctx.h"
#include "daemon/session.h"
#include "figure/kin.h"

#define NIOSH_LOAD_MAX_KG 1000.0 /* the largest load taken */
#define TASK_WORDS 16           /* KEY=VALUE items of one task of niosh-multi */

static const char *const couplings[] = { "good", "fair", "poor" };
/* enum niosh_limit's bits, named as the reply lists them */
static const char *const limit_keys[NIOSH_NLIMITS] = { "h_raised", "h_beyond", "v_beyond",
							"d_raised", "d_beyond", "a_beyond",
							"f_raised", "f_beyond" };

/* the words of a task: KEY=VALUE items (a command's arguments, or one task word's) */
struct task_words {
	int n;
	char *w[TASK_WORDS];
};

static const char *
item(const struct task_words *t, const char *key)
{
	for (int i = 0; i < t->n; i++)
		if (words_is_key(t->w[i], key))
			return t->w[i] + strlen(key) + 1;
	return NULL;
}

/* a length with its unit (m, cm, mm), in cm: a bare number could be either */
static int
length_cm(struct cmd_ctx *c, const struct task_words *t, const char *key, double *dest, int need)
{
	const char *v = item(t, key);
	double m;
	if (!v)
		return need ? cmd_fail(c, "bad-argument", "%s= missing: a length such as 40cm", key) : 0;
	if (words_number(v, UNIT_NONE, &m) == 0)
		return cmd_fail(c, "bad-number", "%s: a length with its unit (40cm, 0.4m, 400mm), not '%.30s'",
				key, v);
	if (words_number(v, UNIT_LENGTH, &m) < 0 || m < 0 || m > 100)
		return cmd_fail(c, "bad-number", "%s: a length from 0 to 100 m with its unit, not '%.30s'",
				key, v);
	*dest = m * 100;
	return 0;
}

/* a plain number from lo to hi (a mass may end in "kg") */
static int
number(struct cmd_ctx *c, const struct task_words *t, const char *key, double lo, double hi,
       const char *what, double *dest, int need)
{
	const char *v = item(t, key);
	if (!v)
		return need ? cmd_fail(c, "bad-argument", "%s= missing: %s", key, what) : 0;
	char num[64];
	size_t n = strlen(v);
	if (strstr(what, " kg") && n > 2 && !strcmp(v + n - 2, "kg"))
		n -= 2;
	double x;
	if (n >= sizeof num)
		return cmd_fail(c, "bad-number", "%s: %s", key, what);
	memcpy(num, v, n);
	num[n] = '\0';
	if (words_number(num, UNIT_NONE, &x) < 0 || !(x >= lo && x <= hi))
		return cmd_fail(c, "bad-number", "%s: %s, not '%.30s'", key, what, v);
	*dest = x;
	return 0;
}

/* every item is one of keys (NULL-terminated) */
static int
only(struct cmd_ctx *c, const struct task_words *t, const char *const *keys, const char *form)
{
	for (int i = 0; i < t->n; i++) {
		int ok = 0;
		for (const char *const *k = keys; *k && !ok; k++)
			ok = words_is_key(t->w[i], *k);
		if (!ok)
			return cmd_fail(c, "bad-argument", "unexpected '%.60s' (%s)", t->w[i], form);
	}
	return 0;
}

/* F, duration and coupling, and the load when need_load */
static int
task_common(struct cmd_ctx *c, const struct task_words *t, struct niosh_task *k, int need_load,
	    int with_duration)
{
	double dur = 0;
	if (number(c, t, "F", 0, 1000, "lifts per minute (0 to 1000)", &k->freq, 1) < 0 ||
	    number(c, t, "load", 0, NIOSH_LOAD_MAX_KG, "a mass in kg (0 to 1000 kg)", &k->load_kg,
		   need_load) < 0)
		return -1;
	if (with_duration && number(c, t, "duration", 1, 8, "1, 2 or 8 (hours of the category)", &dur,
				    1) < 0)
		return -1;
	if (with_duration && dur != 1 && dur != 2 && dur != 8)
		return cmd_fail(c, "bad-argument", "duration: 1, 2 or 8 (hours of the category)");
	k->duration_h = (int)dur;
	const char *cp = item(t, "coupling");
	if (!cp)
		return cmd_fail(c, "bad-argument", "coupling= missing: good, fair or poor");
	int i = 0;
	while (i < 3 && strcmp(cp, couplings[i]))
		i++;
	if (i == 3)
		return cmd_fail(c, "bad-argument", "coupling: good, fair or poor, not '%.20s'", cp);
	k->coupling = (enum niosh_coupling)i;
	return 0;
}

/* the asymmetry angle: degrees, bare or with deg or rad */
static int
angle_deg(struct cmd_ctx *c, const struct task_words *t, double *dest)
{
	const char *v = item(t, "A");
	double x;
	*dest = 0; /* a lift in the sagittal plane unless said */
	if (!v)
		return 0;
	if (words_number(v, UNIT_NONE, &x) == 0)
		*dest = x;
	else if (words_number(v, UNIT_ANGLE, &x) == 0)
		*dest = x * 180 / M_PI;
	else
		return cmd_fail(c, "bad-number", "A: an angle in degrees (30, 30deg), not '%.30s'", v);
	if (!(*dest >= 0 && *dest <= 180))
		return cmd_fail(c, "bad-number", "A: from 0 to 180 degrees, not '%.30s'", v);
	return 0;
}

/* a task given by its numbers (H, V, D, A, F, coupling, load; duration when with_duration) */
static int
task_of(struct cmd_ctx *c, const struct task_words *t, struct niosh_task *k, int with_duration)
{
	static const char *const keys[] = { "H", "V", "D", "A", "F", "duration", "coupling", "load",
					    "load_max", NULL };
	memset(k, 0, sizeof *k);
	if (only(c, t, keys, with_duration ? "H= V= D= A= F= duration= coupling= load="
					    : "H= V= D= A= F= coupling= load= load_max=") < 0 ||
	    length_cm(c, t, "H", &k->h_cm, 1) < 0 || length_cm(c, t, "V", &k->v_cm, 1) < 0 ||
	    length_cm(c, t, "D", &k->d_cm, 1) < 0 || angle_deg(c, t, &k->a_deg) < 0 ||
	    task_common(c, t, k, 1, with_duration) < 0 ||
	    number(c, t, "load_max", 0, NIOSH_LOAD_MAX_KG, "a mass in kg (0 to 1000 kg)",
		   &k->load_max_kg, 0) < 0)
		return -1;
	if (with_duration && item(t, "load_max"))
		return cmd_fail(c, "bad-argument", "load_max: a task of a job's (assess niosh-multi)");
	k->v_origin_cm = k->v_cm; /* the end given is the origin */
	return 0;
}

static json_t *
limits_json(unsigned bits)
{
	json_t *a = json_array();
	for (unsigned i = 0; i < NIOSH_NLIMITS; i++)
		if (bits & (1u << i))
			json_array_append_new(a, json_pack("{ssss}", "limit", limit_keys[i], "what",
							   niosh_limit_name(1u << i, NIOSH_METRIC)));
	return a;
}

/* a real, or null when it is not finite (an LI with an RWL of 0) */
static json_t *
real_or_null(double v)
{
	return isfinite(v) ? json_real(v) : json_null();
}

static void
result_json(json_t *o, const struct niosh_result *r)
{
	json_object_set_new(o, "rwl", json_real(r->rwl));
	json_object_set_new(o, "li", real_or_null(r->li));
	json_object_set_new(o, "hm", json_real(r->hm));
	json_object_set_new(o, "vm", json_real(r->vm));
	json_object_set_new(o, "dm", json_real(r->dm));
	json_object_set_new(o, "am", json_real(r->am));
	json_object_set_new(o, "fm", json_real(r->fm));
	json_object_set_new(o, "cm", json_real(r->cm));
	json_object_set_new(o, "limits", limits_json(r->limits));
}

static void
task_inputs(json_t *o, const struct niosh_task *k)
{
	json_object_set_new(o, "h_cm", json_real(k->h_cm));
	json_object_set_new(o, "v_cm", json_real(k->v_cm));
	json_object_set_new(o, "d_cm", json_real(k->d_cm));
	json_object_set_new(o, "a_deg", json_real(k->a_deg));
	json_object_set_new(o, "f", json_real(k->freq));
	json_object_set_new(o, "duration_h", json_integer(k->duration_h));
	json_object_set_new(o, "coupling", json_string(couplings[k->coupling]));
	json_object_set_new(o, "load_kg", json_real(k->load_kg));
}

/* figure slot fig at the posture in file rel (on a copy of its state): H, V and A */
static int
measure_at(struct cmd_ctx *c, int fig, const char *rel, struct state *copy,
	   struct niosh_geometry *g)
{
	const struct env_figure *f = &c->d->env.fig[fig];
	size_t len;
	char *text = cmd_read_file(c, rel, &len);
	if (!text)
		return -1;
	char err[300];
	state_copy(f->model, f->state, copy);
	int rc = session_posture_onto(f->model, f->is_human, copy, text, len, err, sizeof err);
	free(text);
	if (rc < 0)
		return cmd_fail(c, "bad-file", "%.60s: %s", rel, err);
	if (niosh_measure(f->model, copy, g, err, sizeof err) < 0)
		return cmd_fail(c, "bad-argument", "%s at %.60s: %s", f->name, rel, err);
	return 0;
}

/* the task form: FIG origin=POSTURE dest=POSTURE F= duration= coupling= [load=] [control=] */
static int
niosh_task_form(struct cmd_ctx *c, const struct task_words *t)
{
	static const char *const keys[] = { "origin", "dest", "F", "duration", "coupling", "load",
					    "control", NULL };
	struct daemon *d = c->d;
	int fig = cmd_figure(c, c->argv[0]);
	if (fig < 0)
		return -1;
	const struct env_figure *f = &d->env.fig[fig];
	if (!f->is_human)
		return cmd_fail(c, "bad-argument", "%s is not a human figure: the task is measured at its "
				"hands and ankles", f->name);
	const char *origin = item(t, "origin"), *dest = item(t, "dest"), *ctl = item(t, "control");
	struct niosh_task k = { 0 };
	if (only(c, t, keys, "FIG origin= dest= F= duration= coupling= load= control=") < 0)
		return -1;
	if (!origin || !dest)
		return cmd_fail(c, "bad-argument", "origin=POSTURE and dest=POSTURE: the saved postures "
				"the lift begins and ends at");
	if (ctl && strcmp(ctl, "yes") && strcmp(ctl, "no"))
		return cmd_fail(c, "bad-argument", "control: yes or no, not '%.20s'", ctl);
	int control = ctl && !strcmp(ctl, "yes");
	/* the load: load=, else what the hands hold (grab) */
	double held = assess_live_held_kg(&d->env, fig);
	if (task_common(c, t, &k, held <= 0, 1) < 0)
		return -1;
	int load_given = item(t, "load") != NULL;
	if (!load_given)
		k.load_kg = held;
	struct state *copy = state_make(f->model);
	if (!copy)
		return cmd_fail(c, "internal", "out of memory");
	struct niosh_geometry go, gd;
	int rc = measure_at(c, fig, origin, copy, &go);
	if (rc == 0)
		rc = measure_at(c, fig, dest, copy, &gd);
	state_free(copy);
	if (rc < 0)
		return -1;
	struct niosh_task at[2] = { k, k };
	struct niosh_result r[2];
	const struct niosh_geometry *g[2] = { &go, &gd };
	char err[200];
	for (int i = 0; i < 2; i++) {
		at[i].h_cm = g[i]->h_cm;
		at[i].v_cm = g[i]->v_cm;
		at[i].a_deg = g[i]->a_deg;
		at[i].d_cm = fabs(gd.v_cm - go.v_cm);
		at[i].v_origin_cm = go.v_cm; /* FM reads V at the origin (p. 15) */
		if (niosh_compute(&at[i], &r[i], err, sizeof err) < 0)
			return cmd_fail(c, "bad-argument", "%s", err);
	}
	/* the destination governs only when control is needed there and its RWL is lower */
	int end = control && r[1].rwl < r[0].rwl;
	static const char *const names[] = { "origin", "destination" };
	for (int i = 0; i < 2; i++) {
		json_t *o = json_object();
		json_object_set_new(o, "posture", json_string(i ? dest : origin));
		task_inputs(o, &at[i]);
		result_json(o, &r[i]);
		json_object_set_new(c->result, names[i], o);
	}
	json_object_set_new(c->result, "figure", json_string(f->name));
	json_object_set_new(c->result, "d_cm", json_real(at[0].d_cm));
	json_object_set_new(c->result, "load_kg", json_real(k.load_kg));
	json_object_set_new(c->result, "load_from", json_string(load_given ? "load=" : "held"));
	json_object_set_new(c->result, "control", json_boolean(control));
	json_object_set_new(c->result, "governs", json_string(names[end]));
	json_object_set_new(c->result, "rwl", json_real(r[end].rwl));
	json_object_set_new(c->result, "li", real_or_null(r[end].li));
	return 0;
}

int
cmd_assess_niosh(struct cmd_ctx *c)
{
	struct task_words t = { 0 };
	int task_form = !strchr(c->argv[0], '=');
	for (int i = task_form; i < c->argc && t.n < TASK_WORDS; i++)
		t.w[t.n++] = c->argv[i];
	if (task_form)
		return niosh_task_form(c, &t);
	struct niosh_task k;
	struct niosh_result r;
	char err[200];
	if (task_of(c, &t, &k, 1) < 0)
		return -1;
	if (niosh_compute(&k, &r, err, sizeof err) < 0)
		return cmd_fail(c, "bad-argument", "%s", err);
	result_json(c->result, &r);
	json_t *in = json_object();
	task_inputs(in, &k);
	json_object_set_new(c->result, "inputs", in);
	return 0;
}

/*
 * assess niosh-multi duration=1|2|8 TASK...: each TASK one word of
 * KEY=VALUE items joined by commas, "H=40cm,V=70cm,D=50cm,A=0,F=2,
 * coupling=fair,load=10[,load_max=12]".
 */
int
cmd_assess_niosh_multi(struct cmd_ctx *c)
{
	struct niosh_task k[NIOSH_MAX_TASKS];
	char words[NIOSH_MAX_TASKS][1024];
	double dur = 0;
	int n = 0, have_duration = 0;
	for (int i = 0; i < c->argc; i++) {
		if (words_is_key(c->argv[i], "duration")) {
			struct task_words one = { 1, { c->argv[i] } };
			if (number(c, &one, "duration", 1, 8, "1, 2 or 8 (hours of the category)", &dur,
				   1) < 0)
				return -1;
			if (dur != 1 && dur != 2 && dur != 8)
				return cmd_fail(c, "bad-argument", "duration: 1, 2 or 8 (hours of the category)");
			have_duration = 1;
			continue;
		}
		if (n == NIOSH_MAX_TASKS)
			return cmd_fail(c, "bad-argument", "at most %d tasks in a job", NIOSH_MAX_TASKS);
		if (strlen(c->argv[i]) >= sizeof words[n])
			return cmd_fail(c, "bad-argument", "task %d: too long", n + 1);
		strcpy(words[n], c->argv[i]);
		struct task_words t = { 0 };
		for (char *p = words[n], *comma; p && t.n < TASK_WORDS; p = comma) {
			comma = strchr(p, ',');
			if (comma)
				*comma++ = '\0';
			if (!*p)
				return cmd_fail(c, "bad-argument", "task %d: an empty item", n + 1);
			t.w[t.n++] = p;
		}
		if (task_of(c, &t, &k[n], 0) < 0) {
			char why[sizeof c->msg];
			snprintf(why, sizeof why, "%s", c->msg);
			return cmd_fail(c, c->code, "task %d: %s", n + 1, why);
		}
		n++;
	}
	if (!have_duration)
		return cmd_fail(c, "bad-argument", "duration= missing: 1, 2 or 8 (hours of the job's category)");
	if (!n)
		return cmd_fail(c, "bad-argument", "no task: each is one word H=..,V=..,D=..,F=..,"
				"coupling=..,load=..");
	for (int i = 0; i < n; i++)
		k[i].duration_h = (int)dur;
	struct niosh_multi_result m;
	char err[200];
	if (niosh_composite(k, n, &m, err, sizeof err) < 0)
		return cmd_fail(c, "bad-argument", "%s", err);
	json_t *tasks = json_array(), *order = json_array();
	for (int i = 0; i < n; i++) {
		json_t *o = json_object();
		task_inputs(o, &k[i]);
		json_object_set_new(o, "load_max_kg", json_real(k[i].load_max_kg > 0 ? k[i].load_max_kg
										      : k[i].load_kg));
		json_object_set_new(o, "firwl", json_real(m.firwl[i]));
		json_object_set_new(o, "strwl", json_real(m.strwl[i]));
		json_object_set_new(o, "fili", real_or_null(m.fili[i]));
		json_object_set_new(o, "stli", real_or_null(m.stli[i]));
		json_object_set_new(o, "fm", json_real(m.fm[i]));
		json_array_append_new(tasks, o);
		json_t *step = json_object();
		json_object_set_new(step, "task", json_integer(m.order[i] + 1));
		json_object_set_new(step, "fm_sum", json_real(m.fm_sum[i]));
		json_array_append_new(order, step);
	}
	json_object_set_new(c->result, "cli", real_or_null(m.cli));
	json_object_set_new(c->result, "duration_h", json_integer((int)dur));
	json_object_set_new(c->result, "tasks", tasks);
	json_object_set_new(c->result, "order", order);
	return 0;
}
