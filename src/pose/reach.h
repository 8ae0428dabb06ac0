/*
 * reach.h - "can she reach it?" (§6.1's reach analysis): a hand's palm sent
 * to a target by the solver on a copy of the figure's state, so nothing the
 * person sees changes, and the verdict read from where the palm ends up.
 *
 * The mode says what may move. REACH_ARM: the arm from the clavicle (the
 * chain of the behaviours' hand constraint, §D.1.5). REACH_TORSO: the arm
 * and the spine's vertebrae from spine_0 (L5/S1) up, within each joint's
 * limits, the rest of the body held. REACH_BODY: the behaviours' whole
 * body: the hand's chain runs down through the legs to the root, both feet
 * held where they stand (toes and heels), and with balance on, the centre
 * of mass (with the weights carried) held over the balance point, so the
 * figure bends, squats and shifts to reach. The behaviours' knee and
 * elbow springs (§D.1.6) are off: a reach goes to the joints' limits.
 *
 * A reach object is made once for a model and reused: solving allocates
 * nothing.
 */
#ifndef POSTURE_REACH_H
#define POSTURE_REACH_H

#include "figure/model.h"
#include "figure/state.h"
#include "pose/behave.h"

enum reach_mode { REACH_ARM, REACH_TORSO, REACH_BODY };

#define REACH_TOL_POS 1e-3 /* m: the palm within this of the target has reached it */
#define REACH_TOL_ORI (1.0 * 3.14159265358979323846 / 180) /* rad: and, with rot, turned to it */
#define REACH_LIMITING_MAX 32

struct reach_request {
	int side;          /* BEHAVE_LEFT or BEHAVE_RIGHT */
	double target[3];  /* the palm's goal, world frame */
	int oriented;      /* 1: the palm's axes to rot as well */
	double rot[9];
	enum reach_mode mode;
	int balance;       /* REACH_BODY: 1 holds the centre of mass over the balance point */
	int restarts;      /* 0 ("can reach"): one solve from the posture; n > 0: stuck short
			      of the target, up to n more from random postures within the limits
			      (the same ones for the same request), the best kept */
};

struct reach_result {
	int reached;     /* distance <= REACH_TOL_POS (and angle <= REACH_TOL_ORI when oriented) */
	double distance; /* m: palm to target after the solve */
	double palm[3];  /* where the palm ended, world frame: a point the hand reaches */
	double angle;    /* rad: palm axes to rot (0 when not oriented) */
	double margin;   /* m: the centre of mass's stability margin in the reached posture */
	int limiting[REACH_LIMITING_MAX]; /* joints with a moved dof resting on a limit */
	int nlimiting;
	struct ik_result ik;
};

struct reach;

/* a reach solver for human model m, or NULL (not a human, or out of memory) */
struct reach *reach_make(const struct model *m);
void reach_free(struct reach *r);

/*
 * Solves q from the posture s (unchanged; it needs current frames and
 * centre of mass) with the behaviour parameters p (NULL: the defaults) and
 * the weights the figure carries (pm, n). Returns 0 with *res filled, or
 * -1 for a bad request (side, mode, non-finite numbers).
 */
int reach_solve(struct reach *r, const struct model *m, const struct state *s,
		const struct behave_params *p, const struct point_mass *pm, int n,
		const struct reach_request *q, struct reach_result *res);

/* the posture the last solve reached (or came nearest with) */
const struct state *reach_posture(const struct reach *r);

#endif
