/*
 * journal.h - nothing lost: every state change is on disk before the client
 * hears of it.
 *
 * The journal is an append-only text file of numbered records, each a line
 * ending in its checksum (journal_scan.h): "C line"
 * for a state-changing command, before it "F text" for the state file it
 * read (load posture, load session; escaped to one line), so recovery
 * replays what was read, not what a later save put in its place;
 * "P statement" for a posture the solver
 * reached between commands (the session's root and q statements, 17
 * digits), "B", "E" and "A" for the ends of a kiosk step (journal_step). A snapshot (the session, the undo and redo checkpoints and the
 * number of the last record it includes) bounds the journal: after it is
 * safely renamed into place the journal is emptied, and records it already
 * includes are skipped on recovery, so a crash between the two is harmless.
 *
 * Damage at the end (a record torn by a crash, zero bytes, flipped bits in
 * the last records) is dropped on recovery with one line on stderr saying
 * where and what: the state is the last whole record's. Damage with whole
 * records after it cannot come from a crash; recovery refuses it, naming
 * the byte, rather than lose the acknowledged records after it.
 */
#ifndef POSTURE_JOURNAL_H
#define POSTURE_JOURNAL_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "daemon/daemon.h"

#define JOURNAL_SNAPSHOT_RECORDS 2000 /* snapshot after this many records */
/*
 * A command that read a file bigger than this (a population's CSV) is
 * followed by a snapshot at once, so the journal, read whole on recovery
 * (statefile.h's limit), never holds more than one such file.
 */
#define JOURNAL_FOLD_BYTES (256u << 10)

struct journal {
	int fd;
	char path[4200], snap_path[4200];
	uint64_t seq;        /* the last record written */
	uint64_t since_snap; /* records since the last snapshot */
	uint64_t size;       /* bytes of whole records in the file */
	int torn;            /* a failed write left a piece of a record after them */
	int unchecked;       /* the file read at start was written before records had checksums */
	uint64_t posture_hash[ENV_MAX_FIGURES]; /* postures as the journal knows them */
	uint32_t posture_gen[ENV_MAX_FIGURES];
};

/* a journal whose fd is -1 is off: every call below but journal_open does nothing (a replay) */

/*
 * Opens the journal in state_dir and brings d to the last recorded state
 * (snapshot, then records). Returns 0, or -1 with a message in err.
 */
int journal_open(struct journal *j, struct daemon *d, char *err, size_t errlen);

/*
 * Recovery's work on the journal's text (the whole file): damage in the
 * middle is refused (-1, err naming the byte and the ways out); otherwise
 * the whole records after snap_seq are replayed into d, a damaged tail is
 * told in one line on stderr, *keep is set to the bytes of whole records
 * (the file is cut there) and j->seq is the last whole record's. 0.
 */
int journal_replay_text(struct journal *j, struct daemon *d, const char *text, size_t len,
			uint64_t snap_seq, size_t *keep, char *err, size_t errlen);

/* records a state-changing command line; 0 or -1 (errno) */
int journal_command(struct journal *j, const struct daemon *d, const char *line, size_t len);

/* records the postures the solver changed since the journal last saw them */
int journal_postures(struct journal *j, const struct daemon *d);

/*
 * Marks a kiosk step (daemon_step_*): 'B' it begins, 'E' it ends, 'A' it
 * was taken back. On recovery the marks rebuild the undo checkpoints the
 * steps made, and a step begun but never ended (a crash mid-drag) is
 * taken back: the state is the last completed step's.
 */
int journal_step(struct journal *j, char kind);

/* flushes to disk: call before sending a reply that follows records */
int journal_sync(struct journal *j);

/*
 * Writes a snapshot and empties the journal when it has grown (or force).
 * Not while a step is open: its start would be lost (force: end it first).
 */
int journal_snapshot(struct journal *j, const struct daemon *d, int force);

void journal_close(struct journal *j);

/*
 * The state a snapshot holds, after its first line: the session, then the
 * undo and redo checkpoints. Written: 0, or -1 on a stream error. Read
 * into d (an empty environment): 0, or -1 with what is wrong in err.
 */
int journal_state_write(const struct daemon *d, FILE *f);
int journal_state_read(struct daemon *d, const char *text, size_t len, char *err, size_t errlen);

#endif
