/*
 * rula.c - RULA (McAtamney & Corlett 1993) from measured body angles.
 *
 * Bands and adjustments: the paper's text as quoted in research
 * human-factors §1.1-1.2 (neck, trunk, legs, force/load from the paper;
 * arms and wrist from the ErgoPlus worksheet, identical in every
 * implementation). Tables A, B and C: §1.3, identical in the worksheet OCR
 * and the open implementations except Table A's cell upper arm 6, lower
 * arm 2, wrist 1, twist 1, which the worksheet OCR reads 7 and every
 * implementation 8: the majority 8 is kept. Action levels: §1.4.
 *
 * Edges: a value on the edge between two bands scores the worse band
 * (assess_internal.h); thresholds the method leaves open (assess_config)
 * count when exceeded, the "upright" and "neutral" ones when within.
 *
 * Not modelled, left to the observer through rula_options: muscle use
 * (static or repeated), the load and how it is applied, arm support, shock.
 */
#include <math.h>

#include "assess/assess_internal.h"
#include "assess/rula.h"

/* Table A: [upper arm 1-6][lower arm 1-3][wrist 1-4][wrist twist 1-2] */
static const unsigned char table_a[6][3][4][2] = {
	{ { { 1, 2 }, { 2, 2 }, { 2, 3 }, { 3, 3 } },
	  { { 2, 2 }, { 2, 2 }, { 3, 3 }, { 3, 3 } },
	  { { 2, 3 }, { 3, 3 }, { 3, 3 }, { 4, 4 } } },
	{ { { 2, 3 }, { 3, 3 }, { 3, 4 }, { 4, 4 } },
	  { { 3, 3 }, { 3, 3 }, { 3, 4 }, { 4, 4 } },
	  { { 3, 4 }, { 4, 4 }, { 4, 4 }, { 5, 5 } } },
	{ { { 3, 3 }, { 4, 4 }, { 4, 4 }, { 5, 5 } },
	  { { 3, 4 }, { 4, 4 }, { 4, 4 }, { 5, 5 } },
	  { { 4, 4 }, { 4, 4 }, { 4, 5 }, { 5, 5 } } },
	{ { { 4, 4 }, { 4, 4 }, { 4, 5 }, { 5, 5 } },
	  { { 4, 4 }, { 4, 4 }, { 4, 5 }, { 5, 5 } },
	  { { 4, 4 }, { 4, 5 }, { 5, 5 }, { 6, 6 } } },
	{ { { 5, 5 }, { 5, 5 }, { 5, 6 }, { 6, 7 } },
	  { { 5, 6 }, { 6, 6 }, { 6, 7 }, { 7, 7 } },
	  { { 6, 6 }, { 6, 7 }, { 7, 7 }, { 7, 8 } } },
	/* the contested cell is [5][1][0][0]: 8 (majority), 7 in one worksheet OCR */
	{ { { 7, 7 }, { 7, 7 }, { 7, 8 }, { 8, 9 } },
	  { { 8, 8 }, { 8, 8 }, { 8, 9 }, { 9, 9 } },
	  { { 9, 9 }, { 9, 9 }, { 9, 9 }, { 9, 9 } } },
};

/* Table B: [neck 1-6][trunk 1-6][legs 1-2] */
static const unsigned char table_b[6][6][2] = {
	{ { 1, 3 }, { 2, 3 }, { 3, 4 }, { 5, 5 }, { 6, 6 }, { 7, 7 } },
	{ { 2, 3 }, { 2, 3 }, { 4, 5 }, { 5, 5 }, { 6, 7 }, { 7, 7 } },
	{ { 3, 3 }, { 3, 4 }, { 4, 5 }, { 5, 6 }, { 6, 7 }, { 7, 7 } },
	{ { 5, 5 }, { 5, 6 }, { 6, 7 }, { 7, 7 }, { 7, 7 }, { 8, 8 } },
	{ { 7, 7 }, { 7, 7 }, { 7, 8 }, { 8, 8 }, { 8, 8 }, { 8, 8 } },
	{ { 8, 8 }, { 8, 8 }, { 8, 8 }, { 8, 9 }, { 9, 9 }, { 9, 9 } },
};

