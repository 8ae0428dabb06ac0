/* loop_replay.h - `postured --replay DIR` (daemon/tape.h) */
#ifndef POSTURE_LOOP_REPLAY_H
#define POSTURE_LOOP_REPLAY_H

#include "daemon/loop_config.h"

/*
 * Replays the recording cfg->replay_dir (loop_tape.c): no socket, devices
 * or state directory; the views' frames into cfg->frames_dir when given.
 * Prints "replay: frames=N posture=HASH divergences=N" on standard output
 * and returns 0 when nothing diverged, 1 otherwise (and for a recording it
 * refuses, saying file:line).
 */
int loop_replay(const struct loop_config *cfg);

#endif
