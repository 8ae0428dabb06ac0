/*
 * test_anthropometry.c - the human's landmarks, the figure measured in
 * ANSUR II's postures, and figures built from measures: every ANSUR II
 * subject's 20 measures (data/ansur2) met within 2 mm, mass exactly, as the
 * measuring (pose/anthropometry.c, forward kinematics on the landmark
 * sites) finds them.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/figure.h"
#include "figure/human.h"
#include "figure/kin.h"
#include "figure/model.h"
#include "figure/state.h"
#include "pose/anthropometry.h"

#define DATA "data/ansur2/"
#define TOL_MM 2.0

/* one subject: the 20 measures in measures.h's order (weightkg in kg) */
struct subject {
	double v[HUMAN_MEASURE_N];
};

/* the subjects of one file; n, or -1 when it cannot be read */
static int
read_subjects(const char *path, struct subject **dest)
{
	FILE *f = fopen(path, "r");
	if (!f)
		return -1;
	static char line[1 << 14];
	int col[HUMAN_MEASURE_N], n = 0, cap = 0;
	struct subject *s = NULL;
	if (!fgets(line, sizeof line, f)) {
		fclose(f);
		return -1;
	}
	for (int k = 0; k < HUMAN_MEASURE_N; k++)
		col[k] = -1;
	int c = 0;
	for (char *tok = strtok(line, ",\r\n"); tok; tok = strtok(NULL, ",\r\n"), c++) {
		int k = anthro_find(tok);
		if (k >= 0)
			col[k] = c;
	}
	for (int k = 0; k < HUMAN_MEASURE_N; k++)
		if (col[k] < 0) {
			fclose(f);
			return -1;
		}
	while (fgets(line, sizeof line, f)) {
		if (n == cap) {
			cap = cap ? 2 * cap : 1024;
			s = realloc(s, sizeof *s * (size_t)cap);
			assert_non_null(s);
		}
		double cell[128];
		c = 0;
		/* the measured columns are plain numbers; the text columns after them may hold anything */
		for (char *p = line; c < 128 && *p && *p != '\n'; c++) {
			cell[c] = strtod(p, NULL);
			p = strchr(p, ',');
			if (!p)
				break;
			p++;
		}
		for (int k = 0; k < HUMAN_MEASURE_N; k++)
			s[n].v[k] = cell[col[k]];
		s[n].v[HUMAN_M_WEIGHTKG] /= 10; /* the files hold tenths of a kilogram */
		n++;
	}
	fclose(f);
	*dest = s;
	return n;
}

static struct human_def
def_of(const double v[HUMAN_MEASURE_N], unsigned given, enum human_sex sex)
{
	struct human_def d = human_default_def(sex);
	for (int k = 0; k < HUMAN_MEASURE_N; k++)
		if (given >> k & 1u)
			d.measure[k] = v[k];
	d.measure_given = given;
	if (given >> HUMAN_M_STATURE & 1u)
		d.stature = v[HUMAN_M_STATURE] / 1000;
	if (given >> HUMAN_M_WEIGHTKG & 1u)
		d.mass = v[HUMAN_M_WEIGHTKG];
	return d;
}

static void
measure(const struct model *m, double dest[HUMAN_MEASURE_N])
{
	char err[256];
	if (anthro_measure(m, dest, err, sizeof err) < 0)
		fail_msg("anthro_measure: %s", err);
}

#define ALL ((1u << HUMAN_MEASURE_N) - 1)

/* the figure with its landmark sites, measures given or not */
static struct model *
build_or_fail(const struct human_def *d)
{
	char err[256];
	struct model *m = human_build_landmarked(d, err, sizeof err);
	if (!m)
		fail_msg("human_build: %s", err);
	return m;
}

static const double *
at(const struct model *m, const struct state *s, const char *name)
{
	int k = model_find_site(m, name);
	if (k < 0)
		fail_msg("no site %s", name);
	return s->site_xf[k].p;
}

