/* loop.c - the frame loop: the only file that sees compute and I/O together */
#include "daemon/loop.h"

#include <errno.h>
#include <inttypes.h>
#include <linux/input-event-codes.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/signalfd.h>
#include <time.h>
#include <unistd.h>

#include "daemon/cmd.h"
#include "daemon/events.h"
#include "daemon/notify.h"
#include "daemon/scene.h"
#include "devices/can_dev.h"
#include "devices/escape_chord.h"
#include "devices/hotplug.h"
#include "devices/input_backends.h"
#include "devices/input_devs.h"
#include "devices/motion_scale.h"
#include "figure/kin.h"
#include "interact/interact.h"
#include "interact/mouse_line.h"
#include "interact/obstruct.h"
#include "interact/pick.h"
#include "interact/view_adjust.h"
#include "interact/viewctl.h"
#include "pose/attach.h"
#include "pose/behave.h"

#define LOOP_VIEW_UNDO 8 /* automatic view changes remembered per view */
#define LOOP_EDGE_MARGIN 0.1 /* a dragged G this near the picture's edge: the view follows */

struct loop {
	struct daemon d;
	struct server srv;
	struct journal j;
	int sig_fd;
	uint64_t period_us;
	uint64_t synced_seq;  /* the last journal record known to be on disk */
	uint64_t virtual_us;  /* the clock of settle's frames */
	uint64_t fps_t0, fps_frames;
	uint64_t watchdog_us, watchdog_last;
	struct events events; /* what the clients subscribed to */
	struct input_queue input; /* from the devices and the socket's input lines */
	struct can_map panel;     /* the dial panel's map, when one is given */
	struct input_devs devs;   /* the mice, keyboards and panels read directly */
	/* each device's motion to pixels; the last: the socket's input lines */
	struct motion_scale pointer[INPUT_DEVS_MAX + 1];
	double pointer_gain;
	struct hotplug hotplug;   /* devices arriving; fd -1: not watched */
	struct escape_chord escape; /* the grab's way out at the keyboard */
	struct interact interact;   /* the mode the input drives */
	struct viewctl viewctl[ENV_MAX_VIEWS]; /* change view, one machine per view (Appendix C) */
	struct view_adjust adjust[ENV_MAX_VIEWS]; /* §3.7's automatic adjustments under way */
	/* the cameras before each automatic change, newest last: C takes one back */
	struct camera undo_view[ENV_MAX_VIEWS][LOOP_VIEW_UNDO];
	int nundo_view[ENV_MAX_VIEWS];
	int pointer_view;           /* the view the pointer was last in, -1: none yet */
	double pointer_x, pointer_y;
	struct scene scene;   /* the views' pictures */
	int stop;
};

static uint64_t
real_now(void *ctx)
{
	(void)ctx;
	struct timespec t;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return (uint64_t)t.tv_sec * 1000000u + (uint64_t)t.tv_nsec / 1000u;
}

static uint64_t
clock_us(void)
{
	return real_now(NULL);
}

/* settle's clock: every read advances it, so the time limit cuts alike on every run */
static uint64_t
virtual_now(void *ctx)
{
	struct loop *L = ctx;
	return L->virtual_us += 20;
}

/* a line the loop runs as if a client sent it, journaled when it changes state */
static void
run_own_command(struct loop *L, const char *line)
{
	struct cmd_outcome out;
	cmd_run(&L->d, -1, line, strlen(line), &out);
	if (out.mutated && journal_command(&L->j, &L->d, line, strlen(line)) < 0)
		fprintf(stderr, "postured: journal: %s\n", strerror(errno));
	free(out.json);
}

/* view v's camera, as change view left it, back into the view (eye and target) */
static void
store_camera(struct loop *L, int v, const struct camera *cam)
{
	struct env_view *vw = &L->d.env.view[v];
	memcpy(vw->eye, cam->xf.p, sizeof vw->eye);
	view_camera_vrp(cam, vw->target);
	L->scene.dirty = 1;
}

/* the view v's camera as it is now, journaled as the command that sets it */
static void
journal_camera(struct loop *L, int v)
{
	const struct env_view *vw = &L->d.env.view[v];
	char line[256];
	snprintf(line, sizeof line, "set camera %s eye=%.17g,%.17g,%.17g target=%.17g,%.17g,%.17g",
		 vw->name, vw->eye[0], vw->eye[1], vw->eye[2], vw->target[0], vw->target[1],
		 vw->target[2]);
	run_own_command(L, line);
}

/* the view change view works in: the mode's, else the one the pointer was last in, else the first */
static int
current_view(const struct loop *L)
{
	const struct env *e = &L->d.env;
	if (L->interact.mode != INTERACT_NONE && L->interact.view >= 0)
		return L->interact.view;
	if (L->pointer_view >= 0 && e->view[L->pointer_view].used)
		return L->pointer_view;
	for (int v = 0; v < ENV_MAX_VIEWS; v++)
		if (e->view[v].used)
			return v;
	return -1;
}

