/*
 * viewctl.h - the change view mode of Appendix C.2: a state machine that
 * takes input events and frame times and moves one view's camera with
 * viewop's sweep, pan, zoom and snap. One struct viewctl per view: each
 * view has its own camera, gains and mode.
 *
 * V enters change view from any mode of the caller, even in the middle of
 * a manipulation; the caller's mode is kept and handed back when the mode
 * ends. ESC ends it keeping the view; C ends it restoring the camera as it
 * was when V was pressed. Inside, with pointer motion in pixels (x right,
 * y down):
 *
 *   left            sweep about the world vertical through R    <- dx
 *   middle          sweep about the camera's x through R        <- dy
 *   right           zoom along the line of sight, R kept         <- dy
 *   left + middle   both sweeps (the camera rides a sphere about R)
 *   left + right    horizontal sweep <- dx, zoom <- dy
 *   middle + right  vertical sweep <- dy, zoom <- dx (C.2.1: not one valuator for two)
 *   all three       nothing (no third valuator)
 *
 * Holding CONTROL turns both sweeps into pans (the camera pivots about
 * its own origin); the zoom stays a zoom. Whatever moves follows the
 * pointer, the eyeball in hand of C.1.2: sweeping right moves the camera
 * right round R and up lifts it; panning right turns the line of sight
 * (and R) right and up raises it; pushing the pointer up zooms in. A
 * negative gain turns a direction round.
 *
 * S then a left click snaps R to the picked feature (C.3): the machine
 * answers VIEWCTL_PICK and the caller picks (pick.h) and calls
 * viewctl_snap_to(); then viewctl_frame() each frame gives the eased
 * in-betweens until the snap is done.
 *
 * Motion events carry pixel deltas in x, y: the caller scales device
 * counts to pixels before they come here, and feeds every event through
 * viewctl_event() first, idle or not, so CONTROL is known whenever it was
 * pressed. Buttons count from V on: one already held at V (a manipulation
 * under way) does nothing here until pressed again.
 */
#ifndef POSTURE_INTERACT_VIEWCTL_H
#define POSTURE_INTERACT_VIEWCTL_H

#include <stdint.h>

#include "devices/event.h"
#include "draw/view.h"
#include "interact/viewop.h"

enum viewctl_state {
	VIEWCTL_IDLE,      /* not in change view: the caller's mode has the events */
	VIEWCTL_VIEWING,   /* buttons and motion sweep, pan and zoom */
	VIEWCTL_SNAP_PICK, /* S pressed: the next left click picks the new view reference point */
	VIEWCTL_SNAPPING,  /* the snap's in-betweens, one per frame */
};

enum viewctl_result {
	VIEWCTL_PASS,    /* not for change view: the caller's mode takes the event */
	VIEWCTL_TAKEN,   /* taken; the camera did not change */
	VIEWCTL_CHANGED, /* taken; the camera changed: redraw */
	VIEWCTL_ENTERED, /* V: change view began */
	VIEWCTL_PICK,    /* pick under the pointer now and call viewctl_snap_to() */
	VIEWCTL_ENDED,   /* ESC or C: back to vc->caller_mode; the camera may have changed */
};

/*
 * Gains and times. Sweep and pan map pixels to angles (C.2.1.2: "maps them
 * to angles according to mouse gain parameters"); the zoom's gain
 * "measures linear distances" (C.2.3.2), so it is metres per pixel.
 */
struct viewctl_gains {
	double rad_per_px;    /* sweep and pan */
	double m_per_px;      /* zoom */
	uint64_t snap_us;     /* the longest a snap takes (C.3: one second) */
	double snap_min_rad;  /* the least a snap turns per frame */
};

/* 0.5 deg and 1 cm per pixel, a snap of at most 1 s turning at least 0.5 deg a frame */
struct viewctl_gains viewctl_default_gains(void);

struct viewctl {
	enum viewctl_state state;
	struct viewctl_gains gains;
	int caller_mode;       /* the caller's mode when V came, handed back at the end */
	struct camera before;  /* the camera when V came, for C */
	unsigned buttons;      /* VIEWCTL_BTN_* held, pressed since V */
	int control;           /* CONTROL held (either key) */
	struct viewop_snap snap;
};

#define VIEWCTL_BTN_LEFT 1u
#define VIEWCTL_BTN_MIDDLE 2u
#define VIEWCTL_BTN_RIGHT 4u

/* an idle machine with the given gains */
void viewctl_init(struct viewctl *vc, const struct viewctl_gains *gains);

/*
 * Feeds one event. cam is this view's camera, changed in place. When idle,
 * only V is taken (VIEWCTL_ENTERED), and caller_mode is remembered as the
 * mode to return to; in change view, caller_mode is not looked at.
 * Returns what the caller should do (enum viewctl_result).
 */
enum viewctl_result viewctl_event(struct viewctl *vc, struct camera *cam, int caller_mode,
				  const struct input_event_rec *ev);

/*
 * The answer to VIEWCTL_PICK: target is the picked point, or NULL when
 * nothing was hit. Starts the snap at now_us and returns VIEWCTL_TAKEN,
 * or VIEWCTL_TAKEN back in VIEWCTL_VIEWING when there is nothing to snap
 * to (no hit, or a point viewop_snap_begin refuses). Outside
 * VIEWCTL_SNAP_PICK it does nothing and returns VIEWCTL_PASS.
 */
enum viewctl_result viewctl_snap_to(struct viewctl *vc, const struct camera *cam,
				    const double target[3], uint64_t now_us);

/*
 * Once a frame, before drawing: while snapping, moves cam to the
 * in-between for now_us (VIEWCTL_CHANGED), back to VIEWCTL_VIEWING after
 * the last. Otherwise VIEWCTL_TAKEN in change view, VIEWCTL_PASS when idle.
 */
enum viewctl_result viewctl_frame(struct viewctl *vc, struct camera *cam, uint64_t now_us);

const char *viewctl_state_to_str(enum viewctl_state s);

#endif
