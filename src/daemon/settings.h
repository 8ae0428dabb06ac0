/*
 * settings.h - postured's settings: its long options, given as flags or as
 * the config file's "key = value" lines (--config). A bad setting is said
 * on stderr ("postured: ...", then the file and line it came from).
 */
#ifndef POSTURE_SETTINGS_H
#define POSTURE_SETTINGS_H

#include <limits.h>
#include <stdio.h>

#include "devices/input_devs.h"

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

/* one setting by its long option's name: 0, or -1 said on stderr */
int settings_set(struct settings *s, const char *key, const char *val);

/* the config file's lines from f, path naming it: 0, or -1 said on stderr (the first bad line) */
int settings_read(struct settings *s, FILE *f, const char *path);

/* the same from the file at path */
int settings_read_file(struct settings *s, const char *path);

#endif
