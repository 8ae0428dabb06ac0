/* escape_chord.c - Ctrl+Alt+Backspace seen across the keyboards (see escape_chord.h) */
#include "devices/escape_chord.h"

#include <linux/input-event-codes.h>

/* sets or clears bit in *mask as the key goes down or up (a repeat changes nothing) */
static void
escape_chord_modifier(unsigned char *mask, unsigned char bit, int value)
{
	if (value == 1)
		*mask |= bit;
	else if (value == 0)
		*mask &= (unsigned char)~bit;
}

int
escape_chord_feed(struct escape_chord *c, const struct input_event_rec *e)
{
	if (e->kind != INPUT_KEY)
		return 0;
	switch (e->code) {
	case KEY_LEFTCTRL:
		escape_chord_modifier(&c->ctrl, 1, e->value);
		return 0;
	case KEY_RIGHTCTRL:
		escape_chord_modifier(&c->ctrl, 2, e->value);
		return 0;
	case KEY_LEFTALT:
		escape_chord_modifier(&c->alt, 1, e->value);
		return 0;
	case KEY_RIGHTALT:
		escape_chord_modifier(&c->alt, 2, e->value);
		return 0;
	case KEY_BACKSPACE:
		return e->value == 1 && c->ctrl && c->alt;
	default:
		return 0;
	}
}
