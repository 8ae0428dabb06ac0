/*
 * reba.c - REBA (Hignett & McAtamney 2000) from measured body angles.
 *
 * Bands and adjustments: research human-factors §2.1 (Table 42.2 of
 * Marras & Karwowski's chapter, the FORM-REBA and worksheet forms); tables
 * A, B, C: §2.2, identical in rs9000/ergonomics, Skeleton_analyzer and the
 * worksheet OCR; action levels §2.3. Table A's rows are trunk, its columns
 * neck then legs (one public implementation transposes them: wrong).
 *
 * Edges: a value on the edge between two bands scores the worse band;
 * the open thresholds (assess_config) count when exceeded, "upright" when
 * within. The trunk's and the neck's "twisted or side flexed" is one +1
 * (their ranges after adjustment, 1-5 and 1-3, allow no more); so is the
 * upper arm's "abducted or rotated" and the wrist's "deviated or twisted".
 *
 * Not modelled, left to the observer through reba_options: the load and
 * shock, the coupling, the activity score.
 */
#include <math.h>

#include "assess/assess_internal.h"
#include "assess/reba.h"

/* Table A: [trunk 1-5][neck 1-3][legs 1-4] */
static const unsigned char table_a[5][3][4] = {
	{ { 1, 2, 3, 4 }, { 1, 2, 3, 4 }, { 3, 3, 5, 6 } },
	{ { 2, 3, 4, 5 }, { 3, 4, 5, 6 }, { 4, 5, 6, 7 } },
	{ { 2, 4, 5, 6 }, { 4, 5, 6, 7 }, { 5, 6, 7, 8 } },
	{ { 3, 5, 6, 7 }, { 5, 6, 7, 8 }, { 6, 7, 8, 9 } },
	{ { 4, 6, 7, 8 }, { 6, 7, 8, 9 }, { 7, 8, 9, 9 } },
};

/* Table B: [upper arm 1-6][lower arm 1-2][wrist 1-3] */
static const unsigned char table_b[6][2][3] = {
	{ { 1, 2, 2 }, { 1, 2, 3 } }, { { 1, 2, 3 }, { 2, 3, 4 } }, { { 3, 4, 5 }, { 4, 5, 5 } },
	{ { 4, 5, 5 }, { 5, 6, 7 } }, { { 6, 7, 8 }, { 7, 8, 8 } }, { { 7, 8, 8 }, { 8, 9, 9 } },
};

/* Table C: [score A 1-12][score B 1-12] */
static const unsigned char table_c[12][12] = {
	{ 1, 1, 1, 2, 3, 3, 4, 5, 6, 7, 7, 7 },
	{ 1, 2, 2, 3, 4, 4, 5, 6, 6, 7, 7, 8 },
	{ 2, 3, 3, 3, 4, 5, 6, 7, 7, 8, 8, 8 },
	{ 3, 4, 4, 4, 5, 6, 7, 8, 8, 9, 9, 9 },
	{ 4, 4, 4, 5, 6, 7, 8, 8, 9, 9, 9, 9 },
	{ 6, 6, 6, 7, 8, 8, 9, 9, 10, 10, 10, 10 },
	{ 7, 7, 7, 8, 9, 9, 9, 10, 10, 11, 11, 11 },
	{ 8, 8, 8, 9, 10, 10, 10, 10, 10, 11, 11, 11 },
	{ 9, 9, 9, 10, 10, 10, 11, 11, 11, 12, 12, 12 },
	{ 10, 10, 10, 11, 11, 11, 11, 12, 12, 12, 12, 12 },
	{ 11, 11, 11, 11, 12, 12, 12, 12, 12, 12, 12, 12 },
	{ 12, 12, 12, 12, 12, 12, 12, 12, 12, 12, 12, 12 },
};

static const char *const action_words[5] = {
	"negligible risk: none necessary",
	"low risk: may be necessary",
	"medium risk: necessary",
	"high risk: necessary soon",
	"very high risk: necessary now",
};

static const char *const coupling_words[4] = {
	"good: well-fitting handle and mid-range power grip",
	"fair: hand hold acceptable but not ideal",
	"poor: hand hold not acceptable although possible",
	"unacceptable: awkward, unsafe grip, no handles",
};

static const char *const names_a[3] = { "trunk", "neck", "legs" };
static const char *const names_b[3] = { "upper_arm", "lower_arm", "wrist" };
static const char *const names_c[2] = { "score_a", "score_b" };
static const char *const ua_name[2] = { "upper_arm_flexion_l", "upper_arm_flexion_r" };
static const char *const elbow_name[2] = { "elbow_flexion_l", "elbow_flexion_r" };
static const char *const wrist_name[2] = { "wrist_flexion_l", "wrist_flexion_r" };
static const char *const knee_name[2] = { "knee_flexion_l", "knee_flexion_r" };

struct reba_options
reba_options_default(void)
{
	return (struct reba_options){ .side = ASSESS_SIDE_WORSE };
}

