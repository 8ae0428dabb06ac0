/*
 * loop_replay.c - `postured --replay DIR`: the recorded lines and frames
 * run through the loop's own code under the recording's clock, each frame's
 * postures checked against the recording's (tape.h).
 */
#include "daemon/loop_replay.h"

#include "daemon/loop_state.h"

#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "daemon/cmd.h"
#include "daemon/posture_hash.h"
#include "daemon/tape_dev.h"
#include "daemon/tape_read.h"

/* --speed 1: waits until the recording's time t (from its first) has come in real time */
static void
pace(uint64_t t, uint64_t *t0, uint64_t *real0, double speed)
{
	if (speed <= 0)
		return;
	if (!*t0) {
		*t0 = t;
		*real0 = loop_real_now();
		return;
	}
	uint64_t due = *real0 + (uint64_t)((double)(t - *t0) / speed);
	uint64_t now = loop_real_now();
	if (due > now) {
		struct timespec ts = { (time_t)((due - now) / 1000000u), (long)((due - now) % 1000000u) * 1000 };
		nanosleep(&ts, NULL);
	}
}

/* FNV-1a over 8-byte words: a picture's megabytes hashed at memory speed */
static uint64_t
hash_words(uint64_t h, const uint8_t *p, size_t n)
{
	size_t k = 0;
	for (; k + 8 <= n; k += 8) {
		uint64_t w;
		memcpy(&w, p + k, 8);
		h = (h ^ w) * 1099511628211ull;
	}
	return posture_fnv(h, p + k, n - k);
}

/* --hash-frames: every view drawn after each frame, its pixels folded into *h */
static void
hash_pictures(struct loop *L, uint64_t *h, uint64_t *n)
{
	for (int v = 0; v < ENV_MAX_VIEWS; v++) {
		const struct frame *f;
		char err[256];
		if (!L->d.env.view[v].used || scene_draw(&L->scene, &L->d, v, &f, err, sizeof err) < 0)
			continue;
		for (int y = 0; y < f->height; y++)
			*h = hash_words(*h, f->rgba + (size_t)y * (size_t)f->stride, 4u * (size_t)f->width);
		(*n)++;
	}
}

static int
drive(struct loop *L, const struct loop_config *cfg, uint64_t *pictures, uint64_t *npictures)
{
	double speed = cfg->speed;
	uint64_t until = cfg->until;
	struct tape *t = &L->tape;
	const struct tape_entry *e;
	uint64_t t0 = 0, real0 = 0;
	while (!t->broken[0] && (e = tape_peek(t)) && e->kind != TAPE_STOP &&
	       !(until && t->frames >= until)) {
		if (e->kind == TAPE_LINE) {
			const struct tape_line *l = tape_line_at(t, e->t);
			tape_take(t);
			pace(l->t_us, &t0, &real0, speed);
			struct cmd_outcome out;
			loop_command(L, l->client, l->text, l->len, &out);
			free(out.json);
		} else if (e->kind == TAPE_FRAME) {
			pace(e->t, &t0, &real0, speed);
			loop_live_frame(L);
			scene_sync(&L->scene, &L->d, &L->events);
			if (cfg->hash_frames)
				hash_pictures(L, pictures, npictures);
		} else if (e->kind == TAPE_DEVICE || e->kind == TAPE_DEVCALL || e->kind == TAPE_EVENT) {
			tape_take(t);
			tape_dev_replay(t, e, &L->input);
		} else {
			snprintf(t->broken, sizeof t->broken,
				 "%s/frames:%d: %s between frames, where the replay reads none", t->dir,
				 e->lineno, tape_kind_name((enum tape_kind)e->kind));
		}
	}
	return t->broken[0] ? -1 : 0;
}

int
loop_replay(const struct loop_config *cfg)
{
	struct loop *L = calloc(1, sizeof *L);
	char err[TAPE_PATH_MAX + 600];
	if (!L)
		return 1;
	int status = 1;
	char *config = NULL;
	if (loop_setup(L, cfg) < 0)
		goto out;
	if (tape_replay_open(&L->tape, cfg->replay_dir, &L->d, &config, err, sizeof err) < 0) {
		fprintf(stderr, "postured: replay: %s\n", err);
		goto out;
	}
	free(config); /* main read it already: the settings are in cfg */
	L->scene.replaying = 1;
	L->d.files_read_only = 1;
	modes_sync(&L->modes);
	uint64_t pictures = POSTURE_FNV_BASIS, npictures = 0;
	int rc = drive(L, cfg, &pictures, &npictures);
	const struct tape *t = &L->tape;
	/* the pictures of the end, whatever the pace allowed before */
	L->scene.dirty = 1;
	L->scene.last_png_us = 0;
	scene_publish(&L->scene, &L->d, &L->events, loop_real_now());
	if (rc < 0)
		fprintf(stderr, "postured: replay went astray at frame %" PRIu64 ": %s\n", t->frames,
			t->broken);
	if (t->divergences)
		fprintf(stderr, "postured: replay diverged first at frame %" PRIu64 ": %s\n",
			t->first.frame, t->first.what);
	if (cfg->after && loop_queries(L, cfg->after) < 0)
		rc = -1;
	if (cfg->hash_frames)
		printf("pictures: drawn=%" PRIu64 " hash=%016" PRIx64 "\n", npictures, pictures);
	printf("replay: frames=%" PRIu64 " posture=%016" PRIx64 " divergences=%" PRIu64 "\n",
	       t->frames, posture_env_hash(&L->d.env), t->divergences + (rc < 0));
	fflush(stdout);
	status = rc < 0 || t->divergences ? 1 : 0;
out:
	tape_dev_free(&L->tape);
	tape_free(&L->tape);
	loop_teardown(L);
	return status;
}
