/*
 * cmd.h - the command table (proto/commands.def) and its dispatch: one
 * request line in, one JSON reply out. The handlers it calls work through
 * cmd_ctx.h, below it.
 */
#ifndef POSTURE_CMD_H
#define POSTURE_CMD_H

#include <stddef.h>
#include <stdio.h>

#include "daemon/daemon.h"

enum cmd_flags {
	CMD_MUTATES = 1 << 0,
	CMD_FILE = 1 << 1,
	CMD_SLOW = 1 << 2,
	CMD_NO_UNDO = 1 << 3, /* journaled, not an undo step (the daemon's data: populations) */
};

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

/*
 * The table's entries one by one, for completion and menus: 0 .. n-1 give
 * the verb, the object ("" for none) and the usage; NULL past the end.
 */
const char *cmd_entry_verb(int i);
const char *cmd_entry_object(int i);
const char *cmd_entry_usage(int i);

/* the usage of the command a line starts with (its verb, and object if it has one); NULL */
const char *cmd_usage_of_line(const char *line);

/* prints the markdown table of commands (for docs/protocol.md) */
void cmd_print_table(FILE *f);

#endif
