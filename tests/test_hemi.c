/*
 * test_hemi.c - the visibility map rendered (render_hemicube) against an
 * independent CPU path: pick.h's ray cast through each pixel's centre on
 * the same figures. A box between the origin and the camera shows its id
 * at the face's analytic distance in the camera direction; over the
 * seated human and the vehicle seat, ids and distances agree with the
 * rays except on silhouette pixels; the figure left out is not drawn; and
 * the map allocates nothing once warm.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "draw/demo_scene.h"
#include "draw/hemi.h"
#include "draw/render.h"
#include "draw/view.h"
#include "figure/figure.h"
#include "figure/kin.h"
#include "interact/pick.h"

#include "alloc_count.h"
#include "test_util.h"

#define SEAT "src/figure/library/vehicle_seat.fig"

/* the carton of box.fig, 40 x 25 x 30 cm, standing with its near face at z = -1.35 */
static const char BOX[] = "figure box { segment box { mass = 10kg; color = (0.7, 0.5, 0.3);\n"
			  "geometry = box(40cm, 25cm, 30cm) at trans(0cm, 12.5cm, 0cm);\n"
			  "site base->location = trans(0cm, 0cm, 0cm); }\n"
			  "root = box.base; location = trans(0cm, 0cm, -150cm); }\n";

struct rig {
	struct demo_scene sc;
	struct model *box;
	struct state *bs;
	struct render *r;
	struct drawlist *dl;
	int base[3];
	struct pick_model *pm[3];
	struct hemi_map *map;
};

static void
rig_make(struct rig *g)
{
	char err[256];
	memset(g, 0, sizeof *g);
	assert_int_equal(demo_scene_make(&g->sc, "seated", SEAT, err, sizeof err), 0);
	g->box = figure_read_string(BOX, strlen(BOX), "box", NULL, err, sizeof err);
	if (!g->box)
		fail_msg("box: %s", err);
	g->bs = state_make(g->box);
	kin_forward(g->box, g->bs);
	struct render_def d = render_default_def();
	d.max_w = 64;
	d.max_h = 64;
	d.samples = 0;
	g->r = render_make(&d, err, sizeof err);
	if (!g->r)
		fail_msg("render_make: %s", err);
	g->dl = view_drawlist_make();
	g->map = malloc(sizeof *g->map);
	assert_non_null(g->dl);
	assert_non_null(g->map);
	g->base[0] = render_add_model(g->r, g->sc.human, err, sizeof err);
	g->base[1] = render_add_model(g->r, g->sc.seat, err, sizeof err);
	g->base[2] = render_add_model(g->r, g->box, err, sizeof err);
	g->pm[0] = pick_model_make(g->sc.human);
	g->pm[1] = pick_model_make(g->sc.seat);
	g->pm[2] = pick_model_make(g->box);
	for (int k = 0; k < 3; k++) {
		assert_true(g->base[k] >= 0);
		assert_non_null(g->pm[k]);
	}
}

static void
rig_free(struct rig *g)
{
	for (int k = 0; k < 3; k++)
		pick_model_free(g->pm[k]);
	free(g->map);
	view_drawlist_free(g->dl);
	render_free(g->r);
	state_free(g->bs);
	model_free(g->box);
	demo_scene_free(&g->sc);
}

/* the map from o along dir with the figures whose bit is set in which (1 human, 2 seat, 4 box) */
static void
shoot(struct rig *g, const double o[3], const double dir[3], int which)
{
	struct camera cam;
	assert_int_equal(hemi_camera(&cam, o, dir), 0);
	view_begin(g->dl, &cam, HEMI_N, HEMI_N);
	const struct model *m[3] = { g->sc.human, g->sc.seat, g->box };
	const struct state *s[3] = { g->sc.hs, g->sc.ss, g->bs };
	for (int k = 0; k < 3; k++)
		if (which & 1 << k)
			view_add_figure_ids(g->dl, m[k], s[k], g->base[k], k);
	assert_int_equal(g->dl->dropped, 0);
	assert_int_equal(render_hemicube(g->r, g->dl, g->map), 0);
}