/* Table C: [score C 1-8+][score D 1-7+] */
static const unsigned char table_c[8][7] = {
	{ 1, 2, 3, 3, 4, 5, 5 }, { 2, 2, 3, 4, 4, 5, 5 }, { 3, 3, 3, 4, 4, 5, 6 },
	{ 3, 3, 3, 4, 5, 6, 6 }, { 4, 4, 4, 5, 6, 7, 7 }, { 4, 4, 5, 6, 6, 7, 7 },
	{ 5, 5, 6, 6, 7, 7, 7 }, { 5, 5, 6, 7, 7, 7, 7 },
};

static const char *const action_words[5] = {
	"",
	"acceptable if not maintained or repeated for long periods",
	"further investigation needed; changes may be required",
	"investigation and changes required soon",
	"investigation and changes required immediately",
};

static const char *const names_a[4] = { "upper_arm", "lower_arm", "wrist", "wrist_twist" };
static const char *const names_b[3] = { "neck", "trunk", "legs" };
static const char *const names_c[2] = { "score_c", "score_d" };

/* the body angle names of each side, as body_angles.c names them */
static const char *const ua_name[2] = { "upper_arm_flexion_l", "upper_arm_flexion_r" };
static const char *const elbow_name[2] = { "elbow_flexion_l", "elbow_flexion_r" };
static const char *const wrist_name[2] = { "wrist_flexion_l", "wrist_flexion_r" };
static const char *const twist_name[2] = { "wrist_twist_l", "wrist_twist_r" };

struct rula_options
rula_options_default(void)
{
	return (struct rula_options){ .side = ASSESS_SIDE_WORSE };
}

static int
upper_arm(struct assess_result *r, const struct body_arm *arm, const struct assess_config *cfg,
	  const struct rula_options *o, int side)
{
	const char *band;
	struct assess_part *p = assess_part(r, "upper_arm", ua_name[side], arm->upper_arm_flexion, 1, 6);
	int base = assess_upper_arm_band(arm->upper_arm_flexion, &band);
	assess_band(p, base, band);
	if (arm->shoulder_elevation > cfg->shoulder_raised)
		assess_adjust(p, 1, "shoulder raised: clavicle elevation %.1f > %g deg",
			      arm->shoulder_elevation, cfg->shoulder_raised);
	if (arm->upper_arm_abduction > cfg->arm_abducted)
		assess_adjust(p, 1, "upper arm abducted: %.1f > %g deg", arm->upper_arm_abduction,
			      cfg->arm_abducted);
	if (o->arm_supported)
		assess_adjust(p, -1, "arm supported or person leaning (arm_supported=yes)");
	return assess_close(p, 1, 6);
}

static int
lower_arm(struct assess_result *r, const struct body_arm *arm, const struct assess_config *cfg,
	  int side)
{
	const char *band;
	struct assess_part *p = assess_part(r, "lower_arm", elbow_name[side], arm->elbow_flexion, 1, 3);
	int base = assess_lower_arm_band(arm->elbow_flexion, &band);
	assess_band(p, base, band);
	/* one +1 for either: "working across the midline or out to the side" */
	if (arm->hand_across_midline > cfg->across_midline)
		assess_adjust(p, 1, "working across the midline: hand %.2f m past it > %g m",
			      arm->hand_across_midline, cfg->across_midline);
	else if (arm->hand_out_to_side > cfg->out_to_side)
		assess_adjust(p, 1, "working out to the side: hand %.2f m outside the shoulder > %g m",
			      arm->hand_out_to_side, cfg->out_to_side);
	return assess_close(p, 1, 3);
}

static int
wrist(struct assess_result *r, const struct body_arm *arm, const struct assess_config *cfg, int side)
{
	double w = arm->wrist_flexion, aw = fabs(w);
	struct assess_part *p = assess_part(r, "wrist", wrist_name[side], w, 1, 4);
	if (aw <= cfg->wrist_neutral)
		assess_band(p, 1, "neutral");
	else if (aw < 15)
		assess_band(p, 2, w > 0 ? "0-15 deg flexion" : "0-15 deg extension");
	else
		assess_band(p, 3, w > 0 ? "15 deg flexion or more" : "15 deg extension or more");
	if (fabs(arm->wrist_deviation) > cfg->wrist_deviated)
		assess_adjust(p, 1, "bent from the midline: %s deviation %.1f > %g deg",
			      arm->wrist_deviation > 0 ? "radial" : "ulnar", fabs(arm->wrist_deviation),
			      cfg->wrist_deviated);
	return assess_close(p, 1, 4);
}

