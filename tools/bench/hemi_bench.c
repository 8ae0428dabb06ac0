/*
 * hemi_bench - §3.7.1's obstruction check over the driver scene: the
 * standard human seated in the vehicle seat (demo_scene "seated"), G on
 * the right palm, the camera the scene's own (front left).
 *
 * usage: hemi_bench [SEAT_FILE]   (default src/figure/library/vehicle_seat.fig)
 * One check is what the daemon does when a mode starts or a button goes
 * down: the draw list of the figures in id colours, render_hemicube (the
 * render and the readback) and obstruct_check. Prints the median and p95
 * over CHECKS checks as "BENCH interact.hemicube ms=... p95_ms=...
 * all_ms=... search_ms=...": ms as the daemon checks a dragged palm (the
 * seat, and the human but for the hand and the segments jointed to it,
 * obstruct_own_parts), all_ms with both figures drawn whole, search_ms the
 * decision alone on a map where the camera is hidden (a camera 3 m beyond
 * the pelvis, seen from the palm through the body and the seat's back), so
 * the search for a clear direction runs, and hidden_ms the whole check
 * there (drawn as the daemon draws).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench_util.h"
#include "draw/demo_scene.h"
#include "draw/hemi.h"
#include "draw/render.h"
#include "draw/view.h"
#include "interact/obstruct.h"

#define CHECKS 50


/* the human's parts around the palm, left out as the daemon leaves them out */
static unsigned char own[1024];

/*
 * One check: the map from o towards eye over the figures whose bit is set
 * (1 the human, 2 the seat, 4 the human but for its parts around G); its result.
 */
static int
check(struct render *r, struct drawlist *dl, struct hemi_map *map, const struct demo_scene *sc,
      const int base[2], const double o[3], const double eye[3], int which)
{
	double d[3] = { eye[0] - o[0], eye[1] - o[1], eye[2] - o[2] }, dir[3];
	struct camera cam;
	hemi_camera(&cam, o, d);
	view_begin(dl, &cam, HEMI_N, HEMI_N);
	if (which & 1)
		view_add_figure_ids(dl, sc->human, sc->hs, base[0], 0);
	if (which & 4)
		view_add_figure_ids_except(dl, sc->human, sc->hs, base[0], 0, own);
	if (which & 2)
		view_add_figure_ids(dl, sc->seat, sc->ss, base[1], 1);
	render_hemicube(r, dl, map);
	return obstruct_check(map, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), OBSTRUCT_CONE,
			      dir);
}

static double
median_ms(struct render *r, struct drawlist *dl, struct hemi_map *map,
	  const struct demo_scene *sc, const int base[2], const double o[3], const double eye[3],
	  int which, double *p95, int *result)
{
	double t[CHECKS];
	for (int i = 0; i < CHECKS; i++) {
		double t0 = bench_now_us();
		*result = check(r, dl, map, sc, base, o, eye, which);
		t[i] = (bench_now_us() - t0) / 1000;
	}
	qsort(t, CHECKS, sizeof t[0], bench_cmp_double);
	if (p95)
		*p95 = t[CHECKS * 95 / 100];
	return t[CHECKS / 2];
}

int
main(int argc, char **argv)
{
	const char *seat = argc > 1 ? argv[1] : "src/figure/library/vehicle_seat.fig";
	char err[256];
	struct demo_scene sc;
	if (demo_scene_make(&sc, "seated", seat, err, sizeof err)) {
		fprintf(stderr, "hemi_bench: %s\n", err);
		demo_scene_free(&sc);
		return 1;
	}
	struct render_def rd = render_default_def();
	struct render *r = render_make(&rd, err, sizeof err);
	struct drawlist *dl = view_drawlist_make();
	struct hemi_map *map = malloc(sizeof *map);
	if (!r || !dl || !map) {
		fprintf(stderr, "hemi_bench: %s\n", r ? "out of memory" : err);
		return 1;
	}
	int base[2] = { render_add_model(r, sc.human, err, sizeof err),
			render_add_model(r, sc.seat, err, sizeof err) };
	struct camera cam;
	demo_scene_camera(&sc, &cam);
	int palm = model_find_site(sc.human, "hand_r.palm");
	const double *o = sc.hs->site_xf[palm < 0 ? 0 : palm].p;
	int res, res_all, res_behind;
	double p95;
	if (palm < 0 || obstruct_own_parts(sc.human, sc.hs, sc.human->site_seg[palm], own,
					   (int)sizeof own) < 0) {
		fprintf(stderr, "hemi_bench: no right palm on the human\n");
		return 1;
	}
	check(r, dl, map, &sc, base, o, cam.xf.p, 3); /* warm */
	double ms = median_ms(r, dl, map, &sc, base, o, cam.xf.p, 6, &p95, &res);
	double all = median_ms(r, dl, map, &sc, base, o, cam.xf.p, 3, NULL, &res_all);

	/* beyond the pelvis: the body and the seat's back hide the palm; the decision alone */
	int pelvis = model_find_segment(sc.human, "pelvis");
	const double *pp = sc.hs->seg_xf[pelvis < 0 ? 0 : pelvis].p;
	double u[3] = { pp[0] - o[0], pp[1] - o[1], pp[2] - o[2] };
	double nu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
	const double behind[3] = { pp[0] + 3 * u[0] / nu, pp[1] + 3 * u[1] / nu,
				   pp[2] + 3 * u[2] / nu };
	res_behind = check(r, dl, map, &sc, base, o, behind, 6);
	double d[3] = { behind[0] - o[0], behind[1] - o[1], behind[2] - o[2] }, dir[3];
	double dist = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), t[CHECKS];
	for (int i = 0; i < CHECKS; i++) {
		double t0 = bench_now_us();
		obstruct_check(map, dist, OBSTRUCT_CONE, dir);
		t[i] = (bench_now_us() - t0) / 1000;
	}
	qsort(t, CHECKS, sizeof t[0], bench_cmp_double);
	double worst = median_ms(r, dl, map, &sc, base, o, behind, 6, NULL, &res_behind);
	printf("BENCH interact.hemicube ms=%.3f p95_ms=%.3f all_ms=%.3f search_ms=%.3f "
	       "hidden_ms=%.3f n=%d result=%d all_result=%d hidden_result=%d\n",
	       ms, p95, all, t[CHECKS / 2], worst, HEMI_N, res, res_all, res_behind);
	free(map);
	view_drawlist_free(dl);
	render_free(r);
	demo_scene_free(&sc);
	return 0;
}
