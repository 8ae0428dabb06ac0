/*
 * niosh.c - the revised NIOSH lifting equation at full precision.
 *
 * RWL = LC x HM x VM x DM x AM x FM x CM (Applications Manual p. 7). HM,
 * VM, DM and AM from the formulas ("each multiplier should be computed
 * from the appropriate formula", p. 7), not the rounded Tables 1-4; FM from
 * Table 5 (p. 15), CM from Table 7 (p. 18); the limits of pp. 8-15. The
 * tables as transcribed twice and reconciled in nbarr1/ErgonomicTool
 * (methods/rnle/transcription), identical to research human-factors §4.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "assess/niosh.h"

/* the manual's two sets of constants (p. 7 and the limits of pp. 8-15) */
struct units {
	double lc;           /* load constant */
	double h_min, h_max; /* HM = h_min / H */
	double v_opt, v_coef, v_max;
	double d_min, d_max, d_coef; /* DM = .82 + d_coef / D */
	double v_split;      /* Tables 5 and 7: V < 30 in / 75 cm */
};

static const struct units unit_sets[2] = {
	[NIOSH_METRIC] = { 23, 25, 63, 75, 0.003, 175, 25, 175, 4.5, 75 },
	[NIOSH_US] = { 51, 10, 25, 30, 0.0075, 70, 10, 70, 1.8, 30 },
};

/* Table 5's rows (lifts/min) and columns: <= 1 h, 1-2 h, 2-8 h, each V low | V high */
#define FM_ROWS 18
static const double fm_f[FM_ROWS] = { 0.2, 0.5, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 1e9 };
static const double fm_table[FM_ROWS][6] = {
	{ 1.00, 1.00, .95, .95, .85, .85 }, { .97, .97, .92, .92, .81, .81 },
	{ .94, .94, .88, .88, .75, .75 },   { .91, .91, .84, .84, .65, .65 },
	{ .88, .88, .79, .79, .55, .55 },   { .84, .84, .72, .72, .45, .45 },
	{ .80, .80, .60, .60, .35, .35 },   { .75, .75, .50, .50, .27, .27 },
	{ .70, .70, .42, .42, .22, .22 },   { .60, .60, .35, .35, .18, .18 },
	{ .52, .52, .30, .30, .00, .15 },   { .45, .45, .26, .26, .00, .13 },
	{ .41, .41, .00, .23, .00, .00 },   { .37, .37, .00, .21, .00, .00 },
	{ .00, .34, .00, .00, .00, .00 },   { .00, .31, .00, .00, .00, .00 },
	{ .00, .28, .00, .00, .00, .00 },   { .00, .00, .00, .00, .00, .00 }, /* > 15 */
};

/* Table 7: [coupling][V low | V high] */
static const double cm_table[3][2] = { { 1.00, 1.00 }, { 0.95, 1.00 }, { 0.90, 0.90 } };

static int
duration_index(int hours)
{
	return hours == 1 ? 0 : hours == 2 ? 1 : hours == 8 ? 2 : -1;
}

/* Table 5 for F >= 0 in column col; sets the F limit bits */
static double
fm_column(double f, int col, unsigned *limits)
{
	if (f < 0.2) {
		f = 0.2;
		*limits |= NIOSH_F_RAISED;
	}
	/* the column's maximum frequency: its last row that is not .00 */
	int last = 0;
	for (int i = 0; i < FM_ROWS; i++)
		if (fm_table[i][col] > 0)
			last = i;
	if (f > fm_f[last]) {
		*limits |= NIOSH_F_BEYOND;
		return 0;
	}
	int i = 0;
	while (i + 1 < last && fm_f[i + 1] < f)
		i++;
	if (f <= fm_f[i])
		return fm_table[i][col];
	/* linear in F between rows i and i + 1, both within the column's range */
	double t = (f - fm_f[i]) / (fm_f[i + 1] - fm_f[i]);
	return fm_table[i][col] + t * (fm_table[i + 1][col] - fm_table[i][col]);
}

double
niosh_fm(double freq, int duration_h, double v_cm)
{
	int d = duration_index(duration_h);
	unsigned ignored = 0;
	if (d < 0 || !isfinite(freq) || freq < 0 || isnan(v_cm))
		return NAN;
	return fm_column(freq, 2 * d + (v_cm >= 75), &ignored);
}

