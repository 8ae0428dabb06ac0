/*
 * strength.h - the percent of a population strong enough for the moments a
 * posture and its loads put on each joint, per joint and anatomical axis,
 * and the task's capability, the least of them.
 *
 * Percent capable = 100 Phi((S - |M|) / sigma): S and sigma the mean and
 * standard deviation of the population's maximal static moment of the
 * muscles that resist M (flexors or extensors, ...), by sex, at the joint's
 * angle; Phi the standard normal distribution. This is the construction
 * 3DSSPP describes (its background page points to Chaffin, Andersson &
 * Martin, Occupational Biomechanics, ch. 6, for the strength
 * distributions; research human-factors §5.3) and the Arm Force Field's
 * (La Delfa & Potvin, Applied Ergonomics 59:410-421, 2017, whose published
 * code takes 1 - Phi((load - mean) / sd)).
 *
 * Strength comes from a table of published curves: mean and SD at a
 * source's sample angles, linear between them, none outside them. Where no
 * curve covers a joint, axis, direction and sex, the percent is NAN (null
 * in the reply). strength.c says which curves ship. Fixed arrays; nothing
 * allocates.
 */
#ifndef POSTURE_STRENGTH_H
#define POSTURE_STRENGTH_H

#include <stddef.h>

enum strength_joint {
	STRENGTH_WRIST_L,
	STRENGTH_WRIST_R,
	STRENGTH_ELBOW_L,
	STRENGTH_ELBOW_R,
	STRENGTH_SHOULDER_L,
	STRENGTH_SHOULDER_R,
	STRENGTH_L5S1,
	STRENGTH_HIP_L,
	STRENGTH_HIP_R,
	STRENGTH_KNEE_L,
	STRENGTH_KNEE_R,
	STRENGTH_ANKLE_L,
	STRENGTH_ANKLE_R,
	STRENGTH_NJOINTS,
};

/* a joint whatever its side: what a published curve is about */
enum strength_kind {
	STRENGTH_WRIST,
	STRENGTH_ELBOW,
	STRENGTH_SHOULDER,
	STRENGTH_TORSO, /* L5/S1 */
	STRENGTH_HIP,
	STRENGTH_KNEE,
	STRENGTH_ANKLE,
	STRENGTH_NKINDS,
};

/*
 * The anatomical axes, each signed as assess/statics.h's anat[] (a moment
 * the muscles must supply in that sense): flexion + (extension -; the
 * ankle's dorsiflexion); abduction + (adduction -; the ankle's inversion,
 * the wrist's radial deviation, the torso's bending to the left); internal
 * rotation + (external -; the wrist's pronation, the torso's turning to
 * the left).
 */
enum strength_axis {
	STRENGTH_FLEXION,
	STRENGTH_ABDUCTION,
	STRENGTH_ROTATION,
	STRENGTH_NAXES,
};

enum strength_sex {
	STRENGTH_MALE,
	STRENGTH_FEMALE,
};

/*
 * One published strength curve: the maximal static moment of the muscles
 * acting toward direction (+1 or -1 along axis) of a joint kind, for one
 * sex, at the joint angle on angle_axis (degrees, in the signs above): rows
 * of { angle, mean N m, SD N m } in increasing angle.
 */
struct strength_curve {
	enum strength_kind kind;
	enum strength_axis axis;
	int direction;
	enum strength_sex sex;
	enum strength_axis angle_axis;
	int n;
	const double (*rows)[3];
	const char *source; /* the publication and its table */
};

struct strength_table {
	const struct strength_curve *curves;
	size_t count;
};

/* the curves that ship (strength.c) */
extern const struct strength_table strength_published;

struct strength_input {
	enum strength_sex sex;
	/* N m: the moment the joint's muscles must produce, anatomical axes */
	double moment[STRENGTH_NJOINTS][STRENGTH_NAXES];
	/* degrees: the joint's angles, same axes and signs */
	double angle[STRENGTH_NJOINTS][STRENGTH_NAXES];
};

struct strength_result {
	double percent[STRENGTH_NJOINTS][STRENGTH_NAXES]; /* 0..100; NAN: no curve */
	double mean[STRENGTH_NJOINTS][STRENGTH_NAXES];    /* N m of the muscles resisting; NAN */
	double sd[STRENGTH_NJOINTS][STRENGTH_NAXES];
	double capable;    /* the least percent; NAN when no joint has a curve */
	int weakest_joint; /* enum strength_joint of capable; -1 with it NAN */
	int weakest_axis;
	int modelled;      /* how many (joint, axis) have a percent */
};

/*
 * The percent capable of every joint and axis of in, from the shipped
 * curves (strength_capable) or from table t. Returns 0, or -1 with why in
 * err (dest untouched) for a non-finite moment or angle or an unknown sex.
 */
int strength_capable(const struct strength_input *in, struct strength_result *dest, char *err,
		     size_t errlen);
int strength_capable_table(const struct strength_table *t, const struct strength_input *in,
			   struct strength_result *dest, char *err, size_t errlen);

/* the standard normal distribution function, 0.5 erfc(-z / sqrt 2) */
double strength_phi(double z);

/* 100 Phi((mean - |moment|) / sd); NAN for a non-finite input or sd <= 0 */
double strength_percent(double mean, double sd, double moment);

/*
 * The tint's bands of a percent capable (research human-factors §5.1):
 *   0  >= 99  NIOSH 1981's action limit: within 99 % of men's strength
 *   1  75-99  the UAW-GM guideline's acceptable 75 % (and the action limit
 *             for women)
 *   2  25-75  below the guideline, above the maximum permissible limit
 *   3  < 25   below NIOSH's maximum permissible limit: 25 % of men
 * NIOSH's percentages are widely quoted, their primary text not seen
 * (unconfirmed); -1 for NAN.
 */
int strength_band(double percent);

/*
 * NIOSH 1981's two strength criteria for one sex: 0 at or above the action
 * limit's percent (99 men, 75 women), 2 below the maximum permissible
 * limit's (25 men, 1 women), 1 between; -1 for NAN.
 */
int strength_niosh_band(double percent, enum strength_sex sex);

/* "wrist_l", ..., "l5s1", ...; "flexion", "abduction", "rotation" */
const char *strength_joint_name(enum strength_joint j);
const char *strength_axis_name(enum strength_axis a);
enum strength_kind strength_joint_kind(enum strength_joint j);

#endif
