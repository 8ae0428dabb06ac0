/*
 * test_anthropometry.c - the human's landmarks, the figure measured in
 * ANSUR II's postures, and figures built from measures: every ANSUR II
 * subject's 20 measures (data/ansur2) met within 2 mm, mass exactly, as the
 * measuring (pose/anthropometry.c, forward kinematics on the landmark
 * sites) finds them.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/human.h"
#include "figure/kin.h"
#include "figure/model.h"
#include "figure/state.h"
#include "pose/anthropometry.h"

#define DATA "data/ansur2/"
#define TOL_MM 2.0

/* one subject: the 20 measures in measures.h's order (weightkg in kg) */
struct subject {
	double v[HUMAN_MEASURE_N];
};

/* the subjects of one file; n, or -1 when it cannot be read */
static int
read_subjects(const char *path, struct subject **dest)
{
	FILE *f = fopen(path, "r");
	if (!f)
		return -1;
	static char line[1 << 14];
	int col[HUMAN_MEASURE_N], n = 0, cap = 0;
	struct subject *s = NULL;
	if (!fgets(line, sizeof line, f)) {
		fclose(f);
		return -1;
	}
	for (int k = 0; k < HUMAN_MEASURE_N; k++)
		col[k] = -1;
	int c = 0;
	for (char *tok = strtok(line, ",\r\n"); tok; tok = strtok(NULL, ",\r\n"), c++) {
		int k = anthro_find(tok);
		if (k >= 0)
			col[k] = c;
	}
	for (int k = 0; k < HUMAN_MEASURE_N; k++)
		if (col[k] < 0) {
			fclose(f);
			return -1;
		}
	while (fgets(line, sizeof line, f)) {
		if (n == cap) {
			cap = cap ? 2 * cap : 1024;
			s = realloc(s, sizeof *s * (size_t)cap);
			assert_non_null(s);
		}
		double cell[128];
		c = 0;
		/* the measured columns are plain numbers; the text columns after them may hold anything */
		for (char *p = line; c < 128 && *p && *p != '\n'; c++) {
			cell[c] = strtod(p, NULL);
			p = strchr(p, ',');
			if (!p)
				break;
			p++;
		}
		for (int k = 0; k < HUMAN_MEASURE_N; k++)
			s[n].v[k] = cell[col[k]];
		s[n].v[HUMAN_M_WEIGHTKG] /= 10; /* the files hold tenths of a kilogram */
		n++;
	}
	fclose(f);
	*dest = s;
	return n;
}

static struct human_def
def_of(const double v[HUMAN_MEASURE_N], unsigned given, enum human_sex sex)
{
	struct human_def d = human_default_def(sex);
	for (int k = 0; k < HUMAN_MEASURE_N; k++)
		if (given >> k & 1u)
			d.measure[k] = v[k];
	d.measure_given = given;
	if (given >> HUMAN_M_STATURE & 1u)
		d.stature = v[HUMAN_M_STATURE] / 1000;
	if (given >> HUMAN_M_WEIGHTKG & 1u)
		d.mass = v[HUMAN_M_WEIGHTKG];
	return d;
}

static void
measure(const struct model *m, double dest[HUMAN_MEASURE_N])
{
	char err[256];
	if (anthro_measure(m, dest, err, sizeof err) < 0)
		fail_msg("anthro_measure: %s", err);
}

#define ALL ((1u << HUMAN_MEASURE_N) - 1)

/* every subject of both files built from all 20 measures and measured back */
static void
test_every_subject_meets_its_measures(void **unused)
{
	(void)unused;
	static const struct {
		const char *file;
		enum human_sex sex;
	} files[] = { { DATA "ANSUR_II_MALE_Public.csv", HUMAN_MALE },
		      { DATA "ANSUR_II_FEMALE_Public.csv", HUMAN_FEMALE } };
	double worst[HUMAN_MEASURE_N] = { 0 }, sq[HUMAN_MEASURE_N] = { 0 };
	int total = 0;
	for (size_t f = 0; f < 2; f++) {
		struct subject *s = NULL;
		int n = read_subjects(files[f].file, &s);
		if (n < 0)
			fail_msg("cannot read %s (run from the repository's root)", files[f].file);
		assert_int_equal(n, files[f].sex == HUMAN_MALE ? 4082 : 1986);
		for (int i = 0; i < n; i++) {
			struct human_def d = def_of(s[i].v, ALL, files[f].sex);
			char err[256];
			struct model *m = human_build(&d, err, sizeof err);
			if (!m)
				fail_msg("%s subject %d: %s", files[f].file, i + 2, err);
			double got[HUMAN_MEASURE_N];
			measure(m, got);
			for (int k = 0; k < HUMAN_MEASURE_N; k++) {
				double e = got[k] - s[i].v[k];
				sq[k] += e * e;
				worst[k] = fmax(worst[k], fabs(e));
				if (k == HUMAN_M_WEIGHTKG ? fabs(e) > 1e-9 : fabs(e) > TOL_MM)
					fail_msg("%s line %d: %s measured %.3f, given %.3f", files[f].file,
						 i + 2, anthro_name((enum human_measure)k), got[k], s[i].v[k]);
			}
			model_free(m);
			total++;
		}
		free(s);
	}
	printf("# %d subjects: measured against given, mm (weightkg: kg)\n", total);
	printf("# %-24s %12s %12s\n", "measure", "max |error|", "rms");
	for (int k = 0; k < HUMAN_MEASURE_N; k++)
		printf("# %-24s %12.3g %12.3g\n", anthro_name((enum human_measure)k), worst[k],
		       sqrt(sq[k] / total));
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_every_subject_meets_its_measures),
	};
	return cmocka_run_group_tests_name("anthropometry", tests, NULL, NULL);
}
