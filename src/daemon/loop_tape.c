/*
 * loop_tape.c - the loop recorded (`--record DIR`, `record start|stop`):
 * the settings and the state a recording starts from (tape.h).
 */
#include "daemon/loop_state.h"

#include <dirent.h>
#include <errno.h>
#include <inttypes.h>
#include <libevdev/libevdev.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "daemon/posture_hash.h"
#include "daemon/session.h"
#include "daemon/statefile.h"
#include "daemon/tape_dev.h"

/* the regular files of the shipped figures' folder into dir/library */
static int
copy_library(const char *from, const char *dir)
{
	char path[TAPE_PATH_MAX + 300];
	snprintf(path, sizeof path, "%s/library", dir);
	DIR *d = opendir(from);
	if (!d || mkdir(path, 0750) < 0) {
		if (d)
			closedir(d);
		return -1;
	}
	int rc = 0;
	for (struct dirent *e; rc == 0 && (e = readdir(d));) {
		char src[PATH_MAX + 300];
		struct stat st;
		snprintf(src, sizeof src, "%s/%s", from, e->d_name);
		if (e->d_name[0] == '.' || stat(src, &st) < 0 || !S_ISREG(st.st_mode))
			continue;
		size_t n;
		char *text = statefile_read(src, &n);
		snprintf(path, sizeof path, "%s/library/%.255s", dir, e->d_name);
		rc = text && statefile_write(path, text, n) == 0 ? 0 : -1;
		free(text);
	}
	closedir(d);
	return rc;
}

/* the settings a replay needs, as --config reads them; the files they name are written beside */
static char *
config_text(struct loop *L, const char *dir, char *err, size_t errlen)
{
	const struct loop_config *cfg = L->cfg;
	char *text = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&text, &len);
	if (!f) {
		snprintf(err, errlen, "out of memory");
		return NULL;
	}
	const char *key = libevdev_event_code_get_name(EV_KEY, cfg->view_key ? cfg->view_key : KEY_F2);
	fprintf(f, "# the settings of the daemon this recording was made with\n");
	fprintf(f, "fps = %.17g\n", cfg->fps);
	fprintf(f, "keymap = %s\n", L->d.keymap[0] ? L->d.keymap : "us");
	fprintf(f, "view-key = %s\n", key ? key : "KEY_F2");
	fprintf(f, "screen = %dx%d\n", L->d.screen_w, L->d.screen_h);
	fprintf(f, "pointer-gain = %.17g\n", L->pointer_gain > 0 ? L->pointer_gain : 1.0);
	fprintf(f, "bindings = bindings\n");
	/* the bindings as they are now (`bind` may have changed the file's) */
	char path[TAPE_PATH_MAX + 64];
	snprintf(path, sizeof path, "%s/bindings", dir);
	FILE *b = fopen(path, "wx");
	int bad = !b || dial_bind_write(b, &L->dials.table) < 0;
	if (b && fclose(b) != 0)
		bad = 1;
	if (!bad && L->d.panel && cfg->panel_map) {
		size_t n;
		char *map = statefile_read(cfg->panel_map, &n);
		snprintf(path, sizeof path, "%s/panel.map", dir);
		bad = !map || statefile_write(path, map, n) < 0;
		free(map);
		fprintf(f, "panel = panel.map\n");
	}
	/* the shipped figures come along: a replay elsewhere finds them in the recording */
	if (!bad && cfg->library_dir) {
		bad = copy_library(cfg->library_dir, dir) < 0;
		fprintf(f, "library = library\n");
	}
	if (fclose(f) != 0 || bad) {
		snprintf(err, errlen, "%s: %s", dir, strerror(errno ? errno : EIO));
		free(text);
		return NULL;
	}
	return text;
}

/* why the kiosk cannot start a recording now (its state is not all in the session), or NULL */
const char *
loop_kiosk_busy(const struct loop *L)
{
	const struct modes *M = &L->modes;
	if (M->interact.mode != INTERACT_NONE)
		return "a mode is active at the kiosk (ESC ends it)";
	if (L->d.step.open)
		return "a step is under way at the kiosk";
	if (M->prompt.active)
		return "a command is asking for its arguments at the kiosk";
	if (menu_is_open(&M->menu))
		return "the kiosk's menu is open";
	if (M->kiosk && editline_text(kiosk_line(M->kiosk))[0])
		return "the kiosk's edit line holds text";
	return NULL;
}

int
loop_record(struct daemon *d, const char *dir, char *err, size_t errlen)
{
	struct loop *L = d->loop;
	if (!dir) {
		if (L->tape.mode != TAPE_RECORD) {
			snprintf(err, errlen, "not recording");
			return -1;
		}
		tape_dev_detach(&L->tape, &L->input);
		if (tape_record_stop(&L->tape) < 0) {
			snprintf(err, errlen, "the recording could not be written whole (see the log)");
			return -1;
		}
		return 0;
	}
	const char *busy = loop_kiosk_busy(L);
	if (busy) {
		snprintf(err, errlen, "%s", busy);
		return -1;
	}
	if (L->tape.mode != TAPE_OFF) {
		snprintf(err, errlen, "already %s %s",
			 L->tape.mode == TAPE_RECORD ? "recording into" : "replaying", L->tape.dir);
		return -1;
	}
	/* the input taken first: a recording starts with nothing queued */
	loop_take_input(L);
	/*
	 * The live state made exactly what a replay loads: what the session does
	 * not hold (a solver's warm start, a behaviour's timers) starts afresh in both.
	 */
	size_t len;
	char *text = daemon_session_text(d, &len);
	if (!text || daemon_replace_env(d, text, len, err, errlen) < 0) {
		if (!text)
			snprintf(err, errlen, "out of memory");
		free(text);
		return -1;
	}
	free(text);
	if (d->picked.fig >= 0 && d->picked.fig < ENV_MAX_FIGURES)
		d->picked.gen = d->env.fig[d->picked.fig].gen;
	modes_sync(&L->modes);
	char *config = NULL;
	if (tape_record_start(&L->tape, dir, d, NULL, err, errlen) < 0)
		return -1;
	if (!(config = config_text(L, dir, err, errlen))) {
		tape_record_stop(&L->tape);
		return -1;
	}
	char path[TAPE_PATH_MAX + 64];
	snprintf(path, sizeof path, "%s/config", dir);
	int rc = statefile_write(path, config, strlen(config));
	free(config);
	if (rc < 0) {
		snprintf(err, errlen, "%s: %s", path, strerror(errno));
		tape_record_stop(&L->tape);
		return -1;
	}
	tape_dev_attach(&L->tape, &L->input, &L->devs);
	fprintf(stderr, "postured: recording into %s\n", dir);
	return 0;
}

int
loop_recording(struct daemon *d, const char **dir, uint64_t counts[3])
{
	struct loop *L = d->loop;
	if (L->tape.mode != TAPE_RECORD)
		return 0;
	*dir = L->tape.dir;
	counts[0] = L->tape.frames;
	counts[1] = L->tape.lines;
	counts[2] = L->tape.waits;
	return 1;
}

void
loop_record_end(struct loop *L)
{
	if (L->tape.mode == TAPE_RECORD) {
		tape_dev_detach(&L->tape, &L->input);
		tape_record_stop(&L->tape);
	}
}
