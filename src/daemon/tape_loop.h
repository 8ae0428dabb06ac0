/*
 * tape_loop.h - the loop's side of the tape (tape.h): each input the state
 * takes from outside, recorded as it is taken, or answered from the
 * recording in a replay.
 */
#ifndef POSTURE_DAEMON_TAPE_LOOP_H
#define POSTURE_DAEMON_TAPE_LOOP_H

#include "daemon/tape.h"

/* a clock read the state depends on: the real one (recorded), or the log's */
uint64_t tape_clock(struct tape *t);
/* a client's line about to run: recorded */
void tape_client_line(struct tape *t, int client, const char *line, size_t len);
/*
 * A state file a command reads (load posture, load session): from the disk,
 * with a copy recorded (read.N beside the log); in a replay the recorded
 * text, the disk untouched. The text (malloc'd, NUL-terminated), or NULL
 * with errno as the read failed. path NULL: the path did not resolve
 * (errno says why), recorded as a failed read.
 */
char *tape_read_state(struct tape *t, const char *path, size_t *len);
/* a frame begins: its time (the real one, recorded; or the log's) */
uint64_t tape_frame_begin(struct tape *t);
/*
 * A solve of figure fig is about to run: in a replay, the work to cut it
 * at (NULL: astray, see broken); NULL when recording or off.
 */
const struct ik_work *tape_ik_replay(struct tape *t, int fig);
/* ... and what it did: recorded */
void tape_ik_done(struct tape *t, int fig, const struct ik_work *w);
/* the frame ended with e's figures as they are: recorded, or compared (a divergence noted) */
void tape_frame_end(struct tape *t, const struct env *e);

#endif
