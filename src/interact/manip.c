/*
 * manip.c - the manipulation operator's state machine (Chapter 3, Appendix B).
 *
 * Three inputs reach the state machine: the chord changed, a new mouse
 * line, a new camera. Each state has one handler that takes the input and
 * returns the next state; the chord and the camera are handled alike in
 * every state that acts (re-choose or re-check, then re-anchor), and the
 * mouse line is what tells the states apart.
 */
#include "interact/manip.h"

#include <linux/input-event-codes.h>
#include <math.h>
#include <string.h>

#include "interact/geom.h"

enum manip_input {
	IN_CHORD,  /* buttons or modifiers changed */
	IN_RAY,    /* a new mouse line */
	IN_CAMERA, /* the view changed */
	IN_SCALE,  /* ALT or increments changed how motion maps to G */
};

/* a wheel's spoke shorter than this (m) has no direction to anchor on */
#define SPOKE_MIN 1e-9

struct manip_def
manip_default_def(void)
{
	struct manip_def d = {
		.limit = 20.0 * M_PI / 180.0,
		.fine = 0.1,
		.step = 0.01,
		.step_angle = 5.0 * M_PI / 180.0,
	};
	return d;
}

void
manip_init(struct manip *m, const struct manip_def *def, const struct xform *g,
	   const struct camera *cam)
{
	memset(m, 0, sizeof *m);
	m->limit = def->limit;
	m->fine = def->fine;
	m->step = def->step;
	m->step_angle = def->step_angle;
	m->g = *g;
	m->g0 = *g;
	m->cam = *cam;
	m->state = MANIP_IDLE;
	m->sel = manip_chord(0, 0, 0);
}

/* ---- Table 3.2 ------------------------------------------------------------ */

struct manip_selection
manip_chord(unsigned buttons, int shift, int ctrl)
{
	/*
	 * indexed by the button mask: left, middle, right are x, y, z in
	 * every row (DESIGN.md's erratum); two buttons name the plane of
	 * their axes, kept here as its normal, the axis whose button is up
	 */
	static const struct {
		enum manip_mode mode;
		int axis;
	} translate[8] = {
		{ MANIP_MODE_IDLE, 0 },   /* none */
		{ MANIP_MODE_LINEAR, 0 }, /* left: x */
		{ MANIP_MODE_LINEAR, 1 }, /* middle: y */
		{ MANIP_MODE_PLANAR, 2 }, /* left and middle: xy */
		{ MANIP_MODE_LINEAR, 2 }, /* right: z */
		{ MANIP_MODE_PLANAR, 1 }, /* left and right: xz */
		{ MANIP_MODE_PLANAR, 0 }, /* middle and right: yz */
		{ MANIP_MODE_NONE, 0 },   /* all three: no effect (section 3.3.2) */
	};
	struct manip_selection s = { translate[buttons & 7].mode, shift ? MANIP_LOCAL : MANIP_GLOBAL,
				     translate[buttons & 7].axis };
	/* CONTROL turns one button into a wheel; "only one rotation button may be selected at once" */
	if (ctrl) {
		if (s.mode == MANIP_MODE_LINEAR)
			s.mode = MANIP_MODE_ROTATE;
		else if (s.mode == MANIP_MODE_PLANAR)
			s.mode = MANIP_MODE_NONE;
	}
	if (s.mode == MANIP_MODE_IDLE || s.mode == MANIP_MODE_NONE)
		s.axis = 0;
	return s;
}

/* ---- the anchor and the 20 degree rule ------------------------------------- */

/* axis k (0 1 2: x y z) of the frame in the world, unit */
static void
frame_axis(const struct xform *g, enum manip_frame frame, int k, double dest[3])
{
	if (frame == MANIP_LOCAL) {
		/* G's axes are the columns of its rotation */
		double c[3] = { g->r[k], g->r[3 + k], g->r[6 + k] };
		if (geom_normalize(c, dest) == 0)
			return;
	}
	dest[0] = dest[1] = dest[2] = 0;
	dest[k] = 1;
}

/* from the eye to G's origin; the camera's -z when the eye sits on the origin */
static void
line_of_sight(const struct manip *m, double dest[3])
{
	double d[3];
	for (int i = 0; i < 3; i++)
		d[i] = m->g.p[i] - m->cam.xf.p[i];
	if (mathx_dot(d, d) > 1e-18 && geom_normalize(d, dest) == 0)
		return;
	dest[0] = -m->cam.xf.r[2];
	dest[1] = -m->cam.xf.r[5];
	dest[2] = -m->cam.xf.r[8];
}

