/*
 * cmd_ctx.c - what every handler shares: the error it fails with, and the
 * helpers that read its arguments and build parts of its reply.
 */
#include "daemon/cmd_ctx.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "daemon/family.h"
#include "daemon/jbuf.h"
#include "daemon/statefile.h"
#include "daemon/words.h"
#include "pose/attach.h"
#include "pose/reach.h"

int
cmd_fail(struct cmd_ctx *c, const char *code, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(c->msg, sizeof c->msg, fmt, ap);
	va_end(ap);
	c->code = code;
	return -1;
}

static int
resolve_error(struct cmd_ctx *c, int err, const char *what, const char *ref)
{
	if (err == ENV_STALE)
		return cmd_fail(c, "stale-id", "%s id '%.60s' is stale: what it named is gone", what, ref);
	return cmd_fail(c, "not-found", "no %s '%.60s'", what, ref);
}

int
cmd_side(struct cmd_ctx *c, const char *w)
{
	if (!strcmp(w, "left"))
		return 0;
	if (!strcmp(w, "right"))
		return 1;
	return cmd_fail(c, "bad-argument", "left or right, not '%.20s'", w);
}

static const char *const reach_modes[] = { "arm", "torso", "body" };

const char *
cmd_reach_mode_name(int mode)
{
	return mode >= REACH_ARM && mode <= REACH_BODY ? reach_modes[mode] : "?";
}

int
cmd_reach_words(struct cmd_ctx *c, int *side, int *mode, int *balance)
{
	const char *hand = cmd_key(c, "hand");
	if (!hand)
		return cmd_fail(c, "arity", "hand=left|right");
	if ((*side = cmd_side(c, hand)) < 0)
		return -1;
	const char *m = cmd_key(c, "mode");
	if (m) {
		int k = 0;
		while (k < 3 && strcmp(m, reach_modes[k]))
			k++;
		if (k == 3)
			return cmd_fail(c, "bad-argument", "mode=arm|torso|body");
		*mode = k;
	}
	const char *bal = cmd_key(c, "balance");
	if (bal && strcmp(bal, "on") && strcmp(bal, "off"))
		return cmd_fail(c, "bad-argument", "balance=on|off");
	if (bal && *mode != REACH_BODY)
		return cmd_fail(c, "bad-argument", "balance= is for mode=body (the arm and torso "
				"move nothing the feet carry)");
	*balance = !bal || !strcmp(bal, "on");
	return 0;
}

int
cmd_figure(struct cmd_ctx *c, const char *ref)
{
	int slot = env_find_figure(&c->d->env, ref);
	if (slot < 0)
		return resolve_error(c, slot, "figure", ref);
	return slot;
}

int
cmd_figures(struct cmd_ctx *c, const char *word, int slot[ENV_MAX_FIGURES], const char **family)
{
	*family = NULL;
	if (!words_is_key(word, "family"))
		return (slot[0] = cmd_figure(c, word)) < 0 ? -1 : 1;
	const char *prefix = word + strlen("family=");
	int n = prefix[0] ? family_members(&c->d->env, prefix, slot) : 0;
	if (!n)
		return cmd_fail(c, "not-found", "no family '%.60s' (load family PREFIX sex=... makes one)",
				prefix);
	*family = prefix;
	return n;
}

int
cmd_constraint(struct cmd_ctx *c, const char *ref)
{
	int slot = env_find_constraint(&c->d->env, ref);
	if (slot < 0)
		return resolve_error(c, slot, "constraint", ref);
	return slot;
}

int
cmd_load_ref(struct cmd_ctx *c, const char *ref)
{
	int slot = env_find_load(&c->d->env, ref);
	if (slot < 0)
		return resolve_error(c, slot, "load", ref);
	return slot;
}

const char *
cmd_key(struct cmd_ctx *c, const char *key)
{
	for (int i = 0; i < c->argc; i++)
		if (words_is_key(c->argv[i], key))
			return c->argv[i] + strlen(key) + 1;
	return NULL;
}

