/* modes.c - the interactive modes and the views they move (see modes.h) */
#include "daemon/modes.h"

#include <linux/input-event-codes.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "daemon/cmd.h"
#include "figure/kin.h"
#include "interact/mouse_line.h"
#include "interact/obstruct.h"
#include "interact/pick.h"
#include "pose/behave.h"
#include "pose/spine.h"

void
modes_init(struct modes *M, struct daemon *d, struct scene *scene,
	   void (*run_command)(void *ctx, const char *line), void *ctx)
{
	memset(M, 0, sizeof *M);
	M->d = d;
	M->scene = scene;
	M->run_command = run_command;
	M->ctx = ctx;
	interact_init(&M->interact);
	M->hover_fig = M->hover_seg = -1;
	struct menu_def md = menu_default_def();
	md.verb = cmd_entry_verb;
	md.object = cmd_entry_object;
	md.usage = cmd_entry_usage;
	menu_init(&M->menu, &md);
	d->menu = &M->menu;
	d->menu_view = M->menu_view = -1;
	d->prompt = &M->prompt;
	d->hover_fig = d->hover_seg = -1;
	d->pointer_view = -1;
	d->kiosk_fig.fig = -1;
	struct viewctl_gains gains = viewctl_default_gains();
	for (int v = 0; v < ENV_MAX_VIEWS; v++)
		viewctl_init(&M->viewctl[v], &gains);
	M->pointer_view = -1;
}

static uint64_t
modes_now(const struct modes *M)
{
	return M->d->now_us ? M->d->now_us(M->d) : 0;
}

/* view v's camera, as change view left it, back into the view (eye and target) */
static void
store_camera(struct modes *M, int v, const struct camera *cam)
{
	struct env_view *vw = &M->d->env.view[v];
	memcpy(vw->eye, cam->xf.p, sizeof vw->eye);
	view_camera_vrp(cam, vw->target);
	M->scene->dirty = 1;
}

/* the view v's camera as it is now, journaled as the command that sets it */
static void
journal_camera(struct modes *M, int v)
{
	const struct env_view *vw = &M->d->env.view[v];
	char line[256];
	snprintf(line, sizeof line, "set camera %s eye=%.17g,%.17g,%.17g target=%.17g,%.17g,%.17g",
		 vw->name, vw->eye[0], vw->eye[1], vw->eye[2], vw->target[0], vw->target[1],
		 vw->target[2]);
	M->run_command(M->ctx, line);
}

/* the view change view works in: the kiosk's (the mode's, else the pointer's, else the first) */
static int
current_view(const struct modes *M)
{
	return daemon_kiosk_view(M->d);
}

/* the pointer outside a mode: where S picks */
static void
track_pointer(struct modes *M, const struct input_event_rec *e, long px, long py)
{
	const struct env *env = &M->d->env;
	if (e->kind == INPUT_POINTER && (e->flags & INPUT_F_VIEW) && e->code < ENV_MAX_VIEWS) {
		M->pointer_view = e->code;
		M->pointer_x = e->x;
		M->pointer_y = e->y;
	} else if (e->kind == INPUT_MOTION && M->pointer_view >= 0 &&
		   env->view[M->pointer_view].used) {
		const struct env_view *vw = &env->view[M->pointer_view];
		M->pointer_x = fmin(fmax(M->pointer_x + (double)px, 0), vw->width);
		M->pointer_y = fmin(fmax(M->pointer_y + (double)py, 0), vw->height);
	} else {
		return;
	}
	M->d->pointer_view = M->pointer_view;
	M->d->pointer_x = M->pointer_x;
	M->d->pointer_y = M->pointer_y;
	M->scene->dirty = 1;
}

/* S picked: the snap's target is what lies under the pointer of view v */
static void
snap_pick(struct modes *M, int v, struct camera *cam)
{
	struct env *e = &M->d->env;
	const struct env_view *vw = &e->view[v];
	double x = M->interact.mode != INTERACT_NONE ? M->interact.px : M->pointer_x;
	double y = M->interact.mode != INTERACT_NONE ? M->interact.py : M->pointer_y;
	struct ray r;
	struct pick_hit h;
	int fig, hit = mouse_line(cam, vw->width, vw->height, x, y, &r) == 0 &&
		       daemon_pick(M->d, &r, cam->znear, -1, &h, &fig) > 0;
	viewctl_snap_to(&M->viewctl[v], cam, hit ? h.point : NULL, modes_now(M));
}