/* ANSUR II means (tools/ansur2_landmarks.py's output), fractions of stature: men, women */
static const struct {
	double acromion_y, acromion_x, stylion_z, seat, midpatella_y, trochanterion_x, tibiale_y,
		iliocristale_y;
} ansur[2] = {
	{ 0.0291, 0.0195, 0.0160, 0.0359, -0.0019, 0.0985, -0.0134, 0.0915 },
	{ 0.0325, 0.0123, 0.0151, 0.0452, -0.0104, 0.1087, -0.0173, 0.0923 },
};

/*
 * The landmarks stand where their sources put them, in the built posture:
 * on today's figure (men and women) and on one built from a subject's
 * measures (ANSUR II's first man).
 */
static void
test_landmarks_where_the_sources_put_them(void **unused)
{
	(void)unused;
	struct subject *subj = NULL;
	assert_true(read_subjects(DATA "ANSUR_II_MALE_Public.csv", &subj) > 0);
	struct human_def defs[3] = { human_default_def(HUMAN_MALE), human_default_def(HUMAN_FEMALE),
				     def_of(subj[0].v, ALL, HUMAN_MALE) };
	for (int f = 0; f < 3; f++) {
		struct model *m = build_or_fail(&defs[f]);
		struct state *s = state_make(m);
		kin_update(m, s);
		double H = defs[f].stature, tol = 1e-12;
		int w = defs[f].sex == HUMAN_FEMALE;
		for (int side = 0; side < 2; side++) {
			char n[64];
#define P(fmt) (snprintf(n, sizeof n, fmt, side ? 'r' : 'l'), at(m, s, n))
			const double *hip = P("thigh_%c.origin"), *knee = P("shank_%c.origin");
			const double *ankle = P("foot_%c.origin"), *gh = P("upperarm_%c.origin");
			const double *wrist = P("hand_%c.origin");
			/* the joint centres at the landmarks' levels (Wu et al. 2002; the trochanter's summit) */
			assert_near(P("thigh_%c.trochanterion")[1], hip[1], tol);
			assert_near(P("thigh_%c.lateral_femoral_epicondyle")[1], knee[1], tol);
			assert_near(P("shank_%c.lateral_malleolus")[1], ankle[1], tol);
			assert_near(P("forearm_%c.stylion")[1], wrist[1], tol);
			/* landmarks outside their joints: lateral ones farther from the midline */
			assert_true(fabs(P("thigh_%c.trochanterion")[0]) > fabs(hip[0]));
			assert_true(fabs(P("thigh_%c.lateral_femoral_epicondyle")[0]) > fabs(knee[0]));
			assert_true(fabs(P("shank_%c.lateral_malleolus")[0]) > fabs(ankle[0]));
			assert_true(fabs(P("shank_%c.tibiale")[0]) < fabs(knee[0]));
			/* the dactylion is the middle finger's tip */
			const double *tip = P("hand_%c.fingertip"), *dact = P("hand_%c.dactylion");
			for (int r = 0; r < 3; r++)
				assert_near(dact[r], tip[r], tol);
			if (f < 2) {
				/* today's figure: the offsets are ANSUR II's means */
				assert_near(P("clavicle_%c.acromion")[1] - gh[1], ansur[w].acromion_y * H, 1e-9);
				assert_near(fabs(P("clavicle_%c.acromion")[0]) - fabs(gh[0]),
					    ansur[w].acromion_x * H, 1e-9);
				assert_near(P("thigh_%c.midpatella")[1] - knee[1], ansur[w].midpatella_y * H,
					    1e-9);
				assert_near(fabs(P("thigh_%c.trochanterion")[0]), ansur[w].trochanterion_x * H,
					    1e-9);
				assert_near(P("shank_%c.tibiale")[1] - knee[1], ansur[w].tibiale_y * H, 1e-9);
				/* the elbow's two radiales coincide */
				assert_near(P("upperarm_%c.radiale")[1], P("forearm_%c.radiale")[1], tol);
			}
			/* the suprapatella ahead of the knee, the popliteal behind, the buttock behind the hip */
			assert_true(P("thigh_%c.suprapatella")[2] > knee[2]);
			assert_true(P("thigh_%c.popliteal")[2] < knee[2]);
			assert_true(P("thigh_%c.knee_front")[1] < knee[1]);
			assert_true(P("clavicle_%c.shoulder_blade")[2] < gh[2]);
			assert_true(P("foot_%c.pternion")[2] < ankle[2] && P("toes_%c.acropodion")[2] > ankle[2]);
#undef P
		}
		/* midline and head */
		const double *pelvis = at(m, s, "pelvis.root");
		assert_near(at(m, s, "head.vertex")[1], H, tol);
		assert_near(at(m, s, "head.ectocanthus_r")[1], at(m, s, "eyeball_r.origin")[1], tol);
		assert_near(at(m, s, "head.sellion")[1], at(m, s, "eyeball_r.origin")[1], tol);
		assert_near(at(m, s, "head.cervicale")[1], at(m, s, "head.origin")[1], tol);
		assert_true(at(m, s, "head.cervicale")[2] < at(m, s, "head.origin")[2]);
		assert_near(at(m, s, "T1.suprasternale")[1], at(m, s, "clavicle_r.origin")[1], tol);
		assert_true(at(m, s, "T1.suprasternale")[2] > at(m, s, "clavicle_r.origin")[2]);
		/* the tragion near the Frankfort plane: a little below the eyes */
		double eye = at(m, s, "eyeball_l.origin")[1], tragion = at(m, s, "head.tragion_l")[1];
		assert_true(tragion < eye && tragion > eye - 0.03 * H);
		if (f < 2) {
			assert_near(pelvis[1] - at(m, s, "pelvis.ischial_tuberosity_l")[1], ansur[w].seat * H,
				    1e-9);
			assert_near(at(m, s, "pelvis.iliocristale_r")[1] - pelvis[1],
				    ansur[w].iliocristale_y * H, 1e-9);
		}
		/* every landmark is a site by translation only */
		for (int k = 0; k < m->nsite; k++)
			assert_true(m->site_pure[k]);
		state_free(s);
		model_free(m);
	}
	free(subj);
}

