/* cmd.c - dispatch of request lines through the command table */
#include "daemon/cmd.h"

#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "daemon/cmd_ctx.h"
#include "daemon/envelopes.h"
#include "daemon/session.h"

typedef int (*cmd_handler)(struct cmd_ctx *);

struct cmd_entry {
	const char *verb, *object;
	int min_args, max_args, flags;
	cmd_handler fn;
	const char *usage, *reply, *summary;
};

static const struct cmd_entry table[] = {
#define CMD(verb, obj, mn, mx, fl, fn, usage, reply, summary) \
	{ verb, obj, mn, mx, fl, fn, usage, reply, summary },
#include "proto/commands.def"
#undef CMD
};

#define NCMD ((int)(sizeof table / sizeof *table))

const char *
cmd_entry_verb(int i)
{
	return i >= 0 && i < NCMD ? table[i].verb : NULL;
}

const char *
cmd_entry_object(int i)
{
	return i >= 0 && i < NCMD ? table[i].object : NULL;
}

const char *
cmd_entry_usage(int i)
{
	return i >= 0 && i < NCMD ? table[i].usage : NULL;
}

const char *
cmd_usage_of_line(const char *line)
{
	char verb[32] = "", object[32] = "";
	if (sscanf(line, "%31s %31s", verb, object) < 1)
		return NULL;
	const char *bare = NULL;
	for (int i = 0; i < NCMD; i++) {
		if (strcmp(table[i].verb, verb))
			continue;
		if (!table[i].object[0])
			bare = table[i].usage;
		else if (!strcmp(table[i].object, object))
			return table[i].usage;
	}
	return bare;
}

/* the table entry for the words, or NULL with the error set */
static const struct cmd_entry *
lookup(struct cmd_ctx *c, const struct words *w, int *first_arg)
{
	int verb_known = 0;
	for (int i = 0; i < NCMD; i++) {
		const struct cmd_entry *e = &table[i];
		if (strcmp(e->verb, w->w[0]))
			continue;
		verb_known = 1;
		if (!e->object[0]) {
			*first_arg = 1;
			return e;
		}
		if (w->n > 1 && !strcmp(e->object, w->w[1])) {
			*first_arg = 2;
			return e;
		}
	}
	if (!verb_known) {
		cmd_fail(c, "unknown-command", "unknown command '%.60s' (try 'help')", w->w[0]);
		return NULL;
	}
	char objs[256] = "";
	for (int i = 0; i < NCMD; i++)
		if (!strcmp(table[i].verb, w->w[0]) && strlen(objs) + strlen(table[i].object) + 3 < sizeof objs)
			strcat(strcat(objs, objs[0] ? ", " : ""), table[i].object);
	cmd_fail(c, "unknown-command", "'%.60s' takes one of: %s", w->w[0], objs);
	return NULL;
}

/* 1 when word (or what follows its '=', or what precedes its first '.') names figure slot fig */
static int
names_figure(const struct env *e, const char *word, int fig)
{
	const char *eq = strchr(word, '=');
	const char *w = eq ? eq + 1 : word;
	char head[MODEL_NAME_MAX];
	int slot = env_find_figure(e, w);
	if (slot < 0) {
		const char *dot = strchr(w, '.');
		size_t n = dot ? (size_t)(dot - w) : 0;
		if (n && n < sizeof head) {
			memcpy(head, w, n);
			head[n] = '\0';
			slot = env_find_figure(e, head);
		}
	}
	if (slot < 0 && (slot = env_find_constraint(e, w)) >= 0)
		slot = e->con[slot].fig;
	if (slot < 0 && (slot = env_find_load(e, w)) >= 0)
		slot = e->load[slot].fig;
	return slot == fig;
}

