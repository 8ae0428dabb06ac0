/*
 * envelope_bench - reach envelopes of the standing default male's right hand
 * (the budget: one arm's envelope at 2 cm within 2 s on this
 * machine, every core): the arm at 2 cm, then the torso and the whole body
 * at coarser grids, each from the standing posture.
 *
 * usage: envelope_bench [MODE RES ...]   (MODE arm, torso or body; RES metres)
 *   BENCH reach.envelope mode=arm res=0.02 seconds=... solves=... vertices=... volume=...
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "assess/envelope.h"
#include "figure/human.h"
#include "figure/kin.h"

static int
run(const struct model *m, const struct state *s, enum reach_mode mode, double res)
{
	static const char *const names[] = { "arm", "torso", "body" };
	struct envelope_request req = { .side = BEHAVE_RIGHT, .mode = mode, .balance = 1,
					.resolution = res };
	struct envelope e;
	char err[200];
	if (envelope_compute(m, s, NULL, NULL, 0, &req, &e, err, sizeof err) < 0) {
		fprintf(stderr, "envelope_bench: %s\n", err);
		return -1;
	}
	printf("BENCH reach.envelope mode=%s res=%g seconds=%.3f solves=%ld vertices=%d volume=%.4f "
	       "grid=%dx%dx%d\n",
	       names[mode], res, e.seconds, e.solves, e.reach.nvert, e.reach.volume, e.grid[0],
	       e.grid[1], e.grid[2]);
	fflush(stdout);
	envelope_free(&e);
	return 0;
}

int
main(int argc, char **argv)
{
	char err[200];
	struct human_def hd = human_default_def(HUMAN_MALE);
	struct model *m = human_build(&hd, err, sizeof err);
	if (!m) {
		fprintf(stderr, "envelope_bench: %s\n", err);
		return 1;
	}
	struct state *s = state_make(m);
	if (!s) {
		fprintf(stderr, "envelope_bench: out of memory\n");
		return 1;
	}
	kin_update(m, s);
	int rc = 0;
	if (argc > 1) {
		for (int i = 1; i + 1 < argc && !rc; i += 2) {
			enum reach_mode mode = !strcmp(argv[i], "body")    ? REACH_BODY
					       : !strcmp(argv[i], "torso") ? REACH_TORSO
									   : REACH_ARM;
			rc = run(m, s, mode, atof(argv[i + 1])) < 0;
		}
	} else {
		rc = run(m, s, REACH_ARM, 0.02) < 0 || run(m, s, REACH_TORSO, 0.12) < 0 ||
		     run(m, s, REACH_BODY, 0.25) < 0;
	}
	state_free(s);
	model_free(m);
	return rc;
}
