/*
 * test_ik_work.c - a solve cut by a deadline replays bit for bit from the
 * record of its work (ik_work.h), without a clock: the right arm alone and
 * the behaving human dragging a hand, hundreds of frames in sequence under
 * a clock that jumps by a random amount at every read; the record's line
 * of text; a record one count off replays to another posture.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "test_util.h"
#include "test_human.h"
#include "test_random.h"

#include <limits.h>
#include <stdio.h>
#include <string.h>

#include "figure/human.h"
#include "figure/kin.h"
#include "pose/behave.h"
#include "pose/ik.h"
#include "pose/ik_work.h"

#include "alloc_count.h"

#define FRAMES 300

/* ---- clocks ----------------------------------------------------------------- */

/* jumps by a random amount, up to max_step us, at every read */
struct jumpy_clock {
	uint64_t t, max_step;
};

static uint64_t
jumpy_now(void *ctx)
{
	struct jumpy_clock *c = ctx;
	return c->t += (uint64_t)(urand() * (double)c->max_step);
}

/* a replay must not look at the time */
static uint64_t
forbidden_now(void *ctx)
{
	(void)ctx;
	fail_msg("a replay read the clock");
	return 0;
}

static const struct ik_clock FORBIDDEN = { forbidden_now, NULL };

/* a different cut point each frame: from a few iterations to none */
static void
jumpy_frame(struct jumpy_clock *c)
{
	static const uint64_t STEPS[] = { 5, 20, 60, 150, 400, 2000 };
	c->max_step = STEPS[(int)(urand() * 6)];
}

/* ---- what a replay must reproduce --------------------------------------------- */

/* the record through its line of text, as a frame log holds it */
static struct ik_work
through_text(const struct ik_work *w)
{
	char line[IK_WORK_LINE_MAX], err[160];
	struct ik_work back;
	assert_true(ik_work_write(w, line, sizeof line) > 0);
	if (ik_work_read(line, &back, err, sizeof err) < 0)
		fail_msg("%s: %s", line, err);
	assert_true(ik_work_equal(w, &back));
	return back;
}

static void
assert_same_posture(const struct model *m, const struct state *a, const struct state *b, int frame)
{
	if (state_hash(m, a) != state_hash(m, b) ||
	    memcmp(a->q, b->q, sizeof *a->q * (size_t)m->ndof) != 0 ||
	    memcmp(&a->root_xf, &b->root_xf, sizeof a->root_xf) != 0)
		fail_msg("frame %d: the replay left another posture", frame);
}

static void
assert_same_solve(const struct ik_result *live, const struct ik_result *replay, int frame)
{
	char a[IK_WORK_LINE_MAX], b[IK_WORK_LINE_MAX];
	ik_work_write(&live->work, a, sizeof a);
	ik_work_write(&replay->work, b, sizeof b);
	if (!ik_work_equal(&live->work, &replay->work) || live->status != replay->status ||
	    live->iterations != replay->iterations || live->restarts != replay->restarts ||
	    live->balance_rounds != replay->balance_rounds || live->f_end != replay->f_end)
		fail_msg("frame %d: live \"%s\" (%s), replay \"%s\" (%s)", frame, a,
			 ik_status_to_str(live->status), b, ik_status_to_str(replay->status));
}

/* how varied the cuts were, so the test knows it tried what it claims */
struct cut_tally {
	int cut, ended, after_restart, late_round, group[IK_MAX_GROUPS];
};

static void
tally(struct cut_tally *t, const struct ik_work *w)
{
	if (!w->cut) {
		t->ended++;
		return;
	}
	t->cut++;
	t->after_restart += w->start > 0;
	t->late_round += w->round > 0;
	t->group[w->group]++;
}

/* ---- the right arm ------------------------------------------------------------ */


/* the palm's position and orientation, the chain from the right clavicle */
static struct ik *
arm_problem(const struct model *m)
{
	struct ik *ik = ik_make(m, 2);
	assert_non_null(ik);
	struct ik_constraint_def c = ik_constraint_default_def();
	c.effector_site = model_find_site(m, "hand_r.palm");
	c.ori = IK_FRAME;
	c.pos_weight = 0.5;
	c.start_joint = model_find_joint(m, "clavicle_r");
	c.goal_xf.p[0] = -0.3;
	c.goal_xf.p[1] = 1.3;
	c.goal_xf.p[2] = 0.4;
	assert_int_equal(ik_add(ik, m, &c), 0);
	return ik;
}

