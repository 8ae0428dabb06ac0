/*
 * assess.h - what the posture assessments (RULA, REBA, OWAS) share: the
 * derivation a score carries so a person can check it by hand, and the
 * thresholds the methods' texts leave open.
 *
 * A result is plain data in fixed arrays (nothing allocates: the scores run
 * every frame while a person drags). Each body part records the angle it
 * was scored from, the band that angle fell in, every adjustment with its
 * reason, and its final score; each table look-up records its indices and
 * the cell read. The daemon writes it as JSON; the tint colours parts by it.
 */
#ifndef POSTURE_ASSESS_H
#define POSTURE_ASSESS_H

#include <stddef.h>

#define ASSESS_MAX_PARTS 12
#define ASSESS_MAX_ADJ 5
#define ASSESS_MAX_LOOKUPS 8
#define ASSESS_MAX_IDX 4
#define ASSESS_REASON 96

enum assess_method {
	ASSESS_RULA,
	ASSESS_REBA,
	ASSESS_OWAS,
	ASSESS_NMETHODS,
};

enum assess_side_choice {
	ASSESS_SIDE_LEFT,
	ASSESS_SIDE_RIGHT,
	ASSESS_SIDE_WORSE, /* both scored, the higher grand score kept */
};

struct assess_adjust {
	int value;                   /* +1, -1, ... */
	char reason[ASSESS_REASON];  /* "shoulder raised: clavicle elevation 14.2 > 10" */
};

struct assess_part {
	const char *name;       /* "upper_arm", "trunk", "legs", "load", ... (static) */
	const char *angle_name; /* the body angle scored (body_angles.h name), NULL for none */
	double angle;           /* degrees as measured; NAN when the part has none */
	int base;               /* the band's score */
	char band[ASSESS_REASON]; /* the band as the method states it: "45-90 deg flexion" */
	int nadj;
	struct assess_adjust adj[ASSESS_MAX_ADJ];
	int score;              /* base + adjustments, clamped to the method's range */
	int max;                /* the part's highest possible score (for the tint) */
	int body;               /* 1: a body part (tinted, may be the worst); 0: an add-on
				   the user states (muscle use, load, coupling, activity) */
};

struct assess_lookup {
	const char *table;                   /* "A", "B", "C", "action" (static) */
	int nidx;
	const char *idx_name[ASSESS_MAX_IDX]; /* "upper_arm", "lower_arm", ... (static) */
	int idx[ASSESS_MAX_IDX];             /* 1-based, as the published tables print them */
	int value;                           /* the cell */
};

struct assess_result {
	enum assess_method method;
	int side;            /* enum assess_side_choice scored (LEFT or RIGHT; -1 when none) */
	int score;           /* the grand score */
	int action_level;    /* the method's action level / category */
	const char *action;  /* the method's words for it (static) */
	int nparts;
	struct assess_part part[ASSESS_MAX_PARTS];
	int nlookups;
	struct assess_lookup lookup[ASSESS_MAX_LOOKUPS];
	int worst;           /* index into part[] of the body part that scores highest relative to
				its range, (score - 1) / (max - 1), the first on ties; OWAS: the
				part whose code, made neutral, lowers the category most */
	char code[8];        /* OWAS: the four-digit posture code ("2131"); "" for the others */
};

/*
 * The thresholds the methods' texts leave open, in degrees (or metres, or a
 * fraction where said), settable with `set assess KEY=VALUE`. Each default
 * and where it comes from is in assess_config_keys (assess.c).
 */
struct assess_config {
	double upright;            /* trunk/neck within this of neutral counts as "upright" / 0 */
	double shoulder_raised;    /* clavicle elevation above which the shoulder is raised */
	double arm_abducted;       /* upper-arm abduction above which the arm is abducted */
	double arm_rotated;        /* upper-arm axial rotation (REBA "rotated") */
	double trunk_twist;        /* trunk twist above which it is "twisted" */
	double trunk_side_bend;    /* trunk side bend above which it is "side bending" */
	double neck_twist;
	double neck_side_bend;
	double wrist_neutral;      /* wrist flexion/extension within this is RULA "neutral" */
	double wrist_deviated;     /* radial/ulnar deviation above which the wrist is bent */
	double wrist_twist_end;    /* fraction of the pronation/supination range: "near the end" */
	double across_midline;     /* m the hand passes the midsagittal plane: "across the midline" */
	double out_to_side;        /* m the hand lies outside the shoulder: "out to the side" */
	double uneven_weight;      /* weight share difference between the feet: "unevenly balanced" */
	double knee_bent;          /* knee flexion above which a leg is "bent" (OWAS) */
	double owas_back;          /* OWAS back bent / twisted / side-bent threshold */
	double kneel_height;       /* m: a knee this close to the floor is kneeling */
};

/* the defaults (each with its source in assess_config_keys) */
struct assess_config assess_config_default(void);

struct assess_config_key {
	const char *key;     /* "shoulder_raised" */
	size_t offset;       /* into struct assess_config */
	const char *unit;    /* "deg", "m", "fraction" */
	double min, max;     /* accepted values */
	const char *source;  /* where the default comes from, briefly */
};
extern const struct assess_config_key assess_config_keys[];
extern const size_t assess_config_nkeys;

/*
 * Sets one key; 0, or -1 with why in err for an unknown key or a value
 * outside the key's range (cfg unchanged then).
 */
int assess_config_set(struct assess_config *cfg, const char *key, double value, char *err,
		      size_t errlen);

#endif
