/* dials.c - the dial panel's bindings applied (see dials.h) */
#include "daemon/dials.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "figure/kin.h"
#include "interact/geom.h"
#include "interact/viewop.h"
#include "pose/behave.h"
#include "pose/spine.h"

void
dials_init(struct dials *D, struct modes *M)
{
	memset(D, 0, sizeof *D);
	dial_bind_init(&D->table);
	D->M = M;
}

int
dials_load(struct dials *D, const char *path, const struct can_map *panel, char *err,
	   size_t errlen)
{
	struct dial_bind_lookup lookup = { dial_bind_find_in_map, panel };
	return dial_bind_read(path, panel ? &lookup : NULL, &D->table, err, errlen);
}

static void
say(struct dials *D, const char *why)
{
	snprintf(D->message, sizeof D->message, "dial: %s", why);
	snprintf(D->M->d->message, sizeof D->M->d->message, "%s", D->message);
}

/* DOF k of joint j of figure fig moved by delta, within its limits */
static int
move_dof(struct dials *D, int fig, int j, int k, double delta)
{
	struct env_figure *f = &D->M->d->env.fig[fig];
	const struct model *m = f->model;
	if (k >= m->jnt_ndof[j]) {
		say(D, "the joint has no such DOF");
		return 0;
	}
	int dof = m->jnt_dof0[j] + k;
	double v = fmin(fmax(f->state->q[dof] + delta, m->dof_lo[dof]), m->dof_hi[dof]);
	if (v == f->state->q[dof])
		return 0;
	f->state->q[dof] = v;
	kin_update(m, f->state);
	daemon_step_moves(D->M->d, fig); /* other clients' changes to it wait for the turn */
	return 1;
}

/* the picked joint (the last `manipulate joint`), as Jack's dial box turns it */
static int
move_picked(struct dials *D, int k, double delta)
{
	const struct daemon *d = D->M->d;
	int fig = d->picked.fig;
	if (fig < 0 || fig >= ENV_MAX_FIGURES || d->env.fig[fig].gen != d->picked.gen) {
		say(D, "no joint picked (manipulate joint FIG JOINT picks one)");
		return 0;
	}
	return move_dof(D, fig, d->picked.joint, k, delta);
}

static int
move_named(struct dials *D, const struct dial_target *t, double delta)
{
	const struct env *e = &D->M->d->env;
	int fig = env_find_figure(e, t->figure);
	int j = fig >= 0 ? model_find_joint(e->fig[fig].model, t->joint) : -1;
	if (j < 0) {
		say(D, "its joint is not there");
		return 0;
	}
	return move_dof(D, fig, j, t->dof, delta);
}

static int
move_camera(struct dials *D, int axis, double delta)
{
	int v = modes_current_view(D->M);
	if (v < 0) {
		say(D, "no view to turn");
		return 0;
	}
	struct camera cam;
	view_camera_of_view(&D->M->d->env.view[v], &cam);
	double done = axis == DIAL_CAMERA_SWEEP_H ? viewop_sweep_horizontal(&cam, delta)
		      : axis == DIAL_CAMERA_SWEEP_V ? viewop_sweep_vertical(&cam, delta)
						    : viewop_zoom(&cam, delta);
	if (done == 0)
		return 0;
	modes_set_camera(D->M, v, &cam, 0);
	D->camera_moved = 1;
	return 1;
}

/* the behaving human the dials work on: the mode's, else the first there is; -1 */
static int
behaving_figure(const struct dials *D)
{
	const struct env *e = &D->M->d->env;
	const struct interact *ia = &D->M->interact;
	if (ia->mode != INTERACT_NONE && ia->fig >= 0 && e->fig[ia->fig].behave)
		return ia->fig;
	for (int i = 0; i < ENV_MAX_FIGURES; i++)
		if (e->fig[i].gen && e->fig[i].behave)
			return i;
	return -1;
}