/* the selection's axis (or normal) and the two others, from G as it is now */
static void
selection_axes(struct manip *m)
{
	frame_axis(&m->g, m->sel.frame, m->sel.axis, m->axis);
	/* the plane's axes in index order (xz: x then z); the wheel's with u x v = axis */
	int i = (m->sel.axis + 1) % 3, j = (m->sel.axis + 2) % 3;
	if (m->sel.mode == MANIP_MODE_PLANAR && i > j) {
		int t = i;
		i = j;
		j = t;
	}
	frame_axis(&m->g, m->sel.frame, i, m->u);
	frame_axis(&m->g, m->sel.frame, j, m->v);
}

static int
same_selection(const struct manip_selection *a, const struct manip_selection *b)
{
	return a->mode == b->mode && a->frame == b->frame && a->axis == b->axis;
}

/* the motion counts from G as it is now: no reference line yet, no turn */
static void
restart_motion(struct manip *m)
{
	m->g0 = m->g;
	m->anchored = 0;
	m->angle = 0;
}

/*
 * Takes G and the axis as they are now and says whether section 3.7
 * refuses the selection: an axis near the line of sight for translation,
 * an axis near perpendicular to it (the wheel or plane near edge-on) for
 * rotation and planar translation. "Closer than 20 degrees" refuses, so
 * exactly the limit is allowed. Fills m->refusal when it refuses.
 */
static int
anchor_and_check(struct manip *m)
{
	restart_motion(m);
	selection_axes(m);
	double sight[3];
	line_of_sight(m, sight);
	double angle = geom_line_angle(m->axis, sight);
	int refused = 0;
	const char *msg = NULL;
	switch (m->sel.mode) {
	case MANIP_MODE_LINEAR:
		refused = angle < m->limit;
		msg = "can't translate along that axis from this view";
		break;
	case MANIP_MODE_PLANAR:
		refused = angle > M_PI / 2 - m->limit;
		msg = "can't translate in that plane from this view";
		break;
	case MANIP_MODE_ROTATE:
		refused = angle > M_PI / 2 - m->limit;
		msg = "can't rotate around that axis from this view";
		break;
	case MANIP_MODE_IDLE:
	case MANIP_MODE_NONE:
		break;
	}
	if (!refused)
		return 0;
	m->refusal.active = 1;
	m->refusal.sel = m->sel;
	m->refusal.angle = angle;
	memcpy(m->refusal.axis, m->axis, sizeof m->refusal.axis);
	m->refusal.message = msg;
	return 1;
}

/* ---- following the mouse line ---------------------------------------------- */

/* a motion since the anchor as G takes it: a tenth under ALT, in steps when asked */
static double
applied(const struct manip *m, double motion, double step)
{
	if (m->alt)
		motion *= m->fine;
	if (m->increments && step > 0)
		motion = step * round(motion / step);
	return motion;
}

/* B.1: G's origin moves with the nearest point of the axis */
static void
linear_follow(struct manip *m)
{
	double s;
	if (geom_axis_nearest_ray(m->g0.p, m->axis, &m->ray, &s, NULL) != GEOM_HIT)
		return;
	if (!m->anchored) {
		m->s0 = s;
		m->anchored = 1;
		return;
	}
	double d = applied(m, s - m->s0, m->step);
	for (int i = 0; i < 3; i++)
		m->g.p[i] = m->g0.p[i] + d * m->axis[i];
}

/* B.2: G's origin moves with the point where the mouse line meets the plane */
static void
planar_follow(struct manip *m)
{
	double x[3];
	if (geom_ray_plane(&m->ray, m->g0.p, m->axis, NULL, x) != GEOM_HIT)
		return;
	if (!m->anchored) {
		memcpy(m->x0, x, sizeof m->x0);
		m->anchored = 1;
		return;
	}
	/* the motion in the plane's own axes, so increments step along them */
	double w[3];
	for (int i = 0; i < 3; i++)
		w[i] = x[i] - m->x0[i];
	double du = applied(m, mathx_dot(w, m->u), m->step);
	double dv = applied(m, mathx_dot(w, m->v), m->step);
	for (int i = 0; i < 3; i++)
		m->g.p[i] = m->g0.p[i] + du * m->u[i] + dv * m->v[i];
}

