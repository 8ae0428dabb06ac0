/*
 * tint_bench - what a tinted view costs a frame (set view VIEW tint=...).
 *
 * usage: tint_bench
 * A standard human's right arm swept through 0-180 deg of flexion, RUNS
 * postures; at each, its RULA, REBA and OWAS scored from its body angles
 * (what the live assessment computes and caches, timed for scale), then
 * the tint's own work timed apart: the segment colours of each method
 * (tint_segments: the part-alone levels and the segments' colours), and a
 * figure's draw-list entries with those colours against its own colours.
 * Prints the median and p95 in microseconds:
 *   BENCH tint.frame us=... p95_us=... (the three methods' colours together)
 *   BENCH tint.draw rgba_us=... plain_us=... (view_add_figure_rgba, view_add_figure)
 *   BENCH tint.assess us=... (the three scores, for scale: not the tint's)
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "assess/assess.h"
#include "assess/body_angles.h"
#include "assess/owas.h"
#include "assess/reba.h"
#include "assess/rula.h"
#include "bench_util.h"
#include "daemon/tint.h"
#include "draw/view.h"
#include "figure/human.h"
#include "figure/kin.h"
#include "figure/model.h"
#include "figure/state.h"

#define RUNS 2000

int
main(void)
{
	static double t_tint[RUNS], t_rgba[RUNS], t_plain[RUNS], t_assess[RUNS];
	char err[256];
	struct human_def hd = human_default_def(HUMAN_MALE);
	struct model *m = human_build(&hd, err, sizeof err);
	struct state *s = m ? state_make(m) : NULL;
	struct drawlist *dl = view_drawlist_make();
	static struct tint t;
	if (!m || !s || !dl) {
		fprintf(stderr, "tint_bench: %s\n", m ? "out of memory" : err);
		return 1;
	}
	int shoulder = model_find_joint(m, "shoulder_r");
	struct assess_config cfg = assess_config_default();
	struct rula_options ro = rula_options_default();
	struct reba_options bo = reba_options_default();
	struct owas_options oo = { 0 };
	static struct assess_result res[ASSESS_NMETHODS];
	struct camera cam;
	view_camera_default(&cam);
	int ok = 0;
	for (int i = -1; i < RUNS; i++) { /* -1: a first round untimed (the probes are made then) */
		s->q[m->jnt_dof0[shoulder]] = M_PI * ((i + 181) % 181) / 180;
		kin_update(m, s);
		struct body_angles a;
		double t0 = bench_now_us();
		if (body_angles_measure(m, s, 0, cfg.kneel_height, &a, err, sizeof err) < 0) {
			fprintf(stderr, "tint_bench: %s\n", err);
			return 1;
		}
		rula_score(&a, &cfg, &ro, &res[ASSESS_RULA]);
		reba_score(&a, &cfg, &bo, &res[ASSESS_REBA]);
		owas_score(&a, &cfg, &oo, &res[ASSESS_OWAS]);
		double t1 = bench_now_us();
		for (int k = 0; k < ASSESS_NMETHODS; k++) {
			const struct assess_result *r = &res[k];
			const struct assess_result *side[2] = { r, r };
			if (r->side == ASSESS_SIDE_LEFT || r->side == ASSESS_SIDE_RIGHT)
				side[r->side == ASSESS_SIDE_LEFT ? BODY_RIGHT : BODY_LEFT] = NULL;
			ok += tint_segments(&t.map[0], m, 1, side, t.rgba) == 0;
		}
		double t2 = bench_now_us();
		view_begin(dl, &cam, 640, 480);
		view_add_figure_rgba(dl, m, s, 0, t.rgba);
		double t3 = bench_now_us();
		view_begin(dl, &cam, 640, 480);
		view_add_figure(dl, m, s, 0);
		double t4 = bench_now_us();
		if (i < 0) {
			ok = 0;
			continue;
		}
		t_assess[i] = t1 - t0;
		t_tint[i] = t2 - t1;
		t_rgba[i] = t3 - t2;
		t_plain[i] = t4 - t3;
	}
	if (ok != RUNS * ASSESS_NMETHODS) {
		fprintf(stderr, "tint_bench: %d of %d tints failed\n", RUNS * ASSESS_NMETHODS - ok,
			RUNS * ASSESS_NMETHODS);
		return 1;
	}
	printf("BENCH tint.frame us=%.2f p95_us=%.2f methods=3 segments=%d runs=%d\n",
	       bench_percentile(t_tint, RUNS, 0.5), bench_percentile(t_tint, RUNS, 0.95), m->nseg,
	       RUNS);
	printf("BENCH tint.draw rgba_us=%.2f plain_us=%.2f\n", bench_percentile(t_rgba, RUNS, 0.5),
	       bench_percentile(t_plain, RUNS, 0.5));
	printf("BENCH tint.assess us=%.2f p95_us=%.2f\n", bench_percentile(t_assess, RUNS, 0.5),
	       bench_percentile(t_assess, RUNS, 0.95));
	view_drawlist_free(dl);
	state_free(s);
	model_free(m);
	return 0;
}
