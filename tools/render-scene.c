/*
 * render-scene - renders a scene of the standard human to a PNG file, and
 * measures the renderer (render + readback) with --bench.
 *
 * Scenes: "standing" (the human's rest posture), "seated" (in the vehicle
 * seat: pelvis on the H-point, heels on the heel points, hands on the
 * steering wheel, solved by the IK of ik.h). --icons adds every icon: the
 * manipulation transform's frame on the right hand, the translation arrow,
 * the right elbow's rotation wheel with its limits, the rotation fans to a
 * turned hand goal, the goal icons of the IK constraints, the balance
 * icons, the status and message lines and the pointer.
 */
#include <errno.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "figure/figure.h"
#include "figure/human.h"
#include "pose/ik.h"
#include "figure/kin.h"
#include "draw/render.h"
#include "draw/demo_scene.h"
#include "draw/view.h"

static const char usage[] =
	"usage: render-scene [OPTIONS]\n"
	"  --scene standing|seated   what to show (default standing)\n"
	"  --icons                   every icon, the status and message lines, the pointer\n"
	"  --size WxH                image size (default 640x480)\n"
	"  --samples 0|4             multisampling (default 0)\n"
	"  --no-shadows              no shadows on the floor\n"
	"  --eye X,Y,Z --target X,Y,Z  the camera (default: the scene's)\n"
	"  --seat FILE               the vehicle seat figure (default src/figure/library/vehicle_seat.fig)\n"
	"  --out FILE.png            write the picture (default scene.png)\n"
	"  --bench N                 render N frames after 20 of warm-up and print timings\n";

#define DEG (M_PI / 180)

static int
parse_vec(const char *s, double dest[3])
{
	return sscanf(s, "%lf,%lf,%lf", &dest[0], &dest[1], &dest[2]) == 3 ? 0 : -1;
}

static double
now_s(void)
{
	struct timespec t;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return t.tv_sec + t.tv_nsec * 1e-9;
}

static int
cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

static int
write_png(const char *path, const struct frame *f)
{
	png_image img;
	memset(&img, 0, sizeof img);
	img.version = PNG_IMAGE_VERSION;
	img.width = (png_uint_32)f->width;
	img.height = (png_uint_32)f->height;
	img.format = PNG_FORMAT_RGBA;
	return png_image_write_to_file(&img, path, 0, f->rgba, f->stride, NULL) ? 0 : -1;
}

int
main(int argc, char **argv)
{
	const char *scene = "standing", *out = "scene.png", *seat = "src/figure/library/vehicle_seat.fig";
	int w = 640, h = 480, icons = 0, bench = 0, have_eye = 0, have_target = 0;
	double eye[3], target[3];
	struct render_def rd = render_default_def();
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
		if (!strcmp(a, "--icons")) {
			icons = 1;
		} else if (!strcmp(a, "--no-shadows")) {
			rd.shadows = 0;
		} else if (v && !strcmp(a, "--scene")) {
			scene = argv[++i];
		} else if (v && !strcmp(a, "--size") && sscanf(v, "%dx%d", &w, &h) == 2) {
			i++;
		} else if (v && !strcmp(a, "--samples")) {
			rd.samples = atoi(argv[++i]);
		} else if (v && !strcmp(a, "--eye") && !parse_vec(v, eye)) {
			have_eye = 1, i++;
		} else if (v && !strcmp(a, "--target") && !parse_vec(v, target)) {
			have_target = 1, i++;
		} else if (v && !strcmp(a, "--seat")) {
			seat = argv[++i];
		} else if (v && !strcmp(a, "--out")) {
			out = argv[++i];
		} else if (v && !strcmp(a, "--bench")) {
			bench = atoi(argv[++i]);
		} else {
			fputs(usage, stderr);
			return 2;
		}
	}
	char err[256];
	struct demo_scene sc;
	if (demo_scene_make(&sc, scene, seat, err, sizeof err)) {
		fprintf(stderr, "render-scene: %s\n", err);
		return 1;
	}
	rd.max_w = w;
	rd.max_h = h;
	struct render *r = render_make(&rd, err, sizeof err);
	struct drawlist *dl = view_drawlist_make();
	int base[2] = { 0, 0 };
	if (!r || !dl || (base[0] = render_add_model(r, sc.human, err, sizeof err)) < 0 ||
	    (sc.seat && (base[1] = render_add_model(r, sc.seat, err, sizeof err)) < 0)) {
		fprintf(stderr, "render-scene: %s\n", dl ? err : "out of memory");
		return 1;
	}
	struct camera cam;
	demo_scene_camera(&sc, &cam);
	if (have_eye || have_target) {
		double e[3], t[3];
		memcpy(e, cam.xf.p, sizeof e);
		view_camera_vrp(&cam, t);
		view_camera_aim(&cam, have_eye ? eye : e, have_target ? target : t);
	}
	struct frame f;
	if (bench > 0) {
		/* render + readback per frame, the draw list rebuilt each time as the loop will */
		double *t = malloc(sizeof(double) * (size_t)bench);
		for (int i = 0; i < 20 + bench; i++) {
			double t0 = now_s();
			demo_scene_draw(dl, &sc, &cam, w, h, base, icons);
			render_frame(r, dl, 0, &f);
			if (i >= 20)
				t[i - 20] = now_s() - t0;
		}
		qsort(t, (size_t)bench, sizeof *t, cmp_double);
		struct render_stats st = render_last_stats(r);
		printf("render-scene: %s%s %dx%d samples %d shadows %d: median %.3f ms "
		       "(%.1f fps), instances %d, triangles %d, icon vertices %d\n",
		       scene, icons ? "+icons" : "", w, h, rd.samples, rd.shadows, 1e3 * t[bench / 2],
		       1 / t[bench / 2], st.instances, st.triangles, st.vertices);
		printf("BENCH render.%dx%d.posture fps=%.1f\n", w, h, 1 / t[bench / 2]);
		free(t);
	} else {
		demo_scene_draw(dl, &sc, &cam, w, h, base, icons);
		render_frame(r, dl, 0, &f);
		if (dl->dropped)
			fprintf(stderr, "render-scene: %d items did not fit the draw list\n", dl->dropped);
		if (write_png(out, &f)) {
			fprintf(stderr, "render-scene: cannot write %s\n", out);
			return 1;
		}
	}
	view_drawlist_free(dl);
	render_free(r);
	demo_scene_free(&sc);
	return 0;
}
