/*
 * test_render.c - the renderer: camera math against analytic answers,
 * golden pictures compared with a tolerance that survives harmless driver
 * differences but not a missing or misplaced figure or icon, and no
 * allocation in the frame after warm-up.
 *
 * Goldens live in tests/frames/ as PNG files (320 x 240, no multisampling);
 * UPDATE_GOLDEN=1 rewrites them from the current renderer.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/figure.h"
#include "figure/human.h"
#include "pose/ik.h"
#include "figure/kin.h"
#include "draw/render.h"
#include "draw/demo_scene.h"
#include "draw/view.h"

#include "alloc_count.h"
#include "icosphere.h"

#define W 320
#define H 240
#define SEAT "src/figure/library/vehicle_seat.fig"

#define DEG (M_PI / 180)

/* ---- pictures ------------------------------------------------------------ */

struct rig {
	struct demo_scene sc;
	struct render *r;
	struct drawlist *dl;
	struct camera cam;
	int base[2];
};

static void
rig_make(struct rig *g, const char *scene)
{
	char err[256];
	assert_int_equal(demo_scene_make(&g->sc, scene, SEAT, err, sizeof err), 0);
	struct render_def d = render_default_def();
	d.max_w = W;
	d.max_h = H;
	d.samples = 0;
	g->r = render_make(&d, err, sizeof err);
	if (!g->r)
		fail_msg("render_make: %s", err);
	g->dl = view_drawlist_make();
	assert_non_null(g->dl);
	g->base[0] = render_add_model(g->r, g->sc.human, err, sizeof err);
	assert_true(g->base[0] >= 0);
	if (g->sc.seat) {
		g->base[1] = render_add_model(g->r, g->sc.seat, err, sizeof err);
		assert_true(g->base[1] >= 0);
	}
	demo_scene_camera(&g->sc, &g->cam);
}

static void
rig_free(struct rig *g)
{
	view_drawlist_free(g->dl);
	render_free(g->r);
	demo_scene_free(&g->sc);
}

/* renders the rig's scene (icons: 0 none, 1 all, 2 all but the frame icon) into a packed copy */
static uint8_t *
shoot(struct rig *g, int icons)
{
	struct frame f;
	demo_scene_draw(g->dl, &g->sc, &g->cam, W, H, g->base, icons);
	assert_int_equal(g->dl->dropped, 0);
	assert_int_equal(render_frame(g->r, g->dl, 0, &f), 0);
	assert_int_equal(f.width, W);
	assert_int_equal(f.height, H);
	uint8_t *px = malloc(4 * W * H);
	for (int y = 0; y < H; y++)
		memcpy(px + 4 * W * y, f.rgba + (size_t)f.stride * y, 4 * W);
	return px;
}

static uint8_t *
png_load(const char *path)
{
	png_image img;
	memset(&img, 0, sizeof img);
	img.version = PNG_IMAGE_VERSION;
	if (!png_image_begin_read_from_file(&img, path))
		return NULL;
	img.format = PNG_FORMAT_RGBA;
	if (img.width != W || img.height != H) {
		png_image_free(&img);
		return NULL;
	}
	uint8_t *px = malloc(PNG_IMAGE_SIZE(img));
	if (!png_image_finish_read(&img, NULL, px, 0, NULL)) {
		free(px);
		return NULL;
	}
	return px;
}

static void
png_save(const char *path, const uint8_t *px)
{
	png_image img;
	memset(&img, 0, sizeof img);
	img.version = PNG_IMAGE_VERSION;
	img.width = W;
	img.height = H;
	img.format = PNG_FORMAT_RGBA;
	assert_true(png_image_write_to_file(&img, path, 0, px, 4 * W, NULL));
}

/*
 * The tolerance: fewer than 1 % of the pixels may differ by more than 48
 * counts in a channel, and the mean colour of every block of a 16 x 12 grid
 * (20 x 20 pixels) must agree within 6 counts a channel. Rasterisation
 * differences move edges by a pixel; a missing or displaced body part or
 * icon changes whole blocks. Returns 1 when a and b match; says why not.
 */
