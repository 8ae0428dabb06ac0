/*
 * cmd.h - the command table (proto/commands.def) and its dispatch: one
 * request line in, one JSON reply out.
 */
#ifndef POSTURE_CMD_H
#define POSTURE_CMD_H

#include <jansson.h>
#include <stddef.h>

#include "daemon/daemon.h"
#include "daemon/words.h"

enum cmd_flags {
	CMD_MUTATES = 1 << 0,
	CMD_FILE = 1 << 1,
	CMD_SLOW = 1 << 2,
};

struct cmd_ctx {
	struct daemon *d;
	int client;       /* the requesting client, -1 for the journal and tools */
	int argc;         /* words after verb and object */
	char **argv;
	json_t *result;   /* the handler's result object */
	const char *code; /* error code when a handler fails */
	char msg[512];
	int quit;         /* the client asked to close */
};

/* handlers return 0, or cmd_fail(...) */
/* every handler of proto/commands.def: 0, or cmd_fail(...) */
#define CMD(verb, obj, mn, mx, fl, fn, usage, reply, summary) int fn(struct cmd_ctx *);
#include "proto/commands.def"
#undef CMD

int cmd_fail(struct cmd_ctx *c, const char *code, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* the outcome of one request */
struct cmd_outcome {
	int reply;    /* 0: blank or comment, nothing to send */
	int ok;
	int mutated;  /* ok and the command changes state: journal it */
	int close;    /* close the connection after the reply (quit, too-long, binary) */
	char *json;   /* the reply line, malloc'd, no newline */
};

/*
 * Runs one request line (without its newline). Never fails as a whole: a
 * bad line gives an error reply. out->json must be freed by the caller.
 */
void cmd_run(struct daemon *d, int client, const char *line, size_t len, struct cmd_outcome *out);

/* prints the markdown table of commands (for PROTOCOL.md) */
void cmd_print_table(FILE *f);

/* shared argument helpers for handlers */
int cmd_figure(struct cmd_ctx *c, const char *ref);       /* slot or -1 with the error set */
int cmd_constraint(struct cmd_ctx *c, const char *ref);   /* slot or -1 */
int cmd_side(struct cmd_ctx *c, const char *w);          /* left 0, right 1, or -1 */
const char *cmd_key(struct cmd_ctx *c, const char *key);  /* "key=value" among the args */
/* path inside the state directory: 0 with the full path in dest, or -1 with the error set */
int cmd_path(struct cmd_ctx *c, const char *rel, int for_write, char *dest, size_t len);
json_t *cmd_vec(const double *v, int n);
/* a figure's hands and feet held to other figures, as a list (cmd_attach.c) */
json_t *cmd_attachments(const struct env *e, int fig);
/* "rot=AXIS,ANGLE" (AXIS x, y, z or X,Y,Z) or "yaw=ANGLE" among the args; *given 0 when neither */
int cmd_rotation(struct cmd_ctx *c, double r[9], int *given);

#endif
