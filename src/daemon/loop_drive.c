/*
 * loop_drive.c - the loop driven by a script under a virtual clock: minutes
 * of a kiosk session (random input for the robustness tests, a held button
 * for a minute) in seconds, the same on every run.
 */
#include "daemon/loop_drive.h"

#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/loop_state.h"
#include "daemon/posture_hash.h"
#include "daemon/tape_read.h"

#define DRIVE_TAIL_US 1000000 /* frames run on after the last line */

static void
run(struct loop *L, const struct tape_line *l, int print)
{
	struct cmd_outcome out;
	loop_command(L, l->client, l->text, l->len, &out);
	if (print && out.reply && out.json)
		printf("reply: %s\n", out.json);
	free(out.json);
}

int
loop_drive(const struct loop_config *cfg)
{
	struct loop *L = calloc(1, sizeof *L);
	char err[4600];
	struct tape_line *lines = NULL;
	size_t n = 0;
	int status = 1;
	if (!L)
		return 1;
	if (tape_lines_read(cfg->drive_file, 0, &lines, &n, err, sizeof err) < 0) {
		fprintf(stderr, "postured: drive: %s\n", err);
		free(L);
		return 1;
	}
	if (loop_setup(L, cfg) < 0)
		goto out;
	if (journal_open(&L->j, &L->d, err, sizeof err) < 0) {
		fprintf(stderr, "postured: cannot recover the state: %s\n", err);
		goto out;
	}
	L->scene.replaying = 1; /* pictures without the live timings */
	L->tape.mode = TAPE_VIRTUAL;
	uint64_t end = (n ? lines[n - 1].t_us : 0) + DRIVE_TAIL_US;
	size_t next = 0;
	for (uint64_t k = 0;; k++) {
		L->tape.virtual_us = k * L->period_us;
		while (next < n && lines[next].t_us <= L->tape.virtual_us)
			run(L, &lines[next++], 1);
		loop_live_frame(L);
		scene_sync(&L->scene, &L->d, &L->events);
		/* the journal kept as a live run keeps it, made durable at the end */
		if (journal_snapshot(&L->j, &L->d, 0) < 0)
			fprintf(stderr, "postured: snapshot: %s\n", strerror(errno));
		if (L->tape.virtual_us >= end)
			break;
	}
	status = cfg->after && loop_queries(L, cfg->after) < 0 ? 1 : 0;
	/* as a live daemon stops: the step kept, the postures and a snapshot on disk */
	if (L->d.mode_step)
		L->d.mode_step(&L->d, 'E');
	journal_postures(&L->j, &L->d);
	journal_sync(&L->j);
	journal_snapshot(&L->j, &L->d, 1);
	printf("drive: frames=%" PRIu64 " virtual_s=%.3f posture=%016" PRIx64 "\n", L->tape.frames,
	       (double)L->tape.virtual_us / 1e6, posture_env_hash(&L->d.env));
	fflush(stdout);
out:
	for (size_t i = 0; i < n; i++)
		free(lines[i].text);
	free(lines);
	L->tape.mode = TAPE_OFF;
	loop_teardown(L);
	return status;
}