/* the goal dragged round a loop in front of the shoulder, sometimes out of reach */
static void
drag_goal(struct ik *ik, int frame)
{
	double a = 0.07 * frame;
	struct xform g = ik_get(ik, 0)->goal_xf;
	g.p[0] = -0.3 + 0.35 * cos(a);
	g.p[1] = 1.3 + 0.35 * sin(1.3 * a);
	g.p[2] = 0.4 + 0.3 * sin(0.5 * a);
	double axis[3] = { 1, 0, 0 }, q[4];
	mathx_quat_axis_angle(axis, -1.2 + 0.8 * sin(0.3 * a), q);
	mathx_quat_to_mat(q, g.r);
	ik_set_goal(ik, 0, &g);
}

/*
 * Every frame: a live solve under the jumpy clock from where the last one
 * ended, then the frame's starting state restored into another state and
 * replayed from the record: the same posture, bit for bit.
 */
static void
test_arm_replays_bit_for_bit(void **unused)
{
	(void)unused;
	rng_state = 15;
	struct model *m = test_human();
	struct state *s = state_make(m), *before = state_make(m), *replayed = state_make(m);
	kin_update(m, s);
	struct ik *ik = arm_problem(m);
	struct ik_options live = ik_default_options();
	live.budget_us = 400;
	live.restarts = 2; /* a cut may come after a restart */
	live.restart_after = 20;
	struct ik_options replay = live;
	struct jumpy_clock jc = { 1000, 0 };
	struct ik_clock clock = { jumpy_now, &jc };
	struct cut_tally t = { 0 };
#if COUNT_ALLOCS
	long before_frames = allocs;
	state_free(state_make(m)); /* the hook sees allocations */
	assert_true(allocs > before_frames);
	before_frames = allocs;
#endif
	for (int f = 0; f < FRAMES; f++) {
		drag_goal(ik, f);
		jumpy_frame(&jc);
		state_copy(m, s, before);
		struct ik_result lr = ik_solve(ik, m, s, &live, &clock);
		tally(&t, &lr.work);
		struct ik_work w = through_text(&lr.work);
		state_copy(m, before, replayed);
		replay.replay = &w;
		struct ik_result rr = ik_solve(ik, m, replayed, &replay, &FORBIDDEN);
		assert_same_solve(&lr, &rr, f);
		assert_same_posture(m, s, replayed, f);
	}
#if COUNT_ALLOCS
	assert_int_equal(allocs - before_frames, 0); /* neither solve, nor the record's text */
#endif
	print_message("arm: %d frames cut (%d after a restart), %d ended on their own\n", t.cut,
		      t.after_restart, t.ended);
	assert_true(t.cut > FRAMES / 4 && t.ended > FRAMES / 10 && t.after_restart > 0);
	ik_free(ik);
	state_free(s);
	state_free(before);
	state_free(replayed);
	model_free(m);
}

/* replays lr's work with iterations moved by delta; 1 when the posture differs from s's */
static int
replay_off_by(struct ik *ik, const struct model *m, const struct state *before,
	      const struct state *s, const struct ik_result *lr, int delta, struct state *replayed)
{
	struct ik_work w = lr->work;
	w.iterations += delta;
	struct ik_options o = ik_default_options();
	o.replay = &w;
	state_copy(m, before, replayed);
	struct ik_result rr = ik_solve(ik, m, replayed, &o, &FORBIDDEN);
	assert_false(ik_work_equal(&rr.work, &lr->work));
	return state_hash(m, replayed) != state_hash(m, s);
}

/*
 * A record of a cut one count off cuts elsewhere, and the posture shows it
 * (so the test above can fail): one iteration fewer, or one more.
 */
static void
test_a_record_one_count_off_replays_to_another_posture(void **unused)
{
	(void)unused;
	rng_state = 16;
	struct model *m = test_human();
	struct state *s = state_make(m), *before = state_make(m), *replayed = state_make(m);
	kin_update(m, s);
	struct ik *ik = arm_problem(m);
	struct ik_options live = ik_default_options();
	live.budget_us = 400;
	struct jumpy_clock jc = { 1000, 0 };
	struct ik_clock clock = { jumpy_now, &jc };
	int cuts = 0, fewer = 0, more = 0;
	for (int f = 0; f < FRAMES; f++) {
		drag_goal(ik, f);
		jumpy_frame(&jc);
		state_copy(m, s, before);
		struct ik_result lr = ik_solve(ik, m, s, &live, &clock);
		if (!lr.work.cut || lr.work.iterations < 1)
			continue;
		cuts++;
		fewer += replay_off_by(ik, m, before, s, &lr, -1, replayed);
		more += replay_off_by(ik, m, before, s, &lr, +1, replayed);
	}
	print_message("one count off: of %d cuts, %d replays one iteration short and %d one "
		      "iteration long ended elsewhere\n", cuts, fewer, more);
	/* an iteration whose line search failed, or that found the start settled,
	 * moves nothing, so not every one */
	assert_true(cuts > FRAMES / 4 && fewer > cuts * 9 / 10 && more > cuts * 9 / 10);
	ik_free(ik);
	state_free(s);
	state_free(before);
	state_free(replayed);
	model_free(m);
}