/*
 * B.3: G turns about the axis through its origin by the angle from the
 * first spoke to the current one, G' = R G. The angle is summed from
 * the turns between successive spokes, so cranking past half a turn
 * keeps going instead of flipping sign at the back of the wheel.
 */
static void
rotate_follow(struct manip *m)
{
	double x[3], s[3];
	if (geom_ray_plane(&m->ray, m->g0.p, m->axis, NULL, x) != GEOM_HIT)
		return;
	for (int i = 0; i < 3; i++)
		s[i] = x[i] - m->g0.p[i];
	if (!m->anchored) {
		if (mathx_dot(s, s) < SPOKE_MIN * SPOKE_MIN)
			return;
		memcpy(m->spoke0, s, sizeof s);
		memcpy(m->spoke, s, sizeof s);
		m->angle = 0;
		m->anchored = 1;
		return;
	}
	double turn;
	if (geom_spoke_angle(m->axis, m->spoke, s, &turn) != GEOM_HIT)
		return;
	m->angle += turn;
	memcpy(m->spoke, s, sizeof s);
	double r[9];
	geom_rotation(m->axis, applied(m, m->angle, m->step_angle), r);
	mathx_mat3_mul(r, m->g0.r, m->g.r);
	memcpy(m->g.p, m->g0.p, sizeof m->g.p);
}

/* ---- the states -------------------------------------------------------------- */

static enum manip_state
state_of_mode(enum manip_mode md)
{
	switch (md) {
	case MANIP_MODE_IDLE:
		return MANIP_IDLE;
	case MANIP_MODE_LINEAR:
		return MANIP_LINEAR;
	case MANIP_MODE_PLANAR:
		return MANIP_PLANAR;
	case MANIP_MODE_ROTATE:
		return MANIP_ROTATE;
	case MANIP_MODE_NONE:
		return MANIP_NONE;
	}
	return MANIP_NONE;
}

/* the one follower of the selection's mode */
static void
follow(struct manip *m)
{
	if (!m->have_ray)
		return;
	switch (m->sel.mode) {
	case MANIP_MODE_LINEAR:
		linear_follow(m);
		break;
	case MANIP_MODE_PLANAR:
		planar_follow(m);
		break;
	case MANIP_MODE_ROTATE:
		rotate_follow(m);
		break;
	case MANIP_MODE_IDLE:
	case MANIP_MODE_NONE:
		break;
	}
}

/* the 20 degree rule said no to the current selection; repeat: the same was the last choice */
static enum manip_state
refuse(struct manip *m, int repeat)
{
	m->refusal.repeat = repeat;
	return MANIP_REFUSED;
}

/*
 * The chord changed: make its selection, check it, and anchor on the
 * mouse line the caller gave last (so the icons have their spokes before
 * any motion). A refusal of the selection whose refusal the last press
 * settled on is a repeat (see settle()); the chords on the way to this
 * one change nothing of that.
 */
static enum manip_state
choose(struct manip *m)
{
	m->sel = manip_chord(m->buttons, m->shift != 0, m->ctrl != 0);
	m->refusal.active = 0;
	m->refusal.repeat = 0;
	m->g0 = m->g;
	m->chord_g0 = m->g;
	m->anchored = 0;
	if (m->sel.mode == MANIP_MODE_IDLE || m->sel.mode == MANIP_MODE_NONE)
		return state_of_mode(m->sel.mode);
	if (anchor_and_check(m))
		return refuse(m, m->have_last_refused &&
					 same_selection(&m->last_refused, &m->sel));
	follow(m);
	return state_of_mode(m->sel.mode);
}

/* ALT or increments changed: the motion so far is G's, the rest counts from here */
static void
reanchor(struct manip *m)
{
	restart_motion(m);
	follow(m);
}

/*
 * The camera changed under the same chord: check again, and wait for the
 * next mouse line (from the new view) to anchor on.
 */
static enum manip_state
recheck(struct manip *m, enum manip_state now)
{
	int was_refused = now == MANIP_REFUSED;
	int repeat = m->refusal.repeat;
	m->refusal.active = 0;
	m->refusal.repeat = 0;
	/* still refused: the user has chosen nothing new */
	if (anchor_and_check(m))
		return refuse(m, was_refused && repeat);
	return state_of_mode(m->sel.mode);
}

