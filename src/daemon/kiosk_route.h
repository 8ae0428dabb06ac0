/*
 * kiosk_route.h - where the kiosk's input goes first: the
 * screen's pointer mapped into the view under it (a layout), then the
 * pop-up menu while it is open (or a button on the background opening
 * it), a command's prompt (ESC, a click picking its answer), the keyboard's
 * edit line and values typed in a mode (kiosk.h), and what none of them
 * takes to change view, else to the interactive mode (modes.h).
 */
#ifndef POSTURE_KIOSK_ROUTE_H
#define POSTURE_KIOSK_ROUTE_H

#include "daemon/modes.h"

/* one input event (px, py: a motion in pixels), from a device or an `input` line */
void kiosk_route_input(struct modes *M, const struct input_event_rec *e, long px, long py);

#endif