/* a step of the mode begins ('B') or ends ('E'): one undoable, journaled change */
static void
mode_step(struct modes *M, char end, uint64_t now_us)
{
	if (end == 'B')
		M->step_began_us = now_us;
	if (M->d->mode_step)
		M->d->mode_step(M->d, end);
}

/*
 * Change view takes the event first (V enters it from any mode; inside,
 * everything is its own). Returns 1 when it took the event.
 */
static int
drive_view(struct modes *M, const struct input_event_rec *e, long px, long py)
{
	int v = current_view(M);
	if (v < 0)
		return 0;
	struct camera cam;
	view_camera_of_view(&M->d->env.view[v], &cam);
	struct input_event_rec ev = *e;
	if (ev.kind == INPUT_MOTION) { /* change view moves by pixels */
		ev.x = (double)px;
		ev.y = (double)py;
	}
	enum viewctl_result r = viewctl_event(&M->viewctl[v], &cam, M->interact.mode, &ev);
	switch (r) {
	case VIEWCTL_PASS:
		return 0;
	case VIEWCTL_CHANGED:
		store_camera(M, v, &cam);
		break;
	case VIEWCTL_PICK:
		snap_pick(M, v, &cam);
		break;
	case VIEWCTL_ENDED:
		store_camera(M, v, &cam);
		journal_camera(M, v);
		if (M->view_step) { /* change view was one step: one undo takes the view back */
			M->view_step = 0;
			mode_step(M, 'E', 0);
		}
		break;
	case VIEWCTL_ENTERED:
		if (!M->d->step.open) {
			mode_step(M, 'B', modes_now(M));
			M->view_step = 1;
		}
		M->scene->dirty = 1;
		break;
	case VIEWCTL_TAKEN:
		M->scene->dirty = 1;
		break;
	}
	return 1;
}

/* the automatic adjustments under way (§3.7): about a second, eased, then journaled */
static void
adjust_frames(struct modes *M, uint64_t now_us)
{
	for (int v = 0; v < ENV_MAX_VIEWS; v++) {
		struct view_adjust *va = &M->adjust[v];
		if (!va->active)
			continue;
		if (!M->d->env.view[v].used) {
			va->active = 0;
			continue;
		}
		struct camera cam;
		int more = view_adjust_step(va, now_us, VIEW_ADJUST_US, VIEW_ADJUST_MIN_TURN, &cam);
		store_camera(M, v, &cam);
		const struct env_view *vw = &M->d->env.view[v];
		if (M->interact.view == v) /* the operator sees the new line of sight */
			interact_camera(&M->interact, &cam, vw->width, vw->height);
		if (!more) {
			journal_camera(M, v);
			if (!strcmp(M->d->message, "adjusting the view"))
				M->d->message[0] = '\0';
		}
	}
}


/* a drag ended: its constraint, which only the mode uses, goes (the posture stays) */
static void
end_drag(struct modes *M)
{
	int con = env_find_constraint(&M->d->env, CMD_DRAG_CONSTRAINT);
	if (con >= 0)
		env_remove_constraint(&M->d->env, con);
}



/* the modes whose object is where G is: the view adjusts to keep G workable (§3.7) */
static int
moves_by_operator(enum interact_mode mode)
{
	return mode == INTERACT_FIGURE || mode == INTERACT_DRAG || mode == INTERACT_SITE;
}

/* the camera of view v before an automatic change, for C to take it back */
static void
remember_view(struct modes *M, int v, const struct camera *cam)
{
	if (M->nundo_view[v] == MODES_VIEW_UNDO) { /* the oldest goes */
		memmove(&M->undo_view[v][0], &M->undo_view[v][1],
			sizeof M->undo_view[v][0] * (MODES_VIEW_UNDO - 1));
		M->nundo_view[v]--;
	}
	M->undo_view[v][M->nundo_view[v]++] = *cam;
}

