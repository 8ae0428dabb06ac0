/*
 * ik_work.h - the work one solve did, so that a recording replays it
 * exactly (DESIGN.md, "Recording and replay").
 *
 * Live, a solve is cut by a deadline read from a clock, which no two runs
 * share. Everything else a solve does is a function of its state, its
 * constraints and its options, and the deadline is checked at one place
 * only: before each iteration of the minimiser (after the tests for met
 * objectives and the iteration limit), every iteration counted once in
 * ik_result.iterations whatever its group, balance round or start. The
 * first check that finds the deadline passed ends the whole solve (no
 * further group, round or start). So the count of iterations before the
 * cut decides it: a replay that cuts at the check which finds that many
 * iterations done, and never reads the clock, makes the same solve.
 *
 * The place of the end (round, group, start, iterations of that start)
 * follows from the count; it is kept so that a replay which went astray
 * (a different build, a different input) says where: the replay fills its
 * own record the same way, and ik_work_equal compares the two.
 *
 * A solve that ended on its own (converged, stationary, iteration limit,
 * balance settled) has cut 0; its replay ends the same way by itself.
 */
#ifndef POSTURE_IK_WORK_H
#define POSTURE_IK_WORK_H

#include <stddef.h>

struct ik_work {
	int cut;              /* 1: the deadline ended the solve, 0: it ended on its own */
	int iterations;       /* iterations done, all groups, rounds and starts */
	/* where it ended: the last group minimised (-1: no group had variables) */
	int round;            /* its balance round, from 0 */
	int group;            /* the group */
	int start;            /* its start in that round: 0, or k after k restarts */
	int start_iterations; /* iterations of that start */
};

/* the record of a solve that has not begun */
struct ik_work ik_work_none(void);

/* 1 when a and b record the same work */
int ik_work_equal(const struct ik_work *a, const struct ik_work *b);

/*
 * The record as one line of text, for frame logs:
 *
 *   ik_work cut=C iterations=N round=R group=G start=S start_iterations=K
 *
 * the keys in that order, one space between fields, each value a decimal
 * integer without sign or leading zeros (group may be -1), C 0 or 1.
 */
#define IK_WORK_LINE_MAX 128 /* with the terminating NUL */

/*
 * Writes w's line (no newline) into dest, cap bytes long. Returns the
 * line's length, or -1 when it does not fit (dest then holds an empty
 * string when cap > 0).
 */
int ik_work_write(const struct ik_work *w, char *dest, size_t cap);

/*
 * Parses one line as ik_work_write writes it; one trailing newline is
 * allowed, nothing else. The fields must agree with each other (the
 * start's iterations within the total; no group, no work). Returns 0, or
 * -1 with what is wrong (and at which byte) in err, dest untouched.
 */
int ik_work_read(const char *line, struct ik_work *dest, char *err, size_t errlen);

#endif