/* ---- the behaving human --------------------------------------------------------- */

struct rig {
	struct model *m;
	struct state *s;
	struct ik *ik;
	struct behave b;
};

static void
rig_make(struct rig *r)
{
	char err[200];
	struct human_def hd = human_default_def(HUMAN_MALE);
	r->m = human_build(&hd, err, sizeof err);
	assert_non_null(r->m);
	r->s = state_make(r->m);
	kin_update(r->m, r->s);
	r->ik = ik_make(r->m, 32);
	struct behave_params p = behave_default_params();
	assert_int_equal(behave_attach(&r->b, r->m, r->s, r->ik, &p), 0);
}

static void
rig_free(struct rig *r)
{
	ik_free(r->ik);
	state_free(r->s);
	model_free(r->m);
}

/* the right palm dragged forward, up, across and back down; now and then
 * the centre of mass pushed forward, past the toes, so the figure steps */
static void
drag_hand(struct rig *r, const struct xform *start, int frame)
{
	if (frame % 100 == 50)
		behave_move_com(&r->b, r->m, r->s, r->ik, 0, 0.35, 0);
	double a = 0.05 * frame;
	struct xform g = *start;
	g.p[0] += 0.25 * (1 - cos(a));
	g.p[1] += 0.45 * sin(0.7 * a);
	g.p[2] += 0.35 * sin(a);
	behave_move_hand(&r->b, r->m, r->s, r->ik, BEHAVE_RIGHT, &g, 0);
}

/*
 * Two rigs set up alike: the first lives under the jumpy clock, the second
 * replays each of its frames from the record, starting where the first
 * started. Balance rounds, groups (the body, then the hand) and steps
 * all take part; both stay equal, bit for bit, frame after frame.
 */
static void
test_behaving_human_replays_bit_for_bit(void **unused)
{
	(void)unused;
	rng_state = 17;
	struct rig live, replay;
	rig_make(&live);
	rig_make(&replay);
	struct xform start = live.s->site_xf[live.b.s_palm[BEHAVE_RIGHT]];
	struct ik_options lo = ik_default_options();
	lo.budget_us = 1500;
	struct ik_options ro = lo;
	struct jumpy_clock jc = { 1000, 0 };
	struct ik_clock clock = { jumpy_now, &jc };
	struct cut_tally t = { 0 };
	for (int f = 0; f < FRAMES; f++) {
		assert_same_posture(live.m, live.s, replay.s, f);
		drag_hand(&live, &start, f);
		drag_hand(&replay, &start, f);
		jumpy_frame(&jc);
		struct ik_result lr = behave_frame(&live.b, live.m, live.s, live.ik, &lo, &clock);
		tally(&t, &lr.work);
		struct ik_work w = through_text(&lr.work);
		ro.replay = &w;
		struct ik_result rr = behave_frame(&replay.b, replay.m, replay.s, replay.ik, &ro,
						   &FORBIDDEN);
		assert_same_solve(&lr, &rr, f);
		assert_same_posture(live.m, live.s, replay.s, f);
		assert_int_equal(live.b.steps_taken, replay.b.steps_taken);
		assert_int_equal(live.b.root, replay.b.root);
	}
	print_message("behaving: %d frames cut (body %d, hand %d, %d in a later balance round), "
		      "%d ended on their own, %d steps, posture hash %016llx\n", t.cut, t.group[0],
		      t.group[1], t.late_round, t.ended, live.b.steps_taken,
		      (unsigned long long)state_hash(live.m, live.s));
	assert_true(t.cut > FRAMES / 4 && t.ended > FRAMES / 20);
	assert_true(t.group[0] > 0 && t.group[1] > 0 && t.late_round > 0);
	assert_true(live.b.steps_taken > 0);
	rig_free(&live);
	rig_free(&replay);
}

/* ---- the line of text ----------------------------------------------------------- */