double
niosh_cm(enum niosh_coupling c, double v_cm)
{
	if ((unsigned)c > NIOSH_POOR || isnan(v_cm))
		return NAN;
	return cm_table[c][v_cm >= 75];
}

const char *
niosh_limit_name(unsigned bit, enum niosh_units u)
{
	int us = u == NIOSH_US;
	switch (bit) {
	case NIOSH_H_RAISED: return us ? "H < 10 in: set to 10 (HM = 1)" : "H < 25 cm: set to 25 (HM = 1)";
	case NIOSH_H_BEYOND: return us ? "H > 25 in: HM = 0" : "H > 63 cm: HM = 0";
	case NIOSH_V_BEYOND: return us ? "V > 70 in: VM = 0" : "V > 175 cm: VM = 0";
	case NIOSH_D_RAISED: return us ? "D < 10 in: set to 10 (DM = 1)" : "D < 25 cm: set to 25 (DM = 1)";
	case NIOSH_D_BEYOND: return us ? "D > 70 in: DM = 0" : "D > 175 cm: DM = 0";
	case NIOSH_A_BEYOND: return "A > 135 deg: AM = 0";
	case NIOSH_F_RAISED: return "F < 0.2 lifts/min: set to 0.2";
	case NIOSH_F_BEYOND: return "F above the maximum frequency of its Table 5 column: FM = 0";
	default: return "";
	}
}

/* refuses what no lift can be: NaN, infinities, negatives, unknown categories */
static int
check_task(const struct niosh_task *t, char *err, size_t errlen)
{
	const struct {
		const char *name;
		double v;
	} f[] = { { "H", t->h_cm }, { "V", t->v_cm }, { "D", t->d_cm }, { "A", t->a_deg },
		  { "F", t->freq }, { "load", t->load_kg }, { "V at the origin", t->v_origin_cm },
		  { "maximum load", t->load_max_kg } };
	for (size_t i = 0; i < sizeof f / sizeof f[0]; i++)
		if (!isfinite(f[i].v) || f[i].v < 0) {
			snprintf(err, errlen, "%s = %g: a lift needs a finite number >= 0", f[i].name,
				 f[i].v);
			return -1;
		}
	if (duration_index(t->duration_h) < 0) {
		snprintf(err, errlen, "duration %d h: the manual's categories are 1, 2 and 8 h",
			 t->duration_h);
		return -1;
	}
	if ((unsigned)t->coupling > NIOSH_POOR) {
		snprintf(err, errlen, "coupling %d: good, fair or poor", (int)t->coupling);
		return -1;
	}
	return 0;
}

/* every multiplier but FM, into r; returns LC x HM x VM x DM x AM x CM (the FIRWL) */
static double
multipliers(const struct niosh_task *t, const struct units *u, struct niosh_result *r)
{
	double h = t->h_cm, d = t->d_cm;
	r->limits = 0;
	if (h < u->h_min) {
		h = u->h_min;
		r->limits |= NIOSH_H_RAISED;
	}
	if (h > u->h_max) {
		r->hm = 0;
		r->limits |= NIOSH_H_BEYOND;
	} else {
		r->hm = u->h_min / h;
	}
	if (t->v_cm > u->v_max) {
		r->vm = 0;
		r->limits |= NIOSH_V_BEYOND;
	} else {
		r->vm = 1 - u->v_coef * fabs(t->v_cm - u->v_opt);
	}
	if (d < u->d_min) {
		d = u->d_min;
		r->limits |= NIOSH_D_RAISED;
	}
	if (d > u->d_max) {
		r->dm = 0;
		r->limits |= NIOSH_D_BEYOND;
	} else {
		r->dm = 0.82 + u->d_coef / d;
	}
	if (t->a_deg > 135) {
		r->am = 0;
		r->limits |= NIOSH_A_BEYOND;
	} else {
		r->am = 1 - 0.0032 * t->a_deg;
	}
	r->cm = cm_table[t->coupling][t->v_cm >= u->v_split];
	return u->lc * r->hm * r->vm * r->dm * r->am * r->cm;
}

static double
lifting_index(double load, double rwl)
{
	if (rwl > 0)
		return load / rwl;
	return load > 0 ? INFINITY : 0;
}