/*
 * Today's man (1.75 m, 75 kg, on his landmarked twin) measured: Drillis & Contini's stature
 * fractions (human_data.c) with the landmarks' ANSUR II offsets, worked out
 * by hand; the seated knee measures from the shank as built (it leans a
 * little for balance: the seated shank hangs straight).
 */
static void
test_todays_man_measured(void **unused)
{
	(void)unused;
	struct human_def d = human_default_def(HUMAN_MALE);
	struct model *m = build_or_fail(&d);
	double v[HUMAN_MEASURE_N], H = 1750;
	measure(m, v);
	const double tol = 1e-9;
	double hand = 0.485 - 0.377, sz = 0.0160, rx = 0.014;
	assert_near(v[HUMAN_M_STATURE], H, tol);
	assert_near(v[HUMAN_M_TROCHANTERIONHEIGHT], 0.530 * H, tol);
	assert_near(v[HUMAN_M_LATERALMALLEOLUSHEIGHT], 0.039 * H, tol);
	assert_near(v[HUMAN_M_KNEEHEIGHTMIDPATELLA], (0.285 - 0.0019) * H, tol);
	assert_near(v[HUMAN_M_WRISTHEIGHT], 0.485 * H, tol);
	assert_near(v[HUMAN_M_ACROMIALHEIGHT], (0.818 + 0.0291) * H, tol);
	assert_near(v[HUMAN_M_ACROMIONRADIALELENGTH], hypot(0.818 + 0.0291 - 0.630, 0.0195 - rx) * H, tol);
	assert_near(v[HUMAN_M_RADIALESTYLIONLENGTH], sqrt(pow(0.630 - 0.485, 2) + rx * rx + sz * sz) * H,
		    tol);
	assert_near(v[HUMAN_M_HANDLENGTH], hypot(hand, sz) * H, tol);
	assert_near(v[HUMAN_M_FOOTLENGTH], 0.152 * H, tol);
	assert_near(v[HUMAN_M_BIACROMIALBREADTH], 2 * (0.129 + 0.0195) * H, tol);
	assert_near(v[HUMAN_M_HIPBREADTH], 2 * 0.0985 * H, tol);
	/* span: shoulder joints 0.129 H out, each arm from the shoulder joint to the fingertip */
	assert_near(v[HUMAN_M_SPAN], 2 * (0.129 + 0.818 - 0.377) * H, tol);
	/* seated: the seat 0.0359 H below the hips, the eyes Drillis & Contini's 0.064 H below the top */
	assert_near(v[HUMAN_M_SITTINGHEIGHT], (1 - 0.530 + 0.0359) * H, tol);
	assert_near(v[HUMAN_M_EYEHEIGHTSITTING], (1 - 0.530 + 0.0359 - (1 - 0.936)) * H, tol);
	/* thumbtip reach: the wall 0.0876 H behind the shoulder joint, the pinch 0.6 hands below wrist */
	assert_near(v[HUMAN_M_THUMBTIPREACH],
		    (0.0876 + 0.818 - 0.485 + 0.6 * hypot(hand, sz)) * H, tol);
	/* buttock-knee: the buttock 0.0833 H behind the hip, the thigh, the knee's front 0.0356 H on */
	assert_near(v[HUMAN_M_BUTTOCKKNEELENGTH], (0.0833 + 0.530 - 0.285 + 0.0356) * H, tol);
	struct state *s = state_make(m);
	kin_update(m, s);
	const double *knee = at(m, s, "shank_r.origin"), *ankle = at(m, s, "foot_r.origin");
	double shank = hypot(knee[1] - ankle[1], knee[2] - ankle[2]) * 1000;
	assert_true(shank > (0.285 - 0.039) * H && shank < (0.285 - 0.039) * H * 1.01);
	assert_near(v[HUMAN_M_KNEEHEIGHTSITTING], 0.0356 * H + shank + 0.039 * H, tol);
	assert_near(v[HUMAN_M_POPLITEALHEIGHT], shank + 0.039 * H - 0.0352 * H, tol);
	assert_near(v[HUMAN_M_WEIGHTKG], 75, 1e-12);
	state_free(s);
	model_free(m);
}