/* the pointer outside a mode: where S picks */
static void
track_pointer(struct loop *L, const struct input_event_rec *e, long px, long py)
{
	const struct env *env = &L->d.env;
	if (e->kind == INPUT_POINTER && (e->flags & INPUT_F_VIEW) && e->code < ENV_MAX_VIEWS) {
		L->pointer_view = e->code;
		L->pointer_x = e->x;
		L->pointer_y = e->y;
	} else if (e->kind == INPUT_MOTION && L->pointer_view >= 0 &&
		   env->view[L->pointer_view].used) {
		const struct env_view *vw = &env->view[L->pointer_view];
		L->pointer_x = fmin(fmax(L->pointer_x + (double)px, 0), vw->width);
		L->pointer_y = fmin(fmax(L->pointer_y + (double)py, 0), vw->height);
	}
}

/* S picked: the snap's target is what lies under the pointer of view v */
static void
snap_pick(struct loop *L, int v, struct camera *cam)
{
	struct env *e = &L->d.env;
	const struct env_view *vw = &e->view[v];
	double x = L->interact.mode != INTERACT_NONE ? L->interact.px : L->pointer_x;
	double y = L->interact.mode != INTERACT_NONE ? L->interact.py : L->pointer_y;
	struct ray r;
	struct pick_hit h;
	int fig, hit = mouse_line(cam, vw->width, vw->height, x, y, &r) == 0 &&
		       daemon_pick(&L->d, &r, cam->znear, -1, &h, &fig) > 0;
	viewctl_snap_to(&L->viewctl[v], cam, hit ? h.point : NULL, real_now(NULL));
}

/*
 * Change view takes the event first (V enters it from any mode; inside,
 * everything is its own). Returns 1 when it took the event.
 */
static int
drive_view(struct loop *L, const struct input_event_rec *e, long px, long py)
{
	int v = current_view(L);
	if (v < 0)
		return 0;
	struct camera cam;
	view_camera_of_view(&L->d.env.view[v], &cam);
	struct input_event_rec ev = *e;
	if (ev.kind == INPUT_MOTION) { /* change view moves by pixels */
		ev.x = (double)px;
		ev.y = (double)py;
	}
	enum viewctl_result r = viewctl_event(&L->viewctl[v], &cam, L->interact.mode, &ev);
	switch (r) {
	case VIEWCTL_PASS:
		return 0;
	case VIEWCTL_CHANGED:
		store_camera(L, v, &cam);
		break;
	case VIEWCTL_PICK:
		snap_pick(L, v, &cam);
		break;
	case VIEWCTL_ENDED:
		store_camera(L, v, &cam);
		journal_camera(L, v);
		break;
	case VIEWCTL_TAKEN:
	case VIEWCTL_ENTERED:
		L->scene.dirty = 1;
		break;
	}
	return 1;
}

/* the automatic adjustments under way (§3.7): about a second, eased, then journaled */
static void
adjust_frames(struct loop *L, uint64_t now_us)
{
	for (int v = 0; v < ENV_MAX_VIEWS; v++) {
		struct view_adjust *va = &L->adjust[v];
		if (!va->active)
			continue;
		if (!L->d.env.view[v].used) {
			va->active = 0;
			continue;
		}
		struct camera cam;
		int more = view_adjust_step(va, now_us, VIEW_ADJUST_US, VIEW_ADJUST_MIN_TURN, &cam);
		store_camera(L, v, &cam);
		const struct env_view *vw = &L->d.env.view[v];
		if (L->interact.view == v) /* the operator sees the new line of sight */
			interact_camera(&L->interact, &cam, vw->width, vw->height);
		if (!more) {
			journal_camera(L, v);
			if (!strcmp(L->d.message, "adjusting the view"))
				L->d.message[0] = '\0';
		}
	}
}

/* the snaps under way, one in-between each a frame */
static void
view_frames(struct loop *L, uint64_t now_us)
{
	adjust_frames(L, now_us);
	for (int v = 0; v < ENV_MAX_VIEWS; v++) {
		if (!L->d.env.view[v].used || L->viewctl[v].state != VIEWCTL_SNAPPING)
			continue;
		struct camera cam;
		view_camera_of_view(&L->d.env.view[v], &cam);
		if (viewctl_frame(&L->viewctl[v], &cam, now_us) == VIEWCTL_CHANGED)
			store_camera(L, v, &cam);
	}
}

/* a drag ended: its constraint deleted as a command, so the journal has it too */
static void
end_drag(struct loop *L)
{
	run_own_command(L, "delete constraint " CMD_DRAG_CONSTRAINT);
}

