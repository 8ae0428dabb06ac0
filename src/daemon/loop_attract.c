/*
 * loop_attract.c - the attract mode (`--attract DIR`): while nobody is at
 * the kiosk (no device input and no client line but questions for
 * --attract-after seconds), the recording DIR plays in a loop at its own
 * pace, through the loop's own code as a replay does; the first real input
 * ends it and the state comes back as it was. The journal is off while it
 * plays: a crash mid-demo comes back to the real state.
 */
#include "daemon/loop_state.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/tape_dev.h"
#include "daemon/tape_read.h"

/* what a client may ask while the demo plays, without ending it */
static int
is_question(const char *line, size_t len)
{
	static const char *const verbs[] = { "get", "list", "status", "help", "show",
					     "subscribe", "unsubscribe", "pick", "render" };
	while (len && (*line == ' ' || *line == '\t'))
		line++, len--;
	if (len && *line == '#') { /* a tag: "#TAG verb ..." */
		while (len && *line != ' ')
			line++, len--;
		while (len && *line == ' ')
			line++, len--;
	}
	for (size_t k = 0; k < sizeof verbs / sizeof *verbs; k++) {
		size_t n = strlen(verbs[k]);
		if (len >= n && !memcmp(line, verbs[k], n) && (len == n || line[n] == ' '))
			return 1;
	}
	return 0;
}

/* the environment emptied, the undo history and the loaded populations with it */
static void
clear_state(struct daemon *d)
{
	populations_clear(&d->pops);
	env_clear(&d->env);
	env_init(&d->env);
	daemon_checkpoints_clear(&d->undo);
	daemon_checkpoints_clear(&d->redo);
}

/* the kiosk as nobody has touched it: no mode, prompt, menu, typed line or step */
static void
kiosk_idle(struct loop *L)
{
	interact_end(&L->modes.interact);
	prompt_cancel(&L->modes.prompt);
	(void)menu_close(&L->modes.menu);
	L->modes.menu_view = L->d.menu_view = -1;
	if (L->modes.kiosk)
		kiosk_clear(L->modes.kiosk);
	if (L->d.step.open)
		daemon_step_end(&L->d);
	modes_sync(&L->modes);
}

/* the recording (again) from its start: 0, or -1 (said) */
static int
lap(struct loop *L)
{
	char err[TAPE_PATH_MAX + 600], *config = NULL;
	tape_dev_free(&L->tape);
	tape_free(&L->tape);
	kiosk_idle(L);
	clear_state(&L->d);
	if (tape_replay_open(&L->tape, L->cfg->attract_dir, &L->d, &config, err, sizeof err) < 0) {
		fprintf(stderr, "postured: attract: %s\n", err);
		return -1;
	}
	free(config);
	modes_sync(&L->modes);
	L->scene.dirty = 1;
	const struct tape_entry *e = tape_peek(&L->tape);
	L->attract.t0_rec = e && e->kind == TAPE_FRAME ? e->t : 0;
	L->attract.t0_real = loop_real_now();
	L->attract.laps++;
	return 0;
}

static void
begin(struct loop *L)
{
	size_t len = 0;
	char *text = NULL;
	FILE *f = open_memstream(&text, &len);
	if (!f)
		return;
	int bad = journal_state_write(&L->d, f);
	if (fclose(f) != 0 || bad) {
		free(text);
		return;
	}
	L->attract.saved = text;
	L->attract.saved_len = len;
	L->attract.journal_fd = L->j.fd;
	L->attract.picked_fig = L->d.picked.fig;
	L->attract.picked_joint = L->d.picked.joint;
	L->attract.pointer_view = L->d.pointer_view;
	L->attract.pointer_x = L->d.pointer_x;
	L->attract.pointer_y = L->d.pointer_y;
	L->j.fd = -1; /* the demo is not the state: nothing of it journaled */
	L->attract.on = L->d.attracting = 1;
	L->attract.laps = 0;
	if (lap(L) < 0)
		loop_attract_end(L);
	else
		fprintf(stderr, "postured: attract: %s plays until someone comes\n", L->cfg->attract_dir);
}

