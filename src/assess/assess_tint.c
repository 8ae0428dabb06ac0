/*
 * assess_tint.c - a body part's colour: the action level with that part
 * alone as measured (see assess_tint.h).
 *
 * The level depends on the part's score alone (the rest are at their
 * lowest by definition), so it is a table of (method, part, score) ->
 * level, made once. OWAS's comes from its public classification
 * (owas_category). RULA's and REBA's tables are their scorers' own: each
 * cell is read by scoring, with rula_score and reba_score, a probe posture
 * that is neutral but for that part, posed to give it that score; a probe
 * counts only when the scorer gives the part the score asked for and every
 * other body part its lowest (1) and the add-ons none, so a probe that does
 * not mean what it should leaves the cell unknown (-1) instead of wrong.
 */
#include "assess/assess_tint.h"

#include <string.h>

#include "assess/body_angles.h"
#include "assess/owas.h"
#include "assess/reba.h"
#include "assess/rula.h"

#define TINT_MAX_SCORE 6 /* the highest body part score of RULA and REBA (the upper arm's) */

struct probe_part {
	const char *name; /* the scorer's part name (static) */
	int max;
	signed char level[TINT_MAX_SCORE + 1]; /* [score]: the level alone, -1 unknown */
};

/* RULA's and REBA's cells, [method]; made on first use */
static struct {
	int made;
	int nparts[2];
	struct probe_part part[2][ASSESS_MAX_PARTS];
} probes;

/* standing upright on both feet, arms hanging, elbows at 80 deg: every body part 1 */
static void
neutral(struct body_angles *a)
{
	memset(a, 0, sizeof *a);
	a->hip_trunk_angle = 180;
	a->legs_on_floor = 2;
	for (int s = 0; s < 2; s++) {
		a->arm[s].elbow_flexion = 80;
		a->leg[s].weight_share = 0.5;
		a->leg[s].foot_on_floor = 1;
	}
}

/*
 * Poses part `name` of a (right arm) for score k: angles well inside each
 * band and well past each default threshold (assess_config_default), so
 * the probe does not sit on an edge. 0, or -1 for a part or score it
 * cannot pose.
 */
static int
pose_part(enum assess_method m, const char *name, int k, struct body_angles *a)
{
	static const double arm_flex[5] = { 0, 0, 30, 60, 110 };   /* upper arm 1-4 */
	static const double trunk_flex[5] = { 0, 0, 10, 40, 80 };  /* trunk 1-4 (REBA 1-4) */
	static const double rula_neck[5] = { 0, 0, 15, 30, -20 }; /* RULA neck 1-4 */
	struct body_arm *arm = &a->arm[BODY_RIGHT];
	if (!strcmp(name, "upper_arm") && k <= 6) {
		arm->upper_arm_flexion = arm_flex[k < 4 ? k : 4];
		arm->upper_arm_abduction = k >= 5 ? 60 : 0;
		arm->shoulder_elevation = k >= 6 ? 30 : 0;
	} else if (!strcmp(name, "lower_arm") && k <= (m == ASSESS_RULA ? 3 : 2)) {
		arm->elbow_flexion = k == 1 ? 80 : 30;
		arm->hand_out_to_side = k == 3 ? 0.4 : 0;
	} else if (!strcmp(name, "wrist") && m == ASSESS_RULA && k <= 4) {
		arm->wrist_flexion = k == 1 ? 0 : k == 2 ? 10 : 25;
		arm->wrist_deviation = k == 4 ? 25 : 0;
	} else if (!strcmp(name, "wrist") && m == ASSESS_REBA && k <= 3) {
		arm->wrist_flexion = k == 1 ? 0 : 25;
		arm->wrist_deviation = k == 3 ? 25 : 0;
	} else if (!strcmp(name, "wrist_twist") && k <= 2) {
		arm->wrist_twist = k == 2 ? 80 : 0;
		arm->wrist_twist_fraction = k == 2 ? 0.95 : 0;
	} else if (!strcmp(name, "neck") && m == ASSESS_RULA && k <= 6) {
		a->neck_flexion = rula_neck[k < 4 ? k : 4];
		a->neck_twist = k >= 5 ? 40 : 0;
		a->neck_side_bend = k >= 6 ? 30 : 0;
	} else if (!strcmp(name, "neck") && m == ASSESS_REBA && k <= 3) {
		a->neck_flexion = k == 1 ? 0 : 30;
		a->neck_twist = k == 3 ? 40 : 0;
	} else if (!strcmp(name, "trunk") && k <= (m == ASSESS_RULA ? 6 : 5)) {
		a->trunk_flexion = trunk_flex[k < 4 ? k : 4];
		a->trunk_twist = k >= 5 ? 40 : 0;
		a->trunk_side_bend = k >= 6 ? 30 : 0;
	} else if (!strcmp(name, "legs") && k <= (m == ASSESS_RULA ? 2 : 4)) {
		if (k >= 2) { /* on the left foot alone */
			a->legs_on_floor = 1;
			a->leg[BODY_RIGHT].foot_on_floor = 0;
			a->leg[BODY_LEFT].weight_share = 1;
			a->leg[BODY_RIGHT].weight_share = 0;
		}
		for (int s = 0; s < 2; s++) /* REBA: +1 for 30-60 deg, +2 beyond */
			a->leg[s].knee_flexion = k == 3 ? 45 : k == 4 ? 80 : 0;
	} else {
		return -1;
	}
	return 0;
}

