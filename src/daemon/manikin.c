/* manikin.c - a human's measures and provenance in sessions and replies */
#include "daemon/manikin.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "figure/mvn.h"

static const char *const measure_names[HUMAN_MEASURE_N] = {
#define NAME(e, s) s,
	HUMAN_MEASURES(NAME)
#undef NAME
};

void
manikin_write_words(const struct env_figure *f, FILE *dest)
{
	const struct human_def *hd = &f->human;
	const struct env_manikin *mk = &f->manikin;
	if (hd->measure_given) {
		fprintf(dest, " measure_given=%u measures=", hd->measure_given);
		for (int m = 0; m < HUMAN_MEASURE_N; m++)
			fprintf(dest, "%s%.17g", m ? "," : "", hd->measure[m]);
	}
	if (!mk->population[0])
		return;
	fprintf(dest, " population=%s given=", mk->population);
	int any = 0;
	for (int c = 0; c < POPULATION_NCOL; c++)
		if (mk->given[c])
			fprintf(dest, "%s%s", any++ ? "," : "", population_column_name(c));
	if (!any)
		fprintf(dest, "-");
	fprintf(dest, " mahalanobis=%.17g", mk->mahalanobis);
	if (!isnan(mk->percentile))
		fprintf(dest, " percentile=%.17g", mk->percentile);
	if (mk->family[0])
		fprintf(dest, " family=%s member=%d coverage=%.17g", mk->family, mk->member,
			mk->coverage);
	if (mk->ghost)
		fprintf(dest, " ghost=1");
}

static const char *
word(const struct words *w, int from, const char *key)
{
	for (int i = from; i < w->n; i++)
		if (words_is_key(w->w[i], key))
			return w->w[i] + strlen(key) + 1;
	return NULL;
}

int
manikin_read_words(const struct words *w, int from, struct human_def *hd,
		   struct env_manikin *mk, char *err, size_t errlen)
{
	*mk = (struct env_manikin){ .percentile = NAN, .coverage = NAN };
	const char *given = word(w, from, "measure_given"), *ms = word(w, from, "measures");
	if (given || ms) {
		char *end;
		unsigned long mask = given ? strtoul(given, &end, 10) : 0;
		if (!given || !ms || *end || given[0] == '-' || mask >= (1ul << HUMAN_MEASURE_N) ||
		    words_list(ms, UNIT_NONE, HUMAN_MEASURE_N, hd->measure) < 0) {
			snprintf(err, errlen, "a human's measures are measure_given=MASK measures=%d numbers",
				 HUMAN_MEASURE_N);
			return -1;
		}
		hd->measure_given = (unsigned)mask;
	}
	const char *pop = word(w, from, "population");
	if (!pop)
		return 0;
	const char *cols = word(w, from, "given"), *d = word(w, from, "mahalanobis");
	const char *pct = word(w, from, "percentile"), *fam = word(w, from, "family");
	if (!words_is_name(pop) || !cols || !d || words_number(d, UNIT_NONE, &mk->mahalanobis) < 0 ||
	    (pct && words_number(pct, UNIT_NONE, &mk->percentile) < 0))
		goto bad;
	snprintf(mk->population, sizeof mk->population, "%s", pop);
	if (strcmp(cols, "-")) {
		char buf[4096];
		snprintf(buf, sizeof buf, "%s", cols);
		for (char *save, *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
			int c = population_column(t);
			if (c < 0)
				goto bad;
			mk->given[c] = 1;
		}
	}
	if (fam) {
		const char *member = word(w, from, "member"), *cov = word(w, from, "coverage");
		double v;
		if (!words_is_name(fam) || !member || !cov || words_number(member, UNIT_NONE, &v) < 0 ||
		    v < 0 || v > POPULATION_FAMILY_MAX || v != floor(v) ||
		    words_number(cov, UNIT_NONE, &mk->coverage) < 0)
			goto bad;
		snprintf(mk->family, sizeof mk->family, "%s", fam);
		mk->member = (int)v;
	}
	const char *ghost = word(w, from, "ghost");
	if (ghost && strcmp(ghost, "1"))
		goto bad;
	mk->ghost = ghost != NULL;
	return 0;
bad:
	snprintf(err, errlen, "a manikin's provenance is population=NAME given=NAME,... "
		 "mahalanobis=D [percentile=P] [family=PREFIX member=I coverage=C] [ghost=1]");
	return -1;
}

json_t *
manikin_measures_json(const struct human_def *hd)
{
	json_t *o = json_object();
	for (int m = 0; m < HUMAN_MEASURE_N; m++)
		if (hd->measure_given & (1u << m))
			json_object_set_new(o, measure_names[m], json_real(hd->measure[m]));
	return o;
}

void
manikin_json(const struct env_figure *f, json_t *o)
{
	const struct env_manikin *mk = &f->manikin;
	json_object_set_new(o, "sex", json_string(f->human.sex == HUMAN_FEMALE ? "female" : "male"));
	json_object_set_new(o, "stature", json_real(f->human.stature));
	json_object_set_new(o, "mass", json_real(f->human.mass));
	if (f->human.measure_given)
		json_object_set_new(o, "measures", manikin_measures_json(&f->human));
	if (!mk->population[0])
		return;
	json_t *given = json_array();
	int k = 0;
	for (int c = 0; c < POPULATION_NCOL; c++)
		if (mk->given[c]) {
			json_array_append_new(given, json_string(population_column_name(c)));
			k++;
		}
	json_object_set_new(o, "population", json_string(mk->population));
	json_object_set_new(o, "given", given);
	json_object_set_new(o, "mahalanobis", json_real(mk->mahalanobis));
	/* the share of the population nearer the mean in those measures: chi-square, k dof */
	double inside = k ? 100 * mvn_chi2_cdf(mk->mahalanobis * mk->mahalanobis, k) : 0;
	json_object_set_new(o, "inside", json_real(inside));
	if (!isnan(mk->percentile))
		json_object_set_new(o, "percentile", json_real(mk->percentile));
	if (mk->family[0]) {
		json_object_set_new(o, "family", json_string(mk->family));
		json_object_set_new(o, "member", json_integer(mk->member));
		json_object_set_new(o, "coverage", json_real(100 * mk->coverage));
		json_object_set_new(o, "ghost", json_boolean(mk->ghost));
	}
}
