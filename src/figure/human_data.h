/*
 * human_data.h - the published tables the standard human figure is built
 * from (segment inertia parameters, stature fractions, joint ranges of
 * motion; each cited beside its definition in human_data.c) and the layout
 * of the figure computed from them, which human.c turns into a model.
 */
#ifndef POSTURE_HUMAN_DATA_H
#define POSTURE_HUMAN_DATA_H

#include "figure/human.h"
#include "figure/human_dims.h"

/* de Leva (1996) segments used here (Table 4 rows) */
enum human_dl_seg {
	HUMAN_DL_HEAD,     /* head + neck, vertex to cervicale (C7), the table's second head row */
	HUMAN_DL_UPT,      /* upper trunk, suprasternale to xiphion */
	HUMAN_DL_MPT,      /* middle trunk, xiphion to omphalion */
	HUMAN_DL_LPT,      /* lower trunk, omphalion to mid-hip joint centres */
	HUMAN_DL_UPPERARM, /* shoulder to elbow joint centre */
	HUMAN_DL_FOREARM,  /* elbow to wrist joint centre */
	HUMAN_DL_HAND,     /* wrist joint centre to third metacarpale */
	HUMAN_DL_THIGH,    /* hip to knee joint centre */
	HUMAN_DL_SHANK,    /* knee joint centre to lateral malleolus */
	HUMAN_DL_FOOT,     /* heel to tip of the longest toe */
	HUMAN_DL_N,
};

/*
 * One row: mass as a fraction of body mass; centre of mass as a fraction of
 * the segment length from its first (cranial / proximal / heel) endpoint;
 * radii of gyration about the centre of mass as fractions of the length
 * (sagittal, transverse, longitudinal); the segment length in metres for
 * the table's reference subject.
 */
struct human_dl_row {
	double mass, com, r_sag, r_trans, r_long, len;
};

struct human_dl_table {
	double stature; /* m, of the reference sample */
	double mass;    /* kg */
	struct human_dl_row seg[HUMAN_DL_N];
};

extern const struct human_dl_table human_dl_male, human_dl_female;

/* Drillis & Contini (1966) landmark heights and breadths, fractions of stature */
extern const double human_dc_ankle, human_dc_knee, human_dc_hip, human_dc_wrist,
	human_dc_fingertip, human_dc_elbow, human_dc_shoulder, human_dc_chin, human_dc_eye,
	human_dc_shoulder_half, human_dc_hip_width, human_dc_chest_width, human_dc_foot_length,
	human_dc_foot_width;

/*
 * Per-level range of motion of the 17 thoracolumbar motion segments, in
 * degrees: flexion + extension together, lateral bending to one side, axial
 * rotation to one side. Index k is joint spine_k (0 = L5/S1 ... 16 = T1/T2).
 */
struct human_spine_rom {
	double flex_ext, lat, rot;
};

extern const struct human_spine_rom human_spine_rom[17];
extern const double human_spine_flex_share; /* share of flex_ext that is flexion */

/* cervical spine as a whole (joint spine_17, T1 to head), degrees */
extern const double human_neck_flex, human_neck_ext, human_neck_lat, human_neck_rot;

/*
 * Limb joints: one dof as written for the LEFT side (the right side negates
 * the sign of rotations about y and z, so a joint value means the same
 * anatomical motion on both sides). Limits in degrees.
 */
struct human_dof_spec {
	int axis; /* 0 x, 1 y, 2 z */
	int sign; /* left side */
	double lo, hi;
};

struct human_joint_spec {
	const char *name; /* without the _l / _r suffix */
	int ndof;
	struct human_dof_spec dof[3];
};

enum human_limb_joint {
	HUMAN_LJ_HIP,
	HUMAN_LJ_KNEE,
	HUMAN_LJ_ANKLE,
	HUMAN_LJ_TOE,
	HUMAN_LJ_CLAVICLE,
	HUMAN_LJ_SHOULDER,
	HUMAN_LJ_ELBOW,
	HUMAN_LJ_WRIST,
	HUMAN_LJ_EYE,
	HUMAN_LJ_N,
};

