/*
 * manip.h - the manipulation operator of Chapter 3 (Appendix B): the three
 * mouse buttons, SHIFT and CONTROL choose an axis, a plane or a wheel
 * (Table 3.2), and the mouse line moves the manipulation transform G along
 * it, in it or around it.
 *
 * The caller feeds three things, in any order:
 *   manip_event()  button and key records (devices/event.h);
 *   manip_ray()    the mouse line, again after every pointer motion;
 *   manip_camera() the camera, again whenever it moves.
 * It reads back G (m->g), the state, what to draw (manip_icon) and a
 * refusal (manip_refusal). Nothing here reads a clock or a device.
 *
 * Pressing a button never moves G. Every change of the chord (buttons and
 * modifiers) and every camera change re-anchors: G and the reference (the
 * nearest point of the axis, the point in the plane, the spoke) are taken
 * at that moment, and later rays move G by the change of the reference
 * since then. So a press anywhere on the screen, a change of buttons
 * mid-drag or a camera that moves under a held button makes no jump.
 *
 * The 20 degree rule (section 3.7) is checked when a chord is chosen and
 * when the camera changes: translating along an axis closer than the limit
 * to the line of sight, or rotating about an axis, or translating in a
 * plane, whose plane is closer than the limit to edge-on, is refused: the
 * state is MANIP_REFUSED, G stays, and manip_refusal() says why and
 * whether the user chose that same axis again after the warning, the
 * trigger of the automatic view adjustment. "Chose" is decided on the
 * chord a press of the buttons settles on (held when its first key comes
 * up), not on the chords it passes through while keys go down or up one
 * at a time, so a plane or a wheel has its second try as an axis does.
 *
 * The line of sight is the line from the camera's eye to G's origin, not
 * the camera's -z: in perspective an axis through an object off the
 * centre of the screen degenerates when it points at the eye, and section
 * 3.7's adjustment turns the camera about G's origin to move the line from
 * the eye to the origin away from the axis. When the eye sits on G's
 * origin the camera's -z stands in.
 */
#ifndef POSTURE_INTERACT_MANIP_H
#define POSTURE_INTERACT_MANIP_H

#include "devices/event.h"
#include "draw/view.h"
#include "figure/mathx.h"
#include "interact/ray.h"

/* the buttons as bits of a chord, in Table 3.2's order: x, y, z */
#define MANIP_LEFT 0x1   /* x */
#define MANIP_MIDDLE 0x2 /* y */
#define MANIP_RIGHT 0x4  /* z */

enum manip_mode {
	MANIP_MODE_IDLE,   /* no button */
	MANIP_MODE_LINEAR, /* one button: along that axis (B.1) */
	MANIP_MODE_PLANAR, /* two buttons: in the plane of their axes (B.2) */
	MANIP_MODE_ROTATE, /* CONTROL and one button: about that axis (B.3) */
	MANIP_MODE_NONE,   /* three buttons, or CONTROL with two or three: no effect */
};

enum manip_frame {
	MANIP_GLOBAL, /* the world's axes */
	MANIP_LOCAL,  /* G's axes (SHIFT) */
};

/* one row of Table 3.2 */
struct manip_selection {
	enum manip_mode mode;
	enum manip_frame frame;
	/*
	 * LINEAR, ROTATE: the axis, 0 1 2 for x y z. PLANAR: the axis
	 * whose button is up, the plane's normal (xy plane: 2).
	 */
	int axis;
};

enum manip_state {
	MANIP_IDLE,
	MANIP_NONE,    /* a chord with no action */
	MANIP_REFUSED, /* the 20 degree rule refused the chord's action */
	MANIP_LINEAR,
	MANIP_PLANAR,
	MANIP_ROTATE,
};

/*
 * ALT and increments are not in the dissertation; they follow what users
 * of current tools expect (Blender: a tenth of the motion, steps while
 * snapping). Both act on the motion since the anchor, so G keeps its
 * place when they turn on or off.
 */
struct manip_def {
	double limit;      /* the degenerate-axis threshold, radians (section 3.7: 20 degrees) */
	double fine;       /* the fraction of the motion while ALT is held (0.1) */
	double step;       /* increments: metres of translation along each axis (0.01) */
	double step_angle; /* increments: radians of rotation (5 degrees) */
};

/* why the current chord does nothing, for the message line and the view adjustment */
struct manip_refusal {
	int active;  /* 1 while MANIP_REFUSED */
	int repeat;  /* 1 when the last press settled on this selection's refusal, no action since */
	struct manip_selection sel;
	double angle;        /* between the axis (or the plane's normal) and the line of sight, rad */
	double axis[3];      /* the refused axis or normal, world, unit */
	const char *message; /* "can't translate along that axis from this view", ... */
};

