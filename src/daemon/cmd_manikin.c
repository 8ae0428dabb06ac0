/*
 * cmd_manikin.c - humans of real sizes: the standard human, manikins from
 * measures, percentiles and populations, populations loaded from files,
 * and families of boundary manikins.
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/manikin.h"
#include "figure/kin.h"
#include "figure/mvn.h"
#include "figure/population_csv.h"

/* "sex=male|female" (both: 2) among the args: the sex, -1 with the error set; def when absent */
static int
sex_of(struct cmd_ctx *c, int def, int both)
{
	const char *sex = cmd_key(c, "sex");
	if (!sex)
		return def;
	if (!strcmp(sex, "male"))
		return HUMAN_MALE;
	if (!strcmp(sex, "female"))
		return HUMAN_FEMALE;
	if (both && !strcmp(sex, "both"))
		return 2;
	return cmd_fail(c, "bad-argument", both ? "sex is female, male or both" : "sex is male or female");
}

static const struct population *
population_of(struct cmd_ctx *c, const char **name)
{
	const char *pop = cmd_key(c, "population");
	*name = pop ? pop : POPULATIONS_BUILTIN;
	const struct population *p = populations_find(&c->d->pops, *name);
	if (!p)
		cmd_fail(c, "not-found", "no population '%.60s' (ansur2 is built in; load population NAME PATH)",
			 *name);
	return p;
}

/*
 * A measure's value: millimetres, or a length with its unit (175cm, 1.75m);
 * weightkg in kilograms. Within population_bounds. 0, or -1 with the error set.
 */
static int
measure_value(struct cmd_ctx *c, int col, const char *s, double *dest)
{
	const char *name = population_column_name(col);
	int kg = !strcmp(name, "weightkg");
	size_t n = strlen(s);
	int unit = n && isalpha((unsigned char)s[n - 1]);
	if (kg ? words_number(s, UNIT_NONE, dest) < 0
	       : words_number(s, unit ? UNIT_LENGTH : UNIT_NONE, dest) < 0)
		return cmd_fail(c, "bad-number", "%s: %s", name,
				kg ? "kilograms, a number" : "millimetres, or a length such as 17cm");
	if (!kg && unit)
		*dest *= 1000;
	double lo, hi;
	population_bounds(col, &lo, &hi);
	if (!(*dest >= lo && *dest <= hi))
		return cmd_fail(c, "bad-argument", "%s %g %s is outside %g to %g (half ANSUR II's smallest "
				"to twice its largest)", name, *dest, kg ? "kg" : "mm", lo, hi);
	return 0;
}

/* the legacy human: stature, mass and sex alone (the build's own proportions) */
static int
plain_human(struct cmd_ctx *c, const char *name, int sex)
{
	struct human_def hd = human_default_def((enum human_sex)sex);
	const char *st = cmd_key(c, "stature"), *ms = cmd_key(c, "mass");
	if (st && words_number(st, UNIT_LENGTH, &hd.stature) < 0)
		return cmd_fail(c, "bad-number", "stature: a length such as 1.75 or 175cm");
	if (ms && words_number(ms, UNIT_NONE, &hd.mass) < 0)
		return cmd_fail(c, "bad-number", "mass: kilograms, a number");
	char err[256];
	struct model *m = human_build(&hd, err, sizeof err);
	if (!m)
		return cmd_fail(c, "bad-argument", "%s", err);
	int slot = env_add_figure(&c->d->env, m, name, 1, &hd, NULL);
	return cmd_added(c, slot, name);
}

