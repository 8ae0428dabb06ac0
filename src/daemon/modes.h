/*
 * modes.h - the interactive modes the input drives and the views they
 * move: the manipulation mode (src/interact/interact.h) applied to the
 * figures, change view (V, Appendix C), the automatic viewing adjustments
 * of §3.7 (a refused axis chosen again, an object off the screen or
 * hidden, a dragged object near the edge) with C to take one back. The
 * loop hands it every input event and calls modes_frame once a frame;
 * what changes state for good (a drag's end, a view left) goes through
 * run_command, so the journal has it as a command.
 */
#ifndef POSTURE_DAEMON_MODES_H
#define POSTURE_DAEMON_MODES_H

#include <stdint.h>

#include "daemon/daemon.h"
#include "daemon/scene.h"
#include "devices/event.h"
#include "interact/interact.h"
#include "interact/kiosk.h"
#include "interact/menu.h"
#include "interact/prompt.h"
#include "interact/view_adjust.h"
#include "interact/viewctl.h"

#define MODES_VIEW_UNDO 8      /* automatic view changes remembered per view */
#define MODES_EDGE_MARGIN 0.1  /* a dragged G this near the picture's edge: the view follows */

/* a button held this long ends its drag (never a mode stuck in a step) */
#define MODES_HELD_MAX_US (60ull * 1000000)

/* the segments a figure may have for its own body to obstruct (more: all of it is left out) */
#define MODES_MAX_SEGMENTS 1024

struct modes {
	struct daemon *d;
	struct scene *scene; /* its dirty flag: a picture changed */
	void (*run_command)(void *ctx, const char *line); /* a line run and journaled */
	void *ctx;
	struct interact interact;              /* the mode the input drives */
	struct viewctl viewctl[ENV_MAX_VIEWS]; /* change view, one machine per view */
	struct view_adjust adjust[ENV_MAX_VIEWS]; /* §3.7's automatic adjustments under way */
	/* the cameras before each automatic change, newest last: C takes one back */
	struct camera undo_view[ENV_MAX_VIEWS][MODES_VIEW_UNDO];
	int nundo_view[ENV_MAX_VIEWS];
	int pointer_view;                      /* the view the pointer was last in, -1: none yet */
	double screen_x, screen_y;             /* the pointer on the kiosk's screen (a layout's) */
	unsigned char own_parts[MODES_MAX_SEGMENTS]; /* §3.7.1: the parts around G, left out */
	struct kiosk *kiosk;    /* the keyboard's edit line; NULL: keys go to the modes alone */
	struct prompt prompt;   /* a command asking for its missing arguments */
	struct menu menu;       /* the pop-up menu of commands, open in menu_view */
	int menu_view;
	int hover_fig, hover_seg; /* what a prompt would pick under the pointer (-1: nothing) */
	/* runs a line typed at the kiosk (journaled, its outcome on the message line) */
	void (*run_typed)(void *ctx, const char *line);
	uint64_t step_began_us; /* when the step's first button went down */
	int step_end_due;       /* the last button came up: end the step once it is applied */
	int view_step;          /* change view began a step of its own: its end ends it */
	double pointer_x, pointer_y;
};

void modes_init(struct modes *M, struct daemon *d, struct scene *scene,
		void (*run_command)(void *ctx, const char *line), void *ctx);

/*
 * One input event (px, py: a motion in pixels) for change view: 1 when it
 * took it (V enters it from any mode; inside, everything is its own).
 */
int modes_view_input(struct modes *M, const struct input_event_rec *e, long px, long py);
/* ... else for the interactive mode, its target applied at once */
void modes_mode_input(struct modes *M, const struct input_event_rec *e, long px, long py);
/* the pointer outside a mode followed (where S picks, a prompt picks, the menu opens) */
void modes_track_pointer(struct modes *M, const struct input_event_rec *e, long px, long py);
/* change view is running in the view the keys would go to */
int modes_viewing(const struct modes *M);

/* once a frame: the snaps' and adjustments' in-betweens */
void modes_frame(struct modes *M, uint64_t now_us);

/* view v turned (eased) until p is on the screen and not hidden (§3.7, §3.7.1) */
void modes_bring_into_view(struct modes *M, int v, const double p[3]);

/* G (or the joint) moved from outside (a snap, a typed value): what the mode moves follows */
void modes_apply(struct modes *M);

/*
 * View v's camera moved from outside (a dial): kept in the view, the
 * mode's operator told; journal: also journaled as `set camera`.
 */
void modes_set_camera(struct modes *M, int v, const struct camera *cam, int journal);

/* the view the kiosk works in: the mode's, else the pointer's, else the first; -1: none */
int modes_current_view(const struct modes *M);

/*
 * After a command: the environment may have been replaced (undo, a
 * session loaded), its models and states made anew. A mode whose figure
 * is still there (same slot, same generation) takes the new ones; else it
 * ends.
 */
void modes_sync(struct modes *M);

/* a step begins ('B') or ends ('E'), journaled (daemon.h's mode_step) */
void modes_step(struct modes *M, char end);

#endif