/* one of the three states in which the mouse line moves G */
static int
is_acting(enum manip_state state)
{
	return state == MANIP_LINEAR || state == MANIP_PLANAR || state == MANIP_ROTATE;
}

/*
 * One step of the machine from state now. A new chord always chooses
 * afresh. Idle and none (no button; three buttons, or CONTROL with more
 * than one) wait for it. Refused waits too, but a new view may change the
 * 20 degree rule's answer, so it checks again. The acting states follow
 * the mouse line, check again on a new view and re-anchor on a new scale.
 */
static enum manip_state
next_state(struct manip *m, enum manip_input in, enum manip_state now)
{
	int acting = is_acting(now);
	switch (in) {
	case IN_CHORD:
		return choose(m);
	case IN_RAY:
		if (acting)
			follow(m);
		break;
	case IN_CAMERA:
		if (acting || now == MANIP_REFUSED)
			return recheck(m, now);
		break;
	case IN_SCALE:
		if (acting)
			reanchor(m);
		break;
	}
	return now;
}

static void
dispatch(struct manip *m, enum manip_input in)
{
	m->state = next_state(m, in, m->state);
}

/* ---- the choice a press settles on (section 3.7's "the same axis again") ------ */

/*
 * Keys go down and up one at a time, so a chord of two passes through a
 * chord of one on the way in and on the way out (left then right: x, then
 * the xz plane, then z or x). Those are not choices. What a press of the
 * buttons chose is the chord held when the first of its keys (a button,
 * SHIFT or CONTROL) comes up: the one the user built, and dragged with if
 * the mouse moved. A drag that moves G after that, on what is still held,
 * is an action of its own and takes its place.
 */
static void
settle(struct manip *m)
{
	m->settled = 1;
	m->settled_sel = m->sel;
	m->settled_state = m->state;
}

/*
 * The last button came up: a refusal settled on is remembered (the next
 * choice of the same selection is the second try); an action forgets it;
 * a chord with no action (three buttons, CONTROL with two) leaves it.
 */
static void
remember_choice(struct manip *m)
{
	if (!m->settled)
		return;
	m->settled = 0;
	if (m->settled_state == MANIP_REFUSED) {
		m->last_refused = m->settled_sel;
		m->have_last_refused = 1;
	} else if (is_acting(m->settled_state)) {
		m->have_last_refused = 0;
	}
}

/* ---- the inputs -------------------------------------------------------------- */

/* sets or clears bit in *mask; returns 1 when that changed it */
static int
set_bit(unsigned *mask, unsigned bit, int down)
{
	unsigned old = *mask;
	if (down)
		*mask |= bit;
	else
		*mask &= ~bit;
	return *mask != old;
}

int
manip_event(struct manip *m, const struct input_event_rec *ev)
{
	if (ev->kind != INPUT_BUTTON && ev->kind != INPUT_KEY)
		return 0;
	/* a key repeat changes nothing; any other nonzero value is a press */
	if (ev->kind == INPUT_KEY && ev->value == 2)
		return 0;
	int down = ev->value != 0, changed = 0;
	unsigned held = m->buttons;
	if (ev->kind == INPUT_BUTTON) {
		switch (ev->code) {
		case BTN_LEFT:
			changed = set_bit(&m->buttons, MANIP_LEFT, down);
			break;
		case BTN_MIDDLE:
			changed = set_bit(&m->buttons, MANIP_MIDDLE, down);
			break;
		case BTN_RIGHT:
			changed = set_bit(&m->buttons, MANIP_RIGHT, down);
			break;
		}
	} else {
		switch (ev->code) {
		/* one bit a side, so that releasing one keeps the other held */
		case KEY_LEFTSHIFT:
		case KEY_RIGHTSHIFT:
			changed = set_bit(&m->shift, ev->code == KEY_LEFTSHIFT ? 1 : 2, down);
			break;
		case KEY_LEFTCTRL:
		case KEY_RIGHTCTRL:
			changed = set_bit(&m->ctrl, ev->code == KEY_LEFTCTRL ? 1 : 2, down);
			break;
		case KEY_LEFTALT:
		case KEY_RIGHTALT:
			/* ALT selects nothing (a refused axis is not chosen again by it): it re-anchors */
			if (!set_bit(&m->alt, ev->code == KEY_LEFTALT ? 1 : 2, down))
				return 0;
			dispatch(m, IN_SCALE);
			return 1;
		}
	}
	if (!changed)
		return 0;
	if (!down && held && !m->settled)
		settle(m); /* the chord as it was before this key came up */
	dispatch(m, IN_CHORD);
	if (held && !m->buttons)
		remember_choice(m);
	return 1;
}

