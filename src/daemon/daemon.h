/*
 * daemon.h - what the command handlers may reach besides the environment:
 * the state directory, undo history, frame statistics, and the loop's
 * services (running frames for `settle`, client subscriptions).
 */
#ifndef POSTURE_DAEMON_H
#define POSTURE_DAEMON_H

#include <stdint.h>

#include "assess/assess.h"
#include "devices/can_map.h"
#include "devices/input_devs.h"
#include "devices/queue.h"
#include "draw/frame.h"
#include "interact/dial_bind.h"
#include "interact/interact.h"
#include "interact/kiosk.h"
#include "interact/menu.h"
#include "interact/prompt.h"
#include "interact/pick.h"
#include "pose/env.h"
#include "daemon/populations.h"

struct kms_times_summary; /* draw/kms_pick.h */
struct camera;            /* draw/view.h */
struct hemi_map;          /* draw/hemi.h */
struct assess_live;       /* daemon/assess_live.h */
struct loads_live;        /* daemon/loads_live.h */
struct fit_live;          /* daemon/fit_live.h */
struct envelopes;         /* daemon/envelopes.h */

#define DAEMON_UNDO_MAX 64 /* checkpoints kept for undo, and for redo */
#define VIEW_MAX_W 1920    /* the largest picture a view may ask for */
#define VIEW_MAX_H 1200

/*
 * Each figure's meshes for picking, built when a figure is first picked.
 * A slot's model is rebuilt when its generation or model changes (a
 * session load or undo makes new models under old generations).
 */
struct pick_cache {
	struct pick_model *pm[ENV_MAX_FIGURES];
	const struct model *model[ENV_MAX_FIGURES];
	uint32_t gen[ENV_MAX_FIGURES];
	uint64_t print[ENV_MAX_FIGURES]; /* a hash of the model's geoms, also compared */
};

/* a bounded stack of session texts */
struct checkpoints {
	char *text[DAEMON_UNDO_MAX];
	size_t len[DAEMON_UNDO_MAX];
	int n;
};

struct daemon_stats {
	uint64_t frame;    /* frames run */
	double fps;        /* measured over the last second */
	double ik_us;      /* solver time in the last frame */
	double draw_us;    /* rendering time of a frame's views, smoothed */
	uint64_t stall_max_us; /* the longest loop round outside solving and drawing, in the
				* last whole second the loop ran */
	uint64_t stall_cpu_max_us; /* the same in the loop thread's CPU time: its own work, not
				    * its waits for a CPU */
	uint64_t frames_written; /* pictures the frame writers wrote (files, screen, events) */
	uint64_t frames_dropped; /* pictures replaced by newer ones while a writer was behind */
	uint64_t budget_us; /* the solver's budget in the last frame */
	int clients;
	int iterations;    /* solver iterations in the last frame */
	int time_cut;      /* 1 when the time limit cut the last solve */
	int step_cut;      /* 1 when the step factor shortened a goal */
};

/*
 * A kiosk action as one undoable step: from the first button
 * down in a mode to the last one up (or a typed value, a snap), the state
 * before it is kept; at its end that state becomes one undo checkpoint.
 * The journal marks both ends, so a crash mid-step comes back to the
 * state before it: the last completed step.
 */
struct daemon_step {
	int open;
	int fig;        /* the figure slot the step changes (the busy rule's) */
	uint32_t gen;   /* ... and its generation */
	char mode[32];  /* the mode it is made in, for the busy message */
	char *before;   /* the session when it began */
	size_t len;
};