static void
test_the_line_round_trips(void **unused)
{
	(void)unused;
	struct ik_work cases[] = {
		ik_work_none(),
		{ 1, 9, 0, 0, 0, 9 },
		{ 0, 412, 3, 1, 2, 17 },
		{ 1, INT_MAX, INT_MAX, IK_MAX_GROUPS - 1, INT_MAX, INT_MAX },
	};
	char line[IK_WORK_LINE_MAX], err[160];
	for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
		int n = ik_work_write(&cases[i], line, sizeof line);
		assert_int_equal(n, (int)strlen(line));
		struct ik_work back;
		assert_int_equal(ik_work_read(line, &back, err, sizeof err), 0);
		assert_true(ik_work_equal(&cases[i], &back));
		/* one newline may end it */
		line[n] = '\n', line[n + 1] = '\0';
		assert_int_equal(ik_work_read(line, &back, err, sizeof err), 0);
		assert_true(ik_work_equal(&cases[i], &back));
	}
	ik_work_write(&cases[1], line, sizeof line);
	assert_string_equal(line, "ik_work cut=1 iterations=9 round=0 group=0 start=0 start_iterations=9");
	/* too small a buffer: nothing half written */
	char small[20] = "x";
	assert_int_equal(ik_work_write(&cases[2], small, sizeof small), -1);
	assert_string_equal(small, "");
}

/* a solve with nothing to move records no group, and that survives the text */
static void
test_a_solve_without_variables_records_no_group(void **unused)
{
	(void)unused;
	struct model *m = test_human();
	struct state *s = state_make(m);
	kin_update(m, s);
	struct ik *ik = ik_make(m, 1);
	struct ik_options o = ik_default_options();
	struct ik_result r = ik_solve(ik, m, s, &o, NULL);
	struct ik_work none = ik_work_none();
	assert_true(ik_work_equal(&r.work, &none));
	struct ik_work back = through_text(&r.work);
	assert_int_equal(back.group, -1);
	ik_free(ik);
	state_free(s);
	model_free(m);
}

static void
test_bad_lines_are_refused_with_a_reason(void **unused)
{
	(void)unused;
	static const struct {
		const char *line, *why;
	} BAD[] = {
		{ "", "does not begin" },
		{ "ikwork cut=1 iterations=9 round=0 group=0 start=0 start_iterations=9", "does not begin" },
		{ "ik_work cut=1 iterations=9 round=0 group=0 start=0", "start_iterations=" },
		{ "ik_work iterations=9 cut=1 round=0 group=0 start=0 start_iterations=9", "\" cut=\"" },
		{ "ik_work cut=1  iterations=9 round=0 group=0 start=0 start_iterations=9", "byte 13" },
		{ "ik_work cut=1 iterations=09 round=0 group=0 start=0 start_iterations=9", "not a count" },
		{ "ik_work cut=1 iterations=+9 round=0 group=0 start=0 start_iterations=9", "not a count" },
		{ "ik_work cut=1 iterations= round=0 group=0 start=0 start_iterations=9", "not a count" },
		{ "ik_work cut=1 iterations=2147483648 round=0 group=0 start=0 start_iterations=9",
		  "not a count" },
		{ "ik_work cut=1 iterations=-1 round=0 group=0 start=0 start_iterations=9", "not a count" },
		{ "ik_work cut=1 iterations=9 round=0 group=-12 start=0 start_iterations=9", "count or -1" },
		{ "ik_work cut=1 iterations=9 round=0 group=0 start=0 start_iterations=9 ", "after the last" },
		{ "ik_work cut=1 iterations=9 round=0 group=0 start=0 start_iterations=9\n\n", "after the last" },
		{ "ik_work cut=1 iterations=9 round=0 group=0 start=0 start_iterations=9x", "after the last" },
		{ "ik_work cut=2 iterations=9 round=0 group=0 start=0 start_iterations=9", "neither 0 nor 1" },
		{ "ik_work cut=1 iterations=9 round=0 group=0 start=0 start_iterations=10", "exceeds" },
		{ "ik_work cut=1 iterations=9 round=0 group=4 start=0 start_iterations=9", "beyond" },
		{ "ik_work cut=0 iterations=9 round=0 group=-1 start=0 start_iterations=0", "without a group" },
	};
	char err[160];
	for (size_t i = 0; i < sizeof BAD / sizeof *BAD; i++) {
		struct ik_work w = { 7, 7, 7, 1, 7, 7 }, untouched = w;
		err[0] = '\0';
		if (ik_work_read(BAD[i].line, &w, err, sizeof err) != -1)
			fail_msg("accepted: \"%s\"", BAD[i].line);
		if (!strstr(err, BAD[i].why))
			fail_msg("\"%s\": said \"%s\", want \"%s\"", BAD[i].line, err, BAD[i].why);
		assert_true(ik_work_equal(&w, &untouched));
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_arm_replays_bit_for_bit),
		cmocka_unit_test(test_a_record_one_count_off_replays_to_another_posture),
		cmocka_unit_test(test_behaving_human_replays_bit_for_bit),
		cmocka_unit_test(test_the_line_round_trips),
		cmocka_unit_test(test_a_solve_without_variables_records_no_group),
		cmocka_unit_test(test_bad_lines_are_refused_with_a_reason),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
