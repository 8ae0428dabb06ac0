/* cmd_state.c - files, undo and redo, settling, status and subscriptions */
#include <inttypes.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/assess_live.h"
#include "daemon/loads_live.h"
#include "daemon/cmd_ctx.h"
#include "draw/frame_writer.h"
#include "draw/kms_pick.h"
#include "daemon/posture_hash.h"
#include "daemon/session.h"
#include "daemon/statefile.h"

#define POSTURED_VERSION "0.3"

int
cmd_save_posture(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]);
	char path[4096];
	if (fig < 0 || cmd_path(c, c->argv[1], 1, path, sizeof path) < 0)
		return -1;
	char *buf = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&buf, &len);
	if (!f)
		return cmd_fail(c, "internal", "out of memory");
	session_write_posture(&c->d->env, fig, f);
	fclose(f);
	int rc = statefile_write(path, buf, len);
	free(buf);
	if (rc < 0)
		return cmd_fail(c, "io", "%.60s: %s", c->argv[1], strerror(errno));
	json_object_set_new(c->result, "path", json_string(c->argv[1]));
	return 0;
}

int
cmd_load_posture(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]);
	size_t len;
	char *text = fig < 0 ? NULL : cmd_read_file(c, c->argv[1], &len);
	if (!text)
		return -1;
	char err[300];
	int rc = session_read_posture(&c->d->env, fig, text, len, err, sizeof err);
	free(text);
	if (rc < 0)
		return cmd_fail(c, "bad-file", "%.60s: %s", c->argv[1], err);
	c->d->env.fig[fig].ik_stale = 1; /* the root may have changed */
	return 0;
}

int
cmd_save_session(struct cmd_ctx *c)
{
	char path[4096];
	if (cmd_path(c, c->argv[0], 1, path, sizeof path) < 0)
		return -1;
	size_t len;
	char *text = daemon_session_text(c->d, &len);
	if (!text)
		return cmd_fail(c, "internal", "out of memory");
	int rc = statefile_write(path, text, len);
	free(text);
	if (rc < 0)
		return cmd_fail(c, "io", "%.60s: %s", c->argv[0], strerror(errno));
	json_object_set_new(c->result, "path", json_string(c->argv[0]));
	return 0;
}

/* replaces the environment with one read from text; nothing changes on error */
static int
replace_env(struct cmd_ctx *c, const char *text, size_t len, const char *what)
{
	char err[300];
	if (daemon_replace_env(c->d, text, len, err, sizeof err) < 0)
		return cmd_fail(c, "bad-file", "%s: %s", what, err);
	return 0;
}

int
cmd_load_session(struct cmd_ctx *c)
{
	size_t len;
	char *text = cmd_read_file(c, c->argv[0], &len);
	if (!text)
		return -1;
	int rc = replace_env(c, text, len, c->argv[0]);
	free(text);
	return rc;
}

/* pops from one stack onto the other: undo and redo are mirror images */
static int
step_history(struct cmd_ctx *c, struct checkpoints *from, struct checkpoints *to, const char *what)
{
	if (!from->n)
		return cmd_fail(c, "nothing", "nothing to %s", what);
	size_t now_len;
	char *now = daemon_session_text(c->d, &now_len);
	if (!now)
		return cmd_fail(c, "internal", "out of memory");
	int top = from->n - 1;
	if (replace_env(c, from->text[top], from->len[top], what) < 0) {
		free(now);
		return -1;
	}
	free(from->text[top]);
	from->n--;
	daemon_checkpoints_push(to, now, now_len);
	json_object_set_new(c->result, from == &c->d->undo ? "undone" : "redone", json_true());
	json_object_set_new(c->result, "remaining", json_integer(from->n));
	return 0;
}

int
cmd_undo(struct cmd_ctx *c)
{
	return step_history(c, &c->d->undo, &c->d->redo, "undo");
}

int
cmd_redo(struct cmd_ctx *c)
{
	return step_history(c, &c->d->redo, &c->d->undo, "redo");
}

int
cmd_settle(struct cmd_ctx *c)
{
	double frames = 600;
	const char *f = cmd_key(c, "frames");
	if (c->argc && !f)
		return cmd_fail(c, "bad-argument", "unexpected '%.60s'", c->argv[0]);
	if (f && words_number(f, UNIT_NONE, &frames) < 0)
		return cmd_fail(c, "bad-number", "frames: a whole number");
	if (frames < 1 || frames > 100000 || frames != (int)frames)
		return cmd_fail(c, "bad-argument", "frames: a whole number from 1 to 100000");
	if (!c->d->run_frame)
		return cmd_fail(c, "internal", "no frame loop to settle with");
	int n = 0, changed = 1;
	/* a few quiet frames in a row: the posture has stopped changing */
	for (int quiet = 0; n < (int)frames && quiet < 3; n++) {
		if (c->d->run_frame(c->d, &changed) < 0)
			return cmd_fail(c, "internal", "the frame failed");
		quiet = changed ? 0 : quiet + 1;
	}
	json_object_set_new(c->result, "frames", json_integer(n));
	json_object_set_new(c->result, "settled", json_boolean(!changed));
	/* where every constraint stands: metres and radians from its goal */
	struct env *e = &c->d->env;
	json_t *res = json_array();
	for (int i = 0; i < ENV_MAX_CONSTRAINTS; i++) {
		struct env_constraint *k = &e->con[i];
		if (!k->gen)
			continue;
		struct env_figure *fg = &e->fig[k->fig];
		env_sync_solver(e, k->fig);
		double pe, oe;
		ik_constraint_error(fg->ik, fg->model, fg->state, env_solver_index(e, i), &pe, &oe);
		json_t *o = json_object();
		json_object_set_new(o, "name", json_string(k->name));
		json_object_set_new(o, "pos_error", json_real(pe));
		json_object_set_new(o, "ori_error", json_real(oe));
		json_array_append_new(res, o);
	}
	json_object_set_new(c->result, "residuals", res);
	return 0;
}