extern const struct human_joint_spec human_limb_joints[HUMAN_LJ_N];

enum { HUMAN_NSLICE = 17 };

/* segment indices in build order (the model's segment order too) */
enum {
	HUMAN_SEG_PELVIS,
	HUMAN_SEG_SLICE0, /* + k: L5 (k = 0) ... T1 (k = 16) */
	HUMAN_SEG_HEAD = HUMAN_SEG_SLICE0 + HUMAN_NSLICE,
	HUMAN_SEG_EYE,                /* + side */
	HUMAN_SEG_LIMB = HUMAN_SEG_EYE + 2, /* + HUMAN_LIMB_N * side + limb */
	HUMAN_SEG_N = HUMAN_SEG_LIMB + 16,
};

enum {
	HUMAN_LIMB_THIGH,
	HUMAN_LIMB_SHANK,
	HUMAN_LIMB_FOOT,
	HUMAN_LIMB_TOES,
	HUMAN_LIMB_CLAVICLE,
	HUMAN_LIMB_UPPERARM,
	HUMAN_LIMB_FOREARM,
	HUMAN_LIMB_HAND,
	HUMAN_LIMB_N,
};

extern const char *const human_slice_name[HUMAN_NSLICE];
extern const char *const human_limb_name[HUMAN_LIMB_N];
extern const char *const human_side_sfx[2];

#define HUMAN_EYE_MASS 0.0075     /* kg, each (Bekerman et al. 2014, in human.c) */
#define HUMAN_CLAVICLE_SHARE 0.05 /* of the upper trunk, each (assumption) */
#define HUMAN_SLICE_CHEST 12      /* T5 carries the chest site */

/*
 * The surface landmarks anthropometry measures, as sites (human_dims.c
 * places them): X(ID, site name, segment, bilateral). A bilateral landmark
 * on a limb segment has one site per side with the plain name
 * ("thigh_l.trochanterion"); one on the pelvis or the head gets the side's
 * suffix ("pelvis.iliocristale_l"). The radiale has two sites: where the
 * acromion-radiale length ends (on the upper arm) and where the
 * radiale-stylion length starts (on the forearm); they coincide unless the
 * given measures disagree (human_dims.c).
 */
#define HUMAN_LANDMARKS(X)                                               \
	X(ACROMION, "acromion", HUMAN_LM_CLAVICLE, 1)                    \
	X(SHOULDER_BLADE, "shoulder_blade", HUMAN_LM_CLAVICLE, 1)        \
	X(RADIALE_UPPER, "radiale", HUMAN_LM_UPPERARM, 1)                \
	X(RADIALE, "radiale", HUMAN_LM_FOREARM, 1)                       \
	X(STYLION, "stylion", HUMAN_LM_FOREARM, 1)                       \
	X(DACTYLION, "dactylion", HUMAN_LM_HAND, 1)                      \
	X(THUMBTIP, "thumbtip", HUMAN_LM_HAND, 1)                        \
	X(TROCHANTERION, "trochanterion", HUMAN_LM_THIGH, 1)             \
	X(FEMORAL_EPICONDYLE, "lateral_femoral_epicondyle", HUMAN_LM_THIGH, 1) \
	X(MIDPATELLA, "midpatella", HUMAN_LM_THIGH, 1)                   \
	X(SUPRAPATELLA, "suprapatella", HUMAN_LM_THIGH, 1)               \
	X(KNEE_FRONT, "knee_front", HUMAN_LM_THIGH, 1)                   \
	X(POPLITEAL, "popliteal", HUMAN_LM_THIGH, 1)                     \
	X(TIBIALE, "tibiale", HUMAN_LM_SHANK, 1)                         \
	X(LATERAL_MALLEOLUS, "lateral_malleolus", HUMAN_LM_SHANK, 1)     \
	X(PTERNION, "pternion", HUMAN_LM_FOOT, 1)                        \
	X(ACROPODION, "acropodion", HUMAN_LM_TOES, 1)                    \
	X(ILIOCRISTALE, "iliocristale", HUMAN_LM_PELVIS, 1)              \
	X(ISCHIAL_TUBEROSITY, "ischial_tuberosity", HUMAN_LM_PELVIS, 1)  \
	X(BUTTOCK, "buttock", HUMAN_LM_PELVIS, 1)                        \
	X(TRAGION, "tragion", HUMAN_LM_HEAD, 1)                          \
	X(ECTOCANTHUS, "ectocanthus", HUMAN_LM_HEAD, 1)                  \
	X(SELLION, "sellion", HUMAN_LM_HEAD, 0)                          \
	X(CERVICALE, "cervicale", HUMAN_LM_HEAD, 0)                      \
	X(SUPRASTERNALE, "suprasternale", HUMAN_LM_T1, 0)

