/* loop.c - the frame loop: the only file that sees compute and I/O together */
#include "daemon/loop.h"

#include "daemon/loop_state.h"
#include "daemon/vt.h"

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

#include "daemon/assess_live.h"
#include "daemon/fit_live.h"
#include "daemon/loads_live.h"
#include "daemon/cmd.h"
#include "daemon/envelopes.h"
#include "daemon/kiosk_route.h"
#include "daemon/notify.h"
#include "devices/can_dev.h"
#include "devices/input_backends.h"

/* the state's clock: the recording's in a replay, and recorded while recording */
static uint64_t
state_clock(struct daemon *d)
{
	struct loop *L = d->loop;
	return tape_clock(&L->tape);
}

/* a state file a command loads: through the tape, which records or replays it */
static char *
read_state(struct daemon *d, const char *path, size_t *len)
{
	struct loop *L = d->loop;
	return tape_read_state(&L->tape, path, len);
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

/* ---- frames ------------------------------------------------------------------ */

static int
subscribe(struct daemon *d, int client, unsigned kinds, int on)
{
	struct loop *L = d->loop;
	if (client < 0 || client >= SERVER_MAX_CLIENTS || L->srv.c[client].fd < 0)
		return -1;
	if (on && (kinds & SUB_ASSESSMENT)) /* a new subscriber hears every figure's scores now */
		events_assessment_retell(&L->events);
	if (on && (kinds & SUB_LOADS)) /* ... and every figure's loads */
		events_loads_retell(&L->events);
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

static const struct hemi_map *
id_map(struct daemon *d, const struct camera *cam, int slot, int only, int skip,
       const unsigned char *skip_seg, char *err, size_t errlen)
{
	struct loop *L = d->loop;
	return scene_id_map(&L->scene, d, cam, slot, only, skip, skip_seg, err, errlen);
}

static int
render_picture(struct daemon *d, const struct env_view *v, int fig, const struct frame **dest,
	       char *err, size_t errlen)
{
	struct loop *L = d->loop;
	return scene_draw_picture(&L->scene, d, v, fig, dest, err, errlen);
}

/* the calendar, for a file's date: the one clock read outside the frame's (see daemon.h) */
static int64_t
calendar_s(struct daemon *d)
{
	(void)d;
	struct timespec t;
	clock_gettime(CLOCK_REALTIME, &t);
	return (int64_t)t.tv_sec;
}

static int
input_latencies(struct daemon *d, uint64_t *dest, int max)
{
	struct loop *L = d->loop;
	return scene_latencies(&L->scene, dest, max);
}

static int
flip_times(struct daemon *d, struct kms_times_summary *dest)
{
	struct loop *L = d->loop;
	return scene_flip_times(&L->scene, dest);
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
	loop_attract_input(L, line, len); /* a client's line that is no question ends a demo */
	loop_run_line(L, i, line, len);
}

void
loop_run_line(struct loop *L, int i, const char *line, size_t len)
{
	tape_client_line(&L->tape, i, line, len);
	struct cmd_outcome out;
	loop_command(L, i, line, len, &out);
	int connected = i >= 0 && i < SERVER_MAX_CLIENTS && L->srv.c[i].fd >= 0; /* not in a replay */
	if (connected && out.reply && out.json)
		reply(L, i, out.json);
	free(out.json);
	if (connected && out.close)
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
 * The kiosk's screen (--display, --fb): auto (KMS, else /dev/fb0, saying
 * which and why), kms[:CARD[:CONNECTOR[:MODE]]], fbdev:/dev/fbN or a device
 * path, or file:PATH:WxH, an ordinary file standing for the memory of a
 * 32-bit XRGB framebuffer of that size (for the benchmarks and tests, which
 * have no device). Its size is the kiosk's screen unless --screen gave one.
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
	} else if (!strcmp(spec, "auto")) {
		/* KMS first (page flips, no tearing), else the fbdev emulation or driver */
		char kerr[300];
		if ((s = sink_kms_open(NULL, NULL, NULL, kerr, sizeof kerr))) {
			char desc[160];
			sink_kms_info(s, &w, &h, desc, sizeof desc);
			fprintf(stderr, "postured: display: KMS, %s\n", desc);
		} else if ((s = sink_fb_open("/dev/fb0", err, errlen))) {
			sink_fb_size(s, &w, &h);
			fprintf(stderr, "postured: display: fbdev /dev/fb0 (no KMS: %s)\n", kerr);
		} else {
			char ferr[300];
			snprintf(ferr, sizeof ferr, "%s", err);
			snprintf(err, errlen, "no KMS (%.200s) and no fbdev (%.200s)", kerr, ferr);
		}
	} else if (!strncmp(spec, "kms", 3) && (!spec[3] || spec[3] == ':')) {
		/* kms[:CARD[:CONNECTOR[:MODE]]] */
		char f[3][128] = { "", "", "" }; /* card, connector, mode: each may be empty */
		const char *p = spec[3] ? spec + 4 : "";
		for (int k = 0; k < 3 && *p; k++) {
			size_t n = strcspn(p, k < 2 ? ":" : "");
			snprintf(f[k], sizeof f[k], "%.*s", (int)(n < 127 ? n : 127), p);
			p += n + (p[n] == ':');
		}
		const char *card = f[0], *conn = f[1], *mode = f[2];
		if ((s = sink_kms_open(card[0] ? card : NULL, conn, mode, err, errlen))) {
			char desc[160];
			sink_kms_info(s, &w, &h, desc, sizeof desc);
			fprintf(stderr, "postured: display: KMS, %s\n", desc);
		}
	} else {
		s = sink_fb_open(!strncmp(spec, "fbdev:", 6) ? spec + 6 : spec, err, errlen);
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
	sigaddset(&set, VT_SIG_RELEASE); /* the kiosk's VT switching away, and back (vt.h) */
	sigaddset(&set, VT_SIG_ACQUIRE);
	signal(SIGPIPE, SIG_IGN);
	if (sigprocmask(SIG_BLOCK, &set, NULL) < 0)
		return -1;
	return signalfd(-1, &set, SFD_NONBLOCK | SFD_CLOEXEC);
}

/*
 * The signals: SIGTERM and SIGINT stop the loop; the VT's switch away
 * (the screen given up, then agreed to) and back (agreed, then the screen
 * taken back and drawn whole).
 */
static void
take_signals(struct loop *L)
{
	struct signalfd_siginfo si;
	while (read(L->sig_fd, &si, sizeof si) == (ssize_t)sizeof si) {
		if (si.ssi_signo == VT_SIG_RELEASE && L->vt.fd >= 0) {
			scene_hold_screen(&L->scene, 1);
			vt_release(&L->vt);
			fprintf(stderr, "postured: VT switched away: not drawing\n");
		} else if (si.ssi_signo == VT_SIG_ACQUIRE && L->vt.fd >= 0) {
			vt_acquire(&L->vt);
			scene_hold_screen(&L->scene, 0);
			fprintf(stderr, "postured: VT back: drawing\n");
		} else if (si.ssi_signo == SIGTERM || si.ssi_signo == SIGINT) {
			L->stop = 1;
		}
	}
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
	L->round_t0 = loop_real_now();
	L->round_cpu0 = loop_thread_cpu_us();
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
	uint64_t now = loop_real_now(), cpu = loop_thread_cpu_us() - L->round_cpu0;
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
		if (input_devs_open(&L->devs, spec[k], loop_real_now(), err, errlen) < 0)
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
	uint64_t screens = L->hotplug.screens;
	int arrived = hotplug_read(&L->hotplug);
	int w, h;
	if (L->hotplug.screens != screens && scene_reprobe_screen(&L->scene, &w, &h) > 0 &&
	    !L->screen_given) { /* the kiosk's screen is the new mode's */
		L->d.screen_w = w;
		L->d.screen_h = h;
	}
	if (arrived <= 0)
		return;
	if (input_devs_rescan(&L->devs, loop_real_now()) > 0)
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
loop_setup(struct loop *L, const struct loop_config *cfg)
{
	char err[512];
	L->cfg = cfg;
	L->j.fd = -1;
	L->vt.fd = -1;
	L->sig_fd = -1;
	env_init(&L->d.env);
	snprintf(L->d.state_dir, sizeof L->d.state_dir, "%s", cfg->state_dir);
	snprintf(L->d.library_dir, sizeof L->d.library_dir, "%s", cfg->library_dir ? cfg->library_dir : "");
	L->d.loop = L;
	L->d.run_frame = loop_settle_frame;
	L->d.subscribe = subscribe;
	L->d.render_view = render_view;
	L->d.render_screen = render_screen;
	L->d.render_picture = render_picture;
	L->d.id_map = id_map;
	L->d.calendar_s = calendar_s;
	L->d.input_latencies = input_latencies;
	L->d.flip_times = flip_times;
	L->d.set_input = set_input;
	L->d.record = loop_record;
	L->d.recording = loop_recording;
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
	L->d.now_us = state_clock;
	L->d.read_state = read_state;
	scene_init(&L->scene, cfg->frames_dir);
	L->scene.cpu_us = loop_thread_cpu_us;
	L->scene.wall_us = loop_real_now;
	L->period_us = (uint64_t)(1e6 / cfg->fps);
	server_init(&L->srv);
	if (events_init(&L->events, &L->srv, &L->d) < 0 || assess_live_init(&L->d) < 0 ||
	    loads_live_init(&L->d) < 0 || fit_live_init(&L->d) < 0)
		return -1;
	if (cfg->panel_map) {
		if (can_map_read(cfg->panel_map, &L->panel, err, sizeof err) < 0) {
			fprintf(stderr, "postured: panel map: %s\n", err);
			return -1;
		}
		L->d.panel = &L->panel;
	}
	if (open_devices(L, cfg, err, sizeof err) < 0) {
		fprintf(stderr, "postured: %s\n", err);
		return -1;
	}
	/* the bindings name the dials as the panel's map does (a map arriving later renames) */
	if (cfg->bindings && dials_load(&L->dials, cfg->bindings, L->d.panel, err, sizeof err) < 0) {
		fprintf(stderr, "postured: bindings: %s\n", err);
		return -1;
	}
	if (cfg->fb_device && !(L->scene.fb = open_fb(cfg->fb_device, L, err, sizeof err))) {
		fprintf(stderr, "postured: framebuffer %s: %s\n", cfg->fb_device, err);
		return -1;
	}
	/* a KMS screen follows its connectors: the hot-plug monitor, even with no device read */
	const char *source = cfg->hotplug ? cfg->hotplug : "udev";
	if (L->scene.fb && !strcmp(L->scene.fb->ops->name, "kms") && L->hotplug.fd < 0 &&
	    strcmp(source, "none") && hotplug_open(&L->hotplug, source, err, sizeof err) < 0)
		fprintf(stderr, "postured: no hot-plug (the screen is probed only at start): %s\n", err);
	return 0;
}

int
loop_run(const struct loop_config *cfg)
{
	struct loop *L = calloc(1, sizeof *L);
	char err[512];
	if (!L)
		return 1;
	int status = 1;
	if (loop_setup(L, cfg) < 0)
		goto out;
	if (journal_open(&L->j, &L->d, err, sizeof err) < 0) {
		fprintf(stderr, "postured: cannot recover the state: %s\n", err);
		goto out;
	}
	fprintf(stderr, "postured: state recovered: %d figures, journal at record %" PRIu64 "\n",
		env_count(&L->d.env), L->j.seq);
	if (cfg->init_file && env_count(&L->d.env) == 0 && L->j.seq == 0 && run_init(L, cfg->init_file) < 0)
		goto out;
	L->synced_seq = L->j.seq;
	if (cfg->attract_dir && loop_attract_check(L, err, sizeof err) < 0) {
		fprintf(stderr, "postured: attract: %s\n", err);
		goto out;
	}
	/* a recording starts from the state recovered */
	if (cfg->record_dir && loop_record(&L->d, cfg->record_dir, err, sizeof err) < 0) {
		fprintf(stderr, "postured: record: %s\n", err);
		goto out;
	}
	if (server_open(&L->srv, cfg->socket_path, cfg->tcp_port, cfg->token, err, sizeof err) < 0) {
		fprintf(stderr, "postured: %s\n", err);
		goto out;
	}
	if ((L->sig_fd = open_signals()) < 0) {
		fprintf(stderr, "postured: signals: %s\n", strerror(errno));
		goto out;
	}
	/* the kiosk's VT, once its signals are the loop's to read */
	if (cfg->vt && vt_take(&L->vt, cfg->vt, err, sizeof err) < 0) {
		fprintf(stderr, "postured: VT: %s\n", err);
		goto out;
	}
	/* READY=1, and with it systemd's watchdog, wait for the first frame: llvmpipe compiles
	 * its shaders then, seconds on a slow machine, which the start's timeout is for */
	uint64_t watchdog_us = notify_watchdog_usec();
	int ready = 0;
	L->fps_t0 = loop_real_now();
	fprintf(stderr, "postured: listening on %s%s\n", cfg->socket_path,
		cfg->tcp_port > 0 ? " and 127.0.0.1 (token required)" : "");
	static struct pollfd fds[SERVER_MAX_CLIENTS + 4 + INPUT_DEVS_POLL_MAX];
	static int owner[SERVER_MAX_CLIENTS + 4 + INPUT_DEVS_POLL_MAX];
	uint64_t next = loop_real_now(); /* a first frame at once: then idle, or ticking */
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
		uint64_t now = loop_real_now();
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
			if (owner[k] <= -100) {
				unsigned queued = L->input.len;
				input_devs_ready(&L->devs, -100 - owner[k], loop_real_now(), &L->input);
				if (L->input.len != queued) /* someone at the kiosk: the demo gives way */
					loop_attract_input(L, NULL, 0);
			}
			else if (owner[k] == -3)
				take_signals(L);
			else if (owner[k] == -4)
				devices_arrived(L);
			else if (owner[k] < 0)
				server_accept(&L->srv, fds[k].fd);
			else if (L->srv.c[owner[k]].fd == fds[k].fd &&
				 (fds[k].revents & (POLLIN | POLLHUP | POLLERR)))
				client_input(L, owner[k]);
		}
		/* the attract mode's frames are the frames while it plays */
		int attract_ms = -1;
		if (loop_attract_round(L, &attract_ms)) {
			next = loop_real_now() + (uint64_t)attract_ms * 1000u;
			L->idle = 0;
		} else if (L->idle && (got > 0 || L->input.len)) {
			/* idle, anything coming in starts a frame at once; then the ticks go on */
			L->idle = 0;
			next = loop_real_now();
		}
		if (!L->attract.on && loop_real_now() >= next) {
			L->idle = loop_live_frame(L);
			next += L->idle && L->period_us < LOOP_IDLE_TICK_US ? LOOP_IDLE_TICK_US
									: L->period_us;
			if (next < loop_real_now()) /* fell behind: do not try to catch up */
				next = loop_real_now() + L->period_us;
		}
		if (!ready) {
			ready = 1;
			notify_send("READY=1");
			L->watchdog_us = watchdog_us; /* the next round's feed pings at once */
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
		tape_flush(&L->tape); /* the round's records to the recording's writer */
		L->d.stats.clients = L->srv.nclients;
		for (int i = 0; i < SERVER_MAX_CLIENTS; i++)
			if (L->srv.c[i].fd >= 0)
				server_flush(&L->srv, i);
	}
	fprintf(stderr, "postured: stopping\n");
	loop_attract_end(L); /* the real state is what is kept */
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
	loop_record_end(L);
	loop_teardown(L);
	return status;
}

void
loop_teardown(struct loop *L)
{
	vt_give_back(&L->vt); /* text mode and the keyboard, as they were */
	server_close(&L->srv);
	journal_close(&L->j);
	env_clear(&L->d.env);
	populations_clear(&L->d.pops);
	daemon_checkpoints_clear(&L->d.undo);
	daemon_checkpoints_clear(&L->d.redo);
	daemon_picks_free(&L->d);
	assess_live_free(&L->d);
	loads_live_free(&L->d);
	fit_live_free(&L->d);
	if (L->d.envelopes)
		envelopes_clear(L->d.envelopes);
	free(L->d.envelopes);
	daemon_text_clear(&L->d.file_read); /* the last command's file, if it read one */
	daemon_text_clear(&L->d.file_given);
	kiosk_free(L->modes.kiosk);
	input_devs_close_all(&L->devs, loop_real_now(), &L->input);
	hotplug_close(&L->hotplug);
	events_free(&L->events);
	scene_free(&L->scene);
	free(L);
}
