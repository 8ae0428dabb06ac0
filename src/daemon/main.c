/* main.c - postured: flags and config file -> loop_run(); nothing else */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <linux/input-event-codes.h>

#include "daemon/cmd.h"
#include "daemon/loop.h"
#include "daemon/loop_drive.h"
#include "daemon/loop_replay.h"
#include "daemon/settings.h"
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
	if (settings_read_file(s, path) < 0)
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
		if (!strcmp(argv[i], "--config") && i + 1 < argc && settings_read_file(&s, argv[i + 1]) < 0)
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
		if (strcmp(a, "--config") && settings_set(&s, a + 2, argv[i + 1]) < 0)
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