static int
by_value(const void *a, const void *b)
{
	uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
	return (x > y) - (x < y);
}

/* input to pixels on the framebuffer, over the newest frames that showed input; null: none */
static json_t *
latency(struct daemon *d)
{
	static uint64_t v[FRAME_WRITER_LATENCIES]; /* the loop is single-threaded */
	int n = d->input_latencies ? d->input_latencies(d, v, FRAME_WRITER_LATENCIES) : 0;
	if (n <= 0)
		return json_null();
	qsort(v, (size_t)n, sizeof *v, by_value);
	return json_pack("{sfsfsfsi}", "median", (double)v[n / 2] / 1000,
			 "p99", (double)v[(n * 99) / 100] / 1000, "max", (double)v[n - 1] / 1000,
			 "n", n);
}

/* finished render to flip request on a KMS screen, us, over its newest frames; null: none */
static json_t *
flip_times(struct daemon *d)
{
	struct kms_times_summary t;
	if (!d->flip_times || d->flip_times(d, &t) < 0 || !t.n)
		return json_null();
	return json_pack("{sIsIsIsIsIsIsI}", "median", (json_int_t)t.median.total, "p99",
			 (json_int_t)t.p99.total, "queue", (json_int_t)t.median.queue, "wait",
			 (json_int_t)t.median.wait, "copy", (json_int_t)t.median.copy, "ioctl",
			 (json_int_t)t.median.ioctl, "n", (json_int_t)t.n);
}

int
cmd_status(struct cmd_ctx *c)
{
	const struct daemon_stats *s = &c->d->stats;
	json_object_set_new(c->result, "version", json_string(POSTURED_VERSION));
	json_object_set_new(c->result, "frame", json_integer((json_int_t)s->frame));
	char hash[24];
	snprintf(hash, sizeof hash, "%016" PRIx64, posture_env_hash(&c->d->env));
	json_object_set_new(c->result, "posture", json_string(hash)); /* as a replay prints it */
	json_object_set_new(c->result, "fps", json_real(s->fps));
	json_object_set_new(c->result, "ik_us", json_real(s->ik_us));
	json_object_set_new(c->result, "draw_us", json_real(s->draw_us));
	json_object_set_new(c->result, "stall_max_us", json_integer((json_int_t)s->stall_max_us));
	json_object_set_new(c->result, "stall_cpu_max_us",
			    json_integer((json_int_t)s->stall_cpu_max_us));
	json_object_set_new(c->result, "frames_written", json_integer((json_int_t)s->frames_written));
	json_object_set_new(c->result, "frames_dropped", json_integer((json_int_t)s->frames_dropped));
	json_object_set_new(c->result, "latency_ms", latency(c->d));
	json_object_set_new(c->result, "flip_us", flip_times(c->d));
	json_object_set_new(c->result, "budget_us", json_integer((json_int_t)s->budget_us));
	json_object_set_new(c->result, "clients", json_integer(s->clients));
	json_object_set_new(c->result, "figures", json_integer(env_count(&c->d->env)));
	json_object_set_new(c->result, "undo", json_integer(c->d->undo.n));
	json_object_set_new(c->result, "redo", json_integer(c->d->redo.n));
	/* the figures' assessments computed so far (a cached one counts none) */
	json_object_set_new(c->result, "assessments",
			    json_integer((json_int_t)assess_live_computed(c->d)));
	/* ... and their loads analyses */
	json_object_set_new(c->result, "load_analyses",
			    json_integer((json_int_t)loads_live_computed(c->d)));
	return 0;
}

static int
sub_kinds(struct cmd_ctx *c, unsigned *kinds)
{
	static const struct {
		const char *name;
		unsigned kind;
	} names[] = { { "posture", SUB_POSTURE }, { "telemetry", SUB_TELEMETRY },
		      { "message", SUB_MESSAGE }, { "frame", SUB_FRAME },
		      { "stability", SUB_STABILITY }, { "alert", SUB_ALERT },
		      { "input", SUB_INPUT }, { "kiosk", SUB_KIOSK },
		      { "assessment", SUB_ASSESSMENT }, { "loads", SUB_LOADS } };
	for (size_t i = 0; i < sizeof names / sizeof *names; i++)
		if (!strcmp(c->argv[0], names[i].name)) {
			*kinds = names[i].kind;
			return 0;
		}
	return cmd_fail(c, "bad-argument",
			"events are posture, telemetry, message, frame, stability, alert, input, kiosk, "
			"assessment or loads");
}

static int
subscription(struct cmd_ctx *c, int on)
{
	unsigned kinds = 0;
	if (sub_kinds(c, &kinds) < 0)
		return -1;
	if (c->client < 0 || !c->d->subscribe)
		return cmd_fail(c, "bad-argument", "only a connected client can subscribe");
	return c->d->subscribe(c->d, c->client, kinds, on) < 0
		       ? cmd_fail(c, "internal", "subscription failed")
		       : 0;
}

int
cmd_subscribe(struct cmd_ctx *c)
{
	return subscription(c, 1);
}

int
cmd_unsubscribe(struct cmd_ctx *c)
{
	return subscription(c, 0);
}

int
cmd_quit(struct cmd_ctx *c)
{
	c->quit = 1;
	return 0;
}
