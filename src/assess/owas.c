/*
 * owas.c - OWAS (Karhu et al. 1977) from measured body angles.
 *
 * Codes: research human-factors §3.1 (the OWAS training slides, scribd
 * 630537767 and 617736274). The 20 deg back threshold is the slides'
 * (assess_config owas_back). An arm is "at or above shoulder level" when
 * its elbow is at or above the shoulder joint: one slide set says so, the
 * other reads "arm" without saying which point, and rs9000/ergonomics uses
 * the elbow too; a hand raised on a low elbow (a hand at the face) is not
 * a raised arm.
 *
 * The 252-cell classification (§3.3) is the majority reading of eight
 * public implementations; no primary table was reachable. Two cells are
 * contested: back 3, arms 3, legs 7 reads 1/1/1 in the majority, 1/1/2 in
 * rs9000/ergonomics and a TypeScript file that follows it; back 4, arms 1,
 * legs 3 reads 2/2/3 in the majority, 2/3/3 in those two. The majority is
 * kept for both.
 *
 * Legs, from the contacts: sitting when the figure is seated; kneeling
 * when a knee is within kneel_height of the floor; on one leg when one
 * foot alone bears weight (bent or straight by that leg's knee); on both
 * feet: both knees bent, or straight. Walking (7) is not observable from
 * one posture and never produced.
 */
#include <math.h>

#include "assess/assess_internal.h"
#include "assess/owas.h"

/* [back 1-4][arms 1-3][legs 1-7][load 1-3] */
static const unsigned char table[4][3][7][3] = {
	{ { { 1, 1, 1 }, { 1, 1, 1 }, { 1, 1, 1 }, { 2, 2, 2 }, { 2, 2, 2 }, { 1, 1, 1 }, { 1, 1, 1 } },
	  { { 1, 1, 1 }, { 1, 1, 1 }, { 1, 1, 1 }, { 2, 2, 2 }, { 2, 2, 2 }, { 1, 1, 1 }, { 1, 1, 1 } },
	  { { 1, 1, 1 }, { 1, 1, 1 }, { 1, 1, 1 }, { 2, 2, 3 }, { 2, 2, 3 }, { 1, 1, 1 }, { 1, 1, 2 } } },
	{ { { 2, 2, 3 }, { 2, 2, 3 }, { 2, 2, 3 }, { 3, 3, 3 }, { 3, 3, 3 }, { 2, 2, 2 }, { 2, 3, 3 } },
	  { { 2, 2, 3 }, { 2, 2, 3 }, { 2, 3, 3 }, { 3, 4, 4 }, { 3, 4, 4 }, { 3, 3, 4 }, { 2, 3, 4 } },
	  { { 3, 3, 4 }, { 2, 2, 3 }, { 3, 3, 3 }, { 3, 4, 4 }, { 4, 4, 4 }, { 4, 4, 4 }, { 2, 3, 4 } } },
	/* back 3, arms 3, legs 7: 1/1/1 (majority; 1/1/2 contested) */
	{ { { 1, 1, 1 }, { 1, 1, 1 }, { 1, 1, 2 }, { 3, 3, 3 }, { 4, 4, 4 }, { 1, 1, 1 }, { 1, 1, 1 } },
	  { { 2, 2, 3 }, { 1, 1, 1 }, { 1, 1, 2 }, { 4, 4, 4 }, { 4, 4, 4 }, { 3, 3, 3 }, { 1, 1, 1 } },
	  { { 2, 2, 3 }, { 1, 1, 1 }, { 2, 3, 3 }, { 4, 4, 4 }, { 4, 4, 4 }, { 4, 4, 4 }, { 1, 1, 1 } } },
	/* back 4, arms 1, legs 3: 2/2/3 (majority; 2/3/3 contested) */
	{ { { 2, 3, 3 }, { 2, 2, 3 }, { 2, 2, 3 }, { 4, 4, 4 }, { 4, 4, 4 }, { 4, 4, 4 }, { 2, 3, 4 } },
	  { { 3, 3, 4 }, { 2, 3, 4 }, { 3, 3, 4 }, { 4, 4, 4 }, { 4, 4, 4 }, { 4, 4, 4 }, { 2, 3, 4 } },
	  { { 4, 4, 4 }, { 2, 3, 4 }, { 3, 3, 4 }, { 4, 4, 4 }, { 4, 4, 4 }, { 4, 4, 4 }, { 2, 3, 4 } } },
};

static const char *const action_words[5] = {
	"",
	"normal posture: no corrective measures needed",
	"slightly harmful: corrective measures in the near future",
	"distinctly harmful: corrective measures as soon as possible",
	"extremely harmful: corrective measures immediately",
};

static const char *const back_words[5] = {
	"", "straight", "bent forward or backward", "twisted or bent sideways",
	"bent and twisted, or bent forward and sideways",
};
static const char *const arms_words[4] = {
	"", "both arms below shoulder level", "one arm at or above shoulder level",
	"both arms at or above shoulder level",
};
static const char *const legs_words[8] = {
	"", "sitting", "standing, both legs straight", "standing on one straight leg",
	"standing or squatting, both knees bent", "standing or squatting on one bent leg",
	"kneeling on one or both knees", "walking or moving",
};
static const char *const load_words[4] = {
	"", "10 kg or less", "more than 10 kg, up to 20 kg", "more than 20 kg",
};
static const char *const side_word[2] = { "left", "right" };
static const char *const names[4] = { "back", "arms", "legs", "load" };

int
owas_category(int back, int arms, int legs, int load)
{
	if (back < 1 || back > 4 || arms < 1 || arms > 3 || legs < 1 || legs > 7 || load < 1 ||
	    load > 3)
		return 0;
	return table[back - 1][arms - 1][legs - 1][load - 1];
}