int
cmd_load_human(struct cmd_ctx *c)
{
	int bad, sex = sex_of(c, HUMAN_MALE, 0);
	const char *name = cmd_as_name(c, &bad);
	if (bad || sex < 0)
		return -1;
	/* every argument must be one of ours; measures are the population's columns */
	int measures = 0;
	for (int i = 0; i < c->argc; i++) {
		const char *a = c->argv[i];
		size_t klen;
		if (!strcmp(a, "as")) {
			i++;
			continue;
		}
		const char *v = words_value(a, &klen);
		char key[64];
		if (!v || klen >= sizeof key)
			return cmd_fail(c, "bad-argument", "unexpected '%.60s'", a);
		memcpy(key, a, klen);
		key[klen] = 0;
		if (!strcmp(key, "sex") || !strcmp(key, "stature") || !strcmp(key, "mass") ||
		    !strcmp(key, "population") || !strcmp(key, "percentile"))
			continue;
		if (population_column(key) < 0)
			return cmd_fail(c, "bad-argument", "unexpected '%.60s' (measures are ANSUR II's "
					"names, e.g. sittingheight=900)", a);
		measures++;
	}
	const char *pct_word = cmd_key(c, "percentile");
	if (!measures && !pct_word && !cmd_key(c, "population"))
		return plain_human(c, name, sex);

	/* a manikin: the given measures, the rest predicted by the population */
	const char *pname;
	const struct population *p = population_of(c, &pname);
	if (!p)
		return -1;
	int cols[POPULATION_NCOL], k = 0;
	double vals[POPULATION_NCOL], pct = NAN;
	const int stature = population_column("stature"), weight = population_column("weightkg");
	struct human_def hd = human_default_def((enum human_sex)sex);
	hd.measure_given = 0;
	char err[512];
	for (int i = 0; i < c->argc; i++) {
		const char *a = c->argv[i];
		size_t klen;
		if (!strcmp(a, "as")) {
			i++;
			continue;
		}
		const char *v = words_value(a, &klen);
		char key[64];
		memcpy(key, a, klen);
		key[klen] = 0;
		int col = -1;
		double x;
		if (!strcmp(key, "stature")) {
			if (words_number(v, UNIT_LENGTH, &x) < 0)
				return cmd_fail(c, "bad-number", "stature: a length such as 1.75 or 175cm");
			if (!(x >= HUMAN_STATURE_MIN && x <= HUMAN_STATURE_MAX))
				return cmd_fail(c, "bad-argument", "stature %g m is outside %.1f to %.1f m", x,
						HUMAN_STATURE_MIN, HUMAN_STATURE_MAX);
			col = stature;
			x *= 1000;
		} else if (!strcmp(key, "mass")) {
			if (words_number(v, UNIT_NONE, &x) < 0)
				return cmd_fail(c, "bad-number", "mass: kilograms, a number");
			if (!(x >= HUMAN_MASS_MIN && x <= HUMAN_MASS_MAX))
				return cmd_fail(c, "bad-argument", "mass %g kg is outside %.0f to %.0f kg", x,
						HUMAN_MASS_MIN, HUMAN_MASS_MAX);
			col = weight;
		} else if (!strcmp(key, "percentile")) {
			if (words_number(v, UNIT_NONE, &pct) < 0 || pct < 0 || pct > 100)
				return cmd_fail(c, "bad-number", "percentile: 0 to 100");
			if (population_percentile(p, (enum human_sex)sex, pct, &x, err, sizeof err) < 0)
				return cmd_fail(c, "bad-argument", "population %s: %s", pname, err);
			col = stature;
		} else if ((col = population_column(key)) >= 0 && measure_value(c, col, v, &x) < 0) {
			return -1;
		}
		if (col < 0)
			continue;
		for (int j = 0; j < k; j++)
			if (cols[j] == col)
				return cmd_fail(c, "bad-argument", "%s is given twice (stature, percentile "
						"and mass are measures too: mass is weightkg)",
						population_column_name(col));
		cols[k] = col;
		vals[k++] = x;
	}
	double all[POPULATION_NCOL], dist;
	if (population_predict(p, (enum human_sex)sex, cols, vals, k, all, &dist, err, sizeof err) < 0)
		return cmd_fail(c, "bad-argument", "population %s: %s", pname, err);
	population_to_human(all, &hd);
	struct model *m = human_build(&hd, err, sizeof err);
	if (!m)
		return cmd_fail(c, "bad-argument", "%s", err);
	int slot = env_add_figure(&c->d->env, m, name, 1, &hd, NULL);
	if (cmd_added(c, slot, name) < 0)
		return -1;
	struct env_manikin *mk = &c->d->env.fig[slot].manikin;
	snprintf(mk->population, sizeof mk->population, "%s", pname);
	for (int j = 0; j < k; j++)
		mk->given[cols[j]] = 1;
	mk->mahalanobis = dist;
	mk->percentile = pct;
	json_object_set_new(c->result, "measures", manikin_measures_json(&hd));
	json_object_set_new(c->result, "mahalanobis", json_real(dist));
	return 0;
}