/*
 * The busy rule: while the kiosk is in a step (a drag under
 * way), a client's change to the figure it moves is refused, with the
 * kiosk's mode named, and so is any change of the whole environment
 * (undo, redo, a session loaded); reads, events and other figures go on.
 * A step that names no figure (the dials turning, outside a mode) still
 * ends as one undo, so the whole environment waits for it too: an undo in
 * the middle took back the step before it and lost the turn.
 */
static int
busy_with_step(struct daemon *d, const struct cmd_entry *e, struct cmd_ctx *c)
{
	const struct daemon_step *st = &d->step;
	if (!st->open)
		return 0;
	int whole = e->fn == cmd_undo || e->fn == cmd_redo || e->fn == cmd_load_session;
	if (st->fig < 0 || st->fig >= ENV_MAX_FIGURES || d->env.fig[st->fig].gen != st->gen) {
		if (!whole)
			return 0;
		snprintf(c->msg, sizeof c->msg,
			 "the kiosk is in a step (%s mode, the dials turning or a button held): a "
			 "change of the whole environment waits until it ends", st->mode);
		return 1;
	}
	const char *name = d->env.fig[st->fig].name;
	int touches = whole;
	for (int i = 0; i < c->argc && !touches; i++)
		touches = names_figure(&d->env, c->argv[i], st->fig);
	if (!touches)
		return 0;
	snprintf(c->msg, sizeof c->msg,
		 "the kiosk is moving %s (%s mode, a button held or the dials turning): %s waits "
		 "until the step ends",
		 name, st->mode, whole ? "a change of the whole environment" : "a change to it");
	return 1;
}

static char *
dump_reply(int ok, const char *tag, json_t *result, const char *code, const char *msg)
{
	json_t *r = json_object();
	json_object_set_new(r, "ok", json_boolean(ok));
	if (tag && tag[0])
		json_object_set_new(r, "tag", json_string(tag));
	if (ok) {
		json_object_set_new(r, "result", result ? result : json_object());
	} else {
		json_t *e = json_object();
		json_object_set_new(e, "code", json_string(code));
		/* messages quote client text: keep them valid UTF-8 for JSON */
		json_t *m = json_string(msg);
		json_object_set_new(e, "message", m ? m : json_string("(message not valid UTF-8)"));
		json_object_set_new(r, "error", e);
		json_decref(result);
	}
	char *s = json_dumps(r, JSON_COMPACT | JSON_REAL_PRECISION(17));
	json_decref(r);
	return s;
}

/* bytes a request may not hold (docs/protocol.md Framing) */
static int
has_control_bytes(const char *line, size_t len)
{
	for (size_t i = 0; i < len; i++) {
		unsigned char b = (unsigned char)line[i];
		if ((b < 0x20 && b != '\t') || b == 0x7f)
			return 1;
	}
	return 0;
}

