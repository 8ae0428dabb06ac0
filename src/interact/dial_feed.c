/* dial_feed.c - the dial panel's events through its bindings: moves and commands */
#include "interact/dial_feed.h"

#include <math.h>

/* the binding of the dial whose valuator code is index, or -1 */
static int
dial_by_index(const struct dial_bind *t, int index)
{
	for (int i = 0; i < t->ndial; i++)
		if (t->dial[i].index == index)
			return i;
	return -1;
}

/* one action into dest if there is room; the number written */
static int
emit(struct dial_bind *t, const struct dial_action *a, struct dial_action *dest, int max)
{
	if (max < 1) {
		t->lost++;
		return 0;
	}
	*dest = *a;
	return 1;
}

/* a valuator's value: the reference first, then changes (see the top of dial_bind.h) */
static int
feed_valuator(struct dial_bind *t, const struct input_event_rec *e, struct dial_action *dest,
	      int max)
{
	int code = e->code;
	if (code >= DIAL_BIND_MAX_AXES)
		return 0;
	if (e->flags & INPUT_F_STALE) {
		t->has_ref[code] = 0;
		return 0;
	}
	if (!isfinite(e->x)) {
		t->nonfinite++;
		return 0;
	}
	if (!t->has_ref[code]) {
		t->ref[code] = e->x;
		t->has_ref[code] = 1;
		return 0;
	}
	int k = dial_by_index(t, code);
	if (k < 0) {
		/* unbound: followed all the same, so a later bind starts from here */
		t->ref[code] = e->x;
		return 0;
	}
	const struct dial_bind_dial *d = &t->dial[k];
	double change = e->x - t->ref[code];
	if (change == 0)
		return 0;
	if (fabs(change) <= d->dead) {
		t->dead++;
		return 0;
	}
	double delta = d->gain * change;
	if (d->invert)
		delta = -delta;
	t->ref[code] = e->x;
	if (!isfinite(delta)) {
		t->overflow++;
		return 0;
	}
	/* a zero gain, or a product below the smallest double, moves nothing */
	if (delta == 0)
		return 0;
	struct dial_action a = { .kind = DIAL_ACTION_MOVE, .binding = k, .target = &d->target,
				 .delta = delta };
	return emit(t, &a, dest, max);
}

static int
feed_button(struct dial_bind *t, const struct input_event_rec *e, struct dial_action *dest,
	    int max)
{
	if (e->value != 0 && e->value != 1)
		return 0;
	int k = dial_bind_button_find(t, e->code, e->value ? DIAL_EDGE_PRESS : DIAL_EDGE_RELEASE);
	if (k < 0)
		return 0;
	struct dial_action a = { .kind = DIAL_ACTION_COMMAND, .binding = k,
				 .command = t->button[k].command };
	return emit(t, &a, dest, max);
}

int
dial_bind_feed(struct dial_bind *t, const struct input_event_rec *e, struct dial_action *dest,
	       int max)
{
	switch ((enum input_kind)e->kind) {
	case INPUT_VALUATOR:
		return feed_valuator(t, e, dest, max);
	case INPUT_BUTTON:
		return feed_button(t, e, dest, max);
	case INPUT_ADDED:
	case INPUT_REMOVED:
		/* a panel that comes or goes starts every dial afresh */
		if (e->code == INPUT_CLASS_PANEL)
			dial_bind_reset(t);
		return 0;
	case INPUT_MOTION:
	case INPUT_POINTER:
	case INPUT_WHEEL:
	case INPUT_KEY:
	case INPUT_FRAME:
		return 0;
	}
	return 0;
}
