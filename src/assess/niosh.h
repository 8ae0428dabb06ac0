/*
 * niosh.h - the revised NIOSH lifting equation (Waters, Putz-Anderson,
 * Garg & Fine, Ergonomics 36(7):749-776, 1993; Applications Manual for the
 * Revised NIOSH Lifting Equation, DHHS (NIOSH) 94-110, 1994, revised
 * 9/2021): the recommended weight limit and lifting index of a task at
 * full precision from the manual's formulas, and the composite lifting
 * index of a job of several tasks.
 */
#ifndef POSTURE_NIOSH_H
#define POSTURE_NIOSH_H

#include <stddef.h>

#define NIOSH_MAX_TASKS 10

enum niosh_coupling {
	NIOSH_GOOD,
	NIOSH_FAIR,
	NIOSH_POOR,
};

/*
 * The manual's two sets of constants (p. 7): metric (cm, kg; LC 23 kg) and
 * U.S. customary (in, lb; LC 51 lb). They are not exact conversions of one
 * another, so a task stated in inches and pounds is computed with the
 * U.S. constants to reproduce the manual; the fields named _cm and _kg then
 * hold inches and pounds.
 */
enum niosh_units {
	NIOSH_METRIC,
	NIOSH_US,
};

/* one lifting task evaluated at one end (origin or destination) */
struct niosh_task {
	double h_cm;        /* hands' horizontal distance from the inner ankles' midpoint */
	double v_cm;        /* hands' height above the floor at the end evaluated (CM uses it) */
	double d_cm;        /* vertical travel |V destination - V origin| */
	double a_deg;       /* asymmetry angle from the mid-sagittal plane (AM 0 beyond 135) */
	double freq;        /* lifts per minute, averaged over 15 minutes */
	double load_kg;     /* the load (the average load in a composite) */
	double v_origin_cm; /* the hands' height at the origin (FM uses it, p. 15) */
	int duration_h;     /* the duration category: 1 (<= 1 h), 2 (1-2 h) or 8 (2-8 h) */
	enum niosh_coupling coupling;
	double load_max_kg; /* composite only: the heaviest load, for the FILI; 0: load_kg */
};

/* which of the manual's limits and clamps applied (struct niosh_result.limits) */
enum niosh_limit {
	NIOSH_H_RAISED = 1u << 0, /* H below 25 cm set to 25 (HM 1) */
	NIOSH_H_BEYOND = 1u << 1, /* H beyond 63 cm: HM 0 */
	NIOSH_V_BEYOND = 1u << 2, /* V beyond 175 cm: VM 0 */
	NIOSH_D_RAISED = 1u << 3, /* D below 25 cm set to 25 (DM 1) */
	NIOSH_D_BEYOND = 1u << 4, /* D beyond 175 cm: DM 0 */
	NIOSH_A_BEYOND = 1u << 5, /* A beyond 135 deg: AM 0 */
	NIOSH_F_RAISED = 1u << 6, /* F below 0.2/min set to 0.2 */
	NIOSH_F_BEYOND = 1u << 7, /* F above the column's maximum frequency: FM 0 */
	NIOSH_NLIMITS = 8,
};

struct niosh_result {
	double rwl; /* the recommended weight limit, kg (lb in U.S. units) */
	double li;  /* load / RWL; infinite when the RWL is 0 and the load is not */
	double hm, vm, dm, am, fm, cm;
	unsigned limits; /* enum niosh_limit bits */
};

/* the words of one limit bit, e.g. "H < 25 cm: set to 25 (HM = 1)"; "" for another value */
const char *niosh_limit_name(unsigned bit, enum niosh_units u);

/*
 * The RWL and LI of task t at full precision, metric. Returns 0, or -1 with
 * why in err for nonsense input (a negative or non-finite number, duration
 * not 1, 2 or 8, an unknown coupling); r is unchanged then.
 */
int niosh_compute(const struct niosh_task *t, struct niosh_result *r, char *err, size_t errlen);
int niosh_compute_units(const struct niosh_task *t, enum niosh_units u, struct niosh_result *r,
			char *err, size_t errlen);

/*
 * Table 5 (p. 15): the frequency multiplier for freq lifts/min, duration
 * category 1, 2 or 8 h, hands' height v_cm at the origin (the columns split
 * at 75 cm). Linear in F between the table's rows (p. 7); F below 0.2 reads
 * the 0.2 row; above the column's maximum frequency, its last row that is
 * not .00, FM is 0 (nothing is interpolated toward a .00 row). NAN for a
 * duration not 1, 2 or 8 or a negative or non-finite freq.
 */
double niosh_fm(double freq, int duration_h, double v_cm);

/* Table 7 (p. 18): the coupling multiplier at hands' height v_cm (split at 75 cm) */
double niosh_cm(enum niosh_coupling c, double v_cm);

/*
 * The composite lifting index of a job of n tasks (manual §2.4, pp. 26-28):
 * each task's FIRWL (RWL with FM 1), STRWL (FIRWL x FM), FILI (heaviest
 * load / FIRWL) and STLI (load / STRWL); the tasks renumbered by decreasing
 * STLI (ties: the higher frequency first, p. 57, then the given order);
 * CLI = STLI_1 + sum over k >= 2 of FILI_k (1/FM_1..k - 1/FM_1..k-1), FM_1..k
 * from Table 5 at the summed frequency of tasks 1..k. All tasks share one
 * duration category. Which V selects the Table 5 column of a summed
 * frequency the manual leaves open (OQ-117 of nbarr1/ErgonomicTool's log):
 * the V < 75 cm column (the lower FMs) when any of tasks 1..k lifts from
 * below 75 cm at its origin.
 */
struct niosh_multi_result {
	int n;
	int order[NIOSH_MAX_TASKS];     /* order[k]: the given index of the task renumbered k + 1 */
	double firwl[NIOSH_MAX_TASKS];  /* by the given index */
	double strwl[NIOSH_MAX_TASKS];
	double fili[NIOSH_MAX_TASKS];
	double stli[NIOSH_MAX_TASKS];
	double fm[NIOSH_MAX_TASKS];     /* each task's own FM */
	double fm_sum[NIOSH_MAX_TASKS]; /* fm_sum[k]: FM at the frequency of renumbered tasks 1..k+1 */
	double cli;                     /* infinite when a summed frequency leaves the table */
};

/* Returns 0, or -1 with why in err (n outside 1..NIOSH_MAX_TASKS, a task's nonsense, mixed durations) */
int niosh_composite(const struct niosh_task *tasks, int n, struct niosh_multi_result *r, char *err,
		    size_t errlen);
int niosh_composite_units(const struct niosh_task *tasks, int n, enum niosh_units u,
			  struct niosh_multi_result *r, char *err, size_t errlen);

#endif
