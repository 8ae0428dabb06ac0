/* main.c - postured: flags and config file -> loop_run(); nothing else */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <libevdev/libevdev.h>
#include <linux/input-event-codes.h>

#include "daemon/cmd.h"
#include "daemon/loop.h"
#include "daemon/loop_drive.h"
#include "daemon/loop_replay.h"
#include "daemon/vt.h"

static const char usage[] =
	"usage: postured [OPTIONS]\n"
	"\n"
	"The posture daemon: holds figures and their constraints, solves them every frame,\n"
	"and serves clients over a Unix socket (docs/protocol.md).\n"
	"\n"
	"  --socket PATH      the Unix socket (default $XDG_RUNTIME_DIR/posture/postured.sock,\n"
	"                     else /tmp/posture-UID/postured.sock); created mode 0660\n"
	"  --state-dir DIR    journal, snapshots, posture and session files (default\n"
	"                     $XDG_STATE_HOME/posture, else ~/.local/state/posture)\n"
	"  --frames DIR       where rendered frames go, one DIR/VIEW.png per view,\n"
	"                     replaced atomically at most 10 times a second (default: none)\n"
	"  --display SPEC     show the kiosk's screen (the first view, or the layout's views):\n"
	"                     auto (DRM/KMS, else /dev/fb0; says which and why),\n"
	"                     kms[:CARD[:CONNECTOR[:MODE]]] (e.g. kms:/dev/dri/card0:HDMI-A-1:1920x1080),\n"
	"                     fbdev:/dev/fbN, or file:PATH:WxH (a file standing for fbdev memory)\n"
	"  --fb DEVICE        the same as --display (a framebuffer device or file:PATH:WxH)\n"
	"  --fps N            frame rate of the loop (default 60)\n"
	"  --solve-budget US  the solver's time a frame, all figures (default: the frame less\n"
	"                     its drawing and 0.5 ms)\n"
	"  --tcp PORT         also listen on 127.0.0.1:PORT (needs --token)\n"
	"  --token TOKEN      the token TCP clients must send first (auth TOKEN)\n"
	"  --init FILE        commands to run when the state is empty (a first start)\n"
	"  --library DIR      shipped figure files, loaded as 'load figure lib:NAME'\n"
	"  --input SPEC       the devices to read (repeatable): auto (the default: every\n"
	"                     mouse and keyboard in /dev/input), evdev:PATH, hidraw:VID:PID[:IFACE],\n"
	"                     usb:VID:PID[:IFACE], can:IFACE:MAPFILE, or none\n"
	"  --grab yes|no      the kiosk grab: the evdev devices read by this daemon alone, not\n"
	"                     the console (default no; the way out: postured(8), GRAB)\n"
	"  --pointer-gain G   screen pixels per 1/1000 inch of mouse motion (default 1)\n"
	"  --hotplug SOURCE   devices arriving are opened: udev (the default), kernel (no\n"
	"                     udevd; needs root) or none\n"
	"  --panel FILE       the dial panel's map: its axes and buttons by name (see\n"
	"                     devices/can_map.h; tools/dbc2panel makes one from a DBC file)\n"
	"  --keymap LAYOUT    the kiosk keyboard's layout, LAYOUT[:VARIANT] as xkb-data names\n"
	"                     them (default us; e.g. de, fr, de:nodeadkeys)\n"
	"  --view-key KEY     the key that enters change view from the edit line (default F2)\n"
	"  --screen WxH       the kiosk's screen, where `layout` tiles the views (default: the\n"
	"                     framebuffer's size, else 1280x720)\n"
	"  --bindings FILE    the dial panel's bindings: dials to joints, the view, behaviours\n"
	"                     or G, buttons to commands (see tools/panel.bindings)\n"
	"  --record DIR       record from the start into the new folder DIR: the lines, input and\n"
	"                     the solver's work, for --replay (also `record start` at run time)\n"
	"  --drive FILE       run FILE's lines ('T_US CLIENT TEXT', a recording's form) under a\n"
	"                     virtual clock, frame after frame as fast as it goes, then --after's\n"
	"                     queries; prints 'drive: frames=N virtual_s=S posture=HASH'; the\n"
	"                     state directory and journal as live, no socket or devices\n"
	"  --vt TTY           the kiosk's VT (/dev/ttyN, stdin: the unit's TTYPath=, none): graphics\n"
	"                     mode, its keyboard off, VT switches handled (the screen given up\n"
	"                     and taken back); put back as it was on exit\n"
	"  --vt-restore TTY   make TTY a usable text console again (after a crash) and exit\n"
	"  --attract DIR      the attract mode: the recording DIR replayed in a loop while nobody\n"
	"                     is at the kiosk; the first real input ends it, the state as it was\n"
	"  --attract-after S  seconds without input before it starts (default 60)\n"
	"  --replay DIR       replay a recording (its settings first, then the flags) with no\n"
	"                     socket, devices or state directory, checking every frame's posture\n"
	"                     against the recording's; prints 'replay: frames=N posture=HASH\n"
	"                     divergences=N' and exits 0 when nothing diverged\n"
	"  --until N          stop the replay after its frame N\n"
	"  --after FILE       once the replay stopped, run FILE's commands and print each reply\n"
	"                     as 'reply: JSON' (what a replay test asks of the state)\n"
	"  --hash-frames yes  draw every view after each replayed frame and print the pixels' hash\n"
	"                     as 'pictures: drawn=N hash=HASH' (the same on every run of a machine)\n"
	"  --speed max|X      the replay's pace: as fast as it goes (max, the default) or X times\n"
	"                     real time (1: as recorded)\n"
	"  --config FILE      read 'key = value' lines first (keys: the long options)\n"
	"  --protocol-table   print the command table of docs/protocol.md and exit\n"
	"  --help             this text\n"
	"\n"
	"Signals: SIGTERM and SIGINT stop it cleanly (journal flushed, snapshot written).\n"
	"Under systemd (Type=notify) it reports READY=1 when listening with a first frame drawn,\n"
	"and pings the watchdog.\n";