void
cmd_run(struct daemon *d, int client, const char *line, size_t len, struct cmd_outcome *out)
{
	static struct words w; /* 64 KiB: not on the stack; the loop is single-threaded */
	struct cmd_ctx c = { .d = d, .client = client };
	const char *msg;
	memset(out, 0, sizeof *out);
	daemon_text_clear(&d->file_read); /* the last command's, journaled by now */
	d->journal_as[0] = '\0';
	if (len && line[len - 1] == '\r')
		len--;
	out->reply = 1;
	if (len > WORDS_LINE_MAX) {
		out->close = 1;
		out->json = dump_reply(0, NULL, NULL, "too-long", "line longer than 65536 bytes");
		return;
	}
	if (has_control_bytes(line, len)) {
		out->close = 1;
		out->json = dump_reply(0, NULL, NULL, "binary", "control bytes in a request line");
		return;
	}
	switch (words_split(line, len, &w, &msg)) {
	case WORDS_EMPTY:
		out->reply = 0;
		return;
	case WORDS_PARSE:
		out->json = dump_reply(0, w.tag, NULL, "parse", msg);
		return;
	case WORDS_TOO_MANY:
		out->json = dump_reply(0, w.tag, NULL, "arity", msg);
		return;
	case WORDS_OK:
		break;
	}
	for (int i = 0; i < w.n; i++)
		if (w.w[i][0] == '=') {
			out->json = dump_reply(0, w.tag, NULL, "parse", "an argument with an empty key");
			return;
		}
	int first = 1;
	const struct cmd_entry *e = lookup(&c, &w, &first);
	if (!e) {
		out->json = dump_reply(0, w.tag, NULL, c.code, c.msg);
		return;
	}
	c.argc = w.n - first;
	c.argv = w.w + first;
	if (c.argc < e->min_args || c.argc > e->max_args) {
		out->json = dump_reply(0, w.tag, NULL, "arity", e->usage);
		return;
	}
	if (c.client >= 0 && (e->flags & CMD_MUTATES) && busy_with_step(d, e, &c)) {
		out->json = dump_reply(0, w.tag, NULL, "busy", c.msg);
		return;
	}
	/* a checkpoint for undo, taken before the change */
	char *before = NULL;
	size_t before_len = 0;
	/* the daemon's own lines inside a step (change view's camera) are part of its one undo */
	int checkpoint = (e->flags & CMD_MUTATES) && !(e->flags & CMD_NO_UNDO) && e->fn != cmd_undo &&
			 e->fn != cmd_redo &&
			 !(client == DAEMON_CLIENT_JOURNAL && d->step.open);
	if (checkpoint && !(before = daemon_session_text(d, &before_len))) {
		out->json = dump_reply(0, w.tag, NULL, "internal", "out of memory");
		return;
	}
	c.result = json_object();
	int rc = e->fn(&c);
	if (d->envelopes) /* a figure gone (unload, undo, a session): its envelopes too */
		envelopes_prune(d->envelopes, &d->env);
	if (rc == 0 && checkpoint && !c.unchanged) {
		daemon_checkpoints_push(&d->undo, before, before_len);
		daemon_checkpoints_clear(&d->redo);
		before = NULL;
	}
	free(before);
	out->ok = rc == 0;
	out->mutated = rc == 0 && (e->flags & CMD_MUTATES);
	d->mutations += out->mutated;
	out->close = c.quit;
	out->json = dump_reply(rc == 0, w.tag, c.result, c.code ? c.code : "internal", c.msg);
}

/* a table cell: '|' would end the cell early in markdown */
static void
cell(FILE *f, const char *s)
{
	for (; *s; s++) {
		if (*s == '|')
			fputc('\\', f);
		fputc(*s, f);
	}
}

void
cmd_print_table(FILE *f)
{
	fprintf(f, "| command | mutates | reply | what it does |\n|---|---|---|---|\n");
	for (int i = 0; i < NCMD; i++) {
		fprintf(f, "| `");
		cell(f, table[i].usage);
		fprintf(f, "` | %s | `", table[i].flags & CMD_MUTATES ? "yes" : "");
		cell(f, table[i].reply);
		fprintf(f, "` | %s |\n", table[i].summary);
	}
}

int
cmd_help(struct cmd_ctx *c)
{
	json_t *list = json_array();
	for (int i = 0; i < NCMD; i++) {
		const struct cmd_entry *e = &table[i];
		if (c->argc >= 1 && strcmp(e->verb, c->argv[0]))
			continue;
		if (c->argc == 2 && strcmp(e->object, c->argv[1]))
			continue;
		json_t *o = json_object();
		json_object_set_new(o, "usage", json_string(e->usage));
		json_object_set_new(o, "summary", json_string(e->summary));
		json_object_set_new(o, "reply", json_string(e->reply));
		json_object_set_new(o, "mutates", json_boolean(e->flags & CMD_MUTATES));
		json_array_append_new(list, o);
	}
	if (!json_array_size(list)) {
		json_decref(list);
		return cmd_fail(c, "unknown-command", "no command '%.60s'", c->argv[0]);
	}
	json_object_set_new(c->result, "commands", list);
	return 0;
}