/* C in a mode: the last automatic view change taken back; 1 when there was one */
static int
take_back_view(struct modes *M, int v)
{
	if (v < 0 || !M->nundo_view[v])
		return 0;
	M->adjust[v].active = 0;
	const struct camera *cam = &M->undo_view[v][--M->nundo_view[v]];
	store_camera(M, v, cam);
	const struct env_view *vw = &M->d->env.view[v];
	interact_camera(&M->interact, cam, vw->width, vw->height);
	journal_camera(M, v);
	return 1;
}

/*
 * §3.7: the same axis chosen again after the 20 degree rule's warning
 * turns the camera until it is clear; the operator then goes on.
 */
static void
maybe_adjust_view(struct modes *M, const struct camera *cam)
{
	struct interact *ia = &M->interact;
	if (!moves_by_operator(ia->mode))
		return;
	const struct manip_refusal *rf = manip_refusal(&ia->m);
	struct view_adjust *va = &M->adjust[ia->view];
	if (!rf->active || !rf->repeat || va->active)
		return;
	enum view_adjust_kind kind =
		rf->sel.mode == MANIP_MODE_LINEAR ? VIEW_ADJUST_ALONG : VIEW_ADJUST_ACROSS;
	if (view_adjust_begin(va, cam, ia->m.g.p, rf->axis, kind, ia->m.limit, modes_now(M)) > 0) {
		remember_view(M, ia->view, cam);
		snprintf(M->d->message, sizeof M->d->message, "adjusting the view");
	}
}

/*
 * The segment G sits on, whose neighbourhood is left out of the map: the
 * dragged site's or the moved site's. -1 when the whole figure goes (a
 * figure moved as a whole surrounds its origin; it is the object).
 */
static int
g_segment(const struct modes *M)
{
	const struct interact *ia = &M->interact;
	const struct env *e = &M->d->env;
	if (ia->mode == INTERACT_SITE)
		return e->fig[ia->fig].model->site_seg[ia->site];
	if (ia->mode == INTERACT_DRAG && ia->con >= 0)
		return e->fig[ia->fig].model->site_seg[e->con[ia->con].def.effector_site];
	return -1;
}

/*
 * §3.7.1: the visibility map from p towards view v's camera, with the
 * manipulated figure skip's parts around G left out (they surround its
 * origin and would hide every direction; the rest of its body can hide
 * G like any other figure); when something nearer than the eye hides p,
 * the eye turns about p to the nearest clear direction, eased like the
 * other adjustments, remembered for C, journaled at the end.
 */
static void
avoid_obstruction(struct modes *M, int v, const double p[3], int skip)
{
	if (v < 0 || v >= ENV_MAX_VIEWS || !M->d->env.view[v].used || M->adjust[v].active)
		return;
	struct camera cam;
	view_camera_of_view(&M->d->env.view[v], &cam);
	double d[3] = { cam.xf.p[0] - p[0], cam.xf.p[1] - p[1], cam.xf.p[2] - p[2] }, dir[3];
	double dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
	char err[256];
	if (!(dist > HEMI_ZNEAR))
		return;
	const unsigned char *own = NULL;
	int seg = skip >= 0 && M->interact.fig == skip ? g_segment(M) : -1;
	if (seg >= 0 && obstruct_own_parts(M->d->env.fig[skip].model, M->d->env.fig[skip].state,
					   seg, M->own_parts, MODES_MAX_SEGMENTS) >= 0)
		own = M->own_parts;
	const struct hemi_map *m = scene_hemicube(M->scene, M->d, p, d, skip, own, err, sizeof err);
	if (!m)
		return;
	if (obstruct_check(m, dist, OBSTRUCT_CONE, dir) == 1 &&
	    view_adjust_turn_to(&M->adjust[v], &cam, p, dir, modes_now(M)) > 0) {
		remember_view(M, v, &cam);
		snprintf(M->d->message, sizeof M->d->message, "adjusting the view");
	}
}

