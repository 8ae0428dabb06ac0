/*
 * tape_read.h - a recording read for a replay (tape.h): every file
 * checked, errors as file:line; then its records one by one.
 */
#ifndef POSTURE_DAEMON_TAPE_READ_H
#define POSTURE_DAEMON_TAPE_READ_H

#include "daemon/tape.h"

/*
 * Reads the recording in dir and the state it starts from into d (an
 * empty daemon); config gets the config file's text (free it). Returns 0,
 * or -1 with "file:line: why" in err.
 */
int tape_replay_open(struct tape *t, const char *dir, struct daemon *d, char **config,
		     char *err, size_t errlen);
/*
 * Lines in the form of a recording's `lines` (T_US CLIENT TEXT, in time
 * order) into *dest (count of them; free each text, then the array). A torn
 * last line is dropped when torn_ok. 0, or -1 with "path:line: why".
 */
int tape_lines_read(const char *path, int torn_ok, struct tape_line **dest, size_t *count,
		    char *err, size_t errlen);

/* the next record, not taken; NULL at the end */
const struct tape_entry *tape_peek(const struct tape *t);
/* line n of `lines` (from 1); NULL: no such line */
const struct tape_line *tape_line_at(const struct tape *t, uint64_t n);
/* takes a LINE record (the driver runs it) */
void tape_take(struct tape *t);
/* frees what a replay read, or a recording's buffers */
void tape_free(struct tape *t);

#endif