enum sub_kind {
	SUB_POSTURE = 1 << 0,
	SUB_TELEMETRY = 1 << 1,
	SUB_MESSAGE = 1 << 2,
	SUB_FRAME = 1 << 3,
	SUB_STABILITY = 1 << 4, /* every frame: support polygon, balance point, margin */
	SUB_ALERT = 1 << 5,     /* the stability margin crossing its threshold */
	SUB_INPUT = 1 << 6,     /* every input event, decoded, as the loop takes it */
	SUB_KIOSK = 1 << 7,     /* the kiosk's mode and step, as they change */
	SUB_ASSESSMENT = 1 << 8, /* a figure's RULA, REBA and OWAS scores, as they change */
	SUB_LOADS = 1 << 9,      /* a figure's low back, weakest joint and supports, as they change */
};

/* the client a command comes from when no connection sent it */
#define DAEMON_CLIENT_JOURNAL (-1) /* replayed from the journal, or the daemon's own line */
#define DAEMON_CLIENT_KIOSK (-2)   /* typed at the kiosk's edit line */

/* the name of the constraint a drag holds its site with (cmd_manip.c; the loop ends it) */
#define CMD_DRAG_CONSTRAINT "drag"

struct daemon {
	struct env env;
	struct populations pops; /* the populations loaded (load population), besides ansur2 */
	char state_dir[4096];
	char library_dir[4096]; /* shipped figure files, named "lib:NAME"; empty: none */
	int files_read_only;    /* a replay: its state directory is the recording, read only */
	int attracting;         /* the attract mode plays (get kiosk says so) */
	struct checkpoints undo, redo;
	struct daemon_step step;
	struct daemon_stats stats;
	/* the loop's services; NULL when absent (tools, tests) */
	void *loop;
	int (*run_frame)(struct daemon *d, int *changed); /* one frame with a virtual clock */
	int (*subscribe)(struct daemon *d, int client, unsigned kinds, int on);
	/* renders view v now; the frame stays valid until the next rendering */
	int (*render_view)(struct daemon *d, int v, const struct frame **dest, char *err,
			   size_t errlen);
	/* input to pixels on the framebuffer: the newest samples (us), oldest first; NULL: none */
	int (*input_latencies)(struct daemon *d, uint64_t *dest, int max);
	/* the KMS screen's render-to-flip times (draw/kms_pick.h): 0, or -1: no KMS screen */
	int (*flip_times)(struct daemon *d, struct kms_times_summary *dest);
	/*
	 * An id map (draw/hemi.h, HEMI_N square) through cam, any field of view,
	 * into the scene's map slot 0 or 1 (valid until that slot is drawn again):
	 * every figure but the ghosts, or figure only alone (-1: every one), with
	 * figure skip's segments whose skip_seg[seg] is set left out (NULL: none).
	 * NULL with err when there is no renderer.
	 */
	const struct hemi_map *(*id_map)(struct daemon *d, const struct camera *cam, int slot,
					 int only, int skip, const unsigned char *skip_seg, char *err,
					 size_t errlen);
	/* the kiosk's screen now, as the framebuffer shows it (a layout's views tiled) */
	int (*render_screen)(struct daemon *d, const struct frame **dest, char *err, size_t errlen);
	/*
	 * A picture for a file (scene_draw_picture): through v's camera at its
	 * size, in its tint, of figure slot fig among the objects (-1: every
	 * figure), no overlays; valid until the next rendering. NULL: none.
	 */
	int (*render_picture)(struct daemon *d, const struct env_view *v, int fig,
			      const struct frame **dest, char *err, size_t errlen);
	/*
	 * The calendar's time now, seconds since the epoch (UTC), for what a file
	 * says of when it was made; never the state's: a replay writes no file,
	 * so nothing it replays reads it. NULL: none (tools, tests).
	 */
	int64_t (*calendar_s)(struct daemon *d);
	char message[256]; /* the message line under the pictures (§1.7) */
	/*
	 * The state file the running command read (load posture, load session),
	 * kept until the next command: the journal records its text with the
	 * command, so recovery replays what was read, not what the file holds
	 * by then (it may have been saved over). file_given: on recovery, the
	 * text the next replayed command reads instead of its file.
	 */
	struct daemon_text {
		char *text;
		size_t len;
	} file_read, file_given;
	/*
	 * The line the journal records for the running command in place of the
	 * request (journal_command), kept until the next command; "" for the
	 * request itself. A command whose defaults come from outside the state
	 * (the view the kiosk's pointer is in) writes them out here, so that
	 * recovery, which has no pointer, does what was done.
	 */
	char journal_as[512];
	/* the queue from the devices and the socket's input lines to the loop; NULL: none */
	struct input_queue *input;
	/*
	 * Reads a state file a command loads (a recording keeps a copy; a replay
	 * gives the recorded text): as statefile_read; path NULL: it did not
	 * resolve (errno says why), which a recording notes. NULL: statefile_read.
	 */
	char *(*read_state)(struct daemon *d, const char *path, size_t *len);
	/* the loop's clock, as the state sees it (a replay's is the recording's); NULL: 0 */
	uint64_t (*now_us)(struct daemon *d);
	/* the dial panel's map: its valuators' names; NULL: no panel */
	const struct can_map *panel;
	/* the devices read directly (list devices); NULL: none */
	const struct input_devs *devices;
	/* the kiosk grab (grab -1: unchanged) and the pointer gain (0: unchanged); NULL: none */
	int (*set_input)(struct daemon *d, int grab, double gain);
	/* the interactive mode the input drives (manipulate ...); NULL: none taken */
	struct interact *interact;
	/* the joint the dial box turns: the last `manipulate joint`'s (fig -1: none) */
	struct {
		int fig;
		uint32_t gen;
		int joint;
	} picked;
	/* the dial panel's bindings (bind, list bindings); NULL: none */
	struct dial_bind *bindings;
	/* the kiosk's keyboard and edit line, and its layout's name; NULL: none */
	struct kiosk *kiosk;
	char keymap[128];
	/* a command asking for its missing arguments, and what the pointer would pick; NULL: none */
	const struct prompt *prompt;
	int hover_fig, hover_seg;
	/* the figure the last mode was on (fig -1: none yet): the kiosk's figure after it */
	struct {
		int fig;
		uint32_t gen;
	} kiosk_fig;
	/* the status line the kiosk's view last showed ("": none drawn yet) */
	char status_line[160];
	/* the pop-up menu of commands and the view it is open in; NULL: none */
	const struct menu *menu;
	int menu_view;
	/* the kiosk's pointer outside a mode: its view (-1: none yet) and pixel */
	int pointer_view;
	double pointer_x, pointer_y;
	/* turns view v, eased, until p is in view (§3.7), if it is not; NULL: none */
	void (*bring_into_view)(struct daemon *d, int v, const double p[3]);
	/* G was set from outside (a snap): what the mode moves follows; NULL: none */
	void (*mode_moved)(struct daemon *d);
	/* a step of the mode begins ('B') or ends ('E'), journaled; NULL: none */
	void (*mode_step)(struct daemon *d, char end);
	/* record start (dir) or stop (NULL): 0, or -1 with err; NULL: this daemon cannot */
	int (*record)(struct daemon *d, const char *dir, char *err, size_t errlen);
	/* the recording under way: its folder, frames, lines and the loop's waits; 0: none */
	int (*recording)(struct daemon *d, const char **dir, uint64_t counts[3]);
	double pointer_gain;
	int screen_w, screen_h; /* the kiosk's screen: the framebuffer's, or --screen */
	uint64_t held_max_us; /* a mouse button held this long ends its drag (set input held=) */
	struct pick_cache picks;
	/*
	 * The assessments' settings (set assess), kept in sessions, undo and
	 * the journal; read them with daemon_assess_config (the defaults until
	 * set). Every change counts in assess_serial, so cached scores go stale.
	 */
	struct assess_config assess_cfg;
	int assess_cfg_set;
	uint64_t assess_serial;
	/* each figure's assessment now (assess_live.h); NULL until first asked */
	struct assess_live *assess_live;
	/* each figure's loads analysis now (loads_live.h); NULL until first asked */
	struct loads_live *loads_live;
	/* the figures' collision models and their pairs' last answers (fit_live.h) */
	struct fit_live *fit_live;
	/*
	 * The reach envelopes kept (analyze reach; envelopes.h): derived
	 * results, not in sessions, undo or the journal; those of a figure that
	 * goes go with it. NULL until the first is made.
	 */
	struct envelopes *envelopes;
	/* commands that changed something, counted: what a cached analysis was made under */
	uint64_t mutations;
};

