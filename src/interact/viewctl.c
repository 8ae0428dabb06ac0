/* viewctl.c - the change view mode (see viewctl.h) */
#include "interact/viewctl.h"

#include <linux/input-event-codes.h>
#include <math.h>

struct viewctl_gains
viewctl_default_gains(void)
{
	struct viewctl_gains g = {
		.rad_per_px = 0.5 * M_PI / 180,
		.m_per_px = 0.01,
		.snap_us = 1000000,
		.snap_min_rad = 0.5 * M_PI / 180,
	};
	return g;
}

void
viewctl_init(struct viewctl *vc, const struct viewctl_gains *gains)
{
	*vc = (struct viewctl){ .state = VIEWCTL_IDLE, .gains = *gains };
}

const char *
viewctl_state_to_str(enum viewctl_state s)
{
	switch (s) {
	case VIEWCTL_IDLE:
		return "idle";
	case VIEWCTL_VIEWING:
		return "viewing";
	case VIEWCTL_SNAP_PICK:
		return "snap-pick";
	case VIEWCTL_SNAPPING:
		return "snapping";
	}
	return "?";
}

static unsigned
button_bit(unsigned code)
{
	switch (code) {
	case BTN_LEFT:
		return VIEWCTL_BTN_LEFT;
	case BTN_MIDDLE:
		return VIEWCTL_BTN_MIDDLE;
	case BTN_RIGHT:
		return VIEWCTL_BTN_RIGHT;
	}
	return 0;
}

static int
is_press(const struct input_event_rec *ev, unsigned code)
{
	return ev->kind == INPUT_KEY && ev->code == code && ev->value == 1;
}

/* buttons held, and CONTROL, whatever the state */
static void
track_modifiers(struct viewctl *vc, const struct input_event_rec *ev)
{
	if (ev->kind == INPUT_KEY && (ev->code == KEY_LEFTCTRL || ev->code == KEY_RIGHTCTRL))
		vc->control = ev->value != 0;
	if (ev->kind == INPUT_BUTTON && vc->state != VIEWCTL_IDLE) {
		unsigned bit = button_bit(ev->code);
		if (ev->value)
			vc->buttons |= bit;
		else
			vc->buttons &= ~bit;
	}
}

static enum viewctl_result
end_mode(struct viewctl *vc, struct camera *cam, int restore)
{
	if (restore)
		*cam = vc->before;
	vc->state = VIEWCTL_IDLE;
	vc->buttons = 0;
	return VIEWCTL_ENDED;
}

/* the turn about the vertical: a sweep, or with CONTROL a pan; the moving part follows the pointer */
static double
turn_horizontal(struct viewctl *vc, struct camera *cam, double px)
{
	double a = vc->gains.rad_per_px * px;
	return vc->control ? viewop_pan_horizontal(cam, -a) : viewop_sweep_horizontal(cam, a);
}

/* the turn about the camera's x: px down lowers the camera (sweep) or the line of sight (pan) */
static double
turn_vertical(struct viewctl *vc, struct camera *cam, double px)
{
	double a = vc->gains.rad_per_px * px;
	return vc->control ? viewop_pan_vertical(cam, -a) : viewop_sweep_vertical(cam, a);
}

/* px down backs away */
static double
zoom(struct viewctl *vc, struct camera *cam, double px)
{
	return viewop_zoom(cam, vc->gains.m_per_px * px);
}

static enum viewctl_result
move(struct viewctl *vc, struct camera *cam, double dx, double dy)
{
	const unsigned L = VIEWCTL_BTN_LEFT, M = VIEWCTL_BTN_MIDDLE, R = VIEWCTL_BTN_RIGHT;
	double moved = 0;
	/* C.2.1: two buttons give two effects, never two from one valuator */
	if (vc->buttons == L) {
		moved += fabs(turn_horizontal(vc, cam, dx));
	} else if (vc->buttons == M) {
		moved += fabs(turn_vertical(vc, cam, dy));
	} else if (vc->buttons == R) {
		moved += fabs(zoom(vc, cam, dy));
	} else if (vc->buttons == (L | M)) {
		moved += fabs(turn_horizontal(vc, cam, dx));
		moved += fabs(turn_vertical(vc, cam, dy));
	} else if (vc->buttons == (L | R)) {
		moved += fabs(turn_horizontal(vc, cam, dx));
		moved += fabs(zoom(vc, cam, dy));
	} else if (vc->buttons == (M | R)) {
		moved += fabs(turn_vertical(vc, cam, dy));
		moved += fabs(zoom(vc, cam, dx));
	}
	return moved > 0 ? VIEWCTL_CHANGED : VIEWCTL_TAKEN;
}

/* the keys every change view state answers alike: V (already in), ESC, C */
static int
common_key(struct viewctl *vc, struct camera *cam, const struct input_event_rec *ev,
	   enum viewctl_result *dest)
{
	if (is_press(ev, KEY_ESC)) {
		/* a snap under way ends where it was going */
		if (vc->state == VIEWCTL_SNAPPING)
			viewop_snap_at(&vc->snap, 1, cam);
		*dest = end_mode(vc, cam, 0);
		return 1;
	}
	if (is_press(ev, KEY_C)) {
		*dest = end_mode(vc, cam, 1);
		return 1;
	}
	return 0;
}