int
cmd_load_population(struct cmd_ctx *c)
{
	const char *name = c->argv[0];
	if (!words_is_name(name))
		return cmd_fail(c, "bad-argument", "a population's name: letters, digits, '_'");
	if (!strcmp(name, POPULATIONS_BUILTIN))
		return cmd_fail(c, "exists", "ansur2 is built in: load yours under another name");
	int have = populations_find(&c->d->pops, name) != NULL, used = 0;
	for (int i = 0; i < POPULATIONS_MAX; i++)
		used += c->d->pops.pop[i] != NULL;
	if (!have && used == POPULATIONS_MAX)
		return cmd_fail(c, "limit", "the daemon holds %d populations at most", POPULATIONS_MAX);
	size_t len;
	char *text = cmd_read_file(c, c->argv[1], &len);
	if (!text)
		return -1;
	if (len > POPULATIONS_FILE_MAX) {
		free(text);
		return cmd_fail(c, "bad-file", "%.60s: larger than %u MiB", c->argv[1],
				POPULATIONS_FILE_MAX >> 20);
	}
	char err[512], ignored[2048];
	struct population *p = population_csv_read(text, len, c->argv[1], ignored, sizeof ignored,
						   err, sizeof err);
	free(text);
	if (!p)
		return cmd_fail(c, "bad-file", "%s", err);
	json_t *cols = json_array(), *ign = json_array();
	for (int i = 0; i < POPULATION_NCOL; i++)
		if (!p->lacks[i])
			json_array_append_new(cols, json_string(population_column_name(i)));
	char *save;
	for (char *t = strtok_r(ignored, ",", &save); t; t = strtok_r(NULL, ",", &save))
		json_array_append_new(ign, json_string(t));
	json_object_set_new(c->result, "population", json_string(name));
	json_object_set_new(c->result, "men", json_integer(p->sex[HUMAN_MALE].n));
	json_object_set_new(c->result, "women", json_integer(p->sex[HUMAN_FEMALE].n));
	json_object_set_new(c->result, "measures", cols);
	json_object_set_new(c->result, "ignored", ign);
	populations_add(&c->d->pops, name, p); /* a slot is free or the name's: checked above */
	return 0;
}

/* ---- families ---------------------------------------------------------------- */

struct member {
	char name[MODEL_NAME_MAX];
	int sex, index;
	double dist;
	double chosen[POPULATION_NCOL]; /* the family's measures, in its order */
	struct human_def hd;
	struct model *model;
};

/* "measures=a,b,..." into columns (default stature,weightkg); k or -1 with the error set */
static int
family_measures(struct cmd_ctx *c, const struct population *p, int *cols)
{
	const char *list = cmd_key(c, "measures");
	char buf[2048];
	int k = 0;
	snprintf(buf, sizeof buf, "%s", list ? list : "stature,weightkg");
	char *save;
	for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
		int col = population_column(t);
		if (col < 0)
			return cmd_fail(c, "bad-argument", "measures: '%.40s' is not one of ANSUR II's", t);
		if (p->lacks[col])
			return cmd_fail(c, "bad-argument", "measures: the population has no %s", t);
		for (int j = 0; j < k; j++)
			if (cols[j] == col)
				return cmd_fail(c, "bad-argument", "measures: %s twice", t);
		cols[k++] = col;
	}
	if (!k)
		return cmd_fail(c, "bad-argument", "measures: at least one");
	return k;
}

static void
free_members(struct member *mb, int n)
{
	for (int i = 0; i < n; i++)
		model_free(mb[i].model);
	free(mb);
}

