/*
 * behave_bench - the full default behaviour set, frame by frame, while each
 * manipulation primitive is dragged along a scripted path: the per-frame
 * time (median, p95, max) of behave_frame (behaviours, then the solve with
 * the default step factor and a 10 ms time limit) on one core.
 *
 * Paths, 120 frames each, the goal moving every frame as a drag would:
 * foot: the left toes 25 cm forward and back out; com: the balance point
 * in a 6 cm circle; elevation: the centre of mass down 20 cm and up;
 * torso: a bend forward to 40 degrees and back; pelvis: a turn to 30
 * degrees and back; hand: the right palm in a 30 cm circle in front;
 * head and eyes: the fixation point across a 2 m arc.
 *
 * Then the same with a 15 kg weight in the right hand (behave_set_masses:
 * balance holds the centre of mass with it), as behave.PRIM.loaded: what
 * balance feeling the load costs a frame.
 *
 * "behave_bench -v" also prints each frame's solve (time, rounds,
 * iterations, evaluations, energy, limits) for the one who has to find out
 * where a slow frame goes.
 */
#include <stdio.h>
#include <string.h>

#include "bench_util.h"
#include "pose/behave.h"
#include "figure/human.h"
#include "figure/kin.h"

#define FRAMES 120
#define DEG (M_PI / 180)

enum prim { FOOT, COM, ELEVATION, TORSO, PELVIS, HAND, HEAD, EYES, NPRIM };
static const char *const names[NPRIM] = { "foot", "com", "elevation", "torso",
					  "pelvis", "hand", "head", "eyes" };

/* moves primitive p to the point t (0..1) of its path */
static double elev0; /* the centre of mass's height when the path starts */

static void
drive(enum prim p, double t, struct behave *b, const struct model *m, struct state *s,
      struct ik *ik, const struct xform *foot0, const struct xform *palm0)
{
	double w = sin(M_PI * t); /* out and back */
	switch (p) {
	case FOOT: {
		struct xform g = *foot0;
		g.p[2] += 0.25 * w;
		g.p[0] += 0.05 * w;
		behave_move_foot(b, m, s, ik, BEHAVE_LEFT, &g);
		break;
	}
	case COM: {
		double a = 2 * M_PI * t, target[2] = { 0.03 * cos(a), 0.02 + 0.03 * sin(a) };
		behave_move_com(b, m, s, ik, target[0] - b->bal_point[0], target[1] - b->bal_point[1],
				0);
		break;
	}
	case ELEVATION: /* the held elevation follows the path from where it started */
		behave_move_com(b, m, s, ik, 0, 0, elev0 - 0.20 * w - s->com[1]);
		break;
	case TORSO: {
		double total[3] = { 40 * DEG * w, 0, 0 };
		struct spine_flavor f = spine_bend_from_waist();
		behave_bend_torso(b, m, s, ik, total, &f);
		break;
	}
	case PELVIS: {
		double q[4], r[9], axis[3] = { 0, 1, 0 }, rel[9];
		mathx_quat_axis_angle(axis, 30 * DEG * (sin(M_PI * t) - sin(M_PI * (t - 1.0 / FRAMES))), q);
		mathx_quat_to_mat(q, r);
		memcpy(rel, r, sizeof rel);
		behave_rotate_pelvis(b, m, s, ik, rel);
		break;
	}
	case HAND: {
		struct xform g = *palm0;
		double a = 2 * M_PI * t;
		g.p[1] += 0.25 + 0.15 * sin(a);
		g.p[2] += 0.30 + 0.15 * cos(a);
		behave_move_hand(b, m, s, ik, BEHAVE_RIGHT, &g, 0);
		break;
	}
	case HEAD:
	case EYES: {
		double a = -60 * DEG + 120 * DEG * t, pt[3] = { 2 * sin(a), 1.5, 2 * cos(a) };
		if (p == HEAD)
			behave_move_head(b, ik, pt);
		else
			behave_move_eyes(b, ik, pt);
		break;
	}
	case NPRIM:
		break;
	}
}

int
main(int argc, char **argv)
{
	int verbose = argc > 1 && strcmp(argv[1], "-v") == 0;
	char err[256];
	struct human_def hd = human_default_def(HUMAN_MALE);
	struct ik_clock clock = { bench_clock_us, NULL };
	double us[FRAMES];
	for (int run = 0; run < 2 * NPRIM; run++) {
		int p = run % NPRIM, loaded = run >= NPRIM;
		struct model *m = human_build(&hd, err, sizeof err);
		struct state *s = state_make(m);
		struct ik *ik = ik_make(m, 32);
		struct behave b;
		if (m && s)
			kin_update(m, s);
		if (!m || !s || !ik || behave_attach(&b, m, s, ik, NULL) < 0) {
			fprintf(stderr, "behave_bench: setup failed\n");
			return 1;
		}
		struct ik_options opt = ik_default_options();
		if (loaded) { /* 15 kg at the right palm, on the hand's segment */
			int palm = b.s_palm[1];
			struct point_mass box = { m->site_seg[palm], { 0, 0, 0 }, 15 };
			memcpy(box.local, m->site_loc[palm].p, sizeof box.local);
			behave_set_masses(&b, m, s, &box, 1);
		}
		for (int f = 0; f < 5; f++) /* settle "at ease" first */
			behave_frame(&b, m, s, ik, &opt, &clock);
		struct xform foot0 = s->site_xf[b.s_toe[0]], palm0 = s->site_xf[b.s_palm[1]];
		elev0 = s->com[1];
		for (int f = 0; f < FRAMES; f++) {
			drive((enum prim)p, (f + 1.0) / FRAMES, &b, m, s, ik, &foot0, &palm0);
			double t0 = bench_now_us();
			struct ik_result r = behave_frame(&b, m, s, ik, &opt, &clock);
			us[f] = bench_now_us() - t0;
			if (verbose)
				printf("%s %3d us=%7.1f rounds=%d iter=%3d evals=%4d f=%.3g->%.3g "
				       "limits=%d met=%d %s steps=%d margin=%.3f heels=%.3f,%.3f\n",
				       names[p], f, us[f], r.balance_rounds, r.iterations,
				       r.evaluations, r.f_start, r.f_end, r.active_limits, r.met,
				       ik_status_to_str(r.status), b.steps_taken, b.bal.margin,
				       s->site_xf[b.s_heel[0]].p[1], s->site_xf[b.s_heel[1]].p[1]);
		}
		double med = bench_percentile(us, FRAMES, 0.5), p95 = bench_percentile(us, FRAMES, 0.95);
		printf("BENCH behave.%s%s median_us=%.1f p95_us=%.1f max_us=%.1f steps=%d\n", names[p],
		       loaded ? ".loaded" : "", med, p95, us[FRAMES - 1], b.steps_taken); /* sorted */
		ik_free(ik);
		state_free(s);
		model_free(m);
	}
	return 0;
}