static int
wrist_twist(struct assess_result *r, const struct body_arm *arm, const struct assess_config *cfg,
	    int side)
{
	struct assess_part *p = assess_part(r, "wrist_twist", twist_name[side], arm->wrist_twist, 1, 2);
	if (arm->wrist_twist_fraction > cfg->wrist_twist_end) {
		assess_band(p, 2, "at or near the end of the twisting range");
		assess_adjust(p, 0, "%s %.2f of the range > %g", arm->wrist_twist > 0 ? "pronation" :
			      "supination", arm->wrist_twist_fraction, cfg->wrist_twist_end);
	} else {
		assess_band(p, 1, "mainly in mid-range");
	}
	return assess_close(p, 1, 2);
}

static int
neck(struct assess_result *r, const struct body_angles *a, const struct assess_config *cfg)
{
	double f = a->neck_flexion;
	struct assess_part *p = assess_part(r, "neck", "neck_flexion", f, 1, 6);
	if (f < -cfg->upright)
		assess_band(p, 4, "in extension");
	else if (f < 10)
		assess_band(p, 1, "0-10 deg flexion");
	else if (f < 20)
		assess_band(p, 2, "10-20 deg flexion");
	else
		assess_band(p, 3, "20 deg flexion or more");
	if (fabs(a->neck_twist) > cfg->neck_twist)
		assess_adjust(p, 1, "neck twisted: %.1f > %g deg", fabs(a->neck_twist), cfg->neck_twist);
	if (fabs(a->neck_side_bend) > cfg->neck_side_bend)
		assess_adjust(p, 1, "neck side-bending: %.1f > %g deg", fabs(a->neck_side_bend),
			      cfg->neck_side_bend);
	return assess_close(p, 1, 6);
}

static int
trunk(struct assess_result *r, const struct body_angles *a, const struct assess_config *cfg)
{
	double f = a->trunk_flexion;
	struct assess_part *p = assess_part(r, "trunk", "trunk_flexion", f, 1, 6);
	if (a->seated && a->hip_trunk_angle >= 90) {
		assess_band(p, 1, "sitting and well supported, hip-trunk angle 90 deg or more");
		assess_adjust(p, 0, "seated, hip-trunk angle %.1f >= 90 deg", a->hip_trunk_angle);
	} else if (fabs(f) <= cfg->upright) {
		assess_band(p, 1, "upright");
	} else if (f < 20) {
		/* RULA gives no extension band; the worksheets' 0-20 deg covers leaning back */
		assess_band(p, 2, f > 0 ? "0-20 deg flexion" : "in extension (scored as 0-20 deg)");
	} else if (f < 60) {
		assess_band(p, 3, "20-60 deg flexion");
	} else {
		assess_band(p, 4, "60 deg flexion or more");
	}
	if (fabs(a->trunk_twist) > cfg->trunk_twist)
		assess_adjust(p, 1, "trunk twisted: %.1f > %g deg", fabs(a->trunk_twist), cfg->trunk_twist);
	if (fabs(a->trunk_side_bend) > cfg->trunk_side_bend)
		assess_adjust(p, 1, "trunk side-bending: %.1f > %g deg", fabs(a->trunk_side_bend),
			      cfg->trunk_side_bend);
	return assess_close(p, 1, 6);
}

static int
legs(struct assess_result *r, const struct body_angles *a, const struct assess_config *cfg,
     const struct rula_options *o)
{
	struct assess_part *p = assess_part(r, "legs", NULL, NAN, 1, 2);
	double dw = fabs(a->leg[BODY_LEFT].weight_share - a->leg[BODY_RIGHT].weight_share);
	if (a->seated) {
		if (o->legs_supported || a->legs_on_floor == 2) {
			assess_band(p, 1, "seated, legs and feet well supported");
			assess_adjust(p, 0, o->legs_supported ? "legs_supported=yes" :
				      "both feet bear weight");
		} else {
			assess_band(p, 2, "seated, legs and feet not supported");
			assess_adjust(p, 0, "%d foot bears weight, legs_supported=no", a->legs_on_floor);
		}
	} else if (a->legs_on_floor == 2 && dw <= cfg->uneven_weight) {
		assess_band(p, 1, "standing, weight evenly on both feet");
		assess_adjust(p, 0, "weight share difference %.2f <= %g", dw, cfg->uneven_weight);
	} else {
		assess_band(p, 2, "standing, weight unevenly balanced");
		if (a->legs_on_floor < 2)
			assess_adjust(p, 0, "%d foot bears weight", a->legs_on_floor);
		else
			assess_adjust(p, 0, "weight share difference %.2f > %g", dw, cfg->uneven_weight);
	}
	return assess_close(p, 1, 2);
}

