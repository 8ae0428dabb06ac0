/*
 * reach_bench - one "can reach" in body mode (the budget: 5 ms
 * median): the standing default male's right hand sent to 64 targets
 * around him, near and far, high and low, each solved from the same
 * standing posture on the reach object's copy.
 *
 * usage: reach_bench
 *   BENCH reach.can us=... p95_us=... mode=body targets=64 reached=...
 */
#include <math.h>
#include <stdio.h>

#include "bench_util.h"
#include "figure/human.h"
#include "figure/kin.h"
#include "pose/reach.h"

#define TARGETS 64
#define ROUNDS 5

static double t_us[TARGETS * ROUNDS];

int
main(void)
{
	char err[200];
	struct human_def hd = human_default_def(HUMAN_MALE);
	struct model *m = human_build(&hd, err, sizeof err);
	if (!m) {
		fprintf(stderr, "reach_bench: %s\n", err);
		return 1;
	}
	struct state *s = state_make(m);
	kin_update(m, s);
	struct reach *r = reach_make(m);
	if (!s || !r) {
		fprintf(stderr, "reach_bench: out of memory\n");
		return 1;
	}
	int sh = model_find_site(m, "clavicle_r.shoulder_r"), reached = 0, n = 0;
	for (int round = 0; round < ROUNDS; round++)
		for (int i = 0; i < TARGETS; i++) {
			/* a spiral of directions about the shoulder, 0.3 to 1.2 m out */
			double az = i * 2.399963, el = asin(1 - 2 * (i + 0.5) / TARGETS);
			double d = 0.3 + 0.9 * (i % 7) / 6.0;
			struct reach_request q = { .side = BEHAVE_RIGHT, .mode = REACH_BODY, .balance = 1 };
			q.target[0] = s->site_xf[sh].p[0] + d * cos(el) * sin(az);
			q.target[1] = fmax(0.05, s->site_xf[sh].p[1] + d * sin(el));
			q.target[2] = s->site_xf[sh].p[2] + d * cos(el) * cos(az);
			struct reach_result res;
			double t0 = bench_now_us();
			if (reach_solve(r, m, s, NULL, NULL, 0, &q, &res) < 0) {
				fprintf(stderr, "reach_bench: refused\n");
				return 1;
			}
			t_us[n++] = bench_now_us() - t0;
			reached += round == 0 && res.reached;
		}
	printf("BENCH reach.can us=%.0f p95_us=%.0f mode=body targets=%d reached=%d\n",
	       bench_percentile(t_us, n, 0.5), bench_percentile(t_us, n, 0.95), TARGETS, reached);
	reach_free(r);
	state_free(s);
	model_free(m);
	return 0;
}