struct settings {
	char socket[PATH_MAX], state_dir[PATH_MAX], frames[PATH_MAX], init[PATH_MAX], library[PATH_MAX];
	char fb[PATH_MAX], panel[PATH_MAX], token[128], hotplug[16], keymap[128], bindings[PATH_MAX];
	char record[PATH_MAX], replay[PATH_MAX], after[PATH_MAX], attract[PATH_MAX], drive[PATH_MAX];
	char vt[64];
	int vt_given;
	double attract_after;
	double speed;
	unsigned long long until;
	int hash_frames;
	unsigned view_key;
	int screen_w, screen_h;
	char input[INPUT_DEVS_MAX][INPUT_DEVS_SPEC_MAX];
	const char *inputs[INPUT_DEVS_MAX];
	int ninputs;
	double fps, pointer_gain;
	unsigned solve_budget;
	int tcp, grab;
};

static int
set(struct settings *s, const char *key, const char *val)
{
	char *end;
	if (!strcmp(key, "socket"))
		snprintf(s->socket, sizeof s->socket, "%s", val);
	else if (!strcmp(key, "state-dir"))
		snprintf(s->state_dir, sizeof s->state_dir, "%s", val);
	else if (!strcmp(key, "frames"))
		snprintf(s->frames, sizeof s->frames, "%s", val);
	else if (!strcmp(key, "fb") || !strcmp(key, "display"))
		snprintf(s->fb, sizeof s->fb, "%s", val);
	else if (!strcmp(key, "library"))
		snprintf(s->library, sizeof s->library, "%s", val);
	else if (!strcmp(key, "input")) {
		if (s->ninputs == INPUT_DEVS_MAX || strlen(val) >= INPUT_DEVS_SPEC_MAX) {
			fprintf(stderr, "postured: at most %d inputs of %d bytes\n", INPUT_DEVS_MAX,
				INPUT_DEVS_SPEC_MAX - 1);
			return -1;
		}
		snprintf(s->input[s->ninputs], sizeof s->input[0], "%s", val);
		s->inputs[s->ninputs] = s->input[s->ninputs];
		s->ninputs++;
	} else if (!strcmp(key, "grab")) {
		if (strcmp(val, "yes") && strcmp(val, "no")) {
			fprintf(stderr, "postured: grab must be yes or no\n");
			return -1;
		}
		s->grab = !strcmp(val, "yes");
	} else if (!strcmp(key, "pointer-gain")) {
		s->pointer_gain = strtod(val, &end);
		if (*end || !(s->pointer_gain > 0 && s->pointer_gain <= 100)) {
			fprintf(stderr, "postured: pointer-gain must be a number above 0, at most 100\n");
			return -1;
		}
	} else if (!strcmp(key, "hotplug")) {
		if (strcmp(val, "udev") && strcmp(val, "kernel") && strcmp(val, "none")) {
			fprintf(stderr, "postured: hotplug must be udev, kernel or none\n");
			return -1;
		}
		snprintf(s->hotplug, sizeof s->hotplug, "%s", val);
	} else if (!strcmp(key, "keymap")) {
		if (strlen(val) >= sizeof s->keymap || !val[0]) {
			fprintf(stderr, "postured: keymap is a layout name such as us or de:nodeadkeys\n");
			return -1;
		}
		snprintf(s->keymap, sizeof s->keymap, "%s", val);
	} else if (!strcmp(key, "view-key")) {
		char name[64];
		snprintf(name, sizeof name, "%s%s", strncmp(val, "KEY_", 4) ? "KEY_" : "", val);
		int code = libevdev_event_code_from_name(EV_KEY, name);
		if (code < 0) {
			fprintf(stderr, "postured: view-key '%s' is no key name (F2, KEY_F3, ...)\n", val);
			return -1;
		}
		s->view_key = (unsigned)code;
	} else if (!strcmp(key, "screen")) {
		int w, h, used = 0;
		if (sscanf(val, "%dx%d%n", &w, &h, &used) != 2 || val[used] || w < 64 || h < 64 ||
		    w > 16384 || h > 16384) {
			fprintf(stderr, "postured: screen is WxH in pixels, such as 1920x1080\n");
			return -1;
		}
		s->screen_w = w;
		s->screen_h = h;
	} else if (!strcmp(key, "vt")) {
		snprintf(s->vt, sizeof s->vt, "%s", strcmp(val, "stdin") ? val : "");
		s->vt_given = strcmp(val, "none") != 0;
	} else if (!strcmp(key, "drive")) {
		snprintf(s->drive, sizeof s->drive, "%s", val);
	} else if (!strcmp(key, "attract")) {
		snprintf(s->attract, sizeof s->attract, "%s", val);
	} else if (!strcmp(key, "attract-after")) {
		s->attract_after = strtod(val, &end);
		if (*end || !(s->attract_after >= 1 && s->attract_after <= 86400)) {
			fprintf(stderr, "postured: attract-after is seconds from 1 to 86400\n");
			return -1;
		}
	} else if (!strcmp(key, "record")) {
		snprintf(s->record, sizeof s->record, "%s", val);
	} else if (!strcmp(key, "replay")) {
		snprintf(s->replay, sizeof s->replay, "%s", val);
	} else if (!strcmp(key, "until")) {
		s->until = strtoull(val, &end, 10);
		if (*end || !val[0] || val[0] == '-' || !s->until) {
			fprintf(stderr, "postured: until is a frame number from 1\n");
			return -1;
		}
	} else if (!strcmp(key, "hash-frames")) {
		if (strcmp(val, "yes") && strcmp(val, "no")) {
			fprintf(stderr, "postured: hash-frames is yes or no\n");
			return -1;
		}
		s->hash_frames = !strcmp(val, "yes");
	} else if (!strcmp(key, "after")) {
		snprintf(s->after, sizeof s->after, "%s", val);
	} else if (!strcmp(key, "speed")) {
		s->speed = strcmp(val, "max") ? strtod(val, &end) : 0;
		if (strcmp(val, "max") && (*end || !(s->speed >= 0.01 && s->speed <= 1000))) {
			fprintf(stderr, "postured: speed is max, or a factor of real time from 0.01 to 1000\n");
			return -1;
		}
	} else if (!strcmp(key, "bindings")) {
		snprintf(s->bindings, sizeof s->bindings, "%s", val);
	} else if (!strcmp(key, "panel"))
		snprintf(s->panel, sizeof s->panel, "%s", val);
	else if (!strcmp(key, "init"))
		snprintf(s->init, sizeof s->init, "%s", val);
	else if (!strcmp(key, "token"))
		snprintf(s->token, sizeof s->token, "%s", val);
	else if (!strcmp(key, "fps")) {
		s->fps = strtod(val, &end);
		if (*end || !(s->fps >= 1 && s->fps <= 1000)) {
			fprintf(stderr, "postured: fps must be a number from 1 to 1000\n");
			return -1;
		}
	} else if (!strcmp(key, "solve-budget")) {
		long us = strtol(val, &end, 10);
		if (*end || us < 10 || us > 1000000) {
			fprintf(stderr, "postured: solve-budget is microseconds from 10 to 1000000\n");
			return -1;
		}
		s->solve_budget = (unsigned)us;
	} else if (!strcmp(key, "tcp")) {
		long p = strtol(val, &end, 10);
		if (*end || p < 1 || p > 65535) {
			fprintf(stderr, "postured: tcp must be a port from 1 to 65535\n");
			return -1;
		}
		s->tcp = (int)p;
	} else {
		fprintf(stderr, "postured: unknown setting '%s'\n", key);
		return -1;
	}
	return 0;
}

