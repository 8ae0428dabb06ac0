/*
 * cmd_ctx.h - what a command handler works with: its request (the daemon,
 * the client, the words after verb and object), the reply it builds, the
 * error it fails with, and the argument helpers every handler shares.
 * The dispatch (cmd.h) sits above the handlers; this sits below them.
 */
#ifndef POSTURE_CMD_CTX_H
#define POSTURE_CMD_CTX_H

#include <jansson.h>
#include <stddef.h>

#include "daemon/daemon.h"
#include "daemon/words.h"

struct cmd_ctx {
	struct daemon *d;
	int client;       /* the requesting client; DAEMON_CLIENT_JOURNAL, DAEMON_CLIENT_KIOSK */
	int argc;         /* words after verb and object */
	char **argv;
	json_t *result;   /* the handler's result object */
	const char *code; /* error code when a handler fails */
	char msg[512];
	int quit;         /* the client asked to close */
	int unchanged;    /* a mutating command that, this time, changed nothing: no undo step */
};

/* every handler of proto/commands.def: 0, or cmd_fail(...) */
#define CMD(verb, obj, mn, mx, fl, fn, usage, reply, summary) int fn(struct cmd_ctx *);
#include "proto/commands.def"
#undef CMD

/* sets the error code and message; returns -1, for "return cmd_fail(...)" */
int cmd_fail(struct cmd_ctx *c, const char *code, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* shared argument helpers for handlers */
int cmd_figure(struct cmd_ctx *c, const char *ref);       /* slot or -1 with the error set */
/*
 * The figures a word names: a figure, or "family=PREFIX" every member of
 * that family, into slot; returns how many (1 for a figure), or -1 with the
 * error set. *family gets the prefix for a family, else NULL.
 */
int cmd_figures(struct cmd_ctx *c, const char *word, int slot[ENV_MAX_FIGURES],
		const char **family);
int cmd_constraint(struct cmd_ctx *c, const char *ref);   /* slot or -1 */
int cmd_load_ref(struct cmd_ctx *c, const char *ref);     /* a load's slot or -1 */
int cmd_side(struct cmd_ctx *c, const char *w);          /* left 0, right 1, or -1 */
/*
 * A reach's words (can reach, reach, analyze reach): hand=left|right
 * (required) into *side, mode=arm|torso|body into *mode (enum reach_mode;
 * left as given when absent), balance=on|off into *balance (1 when absent;
 * for mode=body only). 0, or -1 with the error set.
 */
int cmd_reach_words(struct cmd_ctx *c, int *side, int *mode, int *balance);
/* a reach mode's word: "arm", "torso", "body" */
const char *cmd_reach_mode_name(int mode);
const char *cmd_key(struct cmd_ctx *c, const char *key);  /* "key=value" among the args */
/* path inside the state directory: 0 with the full path in dest, or -1 with the error set */
int cmd_path(struct cmd_ctx *c, const char *rel, int for_write, char *dest, size_t len);
/* its checks of the words alone (relative, no ".."), which need no disk: 0, or -1 with the error set */
int cmd_path_words(struct cmd_ctx *c, const char *rel);
json_t *cmd_vec(const double *v, int n);
/* "as NAME" among the arguments: the name, NULL when absent; *bad with the error set */
const char *cmd_as_name(struct cmd_ctx *c, int *bad);
/* a figure added to slot (or env_add_figure's error): its id and name in the reply; 0 or -1 */
int cmd_added(struct cmd_ctx *c, int slot, const char *name);
/*
 * A state file's text, malloc'd (the caller frees it): from the disk, or on
 * recovery the text the journal recorded when the command first ran, or in
 * a replay what the recording kept; a copy is kept for the journal
 * (daemon.h, file_read). NULL with the error set.
 */
char *cmd_read_file(struct cmd_ctx *c, const char *rel, size_t *len);
/* a figure's hands and feet held to other figures, as a list */
json_t *cmd_attachments(const struct env *e, int fig);
/* "rot=AXIS,ANGLE" (AXIS x, y, z or X,Y,Z) or "yaw=ANGLE" among the args; *given 0 when neither */
int cmd_rotation(struct cmd_ctx *c, double r[9], int *given);

/*
 * The JSON text a handler wrote without allocating (an assessment, an
 * analysis) parsed and its keys added to dest: 0, or -1 with the error set
 * (the text overflowed its buffer, or is not an object)
 */
struct jbuf;
int cmd_merge_json(struct cmd_ctx *c, json_t *dest, const struct jbuf *j);

#endif
