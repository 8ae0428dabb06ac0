/*
 * strength.c - percent capable per joint and axis from a table of
 * published strength curves (strength.h).
 *
 * Which curves ship: none yet. Every joint and axis answers NAN (null),
 * because no population strength model could be transcribed from a source
 * seen in full:
 * - 3DSSPP's strength equations (mean and SD of each joint's maximal
 *   moment as functions of the joint angles, by sex; Chaffin, Andersson &
 *   Martin ch. 6, after Stobbe 1982): the textbook's tables were not
 *   reachable, and the public copy of 3DSSPP's source holds its interface,
 *   not its analysis library;
 * - Harbo, Brincks & Andersen 2012 (Eur J Appl Physiol 112:267-275),
 *   isometric strength of 6 joints by sex, age, height and mass: only the
 *   abstract was reachable, not its regression table;
 * - Anderson, Madigan & Nussbaum 2007 (J Biomech 40:3105) and Frey-Law et
 *   al. 2012 torque-angle surfaces: coefficients not retrieved, and they
 *   give means without a population SD;
 * - NASA-STD-3000 vol. 1 §4.9: its tables give forces at the 5th
 *   percentile, not mean and SD of joint moments.
 * A curve added to `published` below (with its source and a test typing
 * the source's rows) turns its joint, axis and sex on; nothing else
 * changes.
 */
#include <math.h>
#include <stdio.h>

#include "assess/strength.h"

static const struct strength_curve published[1] = { { 0 } };

const struct strength_table strength_published = { published, 0 };

static const char *const joint_names[STRENGTH_NJOINTS] = {
	[STRENGTH_WRIST_L] = "wrist_l",	      [STRENGTH_WRIST_R] = "wrist_r",
	[STRENGTH_ELBOW_L] = "elbow_l",	      [STRENGTH_ELBOW_R] = "elbow_r",
	[STRENGTH_SHOULDER_L] = "shoulder_l", [STRENGTH_SHOULDER_R] = "shoulder_r",
	[STRENGTH_L5S1] = "l5s1",	      [STRENGTH_HIP_L] = "hip_l",
	[STRENGTH_HIP_R] = "hip_r",	      [STRENGTH_KNEE_L] = "knee_l",
	[STRENGTH_KNEE_R] = "knee_r",	      [STRENGTH_ANKLE_L] = "ankle_l",
	[STRENGTH_ANKLE_R] = "ankle_r",
};

static const enum strength_kind joint_kinds[STRENGTH_NJOINTS] = {
	[STRENGTH_WRIST_L] = STRENGTH_WRIST,	   [STRENGTH_WRIST_R] = STRENGTH_WRIST,
	[STRENGTH_ELBOW_L] = STRENGTH_ELBOW,	   [STRENGTH_ELBOW_R] = STRENGTH_ELBOW,
	[STRENGTH_SHOULDER_L] = STRENGTH_SHOULDER, [STRENGTH_SHOULDER_R] = STRENGTH_SHOULDER,
	[STRENGTH_L5S1] = STRENGTH_TORSO,	   [STRENGTH_HIP_L] = STRENGTH_HIP,
	[STRENGTH_HIP_R] = STRENGTH_HIP,	   [STRENGTH_KNEE_L] = STRENGTH_KNEE,
	[STRENGTH_KNEE_R] = STRENGTH_KNEE,	   [STRENGTH_ANKLE_L] = STRENGTH_ANKLE,
	[STRENGTH_ANKLE_R] = STRENGTH_ANKLE,
};

const char *
strength_joint_name(enum strength_joint j)
{
	return (unsigned)j < STRENGTH_NJOINTS ? joint_names[j] : "?";
}

const char *
strength_axis_name(enum strength_axis a)
{
	switch (a) {
	case STRENGTH_FLEXION:
		return "flexion";
	case STRENGTH_ABDUCTION:
		return "abduction";
	case STRENGTH_ROTATION:
		return "rotation";
	case STRENGTH_NAXES:
		break;
	}
	return "?";
}

enum strength_kind
strength_joint_kind(enum strength_joint j)
{
	return (unsigned)j < STRENGTH_NJOINTS ? joint_kinds[j] : STRENGTH_NKINDS;
}

double
strength_phi(double z)
{
	return 0.5 * erfc(-z / sqrt(2.0));
}

