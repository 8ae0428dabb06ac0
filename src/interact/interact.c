/* interact.c - the modes around the manipulation operator (see interact.h) */
#include "interact/interact.h"

#include <linux/input-event-codes.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "interact/mouse_line.h"

void
interact_init(struct interact *ia)
{
	memset(ia, 0, sizeof *ia);
	ia->mode = INTERACT_NONE;
	ia->fig = ia->view = -1;
}

/* the operator's message: the 20 degree rule's refusal, or nothing */
static void
interact_update_message(struct interact *ia)
{
	const struct manip_refusal *r = manip_refusal(&ia->m);
	snprintf(ia->message, sizeof ia->message, "%s", r->active && r->message ? r->message : "");
}

/* a new mouse line from the pointer; 1 when G moved */
static int
interact_pointer_moved(struct interact *ia)
{
	struct ray r;
	if (mouse_line(&ia->cam, ia->width, ia->height, ia->px, ia->py, &r) < 0)
		return 0;
	return manip_ray(&ia->m, &r);
}

static double
interact_clamp(double v, double hi)
{
	return v < 0 ? 0 : v > hi ? hi : v;
}

void
interact_start(struct interact *ia, enum interact_mode mode, int fig, int view,
	       const struct xform *g0, const struct xform *obj, const struct camera *cam, int w,
	       int h)
{
	interact_end(ia);
	ia->mode = mode;
	ia->fig = fig;
	ia->tag = 0;
	ia->con = -1;
	ia->con_tag = 0;
	ia->view = view;
	ia->cam = *cam;
	ia->width = w;
	ia->height = h;
	ia->px = w * 0.5;
	ia->py = h * 0.5;
	struct manip_def def = manip_default_def();
	manip_init(&ia->m, &def, g0, cam);
	/* the object in G's frame: obj = G * offset */
	struct xform gi;
	xform_inv(g0, &gi);
	xform_mul(&gi, obj, &ia->offset);
	interact_pointer_moved(ia); /* the first mouse line: no button, so G stays */
	interact_update_message(ia);
}

/* the camera or the view's size changed under the mode */
static void
interact_view_changed(struct interact *ia, const struct camera *cam, int w, int h)
{
	if (memcmp(cam, &ia->cam, sizeof *cam) || w != ia->width || h != ia->height) {
		ia->cam = *cam;
		ia->width = w;
		ia->height = h;
		ia->px = interact_clamp(ia->px, w);
		ia->py = interact_clamp(ia->py, h);
		manip_camera(&ia->m, cam);
	}
}

int
interact_input(struct interact *ia, const struct input_event_rec *e, long px, long py,
	       const struct camera *cam, int w, int h)
{
	if (ia->mode == INTERACT_NONE)
		return 0;
	interact_view_changed(ia, cam, w, h);
	int out = 0;
	switch ((enum input_kind)e->kind) {
	case INPUT_KEY:
	case INPUT_BUTTON:
		if (e->kind == INPUT_KEY && e->code == KEY_ESC && e->value == 1) {
			interact_end(ia);
			return INTERACT_ENDED;
		}
		if (e->kind == INPUT_BUTTON && e->value == 0 &&
		    (e->code == BTN_LEFT || e->code == BTN_MIDDLE || e->code == BTN_RIGHT))
			out |= INTERACT_RELEASED;
		/* buttons, SHIFT, CONTROL and ALT make the chord */
		if (manip_event(&ia->m, e)) {
			out |= INTERACT_ICONS;
			/* a chord chosen where the pointer is: the line anchors it */
			if (interact_pointer_moved(ia))
				out |= INTERACT_MOVED;
		}
		break;
	case INPUT_MOTION:
		if (!px && !py)
			break;
		ia->px = interact_clamp(ia->px + (double)px, w);
		ia->py = interact_clamp(ia->py + (double)py, h);
		if (interact_pointer_moved(ia))
			out |= INTERACT_MOVED;
		break;
	case INPUT_POINTER:
		if (e->flags & INPUT_F_VIEW) {
			if (e->code != ia->view)
				break; /* another view's pointer: not ours */
			ia->px = interact_clamp(e->x, w);
			ia->py = interact_clamp(e->y, h);
		} else {
			ia->px = interact_clamp(e->x * w, w);
			ia->py = interact_clamp(e->y * h, h);
		}
		if (interact_pointer_moved(ia))
			out |= INTERACT_MOVED;
		break;
	default:
		break;
	}
	interact_update_message(ia);
	return out;
}

void
interact_target(const struct interact *ia, struct xform *dest)
{
	xform_mul(&ia->m.g, &ia->offset, dest);
}

void
interact_reset_orientation(struct interact *ia, const struct xform *effector)
{
	struct xform g = ia->m.g;
	memcpy(g.r, effector->r, sizeof g.r);
	manip_set(&ia->m, &g);
}

void
interact_end(struct interact *ia)
{
	ia->mode = INTERACT_NONE;
	ia->fig = ia->view = -1;
	ia->message[0] = '\0';
}

const char *
interact_mode_to_str(enum interact_mode m)
{
	switch (m) {
	case INTERACT_NONE:
		return "none";
	case INTERACT_FIGURE:
		return "figure";
	case INTERACT_DRAG:
		return "drag";
	}
	return "none";
}