static int
back(struct assess_result *r, const struct body_angles *a, const struct assess_config *cfg)
{
	double f = fabs(a->trunk_flexion), tw = fabs(a->trunk_twist), sb = fabs(a->trunk_side_bend);
	int bent = f > cfg->owas_back, turned = tw > cfg->owas_back || sb > cfg->owas_back;
	int code = bent ? (turned ? 4 : 2) : (turned ? 3 : 1);
	struct assess_part *p = assess_part(r, "back", "trunk_flexion", a->trunk_flexion, 1, 4);
	assess_band(p, code, back_words[code]);
	assess_adjust(p, 0, "trunk %s %.1f %s %g deg", a->trunk_flexion >= 0 ? "flexion" : "extension",
		      f, bent ? ">" : "<=", cfg->owas_back);
	assess_adjust(p, 0, "twist %.1f, side bend %.1f: %s %g deg", tw, sb,
		      turned ? "one >" : "both <=", cfg->owas_back);
	return assess_close(p, 1, 4);
}

static int
arms(struct assess_result *r, const struct body_angles *a)
{
	int up = 0;
	struct assess_part *p = assess_part(r, "arms", NULL, NAN, 1, 3);
	for (int s = BODY_LEFT; s <= BODY_RIGHT; s++) {
		double e = a->arm[s].elbow_above_shoulder;
		up += e >= 0;
		assess_adjust(p, 0, "%s elbow %.2f m %s the shoulder", side_word[s], fabs(e),
			      e >= 0 ? "above" : "below");
	}
	assess_band(p, 1 + up, arms_words[1 + up]);
	return assess_close(p, 1, 3);
}

static int
legs(struct assess_result *r, const struct body_angles *a, const struct assess_config *cfg)
{
	const struct body_leg *l = a->leg;
	int code, k = -1;
	struct assess_part *p = assess_part(r, "legs", NULL, NAN, 1, 7);
	if (a->seated) {
		code = 1;
		assess_adjust(p, 0, "seated");
	} else if (l[BODY_LEFT].kneeling || l[BODY_RIGHT].kneeling) {
		code = 6;
		assess_adjust(p, 0, "%s knee within %g m of the floor",
			      l[BODY_LEFT].kneeling ? "left" : "right", cfg->kneel_height);
	} else if (a->legs_on_floor < 2) {
		/* the supporting leg: the one whose foot bears weight, else the one carrying more */
		k = l[BODY_RIGHT].foot_on_floor != l[BODY_LEFT].foot_on_floor ?
			    (l[BODY_RIGHT].foot_on_floor ? BODY_RIGHT : BODY_LEFT) :
			    (l[BODY_RIGHT].weight_share > l[BODY_LEFT].weight_share ? BODY_RIGHT :
										      BODY_LEFT);
		int bent = l[k].knee_flexion > cfg->knee_bent;
		code = bent ? 5 : 3;
		assess_adjust(p, 0, "on the %s foot alone, knee flexion %.1f %s %g deg", side_word[k],
			      l[k].knee_flexion, bent ? ">" : "<=", cfg->knee_bent);
	} else {
		int bl = l[BODY_LEFT].knee_flexion > cfg->knee_bent;
		int br = l[BODY_RIGHT].knee_flexion > cfg->knee_bent;
		code = bl && br ? 4 : 2;
		assess_adjust(p, 0, "on both feet, knee flexion %.1f and %.1f: %s %g deg",
			      l[BODY_LEFT].knee_flexion, l[BODY_RIGHT].knee_flexion,
			      bl && br ? "both >" : "not both >", cfg->knee_bent);
	}
	if (k >= 0) {
		p->angle = l[k].knee_flexion;
		p->angle_name = k == BODY_LEFT ? "knee_flexion_l" : "knee_flexion_r";
	}
	assess_band(p, code, legs_words[code]);
	return assess_close(p, 1, 7);
}

static int
load(struct assess_result *r, const struct owas_options *o)
{
	double kg = o->load_kg >= 0 ? o->load_kg : 0;
	int code = kg <= 10 ? 1 : kg <= 20 ? 2 : 3;
	struct assess_part *p = assess_part(r, "load", NULL, NAN, 0, 3);
	assess_band(p, code, load_words[code]);
	assess_adjust(p, 0, "load %.1f kg", kg);
	return assess_close(p, 1, 3);
}

void
owas_score(const struct body_angles *a, const struct assess_config *cfg,
	   const struct owas_options *o, struct assess_result *r)
{
	assess_begin(r, ASSESS_OWAS, -1);
	int c[4];
	c[0] = back(r, a, cfg);
	c[1] = arms(r, a);
	c[2] = legs(r, a, cfg);
	c[3] = load(r, o);
	for (int i = 0; i < 4; i++)
		r->code[i] = (char)('0' + c[i]);
	r->code[4] = 0;
	r->score = assess_lookup(r, "AC", 4, names, c, owas_category(c[0], c[1], c[2], c[3]));
	r->action_level = r->score;
	r->action = action_words[r->score];
	/* the worst part: the one whose code, made neutral (back 1, arms 1, legs 2 or the
	   seated 1), lowers the category most; the back on ties */
	int neutral[3] = { 1, 1, c[2] == 1 ? 1 : 2 }, best = -1;
	r->worst = 0;
	for (int i = 0; i < 3; i++) {
		int n[4] = { c[0], c[1], c[2], c[3] };
		n[i] = neutral[i];
		int gain = r->score - owas_category(n[0], n[1], n[2], n[3]);
		if (gain > best) {
			best = gain;
			r->worst = i;
		}
	}
}