double
strength_percent(double mean, double sd, double moment)
{
	if (!isfinite(mean) || !isfinite(sd) || !isfinite(moment) || !(sd > 0))
		return NAN;
	return 100 * strength_phi((mean - fabs(moment)) / sd);
}

int
strength_band(double percent)
{
	if (isnan(percent))
		return -1;
	return percent >= 99 ? 0 : percent >= 75 ? 1 : percent >= 25 ? 2 : 3;
}

int
strength_niosh_band(double percent, enum strength_sex sex)
{
	/* NIOSH 1981: AL within 99 % of men / 75 % of women; MPL 25 % of men / 1 % of women */
	double al = sex == STRENGTH_FEMALE ? 75 : 99, mpl = sex == STRENGTH_FEMALE ? 1 : 25;
	if (isnan(percent))
		return -1;
	return percent >= al ? 0 : percent < mpl ? 2 : 1;
}

/* mean and SD of curve c at angle x; 0, or -1 outside its sampled range */
static int
curve_at(const struct strength_curve *c, double x, double *mean, double *sd)
{
	if (c->n < 1 || x < c->rows[0][0] || x > c->rows[c->n - 1][0])
		return -1;
	int i = 0;
	while (i + 1 < c->n && c->rows[i + 1][0] < x)
		i++;
	if (i + 1 >= c->n || x <= c->rows[i][0]) {
		*mean = c->rows[i][1];
		*sd = c->rows[i][2];
		return 0;
	}
	double t = (x - c->rows[i][0]) / (c->rows[i + 1][0] - c->rows[i][0]);
	*mean = c->rows[i][1] + t * (c->rows[i + 1][1] - c->rows[i][1]);
	*sd = c->rows[i][2] + t * (c->rows[i + 1][2] - c->rows[i][2]);
	return 0;
}

static const struct strength_curve *
find_curve(const struct strength_table *t, enum strength_kind k, enum strength_axis axis, int dir,
	   enum strength_sex sex)
{
	for (size_t i = 0; i < t->count; i++) {
		const struct strength_curve *c = &t->curves[i];
		if (c->kind == k && c->axis == axis && c->direction == dir && c->sex == sex)
			return c;
	}
	return NULL;
}

int
strength_capable_table(const struct strength_table *t, const struct strength_input *in,
		       struct strength_result *dest, char *err, size_t errlen)
{
	if (in->sex != STRENGTH_MALE && in->sex != STRENGTH_FEMALE) {
		snprintf(err, errlen, "strength: unknown sex %d", (int)in->sex);
		return -1;
	}
	for (int j = 0; j < STRENGTH_NJOINTS; j++)
		for (int a = 0; a < STRENGTH_NAXES; a++)
			if (!isfinite(in->moment[j][a]) || !isfinite(in->angle[j][a])) {
				snprintf(err, errlen, "strength: %s %s: a moment or angle is not finite",
					 joint_names[j], strength_axis_name((enum strength_axis)a));
				return -1;
			}
	struct strength_result r;
	r.capable = NAN;
	r.weakest_joint = r.weakest_axis = -1;
	r.modelled = 0;
	for (int j = 0; j < STRENGTH_NJOINTS; j++)
		for (int a = 0; a < STRENGTH_NAXES; a++) {
			r.percent[j][a] = r.mean[j][a] = r.sd[j][a] = NAN;
			/* the muscles that resist act toward the moment's own sign */
			int dir = in->moment[j][a] < 0 ? -1 : 1;
			const struct strength_curve *c =
				find_curve(t, joint_kinds[j], (enum strength_axis)a, dir, in->sex);
			double mean, sd;
			if (!c || curve_at(c, in->angle[j][c->angle_axis], &mean, &sd) < 0)
				continue;
			r.mean[j][a] = mean;
			r.sd[j][a] = sd;
			r.percent[j][a] = strength_percent(mean, sd, in->moment[j][a]);
			if (isnan(r.percent[j][a]))
				continue;
			r.modelled++;
			if (isnan(r.capable) || r.percent[j][a] < r.capable) {
				r.capable = r.percent[j][a];
				r.weakest_joint = j;
				r.weakest_axis = a;
			}
		}
	*dest = r;
	return 0;
}

int
strength_capable(const struct strength_input *in, struct strength_result *dest, char *err,
		 size_t errlen)
{
	return strength_capable_table(&strength_published, in, dest, err, errlen);
}
