/* loop.c - the frame loop: the only file that sees compute and I/O together */
#include "daemon/loop.h"

#include <errno.h>
#include <inttypes.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/signalfd.h>
#include <time.h>
#include <unistd.h>

#include "pose/attach.h"
#include "daemon/cmd.h"
#include "daemon/jbuf.h"
#include "figure/kin.h"
#include "daemon/notify.h"
#include "draw/render.h"
#include "draw/sink.h"
#include "draw/view.h"

#define IK_LIMITS_REPORTED 256 /* dofs listed as resting on a limit */

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
	struct jbuf ev; /* events are written here: no allocation in a frame */
	uint64_t told_hash[ENV_MAX_FIGURES]; /* postures as the last posture events told them */
	uint32_t told_gen[ENV_MAX_FIGURES];
	struct scene {
		struct render *r; /* made when first needed */
		int failed;       /* OSMesa could not start: no pictures */
		struct drawlist *dl;
		int mesh_base[ENV_MAX_FIGURES];
		uint32_t mesh_gen[ENV_MAX_FIGURES];
		struct sink *png[ENV_MAX_VIEWS];
		char png_name[ENV_MAX_VIEWS][MODEL_NAME_MAX];
		struct sink *fb;
		struct sink_png_encoder enc; /* frame events */
		uint64_t last_png_us, last_event_us;
		int dirty;
	} scene;
	const char *frames_dir;
	int limit_dofs[IK_LIMITS_REPORTED];
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

/* settle's clock: every read advances it, so the time limit cuts alike on every run */
static uint64_t
virtual_now(void *ctx)
{
	struct loop *L = ctx;
	return L->virtual_us += 20;
}

/* ---- events ------------------------------------------------------------------ */

static int
has_subscribers(const struct loop *L, unsigned kind)
{
	for (int i = 0; i < SERVER_MAX_CLIENTS; i++)
		if (L->srv.c[i].fd >= 0 && (L->srv.c[i].subs & kind) && !L->srv.c[i].closing)
			return 1;
	return 0;
}

/* queues the event in L->ev (a complete JSON object) to every subscriber of kind */
static void
send_event(struct loop *L, unsigned kind)
{
	if (L->ev.overflow) {
		fprintf(stderr, "postured: an event did not fit its buffer; not sent\n");
		return;
	}
	jbuf_raw(&L->ev, "\n");
	for (int i = 0; i < SERVER_MAX_CLIENTS; i++) {
		struct client *c = &L->srv.c[i];
		if (c->fd < 0 || !(c->subs & kind) || c->closing)
			continue;
		if (server_queue(&L->srv, i, L->ev.buf, L->ev.len) < 0) {
			fprintf(stderr, "postured: client %d does not read its events: dropped\n", i);
			server_drop(&L->srv, i);
		}
	}
}

/* starts event kind in L->ev: {"event":kind,"frame":N[,"figure":name] */
static struct jbuf *
event_begin(struct loop *L, const char *kind, const char *figure)
{
	struct jbuf *j = &L->ev;
	jbuf_reset(j);
	jbuf_raw(j, "{\"event\":");
	jbuf_str(j, kind);
	jbuf_key(j, "frame", 0);
	jbuf_int(j, (long long)L->d.stats.frame);
	if (figure) {
		jbuf_key(j, "figure", 0);
		jbuf_str(j, figure);
	}
	return j;
}

static void
posture_event(struct loop *L, int fig)
{
	if (!has_subscribers(L, SUB_POSTURE))
		return;
	const struct env_figure *f = &L->d.env.fig[fig];
	struct jbuf *j = event_begin(L, "posture", f->name);
	jbuf_key(j, "q", 0);
	jbuf_vec(j, f->state->q, f->model->ndof);
	jbuf_key(j, "com", 0);
	jbuf_vec(j, f->state->com, 3);
	jbuf_raw(j, "}");
	send_event(L, SUB_POSTURE);
}

/* a posture event for every figure that changed since the last one, whoever moved it */
static void
posture_changes(struct loop *L)
{
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		const struct env_figure *f = &L->d.env.fig[i];
		if (!f->gen)
			continue;
		uint64_t h = state_hash(f->model, f->state);
		if (L->told_gen[i] == f->gen && L->told_hash[i] == h)
			continue;
		L->told_gen[i] = f->gen;
		L->told_hash[i] = h;
		posture_event(L, i);
	}
}

static void
message_event(struct loop *L)
{
	if (!has_subscribers(L, SUB_MESSAGE))
		return;
	struct jbuf *j = event_begin(L, "message", NULL);
	jbuf_key(j, "text", 0);
	jbuf_str(j, L->d.message);
	jbuf_raw(j, "}");
	send_event(L, SUB_MESSAGE);
}