int
cmd_load_family(struct cmd_ctx *c)
{
	const char *prefix = c->argv[0];
	int sex = sex_of(c, -1, 1);
	if (sex < 0)
		return c->code ? -1 : cmd_fail(c, "bad-argument", "sex=female|male|both is required");
	for (int i = 1; i < c->argc; i++)
		if (!words_is_key(c->argv[i], "sex") && !words_is_key(c->argv[i], "population") &&
		    !words_is_key(c->argv[i], "measures") && !words_is_key(c->argv[i], "coverage") &&
		    !words_is_key(c->argv[i], "n"))
			return cmd_fail(c, "bad-argument", "unexpected '%.60s'", c->argv[i]);
	if (!words_is_name(prefix) || strlen(prefix) > MODEL_NAME_MAX - 12)
		return cmd_fail(c, "bad-argument", "a family's prefix: a name of at most %d bytes",
				MODEL_NAME_MAX - 12);
	const char *pname;
	const struct population *p = population_of(c, &pname);
	int cols[POPULATION_NCOL], k = p ? family_measures(c, p, cols) : -1;
	if (k < 0)
		return -1;
	double coverage = 90, n = 8;
	const char *cw = cmd_key(c, "coverage"), *nw = cmd_key(c, "n");
	if (cw && (words_number(cw, UNIT_NONE, &coverage) < 0 || !(coverage > 0 && coverage < 100)))
		return cmd_fail(c, "bad-number", "coverage: a percentage above 0 and below 100");
	if (nw && (words_number(nw, UNIT_NONE, &n) < 0 || n != floor(n) || n < 0 ||
		   n > POPULATION_FAMILY_MAX))
		return cmd_fail(c, "bad-number", "n: 0 to %d boundary manikins", POPULATION_FAMILY_MAX);
	int nsex = sex == 2 ? 2 : 1, per = (int)n + 1, total = nsex * per, free_slots = 0;
	for (int i = 0; i < ENV_MAX_FIGURES; i++)
		free_slots += !c->d->env.fig[i].gen;
	if (total > free_slots)
		return cmd_fail(c, "limit", "a family of %d manikins: the environment has room for %d "
				"(it holds %d figures at most)", total, free_slots, ENV_MAX_FIGURES);
	struct member *mb = calloc((size_t)total, sizeof *mb);
	double *rows = malloc(sizeof *rows * (size_t)per * POPULATION_NCOL);
	double *dist = malloc(sizeof *dist * (size_t)per);
	char err[512];
	int made = 0, rc = -1;
	if (!mb || !rows || !dist) {
		cmd_fail(c, "internal", "out of memory");
		goto out;
	}
	/* every manikin built before any is added: a family loads whole or not at all */
	for (int s = 0; s < nsex; s++) {
		int sx = sex == 2 ? (s ? HUMAN_MALE : HUMAN_FEMALE) : sex;
		if (population_family(p, (enum human_sex)sx, cols, k, coverage / 100, (int)n, rows, dist,
				      err, sizeof err) < 0) {
			cmd_fail(c, "bad-argument", "population %s: %s", pname, err);
			goto out;
		}
		for (int b = 0; b < per; b++, made++) {
			struct member *m = &mb[made];
			snprintf(m->name, sizeof m->name, "%s%s_%d", prefix,
				 sex == 2 ? (sx == HUMAN_FEMALE ? "_female" : "_male") : "", b);
			if (env_find_figure(&c->d->env, m->name) >= 0) {
				cmd_fail(c, "exists", "a figure named '%s' exists", m->name);
				goto out;
			}
			m->sex = sx;
			m->index = b;
			m->dist = dist[b];
			for (int j = 0; j < k; j++)
				m->chosen[j] = rows[(size_t)b * POPULATION_NCOL + cols[j]];
			m->hd = human_default_def((enum human_sex)sx);
			m->hd.measure_given = 0;
			population_to_human(rows + (size_t)b * POPULATION_NCOL, &m->hd);
			if (!(m->model = human_build(&m->hd, err, sizeof err))) {
				cmd_fail(c, "bad-argument", "%s: %s", m->name, err);
				goto out;
			}
		}
	}
	json_t *list = json_array();
	for (int i = 0; i < total; i++) {
		struct member *m = &mb[i];
		int slot = env_add_figure(&c->d->env, m->model, m->name, 1, &m->hd, NULL);
		m->model = NULL; /* the environment's now */
		if (slot < 0) { /* cannot happen: room and names were checked */
			json_decref(list);
			cmd_fail(c, "internal", "%s could not be added", m->name);
			goto out;
		}
		struct env_manikin *mk = &c->d->env.fig[slot].manikin;
		snprintf(mk->population, sizeof mk->population, "%s", pname);
		for (int j = 0; j < k; j++)
			mk->given[cols[j]] = 1;
		mk->mahalanobis = m->dist;
		snprintf(mk->family, sizeof mk->family, "%s", prefix);
		mk->member = m->index;
		mk->coverage = coverage / 100;
		char id[32];
		env_figure_id(&c->d->env, slot, id);
		json_t *o = json_object(), *chosen = json_object();
		for (int j = 0; j < k; j++)
			json_object_set_new(chosen, population_column_name(cols[j]), json_real(m->chosen[j]));
		json_object_set_new(o, "figure", json_string(id));
		json_object_set_new(o, "name", json_string(m->name));
		json_object_set_new(o, "sex", json_string(m->sex == HUMAN_FEMALE ? "female" : "male"));
		json_object_set_new(o, "member", json_integer(m->index));
		json_object_set_new(o, "mahalanobis", json_real(m->dist));
		json_object_set_new(o, "given", chosen);
		json_object_set_new(o, "measures", manikin_measures_json(&m->hd));
		json_array_append_new(list, o);
	}
	json_t *names = json_array();
	for (int j = 0; j < k; j++)
		json_array_append_new(names, json_string(population_column_name(cols[j])));
	json_object_set_new(c->result, "family", json_string(prefix));
	json_object_set_new(c->result, "population", json_string(pname));
	json_object_set_new(c->result, "given", names);
	json_object_set_new(c->result, "coverage", json_real(coverage));
	json_object_set_new(c->result, "radius", json_real(sqrt(mvn_chi2_quantile(coverage / 100, k))));
	json_object_set_new(c->result, "figures", list);
	rc = 0;
out:
	free_members(mb, mb ? total : 0);
	free(rows);
	free(dist);
	return rc;
}