/* the box's near face is 1.35 m ahead: its id in the middle of the map, at that distance */
static void
test_box_in_camera_direction(void **state)
{
	(void)state;
	struct rig g;
	rig_make(&g);
	const double o[3] = { 0, 0.125, 0 }, dir[3] = { 0, 0, -1 };
	shoot(&g, o, dir, 4);
	for (int y = HEMI_N / 2 - 1; y <= HEMI_N / 2; y++)
		for (int x = HEMI_N / 2 - 1; x <= HEMI_N / 2; x++) {
			int i = y * HEMI_N + x;
			assert_int_equal(g.map->id[i], view_id(2, 0));
			double d[3];
			hemi_pixel_dir(g.map, x, y, d);
			assert_near(g.map->dist[i], 1.35 / -d[2], 2e-3);
		}
	/* straight up there is nothing */
	assert_int_equal(g.map->id[HEMI_N / 2], 0);
	assert_true(isinf(g.map->dist[HEMI_N / 2]));
	/* left out, the box is not there */
	shoot(&g, o, dir, 0);
	assert_int_equal(g.map->id[HEMI_N / 2 * HEMI_N + HEMI_N / 2], 0);
	rig_free(&g);
}

/*
 * From the seated driver's right hand towards a camera front left: every
 * pixel against pick_scene's ray through its centre over the same figures.
 * A pixel's ray and its rasterised coverage differ only on silhouettes, so
 * a few percent may disagree in id; where both hit the same segment the
 * distances agree to a few millimetres.
 */
static void
test_agrees_with_rays(void **state)
{
	(void)state;
	struct rig g;
	rig_make(&g);
	int hand = model_find_site(g.sc.human, "hand_r.palm");
	assert_true(hand >= 0);
	const double *o = g.sc.hs->site_xf[hand].p;
	const double dir[3] = { -1, 0.3, 1 };
	shoot(&g, o, dir, 7);
	struct pick_target t[3] = { { g.pm[0], g.sc.human, g.sc.hs },
				    { g.pm[1], g.sc.seat, g.sc.ss },
				    { g.pm[2], g.box, g.bs } };
	int differ = 0, hits = 0, far = 0;
	for (int y = 0; y < HEMI_N; y++)
		for (int x = 0; x < HEMI_N; x++) {
			struct ray r;
			memcpy(r.o, o, sizeof r.o);
			hemi_pixel_dir(g.map, x, y, r.d);
			struct pick_hit h;
			uint32_t want = 0;
			if (pick_scene(t, 3, &r, HEMI_ZNEAR, &h))
				want = view_id(h.figure, h.segment);
			int i = y * HEMI_N + x;
			if (g.map->id[i] != want) {
				differ++;
				continue;
			}
			if (want) {
				hits++;
				if (fabs(g.map->dist[i] - h.distance) > 5e-3 + 2e-3 * h.distance)
					far++;
			}
		}
	printf("hemi: %d of %d pixels hit, %d differ in id, %d in distance\n", hits,
	       HEMI_N * HEMI_N, differ, far);
	assert_true(hits > HEMI_N * HEMI_N / 20); /* the scene is in the map */
	assert_true(differ < HEMI_N * HEMI_N / 25);
	assert_true(far <= hits / 100);
	rig_free(&g);
}

static void
test_no_alloc(void **state)
{
	(void)state;
	struct rig g;
	rig_make(&g);
	const double o[3] = { 0, 1, 1 }, dir[3] = { 1, 0, 1 };
	shoot(&g, o, dir, 7);
#if COUNT_ALLOCS
	/* the driver (llvmpipe) mallocs and frees per draw; nothing of ours, nothing kept */
	for (int i = 0; i < 5; i++) /* warm: the driver's first readbacks keep buffers */
		shoot(&g, o, dir, 7);
	long live = allocs - frees;
	for (int i = 0; i < 10; i++)
		shoot(&g, o, dir, 7);
	printf("hemi: 10 maps, %ld allocations still live\n", allocs - frees - live);
	assert_true(allocs - frees - live <= 0);
#endif
	rig_free(&g);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_box_in_camera_direction),
		cmocka_unit_test(test_agrees_with_rays),
		cmocka_unit_test(test_no_alloc),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
