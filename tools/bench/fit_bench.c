/*
 * fit_bench - the fit analysis's costs: a frame's full clearance while a
 * drag moves the human, and building the collision models.
 *
 * usage: fit_bench
 * The human seated in the vehicle seat (the demo scene), its hands on the
 * wheel and thighs on the cushion (both interpenetrating the seat's meshes
 * by centimetres, as the demo's grip and seat contact draw them). Each
 * frame the clearance of the human against the seat and of the human with
 * itself, 2 cm threshold, is timed (frames updated before, not timed), in
 * two motions of FRAMES frames:
 *   drag   the right hand dragged: shoulder and elbow turn a little each
 *          frame, out and back (what a drag of the hand moves), with the
 *          caches of the last frames, as the live analysis runs
 *   sweep  the whole body moved each frame from the seated posture towards
 *          a random posture within the limits, half way and back, no caches
 *          (every pair's bound from its boxes alone): the worst case
 * Prints:
 *   BENCH fit.frame us=... p95_us=... max_us=... asked=... candidates=...
 *   BENCH fit.sweep us=... p95_us=... max_us=... asked=... candidates=...
 *     (one frame's clearance: median, 95th percentile, worst; the exact
 *      distances asked and the pairs considered, a frame on average)
 *   BENCH fit.build ms=... triangles=...
 *     (the human's and the seat's collision models, median of 5 builds)
 * The budgets: a frame's clearance within 1 ms; building both within 50 ms.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "draw/demo_scene.h"
#include "figure/kin.h"
#include "fit/clearance.h"

#define SEAT "src/figure/library/vehicle_seat.fig"
#define FRAMES 1000
#define SWEEP 100 /* frames a sweep out and back */

int
main(void)
{
	char err[256];
	struct demo_scene sc;
	if (demo_scene_make(&sc, "seated", SEAT, err, sizeof err) < 0) {
		fprintf(stderr, "fit_bench: %s\n", err);
		return 1;
	}
	double build[5];
	struct fit_model *fh = NULL, *fs = NULL;
	int ntri = 0;
	for (int k = 0; k < 5; k++) {
		fit_model_free(fh);
		fit_model_free(fs);
		double t0 = bench_now_us();
		fh = fit_model_make(sc.human, err, sizeof err);
		fs = fh ? fit_model_make(sc.seat, err, sizeof err) : NULL;
		build[k] = (bench_now_us() - t0) / 1000;
		if (!fh || !fs) {
			fprintf(stderr, "fit_bench: %s\n", err);
			return 1;
		}
		ntri = fh->ntri + fs->ntri;
	}
	struct clearance_work *w = clearance_work_make(64);
	struct clearance_cache *cb = clearance_cache_make(fh, fs), *cs = clearance_cache_make(fh, fh);
	static struct clearance_result res;
	const struct model *m = sc.human;
	double *q0 = malloc(sizeof(double) * (size_t)m->ndof);
	double *q1 = malloc(sizeof(double) * (size_t)m->ndof);
	double *us = malloc(sizeof(double) * FRAMES);
	memcpy(q0, sc.hs->q, sizeof(double) * (size_t)m->ndof);
	int sh = m->jnt_dof0[model_find_joint(m, "shoulder_r")];
	int el = m->jnt_dof0[model_find_joint(m, "elbow_r")];
	for (int motion = 0; motion < 2; motion++) {
		unsigned seed = 1;
		long asked = 0, candidates = 0;
		for (int f = 0; f < FRAMES; f++) {
			int phase = f % SWEEP;
			double a = 0.5 * (1 - cos(2 * M_PI * phase / SWEEP)); /* 0 .. 1 .. 0 */
			if (motion == 0) {
				sc.hs->q[sh] = q0[sh] - 0.8 * a; /* the arm raised forward */
				sc.hs->q[el] = q0[el] + 0.6 * a;
			} else {
				if (phase == 0)
					for (int d = 0; d < m->ndof; d++) {
						double u = (double)rand_r(&seed) / RAND_MAX;
						double t = m->dof_lo[d] + u * (m->dof_hi[d] - m->dof_lo[d]);
						q1[d] = isfinite(t) ? t : q0[d];
					}
				for (int d = 0; d < m->ndof; d++)
					sc.hs->q[d] = q0[d] + 0.5 * a * (q1[d] - q0[d]);
			}
			kin_forward(m, sc.hs);
			double t0 = bench_now_us();
			clearance_begin(&res, 0.02);
			if (clearance_between(w, motion ? NULL : cb, 0, fh, sc.hs, 1, fs, sc.ss, &res) < 0 ||
			    clearance_self(w, motion ? NULL : cs, 0, fh, sc.hs, &res) < 0) {
				fprintf(stderr, "fit_bench: the query failed\n");
				return 1;
			}
			clearance_sort(&res);
			us[f] = bench_now_us() - t0;
			asked += res.asked;
			candidates += res.candidates;
		}
		double p50 = bench_percentile(us, FRAMES, 0.5), p95 = bench_percentile(us, FRAMES, 0.95);
		printf("BENCH fit.%s us=%.1f p95_us=%.1f max_us=%.1f asked=%.1f candidates=%.1f\n",
		       motion ? "sweep" : "frame", p50, p95, us[FRAMES - 1], (double)asked / FRAMES,
		       (double)candidates / FRAMES);
	}
	printf("BENCH fit.build ms=%.2f triangles=%d\n", bench_percentile(build, 5, 0.5), ntri);
	free(q0);
	free(q1);
	free(us);
	clearance_cache_free(cb);
	clearance_cache_free(cs);
	clearance_work_free(w);
	fit_model_free(fh);
	fit_model_free(fs);
	demo_scene_free(&sc);
	return 0;
}