int
cmd_path_words(struct cmd_ctx *c, const char *rel)
{
	if (!rel[0] || rel[0] == '/')
		return cmd_fail(c, "denied", "paths are relative to the state directory");
	for (const char *p = rel; *p; p = strchr(p, '/') ? strchr(p, '/') + 1 : p + strlen(p))
		if (!strncmp(p, "..", 2) && (p[2] == '/' || !p[2]))
			return cmd_fail(c, "denied", "'..' may not appear in a path");
	return 0;
}

int
cmd_path(struct cmd_ctx *c, const char *rel, int for_write, char *dest, size_t len)
{
	if (for_write && c->d->files_read_only)
		return cmd_fail(c, "denied", "a replay writes no files");
	if (cmd_path_words(c, rel) < 0)
		return -1;
	char root[PATH_MAX], full[PATH_MAX], real[PATH_MAX];
	if (!realpath(c->d->state_dir, root))
		return cmd_fail(c, "io", "state directory: %s", strerror(errno));
	if ((size_t)snprintf(full, sizeof full, "%s/%s", root, rel) >= sizeof full || strlen(full) >= len)
		return cmd_fail(c, "bad-argument", "path too long");
	/* the file itself (reading) or its directory (writing) must resolve inside */
	char probe[PATH_MAX];
	snprintf(probe, sizeof probe, "%s", full);
	if (for_write) {
		char *slash = strrchr(probe, '/');
		*slash = 0;
		struct stat st;
		if (!lstat(full, &st) && S_ISLNK(st.st_mode))
			return cmd_fail(c, "denied", "'%.60s' is a symbolic link", rel);
	}
	if (!realpath(probe, real))
		return cmd_fail(c, "not-found", "'%.60s': %s", rel, strerror(errno));
	size_t n = strlen(root);
	if (strncmp(real, root, n) || (real[n] != '/' && real[n] != 0))
		return cmd_fail(c, "denied", "'%.60s' leads outside the state directory", rel);
	snprintf(dest, len, "%s", full);
	return 0;
}

json_t *
cmd_vec(const double *v, int n)
{
	json_t *a = json_array();
	for (int i = 0; i < n; i++)
		json_array_append_new(a, json_real(v[i]));
	return a;
}

int
cmd_rotation(struct cmd_ctx *c, double r[9], int *given)
{
	const char *rot = cmd_key(c, "rot"), *yaw = cmd_key(c, "yaw");
	double axis[3] = { 0, 1, 0 }, angle = 0, q[4];
	*given = rot || yaw;
	if (yaw && words_number(yaw, UNIT_ANGLE, &angle) < 0)
		return cmd_fail(c, "bad-number", "yaw: an angle such as 30deg");
	if (rot) {
		const char *comma = strrchr(rot, ',');
		char ax[128];
		if (!comma || (size_t)(comma - rot) >= sizeof ax ||
		    words_number(comma + 1, UNIT_ANGLE, &angle) < 0)
			return cmd_fail(c, "bad-argument", "rot=AXIS,ANGLE with AXIS x, y, z or X,Y,Z");
		memcpy(ax, rot, (size_t)(comma - rot));
		ax[comma - rot] = 0;
		if (strlen(ax) == 1 && strchr("xyz", ax[0])) {
			axis[0] = axis[1] = axis[2] = 0;
			axis[ax[0] - 'x'] = 1;
		} else if (words_list(ax, UNIT_NONE, 3, axis) < 0) {
			return cmd_fail(c, "bad-argument", "rot=AXIS,ANGLE with AXIS x, y, z or X,Y,Z");
		}
		double n = sqrt(mathx_dot(axis, axis));
		if (!(n > 1e-12))
			return cmd_fail(c, "bad-argument", "rot: the axis has no length");
		for (int i = 0; i < 3; i++)
			axis[i] /= n;
	}
	mathx_quat_axis_angle(axis, angle, q);
	mathx_quat_to_mat(q, r);
	return 0;
}