/* the segment a landmark is on */
enum human_lm_seg {
	HUMAN_LM_PELVIS,
	HUMAN_LM_T1,
	HUMAN_LM_HEAD,
	HUMAN_LM_THIGH, /* limb segments: the side's */
	HUMAN_LM_SHANK,
	HUMAN_LM_FOOT,
	HUMAN_LM_TOES,
	HUMAN_LM_CLAVICLE,
	HUMAN_LM_UPPERARM,
	HUMAN_LM_FOREARM,
	HUMAN_LM_HAND,
};

#define HUMAN_LM_ENUM(e, name, seg, bilateral) HUMAN_LM_##e,
enum human_landmark { HUMAN_LANDMARKS(HUMAN_LM_ENUM) HUMAN_LM_N };
#undef HUMAN_LM_ENUM

struct human_landmark_info {
	const char *name;
	enum human_lm_seg seg;
	int bilateral;
};

extern const struct human_landmark_info human_landmark_info[HUMAN_LM_N];

/*
 * The laid-out figure in its standing rest posture, in the layout frame (x
 * left, y up, z forward, the hip joint centres at z = 0). Landmark points
 * are the left side's; the right side is their mirror image. Per segment:
 * its origin (proximal joint centre), mass, centre of mass (layout frame)
 * and inertia about the centre of mass (world axes).
 */
struct human_layout {
	double H, M;
	const struct human_dl_table *dl;
	double k;      /* stature / de Leva reference stature */
	double norm;   /* 1 / sum of de Leva mass fractions */
	double za;     /* ankle z: the forward lean of the shanks */
	struct human_dims dim;
	double lm[HUMAN_LM_N][3]; /* landmarks, left side (human_landmarks_place) */
	double hip[3], knee[3], ankle[3], heel[3], mtp[3], tip[3], balance[3];
	double sc[3], gh[3], elbow[3], wrist[3], fingertip[3], eye[3];
	double spine[HUMAN_NSLICE + 1][3]; /* spine_k centres; [17] is C7/T1 */
	double y_supr;               /* suprasternale height */
	double head_c[3], head_semi[3], eye_r;
	double foot_box[2][3], toes_box[2][3]; /* min and max corners */
	double org[HUMAN_SEG_N][3], mass[HUMAN_SEG_N], com[HUMAN_SEG_N][3], inertia[HUMAN_SEG_N][6];
};

/*
 * Lays out the figure for d (stature and mass already checked) with its
 * landmarks; returns 0, or -1 with why in err when the given measures are
 * out of range or disagree beyond what the body can meet (human_dims.c).
 */
int human_layout_make(const struct human_def *d, struct human_layout *dest, char *err,
		      size_t errlen);


/* whole-body centre of mass of a layout */
void human_layout_com(const struct human_layout *L, double dest[3]);

/* torso half-width and half-depth (m) at height y */
void human_torso_semi(const struct human_layout *L, double y, double *hw, double *hd);

/* the right side's copy of a left point */
void human_mirror(const double p[3], double dest[3]);

/* unit quaternion rotating +y onto the line through a and b */
void human_quat_y_to(const double a[3], const double b[3], double q[4]);

#endif
