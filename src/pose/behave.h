/*
 * behave.h - behaviours of the human figure (Chapter 5, Appendix D): the
 * natural constraints on toes, heels, pelvis, centre of mass, torso, head,
 * eyes and hands; the behavioural parameters that shape them (Tables 5.1,
 * D.1-D.4); the passive behaviours run every frame (balance point follows
 * feet, pelvis follows feet orientation, automatic rooting, root through the
 * centre of mass); the manipulation primitives (move foot, move centre of
 * mass, rotate pelvis, move hand, move head, move eyes; bend torso comes
 * with the spine model); and the active behaviour "take step when losing
 * balance" and "take step when pelvis is twisted" as motion primitives
 * that last a number of frames.
 *
 * A struct behave drives one human figure's struct ik: behave_attach adds
 * its constraints (after whatever constraints the ik already holds) and
 * behave_frame runs one iteration of Figure 5.1's loop: behaviours, then the
 * solve. Nothing allocates after behave_attach.
 */
#ifndef POSTURE_BEHAVE_H
#define POSTURE_BEHAVE_H

#include "pose/balance.h"
#include "pose/ik.h"
#include "pose/point_mass.h"
#include "pose/spine.h"

enum behave_side {
	BEHAVE_LEFT,
	BEHAVE_RIGHT,
};

enum foot_behavior {
	FOOT_PIVOT,       /* toes stay put and flat, free to turn about the vertical */
	FOOT_HOLD_GLOBAL, /* position and orientation fixed in space */
};

enum heel_behavior {
	HEEL_KEEP_ON_FLOOR,
	HEEL_ALLOW_RISE,
};

enum torso_behavior {
	TORSO_KEEP_VERTICAL,  /* the chest's up axis vertical, free to turn (§D.1.3) */
	TORSO_HOLD_GLOBAL,    /* the chest's whole orientation held */
	TORSO_FREE,
};

enum hand_behavior {
	HAND_FREE,
	HAND_HOLD_GLOBAL, /* where it is now, in space */
	HAND_ON_HIPS,
	HAND_ON_KNEES,
	HAND_ON_SITE,     /* a site of the figure, position and orientation */
};

struct behave_params {
	enum foot_behavior foot[2];
	enum heel_behavior heel[2];
	int foot_follows_line;    /* a moved foot keeps its angle to the balance line (§D.2.2) */
	int hands_laban;          /* a moved hand takes Labanotation's palm orientation (§D.2.4) */
	int seated;               /* rooted at the lower torso; the heels, not the toes, hold the
				   * feet, and balance and stepping rest (§D.1.1) */
	int hold_elevation;       /* the centre of mass keeps its height (§D.1.2) */
	enum torso_behavior torso;
	int fixate_head, fixate_eyes;
	double head_point[3], eyes_point[3];
	enum hand_behavior hand[2];
	int hand_site[2];         /* HAND_ON_SITE: the site */
	double spring_angle;      /* knees and elbows (§D.1.6) */
	/* passive behaviours */
	int balance_follows_feet; /* the balance point keeps its x and z as the feet move */
	int pelvis_follows_feet;  /* the pelvis turns with the feet's mean heading */
	int auto_root;            /* the 60 % / 70 % rules (§5.4.2.4) */
	int root_through_com;     /* zero gravity: the centre of mass stays put (§D.2.5) */
	/* active behaviours */
	int step_when_losing_balance;
	int step_when_twisted;    /* the pelvis turned past twist_limit from the feet (§D.3.2) */
	double twist_limit;       /* radians, 45 degrees by default */
	int step_frames;          /* a step's duration */
	double stability_threshold; /* m: a margin below it is "low" (the stability alert) */
};

struct behave_params behave_default_params(void);

/* a timed movement of a foot (§5.4.3): from -> to over frames, lifted on the way */
struct behave_step {
	int active;
	int side;
	int frame, frames;
	struct xform from, to;
};

#define BEHAVE_NCON 12 /* the natural constraints: toes, heels, balance, pelvis, torso, head, eyes, hands */

