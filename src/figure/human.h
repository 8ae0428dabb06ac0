/*
 * human.h - the standard human figure (§5.5.5, Appendix D), built from
 * stature, body mass and sex with published anthropometry.
 *
 * Conventions of the built figure (later subsystems rely on them):
 *
 * - Metres, radians, kg; y up, floor y = 0; the figure faces +z and +x is
 *   its left. It is built standing: arms hanging with the palms facing the
 *   thighs, looking forward, feet flat. Every dof is 0 in that posture.
 *   The built posture is the standing rest posture of §5.4.2.1: the shanks
 *   lean forward just enough that the line of gravity passes through the
 *   midpoint of foot_l.balance and foot_r.balance, which is placed at the
 *   world origin (x = z = 0).
 * - Every segment frame has its origin at its proximal joint centre and, in
 *   the built posture, axes parallel to the world axes; the pelvis frame's
 *   origin is the midpoint of the hip joint centres. All sites are placed by
 *   translation only (identity orientation).
 * - Site names: the joint J runs from the site "J" on its proximal segment
 *   (e.g. "pelvis.hip_l", "thigh_l.knee_l", "T1.spine_17") to the site
 *   "origin" of its distal segment (e.g. "thigh_l.origin"). The pelvis is
 *   proximal to everything.
 * - Segments (37): pelvis; L5 L4 L3 L2 L1 T12 ... T1; head (with the neck);
 *   eyeball_l/r; thigh, shank, foot, toes, clavicle, upperarm, forearm,
 *   hand, each _l and _r.
 * - Vertebral joints spine_0 (pelvis-L5, the L5/S1 motion segment) to
 *   spine_16 (T2-T1, T1/T2); spine_17 (T1-head) stands for the whole
 *   cervical spine. Each has 3 dofs: flexion (+ = upper body forward, about
 *   +x), lateral bending (+ = to the left, about -z), axial rotation
 *   (+ = face turns left, about +y).
 * - Limb joints are mirrored: the same value means the same anatomical
 *   motion on both sides (rotations about y and z change sign on the right).
 *   Dof order follows the ISB joint coordinate systems: flexion/extension,
 *   ab/adduction, axial rotation.
 *     hip 3 (flexion, abduction, internal rotation), knee 1 (flexion,
 *     0 = straight), ankle 3 (dorsiflexion, inversion, internal rotation),
 *     toe 1 (flexion of the toes at the MTP joints), clavicle 2 (protraction,
 *     elevation: the ISB order of the sternoclavicular joint; attached to
 *     T1), shoulder 3 (flexion, abduction, internal rotation), elbow 1
 *     (flexion, 0 = straight), wrist 3 (flexion, radial deviation,
 *     pronation: Jack's 3-dof wrist with forearm rotation as its axial dof),
 *     eye 2 (abduction = temporal gaze about y, then elevation about x).
 * - Joint order: spine_0 .. spine_17, then hip knee ankle toe clavicle
 *   shoulder elbow wrist for the left and then the right side, then eye_l
 *   and eye_r; so dofs 0 .. 87 are the body's and 88 .. 91 the eyes'.
 */
#ifndef POSTURE_HUMAN_H
#define POSTURE_HUMAN_H

#include <stddef.h>

#include "figure/measures.h"
#include "figure/model.h"

#define HUMAN_NSEG 37
#define HUMAN_NJNT 36
#define HUMAN_NDOF 92      /* all dofs */
#define HUMAN_BODY_NDOF 88 /* without the 4 eye dofs, as §D.1.3 counts */
#define HUMAN_NSPINE 18    /* vertebral joints spine_0 .. spine_17 */