static int
read_config(struct settings *s, const char *path)
{
	FILE *f = fopen(path, "r");
	if (!f) {
		fprintf(stderr, "postured: %s: %s\n", path, strerror(errno));
		return -1;
	}
	char line[4200];
	int n = 0, rc = 0;
	while (rc == 0 && fgets(line, sizeof line, f)) {
		n++;
		char *p = line, *eq;
		while (*p == ' ' || *p == '\t')
			p++;
		if (*p == '#' || *p == '\n' || !*p)
			continue;
		p[strcspn(p, "\r\n")] = 0;
		if (!(eq = strchr(p, '='))) {
			fprintf(stderr, "postured: %s:%d: expected key = value\n", path, n);
			rc = -1;
			break;
		}
		char *k = p, *v = eq + 1, *ke = eq;
		while (ke > k && (ke[-1] == ' ' || ke[-1] == '\t'))
			ke--;
		*ke = 0;
		while (*v == ' ' || *v == '\t')
			v++;
		if (set(s, k, v) < 0) {
			fprintf(stderr, "postured: in %s:%d\n", path, n);
			rc = -1;
		}
	}
	fclose(f);
	return rc;
}

/* mkdir -p with a mode for the directories it creates */
static int
make_dirs(const char *path, mode_t mode)
{
	char buf[PATH_MAX];
	snprintf(buf, sizeof buf, "%s", path);
	for (char *p = buf + 1; *p; p++) {
		if (*p != '/')
			continue;
		*p = 0;
		if (mkdir(buf, mode) < 0 && errno != EEXIST)
			return -1;
		*p = '/';
	}
	return mkdir(buf, mode) < 0 && errno != EEXIST ? -1 : 0;
}