int
niosh_compute_units(const struct niosh_task *t, enum niosh_units un, struct niosh_result *r,
		    char *err, size_t errlen)
{
	if ((unsigned)un > NIOSH_US) {
		snprintf(err, errlen, "unknown units %d", (int)un);
		return -1;
	}
	if (check_task(t, err, errlen) < 0)
		return -1;
	const struct units *u = &unit_sets[un];
	struct niosh_result o;
	double firwl = multipliers(t, u, &o);
	/* FM at the origin's V (p. 15), whichever end is evaluated */
	o.fm = fm_column(t->freq, 2 * duration_index(t->duration_h) + (t->v_origin_cm >= u->v_split),
			 &o.limits);
	o.rwl = firwl * o.fm;
	o.li = lifting_index(t->load_kg, o.rwl);
	*r = o;
	return 0;
}

int
niosh_compute(const struct niosh_task *t, struct niosh_result *r, char *err, size_t errlen)
{
	return niosh_compute_units(t, NIOSH_METRIC, r, err, errlen);
}

int
niosh_composite_units(const struct niosh_task *tasks, int n, enum niosh_units un,
		      struct niosh_multi_result *r, char *err, size_t errlen)
{
	if (n < 1 || n > NIOSH_MAX_TASKS) {
		snprintf(err, errlen, "%d tasks: a composite takes 1 to %d", n, NIOSH_MAX_TASKS);
		return -1;
	}
	if ((unsigned)un > NIOSH_US) {
		snprintf(err, errlen, "unknown units %d", (int)un);
		return -1;
	}
	const struct units *u = &unit_sets[un];
	struct niosh_multi_result o;
	memset(&o, 0, sizeof o);
	o.n = n;
	for (int i = 0; i < n; i++) {
		const struct niosh_task *t = &tasks[i];
		char why[160];
		if (check_task(t, why, sizeof why) < 0) {
			snprintf(err, errlen, "task %d: %s", i + 1, why);
			return -1;
		}
		if (t->duration_h != tasks[0].duration_h) {
			snprintf(err, errlen, "task %d lasts %d h, task 1 %d h: the tasks of a job share "
				 "one duration category", i + 1, t->duration_h, tasks[0].duration_h);
			return -1;
		}
		struct niosh_result m;
		unsigned lim = 0;
		double heaviest = t->load_max_kg > t->load_kg ? t->load_max_kg : t->load_kg;
		o.firwl[i] = multipliers(t, u, &m);
		o.fm[i] = fm_column(t->freq, 2 * duration_index(t->duration_h) +
					     (t->v_origin_cm >= u->v_split), &lim);
		o.strwl[i] = o.firwl[i] * o.fm[i];
		o.fili[i] = lifting_index(heaviest, o.firwl[i]);
		o.stli[i] = lifting_index(t->load_kg, o.strwl[i]);
	}
	/* renumbered by decreasing STLI; ties: the higher frequency, then the given order */
	for (int i = 0; i < n; i++)
		o.order[i] = i;
	for (int i = 1; i < n; i++)
		for (int j = i; j > 0; j--) {
			int a = o.order[j - 1], b = o.order[j];
			int swap = o.stli[b] > o.stli[a] ||
				   (o.stli[b] == o.stli[a] && tasks[b].freq > tasks[a].freq);
			if (!swap)
				break;
			o.order[j - 1] = b;
			o.order[j] = a;
		}
	double fsum = 0;
	int low = 0;
	o.cli = o.stli[o.order[0]];
	for (int k = 0; k < n; k++) {
		const struct niosh_task *t = &tasks[o.order[k]];
		unsigned lim = 0;
		fsum += t->freq;
		low |= t->v_origin_cm < u->v_split;
		o.fm_sum[k] = fm_column(fsum, 2 * duration_index(t->duration_h) + !low, &lim);
		if (k == 0)
			continue;
		if (o.fm_sum[k] <= 0 || o.fm_sum[k - 1] <= 0)
			o.cli = INFINITY;
		else
			o.cli += o.fili[o.order[k]] * (1 / o.fm_sum[k] - 1 / o.fm_sum[k - 1]);
	}
	*r = o;
	return 0;
}

int
niosh_composite(const struct niosh_task *tasks, int n, struct niosh_multi_result *r, char *err,
		size_t errlen)
{
	return niosh_composite_units(tasks, n, NIOSH_METRIC, r, err, errlen);
}