void
modes_bring_into_view(struct modes *M, int v, const double p[3])
{
	struct daemon *d = M->d;
	if (v < 0 || v >= ENV_MAX_VIEWS || !d->env.view[v].used || M->adjust[v].active)
		return;
	const struct env_view *vw = &d->env.view[v];
	struct camera cam;
	view_camera_of_view(vw, &cam);
	if (!view_adjust_visible(&cam, vw->width, vw->height, p) &&
	    view_adjust_focus(&M->adjust[v], &cam, p, modes_now(M)) > 0)
		remember_view(M, v, &cam);
	else if (M->interact.mode != INTERACT_NONE && M->interact.view == v)
		avoid_obstruction(M, v, p, M->interact.fig);
}

/*
 * bend torso from G: G's turn since the mode began, in the pelvis's axes
 * then (x left, y up, z forward), as a rotation vector: its x is flexion
 * (+ forward), its y axial rotation (+ to the left) and its -z the lateral
 * bend (+ to the left), added to the bend the spine had. One button turns
 * about one axis, so each wheel drives one direction exactly.
 */
static void
bend_torso(struct behave *b, struct env_figure *f, const struct interact *ia,
	   const struct xform *g)
{
	double turn[9], w[3];
	mathx_mat3_tmul(ia->applied_r, g->r, turn); /* G0^T G */
	mathx_rotation_vector(turn, w);
	double total[3] = { ia->torso0[SPINE_FLEX] + w[0], ia->torso0[SPINE_LAT] - w[2],
			    ia->torso0[SPINE_AXIAL] + w[1] };
	struct spine_flavor fl = spine_bend_from_waist();
	behave_bend_torso(b, f->model, f->state, f->ik, total, &fl);
}

/* a primitive's goal from G, as its move command sets it (Table 5.2) */
static void
drive_primitive(struct modes *M, struct env_figure *f, struct interact *ia)
{
	struct behave *b = f->behave;
	if (!b)
		return;
	env_sync_solver(&M->d->env, (int)(f - M->d->env.fig));
	struct xform g;
	interact_target(ia, &g);
	switch (ia->primitive) {
	case INTERACT_HAND:
		behave_move_hand(b, f->model, f->state, f->ik, ia->side, &g, 0);
		break;
	case INTERACT_FOOT:
		behave_move_foot(b, f->model, f->state, f->ik, ia->side, &g);
		break;
	case INTERACT_COM: {
		/* move com shifts by offsets: those of G since the centre of mass last went */
		/* the centre of mass balance holds: with the weights the figure carries */
		double com[3];
		kin_com(f->model, f->state);
		behave_com(b, f->state, com);
		double d[3] = { g.p[0] - com[0], g.p[1] - com[1], g.p[2] - com[2] };
		behave_move_com(b, f->model, f->state, f->ik, d[0], d[2], d[1]);
		break;
	}
	case INTERACT_HEAD:
		behave_move_head(b, f->ik, g.p);
		break;
	case INTERACT_PELVIS: {
		/* rotate pelvis turns by increments: G's turn since the last one, in world axes */
		double inv[9], turn[9];
		for (int i = 0; i < 3; i++)
			for (int j = 0; j < 3; j++)
				inv[3 * i + j] = ia->applied_r[3 * j + i];
		mathx_mat3_mul(g.r, inv, turn);
		behave_rotate_pelvis(b, f->model, f->state, f->ik, turn);
		memcpy(ia->applied_r, g.r, sizeof g.r);
		break;
	}
	case INTERACT_EYES:
		behave_move_eyes(b, f->ik, g.p);
		break;
	case INTERACT_TORSO:
		bend_torso(b, f, ia, &g);
		break;
	}
}