/* frees the undo and redo texts */
void daemon_checkpoints_clear(struct checkpoints *c);
/* pushes a text (taking ownership); drops the oldest when full */
void daemon_checkpoints_push(struct checkpoints *c, char *text, size_t len);

/*
 * The view the kiosk works in: the mode's, else the one the pointer was
 * last in, else the first there is; -1: no view. Change view turns it,
 * the edit line shows in it.
 */
int daemon_kiosk_view(const struct daemon *d);

/*
 * The kiosk's figure, the one its status line names: the figure a mode is
 * on while one is; else the shown family's selected member; else the
 * figure the last mode was on, while it is there; -1: none.
 */
int daemon_kiosk_figure(const struct daemon *d);

/*
 * 1 when figure slot fig is a ghost (family.h): drawn translucent, never
 * picked. The figure a mode is on is none.
 */
int daemon_is_ghost(const struct daemon *d, int fig);

/*
 * Replaces the environment and the assessments' settings with the session
 * in text (a session without settings: the defaults); nothing changes on
 * error (0, or -1 with err).
 */
int daemon_replace_env(struct daemon *d, const char *text, size_t len, char *err, size_t errlen);

/*
 * A step begins on figure slot fig in mode (the state now kept); a no-op
 * when one is open. 0, or -1 when out of memory (no step then).
 */