/* the camera of view v before an automatic change, for C to take it back */
static void
remember_view(struct loop *L, int v, const struct camera *cam)
{
	if (L->nundo_view[v] == LOOP_VIEW_UNDO) { /* the oldest goes */
		memmove(&L->undo_view[v][0], &L->undo_view[v][1],
			sizeof L->undo_view[v][0] * (LOOP_VIEW_UNDO - 1));
		L->nundo_view[v]--;
	}
	L->undo_view[v][L->nundo_view[v]++] = *cam;
}

/* C in a mode: the last automatic view change taken back; 1 when there was one */
static int
take_back_view(struct loop *L, int v)
{
	if (v < 0 || !L->nundo_view[v])
		return 0;
	L->adjust[v].active = 0;
	const struct camera *cam = &L->undo_view[v][--L->nundo_view[v]];
	store_camera(L, v, cam);
	const struct env_view *vw = &L->d.env.view[v];
	interact_camera(&L->interact, cam, vw->width, vw->height);
	journal_camera(L, v);
	return 1;
}

/*
 * §3.7: the same axis chosen again after the 20 degree rule's warning
 * turns the camera until it is clear; the operator then goes on.
 */
static void
maybe_adjust_view(struct loop *L, const struct camera *cam)
{
	struct interact *ia = &L->interact;
	if (ia->mode != INTERACT_FIGURE && ia->mode != INTERACT_DRAG)
		return;
	const struct manip_refusal *rf = manip_refusal(&ia->m);
	struct view_adjust *va = &L->adjust[ia->view];
	if (!rf->active || !rf->repeat || va->active)
		return;
	enum view_adjust_kind kind =
		rf->sel.mode == MANIP_MODE_LINEAR ? VIEW_ADJUST_ALONG : VIEW_ADJUST_ACROSS;
	if (view_adjust_begin(va, cam, ia->m.g.p, rf->axis, kind, ia->m.limit, real_now(NULL)) > 0) {
		remember_view(L, ia->view, cam);
		snprintf(L->d.message, sizeof L->d.message, "adjusting the view");
	}
}

/*
 * §3.7.1: the visibility map from p towards view v's camera, figure slot
 * skip left out (the manipulated figure's own body surrounds its origin:
 * it would hide every direction); when something nearer than the eye
 * hides p, the eye turns about p to the nearest clear direction, eased
 * like the other adjustments, remembered for C, journaled at the end.
 */
static void
avoid_obstruction(struct loop *L, int v, const double p[3], int skip)
{
	if (v < 0 || v >= ENV_MAX_VIEWS || !L->d.env.view[v].used || L->adjust[v].active)
		return;
	struct camera cam;
	view_camera_of_view(&L->d.env.view[v], &cam);
	double d[3] = { cam.xf.p[0] - p[0], cam.xf.p[1] - p[1], cam.xf.p[2] - p[2] }, dir[3];
	double dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
	char err[256];
	if (!(dist > HEMI_ZNEAR))
		return;
	const struct hemi_map *m = scene_hemicube(&L->scene, &L->d, p, d, skip, err, sizeof err);
	if (!m)
		return;
	if (obstruct_check(m, dist, OBSTRUCT_CONE, dir) == 1 &&
	    view_adjust_turn_to(&L->adjust[v], &cam, p, dir, real_now(NULL)) > 0) {
		remember_view(L, v, &cam);
		snprintf(L->d.message, sizeof L->d.message, "adjusting the view");
	}
}

static void
bring_into_view(struct daemon *d, int v, const double p[3])
{
	struct loop *L = d->loop;
	if (v < 0 || v >= ENV_MAX_VIEWS || !d->env.view[v].used || L->adjust[v].active)
		return;
	const struct env_view *vw = &d->env.view[v];
	struct camera cam;
	view_camera_of_view(vw, &cam);
	if (!view_adjust_visible(&cam, vw->width, vw->height, p) &&
	    view_adjust_focus(&L->adjust[v], &cam, p, real_now(NULL)) > 0)
		remember_view(L, v, &cam);
	else if (L->interact.mode != INTERACT_NONE && L->interact.view == v)
		avoid_obstruction(L, v, p, L->interact.fig);
}

/* a primitive's goal from G, as its move command sets it (Table 5.2) */
static void
drive_primitive(struct loop *L, struct env_figure *f, struct interact *ia)
{
	struct behave *b = f->behave;
	if (!b)
		return;
	env_sync_solver(&L->d.env, (int)(f - L->d.env.fig));
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
		kin_com(f->model, f->state);
		double d[3] = { g.p[0] - f->state->com[0], g.p[1] - f->state->com[1],
				g.p[2] - f->state->com[2] };
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
	}
}