static int
muscle_use(struct assess_result *r, const struct rula_options *o)
{
	struct assess_part *p = assess_part(r, "muscle_use", NULL, NAN, 0, 1);
	if (o->static_posture || o->repeated)
		assess_band(p, 1, o->static_posture ? "posture mainly static (held over 1 min)" :
			    "action repeated more than 4 times a minute");
	else
		assess_band(p, 0, "neither static nor repeated");
	return assess_close(p, 0, 1);
}

static int
force_load(struct assess_result *r, const struct rula_options *o)
{
	double kg = o->load_kg >= 0 ? o->load_kg : 0;
	int held = o->static_posture || o->repeated;
	struct assess_part *p = assess_part(r, "force_load", NULL, NAN, 0, 3);
	if (o->shock)
		assess_band(p, 3, "shock or forces with a rapid build-up");
	else if (kg < 2)
		assess_band(p, 0, "less than 2 kg");
	else if (kg <= 10)
		assess_band(p, held ? 2 : 1, held ? "2-10 kg static or repeated" : "2-10 kg intermittent");
	else
		assess_band(p, held ? 3 : 2, held ? "more than 10 kg static or repeated" :
			    "more than 10 kg intermittent");
	assess_adjust(p, 0, "load %.1f kg, %s", kg, held ? "static or repeated" : "intermittent");
	return assess_close(p, 0, 3);
}

/* one side's whole derivation */
static void
score_side(const struct body_angles *a, const struct assess_config *cfg,
	   const struct rula_options *o, int side, struct assess_result *r)
{
	const struct body_arm *arm = &a->arm[side == ASSESS_SIDE_LEFT ? BODY_LEFT : BODY_RIGHT];
	int s = side == ASSESS_SIDE_LEFT ? BODY_LEFT : BODY_RIGHT;
	assess_begin(r, ASSESS_RULA, side);
	/* the parts in the tables' order (one statement each: an initializer list's order is unspecified) */
	int ia[4], ib[3], extra;
	ia[0] = upper_arm(r, arm, cfg, o, s);
	ia[1] = lower_arm(r, arm, cfg, s);
	ia[2] = wrist(r, arm, cfg, s);
	ia[3] = wrist_twist(r, arm, cfg, s);
	ib[0] = neck(r, a, cfg);
	ib[1] = trunk(r, a, cfg);
	ib[2] = legs(r, a, cfg, o);
	extra = muscle_use(r, o);
	extra += force_load(r, o);
	int sa = assess_lookup(r, "A", 4, names_a, ia,
			       table_a[ia[0] - 1][ia[1] - 1][ia[2] - 1][ia[3] - 1]);
	int sb = assess_lookup(r, "B", 3, names_b, ib, table_b[ib[0] - 1][ib[1] - 1][ib[2] - 1]);
	/* scores C and D of 8 and 7 or more read the table's last row and column */
	int sc = sa + extra, sd = sb + extra;
	int ic[2] = { sc < 8 ? sc : 8, sd < 7 ? sd : 7 };
	r->score = assess_lookup(r, "C", 2, names_c, ic, table_c[ic[0] - 1][ic[1] - 1]);
	r->action_level = r->score <= 2 ? 1 : r->score <= 4 ? 2 : r->score <= 6 ? 3 : 4;
	r->action = action_words[r->action_level];
	assess_set_worst(r);
}

void
rula_score(const struct body_angles *a, const struct assess_config *cfg,
	   const struct rula_options *o, struct assess_result *r)
{
	if (o->side == ASSESS_SIDE_LEFT || o->side == ASSESS_SIDE_RIGHT) {
		score_side(a, cfg, o, o->side, r);
		return;
	}
	/* worse: both arms, the higher grand score kept, the right arm on ties */
	struct assess_result left;
	score_side(a, cfg, o, ASSESS_SIDE_RIGHT, r);
	score_side(a, cfg, o, ASSESS_SIDE_LEFT, &left);
	if (left.score > r->score)
		*r = left;
}