/* ---- a family shown side by side or overlaid ---------------------------------- */

/* family members first by sex (women first), then by number */
static int
member_order(const struct env *e, int a, int b)
{
	const struct env_figure *x = &e->fig[a], *y = &e->fig[b];
	if (x->human.sex != y->human.sex)
		return x->human.sex == HUMAN_FEMALE ? -1 : 1;
	return x->manikin.member - y->manikin.member;
}

int
cmd_arrange_family(struct cmd_ctx *c)
{
	struct env *e = &c->d->env;
	const char *prefix = c->argv[0], *how = c->argv[1];
	int row = !strcmp(how, "row");
	if (!row && strcmp(how, "overlay"))
		return cmd_fail(c, "bad-argument", "arrange family PREFIX row [spacing=M] | overlay "
				"[selected=FIG]");
	for (int i = 2; i < c->argc; i++)
		if (!words_is_key(c->argv[i], row ? "spacing" : "selected"))
			return cmd_fail(c, "bad-argument", "unexpected '%.60s'", c->argv[i]);
	int slot[ENV_MAX_FIGURES], n = 0;
	for (int i = 0; i < ENV_MAX_FIGURES; i++)
		if (e->fig[i].gen && e->fig[i].is_human && !strcmp(e->fig[i].manikin.family, prefix)) {
			int k = n++;
			for (; k > 0 && member_order(e, slot[k - 1], i) > 0; k--) /* insertion, in order */
				slot[k] = slot[k - 1];
			slot[k] = i;
		}
	if (!n)
		return cmd_fail(c, "not-found", "no family '%.60s' (load family)", prefix);
	double spacing = 0.8;
	const char *sw = cmd_key(c, "spacing"), *sel = cmd_key(c, "selected");
	if (sw && (words_number(sw, UNIT_LENGTH, &spacing) < 0 || !(spacing > 0 && spacing <= 100)))
		return cmd_fail(c, "bad-number", "spacing: a length above 0 and at most 100 m");
	int selected = slot[0];
	if (sel) {
		if ((selected = cmd_figure(c, sel)) < 0)
			return -1;
		if (strcmp(e->fig[selected].manikin.family, prefix))
			return cmd_fail(c, "bad-argument", "%s is not one of family %s", e->fig[selected].name,
					prefix);
	}
	/*
	 * each member moved across the floor by its pelvis, whatever its root (heights and turns
	 * kept), about the members' mean place: row, overlay and row again come back alike
	 */
	double x0 = 0, z0 = 0;
	for (int k = 0; k < n; k++) {
		const struct env_figure *f = &e->fig[slot[k]];
		const double *p = f->state->site_xf[model_find_site(f->model, HUMAN_SITE_ROOT)].p;
		x0 += p[0] / n;
		z0 += p[2] / n;
	}
	json_t *list = json_array();
	for (int k = 0; k < n; k++) {
		struct env_figure *f = &e->fig[slot[k]];
		const double *p = f->state->site_xf[model_find_site(f->model, HUMAN_SITE_ROOT)].p;
		double x = row ? x0 + (k - (n - 1) / 2.0) * spacing : x0;
		f->state->root_xf.p[0] += x - p[0];
		f->state->root_xf.p[2] += z0 - p[2];
		kin_update(f->model, f->state);
		f->manikin.ghost = !row && slot[k] != selected;
		json_t *o = json_object();
		json_object_set_new(o, "name", json_string(f->name));
		json_object_set_new(o, "ghost", json_boolean(f->manikin.ghost));
		json_array_append_new(list, o);
	}
	json_object_set_new(c->result, "figures", list);
	return 0;
}