/* the figure's attachments, for get behavior */
json_t *
cmd_attachments(const struct env *e, int fig)
{
	json_t *list = json_array();
	for (int i = 0; i < ENV_MAX_ATTACH; i++) {
		const struct env_attach *a = &e->att[i];
		if (!a->used || a->fig != fig)
			continue;
		const struct env_figure *o = &e->fig[a->obj];
		json_t *j = json_object();
		json_object_set_new(j, "limb", json_string(a->limb == ATTACH_HAND ? "hand" : "foot"));
		json_object_set_new(j, "side", json_string(a->side ? "right" : "left"));
		json_object_set_new(j, "kind", json_string(a->kind == ATTACH_GRAB ? "grab" : "local"));
		json_object_set_new(j, "object", json_string(o->name));
		json_object_set_new(j, "segment", json_string(o->model->seg_name[a->seg]));
		json_array_append_new(list, j);
	}
	return list;
}

/* "as NAME" among the arguments; returns the name, NULL when absent, or sets an error */
const char *
cmd_as_name(struct cmd_ctx *c, int *bad)
{
	*bad = 0;
	for (int i = 0; i < c->argc; i++) {
		if (strcmp(c->argv[i], "as"))
			continue;
		if (i + 1 >= c->argc || !words_is_name(c->argv[i + 1])) {
			*bad = 1;
			cmd_fail(c, "bad-argument", "'as' takes a name: letters, digits, '_'");
			return NULL;
		}
		return c->argv[i + 1];
	}
	return NULL;
}

int
cmd_added(struct cmd_ctx *c, int slot, const char *name)
{
	if (slot == ENV_EXISTS)
		return cmd_fail(c, "exists", "a figure named '%s' exists", name ? name : "");
	if (slot < 0)
		return cmd_fail(c, "limit", "the environment holds %d figures at most", ENV_MAX_FIGURES);
	char id[32];
	env_figure_id(&c->d->env, slot, id);
	json_object_set_new(c->result, "figure", json_string(id));
	json_object_set_new(c->result, "name", json_string(c->d->env.fig[slot].name));
	return 0;
}

/*
 * A state file's text (the caller frees it): from the disk, or on recovery
 * the text the journal recorded when the command first ran, or in a replay
 * what the recording kept (d->read_state: the tape records each read and
 * how it failed, and answers them in a replay, whose state directory holds
 * none of the files). A copy is kept for the journal (daemon.h, file_read).
 */
char *
cmd_read_file(struct cmd_ctx *c, const char *rel, size_t *len)
{
	struct daemon *d = c->d;
	char path[4096];
	char *text = d->file_given.text;
	*len = d->file_given.len;
	d->file_given.text = NULL;
	if (!text) {
		if (cmd_path_words(c, rel) < 0)
			return NULL;
		const char *at = NULL; /* a replay's reads need no path: the recording answers */
		if (!d->files_read_only) {
			if (cmd_path(c, rel, 0, path, sizeof path) < 0) {
				errno = !strcmp(c->code, "denied") ? EACCES : ENOENT;
				if (d->read_state)
					d->read_state(d, NULL, len); /* recorded as failed */
				return NULL;
			}
			at = path;
		}
		text = d->read_state ? d->read_state(d, at, len) : statefile_read(at, len);
		if (!text) {
			cmd_fail(c, errno == ENOENT ? "not-found" : errno == EACCES ? "denied" : "bad-file",
				 "%.60s: %s", rel, strerror(errno));
			return NULL;
		}
	}
	daemon_text_clear(&d->file_read);
	if ((d->file_read.text = malloc(*len + 1))) {
		memcpy(d->file_read.text, text, *len + 1);
		d->file_read.len = *len;
	}
	return text;
}

int
cmd_merge_json(struct cmd_ctx *c, json_t *dest, const struct jbuf *j)
{
	if (j->overflow)
		return cmd_fail(c, "internal", "the reply did not fit its buffer");
	json_error_t e;
	json_t *o = json_loadb(j->buf, j->len, 0, &e);
	if (!o || !json_is_object(o)) {
		json_decref(o);
		return cmd_fail(c, "internal", "the reply's JSON: %s", e.text);
	}
	json_object_update(dest, o);
	json_decref(o);
	return 0;
}