static int
same_picture(const uint8_t *a, const uint8_t *b, const char *what)
{
	long bad = 0;
	for (int i = 0; i < W * H; i++)
		for (int c = 0; c < 3; c++)
			if (abs(a[4 * i + c] - b[4 * i + c]) > 48) {
				bad++;
				break;
			}
	double worst = 0;
	const int bw = W / 16, bh = H / 12;
	for (int by = 0; by < 12; by++)
		for (int bx = 0; bx < 16; bx++)
			for (int c = 0; c < 3; c++) {
				double sa = 0, sb = 0;
				for (int y = by * bh; y < (by + 1) * bh; y++)
					for (int x = bx * bw; x < (bx + 1) * bw; x++) {
						sa += a[4 * (W * y + x) + c];
						sb += b[4 * (W * y + x) + c];
					}
				double d = fabs(sa - sb) / (bw * bh);
				worst = d > worst ? d : worst;
			}
	int ok = bad < W * H / 100 && worst <= 6;
	if (!ok)
		printf("# %s: %ld pixels (%.2f %%) off by > 48, worst block %.1f counts\n", what, bad,
		       100.0 * bad / (W * H), worst);
	return ok;
}

/* compares with tests/frames/NAME.png, or writes it under UPDATE_GOLDEN=1 */
static void
golden(const char *name, const uint8_t *px)
{
	char path[128];
	snprintf(path, sizeof path, "tests/frames/%s.png", name);
	const char *up = getenv("UPDATE_GOLDEN");
	if (up && !strcmp(up, "1")) {
		png_save(path, px);
		return;
	}
	uint8_t *ref = png_load(path);
	if (!ref)
		fail_msg("%s: missing or not %dx%d (run with UPDATE_GOLDEN=1)", path, W, H);
	int ok = same_picture(px, ref, name);
	if (!ok) {
		snprintf(path, sizeof path, "build/%s.actual.png", name);
		png_save(path, px);
	}
	free(ref);
	assert_true(ok);
}

static void
test_golden_standing(void **unused)
{
	(void)unused;
	struct rig g;
	rig_make(&g, "standing");
	uint8_t *px = shoot(&g, 0);
	golden("standing", px);

	/* the figure 5 cm to its left: the comparison must fail */
	g.sc.hs->root_xf.p[0] += 0.05;
	kin_update(g.sc.human, g.sc.hs);
	uint8_t *moved = shoot(&g, 0);
	assert_false(same_picture(moved, px, "standing moved 5 cm (expected to differ)"));
	free(moved);
	free(px);
	rig_free(&g);
}

static void
test_golden_seated(void **unused)
{
	(void)unused;
	struct rig g;
	rig_make(&g, "seated");
	/* the pelvis sits on the H-point */
	int hp = model_find_site(g.sc.seat, "cushion.h_point");
	int root = model_find_site(g.sc.human, HUMAN_SITE_ROOT);
	for (int k = 0; k < 3; k++)
		assert_true(fabs(g.sc.hs->site_xf[root].p[k] - g.sc.ss->site_xf[hp].p[k]) < 1e-9);
	uint8_t *px = shoot(&g, 1);
	golden("seated", px);
	free(px);
	rig_free(&g);
}

static void
test_golden_icons(void **unused)
{
	(void)unused;
	struct rig g;
	rig_make(&g, "standing");
	uint8_t *px = shoot(&g, 1);
	golden("icons", px);
	/* translucent icons blend colour, not coverage: every pixel stays opaque,
	 * or a PNG of the frame would show the page through it */
	for (int i = 0; i < W * H; i++)
		assert_int_equal(px[4 * i + 3], 255);

	/* without the manipulation transform's frame icon: must fail */
	uint8_t *less = shoot(&g, 2);
	assert_false(same_picture(less, px, "icons without the frame icon (expected to differ)"));
	/* and the pictures without icons differ from those with */
	uint8_t *none = shoot(&g, 0);
	assert_false(same_picture(none, px, "no icons (expected to differ)"));
	free(none);
	free(less);
	free(px);
	rig_free(&g);
}

/* ---- cameras ------------------------------------------------------------ */

static double
lcg(uint32_t *s)
{
	*s = *s * 1664525u + 1013904223u;
	return (*s >> 8) / 16777216.0;
}

