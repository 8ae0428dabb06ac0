/*
 * ik_body - the BODY benchmark of inverse kinematics: the standing human
 * with both feet held, balance on and the torso kept vertical (stance.h),
 * one hand (palm position and orientation, solved after the body) moved to
 * 200 random reachable targets: the palm frames of random arm postures of
 * the stance at rest (settled with its knee springs). Each target starts
 * from that rest posture; frames are ik_solve calls with the default step factor (25 cm,
 * 5 degrees) and time limit (the hand, not the body, may restart from a
 * random arm posture when trapped at its joint limits), until the hand is within 1 mm and 1 degree
 * with the feet held (1 mm, 1 degree) and the centre of mass within 5 mm of
 * the balance line, or 300 frames.
 *
 * Prints the per-frame solve time (median, p95, max), the frames to reach
 * a target and the success rate, as BENCH lines.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_util.h"
#include "figure/human.h"
#include "pose/ik.h"
#include "figure/kin.h"
#include "pose/stance.h"

#define TARGETS 200
#define MAX_FRAMES 300
#define DEG (M_PI / 180)





/* every constraint of the stance and the hand met to the success test */
static int
reached(const struct ik *ik, const struct model *m, const struct state *s, const struct stance *st)
{
	double pe, oe;
	ik_constraint_error(ik, m, s, st->hand_r, &pe, &oe);
	if (pe > 1e-3 || oe > DEG)
		return 0;
	ik_constraint_error(ik, m, s, st->foot_r, &pe, &oe);
	if (pe > 1e-3 || oe > DEG)
		return 0;
	double dx = s->com[0] - st->balance_point[0], dz = s->com[2] - st->balance_point[2];
	if (dx * dx + dz * dz > 5e-3 * 5e-3)
		return 0;
	for (int d = 0; d < m->ndof; d++)
		if (s->q[d] < m->dof_lo[d] || s->q[d] > m->dof_hi[d])
			return 0;
	return 1;
}

int
main(void)
{
	char err[256];
	struct human_def def = human_default_def(HUMAN_MALE);
	struct model *m = human_build(&def, err, sizeof err);
	if (!m) {
		fprintf(stderr, "ik_body: %s\n", err);
		return 1;
	}
	struct state *s = state_make(m), *probe = state_make(m), *rest = state_make(m);
	kin_update(m, s);
	kin_update(m, probe);
	kin_update(m, rest);
	struct ik *ik = ik_make(m, 8);
	struct stance st;
	if (stance_standing(ik, m, s, &st) < 0 || stance_hand(ik, m, s, &st, 1) < 0) {
		fprintf(stderr, "ik_body: could not set up the stance\n");
		return 1;
	}
	int clav = model_find_joint(m, "clavicle_r"), wrist = model_find_joint(m, "wrist_r");
	int palm = model_find_site(m, "hand_r.palm");
	int d0 = m->jnt_dof0[clav], d1 = m->jnt_dof0[wrist] + m->jnt_ndof[wrist];
	struct ik_options opt = ik_default_options();
	/* a hand trapped at its joint limits may start again elsewhere; the body may not */
	opt.restarts = 2;
	opt.restart_groups = 1u << 1;
	opt.restart_after = 50;
	struct ik_clock clock = { bench_clock_us, NULL };

	/* the rest posture: the stance settled "at ease" (knees off full extension) */
	for (int i = 0; i < 50; i++)
		ik_solve(ik, m, s, &opt, &clock);
	state_copy(m, s, rest);

	static double frame_us[TARGETS * MAX_FRAMES];
	double frames_to[TARGETS];
	int nframes = 0, ok = 0, cut = 0, rounds = 0, solves = 0, restarts = 0;
	srand(2);
	for (int t = 0; t < TARGETS; t++) {
		/* a reachable target: the palm of a random arm posture at rest */
		state_copy(m, rest, probe);
		for (int d = d0; d < d1; d++)
			probe->q[d] = m->dof_lo[d] + (m->dof_hi[d] - m->dof_lo[d]) * rand() / RAND_MAX;
		kin_update(m, probe);
		ik_set_goal(ik, st.hand_r, &probe->site_xf[palm]);
		/* from the rest posture */
		state_copy(m, rest, s);
		int f = 0, done = 0;
		for (; f < MAX_FRAMES && !done; f++) {
			double t0 = bench_now_us();
			struct ik_result r = ik_solve(ik, m, s, &opt, &clock);
			frame_us[nframes++] = bench_now_us() - t0;
			cut += r.status == IK_TIME_LIMIT;
			rounds += r.balance_rounds;
			restarts += r.restarts;
			solves++;
			done = !r.stepped && reached(ik, m, s, &st);
		}
		frames_to[t] = f;
		ok += done;
	}
	int n = nframes;
	double med = bench_percentile(frame_us, n, 0.5), p95 = bench_percentile(frame_us, n, 0.95);
	double max = frame_us[n - 1];
	double fmed = bench_percentile(frames_to, TARGETS, 0.5), fp95 = bench_percentile(frames_to, TARGETS, 0.95);
	printf("ik_body: %d targets, %d frames, time limit %.1f ms, step %.0f cm / %.0f deg, "
	       "%.2f balance rounds a frame, %d frames cut by the time limit\n",
	       TARGETS, n, opt.budget_us / 1e3, opt.step_pos * 100, opt.step_ori / DEG,
	       (double)rounds / solves, cut);
	printf("BENCH ik.body.frame median_us=%.1f p95_us=%.1f max_us=%.1f\n", med, p95, max);
	printf("BENCH ik.body.reach success=%.1f frames_median=%.0f frames_p95=%.0f restarts=%.2f\n",
	       100.0 * ok / TARGETS, fmed, fp95, (double)restarts / TARGETS);
	ik_free(ik);
	state_free(s);
	state_free(probe);
	state_free(rest);
	model_free(m);
	return 0;
}