/* every subject of both files built from all 20 measures and measured back */
static void
test_every_subject_meets_its_measures(void **unused)
{
	(void)unused;
	static const struct {
		const char *file;
		enum human_sex sex;
	} files[] = { { DATA "ANSUR_II_MALE_Public.csv", HUMAN_MALE },
		      { DATA "ANSUR_II_FEMALE_Public.csv", HUMAN_FEMALE } };
	double worst[HUMAN_MEASURE_N] = { 0 }, sq[HUMAN_MEASURE_N] = { 0 };
	int total = 0;
	for (size_t f = 0; f < 2; f++) {
		struct subject *s = NULL;
		int n = read_subjects(files[f].file, &s);
		if (n < 0)
			fail_msg("cannot read %s (run from the repository's root)", files[f].file);
		assert_int_equal(n, files[f].sex == HUMAN_MALE ? 4082 : 1986);
		for (int i = 0; i < n; i++) {
			struct human_def d = def_of(s[i].v, ALL, files[f].sex);
			char err[256];
			struct model *m = human_build(&d, err, sizeof err);
			if (!m)
				fail_msg("%s subject %d: %s", files[f].file, i + 2, err);
			double got[HUMAN_MEASURE_N];
			measure(m, got);
			for (int k = 0; k < HUMAN_MEASURE_N; k++) {
				double e = got[k] - s[i].v[k];
				sq[k] += e * e;
				worst[k] = fmax(worst[k], fabs(e));
				if (k == HUMAN_M_WEIGHTKG ? fabs(e) > 1e-9 : fabs(e) > TOL_MM)
					fail_msg("%s line %d: %s measured %.3f, given %.3f", files[f].file,
						 i + 2, anthro_name((enum human_measure)k), got[k], s[i].v[k]);
			}
			model_free(m);
			total++;
		}
		free(s);
	}
	printf("# %d subjects: measured against given, mm (weightkg: kg)\n", total);
	printf("# %-24s %12s %12s\n", "measure", "max |error|", "rms");
	for (int k = 0; k < HUMAN_MEASURE_N; k++)
		printf("# %-24s %12.3g %12.3g\n", anthro_name((enum human_measure)k), worst[k],
		       sqrt(sq[k] / total));
}

/* a small deterministic generator for the subsets */
static unsigned
next_rand(unsigned *state)
{
	*state = *state * 1103515245u + 12345u;
	return *state >> 8;
}

