/*
 * visibility_bench - one `analyze visibility` query as the daemon answers it,
 * over the driver scene (demo_scene "seated": the standard human in the
 * vehicle seat, palms on the wheel): what the driver sees of its own left
 * hand on the wheel.
 *
 * usage: visibility_bench [SEAT_FILE]   (default src/figure/library/vehicle_seat.fig)
 * A query: the cyclopean eye and mean line of sight from the eye sites, the
 * fixation (eyes, then head), the parts the eye sits in (obstruct_own_parts
 * of both eyeballs), the target's bounding sphere from its pick model's box
 * (built once, as the daemon caches it), the map's camera, the two id maps
 * (the hand alone, then both figures but the eye's own parts; draw list and
 * render_hemicube each) and the count. Prints the median and p95 over
 * QUERIES queries: "BENCH vision.visibility median_ms=... p95_ms=...".
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "draw/demo_scene.h"
#include "draw/hemi.h"
#include "draw/render.h"
#include "draw/view.h"
#include "interact/obstruct.h"
#include "interact/pick.h"
#include "interact/visibility.h"

#define QUERIES 60

static unsigned char own[1024], only[1024], tmp[1024];
static struct hemi_map alone, all;

struct rig {
	struct demo_scene sc;
	struct render *r;
	struct drawlist *dl;
	struct pick_model *pm;
	int base[2], gaze[2], eyeball[2], head, hand;
};

/* one query; the share seen */
static double
query(struct rig *g, struct vis_coverage *cov)
{
	const struct model *m = g->sc.human;
	const struct state *s = g->sc.hs;
	const struct xform *a = &s->site_xf[g->gaze[0]], *b = &s->site_xf[g->gaze[1]];
	double eye[3], dir[3], c[3], mid[3], h2 = 0;
	for (int i = 0; i < 3; i++) {
		eye[i] = 0.5 * (a->p[i] + b->p[i]);
		dir[i] = a->r[3 * i + 2] + b->r[3 * i + 2];
	}
	double n = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
	for (int i = 0; i < 3; i++)
		dir[i] /= n;
	obstruct_own_parts(m, s, g->eyeball[0], own, (int)sizeof own);
	obstruct_own_parts(m, s, g->eyeball[1], tmp, (int)sizeof tmp);
	for (int k = 0; k < m->nseg; k++) {
		own[k] = (own[k] || tmp[k]) && k != g->hand;
		only[k] = k != g->hand;
	}
	const double *lo = &g->pm->seg_lo[3 * g->hand], *hi = &g->pm->seg_hi[3 * g->hand];
	for (int k = 0; k < 3; k++) {
		mid[k] = 0.5 * (lo[k] + hi[k]);
		h2 += 0.25 * (hi[k] - lo[k]) * (hi[k] - lo[k]);
	}
	xform_apply(&s->seg_xf[g->hand], mid, c);
	static const struct vis_limits lim = { -M_PI / 4, M_PI / 4, -M_PI / 4, 35 * M_PI / 180 };
	struct vis_fixation fx;
	vis_fixate(eye, dir, s->seg_xf[g->head].r, &lim, c, &fx);
	struct camera cam;
	if (vis_map_camera(&cam, eye, c, sqrt(h2)) < 0)
		return -1;
	view_begin(g->dl, &cam, HEMI_N, HEMI_N);
	view_add_figure_ids_except(g->dl, m, s, g->base[0], 0, only);
	render_hemicube(g->r, g->dl, &alone);
	view_begin(g->dl, &cam, HEMI_N, HEMI_N);
	view_add_figure_ids_except(g->dl, m, s, g->base[0], 0, own);
	view_add_figure_ids(g->dl, g->sc.seat, g->sc.ss, g->base[1], 1);
	render_hemicube(g->r, g->dl, &all);
	vis_coverage(&alone, &all, view_id(0, g->hand), cov);
	return cov->fraction;
}

int
main(int argc, char **argv)
{
	const char *seat = argc > 1 ? argv[1] : "src/figure/library/vehicle_seat.fig";
	char err[256];
	struct rig g;
	memset(&g, 0, sizeof g);
	if (demo_scene_make(&g.sc, "seated", seat, err, sizeof err)) {
		fprintf(stderr, "visibility_bench: %s\n", err);
		demo_scene_free(&g.sc);
		return 1;
	}
	struct render_def rd = render_default_def();
	g.r = render_make(&rd, err, sizeof err);
	g.dl = view_drawlist_make();
	g.pm = pick_model_make(g.sc.human);
	if (!g.r || !g.dl || !g.pm) {
		fprintf(stderr, "visibility_bench: %s\n", g.r ? "out of memory" : err);
		return 1;
	}
	g.base[0] = render_add_model(g.r, g.sc.human, err, sizeof err);
	g.base[1] = render_add_model(g.r, g.sc.seat, err, sizeof err);
	const struct model *m = g.sc.human;
	g.gaze[0] = model_find_site(m, "eyeball_l.gaze");
	g.gaze[1] = model_find_site(m, "eyeball_r.gaze");
	g.eyeball[0] = model_find_segment(m, "eyeball_l");
	g.eyeball[1] = model_find_segment(m, "eyeball_r");
	g.head = model_find_segment(m, "head");
	g.hand = model_find_segment(m, "hand_l");
	if (g.gaze[0] < 0 || g.gaze[1] < 0 || g.eyeball[0] < 0 || g.eyeball[1] < 0 || g.head < 0 ||
	    g.hand < 0 || m->nseg > (int)sizeof own) {
		fprintf(stderr, "visibility_bench: the human has no eyes or no left hand\n");
		return 1;
	}
	struct vis_coverage cov;
	if (query(&g, &cov) < 0) { /* warm */
		fprintf(stderr, "visibility_bench: the eye is inside the hand's bounds\n");
		return 1;
	}
	double t[QUERIES];
	for (int i = 0; i < QUERIES; i++) {
		double t0 = bench_now_us();
		query(&g, &cov);
		t[i] = (bench_now_us() - t0) / 1000;
	}
	double med = bench_percentile(t, QUERIES, 0.5), p95 = bench_percentile(t, QUERIES, 0.95);
	printf("BENCH vision.visibility median_ms=%.3f p95_ms=%.3f n=%d fraction=%.4f pixels=%d "
	       "resolution=%.4f occluders=%d\n",
	       med, p95, HEMI_N, cov.fraction, cov.pixels, cov.edge_share, cov.nocc);
	pick_model_free(g.pm);
	view_drawlist_free(g.dl);
	render_free(g.r);
	demo_scene_free(&g.sc);
	return 0;
}