/* why a goal is (not) reached: the solver's view of one figure's frame */
static void
telemetry_event(struct loop *L, int fig, const struct ik_result *r, uint64_t budget, double us)
{
	if (!has_subscribers(L, SUB_TELEMETRY))
		return;
	struct env *e = &L->d.env;
	const struct env_figure *f = &e->fig[fig];
	const struct model *m = f->model;
	struct jbuf *j = event_begin(L, "telemetry", f->name);
	jbuf_key(j, "budget_us", 0);
	jbuf_int(j, (long long)budget);
	jbuf_key(j, "used_us", 0);
	jbuf_num(j, us);
	jbuf_key(j, "iterations", 0);
	jbuf_int(j, r->iterations);
	jbuf_key(j, "status", 0);
	jbuf_str(j, ik_status_to_str(r->status));
	jbuf_key(j, "time_limit_cut", 0);
	jbuf_bool(j, r->status == IK_TIME_LIMIT);
	jbuf_key(j, "step_factor_cut", 0);
	jbuf_bool(j, r->stepped);
	jbuf_key(j, "balance_rounds", 0);
	jbuf_int(j, r->balance_rounds);
	jbuf_key(j, "energy", 0);
	jbuf_num(j, r->f_end);
	jbuf_key(j, "constraints", 0);
	jbuf_raw(j, "[");
	int first = 1;
	for (int i = 0; i < ENV_MAX_CONSTRAINTS; i++) {
		const struct env_constraint *c = &e->con[i];
		if (!c->gen || c->fig != fig)
			continue;
		double pe, oe;
		ik_constraint_error(f->ik, m, f->state, env_solver_index(e, i), &pe, &oe);
		jbuf_raw(j, first ? "{" : ",{");
		first = 0;
		jbuf_key(j, "name", 1);
		jbuf_str(j, c->name);
		jbuf_key(j, "enabled", 0);
		jbuf_bool(j, c->def.enabled);
		jbuf_key(j, "pos_error", 0);
		jbuf_num(j, pe);
		jbuf_key(j, "ori_error", 0);
		jbuf_num(j, oe);
		jbuf_raw(j, "}");
	}
	jbuf_raw(j, "]");
	jbuf_key(j, "active_limits", 0);
	jbuf_raw(j, "[");
	int nlim = ik_active_limits(f->ik, m, f->state, L->limit_dofs, IK_LIMITS_REPORTED);
	for (int k = 0; k < nlim; k++) {
		int d = L->limit_dofs[k];
		jbuf_raw(j, k ? ",{" : "{");
		jbuf_key(j, "joint", 1);
		jbuf_str(j, m->jnt_name[m->dof_jnt[d]]);
		jbuf_key(j, "dof", 0);
		jbuf_int(j, d - m->jnt_dof0[m->dof_jnt[d]]);
		jbuf_key(j, "at", 0);
		jbuf_str(j, f->state->q[d] <= m->dof_lo[d] ? "lower" : "upper");
		jbuf_raw(j, "}");
	}
	jbuf_raw(j, "]}");
	send_event(L, SUB_TELEMETRY);
}

/* the balance of a behaving figure as it stands after its frame */
static void
balance_fields(struct jbuf *j, const struct behave *b)
{
	jbuf_key(j, "margin", 0);
	jbuf_num(j, b->bal.margin);
	jbuf_key(j, "threshold", 0);
	jbuf_num(j, b->p.stability_threshold);
	jbuf_key(j, "com", 0);
	jbuf_vec(j, b->bal.point, 2);
}

/*
 * Stability as data: every frame the support polygon, the balance point
 * the behaviours hold, the centre of mass on the floor, its parameters and
 * the margin; and an alert when the margin crosses the figure's threshold.
 */