static void
test_camera_center_and_twist(void **unused)
{
	(void)unused;
	uint32_t seed = 7;
	struct camera c;
	view_camera_default(&c);
	for (int i = 0; i < 500; i++) {
		double eye[3], target[3], px[2], vrp[3];
		for (int k = 0; k < 3; k++) {
			eye[k] = 10 * lcg(&seed) - 5;
			target[k] = 10 * lcg(&seed) - 5;
		}
		assert_int_equal(view_camera_aim(&c, eye, target), 0);
		/* no twist: x horizontal, y up-ish, a right-handed orthonormal frame */
		const double *r = c.xf.r;
		assert_true(fabs(r[3]) < 1e-12);
		assert_true(r[4] >= -1e-12);
		for (int a = 0; a < 3; a++)
			for (int b = 0; b < 3; b++) {
				double d = r[a] * r[b] + r[3 + a] * r[3 + b] + r[6 + a] * r[6 + b];
				assert_true(fabs(d - (a == b)) < 1e-12);
			}
		double det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
			     r[2] * (r[3] * r[7] - r[4] * r[6]);
		assert_true(fabs(det - 1) < 1e-12);
		/* -z looks at the target, which lies at the view reference distance */
		view_camera_vrp(&c, vrp);
		for (int k = 0; k < 3; k++)
			assert_true(fabs(vrp[k] - target[k]) < 1e-9);
		/* points on the line of sight project to the image centre */
		for (double t = 0.5; t < 3; t += 0.5) {
			double p[3];
			for (int k = 0; k < 3; k++)
				p[k] = eye[k] + t * (target[k] - eye[k]);
			if (t * c.vrd <= c.znear)
				continue;
			assert_int_equal(view_project(&c, 640, 480, p, px), 1);
			assert_true(fabs(px[0] - 320) < 1e-6 && fabs(px[1] - 240) < 1e-6);
		}
		/* a point behind the camera is not in view */
		double back[3];
		for (int k = 0; k < 3; k++)
			back[k] = eye[k] - (target[k] - eye[k]);
		assert_int_equal(view_project(&c, 640, 480, back, px), 0);
	}
	/* looking straight down keeps a horizontal x */
	double eye[3] = { 0, 5, 0 }, down[3] = { 0, 0, 0 };
	assert_int_equal(view_camera_aim(&c, eye, down), 0);
	assert_true(fabs(c.xf.r[3]) < 1e-12);
	assert_int_equal(view_camera_aim(&c, eye, eye), -1);
}

static void
test_camera_matrices(void **unused)
{
	(void)unused;
	/* the GL matrices put a point where view_project does; the mouse line inverts it */
	struct camera c;
	view_camera_default(&c);
	double eye[3] = { 1.2, 1.7, 2.5 }, target[3] = { -0.2, 0.8, 0.1 };
	view_camera_aim(&c, eye, target);
	float v[16], p[16];
	view_camera_view_matrix(&c, v);
	view_camera_proj_matrix(&c, 640.0 / 480, p);
	uint32_t seed = 3;
	for (int i = 0; i < 100; i++) {
		double q[3] = { lcg(&seed) - 0.5, 2 * lcg(&seed), lcg(&seed) - 0.5 }, px[2];
		float e[4], cl[4];
		for (int r = 0; r < 4; r++)
			e[r] = (float)(v[r] * q[0] + v[4 + r] * q[1] + v[8 + r] * q[2] + v[12 + r]);
		for (int r = 0; r < 4; r++)
			cl[r] = p[r] * e[0] + p[4 + r] * e[1] + p[8 + r] * e[2] + p[12 + r] * e[3];
		assert_int_equal(view_project(&c, 640, 480, q, px), 1);
		assert_true(fabs((cl[0] / cl[3] + 1) / 2 * 640 - px[0]) < 1e-3);
		assert_true(fabs((1 - cl[1] / cl[3]) / 2 * 480 - px[1]) < 1e-3);
		double o[3], d[3], back[2];
		view_mouse_line(&c, 640, 480, px[0], px[1], o, d);
		double t = (q[0] - o[0]) * d[0] + (q[1] - o[1]) * d[1] + (q[2] - o[2]) * d[2];
		for (int k = 0; k < 3; k++)
			assert_true(fabs(o[k] + t * d[k] - q[k]) < 1e-9);
		(void)back;
	}
}

/* ---- the frame allocates nothing ----------------------------------------- */

static void
test_frame_no_alloc(void **unused)
{
	(void)unused;
	struct rig g;
	rig_make(&g, "seated");
	struct frame f;
	for (int i = 0; i < 5; i++) {
		demo_scene_draw(g.dl, &g.sc, &g.cam, W, H, g.base, 1);
		render_frame(g.r, g.dl, 0, &f);
	}
#if COUNT_ALLOCS
	long before = allocs;
	for (int i = 0; i < 20; i++)
		demo_scene_draw(g.dl, &g.sc, &g.cam, W, H, g.base, 1);
	assert_int_equal(allocs - before, 0);
	/*
	 * render.c allocates nothing in render_frame; llvmpipe's binner takes
	 * scene memory from malloc and gives it back at the end of every
	 * frame. So: nothing may accumulate (allocations minus frees stay put).
	 */
	before = allocs;
	long live = allocs - frees;
	for (int i = 0; i < 20; i++)
		render_frame(g.r, g.dl, (uint64_t)i, &f);
	printf("# render_frame: 20 frames, %ld allocations by the driver, %ld still live\n",
	       allocs - before, allocs - frees - live);
	assert_true(allocs - frees - live <= 0);
#endif
#if COUNT_ALLOCS
	assert_int_equal(f.seq, 25);
#else
	assert_int_equal(f.seq, 5);
#endif
	rig_free(&g);
}

