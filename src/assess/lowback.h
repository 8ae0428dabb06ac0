/*
 * lowback.h - the low back's compression and shear at the L5/S1 disc by
 * Chaffin's single-equivalent-muscle sagittal model (Chaffin, Andersson &
 * Martin, Occupational Biomechanics, ch. 6), compared with NIOSH's limits
 * (Work Practices Guide for Manual Lifting, DHHS (NIOSH) 81-122, 1981):
 * 3400 N the action limit, 6400 N the maximum permissible limit.
 *
 * The level is L5/S1: the human's spine_0, where the lumbar column meets
 * the sacrum (figure/human.c). The input is plain numbers in the world
 * frame: what everything above the disc (the segments' weights and the
 * loads on them) puts on it, reduced to the disc centre, and the disc's
 * orientation. Nothing allocates; about 20 ns.
 *
 * The derivation, with the free body everything above L5/S1:
 *   l = n x a, the disc's lateral axis (n the disc's cranial normal, a the
 *       figure's forward direction in the disc plane);
 *   M_ext = max(0, load_moment . l), the extensor moment the load needs
 *       (a load in front of the disc flexes the trunk about +l);
 *   F_m = M_ext / E, the single equivalent extensor pulling caudally along
 *       -n at E behind the disc centre;
 *   compression = F_m - load_force . n;
 *   shear_ap = load_force . a (+ the upper vertebra pushed forward);
 *   shear_lat = load_force . l.
 * E and what the model leaves out are in lowback.c and the result's flags.
 *
 * From the statics (assess/statics.h, rooted at the pelvis, so spine_0's
 * distal part is everything above L5/S1): load_force = -force[spine_0],
 * load_moment = -moment[spine_0] (the statics gives what the pelvis applies
 * to the upper body); disc_normal and anterior the world +y and +z of
 * spine_0's distal segment, the L5 slice, whose frame the disc follows.
 */
#ifndef POSTURE_LOWBACK_H
#define POSTURE_LOWBACK_H

#include <stddef.h>

/* NIOSH 1981's L5/S1 compression limits, newtons (research human-factors §5.1) */
#define LOWBACK_ACTION_LIMIT 3400.0
#define LOWBACK_MAX_LIMIT 6400.0

struct lowback_input {
	double load_force[3];  /* N, world: the resultant of everything above L5/S1 */
	double load_moment[3]; /* N m, world: its moment about the disc centre */
	double disc_normal[3]; /* unit, world: the disc's cranial normal (L5's up axis) */
	double anterior[3];    /* world: forward, best L5's own forward axis; its part in the disc plane is used */
};

/* what the result leaves out (struct lowback_result.flags) */
enum lowback_flag {
	/* the load extends the trunk (M . l < 0): the flexors that then act
	   (the abdominal wall) have no sourced moment arm; compression counts
	   the load alone and is an underestimate */
	LOWBACK_FLEXOR_UNMODELLED = 1u << 0,
};

enum lowback_zone {
	LOWBACK_BELOW_ACTION, /* compression <= 3400 N */
	LOWBACK_ABOVE_ACTION, /* above 3400 N, <= 6400 N */
	LOWBACK_ABOVE_MAX,    /* above 6400 N */
};

struct lowback_result {
	const char *level;   /* "L5/S1" */
	const char *model;   /* "chaffin-sagittal" */
	double compression;  /* N along the disc normal, + compressive */
	double shear_ap;     /* N in the disc plane along a, + the upper vertebra forward */
	double shear_lat;    /* N in the disc plane along l = n x a */
	double muscle_force; /* N, the single equivalent extensor F_m */
	double moment_arm;   /* m, E as used */
	double moment_sagittal; /* N m, load_moment . l (+ flexing) */
	/* the parts a sagittal model turns into no muscle force: the
	   compression leaves out what resisting them costs */
	double moment_lateral;  /* N m, load_moment . a (lateral bend) */
	double moment_axial;    /* N m, load_moment . n (twist) */
	double action_limit; /* 3400 N */
	double max_limit;    /* 6400 N */
	enum lowback_zone zone;
	unsigned flags;      /* enum lowback_flag bits */
};

/*
 * The disc loads of in into dest. Returns 0, or -1 with why in err (dest
 * untouched) for a non-finite number, a disc normal not of unit length
 * (within 1e-6), or a forward direction that lies along the normal.
 */
int lowback_compute(const struct lowback_input *in, struct lowback_result *dest, char *err,
		    size_t errlen);

/* the same with the extensor's moment arm e_m (m, > 0) instead of the model's */
int lowback_compute_arm(const struct lowback_input *in, double e_m, struct lowback_result *dest,
			char *err, size_t errlen);

/*
 * What the model always leaves out, for the reply's "unmodelled" list:
 * "abdominal_pressure", "disc_angle_regression", "lateral_and_axial_moments"
 * (lowback.c says why); "flexors" joins them when the result has
 * LOWBACK_FLEXOR_UNMODELLED.
 */
extern const char *const lowback_unmodelled[];
extern const int lowback_nunmodelled;

/* the model's extensor moment arm, m (lowback.c says where it comes from) */
double lowback_moment_arm(void);

/* "below_action", "above_action", "above_max" */
const char *lowback_zone_name(enum lowback_zone z);

#endif