/* builds from the given subset of a subject's measures; each given one is met */
static void
check_subset(const double v[HUMAN_MEASURE_N], unsigned given, enum human_sex sex, const char *who)
{
	struct human_def d = def_of(v, given, sex);
	char err[256];
	struct model *m = human_build(&d, err, sizeof err);
	if (!m)
		fail_msg("%s, measures %#x: %s", who, given, err);
	double got[HUMAN_MEASURE_N];
	measure(m, got);
	for (int k = 0; k < HUMAN_MEASURE_N; k++) {
		if (!(given >> k & 1u))
			continue;
		double e = fabs(got[k] - v[k]);
		if (k == HUMAN_M_WEIGHTKG ? e > 1e-9 : e > TOL_MM)
			fail_msg("%s, measures %#x: %s measured %.3f, given %.3f", who, given,
				 anthro_name((enum human_measure)k), got[k], v[k]);
	}
	model_free(m);
}

#define BIT(x) (1u << HUMAN_M_##x)

/*
 * Any subset of a subject's measures with the stature is met (those not
 * given take ANSUR II's mean ratios to stature): the arm's and the
 * shoulders' chains with members missing, and random subsets, for every
 * 10th subject.
 */
static void
test_subsets_of_measures_are_met(void **unused)
{
	(void)unused;
	static const unsigned chains[] = {
		BIT(WRISTHEIGHT),
		BIT(ACROMIONRADIALELENGTH) | BIT(WRISTHEIGHT),
		BIT(RADIALESTYLIONLENGTH) | BIT(WRISTHEIGHT),
		BIT(ACROMIONRADIALELENGTH) | BIT(RADIALESTYLIONLENGTH) | BIT(WRISTHEIGHT),
		BIT(ACROMIALHEIGHT) | BIT(WRISTHEIGHT),
		BIT(ACROMIALHEIGHT) | BIT(ACROMIONRADIALELENGTH) | BIT(RADIALESTYLIONLENGTH),
		BIT(ACROMIALHEIGHT) | BIT(ACROMIONRADIALELENGTH) | BIT(RADIALESTYLIONLENGTH) |
			BIT(WRISTHEIGHT),
		BIT(BIACROMIALBREADTH),
		BIT(SPAN),
		BIT(SPAN) | BIT(BIACROMIALBREADTH),
		BIT(SPAN) | BIT(HANDLENGTH),
		BIT(TROCHANTERIONHEIGHT),
		BIT(KNEEHEIGHTMIDPATELLA),
		BIT(LATERALMALLEOLUSHEIGHT) | BIT(TROCHANTERIONHEIGHT),
		BIT(EYEHEIGHTSITTING),
		BIT(SITTINGHEIGHT) | BIT(EYEHEIGHTSITTING),
		BIT(KNEEHEIGHTSITTING) | BIT(POPLITEALHEIGHT) | BIT(BUTTOCKKNEELENGTH),
		BIT(WEIGHTKG),
		BIT(THUMBTIPREACH) | BIT(HANDLENGTH),
	};
	static const struct {
		const char *file;
		enum human_sex sex;
	} files[] = { { DATA "ANSUR_II_MALE_Public.csv", HUMAN_MALE },
		      { DATA "ANSUR_II_FEMALE_Public.csv", HUMAN_FEMALE } };
	unsigned seed = 24;
	int built = 0;
	for (size_t f = 0; f < 2; f++) {
		struct subject *s = NULL;
		int n = read_subjects(files[f].file, &s);
		assert_true(n > 0);
		for (int i = 0; i < n; i += 10) {
			char who[128];
			snprintf(who, sizeof who, "%s line %d", files[f].file, i + 2);
			/* with the stature, which scales what is not given */
			for (size_t c = 0; c < sizeof chains / sizeof *chains; c++, built++)
				check_subset(s[i].v, chains[c] | BIT(STATURE), files[f].sex, who);
			for (int r = 0; r < 4; r++, built++)
				check_subset(s[i].v, (next_rand(&seed) & ALL) | BIT(STATURE), files[f].sex,
					     who);
		}
		free(s);
	}
	print_message("%d figures from subsets of measures\n", built);
}

