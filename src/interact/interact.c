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
	ia->def = manip_default_def();
}

void
interact_increments(struct interact *ia, int on, double step, double step_angle)
{
	ia->increments = !!on;
	ia->def.step = step;
	ia->def.step_angle = step_angle;
	if (ia->mode == INTERACT_NONE)
		return;
	manip_steps(&ia->m, step, step_angle);
	manip_increments(&ia->m, on);
}

/* the operator's message: the 20 degree rule's refusal, or nothing */
static void
interact_update_message(struct interact *ia)
{
	const struct manip_refusal *r = manip_refusal(&ia->m);
	snprintf(ia->message, sizeof ia->message, "%s", r->active && r->message ? r->message : "");
}

void
interact_dof_view(const struct model *m, const struct state *s, int dof, struct joint_dof_view *dest)
{
	int j = m->dof_jnt[dof];
	double dir = s->jnt_dir[j]; /* pointing up the rooting: the child moves by -q */
	dest->rotation = m->dof_kind[dof] == DOF_ROTATION;
	for (int k = 0; k < 3; k++) {
		dest->axis[k] = dir * s->dof_axis_w[3 * dof + k];
		dest->pivot[k] = s->dof_pivot_w[3 * dof + k];
	}
	/* the value the mouse moves is the child's motion, dir * q */
	dest->value = dir * s->q[dof];
	dest->lo = dir > 0 ? m->dof_lo[dof] : -m->dof_hi[dof];
	dest->hi = dir > 0 ? m->dof_hi[dof] : -m->dof_lo[dof];
}

/* joint mode: a new mouse line turns the selected DOF; 1 when a value changed */
static int
interact_joint_ray(struct interact *ia, const struct ray *r)
{
	if (ia->jm.dof < 0)
		return 0;
	int dof = ia->model->jnt_dof0[ia->joint] + ia->jm.dof;
	struct joint_dof_view dv;
	interact_dof_view(ia->model, ia->state, dof, &dv);
	double v;
	if (!joint_manip_ray(&ia->jm, &dv, r, &v))
		return 0;
	double dir = ia->state->jnt_dir[ia->joint];
	ia->moved_dof = dof;
	ia->moved_value = dir * v;
	return 1;
}

int
interact_joint_type(struct interact *ia, double typed)
{
	if (ia->mode != INTERACT_JOINT || ia->jm.dof < 0)
		return 0;
	int dof = ia->model->jnt_dof0[ia->joint] + ia->jm.dof;
	struct joint_dof_view dv;
	interact_dof_view(ia->model, ia->state, dof, &dv);
	double dir = ia->state->jnt_dir[ia->joint], v;
	/* typed in the DOF's own sense: the mouse's value is dir * q */
	if (!joint_manip_type(&ia->jm, &dv, dir * typed, &v))
		return 0;
	ia->moved_dof = dof;
	ia->moved_value = dir * v;
	return 1;
}

int
interact_joint_rotation(const struct interact *ia)
{
	if (ia->mode != INTERACT_JOINT || ia->jm.dof < 0)
		return -1;
	return ia->model->dof_kind[ia->model->jnt_dof0[ia->joint] + ia->jm.dof] == DOF_ROTATION;
}

/* a new mouse line from the pointer; 1 when G (or the joint) moved */
static int
interact_pointer_moved(struct interact *ia)
{
	struct ray r;
	if (mouse_line(&ia->cam, ia->width, ia->height, ia->px, ia->py, &r) < 0)
		return 0;
	if (ia->mode == INTERACT_JOINT)
		return interact_joint_ray(ia, &r);
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
	manip_init(&ia->m, &ia->def, g0, cam);
	manip_increments(&ia->m, ia->increments);
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

void
interact_camera(struct interact *ia, const struct camera *cam, int w, int h)
{
	if (ia->mode == INTERACT_NONE)
		return;
	interact_view_changed(ia, cam, w, h);
	interact_update_message(ia);
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
		if (ia->mode == INTERACT_JOINT ? joint_manip_event(&ia->jm, e)
					       : manip_event(&ia->m, e)) {
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
	if (ia->mode == INTERACT_JOINT)
		ia->message[0] = '\0'; /* the 20 degree rule is the operator's, not the joint's */
	else
		interact_update_message(ia);
	return out;
}

void
interact_target(const struct interact *ia, struct xform *dest)
{
	xform_mul(&ia->m.g, &ia->offset, dest);
}

void
interact_start_joint(struct interact *ia, int fig, int view, const struct model *m,
		     const struct state *s, int joint, const struct camera *cam, int w, int h)
{
	struct xform g;
	xform_identity(&g);
	int dof0 = m->jnt_dof0[joint];
	for (int k = 0; k < 3; k++)
		g.p[k] = s->dof_pivot_w[3 * dof0 + k];
	/* the joint first: interact_start's first mouse line reaches it (and selects nothing) */
	ia->model = m;
	ia->state = s;
	ia->joint = joint;
	joint_manip_init(&ia->jm, m->jnt_ndof[joint]);
	interact_start(ia, INTERACT_JOINT, fig, view, &g, &g, cam, w, h);
}

void
interact_reset_orientation(struct interact *ia, const struct xform *effector)
{
	struct xform g = ia->m.g;
	memcpy(g.r, effector->r, sizeof g.r);
	manip_set(&ia->m, &g);
}

unsigned
interact_buttons(const struct interact *ia)
{
	if (ia->mode == INTERACT_NONE)
		return 0;
	return ia->mode == INTERACT_JOINT ? ia->jm.buttons : ia->m.buttons;
}

const char *
interact_name(const struct interact *ia)
{
	return ia->mode == INTERACT_PRIMITIVE ? interact_primitive_to_str(ia->primitive)
					      : interact_mode_to_str(ia->mode);
}

void
interact_end(struct interact *ia)
{
	ia->jm.dof = -1;
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
	case INTERACT_JOINT:
		return "joint";
	case INTERACT_PRIMITIVE:
		return "primitive";
	case INTERACT_SITE:
		return "site";
	}
	return "none";
}

const char *
interact_primitive_to_str(enum interact_primitive p)
{
	static const char *const names[] = { "hand", "foot", "com", "head", "eyes", "pelvis", "torso" };
	return (unsigned)p < sizeof names / sizeof *names ? names[p] : "none";
}