static enum viewctl_result
handle_idle(struct viewctl *vc, struct camera *cam, int caller_mode,
	    const struct input_event_rec *ev)
{
	if (!is_press(ev, KEY_V))
		return VIEWCTL_PASS;
	vc->state = VIEWCTL_VIEWING;
	vc->caller_mode = caller_mode;
	vc->before = *cam;
	vc->buttons = 0;
	return VIEWCTL_ENTERED;
}

/*
 * What the viewer does with an event it has no use for: a device coming or
 * going is the caller's business, anything else is swallowed so that it
 * does not act on the figure while the view is being changed.
 */
static enum viewctl_result
swallowed_unless_device(const struct input_event_rec *ev)
{
	switch ((enum input_kind)ev->kind) {
	case INPUT_MOTION:
	case INPUT_POINTER:
	case INPUT_BUTTON:
	case INPUT_KEY:
	case INPUT_WHEEL:
	case INPUT_VALUATOR:
	case INPUT_FRAME:
		return VIEWCTL_TAKEN;
	case INPUT_ADDED:
	case INPUT_REMOVED:
		return VIEWCTL_PASS;
	}
	return VIEWCTL_PASS;
}

static enum viewctl_result
handle_viewing(struct viewctl *vc, struct camera *cam, const struct input_event_rec *ev)
{
	enum viewctl_result r;
	if (ev->kind == INPUT_MOTION)
		return move(vc, cam, ev->x, ev->y);
	if (ev->kind != INPUT_KEY)
		return swallowed_unless_device(ev);
	if (common_key(vc, cam, ev, &r))
		return r;
	if (is_press(ev, KEY_S))
		vc->state = VIEWCTL_SNAP_PICK;
	return VIEWCTL_TAKEN;
}

static enum viewctl_result
handle_snap_pick(struct viewctl *vc, struct camera *cam, const struct input_event_rec *ev)
{
	enum viewctl_result r;
	if (ev->kind == INPUT_BUTTON)
		return ev->code == BTN_LEFT && ev->value == 1 ? VIEWCTL_PICK : VIEWCTL_TAKEN;
	if (ev->kind != INPUT_KEY)
		return swallowed_unless_device(ev);
	if (common_key(vc, cam, ev, &r))
		return r;
	return VIEWCTL_TAKEN;
}

static enum viewctl_result
handle_snapping(struct viewctl *vc, struct camera *cam, const struct input_event_rec *ev)
{
	enum viewctl_result r;
	if (ev->kind != INPUT_KEY)
		return swallowed_unless_device(ev);
	if (common_key(vc, cam, ev, &r))
		return r;
	if (is_press(ev, KEY_S)) {
		/* another snap: this one ends at once where it was going */
		viewop_snap_at(&vc->snap, 1, cam);
		vc->state = VIEWCTL_SNAP_PICK;
		return VIEWCTL_CHANGED;
	}
	return VIEWCTL_TAKEN;
}

enum viewctl_result
viewctl_event(struct viewctl *vc, struct camera *cam, int caller_mode,
	      const struct input_event_rec *ev)
{
	track_modifiers(vc, ev);
	switch (vc->state) {
	case VIEWCTL_IDLE:
		return handle_idle(vc, cam, caller_mode, ev);
	case VIEWCTL_VIEWING:
		return handle_viewing(vc, cam, ev);
	case VIEWCTL_SNAP_PICK:
		return handle_snap_pick(vc, cam, ev);
	case VIEWCTL_SNAPPING:
		return handle_snapping(vc, cam, ev);
	}
	return VIEWCTL_PASS;
}

enum viewctl_result
viewctl_snap_to(struct viewctl *vc, const struct camera *cam, const double target[3],
		uint64_t now_us)
{
	if (vc->state != VIEWCTL_SNAP_PICK)
		return VIEWCTL_PASS;
	if (target && viewop_snap_begin(&vc->snap, cam, target, now_us) == 0)
		vc->state = VIEWCTL_SNAPPING;
	else
		vc->state = VIEWCTL_VIEWING;
	return VIEWCTL_TAKEN;
}

enum viewctl_result
viewctl_frame(struct viewctl *vc, struct camera *cam, uint64_t now_us)
{
	switch (vc->state) {
	case VIEWCTL_IDLE:
		return VIEWCTL_PASS;
	case VIEWCTL_VIEWING:
	case VIEWCTL_SNAP_PICK:
		return VIEWCTL_TAKEN;
	case VIEWCTL_SNAPPING:
		if (!viewop_snap_step(&vc->snap, now_us, vc->gains.snap_us, vc->gains.snap_min_rad, cam))
			vc->state = VIEWCTL_VIEWING;
		return VIEWCTL_CHANGED;
	}
	return VIEWCTL_PASS;
}