/* ---- a mesh made at run time ---------------------------------------------- */

/* pixels of the two pictures (W x H, packed) that differ by more than 8 in any channel */
static int
differing(const uint8_t *a, const uint8_t *b)
{
	int n = 0;
	for (int i = 0; i < W * H; i++)
		for (int k = 0; k < 3; k++)
			if (abs(a[4 * i + k] - b[4 * i + k]) > 8) {
				n++;
				break;
			}
	return n;
}

static uint8_t *
shoot_with(struct rig *g, int mesh, const float rgba[4])
{
	static const float identity[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
	struct frame f;
	demo_scene_draw(g->dl, &g->sc, &g->cam, W, H, g->base, 0);
	if (mesh >= 0)
		assert_true(view_add_instance(g->dl, mesh, identity, rgba, 0) >= 0);
	assert_int_equal(render_frame(g->r, g->dl, 0, &f), 0);
	uint8_t *px = malloc(4 * W * H);
	for (int y = 0; y < H; y++)
		memcpy(px + 4 * W * y, f.rgba + (size_t)f.stride * y, 4 * W);
	return px;
}

/*
 * render_set_mesh: a see-through sphere about the figure's chest changes the
 * picture where it covers, and only there and translucently (the figure shows
 * through: the pixels are neither the background's nor the sphere's flat
 * colour); emptied, the picture is the one without it; replaced by a bigger
 * one, more changes; bad meshes and ids refused.
 */
static void
test_run_time_mesh(void **unused)
{
	(void)unused;
	struct rig g;
	rig_make(&g, "standing");
	char err[256];
	struct icosphere s, big;
	const double c[3] = { 0, 1.2, 0 };
	icosphere_make(&s, 3, 0.3, c);
	icosphere_make(&big, 3, 0.6, c);
	const float blue[4] = { 0.25f, 0.55f, 0.95f, 0.3f };
	uint8_t *plain = shoot_with(&g, -1, blue);
	int id = render_set_mesh(g.r, -1, s.vert, s.normal, s.nvert, s.tri, s.ntri, err, sizeof err);
	assert_true(id >= VIEW_MESH_BUILTIN);
	uint8_t *with = shoot_with(&g, id, blue);
	int small_n = differing(plain, with);
	assert_true(small_n > 500);
	/* the centre pixel (the chest behind the sphere) is tinted, not replaced */
	double px[2];
	assert_int_equal(view_project(&g.cam, W, H, c, px), 1);
	int i = 4 * (W * (int)px[1] + (int)px[0]);
	assert_true(with[i + 2] > plain[i + 2]); /* bluer */
	assert_true(abs(with[i] - plain[i]) < 200);
	assert_int_equal(render_set_mesh(g.r, id, big.vert, big.normal, big.nvert, big.tri, big.ntri,
					 err, sizeof err), id);
	uint8_t *bigger = shoot_with(&g, id, blue);
	assert_true(differing(plain, bigger) > small_n * 2);
	assert_int_equal(render_set_mesh(g.r, id, NULL, NULL, 0, NULL, 0, err, sizeof err), id);
	uint8_t *emptied = shoot_with(&g, id, blue);
	assert_int_equal(differing(plain, emptied), 0);
	/* refused: an index past the vertices, a built-in mesh's id */
	s.tri[7] = s.nvert;
	assert_int_equal(render_set_mesh(g.r, id, s.vert, s.normal, s.nvert, s.tri, s.ntri, err,
					 sizeof err), -1);
	assert_int_equal(render_set_mesh(g.r, VIEW_MESH_SPHERE, big.vert, big.normal, big.nvert,
					 big.tri, big.ntri, err, sizeof err), -1);
	free(plain);
	free(with);
	free(bigger);
	free(emptied);
	icosphere_free(&s);
	icosphere_free(&big);
	rig_free(&g);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_camera_center_and_twist),
		cmocka_unit_test(test_camera_matrices),
		cmocka_unit_test(test_golden_standing),
		cmocka_unit_test(test_golden_seated),
		cmocka_unit_test(test_golden_icons),
		cmocka_unit_test(test_frame_no_alloc),
		cmocka_unit_test(test_run_time_mesh),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
