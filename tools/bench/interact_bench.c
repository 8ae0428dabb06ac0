/*
 * interact_bench - the cost of one interactive frame (its target:
 * median at most 0.5 ms): the pointer moves, the mode turns it into a
 * mouse line and the operator moves G (interact_input), the feature under
 * the pointer is picked, G feeds the behaviour primitive (move hand), and
 * the behaviours solve the frame (behave_frame, the default step factor
 * and 10 ms limit). The standing human, behaviours on, the right palm
 * dragged along x and y in a 30 cm circle seen from the front, 240 frames.
 * Prints the whole frame and the interaction's own share (all but the
 * solve).
 */
#include <linux/input-event-codes.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bench_util.h"
#include "figure/human.h"
#include "figure/kin.h"
#include "interact/interact.h"
#include "interact/mouse_line.h"
#include "interact/pick.h"
#include "pose/behave.h"

#define FRAMES 240

int
main(void)
{
	char err[256];
	struct human_def hd = human_default_def(HUMAN_MALE);
	struct model *m = human_build(&hd, err, sizeof err);
	struct state *s = m ? state_make(m) : NULL;
	struct ik *ik = m ? ik_make(m, 32) : NULL;
	struct behave b;
	if (!m || !s || !ik)
		return 1;
	kin_update(m, s);
	if (behave_attach(&b, m, s, ik, NULL) < 0)
		return 1;
	struct pick_model *pm = pick_model_make(m);
	if (!pm)
		return 1;
	struct ik_clock clock = { bench_clock_us, NULL };
	struct ik_options opt = ik_default_options();
	for (int f = 0; f < 5; f++)
		behave_frame(&b, m, s, ik, &opt, &clock);

	struct camera cam;
	double eye[3] = { 0, 1.2, 3 }, target[3] = { 0, 1, 0 };
	view_camera_default(&cam);
	view_camera_aim(&cam, eye, target);
	const int w = 640, h = 480;
	static struct interact ia;
	interact_init(&ia);
	struct xform g = s->site_xf[b.s_palm[1]];
	interact_start(&ia, INTERACT_PRIMITIVE, 0, 0, &g, &g, &cam, w, h);
	/* two buttons: the palm moves in the xy plane facing the camera */
	struct input_event_rec e = { .kind = INPUT_BUTTON, .code = BTN_LEFT, .value = 1 };
	interact_input(&ia, &e, 0, 0, &cam, w, h);
	e.code = BTN_MIDDLE;
	interact_input(&ia, &e, 0, 0, &cam, w, h);

	double whole[FRAMES], own[FRAMES];
	struct pick_target t = { pm, m, s };
	int hits = 0;
	for (int f = 0; f < FRAMES; f++) {
		double a = 2 * M_PI * (f + 1) / FRAMES;
		/* the pointer round a circle of about 30 cm at the palm's distance */
		struct input_event_rec mv = { .kind = INPUT_MOTION };
		long dx = lround(-8 * sin(a)), dy = lround(-8 * cos(a));
		double t0 = bench_now_us();
		int r = interact_input(&ia, &mv, dx, dy, &cam, w, h);
		struct ray ray;
		struct pick_hit hit;
		if (mouse_line(&cam, w, h, ia.px, ia.py, &ray) == 0)
			hits += pick_scene(&t, 1, &ray, cam.znear, &hit);
		if (r & INTERACT_MOVED) {
			struct xform goal;
			interact_target(&ia, &goal);
			behave_move_hand(&b, m, s, ik, 1, &goal, 0);
		}
		double t1 = bench_now_us();
		behave_frame(&b, m, s, ik, &opt, &clock);
		double t2 = bench_now_us();
		whole[f] = t2 - t0;
		own[f] = t1 - t0;
	}
	double med = bench_percentile(whole, FRAMES, 0.5), p95 = bench_percentile(whole, FRAMES, 0.95);
	double omed = bench_percentile(own, FRAMES, 0.5), op95 = bench_percentile(own, FRAMES, 0.95);
	printf("BENCH interact.frame median_us=%.1f p95_us=%.1f interaction_median_us=%.1f "
	       "interaction_p95_us=%.1f frames=%d picks_hit=%d\n",
	       med, p95, omed, op95, FRAMES, hits);
	pick_model_free(pm);
	ik_free(ik);
	state_free(s);
	model_free(m);
	return 0;
}