struct behave {
	struct behave_params p;
	struct ik_constraint_def def[BEHAVE_NCON]; /* kept while the solver is refilled */
	/* the constraints' indices in the ik */
	int c_toe[2], c_heel[2], c_balance, c_pelvis, c_torso, c_head, c_eye[2], c_hand[2];
	/* sites and joints used every frame */
	int s_toe[2], s_heel[2], s_tip[2], s_pelvis, s_lower, s_chest, s_head, s_eye[2], s_palm[2];
	int s_hip[2], s_knee[2], s_shoulder[2];
	int j_clav[2], j_spine0, j_neck, j_eye[2];
	double leg_length;        /* hip height standing, for the 70 % rule */
	/* what the behaviours hold */
	double bal_x, bal_z;      /* the balance point's parameters */
	double bal_point[2];      /* where the balance point goes this frame */
	double elevation;         /* the centre of mass's height when held */
	double pelvis_turn[9];    /* the pelvis's orientation relative to the feet's heading */
	double com_fixed[3];      /* root through the centre of mass: where it stays */
	enum balance_root root;
	struct balance bal;       /* measured this frame */
	struct behave_step step;
	int steps_taken;
	int stability_low;     /* the margin is below the threshold, as last measured */
	int stability_changed; /* ... and was not when the last alert was told (at the solve) */
	int alert_low;         /* stability_low as the last solve told it */
	int detached; /* def[] holds the constraints; they are not (yet) in the solver */
	/* the weights carried (behave_set_masses): not packed, the environment's loads */
	struct point_mass mass[POINT_MASS_MAX];
	int nmass;
	int masses_adopt; /* unpacked: the next masses are those it was packed with */
};

/*
 * Sets up behaviour for the human (m, s) on ik: roots it through the left
 * toes, adds its natural constraints holding the current posture, the limit
 * springs, and the current balance parameters. Returns 0, or -1 when the
 * figure lacks a needed site or the ik is full.
 */
int behave_attach(struct behave *b, const struct model *m, struct state *s, struct ik *ik,
		  const struct behave_params *p);

/*
 * A posture put on the figure from outside (a reach taken): the behaviours
 * attached again on ik, emptied of their constraints by the caller, holding
 * the posture s as it now is (feet, balance point, pelvis, torso, hands),
 * with the same parameters, weights and steps taken, so the next frame does
 * not pull the body back. Returns 0, or -1 as behave_attach.
 */
int behave_hold_posture(struct behave *b, const struct model *m, struct state *s, struct ik *ik);

/*
 * One frame: passive and active behaviours update the constraints, then
 * the ik solves (with opt and clock) and the balance is measured again.
 * The solve is the frame's only use of the clock, so the result's work,
 * given back as opt->replay to a behaviour in the same state, replays the
 * frame exactly (ik_work.h).
 */
struct ik_result behave_frame(struct behave *b, const struct model *m, struct state *s,
			      struct ik *ik, const struct ik_options *opt,
			      const struct ik_clock *clock);

/*
 * The solver is about to be cleared and refilled (a figure's constraint set
 * changed): keep the behaviour's constraints, then add them back after the
 * others. behave_restore_constraints returns 0, or -1 when the ik is full.
 */
void behave_keep_constraints(struct behave *b, const struct ik *ik);
int behave_restore_constraints(struct behave *b, const struct model *m, struct ik *ik);

/*
 * The weights the figure carries (point_mass.h), set before each frame:
 * balance (its constraint, the balance point and parameters, the margin and
 * the stability alert, stepping) and root through the centre of mass hold
 * the centre of mass of the figure with them, so a weight held out in front
 * moves the hips back. What is held where the figure stands (a held
 * elevation, the fixed centre of mass) moves with the jump a change of
 * weights makes, so the body does not rise or slide for it; the first
 * masses after behave_unpack are taken as those the state was packed with
 * (and balance is measured again with them, as behave_measure).
 * The rooting and squat tests read the body's own height (they tell a
 * posture). Returns 0, or -1 for masses the figure cannot carry (nothing
 * changes). s needs kin_com.
 */
