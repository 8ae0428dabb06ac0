/*
 * tape.h - what the live loop takes from outside itself, written down as
 * it is taken (recording) and given back in the same order (replay), so a
 * replay makes the same postures bit for bit (DESIGN.md, "Recording and
 * replay").
 *
 * The loop is deterministic but for what comes in: the clock, the lines
 * clients send, the devices' bytes, and where each time-limited solve was
 * cut. Recording, each of these is appended to the frame log at the moment
 * the loop takes it; replaying, the loop asks the tape instead of the
 * world, and the tape answers from the log in order (tape_loop.h). A replay that asks
 * for something else than the log holds next has gone astray: the tape
 * says where (file:line) and stops.
 *
 * A recording is a folder (tape.c makes it, tape_read.c reads it):
 *
 *   manifest  "posture-recording 1", then "state recording" (being written,
 *             or killed) or "state complete frames=N lines=N", then one
 *             "file NAME KIND" line per file with what it is
 *   config    the settings the replay needs, key = value (postured --config)
 *   start     the state when recording began: the session and the undo
 *             and redo checkpoints (journal_state_write), then "kiosk"
 *             lines for what lives outside the session
 *   lines     the clients' lines, socket commands and injected `input`
 *             lines alike: "T_US CLIENT TEXT", control bytes and '\' as
 *             \xHH and \\
 *   frames    the frame log, one record a line:
 *               clock T            a clock read the state depends on
 *               line N             line N of `lines` ran here
 *               frame N t=T        a frame began at T
 *               ik FIG ik_work ... the work a solve of figure FIG did (ik_work.h)
 *               fig FIG HASH       after a frame: a figure whose hash changed
 *               joints FIG H...    ... and its joints' hashes, for reports
 *               posture N HASH     after frame N: the hash of every figure
 *               device, dev, event the devices' decoder calls (tape_dev.h)
 *               stop               the recording ended cleanly
 *   devN.*    device DEV's bytes in its ecosystem's format (evemu,
 *             hid-recorder, candump log), each readable by that ecosystem's
 *             tools
 *
 * Killed, a recording is read up to its last complete frame (its last
 * "posture" record); complete, it must hold what its manifest says, and
 * anything malformed or missing is refused with file:line.
 */
#ifndef POSTURE_DAEMON_TAPE_H
#define POSTURE_DAEMON_TAPE_H

#include <pthread.h>
#include <stddef.h>
#include <stdint.h>

#include "daemon/daemon.h"
#include "devices/input_devs.h"
#include "devices/queue.h"
#include "pose/ik_work.h"

#define TAPE_VERSION 1
#define TAPE_OUT_BYTES (4u << 20) /* each file's buffer between the loop and the writer */
#define TAPE_PATH_MAX 4096
#define TAPE_FLUSH_US 50000       /* what the loop wrote reaches the file this late at most */
#define TAPE_DEVS 16              /* devices recorded (INPUT_DEVS_MAX) */
#define TAPE_JOINTS_MAX 128       /* joints reported per figure */

/* TAPE_VIRTUAL: a run driven by a script under a virtual clock (loop_drive.c): the clock is
 * virtual_us, nothing recorded or replayed */
enum tape_mode { TAPE_OFF, TAPE_RECORD, TAPE_REPLAY, TAPE_VIRTUAL };

/* one file being written: the loop fills buf, the writer thread drains it */
struct tape_out {
	int fd;
	char *buf, *wbuf;
	size_t len, wlen;
};

enum tape_out_id { TAPE_OUT_FRAMES, TAPE_OUT_LINES, TAPE_OUT_DEV0 };
#define TAPE_DEV_FILES 32 /* devices recorded, a file each (a device plugged again: a new one) */
#define TAPE_OUTS (TAPE_OUT_DEV0 + TAPE_DEV_FILES)

enum tape_kind {
	TAPE_CLOCK,
	TAPE_LINE,
	TAPE_FRAME,
	TAPE_IK,
	TAPE_FIG,
	TAPE_JOINTS,
	TAPE_POSTURE,
	TAPE_STOP,
	TAPE_DEVICE,  /* a device's file begins: fig the device, text "FORMAT FILE MAP", x its dpi */
	TAPE_DEVCALL, /* a decoder call: fig the device, sub its kind, arg, t, count; text resync bytes */
	TAPE_EVENT,   /* an event no decoder made (a device arriving or leaving): ev */
	TAPE_FILE,    /* a state file a command read: t its number (read.N), fig its errno or 0 */
};