/* "+1 if twisting or side flexed": one adjustment naming what exceeded */
static void
twist_or_side(struct assess_part *p, const char *what, double twist, double side, double twist_max,
	      double side_max)
{
	twist = fabs(twist);
	side = fabs(side);
	if (twist > twist_max && side > side_max)
		assess_adjust(p, 1, "%s twisted %.1f > %g and side flexed %.1f > %g deg", what, twist,
			      twist_max, side, side_max);
	else if (twist > twist_max)
		assess_adjust(p, 1, "%s twisted: %.1f > %g deg", what, twist, twist_max);
	else if (side > side_max)
		assess_adjust(p, 1, "%s side flexed: %.1f > %g deg", what, side, side_max);
}

static int
trunk(struct assess_result *r, const struct body_angles *a, const struct assess_config *cfg)
{
	double f = a->trunk_flexion;
	struct assess_part *p = assess_part(r, "trunk", "trunk_flexion", f, 1, 5);
	if (fabs(f) <= cfg->upright)
		assess_band(p, 1, "upright");
	else if (f > -20 && f < 20)
		assess_band(p, 2, f > 0 ? "0-20 deg flexion" : "0-20 deg extension");
	else if (f <= -20)
		assess_band(p, 3, "more than 20 deg extension");
	else if (f < 60)
		assess_band(p, 3, "20-60 deg flexion");
	else
		assess_band(p, 4, "more than 60 deg flexion");
	twist_or_side(p, "trunk", a->trunk_twist, a->trunk_side_bend, cfg->trunk_twist,
		      cfg->trunk_side_bend);
	return assess_close(p, 1, 5);
}

static int
neck(struct assess_result *r, const struct body_angles *a, const struct assess_config *cfg)
{
	double f = a->neck_flexion;
	struct assess_part *p = assess_part(r, "neck", "neck_flexion", f, 1, 3);
	if (f < -cfg->upright)
		assess_band(p, 2, "in extension");
	else if (f < 20)
		assess_band(p, 1, "0-20 deg flexion");
	else
		assess_band(p, 2, "more than 20 deg flexion");
	twist_or_side(p, "neck", a->neck_twist, a->neck_side_bend, cfg->neck_twist, cfg->neck_side_bend);
	return assess_close(p, 1, 3);
}

static int
legs(struct assess_result *r, const struct body_angles *a, const struct assess_config *cfg)
{
	/* the knee adjustment reads the more flexed of the legs that bear weight (both when none does) */
	int k = BODY_LEFT;
	const struct body_leg *l = a->leg, *rt = &a->leg[BODY_RIGHT];
	int both = l->foot_on_floor == rt->foot_on_floor;
	if (both ? rt->knee_flexion > l->knee_flexion : rt->foot_on_floor)
		k = BODY_RIGHT;
	double knee = a->leg[k].knee_flexion;
	double dw = fabs(l->weight_share - rt->weight_share);
	struct assess_part *p = assess_part(r, "legs", knee_name[k], knee, 1, 4);
	if (a->seated) {
		assess_band(p, 1, "sitting");
	} else if (a->legs_on_floor == 2 && dw <= cfg->uneven_weight) {
		assess_band(p, 1, "bilateral weight bearing");
		assess_adjust(p, 0, "weight share difference %.2f <= %g", dw, cfg->uneven_weight);
	} else {
		assess_band(p, 2, "unilateral or feather weight bearing, or unstable");
		if (a->legs_on_floor < 2)
			assess_adjust(p, 0, "%d foot bears weight", a->legs_on_floor);
		else
			assess_adjust(p, 0, "weight share difference %.2f > %g", dw, cfg->uneven_weight);
	}
	if (knee >= 30 && knee < 60)
		assess_adjust(p, 1, "knee flexion %.1f in 30-60 deg", knee);
	else if (knee >= 60 && !a->seated)
		assess_adjust(p, 2, "knee flexion %.1f: more than 60 deg", knee);
	return assess_close(p, 1, 4);
}

static int
load(struct assess_result *r, const struct reba_options *o)
{
	double kg = o->load_kg >= 0 ? o->load_kg : 0;
	struct assess_part *p = assess_part(r, "load", NULL, NAN, 0, 3);
	if (kg < 5)
		assess_band(p, 0, "less than 5 kg");
	else if (kg <= 10)
		assess_band(p, 1, "5-10 kg");
	else
		assess_band(p, 2, "more than 10 kg");
	assess_adjust(p, 0, "load %.1f kg", kg);
	if (o->shock)
		assess_adjust(p, 1, "shock or rapid build-up of force (shock=yes)");
	return assess_close(p, 0, 3);
}

