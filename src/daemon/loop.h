/*
 * loop.h - the daemon's one thread: poll over sockets, signals and the
 * frame timer; each frame applies queued commands, solves the constraints
 * within the frame's budget (§4.7.2) and publishes events (Figure 5.1).
 */
#ifndef POSTURE_LOOP_H
#define POSTURE_LOOP_H

#include "daemon/loop_config.h"

/* runs until SIGTERM or SIGINT; returns the process exit status */
int loop_run(const struct loop_config *cfg);

#endif