int behave_set_masses(struct behave *b, const struct model *m, const struct state *s,
		      const struct point_mass *pm, int n);
/* the centre of mass balance holds: the figure's with its weights (needs kin_com) */
void behave_com(const struct behave *b, const struct state *s, double dest[3]);

/* the behaviour's constraint k (0..BEHAVE_NCON-1) as it stands */
const struct ik_constraint_def *behave_def(const struct behave *b, const struct ik *ik, int k);

/*
 * Parameters and state as numbers, for session files and the journal:
 * behave_pack writes at most max values and returns how many it needs;
 * behave_unpack rebuilds b for model m from them (its constraints then
 * come from def[], set by the caller, at the next behave_restore_constraints).
 * Returns 0, or -1 for a wrong count or a figure that is not a human.
 */
int behave_pack(const struct behave *b, double *dest, int max);
int behave_unpack(struct behave *b, const struct model *m, const double *v, int n);

/* applies changed parameters (foot, heel, torso, head, eyes, hands) to the constraints */
void behave_set_params(struct behave *b, const struct model *m, struct state *s, struct ik *ik,
		       const struct behave_params *p);

/*
 * The balance measured again on the posture as it is (a figure restored
 * from a session): the margin, and whether it is low, as a solve leaves
 * them; the alert's edge is not moved (a restored state tells no alert).
 */
void behave_measure(struct behave *b, const struct model *m, const struct state *s);

/* ---- manipulation primitives (Table 5.2): goals the frames walk to ---- */

/* the foot's toes to a frame on the floor; the support moves to the other foot */
void behave_move_foot(struct behave *b, const struct model *m, struct state *s, struct ik *ik,
		      int side, const struct xform *goal);
/* the site that holds a foot: the toes standing, the heel seated (§D.1.1) */
int behave_foot_site(const struct behave *b, int side);
/* the foot's holding site to goal (standing: the toes, and the heel's place on the
 * floor; seated: the heel's whole frame); the support stays as it is */
void behave_set_foot_goal(struct behave *b, struct ik *ik, int side, const struct xform *goal);
/* the balance point by (dx, dz) on the floor and the centre of mass up by dy (0: free) */
void behave_move_com(struct behave *b, const struct model *m, struct state *s, struct ik *ik,
		     double dx, double dz, double dy);
/*
 * Bends the torso by total angles (flexion, lateral, axial; radians)
 * distributed over the vertebrae as the flavour says (§5.5.3, §D.1.3), then
 * holds the chest's new orientation while the rest of the body balances
 * (Figure 5.7). Returns 0, or -1 for a bad flavour or total.
 */
int behave_bend_torso(struct behave *b, const struct model *m, struct state *s, struct ik *ik,
		      const double total[3], const struct spine_flavor *flavor);

/* the pelvis turned by r (world axes) relative to the feet's heading */
void behave_rotate_pelvis(struct behave *b, const struct model *m, struct state *s,
			  struct ik *ik, const double r[9]);
/* the palm (or, from_wrist, the forearm just above the wrist) to goal */
void behave_move_hand(struct behave *b, const struct model *m, struct state *s, struct ik *ik,
		      int side, const struct xform *goal, int from_wrist);
/*
 * Hands maintain consistent orientation (§D.2.4): the arm's region for a
 * palm at p (relative to the shoulder, in the chest's frame), and the
 * palm orientation Labanotation gives a hand arriving at goal->p from
 * another region (palms in when hanging, facing each other raised forward
 * or up, forward when out to the side, backward across the body). Within
 * one region the goal's orientation is left as it is.
 */
enum hand_region { REGION_HANG, REGION_FORWARD_UP, REGION_SIDE, REGION_ACROSS };
enum hand_region behave_hand_region(const struct behave *b, const struct state *s, int side,
				    const double p[3]);
void behave_predict_hand(const struct behave *b, const struct state *s, int side, struct xform *goal);
void behave_move_head(struct behave *b, struct ik *ik, const double point[3]);
void behave_move_eyes(struct behave *b, struct ik *ik, const double point[3]);

#endif