static void
defaults(struct settings *s)
{
	const char *run = getenv("XDG_RUNTIME_DIR"), *st = getenv("XDG_STATE_HOME"),
		   *home = getenv("HOME");
	if (run && run[0])
		snprintf(s->socket, sizeof s->socket, "%s/posture/postured.sock", run);
	else
		snprintf(s->socket, sizeof s->socket, "/tmp/posture-%ld/postured.sock", (long)getuid());
	if (st && st[0])
		snprintf(s->state_dir, sizeof s->state_dir, "%s/posture", st);
	else
		snprintf(s->state_dir, sizeof s->state_dir, "%s/.local/state/posture", home ? home : ".");
	s->fps = 60;
	s->attract_after = 60;
	s->pointer_gain = 1;
	snprintf(s->keymap, sizeof s->keymap, "us");
	s->view_key = KEY_F2;
}

/*
 * A recording's settings (its config file), with the files it names
 * (bindings, the panel's map, the shipped figures) found in the
 * recording's folder.
 */
static int
replay_settings(struct settings *s, const char *dir)
{
	char path[PATH_MAX + 16];
	snprintf(path, sizeof path, "%s/config", dir);
	if (read_config(s, path) < 0)
		return -1;
	char *names[] = { s->bindings, s->panel, s->library };
	for (int k = 0; k < 3; k++)
		if (names[k][0] && names[k][0] != '/') {
			char full[PATH_MAX * 2 + 2];
			int n = snprintf(full, sizeof full, "%s/%s", dir, names[k]);
			if (n >= PATH_MAX) {
				fprintf(stderr, "postured: %s: path too long\n", full);
				return -1;
			}
			memcpy(names[k], full, (size_t)n + 1);
		}
	return 0;
}