int
loop_attract_check(struct loop *L, char *err, size_t errlen)
{
	struct daemon *d = calloc(1, sizeof *d);
	struct tape *t = calloc(1, sizeof *t);
	char *config = NULL;
	int rc = -1;
	if (d && t) {
		env_init(&d->env);
		snprintf(d->state_dir, sizeof d->state_dir, "%s", L->d.state_dir);
		snprintf(d->library_dir, sizeof d->library_dir, "%s", L->d.library_dir);
		rc = tape_replay_open(t, L->cfg->attract_dir, d, &config, err, errlen);
		free(config);
		tape_free(t);
		clear_state(d);
		env_clear(&d->env);
	} else {
		snprintf(err, errlen, "out of memory");
	}
	free(d);
	free(t);
	return rc;
}

void
loop_attract_end(struct loop *L)
{
	if (!L->attract.on)
		return;
	char err[512];
	tape_dev_free(&L->tape);
	tape_free(&L->tape);
	L->tape.mode = TAPE_OFF;
	kiosk_idle(L);
	clear_state(&L->d);
	if (journal_state_read(&L->d, L->attract.saved, L->attract.saved_len, err, sizeof err) < 0)
		fprintf(stderr, "postured: attract: the state before it did not come back: %s\n", err);
	free(L->attract.saved);
	L->attract.saved = NULL;
	L->j.fd = L->attract.journal_fd;
	L->d.picked.fig = L->attract.picked_fig;
	L->d.picked.joint = L->attract.picked_joint;
	L->d.picked.gen = L->d.picked.fig >= 0 && L->d.picked.fig < ENV_MAX_FIGURES
				  ? L->d.env.fig[L->d.picked.fig].gen : 0;
	L->d.pointer_view = L->attract.pointer_view;
	L->d.pointer_x = L->attract.pointer_x;
	L->d.pointer_y = L->attract.pointer_y;
	L->attract.on = L->d.attracting = 0;
	L->d.message[0] = 0;
	modes_sync(&L->modes);
	L->scene.dirty = 1;
	fprintf(stderr, "postured: attract: ended after %d laps; the state is as it was\n",
		L->attract.laps);
}

void
loop_attract_input(struct loop *L, const char *line, size_t len)
{
	if (line && is_question(line, len))
		return;
	L->attract.last_input_us = loop_real_now();
	loop_attract_end(L);
}

int
loop_attract_round(struct loop *L, int *wait_ms)
{
	uint64_t now = loop_real_now();
	if (!L->cfg->attract_dir)
		return 0;
	if (!L->attract.last_input_us)
		L->attract.last_input_us = now;
	if (!L->attract.on) {
		uint64_t after = (uint64_t)(L->cfg->attract_after * 1e6);
		if (now - L->attract.last_input_us < after || L->tape.mode != TAPE_OFF ||
		    loop_kiosk_busy(L))
			return 0;
		begin(L);
		if (!L->attract.on) {
			L->attract.last_input_us = now; /* tried again after the idle time */
			return 0;
		}
	}
	struct tape *t = &L->tape;
	const struct tape_entry *e;
	uint64_t at = L->attract.t0_rec + (now - L->attract.t0_real);
	*wait_ms = 10;
	while (!t->broken[0] && (e = tape_peek(t)) && e->kind != TAPE_STOP) {
		if (e->kind == TAPE_LINE) {
			const struct tape_line *l = tape_line_at(t, e->t);
			if (l->t_us > at)
				return 1;
			tape_take(t);
			struct cmd_outcome out;
			loop_command(L, l->client, l->text, l->len, &out);
			free(out.json);
		} else if (e->kind == TAPE_FRAME) {
			if (e->t > at)
				return 1;
			loop_live_frame(L);
		} else if (e->kind == TAPE_DEVICE || e->kind == TAPE_DEVCALL || e->kind == TAPE_EVENT) {
			tape_take(t);
			tape_dev_replay(t, e, &L->input);
		} else {
			snprintf(t->broken, sizeof t->broken, "a record between frames");
		}
	}
	if (t->broken[0]) {
		fprintf(stderr, "postured: attract: the recording went astray: %s\n", t->broken);
		L->attract.last_input_us = now; /* tried again after the idle time */
		loop_attract_end(L);
		return 0;
	}
	if (lap(L) < 0) /* the recording ended: again from its start */
		loop_attract_end(L);
	return L->attract.on;
}
