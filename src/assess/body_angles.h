/*
 * body_angles.h - the angles the posture assessments are scored from,
 * measured on a human figure (figure/human.h) as the methods define them:
 * body planes from the pelvis and the shoulders, the trunk from the
 * vertical, the limbs and the neck relative to the trunk.
 *
 * Degrees. Signs: flexion +, extension -; side bend and twist + to the
 * figure's left; abduction + away from the midline; wrist deviation +
 * radial; wrist twist + pronation. Lengths in metres. Nothing allocates.
 *
 * Everything is measured from the segments' global frames and sites, never
 * read from joint values, so the angles are the same however the posture
 * was made (by hand, IK, the spine's spreading) and wherever the figure is
 * rooted or turned. Which frames and points each angle takes, and where
 * that choice comes from, is in body_angles.c and body_angle_names.
 */
#ifndef POSTURE_BODY_ANGLES_H
#define POSTURE_BODY_ANGLES_H

#include <stddef.h>

#include "figure/model.h"
#include "figure/state.h"

enum body_side {
	BODY_LEFT,
	BODY_RIGHT,
};

struct body_arm {
	/*
	 * The upper arm relative to the thorax (T1's frame): the swing from the
	 * thorax's down axis to the arm, as a rotation vector (elevation times
	 * its unit axis), split into its flexion and abduction components; so
	 * flexion = e sin(p), abduction = e cos(p) for elevation e in the plane
	 * of elevation p. Exact in the sagittal and coronal planes, continuous
	 * through 90 deg abduction (singular only with the arm straight up).
	 */
	double upper_arm_flexion;
	double upper_arm_abduction;
	double upper_arm_rotation;  /* internal +: the twist about the arm left by that swing */
	double shoulder_elevation;  /* the clavicle's lateral axis above the thorax's x-z plane */
	double elbow_flexion;       /* 0 = straight */
	double wrist_flexion;       /* the hand in the forearm, after pronation (see .c) */
	double wrist_deviation;     /* radial + */
	double wrist_twist;         /* forearm pronation +, supination - */
	double wrist_twist_fraction; /* |twist| over the limit on its side: 0 mid, 1 at the end */
	double hand_across_midline; /* m the palm past the thorax's midsagittal plane (+ crossed) */
	double hand_out_to_side;    /* m the palm outside the shoulder joint along the thorax's x */
	double elbow_above_shoulder; /* m the elbow lies above the shoulder joint centre */
	double hand_above_shoulder;  /* m the palm lies above the shoulder joint centre */
};

struct body_leg {
	double hip_flexion;   /* the thigh (hip to knee) in the pelvis's sagittal plane */
	double knee_flexion;  /* the shank's long axis against the thigh's: 0 = straight */
	double weight_share;  /* 0..1 of the body's weight over this foot (balance.h's weight_l) */
	int foot_on_floor;    /* the foot bears weight (balance.h's contact height) */
	int kneeling;         /* the knee's front within the kneel height of the floor */
};

struct body_angles {
	/*
	 * The trunk axis runs from L5/S1 to C7/T1 (the spine's chord: vertical
	 * when the figure stands upright; the hips' midpoint lies 3 cm in front
	 * of the spine and would read 3 deg of extension there). The sagittal
	 * plane is the vertical plane across the hip line.
	 */
	double trunk_flexion;   /* the trunk axis in the sagittal plane vs vertical */
	double trunk_side_bend; /* the trunk axis's angle out of the sagittal plane */
	double trunk_twist;     /* the shoulder line against the hip line, about the trunk axis */
	double hip_trunk_angle; /* between the trunk axis and the thighs' mean axis: 180 standing */
	double neck_flexion;    /* the head's frame relative to the thorax's (T1) */
	double neck_side_bend;
	double neck_twist;
	struct body_arm arm[2];  /* enum body_side */
	struct body_leg leg[2];
	int seated;             /* as the caller says (behave_params.seated) */
	int legs_on_floor;      /* how many feet bear weight */
};

/*
 * Measures the angles of human figure m in state s (frames current:
 * kin_update). seated comes from the figure's behaviour; kneel_height (m)
 * from struct assess_config. Returns 0, or -1 with why in err (dest
 * untouched) for a figure without the built-in human's segments, sites and
 * wrists, or a posture whose frames are not finite. About 2.5 us.
 */
int body_angles_measure(const struct model *m, const struct state *s, int seated,
			double kneel_height, struct body_angles *dest, char *err, size_t errlen);

/*
 * The angles by name, for `get angles`: "trunk_flexion", "upper_arm_flexion_l",
 * "knee_flexion_r", "weight_share_l", ... in a fixed order; unit "deg", "m",
 * "fraction", "flag" (0 or 1) or "count". body_angle_value reads angle i of a.
 */
struct body_angle_name {
	const char *name;
	const char *unit;
	const char *what; /* one line: how it is measured */
	size_t offset;    /* of the value in struct body_angles */
	int integer;      /* 1: an int there, else a double */
};
extern const struct body_angle_name body_angle_names[];
extern const size_t body_angle_count;
double body_angle_value(const struct body_angles *a, size_t i);
/* the index of a name, -1 when unknown */
int body_angle_find(const char *name);

#endif