static int
move_behavior(struct dials *D, int param, double delta)
{
	int fig = behaving_figure(D);
	if (fig < 0) {
		say(D, "no behaving human (behave FIG on)");
		return 0;
	}
	struct env *e = &D->M->d->env;
	struct env_figure *f = &e->fig[fig];
	env_sync_solver(e, fig);
	daemon_step_moves(D->M->d, fig);
	if (param == DIAL_BEHAVIOR_ELEVATION) {
		behave_move_com(f->behave, f->model, f->state, f->ik, 0, 0, delta);
		return 1;
	}
	double total[3];
	spine_totals(f->model, f->state, total);
	total[param == DIAL_BEHAVIOR_TORSO_FORWARD ? SPINE_FLEX
	      : param == DIAL_BEHAVIOR_TORSO_LATERAL ? SPINE_LAT
						     : SPINE_AXIAL] += delta;
	struct spine_flavor fl = spine_bend_from_waist();
	return behave_bend_torso(f->behave, f->model, f->state, f->ik, total, &fl) == 0;
}

/* G along (or about) a world axis, and what the mode moves with it */
static int
move_manip(struct dials *D, int axis, double delta)
{
	struct interact *ia = &D->M->interact;
	if (ia->mode == INTERACT_NONE || ia->mode == INTERACT_JOINT) {
		say(D, "the manipulation transform turns in a figure, site, drag or primitive mode");
		return 0;
	}
	struct xform g = ia->m.g;
	double u[3] = { 0, 0, 0 };
	u[axis % 3] = 1;
	if (axis < 3) {
		g.p[axis] += delta;
	} else {
		double r[9];
		geom_rotation(u, delta, r);
		mathx_mat3_mul(r, ia->m.g.r, g.r);
	}
	manip_set(&ia->m, &g);
	modes_apply(D->M);
	return 1;
}

static int
apply_move(struct dials *D, const struct dial_target *t, double delta)
{
	switch ((enum dial_target_kind)t->kind) {
	case DIAL_TARGET_DOF:
		return move_picked(D, t->dof, delta);
	case DIAL_TARGET_JOINT:
		return move_named(D, t, delta);
	case DIAL_TARGET_CAMERA:
		return move_camera(D, t->axis, delta);
	case DIAL_TARGET_BEHAVIOR:
		return move_behavior(D, t->axis, delta);
	case DIAL_TARGET_MANIP:
		return move_manip(D, t->axis, delta);
	}
	return 0;
}

/* the dials' step over: the view they turned journaled, one undo for the turn */
static void
end_turn(struct dials *D)
{
	int v = modes_current_view(D->M);
	if (D->camera_moved && v >= 0) {
		struct camera cam;
		view_camera_of_view(&D->M->d->env.view[v], &cam);
		modes_set_camera(D->M, v, &cam, 1);
	}
	D->camera_moved = 0;
	D->stepping = 0;
	modes_step(D->M, 'E');
}

int
dials_input(struct dials *D, const struct input_event_rec *e)
{
	/* a key or a button is the person doing something else: the turn is over */
	if (D->stepping && (e->kind == INPUT_KEY || e->kind == INPUT_BUTTON))
		end_turn(D);
	struct dial_action a[4];
	int n = dial_bind_feed(&D->table, e, a, 4), moved = 0;
	for (int i = 0; i < n; i++) {
		if (a[i].kind == DIAL_ACTION_COMMAND) {
			D->M->run_typed(D->M->ctx, a[i].command);
			moved = 1;
			continue;
		}
		/* the first move of a turn begins its step, before anything changes */
		if (!D->stepping && !D->M->d->step.open) {
			modes_step(D->M, 'B');
			D->stepping = D->M->d->step.open;
		}
		if (apply_move(D, a[i].target, a[i].delta)) {
			moved = 1;
			D->last_us = e->t_us;
		}
	}
	if (moved)
		D->M->scene->dirty = 1;
	return moved;
}

void
dials_frame(struct dials *D, uint64_t now_us)
{
	if (!D->stepping || now_us < D->last_us || now_us - D->last_us < DIALS_STILL_US)
		return;
	end_turn(D);
}
