/* loop_drive.h - `postured --drive FILE`: the loop run by a script under a virtual clock */
#ifndef POSTURE_LOOP_DRIVE_H
#define POSTURE_LOOP_DRIVE_H

#include "daemon/loop_config.h"

/*
 * Runs the lines of cfg->drive_file ("T_US CLIENT TEXT", as a recording's
 * `lines`) under a virtual clock: frame after frame, 1/fps apart in virtual
 * time, each frame's lines run first as their client's (replies on
 * standard output as "reply: JSON" when the line asks for one), every
 * solve cut by a virtual clock, so the run is the same on every run and
 * as fast as the machine goes. No socket or devices; the state directory
 * and its journal as in a live run. Ends a second of virtual time after
 * the last line; --after's queries then; prints "drive: frames=N
 * virtual_s=S posture=HASH". Returns 0, or 1 for a file it cannot read.
 */
int loop_drive(const struct loop_config *cfg);

#endif