int daemon_step_begin(struct daemon *d, int fig, const char *mode);
/*
 * The open step moves figure slot fig (occupied) when it names none yet,
 * as a dial turn outside a mode learns only as it moves: the busy rule
 * then guards that figure. Nothing when no step is open.
 */
void daemon_step_moves(struct daemon *d, int fig);
/*
 * The open step ends: when it changed anything, the state before it is
 * pushed for undo and redo is forgotten (1); else nothing (0).
 */
int daemon_step_end(struct daemon *d);
/*
 * The open step taken back (a crash mid-step): the state before it
 * restored, but for the views, whose cameras stay; 0, or -1 with err.
 */
int daemon_step_abandon(struct daemon *d, char *err, size_t errlen);

/*
 * The pick model of figure slot fig (occupied), built or rebuilt when its
 * model is new to the cache; NULL when out of memory.
 */
const struct pick_model *daemon_pick_model(struct daemon *d, int fig);

/*
 * The nearest hit of r on every figure but slot skip (-1: none skipped)
 * and the ghosts, not nearer than tmin: 1 with dest and the figure's slot
 * in *fig, 0 on a miss, -1 out of memory.
 */
int daemon_pick(struct daemon *d, const struct ray *r, double tmin, int skip, struct pick_hit *dest,
		int *fig);
/* frees every cached pick model */
void daemon_picks_free(struct daemon *d);

/* the assessments' settings now: those set (set assess, a session), else the defaults */
struct assess_config daemon_assess_config(const struct daemon *d);
/* the assessments' settings replaced; what was scored under the old ones goes stale */
void daemon_set_assess_config(struct daemon *d, const struct assess_config *cfg);

/*
 * The whole state a session file, an undo checkpoint and a snapshot keep:
 * the environment and the assessments' settings, as text (malloc'd; NULL
 * when out of memory).
 */
char *daemon_session_text(const struct daemon *d, size_t *len);

/* lets a kept text go (file_read, file_given) */
void daemon_text_clear(struct daemon_text *t);

#endif