/* dof index within a joint, for the 3-dof joints (hip, ankle, shoulder, wrist, spine) */
#define HUMAN_DOF_FLEX 0 /* flexion (ankle: dorsiflexion) */
#define HUMAN_DOF_ABD 1  /* abduction (ankle: inversion, wrist: radial deviation, spine: left bend) */
#define HUMAN_DOF_ROT 2  /* internal rotation (wrist: pronation, spine: turn left) */
/* clavicle and eye dof indices */
#define HUMAN_DOF_CLAV_PROTRACT 0
#define HUMAN_DOF_CLAV_ELEVATE 1
#define HUMAN_DOF_EYE_YAW 0   /* abduction (temporal) */
#define HUMAN_DOF_EYE_PITCH 1 /* elevation */

/* reference sites used by behaviours ("segment.site") */
#define HUMAN_SITE_ROOT "pelvis.root"               /* default root, mid hip joints */
#define HUMAN_SITE_LOWER_TORSO "pelvis.lower_torso" /* at the standing centre of mass */
#define HUMAN_SITE_PELVIS "pelvis.center"
#define HUMAN_SITE_CHEST "T5.chest" /* the keep-vertical constraint's site */
#define HUMAN_SITE_HEAD "head.between_eyes"

/*
 * The balance reference of each foot (foot_*.balance) lies on the floor
 * this fraction of stature in front of the ankle joint: 3.5 cm for 1.75 m,
 * and within Carlsoo's 2-5 cm (§5.4.2.1, [20]) for every allowed stature.
 */
#define HUMAN_BALANCE_AHEAD 0.02

#define HUMAN_STATURE_MIN 1.0
#define HUMAN_STATURE_MAX 2.5
#define HUMAN_MASS_MIN 20.0
#define HUMAN_MASS_MAX 300.0

enum human_sex {
	HUMAN_MALE,
	HUMAN_FEMALE,
};

struct human_def {
	double stature; /* m */
	double mass;    /* kg */
	enum human_sex sex;
	/*
	 * ANSUR II measures the build must meet (mm; weightkg in kg), each used
	 * only where its bit (1u << HUMAN_M_x) is set in measure_given; a
	 * zero-initialised definition gives none, the figure from stature, mass
	 * and sex alone. Stature and mass stay in the two fields above.
	 */
	double measure[HUMAN_MEASURE_N];
	unsigned measure_given;
};

/*
 * 1.75 m / 75 kg for a man; for a woman the ANSUR II (2012) means of US Army
 * women, 1.628 m / 67.7 kg (Gordon et al. 2014, NATICK/TR-15/007).
 */
struct human_def human_default_def(enum human_sex sex);

/*
 * Builds the figure standing on the floor (y = 0), facing +z, x to its left.
 * Returns NULL with a message in err for a stature outside [1.0, 2.5] m, a
 * mass outside [20, 300] kg, an unknown sex, given measures no body can
 * meet (the message names them), or when out of memory.
 *
 * With measures given (measure_given != 0) the figure meets them as
 * pose/anthropometry.h measures it, within 2 mm and its mass exactly
 * (figure/human_dims.c says how, and what the measures not given become),
 * and it carries the surface landmarks anthropometry measures as sites:
 * acromion, shoulder_blade (clavicle_*); radiale (upperarm_*, where the
 * acromion-radiale length ends; forearm_*, where the radiale-stylion length
 * starts), stylion (forearm_*); dactylion, thumbtip (hand_*);
 * trochanterion, lateral_femoral_epicondyle, midpatella, suprapatella,
 * knee_front, popliteal (thigh_*); tibiale, lateral_malleolus (shank_*);
 * pternion (foot_*); acropodion (toes_*); iliocristale_l/_r,
 * ischial_tuberosity_l/_r, buttock_l/_r (pelvis); tragion_l/_r,
 * ectocanthus_l/_r, sellion, cervicale (head); suprasternale (T1). Without
 * measures it is today's figure, bit for bit and site for site: its site
 * indices, which posture hashes and recordings hold, stay as they were.
 */
struct model *human_build(const struct human_def *d, char *err, size_t errlen);

/* as human_build, with the landmark sites also when no measure is given */
struct model *human_build_landmarked(const struct human_def *d, char *err, size_t errlen);

#endif