/* G (or the joint) moved: what the mode moves follows, at once */
static void
apply_mode(struct loop *L)
{
	struct interact *ia = &L->interact;
	struct env *env = &L->d.env;
	if (ia->mode == INTERACT_NONE || ia->fig < 0)
		return;
	struct env_figure *f = &env->fig[ia->fig];
	switch (ia->mode) {
	case INTERACT_FIGURE:
		interact_target(ia, &f->state->root_xf);
		kin_update(f->model, f->state);
		break;
	case INTERACT_JOINT:
		f->state->q[ia->moved_dof] = ia->moved_value;
		kin_update(f->model, f->state);
		break;
	case INTERACT_PRIMITIVE:
		drive_primitive(L, f, ia);
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
	L->scene.dirty = 1;
}

static void
mode_moved(struct daemon *d)
{
	apply_mode(d->loop);
}

/* an input event to the interactive mode; its target applied at once */
static void
drive_mode(struct loop *L, const struct input_event_rec *e, long px, long py)
{
	struct interact *ia = &L->interact;
	if (ia->mode == INTERACT_NONE)
		return;
	struct env *env = &L->d.env;
	const struct env_view *vw = ia->view >= 0 ? &env->view[ia->view] : NULL;
	struct env_figure *f = ia->fig >= 0 ? &env->fig[ia->fig] : NULL;
	struct env_constraint *con = ia->mode == INTERACT_DRAG && ia->con >= 0 ? &env->con[ia->con]
									       : NULL;
	if (!vw || !vw->used || !f || f->gen != ia->tag ||
	    (ia->mode == INTERACT_DRAG && (!con || con->gen != ia->con_tag))) {
		interact_end(ia); /* its view, figure or constraint went away */
		return;
	}
	if (e->kind == INPUT_KEY && e->code == KEY_C && e->value == 1 && take_back_view(L, ia->view))
		return;
	struct camera cam;
	view_camera_of_view(vw, &cam);
	enum interact_mode mode = ia->mode;
	int r = interact_input(ia, e, px, py, &cam, vw->width, vw->height);
	if (r)
		L->scene.dirty = 1;
	maybe_adjust_view(L, &cam);
	/* a new drag: is the object still in sight (§3.7.1)? */
	if ((mode == INTERACT_FIGURE || mode == INTERACT_DRAG) && ia->mode == mode &&
	    e->kind == INPUT_BUTTON && e->value == 1 &&
	    (e->code == BTN_LEFT || e->code == BTN_MIDDLE || e->code == BTN_RIGHT))
		avoid_obstruction(L, ia->view, ia->m.g.p, ia->fig);
	if (r & INTERACT_ENDED) {
		if (mode == INTERACT_DRAG)
			end_drag(L);
		return;
	}
	if (mode == INTERACT_DRAG && (r & INTERACT_RELEASED)) {
		/* §4.6.2: the orientation offset resets when a button comes up */
		struct xform eff;
		xform_mul(&f->state->site_xf[con->def.effector_site], &con->def.effector_offset, &eff);
		interact_reset_orientation(ia, &eff);
		r |= INTERACT_MOVED;
	}
	if (!(r & INTERACT_MOVED))
		return;
	/* beyond the dissertation: a dragged G near the edge of the picture, the view follows */
	if ((mode == INTERACT_FIGURE || mode == INTERACT_DRAG) && !L->adjust[ia->view].active &&
	    !view_adjust_inside(&cam, vw->width, vw->height, ia->m.g.p, LOOP_EDGE_MARGIN) &&
	    view_adjust_focus(&L->adjust[ia->view], &cam, ia->m.g.p, real_now(NULL)) > 0)
		remember_view(L, ia->view, &cam);
	apply_mode(L);
}

/* the input queued since the last frame, taken in order */
static void
take_input(struct loop *L)
{
	struct input_event_rec e;
	while (input_queue_pop(&L->input, &e)) {
		long px = 0, py = 0;
		struct motion_scale *m = e.device < INPUT_DEVS_MAX ? &L->pointer[e.device]
								   : &L->pointer[INPUT_DEVS_MAX];
		if (e.kind == INPUT_ADDED && e.device < INPUT_DEVS_MAX)
			motion_scale_init(m, L->devs.place[e.device].info.dpi, L->pointer_gain);
		else if (e.kind == INPUT_MOTION)
			motion_scale_apply(m, e.x, e.y, &px, &py);
		if (escape_chord_feed(&L->escape, &e) && L->devs.grab) {
			input_devs_set_grab(&L->devs, 0);
			fprintf(stderr, "postured: Ctrl+Alt+Backspace: the kiosk grab given up "
					"('set input grab=yes' takes it again)\n");
		}
		events_input(&L->events, &e, px, py);
		track_pointer(L, &e, px, py);
		if (!drive_view(L, &e, px, py))
			drive_mode(L, &e, px, py);
	}
}

/* ---- frames ------------------------------------------------------------------ */

static int
has_work(const struct env *e, int fig)
{
	if (e->fig[fig].behave)
		return 1;
	for (int i = 0; i < ENV_MAX_CONSTRAINTS; i++)
		if (e->con[i].gen && e->con[i].fig == fig && e->con[i].def.enabled)
			return 1;
	return 0;
}

/* one frame: solve every figure with work within the budget */
static int
frame(struct loop *L, const struct ik_clock *clock, uint64_t budget_us, int *changed)
{
	struct env *e = &L->d.env;
	int busy = 0;
	*changed = 0;
	for (int i = 0; i < ENV_MAX_FIGURES; i++)
		busy += e->fig[i].gen && has_work(e, i);
	L->d.stats.ik_us = 0;
	L->d.stats.iterations = 0;
	L->d.stats.time_cut = L->d.stats.step_cut = 0;
	L->d.stats.budget_us = budget_us;
	for (int i = 0; i < ENV_MAX_FIGURES && busy; i++) {
		struct env_figure *f = &e->fig[i];
		if (!f->gen || !has_work(e, i))
			continue;
		env_sync_solver(e, i);
		uint64_t before = state_hash(f->model, f->state);
		struct ik_options opt = ik_default_options();
		opt.budget_us = budget_us / (uint64_t)busy; /* an equal share each */
		if (f->behave) /* hands and feet holding on to objects go where the objects are */
			attach_before_solve(e, i);
		uint64_t t0 = real_now(NULL);
		struct ik_result r = f->behave ? behave_frame(f->behave, f->model, f->state, f->ik, &opt,
							      clock)
					       : ik_solve(f->ik, f->model, f->state, &opt, clock);
		double us = (double)(real_now(NULL) - t0);
		L->d.stats.ik_us += us;
		L->d.stats.iterations += r.iterations;
		L->d.stats.time_cut |= r.status == IK_TIME_LIMIT;
		L->d.stats.step_cut |= r.stepped;
		*changed |= state_hash(f->model, f->state) != before;
		if (f->behave) /* objects its hands grabbed follow them */
			*changed |= attach_after_solve(e, i);
		events_telemetry(&L->events, i, &r, opt.budget_us, us);
		if (f->behave)
			events_stability(&L->events, i);
	}
	L->d.stats.frame++;
	return 0;
}

static int
settle_frame(struct daemon *d, int *changed)
{
	struct loop *L = d->loop;
	struct ik_clock clock = { virtual_now, L };
	take_input(L);
	view_frames(L, real_now(NULL)); /* a snap is eased over real time, settle or not */
	int rc = frame(L, &clock, L->period_us, changed);
	events_posture_changes(&L->events);
	return rc;
}

static int
subscribe(struct daemon *d, int client, unsigned kinds, int on)
{
	struct loop *L = d->loop;
	if (client < 0 || client >= SERVER_MAX_CLIENTS || L->srv.c[client].fd < 0)
		return -1;
	if (on)
		L->srv.c[client].subs |= kinds;
	else
		L->srv.c[client].subs &= ~kinds;
	return 0;
}

static int
render_view(struct daemon *d, int v, const struct frame **dest, char *err, size_t errlen)
{
	struct loop *L = d->loop;
	return scene_draw(&L->scene, d, v, dest, err, errlen);
}

/* ---- requests ---------------------------------------------------------------- */

static void
reply(struct loop *L, int i, const char *json)
{
	size_t n = strlen(json);
	char *line = malloc(n + 1);
	if (!line)
		return;
	memcpy(line, json, n);
	line[n] = '\n';
	if (server_queue(&L->srv, i, line, n + 1) < 0) {
		fprintf(stderr, "postured: client %d does not read its replies: dropped\n", i);
		server_drop(&L->srv, i);
	}
	free(line);
}

static void
error_reply(struct loop *L, int i, const char *code, const char *msg)
{
	char buf[256];
	snprintf(buf, sizeof buf, "{\"ok\":false,\"error\":{\"code\":\"%s\",\"message\":\"%s\"}}", code,
		 msg);
	reply(L, i, buf);
}

/* runs one request line of client i */
static void
request(struct loop *L, int i, const char *line, size_t len)
{
	struct client *c = &L->srv.c[i];
	if (!c->authed) { /* TCP: the first line must carry the token */
		size_t tl = strlen(L->srv.token);
		int good = len == 5 + tl && !memcmp(line, "auth ", 5) && !memcmp(line + 5, L->srv.token, tl);
		if (good) {
			c->authed = 1;
			reply(L, i, "{\"ok\":true,\"result\":{}}");
		} else {
			error_reply(L, i, "denied", "the first line must be: auth TOKEN");
			c->closing = 1;
		}
		return;
	}
	/* a command sees every input that came before it (a mode moved by them, say) */
	take_input(L);
	/* what the solver did since the last reply is made durable first */
	if (journal_postures(&L->j, &L->d) < 0)
		fprintf(stderr, "postured: journal: %s\n", strerror(errno));
	struct cmd_outcome out;
	cmd_run(&L->d, i, line, len, &out);
	/* a change is replayed from its command; frames a command ran (settle)
	 * are recorded as the postures they reached */
	int rc = out.mutated ? journal_command(&L->j, &L->d, line, len)
			     : journal_postures(&L->j, &L->d);
	if (rc < 0)
		fprintf(stderr, "postured: journal: %s\n", strerror(errno));
	if (out.mutated)
		L->scene.dirty = 1;
	if (out.reply) { /* the message line under the pictures */
		snprintf(L->d.message, sizeof L->d.message, "> %.*s  %s", (int)(len > 100 ? 100 : len),
			 line, out.ok ? "ok" : "refused");
		events_message(&L->events);
	}
	events_posture_changes(&L->events);
	if (out.reply && out.json)
		reply(L, i, out.json);
	free(out.json);
	if (out.close && L->srv.c[i].fd >= 0)
		L->srv.c[i].closing = 1;
}

static void
client_input(struct loop *L, int i)
{
	long got = server_read(&L->srv, i);
	if (got <= 0) { /* the peer left (a half line is simply dropped) */
		server_drop(&L->srv, i);
		return;
	}
	struct client *c = &L->srv.c[i];
	size_t len, used;
	const char *line;
	while (c->fd >= 0 && !c->closing && (line = server_line(c, &len, &used))) {
		request(L, i, line, len);
		if (c->fd >= 0)
			server_consume(c, used);
	}
	if (c->fd >= 0 && !c->closing && c->in_len == SERVER_IN_MAX) {
		error_reply(L, i, "too-long", "line longer than 65536 bytes");
		c->closing = 1;
	}
}

/* ---- the loop ---------------------------------------------------------------- */

/* a first start: the init file's commands, journaled like a client's */
static int
run_init(struct loop *L, const char *path)
{
	FILE *f = fopen(path, "r");
	if (!f) {
		fprintf(stderr, "postured: %s: %s\n", path, strerror(errno));
		return -1;
	}
	char line[4096];
	int n = 0, rc = 0;
	while (rc == 0 && fgets(line, sizeof line, f)) {
		n++;
		size_t len = strcspn(line, "\r\n");
		struct cmd_outcome out;
		cmd_run(&L->d, -1, line, len, &out);
		if (out.reply && !out.ok) {
			fprintf(stderr, "postured: %s:%d: %s\n", path, n, out.json ? out.json : "");
			rc = -1;
		} else if (out.mutated && journal_command(&L->j, &L->d, line, len) < 0) {
			rc = -1;
		}
		free(out.json);
	}
	fclose(f);
	return rc == 0 ? journal_sync(&L->j) : -1;
}

static int
open_signals(void)
{
	sigset_t set;
	sigemptyset(&set);
	sigaddset(&set, SIGTERM);
	sigaddset(&set, SIGINT);
	signal(SIGPIPE, SIG_IGN);
	if (sigprocmask(SIG_BLOCK, &set, NULL) < 0)
		return -1;
	return signalfd(-1, &set, SFD_NONBLOCK | SFD_CLOEXEC);
}

static void
live_frame(struct loop *L)
{
	struct ik_clock clock = { real_now, NULL };
	int changed;
	uint64_t draw = (uint64_t)L->d.stats.draw_us;
	uint64_t budget = L->period_us > draw + 500 ? L->period_us - draw - 500 : L->period_us / 4;
	take_input(L);
	view_frames(L, real_now(NULL));
	frame(L, &clock, budget, &changed);
	uint64_t now = real_now(NULL);
	L->scene.dirty |= changed;
	events_posture_changes(&L->events);
	uint64_t t0 = real_now(NULL);
	if (scene_publish(&L->scene, &L->d, &L->events, now)) {
		/* drawing's share of the frame, smoothed: the solver gets the rest (§4.7.2) */
		double us = (double)(real_now(NULL) - t0);
		L->d.stats.draw_us = L->d.stats.draw_us ? 0.8 * L->d.stats.draw_us + 0.2 * us : us;
	}
	L->fps_frames++;
	if (now - L->fps_t0 >= 1000000) {
		L->d.stats.fps = (double)L->fps_frames * 1e6 / (double)(now - L->fps_t0);
		L->fps_t0 = now;
		L->fps_frames = 0;
	}
	if (L->watchdog_us && now - L->watchdog_last >= L->watchdog_us / 2) {
		notify_send("WATCHDOG=1");
		L->watchdog_last = now;
	}
}

/* the devices opened since the last call, announced */
static void
announce_devices(struct loop *L)
{
	for (int i; (i = input_devs_next_new(&L->devs)) >= 0;) {
		const struct input_devs_place *p = &L->devs.place[i];
		fprintf(stderr, "postured: input %d: %s (%s, %s)\n", i, p->info.path, p->info.name,
			p->be->name);
		/* a panel's map names its dials in events, unless --panel gave one */
		if (!L->d.panel && p->be == &input_backend_can && ((const struct can_dev *)p->dev)->map) {
			L->panel = *((const struct can_dev *)p->dev)->map;
			L->d.panel = &L->panel;
		}
	}
}

/* the --input specs (auto when none): each device opened announced, the rest logged */
static int
open_devices(struct loop *L, const struct loop_config *cfg, char *err, size_t errlen)
{
	static const char *const fallback[] = { "auto" };
	const char *const *spec = cfg->ninputs ? cfg->inputs : fallback;
	int nspec = cfg->ninputs ? cfg->ninputs : 1;
	L->pointer_gain = cfg->pointer_gain > 0 ? cfg->pointer_gain : 1;
	L->d.pointer_gain = L->pointer_gain;
	for (int i = 0; i <= INPUT_DEVS_MAX; i++)
		motion_scale_init(&L->pointer[i], INPUT_DEV_DPI_DEFAULT, L->pointer_gain);
	input_devs_init(&L->devs, input_backends, input_backends_count, cfg->grab, &L->input);
	L->d.devices = &L->devs;
	for (int k = 0; k < nspec; k++)
		if (input_devs_open(&L->devs, spec[k], real_now(NULL), err, errlen) < 0)
			return -1;
	announce_devices(L);
	for (int k = 0; k < L->devs.nskip; k++)
		fprintf(stderr, "postured: input %s skipped: %s\n", L->devs.skip[k].what,
			L->devs.skip[k].why);
	/* hot-plug: only when something is read directly; a monitor refused is said once */
	L->hotplug.fd = -1;
	const char *source = cfg->hotplug ? cfg->hotplug : "udev";
	if (L->devs.nspec && strcmp(source, "none") &&
	    !(nspec == 1 && !strcmp(spec[0], "none")) &&
	    hotplug_open(&L->hotplug, source, err, errlen) < 0)
		fprintf(stderr, "postured: no hot-plug (devices are read as they were at start): %s\n",
			err);
	return 0;
}

/* something arrived: the specs opened again, what is new announced */
static void
devices_arrived(struct loop *L)
{
	if (hotplug_read(&L->hotplug) <= 0)
		return;
	if (input_devs_rescan(&L->devs, real_now(NULL)) > 0)
		announce_devices(L);
}

static int
set_input(struct daemon *d, int grab, double gain)
{
	struct loop *L = d->loop;
	int rc = 0;
	if (grab >= 0)
		rc = input_devs_set_grab(&L->devs, grab);
	if (gain > 0) {
		L->pointer_gain = gain;
		for (int i = 0; i <= INPUT_DEVS_MAX; i++)
			motion_scale_init(&L->pointer[i],
					  i < INPUT_DEVS_MAX && L->devs.place[i].be ? L->devs.place[i].info.dpi
										    : INPUT_DEV_DPI_DEFAULT,
					  gain);
	}
	d->pointer_gain = L->pointer_gain;
	return rc;
}

int
loop_run(const struct loop_config *cfg)
{
	struct loop *L = calloc(1, sizeof *L);
	char err[512];
	if (!L)
		return 1;
	env_init(&L->d.env);
	snprintf(L->d.state_dir, sizeof L->d.state_dir, "%s", cfg->state_dir);
	snprintf(L->d.library_dir, sizeof L->d.library_dir, "%s", cfg->library_dir ? cfg->library_dir : "");
	L->d.loop = L;
	L->d.run_frame = settle_frame;
	L->d.subscribe = subscribe;
	L->d.render_view = render_view;
	L->d.set_input = set_input;
	interact_init(&L->interact);
	L->d.interact = &L->interact;
	L->d.bring_into_view = bring_into_view;
	L->d.mode_moved = mode_moved;
	struct viewctl_gains gains = viewctl_default_gains();
	for (int v = 0; v < ENV_MAX_VIEWS; v++)
		viewctl_init(&L->viewctl[v], &gains);
	L->pointer_view = -1;
	L->hotplug.fd = -1;
	input_queue_init(&L->input);
	L->d.input = &L->input;
	L->d.now_us = clock_us;
	scene_init(&L->scene, cfg->frames_dir);
	L->period_us = (uint64_t)(1e6 / cfg->fps);
	L->srv.unix_fd = L->srv.tcp_fd = -1;
	int status = 1;
	if (events_init(&L->events, &L->srv, &L->d) < 0)
		goto out;
	if (cfg->panel_map) {
		if (can_map_read(cfg->panel_map, &L->panel, err, sizeof err) < 0) {
			fprintf(stderr, "postured: panel map: %s\n", err);
			goto out;
		}
		L->d.panel = &L->panel;
	}
	if (open_devices(L, cfg, err, sizeof err) < 0) {
		fprintf(stderr, "postured: %s\n", err);
		goto out;
	}
	if (cfg->fb_device && !(L->scene.fb = sink_fb_open(cfg->fb_device, err, sizeof err))) {
		fprintf(stderr, "postured: framebuffer %s: %s\n", cfg->fb_device, err);
		goto out;
	}
	if (journal_open(&L->j, &L->d, err, sizeof err) < 0) {
		fprintf(stderr, "postured: cannot recover the state: %s\n", err);
		goto out;
	}
	fprintf(stderr, "postured: state recovered: %d figures, journal at record %" PRIu64 "\n",
		env_count(&L->d.env), L->j.seq);
	if (cfg->init_file && env_count(&L->d.env) == 0 && L->j.seq == 0 && run_init(L, cfg->init_file) < 0)
		goto out;
	L->synced_seq = L->j.seq;
	if (server_open(&L->srv, cfg->socket_path, cfg->tcp_port, cfg->token, err, sizeof err) < 0) {
		fprintf(stderr, "postured: %s\n", err);
		goto out;
	}
	if ((L->sig_fd = open_signals()) < 0) {
		fprintf(stderr, "postured: signals: %s\n", strerror(errno));
		goto out;
	}
	L->watchdog_us = notify_watchdog_usec();
	L->fps_t0 = real_now(NULL);
	notify_send("READY=1");
	fprintf(stderr, "postured: listening on %s%s\n", cfg->socket_path,
		cfg->tcp_port > 0 ? " and 127.0.0.1 (token required)" : "");
	static struct pollfd fds[SERVER_MAX_CLIENTS + 4 + INPUT_DEVS_POLL_MAX];
	static int owner[SERVER_MAX_CLIENTS + 4 + INPUT_DEVS_POLL_MAX];
	uint64_t next = real_now(NULL) + L->period_us;
	while (!L->stop) {
		int n = server_pollfds(&L->srv, fds, owner);
		fds[n] = (struct pollfd){ .fd = L->sig_fd, .events = POLLIN };
		owner[n++] = -3;
		if (hotplug_fd(&L->hotplug) >= 0) {
			fds[n] = (struct pollfd){ .fd = hotplug_fd(&L->hotplug), .events = POLLIN };
			owner[n++] = -4;
		}
		/* the devices: owner -100 - their tag */
		int tags[INPUT_DEVS_POLL_MAX];
		int nd = input_devs_pollfds(&L->devs, fds + n, tags, INPUT_DEVS_POLL_MAX);
		for (int k = 0; k < nd; k++)
			owner[n++] = -100 - tags[k];
		uint64_t now = real_now(NULL);
		int timeout = now >= next ? 0 : (int)((next - now + 999) / 1000);
		if (poll(fds, (nfds_t)n, timeout) < 0 && errno != EINTR) {
			fprintf(stderr, "postured: poll: %s\n", strerror(errno));
			break;
		}
		for (int k = 0; k < n; k++) {
			if (!fds[k].revents)
				continue;
			if (owner[k] <= -100)
				input_devs_ready(&L->devs, -100 - owner[k], real_now(NULL), &L->input);
			else if (owner[k] == -3)
				L->stop = 1;
			else if (owner[k] == -4)
				devices_arrived(L);
			else if (owner[k] < 0)
				server_accept(&L->srv, fds[k].fd);
			else if (L->srv.c[owner[k]].fd == fds[k].fd &&
				 (fds[k].revents & (POLLIN | POLLHUP | POLLERR)))
				client_input(L, owner[k]);
		}
		if (real_now(NULL) >= next) {
			live_frame(L);
			next += L->period_us;
			if (next < real_now(NULL)) /* fell behind: do not try to catch up */
				next = real_now(NULL) + L->period_us;
		}
		/* replies leave only after what they acknowledge is on disk */
		if (L->j.seq != L->synced_seq) {
			if (journal_sync(&L->j) < 0)
				fprintf(stderr, "postured: journal sync: %s\n", strerror(errno));
			L->synced_seq = L->j.seq;
			if (journal_snapshot(&L->j, &L->d, 0) < 0)
				fprintf(stderr, "postured: snapshot: %s\n", strerror(errno));
		}
		L->d.stats.clients = L->srv.nclients;
		for (int i = 0; i < SERVER_MAX_CLIENTS; i++)
			if (L->srv.c[i].fd >= 0)
				server_flush(&L->srv, i);
	}
	fprintf(stderr, "postured: stopping\n");
	notify_send("STOPPING=1");
	/* what the solver did last, then a snapshot: a clean start next time */
	journal_postures(&L->j, &L->d);
	journal_sync(&L->j);
	if (journal_snapshot(&L->j, &L->d, 1) < 0)
		fprintf(stderr, "postured: final snapshot: %s\n", strerror(errno));
	status = 0;
out:
	server_close(&L->srv);
	journal_close(&L->j);
	env_clear(&L->d.env);
	daemon_checkpoints_clear(&L->d.undo);
	daemon_checkpoints_clear(&L->d.redo);
	daemon_picks_free(&L->d);
	input_devs_close_all(&L->devs, real_now(NULL), &L->input);
	hotplug_close(&L->hotplug);
	events_free(&L->events);
	scene_free(&L->scene);
	free(L);
	return status;
}