/* G (or the joint) moved: what the mode moves follows, at once */
void
modes_apply(struct modes *M)
{
	struct interact *ia = &M->interact;
	struct env *env = &M->d->env;
	if (ia->mode == INTERACT_NONE || ia->fig < 0)
		return;
	struct env_figure *f = &env->fig[ia->fig];
	switch (ia->mode) {
	case INTERACT_FIGURE:
		interact_target(ia, &f->state->root_xf);
		kin_update(f->model, f->state);
		break;
	case INTERACT_SITE: {
		/* the site's new frame on its segment, which stays put */
		struct xform g, seg_inv, loc;
		interact_target(ia, &g);
		xform_inv(&f->state->seg_xf[f->model->site_seg[ia->site]], &seg_inv);
		xform_mul(&seg_inv, &g, &loc);
		env_place_site(env, ia->fig, ia->site, &loc);
		break;
	}
	case INTERACT_JOINT:
		f->state->q[ia->moved_dof] = ia->moved_value;
		kin_update(f->model, f->state);
		break;
	case INTERACT_PRIMITIVE:
		drive_primitive(M, f, ia);
		break;
	case INTERACT_DRAG: {
		struct ik_constraint_def def = env->con[ia->con].def;
		interact_target(ia, &def.goal_xf);
		env_set_constraint(env, ia->con, &def);
		break;
	}
	case INTERACT_NONE:
		break;
	}
	M->scene->dirty = 1;
}

/* the buttons came up (or the mode ended): the step is over, with what it moved */
static void
end_step_if_due(struct modes *M)
{
	if (!M->step_end_due)
		return;
	M->step_end_due = 0;
	mode_step(M, 'E', 0);
}


/* an input event to the interactive mode; its target applied at once */
static void
drive_mode(struct modes *M, const struct input_event_rec *e, long px, long py)
{
	struct interact *ia = &M->interact;
	if (ia->mode == INTERACT_NONE)
		return;
	struct env *env = &M->d->env;
	const struct env_view *vw = ia->view >= 0 ? &env->view[ia->view] : NULL;
	struct env_figure *f = ia->fig >= 0 ? &env->fig[ia->fig] : NULL;
	struct env_constraint *con = ia->mode == INTERACT_DRAG && ia->con >= 0 ? &env->con[ia->con]
									       : NULL;
	if (!vw || !vw->used || !f || f->gen != ia->tag ||
	    (ia->mode == INTERACT_DRAG && (!con || con->gen != ia->con_tag))) {
		interact_end(ia); /* its view, figure or constraint went away */
		return;
	}
	if (e->kind == INPUT_KEY && e->code == KEY_C && e->value == 1 && take_back_view(M, ia->view))
		return;
	struct camera cam;
	view_camera_of_view(vw, &cam);
	enum interact_mode mode = ia->mode;
	/* the first button down begins a step, the last one up ends it */
	int first_press = input_is_mouse_button(e) && e->value == 1 && !interact_buttons(ia);
	int r = interact_input(ia, e, px, py, &cam, vw->width, vw->height);
	if (first_press && interact_buttons(ia)) /* a press never moves G: the state is still before */
		mode_step(M, 'B', modes_now(M));
	if (((r & INTERACT_RELEASED) && !interact_buttons(ia)) || (r & INTERACT_ENDED))
		M->step_end_due = 1;
	if (r)
		M->scene->dirty = 1;
	maybe_adjust_view(M, &cam);
	/* a new drag: is the object still in sight (§3.7.1)? */
	if (moves_by_operator(mode) && ia->mode == mode &&
	    e->kind == INPUT_BUTTON && e->value == 1 &&
	    (e->code == BTN_LEFT || e->code == BTN_MIDDLE || e->code == BTN_RIGHT))
		avoid_obstruction(M, ia->view, ia->m.g.p, ia->fig);
	if (r & INTERACT_ENDED) {
		if (mode == INTERACT_DRAG)
			end_drag(M);
		end_step_if_due(M);
		return;
	}
	if (mode == INTERACT_DRAG && (r & INTERACT_RELEASED)) {
		/* §4.6.2: the orientation offset resets when a button comes up */
		struct xform eff;
		xform_mul(&f->state->site_xf[con->def.effector_site], &con->def.effector_offset, &eff);
		interact_reset_orientation(ia, &eff);
		r |= INTERACT_MOVED;
	}
	if (!(r & INTERACT_MOVED)) {
		end_step_if_due(M);
		return;
	}
	/* beyond the dissertation: a dragged G near the edge of the picture, the view follows */
	if (moves_by_operator(mode) && !M->adjust[ia->view].active &&
	    !view_adjust_inside(&cam, vw->width, vw->height, ia->m.g.p, MODES_EDGE_MARGIN) &&
	    view_adjust_focus(&M->adjust[ia->view], &cam, ia->m.g.p, modes_now(M)) > 0)
		remember_view(M, ia->view, &cam);
	modes_apply(M);
	end_step_if_due(M);
}