static void
score(enum assess_method m, const struct body_angles *a, const struct assess_config *cfg,
      struct assess_result *dest)
{
	if (m == ASSESS_RULA) {
		struct rula_options o = rula_options_default();
		o.side = ASSESS_SIDE_RIGHT;
		rula_score(a, cfg, &o, dest);
	} else {
		struct reba_options o = reba_options_default();
		o.side = ASSESS_SIDE_RIGHT;
		reba_score(a, cfg, &o, dest);
	}
}

/* 1 when r gives part p score k, every other body part 1 and every add-on 0 */
static int
probe_holds(const struct assess_result *r, int p, int k)
{
	for (int q = 0; q < r->nparts; q++) {
		int want = q == p ? k : r->part[q].body ? 1 : 0;
		if (r->part[q].score != want)
			return 0;
	}
	return 1;
}

static void
make_probes(void)
{
	struct assess_config cfg = assess_config_default();
	for (int m = ASSESS_RULA; m <= ASSESS_REBA; m++) {
		struct body_angles a;
		struct assess_result base, r;
		neutral(&a);
		score((enum assess_method)m, &a, &cfg, &base);
		int n = 0;
		for (int p = 0; p < base.nparts && n < ASSESS_MAX_PARTS; p++) {
			if (!base.part[p].body)
				continue;
			struct probe_part *pp = &probes.part[m][n++];
			pp->name = base.part[p].name;
			pp->max = base.part[p].max < TINT_MAX_SCORE ? base.part[p].max : TINT_MAX_SCORE;
			memset(pp->level, -1, sizeof pp->level);
			for (int k = 1; k <= pp->max; k++) {
				neutral(&a);
				if (pose_part((enum assess_method)m, pp->name, k, &a) < 0)
					continue;
				score((enum assess_method)m, &a, &cfg, &r);
				if (r.nparts == base.nparts && probe_holds(&r, p, k))
					pp->level[k] = (signed char)r.action_level;
			}
		}
		probes.nparts[m] = n;
	}
	probes.made = 1;
}

int
assess_part_level(const struct assess_result *r, int part)
{
	if (part < 0 || part >= r->nparts || part >= ASSESS_MAX_PARTS || !r->part[part].body ||
	    !r->part[part].name)
		return -1;
	const struct assess_part *p = &r->part[part];
	if (r->method == ASSESS_OWAS) {
		/* each digit alone, the others (and the load) at code 1 */
		int back = 1, arms = 1, legs = 1;
		if (!strcmp(p->name, "back"))
			back = p->score;
		else if (!strcmp(p->name, "arms"))
			arms = p->score;
		else if (!strcmp(p->name, "legs"))
			legs = p->score;
		else
			return -1;
		int ac = owas_category(back, arms, legs, 1);
		return ac > 0 ? ac : -1;
	}
	if (r->method != ASSESS_RULA && r->method != ASSESS_REBA)
		return -1;
	if (!probes.made)
		make_probes();
	for (int i = 0; i < probes.nparts[r->method]; i++) {
		const struct probe_part *pp = &probes.part[r->method][i];
		if (!strcmp(pp->name, p->name))
			return p->score >= 1 && p->score <= pp->max ? pp->level[p->score] : -1;
	}
	return -1;
}

enum assess_colour
assess_level_colour(enum assess_method method, int level)
{
	switch (method) {
	case ASSESS_REBA: /* 0 none; 1 may be and 2 necessary; 3 soon; 4 now */
		return level <= 0 ? ASSESS_GREEN : level <= 2 ? ASSESS_YELLOW
			: level == 3 ? ASSESS_ORANGE : ASSESS_RED;
	case ASSESS_RULA:
	case ASSESS_OWAS:
	case ASSESS_NMETHODS:
		break;
	}
	return level <= 1 ? ASSESS_GREEN : level == 2 ? ASSESS_YELLOW
		: level == 3 ? ASSESS_ORANGE : ASSESS_RED;
}

const char *
assess_colour_levels(enum assess_method method, enum assess_colour c)
{
	static const char *const reba[ASSESS_NCOLOURS] = { "0", "1-2", "3", "4" };
	static const char *const four[ASSESS_NCOLOURS] = { "1", "2", "3", "4" };
	if ((int)c < 0 || c >= ASSESS_NCOLOURS)
		return "";
	return method == ASSESS_REBA ? reba[c] : four[c];
}

const char *
assess_level_word(enum assess_method method)
{
	return method == ASSESS_OWAS ? "AC" : "AL";
}