static void
stability_events(struct loop *L, int fig)
{
	const struct env_figure *f = &L->d.env.fig[fig];
	const struct behave *b = f->behave;
	if (b->stability_changed && has_subscribers(L, SUB_ALERT)) {
		struct jbuf *j = event_begin(L, "alert", f->name);
		jbuf_key(j, "stability", 0);
		jbuf_str(j, b->stability_low ? "low" : "ok");
		balance_fields(j, b);
		jbuf_raw(j, "}");
		send_event(L, SUB_ALERT);
	}
	if (!has_subscribers(L, SUB_STABILITY))
		return;
	struct jbuf *j = event_begin(L, "stability", f->name);
	balance_fields(j, b);
	jbuf_key(j, "low", 0);
	jbuf_bool(j, b->stability_low);
	jbuf_key(j, "balance_point", 0);
	jbuf_vec(j, b->bal_point, 2);
	jbuf_key(j, "x", 0);
	jbuf_num(j, b->bal.x);
	jbuf_key(j, "z", 0);
	jbuf_num(j, b->bal.z);
	jbuf_key(j, "weight_left", 0);
	jbuf_num(j, b->bal.weight_l);
	jbuf_key(j, "stepping", 0);
	jbuf_bool(j, b->step.active);
	jbuf_key(j, "polygon", 0);
	jbuf_raw(j, "[");
	for (int k = 0; k < b->bal.npoly; k++) {
		if (k)
			jbuf_raw(j, ",");
		jbuf_vec(j, b->bal.poly[k], 2);
	}
	jbuf_raw(j, "]}");
	send_event(L, SUB_STABILITY);
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
		telemetry_event(L, i, &r, opt.budget_us, us);
		if (f->behave)
			stability_events(L, i);
	}
	L->d.stats.frame++;
	return 0;
}

static int
settle_frame(struct daemon *d, int *changed)
{
	struct loop *L = d->loop;
	struct ik_clock clock = { virtual_now, L };
	int rc = frame(L, &clock, L->period_us, changed);
	posture_changes(L);
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

/* ---- pictures ---------------------------------------------------------------- */

#define PNG_PERIOD_US 100000 /* frame files and frame events: at most 10 a second */

static int
scene_ready(struct loop *L, char *err, size_t errlen)
{
	struct scene *sc = &L->scene;
	if (sc->r)
		return 0;
	if (sc->failed) {
		snprintf(err, errlen, "the renderer could not start");
		return -1;
	}
	struct render_def rd = render_default_def();
	rd.max_w = VIEW_MAX_W;
	rd.max_h = VIEW_MAX_H;
	sc->r = render_make(&rd, err, errlen);
	sc->dl = sc->r ? view_drawlist_make() : NULL;
	if (!sc->r || !sc->dl) {
		fprintf(stderr, "postured: no pictures: %s\n", err);
		render_free(sc->r);
		sc->r = NULL;
		sc->failed = 1;
		return -1;
	}
	return 0;
}

/* builds and renders view v into the renderer's buffer */
static int
scene_draw(struct loop *L, int v, const struct frame **dest, char *err, size_t errlen)
{
	struct scene *sc = &L->scene;
	struct env *e = &L->d.env;
	const struct env_view *vw = &e->view[v];
	if (scene_ready(L, err, errlen) < 0)
		return -1;
	struct camera cam;
	view_camera_default(&cam);
	view_camera_aim(&cam, vw->eye, vw->target);
	view_begin(sc->dl, &cam, vw->width, vw->height);
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		struct env_figure *f = &e->fig[i];
		if (!f->gen)
			continue;
		if (sc->mesh_gen[i] != f->gen) { /* a figure new to the renderer */
			int base = render_add_model(sc->r, f->model, err, errlen);
			if (base < 0)
				fprintf(stderr, "postured: figure %s drawn without its meshes: %s\n", f->name, err);
			sc->mesh_base[i] = base < 0 ? 0 : base;
			sc->mesh_gen[i] = f->gen;
		}
		view_add_figure(sc->dl, f->model, f->state, sc->mesh_base[i]);
		if (!vw->icons)
			continue;
		if (f->is_human)
			view_add_balance(sc->dl, f->model, f->state);
		env_sync_solver(e, i);
		view_add_goals(sc->dl, f->ik, f->model, f->state);
	}
	char status[200];
	snprintf(status, sizeof status, "%s   frame %llu   %.0f fps   solver %.0f us   drawing %.1f ms",
		 vw->name, (unsigned long long)L->d.stats.frame, L->d.stats.fps, L->d.stats.ik_us,
		 L->d.stats.draw_us / 1000);
	view_add_status(sc->dl, status, L->d.message, 0);
	static struct frame frame;
	if (render_frame(sc->r, sc->dl, L->d.stats.frame, &frame) < 0) {
		snprintf(err, errlen, "render_frame failed");
		return -1;
	}
	frame.seq = L->d.stats.frame;
	*dest = &frame;
	return 0;
}

static int
render_view(struct daemon *d, int v, const struct frame **dest, char *err, size_t errlen)
{
	return scene_draw(d->loop, v, dest, err, errlen);
}