static int
upper_arm(struct assess_result *r, const struct body_arm *arm, const struct assess_config *cfg,
	  const struct reba_options *o, int side)
{
	const char *band;
	struct assess_part *p = assess_part(r, "upper_arm", ua_name[side], arm->upper_arm_flexion, 1, 6);
	int base = assess_upper_arm_band(arm->upper_arm_flexion, &band);
	assess_band(p, base, band);
	double rot = fabs(arm->upper_arm_rotation);
	if (arm->upper_arm_abduction > cfg->arm_abducted)
		assess_adjust(p, 1, "arm abducted: %.1f > %g deg", arm->upper_arm_abduction,
			      cfg->arm_abducted);
	else if (rot > cfg->arm_rotated)
		assess_adjust(p, 1, "arm rotated: %.1f > %g deg", rot, cfg->arm_rotated);
	if (arm->shoulder_elevation > cfg->shoulder_raised)
		assess_adjust(p, 1, "shoulder raised: clavicle elevation %.1f > %g deg",
			      arm->shoulder_elevation, cfg->shoulder_raised);
	if (o->arm_supported)
		assess_adjust(p, -1, "arm supported, leaning or gravity-assisted (arm_supported=yes)");
	return assess_close(p, 1, 6);
}

static int
lower_arm(struct assess_result *r, const struct body_arm *arm, int side)
{
	const char *band;
	struct assess_part *p = assess_part(r, "lower_arm", elbow_name[side], arm->elbow_flexion, 1, 2);
	int base = assess_lower_arm_band(arm->elbow_flexion, &band);
	assess_band(p, base, band);
	return assess_close(p, 1, 2);
}

static int
wrist(struct assess_result *r, const struct body_arm *arm, const struct assess_config *cfg, int side)
{
	double w = arm->wrist_flexion, dev = fabs(arm->wrist_deviation);
	struct assess_part *p = assess_part(r, "wrist", wrist_name[side], w, 1, 3);
	if (fabs(w) < 15)
		assess_band(p, 1, "0-15 deg flexion or extension");
	else
		assess_band(p, 2, "more than 15 deg flexion or extension");
	if (dev > cfg->wrist_deviated)
		assess_adjust(p, 1, "wrist deviated: %.1f > %g deg", dev, cfg->wrist_deviated);
	else if (arm->wrist_twist_fraction > cfg->wrist_twist_end)
		assess_adjust(p, 1, "wrist twisted: %.2f of the range > %g", arm->wrist_twist_fraction,
			      cfg->wrist_twist_end);
	return assess_close(p, 1, 3);
}

static int
coupling(struct assess_result *r, const struct reba_options *o)
{
	int c = o->coupling < 0 ? 0 : o->coupling > 3 ? 3 : o->coupling;
	struct assess_part *p = assess_part(r, "coupling", NULL, NAN, 0, 3);
	assess_band(p, c, coupling_words[c]);
	return assess_close(p, 0, 3);
}

static int
activity(struct assess_result *r, const struct reba_options *o)
{
	int n = o->activity < 0 ? 0 : o->activity > 3 ? 3 : o->activity;
	struct assess_part *p = assess_part(r, "activity", NULL, NAN, 0, 3);
	assess_band(p, n, n ? "static, repeated or rapidly changing postures (activity items)" :
		    "no activity item");
	return assess_close(p, 0, 3);
}

static void
score_side(const struct body_angles *a, const struct assess_config *cfg,
	   const struct reba_options *o, int side, struct assess_result *r)
{
	int s = side == ASSESS_SIDE_LEFT ? BODY_LEFT : BODY_RIGHT;
	const struct body_arm *arm = &a->arm[s];
	assess_begin(r, ASSESS_REBA, side);
	/* the parts in the tables' order (one statement each: an initializer list's order is unspecified) */
	int ia[3], ib[3], ic[2];
	ia[0] = trunk(r, a, cfg);
	ia[1] = neck(r, a, cfg);
	ia[2] = legs(r, a, cfg);
	int ld = load(r, o);
	ib[0] = upper_arm(r, arm, cfg, o, s);
	ib[1] = lower_arm(r, arm, s);
	ib[2] = wrist(r, arm, cfg, s);
	int cp = coupling(r, o);
	int act = activity(r, o);
	ic[0] = assess_lookup(r, "A", 3, names_a, ia, table_a[ia[0] - 1][ia[1] - 1][ia[2] - 1]) + ld;
	ic[1] = assess_lookup(r, "B", 3, names_b, ib, table_b[ib[0] - 1][ib[1] - 1][ib[2] - 1]) + cp;
	r->score = assess_lookup(r, "C", 2, names_c, ic, table_c[ic[0] - 1][ic[1] - 1]) + act;
	r->action_level = r->score == 1 ? 0 : r->score <= 3 ? 1 : r->score <= 7 ? 2 :
			  r->score <= 10 ? 3 : 4;
	r->action = action_words[r->action_level];
	assess_set_worst(r);
}

void
reba_score(const struct body_angles *a, const struct assess_config *cfg,
	   const struct reba_options *o, struct assess_result *r)
{
	if (o->side == ASSESS_SIDE_LEFT || o->side == ASSESS_SIDE_RIGHT) {
		score_side(a, cfg, o, o->side, r);
		return;
	}
	/* worse: both arms, the higher REBA score kept, the right arm on ties */
	struct assess_result left;
	score_side(a, cfg, o, ASSESS_SIDE_RIGHT, r);
	score_side(a, cfg, o, ASSESS_SIDE_LEFT, &left);
	if (left.score > r->score)
		*r = left;
}