/* what section 3.6's icons need; valid in every state */
struct manip_icon {
	enum manip_state state;
	struct manip_selection sel;
	double origin[3];   /* G's origin: where the arrow, plane or wheel is drawn */
	double axis[3];     /* LINEAR, ROTATE: the axis; PLANAR: the normal; world, unit */
	double u[3], v[3];  /* PLANAR: the plane's two axes (lower index first); ROTATE: wheel plane, u x v = axis */
	int has_spokes;     /* ROTATE, once a mouse line has met the wheel's plane */
	double spoke0[3];   /* the first spoke (from the origin to the first point), world */
	double spoke[3];    /* the current spoke */
	double angle;       /* ROTATE: the spokes' turn since the anchor, rad (may pass +-pi) */
};

struct manip {
	double limit;
	/* the inputs */
	unsigned buttons;  /* MANIP_LEFT | MANIP_MIDDLE | MANIP_RIGHT */
	unsigned shift;    /* bit 0 the left key, bit 1 the right one */
	unsigned ctrl;
	unsigned alt;
	int increments;    /* manip_increments() */
	double fine, step, step_angle;
	struct ray ray;
	int have_ray;
	struct camera cam;
	/* the state */
	enum manip_state state;
	struct manip_selection sel;
	struct xform g;    /* the manipulation transform, world */
	/* the anchor: G and the reference when the chord or camera last changed */
	int anchored;      /* 0 until a mouse line meets the axis, plane or wheel */
	struct xform g0;
	struct xform chord_g0; /* G when the chord was chosen: what a typed value counts from */
	double axis[3];    /* world, unit: the axis, or the plane's normal */
	double u[3], v[3]; /* the plane's axes (index order), or the wheel's (u x v = axis) */
	double s0;         /* LINEAR: axis parameter of the nearest point */
	double x0[3];      /* PLANAR: the point in the plane */
	double spoke0[3], spoke[3]; /* ROTATE: first and latest spoke */
	double angle;      /* ROTATE: summed turn of the spokes since the anchor */
	/* the 20 degree rule */
	struct manip_refusal refusal;
	int have_last_refused;              /* the last press settled on a refusal ... */
	struct manip_selection last_refused; /* ... of this selection */
	int settled;                        /* this press's choice is taken (a key came up) */
	struct manip_selection settled_sel; /* that choice */
	enum manip_state settled_state;     /* and whether it was refused or acted */
};

/* 20 degrees; ALT a tenth; increments of 1 cm and 5 degrees */
struct manip_def manip_default_def(void);

/* an idle operator on G seen through cam, no button or key down */
void manip_init(struct manip *m, const struct manip_def *def, const struct xform *g,
		const struct camera *cam);

/*
 * Table 3.2: the selection a chord makes. buttons is a MANIP_LEFT...
 * mask; shift and ctrl are 0 or not.
 */
struct manip_selection manip_chord(unsigned buttons, int shift, int ctrl);

/*
 * A button (BTN_LEFT, BTN_MIDDLE, BTN_RIGHT) or key (KEY_LEFTSHIFT,
 * KEY_RIGHTSHIFT, KEY_LEFTCTRL, KEY_RIGHTCTRL, KEY_LEFTALT, KEY_RIGHTALT)
 * record. Returns 1 when the chord changed (the selection was re-made, or
 * for ALT the motion re-anchored; G did not move), 0 for anything else:
 * other codes and kinds, key repeats, a press of what is already down.
 */
int manip_event(struct manip *m, const struct input_event_rec *ev);

/*
 * A new mouse line. Returns 1 when G moved. A line that does not meet the
 * axis, plane or wheel (parallel, behind the eye, through the wheel's
 * centre) leaves G where it was.
 */
int manip_ray(struct manip *m, const struct ray *r);

/*
 * The camera moved: the 20 degree rule is checked again (a refused chord
 * may become active, an active one refused) and the next mouse line
 * re-anchors, so the view change itself does not move G.
 */
void manip_camera(struct manip *m, const struct camera *cam);

/* motion in steps of def.step and def.step_angle since the anchor (on 1) or free (0); re-anchors */
void manip_increments(struct manip *m, int on);

/*
 * The increments' sizes (metres, radians; both > 0): the motion so far is
 * G's, the rest counts from here in the new steps, as when increments turn on.
 */
void manip_steps(struct manip *m, double step, double step_angle);

/*
 * A value typed during a manipulation (Blender's way: "10cm", "-30deg"):
 * G is the chord's starting G moved exactly that far along the active axis
 * (LINEAR) or turned that far about it (ROTATE); the mouse goes on from
 * there, and a further value again counts from the chord's start. Returns
 * 0, or -1 in any other state (nothing moves).
 */
int manip_type(struct manip *m, double value);

/* G set from outside (snapping, a command): kept, and the next mouse line re-anchors */
void manip_set(struct manip *m, const struct xform *g);

void manip_icon(const struct manip *m, struct manip_icon *dest);

/* the refusal, with active 0 unless the state is MANIP_REFUSED */
const struct manip_refusal *manip_refusal(const struct manip *m);

const char *manip_state_to_str(enum manip_state s);
const char *manip_mode_to_str(enum manip_mode md);

#endif
