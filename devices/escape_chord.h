/*
 * escape_chord.h - the kiosk grab's way out at the keyboard: Ctrl+Alt+
 * Backspace (the X server's old "zap" chord, which people who run kiosks
 * know). While the daemon holds the grab, the console and its VT switch
 * keys see nothing; this chord, read by the daemon itself from any
 * keyboard it reads, gives the grab up, so a person at the station gets
 * the console back without a second terminal. Pure: events in, a yes out.
 */
#ifndef POSTURE_DEVICES_ESCAPE_CHORD_H
#define POSTURE_DEVICES_ESCAPE_CHORD_H

#include "devices/event.h"

struct escape_chord {
	unsigned char ctrl, alt; /* bits: left 1, right 2 */
};

/* feeds one event; returns 1 when it completes the chord (Backspace pressed with Ctrl and Alt down) */
int escape_chord_feed(struct escape_chord *c, const struct input_event_rec *e);

#endif