/* change view is running in the view the keys would go to */
static int
viewing(const struct modes *M)
{
	int v = current_view(M);
	return v >= 0 && M->viewctl[v].state != VIEWCTL_IDLE;
}

/*
 * A button held for MODES_HELD_MAX_US with nothing else happening is a
 * button stuck (or a person gone): its drag ends as a release would end
 * it, so the kiosk is never left in a step.
 */
static void
release_held_buttons(struct modes *M, uint64_t now_us)
{
	struct interact *ia = &M->interact;
	uint64_t limit = M->d->held_max_us ? M->d->held_max_us : MODES_HELD_MAX_US;
	if (!M->d->step.open || !interact_buttons(ia) || now_us < M->step_began_us ||
	    now_us - M->step_began_us < limit)
		return;
	static const unsigned short codes[] = { BTN_LEFT, BTN_MIDDLE, BTN_RIGHT };
	for (int k = 0; k < 3 && interact_buttons(ia); k++) {
		if (!(interact_buttons(ia) & (1u << k)))
			continue;
		struct input_event_rec up = { .t_us = now_us, .device = INPUT_DEVICE_SOCKET,
					      .kind = INPUT_BUTTON, .code = codes[k], .value = 0 };
		drive_mode(M, &up, 0, 0);
	}
	snprintf(M->d->message, sizeof M->d->message,
		 "a button held for %.0f s: its drag ended", (double)limit / 1e6);
}

/* the snaps and adjustments under way, one in-between each a frame */
void
modes_frame(struct modes *M, uint64_t now_us)
{
	release_held_buttons(M, now_us);
	adjust_frames(M, now_us);
	for (int v = 0; v < ENV_MAX_VIEWS; v++) {
		if (!M->d->env.view[v].used || M->viewctl[v].state != VIEWCTL_SNAPPING)
			continue;
		struct camera cam;
		view_camera_of_view(&M->d->env.view[v], &cam);
		if (viewctl_frame(&M->viewctl[v], &cam, now_us) == VIEWCTL_CHANGED)
			store_camera(M, v, &cam);
	}
}

void
modes_set_camera(struct modes *M, int v, const struct camera *cam, int journal)
{
	store_camera(M, v, cam);
	const struct env_view *vw = &M->d->env.view[v];
	if (M->interact.mode != INTERACT_NONE && M->interact.view == v)
		interact_camera(&M->interact, cam, vw->width, vw->height);
	if (journal)
		journal_camera(M, v);
}

int
modes_current_view(const struct modes *M)
{
	return current_view(M);
}

void
modes_step(struct modes *M, char end)
{
	mode_step(M, end, modes_now(M));
}

void
modes_sync(struct modes *M)
{
	struct interact *ia = &M->interact;
	if (ia->mode == INTERACT_NONE)
		return;
	const struct env_figure *f = ia->fig >= 0 ? &M->d->env.fig[ia->fig] : NULL;
	if (!f || !f->gen || f->gen != ia->tag) {
		interact_end(ia);
		if (M->kiosk)
			kiosk_mode_ended(M->kiosk);
		return;
	}
	ia->model = f->model;
	ia->state = f->state;
	/* the kiosk's figure once the mode is over (daemon_kiosk_figure) */
	M->d->kiosk_fig.fig = ia->fig;
	M->d->kiosk_fig.gen = f->gen;
}

int
modes_view_input(struct modes *M, const struct input_event_rec *e, long px, long py)
{
	return drive_view(M, e, px, py);
}

void
modes_mode_input(struct modes *M, const struct input_event_rec *e, long px, long py)
{
	drive_mode(M, e, px, py);
}

void
modes_track_pointer(struct modes *M, const struct input_event_rec *e, long px, long py)
{
	track_pointer(M, e, px, py);
}

int
modes_viewing(const struct modes *M)
{
	return viewing(M);
}
