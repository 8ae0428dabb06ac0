/*
 * dial_feed.h - the dial panel's events through its bindings (dial_bind.h):
 * a dial's value becomes a move of its target, a button's edge its command.
 * The rules (relative dials, dead zone, stale values) are dial_bind.h's.
 */
#ifndef POSTURE_DIAL_FEED_H
#define POSTURE_DIAL_FEED_H

#include "interact/dial_bind.h"

enum dial_action_kind {
	DIAL_ACTION_MOVE,    /* add delta to target */
	DIAL_ACTION_COMMAND, /* run command */
};

/*
 * What one event asks for. target and command point into the table and
 * stay valid until it changes.
 */
struct dial_action {
	uint8_t kind;          /* enum dial_action_kind */
	int binding;           /* the index of the dial or button binding */
	const struct dial_target *target; /* MOVE */
	double delta;          /* MOVE: metres or radians (gain, invert applied), finite */
	const char *command;   /* COMMAND */
};

/*
 * The actions of one event, at most max into dest: a bound dial's value
 * gives at most one move, a bound button's edge one command; a panel's
 * INPUT_ADDED or INPUT_REMOVED forgets the references. Returns the number
 * written; actions beyond max are counted lost. Allocates nothing.
 */
int dial_bind_feed(struct dial_bind *t, const struct input_event_rec *e, struct dial_action *dest,
		   int max);

#endif