/* a subject's measures with one changed, expected refused with `want` in the message */
static void
check_refused(const double v[HUMAN_MEASURE_N], unsigned given, int k, double value,
	      const char *want)
{
	double w[HUMAN_MEASURE_N];
	memcpy(w, v, sizeof w);
	if (k >= 0)
		w[k] = value;
	struct human_def d = def_of(w, given, HUMAN_MALE);
	char err[256] = "";
	struct model *m = human_build(&d, err, sizeof err);
	if (m)
		fail_msg("built with %s = %g; want refused (%s)", k >= 0 ? anthro_name(k) : "-", value,
			 want);
	if (!strstr(err, want))
		fail_msg("refused with '%s'; want '%s' in it", err, want);
	print_message("refused: %s\n", err);
}

/* measures no body can meet, or that are no measures, are refused with why; nothing is built */
static void
test_impossible_measures_are_refused(void **unused)
{
	(void)unused;
	struct subject *s = NULL;
	assert_true(read_subjects(DATA "ANSUR_II_MALE_Public.csv", &s) > 0);
	const double *v = s[0].v;
	/* the seat above the hips: a sitting height far below stature less leg */
	check_refused(v, ALL & ~BIT(EYEHEIGHTSITTING), HUMAN_M_SITTINGHEIGHT,
		      v[HUMAN_M_SITTINGHEIGHT] - 200, "the seat below the hip joint centres");
	/* arm lengths that overshoot the drop from shoulder to wrist by 15 cm */
	check_refused(v, ALL, HUMAN_M_ACROMIONRADIALELENGTH, v[HUMAN_M_ACROMIONRADIALELENGTH] + 150,
		      "radiale");
	/* a span shorter than the arms alone */
	check_refused(v, ALL, HUMAN_M_SPAN, 2 * (v[HUMAN_M_ACROMIALHEIGHT] - v[HUMAN_M_WRISTHEIGHT]),
		      "span");
	/* hips narrower than the hip joints */
	check_refused(v, ALL, HUMAN_M_HIPBREADTH, 100, "hipbreadth");
	/* knees: the popliteal above the knee's top */
	check_refused(v, ALL, HUMAN_M_POPLITEALHEIGHT, v[HUMAN_M_KNEEHEIGHTSITTING] + 10,
		      "poplitealheight");
	check_refused(v, ALL, HUMAN_M_KNEEHEIGHTMIDPATELLA, v[HUMAN_M_TROCHANTERIONHEIGHT],
		      "kneeheightmidpatella");
	check_refused(v, ALL, HUMAN_M_THUMBTIPREACH, 300, "thumbtipreach");
	check_refused(v, ALL, HUMAN_M_EYEHEIGHTSITTING, v[HUMAN_M_SITTINGHEIGHT] + 5,
		      "eyeheightsitting");
	/* not measures */
	check_refused(v, ALL, HUMAN_M_HANDLENGTH, -190, "positive");
	check_refused(v, ALL, HUMAN_M_FOOTLENGTH, NAN, "positive");
	check_refused(v, ALL, HUMAN_M_BUTTOCKKNEELENGTH, INFINITY, "positive");
	check_refused(v, ALL | 1u << HUMAN_MEASURE_N, -1, 0, "unknown");
	/* stature and weight said twice, differently */
	struct human_def d = def_of(v, ALL, HUMAN_MALE);
	d.stature += 0.01;
	char err[256] = "";
	assert_null(human_build(&d, err, sizeof err));
	assert_non_null(strstr(err, "stature"));
	d = def_of(v, ALL, HUMAN_MALE);
	d.mass += 1;
	assert_null(human_build(&d, err, sizeof err));
	assert_non_null(strstr(err, "weightkg"));
	free(s);
}

