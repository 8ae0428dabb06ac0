/* loop.c - the frame loop: the only file that sees compute and I/O together */
#include "daemon/loop.h"

#include <errno.h>
#include <inttypes.h>
#include <jansson.h>
#include <linux/fb.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/signalfd.h>
#include <time.h>
#include <unistd.h>

#include "daemon/cmd.h"
#include "daemon/complete.h"
#include "daemon/dials.h"
#include "daemon/events.h"
#include "daemon/kiosk_route.h"
#include "daemon/modes.h"
#include "daemon/notify.h"
#include "daemon/scene.h"
#include "devices/can_dev.h"
#include "devices/escape_chord.h"
#include "devices/hotplug.h"
#include "devices/input_backends.h"
#include "devices/input_devs.h"
#include "devices/motion_scale.h"
#include "pose/attach.h"
#include "pose/behave.h"

/*
 * Idle, the loop still ticks this often: what waits on time alone (the
 * dials' step ending after they have been still, a held button's release)
 * happens at most this late, for a solve of a figure at rest each time.
 */
#define LOOP_IDLE_TICK_US 250000

struct loop {
	struct daemon d;
	struct server srv;
	struct journal j;
	struct complete complete; /* Tab at the kiosk's edit line */
	struct dials dials;       /* the dial panel's bindings at work */
	int screen_given;         /* --screen: the kiosk's screen is not the framebuffer's */
	int sig_fd;
	uint64_t period_us;
	uint64_t synced_seq;  /* the last journal record known to be on disk */
	uint64_t virtual_us;  /* the clock of settle's frames */
	uint64_t fps_t0, fps_frames;
	uint64_t watchdog_us, watchdog_last;
	/*
	 * the poll round under way: its start, and its solving so far (frames of
	 * settle included), in real time and in the loop thread's CPU time
	 */
	uint64_t round_t0, round_cpu0, round_drawn0, round_drawn_cpu0; /* round_t0 0: none yet */
	uint64_t round_solve_us, round_solve_cpu_us;
	uint64_t stall_t0, stall_max, stall_cpu_max; /* the second being measured, its longest */
	int idle; /* the last frame changed nothing: slow ticks until something comes in */
	struct events events; /* what the clients subscribed to */
	struct input_queue input; /* from the devices and the socket's input lines */
	struct can_map panel;     /* the dial panel's map, when one is given */
	struct input_devs devs;   /* the mice, keyboards and panels read directly */
	/* each device's motion to pixels; the last: the socket's input lines */
	struct motion_scale pointer[INPUT_DEVS_MAX + 1];
	double pointer_gain;
	struct hotplug hotplug;   /* devices arriving; fd -1: not watched */
	struct escape_chord escape; /* the grab's way out at the keyboard */
	struct modes modes;         /* the interactive modes the input drives, and their views */
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

/* the loop thread's own CPU time: a round's stall apart from the CPUs being busy elsewhere */
static uint64_t
thread_cpu_us(void)
{
	struct timespec t;
	clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
	return (uint64_t)t.tv_sec * 1000000u + (uint64_t)t.tv_nsec / 1000u;
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
	modes_sync(&L->modes);
	if (out.mutated && journal_command(&L->j, &L->d, line, strlen(line)) < 0)
		fprintf(stderr, "postured: journal: %s\n", strerror(errno));
	free(out.json);
}

static void
bring_into_view(struct daemon *d, int v, const double p[3])
{
	struct loop *L = d->loop;
	modes_bring_into_view(&L->modes, v, p);
}

static void
mode_moved(struct daemon *d)
{
	struct loop *L = d->loop;
	modes_apply(&L->modes);
}

/*
 * A step of the mode: at its start and its end the postures are made
 * durable and the mark journaled (journal_step), so a crash mid-step is
 * taken back on recovery and a completed one is one undo.
 */
static void
mode_step(struct daemon *d, char end)
{
	struct loop *L = d->loop;
	if (journal_postures(&L->j, d) < 0)
		fprintf(stderr, "postured: journal: %s\n", strerror(errno));
	if (end == 'B') {
		/* the busy rule's figure: the one a button held in the mode drags */
		const struct interact *ia = d->interact;
		int fig = ia->mode != INTERACT_NONE && interact_buttons(ia) ? ia->fig : -1;
		if (d->step.open || daemon_step_begin(d, fig, interact_name(ia)) < 0)
			return;
	} else {
		if (!d->step.open)
			return;
		daemon_step_end(d);
	}
	if (journal_step(&L->j, end) < 0)
		fprintf(stderr, "postured: journal: %s\n", strerror(errno));
	events_kiosk(&L->events);
}

/*
 * A line typed at the kiosk: run as the kiosk's (its modes start, the busy
 * rule is not for it), journaled when it changes state, and its outcome
 * on the message line, the error's own words when it failed.
 */
static void
typed_at_kiosk(void *ctx, const char *line)
{
	struct loop *L = ctx;
	struct cmd_outcome out;
	size_t len = strlen(line);
	cmd_run(&L->d, DAEMON_CLIENT_KIOSK, line, len, &out);
	modes_sync(&L->modes);
	if (out.mutated && journal_command(&L->j, &L->d, line, len) < 0)
		fprintf(stderr, "postured: journal: %s\n", strerror(errno));
	json_t *reply = out.json ? json_loads(out.json, 0, NULL) : NULL;
	const char *why = json_string_value(json_object_get(json_object_get(reply, "error"), "message"));
	snprintf(L->d.message, sizeof L->d.message, "> %.100s  %s%.120s", line,
		 out.ok ? "ok" : "refused: ", out.ok ? "" : why ? why : "");
	json_decref(reply);
	free(out.json);
	L->scene.dirty = 1;
	events_message(&L->events);
}

static void
command_from_modes(void *ctx, const char *line)
{
	run_own_command(ctx, line);
}

/* the input queued since the last frame, taken in order; returns how many events */
static int
take_input(struct loop *L)
{
	struct input_event_rec e;
	int n = 0;
	while (input_queue_pop(&L->input, &e)) {
		n++;
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
		if (!L->scene.input_us && e.kind != INPUT_FRAME) /* the oldest the pictures owe */
			L->scene.input_us = e.t_us;
		events_input(&L->events, &e, px, py);
		dials_input(&L->dials, &e);
		kiosk_route_input(&L->modes, &e, px, py);
	}
	events_kiosk(&L->events);
	return n;
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
	uint64_t start = real_now(NULL), start_cpu = thread_cpu_us();
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
	L->round_solve_us += real_now(NULL) - start;
	L->round_solve_cpu_us += thread_cpu_us() - start_cpu;
	return 0;
}

static int
settle_frame(struct daemon *d, int *changed)
{
	struct loop *L = d->loop;
	struct ik_clock clock = { virtual_now, L };
	take_input(L);
	modes_frame(&L->modes, real_now(NULL)); /* a snap is eased over real time, settle or not */
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

static int
input_latencies(struct daemon *d, uint64_t *dest, int max)
{
	struct loop *L = d->loop;
	return scene_latencies(&L->scene, dest, max);
}

static int
render_screen(struct daemon *d, const struct frame **dest, char *err, size_t errlen)
{
	struct loop *L = d->loop;
	return scene_draw_screen(&L->scene, d, dest, err, errlen);
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
	modes_sync(&L->modes);
	/* a change is replayed from its command; frames a command ran (settle)
	 * are recorded as the postures they reached */
	int rc = out.mutated ? journal_command(&L->j, &L->d, line, len)
			     : journal_postures(&L->j, &L->d);
	if (rc < 0)
		fprintf(stderr, "postured: journal: %s\n", strerror(errno));
	if (out.mutated)
		L->scene.dirty = 1;
	events_kiosk(&L->events);
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

/*
 * The kiosk's keyboard: the configured layout (a layout xkb-data does not
 * know is said, and the keys then go to the modes alone, as before).
 */
static void
start_kiosk(struct loop *L, const struct loop_config *cfg)
{
	struct kiosk_def kd = kiosk_default_def();
	char names[128], err[300];
	if (cfg->keymap && kiosk_keymap_names(cfg->keymap, &kd.keymap, names, sizeof names) < 0) {
		fprintf(stderr, "postured: keymap '%s' is not LAYOUT[:VARIANT]; the kiosk takes no "
				"typing\n", cfg->keymap);
		return;
	}
	if (cfg->view_key)
		kd.view_key = cfg->view_key;
	L->complete.d = &L->d;
	kd.complete = complete_words;
	kd.complete_user = &L->complete;
	if (!(L->modes.kiosk = kiosk_create(&kd, err, sizeof err)))
		fprintf(stderr, "postured: the kiosk takes no typing: %s\n", err);
	L->modes.run_typed = typed_at_kiosk;
	L->d.kiosk = L->modes.kiosk;
	snprintf(L->d.keymap, sizeof L->d.keymap, "%s", cfg->keymap ? cfg->keymap : "us");
}

/*
 * The framebuffer: a device (/dev/fbN), or file:PATH:WxH, an ordinary file
 * standing for the memory of a 32-bit XRGB framebuffer of that size (for
 * the benchmarks and tests, which have no device). Its size is the
 * kiosk's screen unless --screen gave one.
 */
static struct sink *
open_fb(const char *spec, struct loop *L, char *err, size_t errlen)
{
	struct sink *s;
	int w = 0, h = 0;
	if (!strncmp(spec, "file:", 5)) {
		char path[4096];
		const char *colon = strrchr(spec + 5, ':');
		int used = 0;
		if (!colon || (size_t)(colon - spec - 5) >= sizeof path ||
		    sscanf(colon + 1, "%dx%d%n", &w, &h, &used) != 2 || colon[1 + used] || w < 16 ||
		    h < 16 || w > 16384 || h > 16384) {
			snprintf(err, errlen, "file:PATH:WxH, such as file:/tmp/fb:1280x720");
			return NULL;
		}
		snprintf(path, sizeof path, "%.*s", (int)(colon - spec - 5), spec + 5);
		struct fb_var_screeninfo var = { .xres = (unsigned)w, .yres = (unsigned)h,
						 .xres_virtual = (unsigned)w, .yres_virtual = (unsigned)h,
						 .bits_per_pixel = 32 };
		var.red = (struct fb_bitfield){ 16, 8, 0 };
		var.green = (struct fb_bitfield){ 8, 8, 0 };
		var.blue = (struct fb_bitfield){ 0, 8, 0 };
		struct fb_fix_screeninfo fix = { .line_length = 4u * (unsigned)w,
						 .smem_len = 4u * (unsigned)w * (unsigned)h,
						 .visual = FB_VISUAL_TRUECOLOR };
		s = sink_fb_open_file(path, &var, &fix, err, errlen);
	} else {
		s = sink_fb_open(spec, err, errlen);
		if (s)
			sink_fb_size(s, &w, &h);
	}
	if (s && w > 0 && !L->screen_given) {
		L->d.screen_w = w;
		L->d.screen_h = h;
	}
	return s;
}

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

/*
 * One frame of the running loop. Returns 1 when it changed nothing and
 * nothing waits to be shown: the loop may tick slowly (LOOP_IDLE_TICK_US)
 * until something comes in. Clients following every frame (telemetry,
 * stability) keep it at full rate.
 */
static int
live_frame(struct loop *L)
{
	struct ik_clock clock = { real_now, NULL };
	int changed;
	uint64_t draw = (uint64_t)L->d.stats.draw_us;
	uint64_t budget = L->period_us > draw + 500 ? L->period_us - draw - 500 : L->period_us / 4;
	/* what this frame changes on screen, apart from what was waiting already */
	int waiting = L->scene.dirty;
	L->scene.dirty = 0;
	int moved = take_input(L) > 0;
	modes_frame(&L->modes, real_now(NULL));
	dials_frame(&L->dials, real_now(NULL));
	events_kiosk(&L->events);
	frame(L, &clock, budget, &changed);
	uint64_t now = real_now(NULL);
	moved |= changed || L->scene.dirty;
	L->scene.dirty |= waiting || changed;
	events_posture_changes(&L->events);
	uint64_t drawn = L->scene.drawn_us;
	if (scene_publish(&L->scene, &L->d, &L->events, now)) {
		/* rendering's share of the frame, smoothed: the solver gets the rest (§4.7.2) */
		double us = (double)(L->scene.drawn_us - drawn);
		L->d.stats.draw_us = L->d.stats.draw_us ? 0.8 * L->d.stats.draw_us + 0.2 * us : us;
	}
	L->fps_frames++;
	if (now - L->fps_t0 >= 1000000) {
		L->d.stats.fps = (double)L->fps_frames * 1e6 / (double)(now - L->fps_t0);
		L->fps_t0 = now;
		L->fps_frames = 0;
	}
	return !moved && !scene_waiting(&L->scene, &L->events) &&
	       !events_wanted(&L->events, SUB_TELEMETRY | SUB_STABILITY);
}

/* systemd's watchdog, fed at half its period; returns ms to the next feed, -1: none */
static int
feed_watchdog(struct loop *L, uint64_t now)
{
	if (!L->watchdog_us)
		return -1;
	if (now - L->watchdog_last >= L->watchdog_us / 2) {
		notify_send("WATCHDOG=1");
		L->watchdog_last = now;
	}
	return (int)((L->watchdog_last + L->watchdog_us / 2 - now + 999) / 1000);
}

/* a poll round begins: the clocks its stall is measured from */
static void
round_begin(struct loop *L)
{
	L->round_t0 = real_now(NULL);
	L->round_cpu0 = thread_cpu_us();
	L->round_drawn0 = L->scene.drawn_us;
	L->round_drawn_cpu0 = L->scene.drawn_cpu_us;
	L->round_solve_us = L->round_solve_cpu_us = 0;
}

/*
 * the round less its solving and rendering: how long the loop kept input,
 * clients and the screen waiting for anything else; and how much of that
 * was the loop's own work (its CPU time), not waiting for a CPU
 */
static void
round_end(struct loop *L)
{
	if (!L->round_t0)
		return;
	uint64_t now = real_now(NULL), cpu = thread_cpu_us() - L->round_cpu0;
	uint64_t work = L->round_solve_us + (L->scene.drawn_us - L->round_drawn0);
	uint64_t work_cpu = L->round_solve_cpu_us + (L->scene.drawn_cpu_us - L->round_drawn_cpu0);
	uint64_t stall = now - L->round_t0 > work ? now - L->round_t0 - work : 0;
	uint64_t stall_cpu = cpu > work_cpu ? cpu - work_cpu : 0;
	if (stall > L->stall_max)
		L->stall_max = stall;
	if (stall_cpu > L->stall_cpu_max)
		L->stall_cpu_max = stall_cpu;
	/* published a second at a time, like fps: start-up stalls age out */
	if (now - L->stall_t0 >= 1000000) {
		L->d.stats.stall_max_us = L->stall_max;
		L->d.stats.stall_cpu_max_us = L->stall_cpu_max;
		L->stall_max = L->stall_cpu_max = 0;
		L->stall_t0 = now;
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
			struct dial_bind_lookup lookup = { dial_bind_find_in_map, L->d.panel };
			int left = dial_bind_resolve(&L->dials.table, &lookup);
			if (left > 0)
				fprintf(stderr, "postured: %d dial bindings name no dial of %s's map\n",
					left, p->info.path);
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
	L->d.render_screen = render_screen;
	L->d.input_latencies = input_latencies;
	L->d.set_input = set_input;
	modes_init(&L->modes, &L->d, &L->scene, command_from_modes, L);
	start_kiosk(L, cfg);
	L->d.picked.fig = -1;
	L->screen_given = cfg->screen_w > 0;
	L->d.screen_w = cfg->screen_w ? cfg->screen_w : 1280;
	L->d.screen_h = cfg->screen_h ? cfg->screen_h : 720;
	dials_init(&L->dials, &L->modes);
	L->d.bindings = &L->dials.table;
	L->d.interact = &L->modes.interact;
	L->d.bring_into_view = bring_into_view;
	L->d.mode_moved = mode_moved;
	L->d.mode_step = mode_step;
	L->d.held_max_us = MODES_HELD_MAX_US;
	L->hotplug.fd = -1;
	input_queue_init(&L->input);
	L->d.input = &L->input;
	L->d.now_us = clock_us;
	scene_init(&L->scene, cfg->frames_dir);
	L->scene.cpu_us = thread_cpu_us;
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
	/* the bindings name the dials as the panel's map does (a map arriving later renames) */
	if (cfg->bindings && dials_load(&L->dials, cfg->bindings, L->d.panel, err, sizeof err) < 0) {
		fprintf(stderr, "postured: bindings: %s\n", err);
		goto out;
	}
	if (cfg->fb_device && !(L->scene.fb = open_fb(cfg->fb_device, L, err, sizeof err))) {
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
	uint64_t next = real_now(NULL); /* a first frame at once: then idle, or ticking */
	while (!L->stop) {
		round_end(L);
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
		int watchdog_ms = feed_watchdog(L, now);
		int timeout = now >= next ? 0 : (int)((next - now + 999) / 1000);
		if (watchdog_ms >= 0 && watchdog_ms < timeout)
			timeout = watchdog_ms;
		int got = poll(fds, (nfds_t)n, timeout);
		if (got < 0 && errno != EINTR) {
			fprintf(stderr, "postured: poll: %s\n", strerror(errno));
			break;
		}
		round_begin(L);
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
		/* idle, anything coming in starts a frame at once; then the ticks go on */
		if (L->idle && (got > 0 || L->input.len)) {
			L->idle = 0;
			next = real_now(NULL);
		}
		if (real_now(NULL) >= next) {
			L->idle = live_frame(L);
			next += L->idle && L->period_us < LOOP_IDLE_TICK_US ? LOOP_IDLE_TICK_US
									: L->period_us;
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
		scene_sync(&L->scene, &L->d, &L->events); /* frame events, failures, counters */
		L->d.stats.clients = L->srv.nclients;
		for (int i = 0; i < SERVER_MAX_CLIENTS; i++)
			if (L->srv.c[i].fd >= 0)
				server_flush(&L->srv, i);
	}
	fprintf(stderr, "postured: stopping\n");
	notify_send("STOPPING=1");
	/* a step under way is kept as it is, as a release would keep it */
	mode_step(&L->d, 'E');
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
	kiosk_free(L->modes.kiosk);
	input_devs_close_all(&L->devs, real_now(NULL), &L->input);
	hotplug_close(&L->hotplug);
	events_free(&L->events);
	scene_free(&L->scene);
	free(L);
	return status;
}