static void
frame_event(struct loop *L, const char *view, const struct frame *f)
{
	char err[160];
	struct scene *sc = &L->scene;
	if (sink_png_encode(&sc->enc, f, err, sizeof err) < 0)
		return;
	struct jbuf *j = event_begin(L, "frame", NULL);
	jbuf_key(j, "view", 0);
	jbuf_str(j, view);
	jbuf_key(j, "width", 0);
	jbuf_int(j, f->width);
	jbuf_key(j, "height", 0);
	jbuf_int(j, f->height);
	jbuf_key(j, "png", 0);
	jbuf_base64(j, sc->enc.data, sc->enc.len);
	jbuf_raw(j, "}");
	send_event(L, SUB_FRAME);
}

/* the views' pictures after a frame that changed something */
static void
scene_publish(struct loop *L, uint64_t now)
{
	struct scene *sc = &L->scene;
	struct env *e = &L->d.env;
	int files = L->frames_dir && now - sc->last_png_us >= PNG_PERIOD_US;
	int events = has_subscribers(L, SUB_FRAME) && now - sc->last_event_us >= PNG_PERIOD_US;
	if (!sc->dirty || (!files && !events && !sc->fb) || sc->failed)
		return;
	uint64_t t0 = real_now(NULL);
	int first = 1;
	for (int v = 0; v < ENV_MAX_VIEWS; v++) {
		const struct env_view *vw = &e->view[v];
		const struct frame *f;
		char err[256];
		if (!vw->used || scene_draw(L, v, &f, err, sizeof err) < 0)
			continue;
		if (first && sc->fb && sink_write(sc->fb, f, err, sizeof err) < 0)
			fprintf(stderr, "postured: framebuffer: %s\n", err);
		first = 0;
		if (files) {
			if (!sc->png[v] || strcmp(sc->png_name[v], vw->name)) {
				char path[4200];
				sink_close(sc->png[v]);
				snprintf(path, sizeof path, "%s/%s.png", L->frames_dir, vw->name);
				sc->png[v] = sink_png_latest(path, err, sizeof err);
				snprintf(sc->png_name[v], sizeof sc->png_name[v], "%s", vw->name);
			}
			if (sc->png[v] && sink_write(sc->png[v], f, err, sizeof err) < 0)
				fprintf(stderr, "postured: frame file: %s\n", err);
		}
		if (events)
			frame_event(L, vw->name, f);
	}
	if (files)
		sc->last_png_us = now;
	if (events)
		sc->last_event_us = now;
	sc->dirty = 0;
	/* drawing's share of the frame, smoothed: the solver gets the rest (§4.7.2) */
	double us = (double)(real_now(NULL) - t0);
	L->d.stats.draw_us = L->d.stats.draw_us ? 0.8 * L->d.stats.draw_us + 0.2 * us : us;
}

static void
scene_free(struct scene *sc)
{
	for (int v = 0; v < ENV_MAX_VIEWS; v++)
		sink_close(sc->png[v]);
	sink_close(sc->fb);
	sink_png_encoder_free(&sc->enc);
	view_drawlist_free(sc->dl);
	render_free(sc->r);
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
		message_event(L);
	}
	posture_changes(L);
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
	frame(L, &clock, budget, &changed);
	uint64_t now = real_now(NULL);
	L->scene.dirty |= changed;
	posture_changes(L);
	scene_publish(L, now);
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
	L->frames_dir = cfg->frames_dir;
	L->scene.dirty = 1;
	sink_png_encoder_init(&L->scene.enc);
	L->period_us = (uint64_t)(1e6 / cfg->fps);
	L->srv.unix_fd = L->srv.tcp_fd = -1;
	int status = 1;
	if (jbuf_init(&L->ev, 1u << 20) < 0)
		goto out;
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
	static struct pollfd fds[SERVER_MAX_CLIENTS + 3];
	static int owner[SERVER_MAX_CLIENTS + 3];
	uint64_t next = real_now(NULL) + L->period_us;
	while (!L->stop) {
		int n = server_pollfds(&L->srv, fds, owner);
		fds[n] = (struct pollfd){ .fd = L->sig_fd, .events = POLLIN };
		owner[n++] = -3;
		uint64_t now = real_now(NULL);
		int timeout = now >= next ? 0 : (int)((next - now + 999) / 1000);
		if (poll(fds, (nfds_t)n, timeout) < 0 && errno != EINTR) {
			fprintf(stderr, "postured: poll: %s\n", strerror(errno));
			break;
		}
		for (int k = 0; k < n; k++) {
			if (!fds[k].revents)
				continue;
			if (owner[k] == -3)
				L->stop = 1;
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
			if (cfg->init_file && env_count(&L->d.env) == 0 && L->j.seq == 0 && run_init(L, cfg->init_file) < 0)
		goto out;
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
	jbuf_free(&L->ev);
	scene_free(&L->scene);
	free(L);
	return status;
}
