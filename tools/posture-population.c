/*
 * posture-population - a population's statistics and what it predicts,
 * outside the daemon: check a CSV before `load population`, complete
 * people's measures in bulk for a study, list a family's measures. The
 * tests compare its numbers with numpy and scipy.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/mvn.h"
#include "figure/population.h"
#include "figure/population_csv.h"

static const char usage[] =
	"usage: posture-population [--population FILE.csv] [--sex male|female] COMMAND ...\n"
	"\n"
	"  --population FILE.csv  a CSV in ANSUR II's layout (default: the built-in ansur2)\n"
	"  --sex male|female      the sex the commands below work on (default female)\n"
	"commands (CSV out: a header, then rows; measures in mm, weightkg in kg):\n"
	"  check                  read the population: people of each sex and its columns\n"
	"  stats                  each column: mean and standard deviation of the sex\n"
	"  predict NAME,...       for each line of standard input (the named measures'\n"
	"                         values, comma-separated), every column's conditional\n"
	"                         expectation, and the Mahalanobis distance of the line\n"
	"  percentile P           the P-th percentile stature and the rest given it\n"
	"  family NAME,... COVERAGE N\n"
	"                         the centre and N boundary manikins of the named measures\n"
	"                         on the ellipsoid covering COVERAGE percent\n"
	"  chi2 P K               the chi-square quantile of probability P, K degrees of freedom\n";

static int
names_to_cols(const char *list, int *cols, int max)
{
	char buf[4096];
	int k = 0;
	snprintf(buf, sizeof buf, "%s", list);
	for (char *save, *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
		int c = population_column(t);
		if (c < 0 || k >= max) {
			fprintf(stderr, "posture-population: '%s' is not one of ANSUR II's measures\n", t);
			return -1;
		}
		cols[k++] = c;
	}
	return k;
}

static void
print_header(const struct population *p, const char *last)
{
	int first = 1;
	for (int c = 0; c < POPULATION_NCOL; c++)
		if (!p->lacks[c]) {
			printf("%s%s", first ? "" : ",", population_column_name(c));
			first = 0;
		}
	printf(last ? ",%s\n" : "\n", last);
}

static void
print_row(const struct population *p, const double *v, double last)
{
	int first = 1;
	for (int c = 0; c < POPULATION_NCOL; c++)
		if (!p->lacks[c]) {
			printf("%s%.17g", first ? "" : ",", v[c]);
			first = 0;
		}
	printf(",%.17g\n", last);
}

static char *
read_all(const char *path, size_t *len)
{
	FILE *f = fopen(path, "rb");
	char *buf = NULL;
	size_t cap = 0;
	*len = 0;
	if (!f)
		return NULL;
	for (;;) {
		if (*len + 65536 + 1 > cap) {
			char *b = realloc(buf, cap = 2 * cap + 65536 + 1);
			if (!b) {
				free(buf);
				fclose(f);
				return NULL;
			}
			buf = b;
		}
		size_t n = fread(buf + *len, 1, cap - *len - 1, f);
		*len += n;
		if (!n)
			break;
	}
	fclose(f);
	buf[*len] = 0;
	return buf;
}

static int
predict_lines(const struct population *p, enum human_sex sex, const int *cols, int k)
{
	char line[65536], err[512];
	double vals[POPULATION_NCOL], out[POPULATION_NCOL], dist;
	print_header(p, "mahalanobis");
	while (fgets(line, sizeof line, stdin)) {
		int got = 0;
		for (char *save, *t = strtok_r(line, ",\n", &save); t; t = strtok_r(NULL, ",\n", &save)) {
			char *end;
			if (got >= k || ((vals[got++] = strtod(t, &end)), *end && *end != '\r')) {
				fprintf(stderr, "posture-population: predict takes %d numbers a line\n", k);
				return -1;
			}
		}
		if (got != k) {
			fprintf(stderr, "posture-population: predict takes %d numbers a line\n", k);
			return -1;
		}
		if (population_predict(p, sex, cols, vals, k, out, &dist, err, sizeof err) < 0) {
			fprintf(stderr, "posture-population: %s\n", err);
			return -1;
		}
		print_row(p, out, dist);
	}
	return 0;
}

int
main(int argc, char **argv)
{
	const char *file = NULL;
	enum human_sex sex = HUMAN_FEMALE;
	int i = 1;
	for (; i < argc && argv[i][0] == '-'; i += 2) {
		if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
			fputs(usage, stdout);
			return 0;
		}
		if (i + 1 >= argc) {
			fprintf(stderr, "posture-population: %s needs a value\n%s", argv[i], usage);
			return 2;
		}
		if (!strcmp(argv[i], "--population")) {
			file = argv[i + 1];
		} else if (!strcmp(argv[i], "--sex") && (!strcmp(argv[i + 1], "male") ||
							 !strcmp(argv[i + 1], "female"))) {
			sex = !strcmp(argv[i + 1], "male") ? HUMAN_MALE : HUMAN_FEMALE;
		} else {
			fprintf(stderr, "posture-population: bad option %s\n%s", argv[i], usage);
			return 2;
		}
	}
	if (i >= argc) {
		fputs(usage, stderr);
		return 2;
	}
	const char *cmd = argv[i++];
	char err[512], ignored[4096] = "";
	struct population *owned = NULL;
	const struct population *p = population_ansur2();
	if (file) {
		size_t len;
		char *text = read_all(file, &len);
		if (!text) {
			fprintf(stderr, "posture-population: %s: %s\n", file, strerror(errno));
			return 1;
		}
		owned = population_csv_read(text, len, file, ignored, sizeof ignored, err, sizeof err);
		free(text);
		if (!owned) {
			fprintf(stderr, "posture-population: %s\n", err);
			return 1;
		}
		p = owned;
	}
	int rc = 0, cols[POPULATION_NCOL], k;
	double out[POPULATION_NCOL], mm;
	if (!strcmp(cmd, "check") && i == argc) {
		printf("men %d\nwomen %d\ncolumns", p->sex[HUMAN_MALE].n, p->sex[HUMAN_FEMALE].n);
		for (int c = 0; c < POPULATION_NCOL; c++)
			if (!p->lacks[c])
				printf(" %s", population_column_name(c));
		printf("\nignored %s\n", ignored[0] ? ignored : "-");
	} else if (!strcmp(cmd, "stats") && i == argc) {
		const struct population_group *g = &p->sex[sex];
		printf("column,n,mean,sd\n");
		for (int c = 0; g->n && c < POPULATION_NCOL; c++)
			if (!p->lacks[c])
				printf("%s,%d,%.17g,%.17g\n", population_column_name(c), g->n, g->mean[c],
				       sqrt(population_cov(g, c, c)));
	} else if (!strcmp(cmd, "predict") && i + 1 == argc) {
		if ((k = names_to_cols(argv[i], cols, POPULATION_NCOL)) < 0 ||
		    predict_lines(p, sex, cols, k) < 0)
			rc = 1;
	} else if (!strcmp(cmd, "percentile") && i + 1 == argc) {
		double pct = strtod(argv[i], NULL), dist;
		int st = population_column("stature");
		if (population_percentile(p, sex, pct, &mm, err, sizeof err) < 0 ||
		    population_predict(p, sex, &st, &mm, 1, out, &dist, err, sizeof err) < 0) {
			fprintf(stderr, "posture-population: %s\n", err);
			rc = 1;
		} else {
			print_header(p, "mahalanobis");
			print_row(p, out, dist);
		}
	} else if (!strcmp(cmd, "family") && i + 3 == argc) {
		int n = atoi(argv[i + 2]);
		double cover = strtod(argv[i + 1], NULL) / 100;
		double *rows = malloc(sizeof *rows * (size_t)(n + 1) * POPULATION_NCOL);
		double *dist = malloc(sizeof *dist * (size_t)(n + 1));
		if (!rows || !dist || n < 0 || (k = names_to_cols(argv[i], cols, POPULATION_NCOL)) < 0 ||
		    population_family(p, sex, cols, k, cover, n, rows, dist, err, sizeof err) < 0) {
			fprintf(stderr, "posture-population: %s\n", rows && dist && n >= 0 ? err : "bad n");
			rc = 1;
		} else {
			print_header(p, "mahalanobis");
			for (int b = 0; b <= n; b++)
				print_row(p, rows + (size_t)b * POPULATION_NCOL, dist[b]);
		}
		free(rows);
		free(dist);
	} else if (!strcmp(cmd, "chi2") && i + 2 == argc) {
		printf("%.17g\n", mvn_chi2_quantile(strtod(argv[i], NULL), atoi(argv[i + 1])));
	} else {
		fprintf(stderr, "posture-population: bad command\n%s", usage);
		rc = 2;
	}
	population_free(owned);
	return rc;
}
