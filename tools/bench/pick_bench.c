/*
 * pick_bench - picking (pick.h) over the driver scene: the standard human
 * seated in the vehicle seat (demo_scene "seated"), seen through the
 * scene's own camera at 1280 x 720.
 *
 * usage: pick_bench [SEAT_FILE]   (default src/figure/library/vehicle_seat.fig)
 * Each pick is the whole job for one pointer position: the mouse line
 * through a random pixel, then the nearest hit over both figures (the
 * human and the seat). Pixels are drawn uniformly over the human's
 * projected extent (its segments' origins, 10 % margin), so most picks
 * land on the figure and the rest on the seat or the background. Prints
 * the median over batches of the time per pick as
 * "BENCH interact.pick us=... p95_us=... hit=... human=...", with the
 * share of picks that hit something and that hit the human; also the time
 * to build the pick models once (build_ms).
 */
#include <stdio.h>
#include <stdlib.h>

#include "bench_util.h"
#include "draw/demo_scene.h"
#include "draw/view.h"
#include "interact/mouse_line.h"
#include "interact/pick.h"

#define W 1280
#define H 720
#define BATCHES 31
#define PICKS 2000

int
main(int argc, char **argv)
{
	const char *seat = argc > 1 ? argv[1] : "src/figure/library/vehicle_seat.fig";
	char err[256];
	struct demo_scene sc;
	if (demo_scene_make(&sc, "seated", seat, err, sizeof err)) {
		fprintf(stderr, "pick_bench: %s\n", err);
		demo_scene_free(&sc);
		return 1;
	}
	struct camera cam;
	demo_scene_camera(&sc, &cam);

	double t0 = bench_now_us();
	struct pick_model *ph = pick_model_make(sc.human), *ps = pick_model_make(sc.seat);
	double build_ms = (bench_now_us() - t0) / 1000;
	if (!ph || !ps) {
		fprintf(stderr, "pick_bench: out of memory\n");
		return 1;
	}
	struct pick_target t[2] = { { ph, sc.human, sc.hs }, { ps, sc.seat, sc.ss } };

	/* the human's extent on screen */
	double lo[2] = { W, H }, hi[2] = { 0, 0 };
	for (int s = 0; s < sc.human->nseg; s++) {
		double px[2];
		if (!view_project(&cam, W, H, sc.hs->seg_xf[s].p, px))
			continue;
		for (int k = 0; k < 2; k++) {
			lo[k] = px[k] < lo[k] ? px[k] : lo[k];
			hi[k] = px[k] > hi[k] ? px[k] : hi[k];
		}
	}
	for (int k = 0; k < 2; k++) {
		double m = 0.1 * (hi[k] - lo[k]), lim = k ? H : W;
		lo[k] = lo[k] - m < 0 ? 0 : lo[k] - m;
		hi[k] = hi[k] + m > lim ? lim : hi[k] + m;
	}

	static double pix[PICKS][2];
	srand(13);
	for (int i = 0; i < PICKS; i++)
		for (int k = 0; k < 2; k++)
			pix[i][k] = lo[k] + (hi[k] - lo[k]) * rand() / RAND_MAX;

	double batch[BATCHES];
	int hits = 0, human = 0;
	for (int b = 0; b < BATCHES; b++) {
		double b0 = bench_now_us();
		for (int i = 0; i < PICKS; i++) {
			struct ray r;
			struct pick_hit h;
			mouse_line(&cam, W, H, pix[i][0], pix[i][1], &r);
			if (pick_scene(t, 2, &r, cam.znear, &h) && b == 0) {
				hits++;
				human += h.figure == 0;
			}
		}
		batch[b] = (bench_now_us() - b0) / PICKS;
	}
	double sorted[BATCHES];
	for (int b = 0; b < BATCHES; b++)
		sorted[b] = batch[b];
	double med = bench_percentile(sorted, BATCHES, 0.5), p95 = bench_percentile(sorted, BATCHES, 0.95);
	printf("pick_bench: human %d segments %d triangles, seat %d segments %d triangles; "
	       "%d picks x %d batches over pixels (%.0f..%.0f, %.0f..%.0f) of %dx%d\n",
	       sc.human->nseg, ph->ntri, sc.seat->nseg, ps->ntri, PICKS, BATCHES, lo[0], hi[0],
	       lo[1], hi[1], W, H);
	printf("BENCH interact.pick us=%.3f p95_us=%.3f hit=%.2f human=%.2f build_ms=%.1f\n", med,
	       p95, (double)hits / PICKS, (double)human / PICKS, build_ms);
	pick_model_free(ph);
	pick_model_free(ps);
	demo_scene_free(&sc);
	return 0;
}