/* figures built from measures stand balanced as today's does, their masses and inertias physical */
static void
test_measured_figures_stand_balanced(void **unused)
{
	(void)unused;
	struct subject *s = NULL;
	int n = read_subjects(DATA "ANSUR_II_FEMALE_Public.csv", &s);
	assert_true(n > 0);
	for (int i = 0; i < n; i += 97) {
		struct human_def d = def_of(s[i].v, ALL, HUMAN_FEMALE);
		struct model *m = build_or_fail(&d);
		struct state *st = state_make(m);
		kin_update(m, st);
		const double *bl = at(m, st, "foot_l.balance"), *br = at(m, st, "foot_r.balance");
		assert_near(st->com[0], (bl[0] + br[0]) / 2, 1e-9);
		assert_near(st->com[2], (bl[2] + br[2]) / 2, 1e-9);
		assert_near(m->total_mass, s[i].v[HUMAN_M_WEIGHTKG], 1e-9);
		for (int g = 0; g < m->nseg; g++) {
			const double *I = &m->seg_inertia[6 * g];
			assert_true(m->seg_mass[g] > 0);
			/* principal moments obey the triangle inequality; checked on the diagonal here */
			assert_true(I[0] > 0 && I[1] > 0 && I[2] > 0);
			assert_true(I[0] + I[1] >= I[2] && I[1] + I[2] >= I[0] && I[0] + I[2] >= I[1]);
		}
		state_free(st);
		model_free(m);
	}
	free(s);
}

/* only a figure with the human's landmarks is measured */
static void
test_other_figures_are_not_measured(void **unused)
{
	(void)unused;
	char err[512] = "";
	struct model *m = figure_read_file("src/figure/library/chair.fig", err, sizeof err);
	if (!m)
		fail_msg("chair.fig: %s", err);
	double v[HUMAN_MEASURE_N];
	assert_int_equal(anthro_measure(m, v, err, sizeof err), -1);
	assert_non_null(strstr(err, "landmarks"));
	model_free(m);
}

/*
 * Today's figure (no measures) keeps its sites, and their order, as they
 * were: the landmarks are on its twin, whose body is the same bit for bit.
 */
static void
test_todays_figure_keeps_its_sites(void **unused)
{
	(void)unused;
	for (int sex = 0; sex < 2; sex++) {
		struct human_def d = human_default_def(sex ? HUMAN_FEMALE : HUMAN_MALE);
		char err[256];
		struct model *m = human_build(&d, err, sizeof err), *twin = build_or_fail(&d);
		assert_non_null(m);
		assert_int_equal(m->nsite, 101);
		assert_int_equal(model_find_site(m, "thigh_l.trochanterion"), -1);
		assert_int_equal(twin->nsite, 101 + 47);
		assert_int_equal(m->nseg, twin->nseg);
		assert_int_equal(m->ndof, twin->ndof);
		assert_true(memcmp(m->seg_mass, twin->seg_mass, sizeof *m->seg_mass * (size_t)m->nseg) == 0);
		assert_true(memcmp(m->seg_com, twin->seg_com, 3 * sizeof *m->seg_com * (size_t)m->nseg) == 0);
		assert_true(memcmp(m->seg_inertia, twin->seg_inertia,
				   6 * sizeof *m->seg_inertia * (size_t)m->nseg) == 0);
		for (int k = 0; k < m->nsite; k++) {
			char name[2 * MODEL_NAME_MAX];
			int t = model_find_site(twin, model_site_fullname(m, k, name, sizeof name));
			assert_true(t >= 0);
			assert_true(memcmp(&m->site_pos[3 * k], &twin->site_pos[3 * t], 3 * sizeof(double)) == 0);
		}
		/* measuring today's figure measures its twin */
		double a[HUMAN_MEASURE_N], b[HUMAN_MEASURE_N];
		assert_int_equal(anthro_measure(m, a, err, sizeof err), -1);
		assert_int_equal(anthro_measure_figure(m, &d, a, err, sizeof err), 0);
		measure(twin, b);
		assert_true(memcmp(a, b, sizeof a) == 0);
		model_free(m);
		model_free(twin);
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_todays_figure_keeps_its_sites),
		cmocka_unit_test(test_landmarks_where_the_sources_put_them),
		cmocka_unit_test(test_todays_man_measured),
		cmocka_unit_test(test_every_subject_meets_its_measures),
		cmocka_unit_test(test_subsets_of_measures_are_met),
		cmocka_unit_test(test_impossible_measures_are_refused),
		cmocka_unit_test(test_measured_figures_stand_balanced),
		cmocka_unit_test(test_other_figures_are_not_measured),
	};
	return cmocka_run_group_tests_name("anthropometry", tests, NULL, NULL);
}