void
manip_increments(struct manip *m, int on)
{
	if (m->increments == !!on)
		return;
	m->increments = !!on;
	dispatch(m, IN_SCALE);
}

void
manip_steps(struct manip *m, double step, double step_angle)
{
	if (m->step == step && m->step_angle == step_angle)
		return;
	m->step = step;
	m->step_angle = step_angle;
	if (m->increments)
		dispatch(m, IN_SCALE);
}

int
manip_ray(struct manip *m, const struct ray *r)
{
	struct xform before = m->g;
	m->ray = *r;
	m->have_ray = 1;
	dispatch(m, IN_RAY);
	int moved = memcmp(&before, &m->g, sizeof before) != 0;
	if (moved && m->settled)
		settle(m); /* a drag on what is held after a key came up */
	return moved;
}

void
manip_camera(struct manip *m, const struct camera *cam)
{
	m->cam = *cam;
	dispatch(m, IN_CAMERA);
}

int
manip_type(struct manip *m, double value)
{
	if (!isfinite(value) || (m->state != MANIP_LINEAR && m->state != MANIP_ROTATE))
		return -1;
	struct xform g = m->chord_g0;
	if (m->state == MANIP_LINEAR) {
		for (int i = 0; i < 3; i++)
			g.p[i] += value * m->axis[i];
	} else {
		double r[9];
		geom_rotation(m->axis, value, r);
		mathx_mat3_mul(r, m->chord_g0.r, g.r);
	}
	m->g = g;
	/* the mouse goes on from here: the next line anchors anew */
	m->g0 = g;
	m->anchored = 0;
	m->angle = 0;
	return 0;
}

void
manip_set(struct manip *m, const struct xform *g)
{
	m->g = *g;
	m->g0 = *g;
	m->anchored = 0;
	m->angle = 0;
	if (m->state == MANIP_LINEAR || m->state == MANIP_PLANAR || m->state == MANIP_ROTATE)
		selection_axes(m);
}

/* ---- what the caller reads ----------------------------------------------------- */

void
manip_icon(const struct manip *m, struct manip_icon *dest)
{
	memset(dest, 0, sizeof *dest);
	dest->state = m->state;
	dest->sel = m->sel;
	memcpy(dest->origin, m->g.p, sizeof dest->origin);
	if (m->sel.mode == MANIP_MODE_IDLE || m->sel.mode == MANIP_MODE_NONE)
		return;
	memcpy(dest->axis, m->axis, sizeof dest->axis);
	if (m->state == MANIP_REFUSED)
		memcpy(dest->axis, m->refusal.axis, sizeof dest->axis);
	memcpy(dest->u, m->u, sizeof dest->u);
	memcpy(dest->v, m->v, sizeof dest->v);
	if (m->sel.mode == MANIP_MODE_ROTATE && m->anchored) {
		dest->has_spokes = 1;
		memcpy(dest->spoke0, m->spoke0, sizeof dest->spoke0);
		memcpy(dest->spoke, m->spoke, sizeof dest->spoke);
		dest->angle = m->angle;
	}
}

const struct manip_refusal *
manip_refusal(const struct manip *m)
{
	return &m->refusal;
}

const char *
manip_state_to_str(enum manip_state s)
{
	switch (s) {
	case MANIP_IDLE:
		return "idle";
	case MANIP_NONE:
		return "none";
	case MANIP_REFUSED:
		return "refused";
	case MANIP_LINEAR:
		return "linear";
	case MANIP_PLANAR:
		return "planar";
	case MANIP_ROTATE:
		return "rotate";
	}
	return "?";
}

const char *
manip_mode_to_str(enum manip_mode md)
{
	switch (md) {
	case MANIP_MODE_IDLE:
		return "idle";
	case MANIP_MODE_LINEAR:
		return "linear";
	case MANIP_MODE_PLANAR:
		return "planar";
	case MANIP_MODE_ROTATE:
		return "rotate";
	case MANIP_MODE_NONE:
		return "none";
	}
	return "?";
}