/* --replay: no socket, devices or state directory; the recording's folder is read only */
static int
replay(struct settings *s)
{
	static const char *const no_input[] = { "none" };
	struct loop_config cfg = { .socket_path = "", .state_dir = s->replay,
				   .frames_dir = s->frames[0] ? s->frames : NULL, .fps = s->fps,
				   .library_dir = s->library[0] ? s->library : NULL,
				   .fb_device = s->fb[0] ? s->fb : NULL,
				   .panel_map = s->panel[0] ? s->panel : NULL,
				   .inputs = no_input, .ninputs = 1, .pointer_gain = s->pointer_gain,
				   .hotplug = "none", .keymap = s->keymap, .view_key = s->view_key,
				   .bindings = s->bindings[0] ? s->bindings : NULL,
				   .screen_w = s->screen_w, .screen_h = s->screen_h,
				   .replay_dir = s->replay, .speed = s->speed, .until = s->until,
				   .after = s->after[0] ? s->after : NULL, .hash_frames = s->hash_frames };
	if (s->frames[0] && make_dirs(s->frames, 0750) < 0) {
		fprintf(stderr, "postured: %s: %s\n", s->frames, strerror(errno));
		return 1;
	}
	return loop_replay(&cfg);
}

int
main(int argc, char **argv)
{
	struct settings s = { 0 };
	defaults(&s);
	/* a recording's settings first, then the config file, so flags win */
	for (int i = 1; i < argc; i++)
		if (!strcmp(argv[i], "--replay") && i + 1 < argc && replay_settings(&s, argv[i + 1]) < 0)
			return 2;
	for (int i = 1; i < argc; i++)
		if (!strcmp(argv[i], "--config") && i + 1 < argc && read_config(&s, argv[i + 1]) < 0)
			return 2;
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i];
		if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
			fputs(usage, stdout);
			return 0;
		}
		if (!strcmp(a, "--vt-restore") && i + 1 < argc) { /* after a crash: a usable console */
			char err[300];
			if (vt_restore_console(argv[i + 1], err, sizeof err) < 0) {
				fprintf(stderr, "postured: %s\n", err);
				return 1;
			}
			return 0;
		}
		if (!strcmp(a, "--protocol-table")) {
			cmd_print_table(stdout);
			return 0;
		}
		if (strncmp(a, "--", 2) || i + 1 >= argc) {
			fprintf(stderr, "postured: unknown or incomplete option '%s'\n%s", a, usage);
			return 2;
		}
		if (strcmp(a, "--config") && set(&s, a + 2, argv[i + 1]) < 0)
			return 2;
		i++;
	}
	if (s.replay[0])
		return replay(&s);
	char sockdir[PATH_MAX];
	snprintf(sockdir, sizeof sockdir, "%s", s.socket);
	char *slash = strrchr(sockdir, '/');
	if (slash && slash != sockdir)
		*slash = 0;
	if (make_dirs(s.state_dir, 0700) < 0 || (slash && make_dirs(sockdir, 0700) < 0) ||
	    (s.frames[0] && make_dirs(s.frames, 0750) < 0)) {
		fprintf(stderr, "postured: cannot create a directory: %s\n", strerror(errno));
		return 1;
	}
	fprintf(stderr, "postured: socket %s, state %s, frames %s, %.0f fps%s\n", s.socket,
		s.state_dir, s.frames[0] ? s.frames : "(none)", s.fps, s.tcp ? ", tcp on" : "");
	struct loop_config cfg = {
		.socket_path = s.socket, .state_dir = s.state_dir,
		.frames_dir = s.frames[0] ? s.frames : NULL, .fps = s.fps, .tcp_port = s.tcp,
		.solve_budget_us = s.solve_budget,
		.token = s.token, .init_file = s.init[0] ? s.init : NULL,
		.library_dir = s.library[0] ? s.library : NULL, .fb_device = s.fb[0] ? s.fb : NULL,
		.panel_map = s.panel[0] ? s.panel : NULL, .inputs = s.inputs, .ninputs = s.ninputs,
		.grab = s.grab, .pointer_gain = s.pointer_gain,
		.hotplug = s.hotplug[0] ? s.hotplug : NULL, .keymap = s.keymap,
		.view_key = s.view_key, .bindings = s.bindings[0] ? s.bindings : NULL,
		.screen_w = s.screen_w, .screen_h = s.screen_h,
		.record_dir = s.record[0] ? s.record : NULL,
		.attract_dir = s.attract[0] ? s.attract : NULL, .attract_after = s.attract_after,
		.drive_file = s.drive[0] ? s.drive : NULL, .after = s.after[0] ? s.after : NULL,
		.vt = s.vt_given ? s.vt : NULL,
	};
	if (cfg.drive_file) { /* nothing but the script comes in */
		static const char *const none[] = { "none" };
		cfg.inputs = none;
		cfg.ninputs = 1;
		cfg.hotplug = "none";
		return loop_drive(&cfg);
	}
	return loop_run(&cfg);
}
