/*
 * loop_state.h - the loop's state and the pieces its files share:
 * loop.c (the live poll loop), loop_frame.c (one frame), loop_tape.c
 * (recording) and loop_replay.c. Nothing outside src/daemon/loop*.c
 * includes it.
 */
#ifndef POSTURE_LOOP_STATE_H
#define POSTURE_LOOP_STATE_H

#include "daemon/cmd.h"
#include "daemon/complete.h"
#include "daemon/dials.h"
#include "daemon/events.h"
#include "daemon/journal.h"
#include "daemon/loop_config.h"
#include "daemon/modes.h"
#include "daemon/scene.h"
#include "daemon/server.h"
#include "daemon/tape.h"
#include "daemon/tape_loop.h"
#include "daemon/vt.h"
#include "devices/escape_chord.h"
#include "devices/hotplug.h"
#include "devices/input_devs.h"
#include "devices/motion_scale.h"

/*
 * Idle, the loop still ticks this often: what waits on time alone (the
 * dials' step ending after they have been still, a held button's release)
 * happens at most this late, for a solve of a figure at rest each time.
 */
#define LOOP_IDLE_TICK_US 250000

struct loop {
	struct daemon d;
	struct server srv;
	struct journal j;
	struct complete complete; /* Tab at the kiosk's edit line */
	struct dials dials;       /* the dial panel's bindings at work */
	int screen_given;         /* --screen: the kiosk's screen is not the framebuffer's */
	int sig_fd;
	uint64_t period_us;
	uint64_t synced_seq;  /* the last journal record known to be on disk */
	uint64_t virtual_us;  /* the clock of settle's frames */
	uint64_t fps_t0, fps_frames;
	uint64_t watchdog_us, watchdog_last;
	/*
	 * the poll round under way: its start, and its solving so far (frames of
	 * settle included), in real time and in the loop thread's CPU time
	 */
	uint64_t round_t0, round_cpu0, round_drawn0, round_drawn_cpu0; /* round_t0 0: none yet */
	uint64_t round_solve_us, round_solve_cpu_us;
	uint64_t stall_t0, stall_max, stall_cpu_max; /* the second being measured, its longest */
	int idle; /* the last frame changed nothing: slow ticks until something comes in */
	struct events events; /* what the clients subscribed to */
	struct input_queue input; /* from the devices and the socket's input lines */
	struct can_map panel;     /* the dial panel's map, when one is given */
	struct input_devs devs;   /* the mice, keyboards and panels read directly */
	/* each device's motion to pixels; the last: the socket's input lines */
	struct motion_scale pointer[INPUT_DEVS_MAX + 1];
	double pointer_gain;
	struct hotplug hotplug;   /* devices arriving; fd -1: not watched */
	struct escape_chord escape; /* the grab's way out at the keyboard */
	struct modes modes;         /* the interactive modes the input drives, and their views */
	struct scene scene;   /* the views' pictures */
	struct tape tape;     /* a recording being made, or the one being replayed */
	struct vt vt;         /* the kiosk's VT, when the daemon owns one (fd -1: none) */
	/* the attract mode (loop_attract.c): a recording replayed while nobody is at the kiosk */
	struct {
		int on;
		uint64_t last_input_us; /* real input last came (a device, a client's line) */
		uint64_t t0_rec, t0_real; /* the recording's time now plays at real time t0_real */
		char *saved;            /* the state it ends by restoring (journal_state_write) */
		size_t saved_len;
		int journal_fd;         /* the journal, off while the demo plays */
		int picked_fig, picked_joint, pointer_view; /* the kiosk's, outside the session */
		double pointer_x, pointer_y;
		int laps;
	} attract;
	const struct loop_config *cfg;
	int stop;
};


/* loop.c: everything the live loop and a replay share made ready (said on stderr when not): 0, or -1 */
int loop_setup(struct loop *L, const struct loop_config *cfg);
/* ... and undone, L freed */
void loop_teardown(struct loop *L);

/* loop_frame.c: the real clock (CLOCK_MONOTONIC, us): for what the state never sees */
uint64_t loop_real_now(void);
/* the loop thread's CPU time (us) */
uint64_t loop_thread_cpu_us(void);
/* the input queued since the last frame, taken in order; returns how many events */
int loop_take_input(struct loop *L);
/* one frame of the running loop: 1 when it changed nothing and nothing waits to be shown */
int loop_live_frame(struct loop *L);
/* `settle`'s frames: the daemon's run_frame */
int loop_settle_frame(struct daemon *d, int *changed);
/* a client's line (client: its slot, or DAEMON_CLIENT_*), recorded and run as a request */
void loop_run_line(struct loop *L, int client, const char *line, size_t len);
/* loop_frame.c: ... its running: input taken first, journaled, the message line; out's json is
 * the caller's to free */
void loop_command(struct loop *L, int client, const char *line, size_t len,
		  struct cmd_outcome *out);
/*
 * loop_frame.c: --after FILE: its lines run as the daemon's own (blank and
 * '#' lines skipped), each reply printed as "reply: JSON" on standard
 * output: what a replay test or a driven run asks of the state it reached.
 * 0, or -1 when FILE cannot be read.
 */
int loop_queries(struct loop *L, const char *path);

/* loop_attract.c: --attract DIR. Real input came (a device's event, a client's line that is
 * not a question): an attract under way ends, the state as it was */
void loop_attract_input(struct loop *L, const char *line, size_t len);
/* each poll round: starts it after --attract-after idle, plays what is due; 1 while it plays
 * (its frames are the frames); *wait_ms: when something is due next */
int loop_attract_round(struct loop *L, int *wait_ms);
/* the attract's recording read once at start: 0, or -1 with err */
int loop_attract_check(struct loop *L, char *err, size_t errlen);
/* the attract's end, as at real input (the daemon stopping) */
void loop_attract_end(struct loop *L);

/* loop_tape.c: why the kiosk cannot start a recording or a demo now, or NULL */
const char *loop_kiosk_busy(const struct loop *L);
/* loop_tape.c: `record start|stop` (the daemon's record hook) */
int loop_record(struct daemon *d, const char *dir, char *err, size_t errlen);
/* the daemon's recording hook: the recording under way (1), or none (0) */
int loop_recording(struct daemon *d, const char **dir, uint64_t counts[3]);
/* ... and the recording's end when the loop stops */
void loop_record_end(struct loop *L);

#endif