struct tape_entry {
	uint8_t kind;
	int lineno;       /* in frames */
	int fig;          /* IK, FIG, JOINTS; DEVICE, DEVCALL: the device */
	uint64_t t;       /* CLOCK, FRAME, DEVCALL: the time; LINE, POSTURE: the number */
	uint64_t hash;    /* FIG, POSTURE */
	struct ik_work work;
	uint32_t *joints; /* JOINTS: njoints hashes (allocated) */
	int njoints;
	int sub, arg;     /* DEVCALL: enum input_tap_kind and its argument */
	uint64_t count;   /* DEVCALL: the records fed */
	char *text;       /* DEVICE: "FORMAT FILE MAP"; DEVCALL resync: the bytes (allocated) */
	size_t ntext;
	double x;         /* DEVICE: the device's dpi */
	struct input_event_rec ev; /* EVENT */
};

struct tape_line {
	uint64_t t_us;
	int client;
	char *text; /* unescaped, NUL-terminated (a NUL inside: len says) */
	size_t len;
};

/* where a replay first differed from its recording */
struct tape_divergence {
	uint64_t frame;
	int fig;           /* -1: not one figure's */
	char what[512];
};

struct replay_dev;

struct tape {
	enum tape_mode mode;
	char dir[TAPE_PATH_MAX];
	uint64_t frames, lines; /* written or replayed */
	uint64_t reads;         /* state files read (load posture, load session), a copy each */
	uint64_t virtual_us;    /* TAPE_VIRTUAL: the time now */
	/* recording */
	struct tape_out out[TAPE_OUTS];
	int nout;                  /* files opened */
	pthread_t writer;
	pthread_mutex_t mu;
	pthread_cond_t work, room;
	int writer_on, quit, write_error;
	uint64_t waits;            /* times the loop waited for the writer (a full buffer) */
	uint64_t flushed_us;       /* the writer last woken */
	uint64_t fig_hash[ENV_MAX_FIGURES]; /* as last written (0: none) */
	/* the devices' files (tape_dev.c): each index's out (0: none yet), files made */
	uint8_t dev_open[TAPE_DEVS];
	int dev_out[TAPE_DEVS];
	int dev_files;
	char dev_file[TAPE_DEV_FILES][256]; /* "NAME FORMAT what": the manifest's lines */
	char dev_iface[TAPE_DEVS][32];
	struct input_queue_tap tap;
	const struct input_devs *devs;
	/* replaying */
	struct tape_entry *ent;
	size_t nent, pos;
	struct tape_line *line;
	size_t nline;
	int complete;               /* the manifest says it was stopped cleanly */
	uint64_t live_fig[ENV_MAX_FIGURES]; /* the recording's hashes, as of the frame replayed */
	uint32_t live_joints[ENV_MAX_FIGURES][TAPE_JOINTS_MAX];
	int live_njoints[ENV_MAX_FIGURES];
	char broken[TAPE_PATH_MAX + 600];         /* the replay went astray: where and why; "": no */
	uint64_t divergences;       /* frames whose posture differed */
	struct tape_divergence first;
	uint64_t last_posture;      /* the hash after the last frame replayed */
	struct replay_dev *rdev[TAPE_DEVS]; /* the recording's devices, played back */
	double dpi[TAPE_DEVS];      /* ... and their mice's resolutions */
};

/* the time now (CLOCK_MONOTONIC, us) */
uint64_t tape_real_now(void);

/* a record's kind in words ("a clock read", "a frame's end"), for messages */
const char *tape_kind_name(enum tape_kind kind);

/* ---- recording ---- */

/*
 * Starts a recording into dir (made; it must not exist or be empty) of the
 * loop whose daemon is d, with config (the settings, "key = value\n"
 * lines; NULL: the caller writes it) and the state as it is now. Returns 0, or -1 with err (nothing
 * left behind but an empty folder).
 */
int tape_record_start(struct tape *t, const char *dir, const struct daemon *d,
		      const char *config, char *err, size_t errlen);
/* ends the recording: the rest written, "stop", the manifest completed; 0, or -1 */
int tape_record_stop(struct tape *t);
/* hands what the loop wrote to the writer thread (called each poll round; wakes it every TAPE_FLUSH_US) */
void tape_flush(struct tape *t);

/*
 * Appending to a recording's files from the loop: the bytes go into the
 * file's buffer and the writer thread writes them, so the loop never waits
 * on the disk (unless a buffer fills: counted in waits).
 */
/* appends formatted text (at most 1 KiB) to file id */
void tape_out_printf(struct tape *t, int id, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));
/* appends n bytes to file id */
void tape_out_bytes(struct tape *t, int id, const void *bytes, size_t n);
/* appends a line of any bytes as one text line: control bytes and '\' as \xHH and \\, then '\n' */
void tape_out_escaped(struct tape *t, int id, const char *text, size_t n);
/* opens file id as dir/name for writing (it must not exist): 0, or -1 with errno */
int tape_out_open(struct tape *t, int id, const char *name);
/* writes the whole file dir/name at once (replaced atomically): 0, or -1 with errno */
int tape_write_file(const struct tape *t, const char *name, const char *text, size_t len);

#endif
