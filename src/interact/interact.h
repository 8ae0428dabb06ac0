/*
 * interact.h - the interactive modes around the manipulation operator:
 * which object G moves, through which view, and the pointer that makes the
 * mouse line. The daemon (or the kiosk) starts a mode, feeds it every
 * input event with the view's camera, and applies the target it reads
 * back; nothing here reads a clock, a device or the environment.
 *
 * A mode holds the object's frame in G's frame, fixed when the mode
 * starts, so the object follows G rigidly: moving a figure moves its root
 * site's frame (the figure's location) as G moves.
 *
 * The pointer: absolute positions (INPUT_POINTER, in the view's pixels or
 * 0..1 of the view) set it; relative motion moves it by the pixels the
 * caller computed from the counts (devices/motion_scale.h); it stays
 * inside the view. Every pointer change gives the operator a new mouse
 * line. ESC (pressed) ends the mode; G stays where it is.
 */
#ifndef POSTURE_INTERACT_INTERACT_H
#define POSTURE_INTERACT_INTERACT_H

#include "devices/event.h"
#include "draw/view.h"
#include "figure/mathx.h"
#include "figure/model.h"
#include "figure/state.h"
#include "interact/joint_manip.h"
#include "interact/manip.h"

enum interact_mode {
	INTERACT_NONE,
	INTERACT_FIGURE, /* manipulate figure: the figure's location follows G */
	INTERACT_DRAG,   /* drag: G is the goal of a constraint on a site (§4.6.1) */
	INTERACT_JOINT,  /* manipulate joint: the buttons turn its DOFs (§3.8) */
	INTERACT_PRIMITIVE, /* a Chapter 5 primitive (Table 5.2): G feeds a behaviour command */
	INTERACT_SITE,   /* manipulate site: the site moves on its segment with G */
};

/* the primitives a mode can drive, as the behaviour commands name them */
enum interact_primitive {
	INTERACT_HAND, /* move hand: G is the palm's goal */
	INTERACT_FOOT, /* move foot: G is the foot's goal */
	INTERACT_COM,  /* move com: G's motion shifts the balance point, and the height */
	INTERACT_HEAD, /* move head: G is the point the head fixates */
	INTERACT_EYES, /* move eyes: G is the point the eyes fixate */
	INTERACT_PELVIS, /* rotate pelvis: G's turns turn the pelvis relative to the feet */
	INTERACT_TORSO,  /* bend torso: G's turn in the pelvis's axes is the spine's bend */
};

/* what interact_input did */
#define INTERACT_MOVED 0x1 /* G moved: apply interact_target() */
#define INTERACT_ENDED 0x2 /* the mode ended (ESC) */
#define INTERACT_ICONS 0x4 /* the chord changed: the icons change, G did not move */
#define INTERACT_RELEASED 0x8 /* a button came up (dragging: the orientation offset resets) */

#define INTERACT_MESSAGE_MAX 128

struct interact {
	enum interact_mode mode;
	int fig;              /* the object: a figure slot */
	unsigned long tag;    /* the caller's: e.g. the slot's generation, to tell a reused slot */
	int con;              /* dragging: the constraint whose goal G is, and its tag */
	unsigned long con_tag;
	int view;             /* the view the pointer is in */
	double px, py;        /* the pointer, the view's pixels (origin top left) */
	struct camera cam;    /* the camera the operator last saw */
	int width, height;
	struct manip m;
	struct manip_def def; /* the operator every mode starts with: increments' sizes ... */
	int increments;       /* ... and whether they are on, kept from mode to mode */
	struct xform offset;  /* the object in G's frame */
	/* manipulating a joint: the figure (kin_update done), the joint, and what moved */
	const struct model *model;
	const struct state *state;
	int joint;
	struct joint_manip jm;
	int site;             /* INTERACT_SITE: the site G carries */
	enum interact_primitive primitive; /* INTERACT_PRIMITIVE: which, and the side */
	int side;
	double applied_r[9];  /* INTERACT_PELVIS: G's rotation the pelvis has been turned to;
			       * INTERACT_TORSO: G's rotation when the mode began */
	double torso0[3];     /* INTERACT_TORSO: the spine's bend (flexion, lateral, axial) then */
	int moved_dof;        /* INTERACT_MOVED in joint mode: this DOF (model index) ... */
	double moved_value;   /* ... takes this value */
	char message[INTERACT_MESSAGE_MAX];
};

void interact_init(struct interact *ia);

/*
 * Starts mode on figure fig through view (its camera cam, its size w x h):
 * G starts at g0, the object is at obj (both world). The pointer starts at
 * the view's centre. A mode already running is ended first.
 */
void interact_start(struct interact *ia, enum interact_mode mode, int fig, int view,
		    const struct xform *g0, const struct xform *obj, const struct camera *cam,
		    int w, int h);

/*
 * One input event, with the view's camera and size now (they may have
 * changed since the last event) and, for INPUT_MOTION, the motion in
 * pixels. Returns INTERACT_* bits; 0 when nothing happened (no mode, an
 * event of no meaning here).
 */
int interact_input(struct interact *ia, const struct input_event_rec *e, long px, long py,
		   const struct camera *cam, int w, int h);

/* the view's camera or size changed between events (an automatic adjustment): tell the operator */
void interact_camera(struct interact *ia, const struct camera *cam, int w, int h);

/* where the object goes: G times the offset */
void interact_target(const struct interact *ia, struct xform *dest);

/*
 * Dragging (§4.6.2): when a button comes up, the orientation offset
 * between G and the effector resets: G takes the effector's orientation
 * (at effector, world), keeping its origin; the next motion goes on from
 * there.
 */
void interact_reset_orientation(struct interact *ia, const struct xform *effector);

/*
 * Starts manipulating joint `joint` of a figure (model m, state s, kept
 * current by the caller while the mode lasts) through a view. G sits on
 * the joint's pivot. INTERACT_MOVED then means: set DOF moved_dof to
 * moved_value and update the figure.
 */
void interact_start_joint(struct interact *ia, int fig, int view, const struct model *m,
			  const struct state *s, int joint, const struct camera *cam, int w, int h);

/*
 * Joint mode: a value typed for the selected DOF (its displacement from
 * where it was selected, in the DOF's own sense). Returns 1 with
 * moved_dof and moved_value set (apply them as for INTERACT_MOVED), 0
 * when no DOF is selected.
 */
int interact_joint_type(struct interact *ia, double typed);

/* 1 when the joint mode's selected DOF is a rotation, 0 a translation, -1 none selected */
int interact_joint_rotation(const struct interact *ia);

/* DOF dof of a figure as the mouse sees it now (kin_update done); see joint_manip.h */
void interact_dof_view(const struct model *m, const struct state *s, int dof,
		       struct joint_dof_view *dest);

/*
 * Increments on or off, and their sizes (metres, radians, > 0): for the
 * mode running and every mode after it. A person sets them once.
 */
void interact_increments(struct interact *ia, int on, double step, double step_angle);

/* the mouse buttons held in the mode (MANIP_LEFT | MANIP_MIDDLE | MANIP_RIGHT), 0: none */
unsigned interact_buttons(const struct interact *ia);

/* the mode's name as the commands give it: "figure", "joint", "drag", "site", "hand", ... */
const char *interact_name(const struct interact *ia);

void interact_end(struct interact *ia);

const char *interact_mode_to_str(enum interact_mode m);
/* "hand", "foot", "com", "head", "eyes", "pelvis", "torso": as the modes are named */
const char *interact_primitive_to_str(enum interact_primitive p);

#endif
