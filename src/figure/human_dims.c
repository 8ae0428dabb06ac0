/*
 * human_dims.c - where the human's joint centres and surface landmarks go:
 * today's stature fractions (Drillis & Contini, Hara et al.; human.c), or
 * the ANSUR II measures a build is given (measures.h), met as
 * anthropometry/anthropometry.c measures them.
 *
 * Landmarks (sites by translation, left side; the right is mirrored) sit
 * at fixed offsets from the joint centres; the offsets are ANSUR II means
 * (fractions of stature, per sex; tools/ansur2_landmarks.py derives them
 * from data/ansur2), de Leva (1996), or assumptions named below. With
 * measures given, each measure sets one thing of the body, in an order in
 * which nothing set later changes a measure met earlier:
 *
 *   lateralmalleolusheight  the ankle joint centre's height (the lateral
 *                           malleolus is level with it: the ankle joint
 *                           centre is the malleoli's midpoint, Wu et al.
 *                           2002, J Biomech 35:543)
 *   kneeheightmidpatella    the knee joint centre's, at the lateral femoral
 *                           epicondyle (Wu et al. 2002), the midpatella an
 *                           ANSUR mean below or above it
 *   trochanterionheight     the hip joint centre's: the summit of the
 *                           greater trochanter is level with the femoral
 *                           head's centre (assumption from surface anatomy)
 *   stature                 the vertex; the trunk between the hip and C7/T1
 *                           stretches to fill what the legs leave (the head
 *                           keeps its stature fraction)
 *   acromialheight          the acromion; the shoulder joint an ANSUR-de
 *                           Leva offset below it
 *   acromionradialelength,  the elbow, wrist and fingertip (below)
 *   radialestylionlength,
 *   wristheight, handlength
 *   biacromialbreadth, span the acromion's and the shoulder joint's
 *                           distance from the midline (below)
 *   sittingheight           the seat's depth below the hip joint centres
 *                           (the ischial tuberosities, seated)
 *   eyeheightsitting        the eyes' height
 *   kneeheightsitting       the suprapatella's distance from the knee axis
 *   poplitealheight         the popliteal's
 *   buttockkneelength       the buttock's distance behind the hip joint
 *   thumbtipreach           the shoulder blades' distance behind the
 *                           shoulder joint (the wall the reach starts from)
 *   hipbreadth              the trochanterions' distance from the midline
 *   footlength              the foot's length
 *   weightkg                the mass (in the definition's mass, exactly)
 *
 * Where measures overdetermine the body:
 *   - acromialheight - wristheight = acromionradialelength +
 *     radialestylionlength for a straight hanging arm (up to the landmarks'
 *     small sideways offsets). ANSUR II's own subjects miss it by -52 to
 *     +34 mm (mean -10, SD 11: observers' error and how the arm hangs), and
 *     no rigid arm has its landmarks farther apart vertically than along
 *     it. So the radiale has two sites: the end of the acromion-radiale
 *     length on the upper arm and the start of the radiale-stylion length on
 *     the forearm, the elbow joint centre midway; the gap between them is
 *     the measures' disagreement.
 *   - span = 2 (the shoulder joint's distance from the midline + the arm
 *     from the shoulder joint to the middle finger's tip), and
 *     biacromialbreadth = 2 (that distance + the acromion's overhang
 *     outside the joint): the overhang is what the two leave.
 * The offsets these leave free (the seat, the overhang, the radiale gap,
 * the knee's depths, the buttock, the shoulder blades) must stay within
 * bounds wider than every ANSUR II subject's; outside them the build is
 * refused with the measures that disagree named.
 *
 * With any measure given, one not given follows from the others where it
 * closes one of the sets above (wristheight, else radialestylionlength,
 * else acromionradialelength, else acromialheight with the radiales
 * coinciding; span, else biacromialbreadth, with the overhang's mean), or
 * where its landmark's offset is free (sittingheight, eyeheightsitting,
 * the seated knee's measures, buttockkneelength, thumbtipreach,
 * hipbreadth: the offset keeps its ANSUR mean); any other takes the ANSUR
 * II mean of its ratio to stature (the sex's proportions at this stature).
 * The daemon's `load human` gives all 20, those not given predicted from
 * the given ones. With none, the figure is today's.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "figure/human_data.h"

/*
 * ANSUR II means as fractions of stature (tools/ansur2_landmarks.py; the
 * relations are in its header), men and women.
 */
struct human_lm_fractions {
	double acromion_y;     /* acromion above the shoulder joint (ANSUR acromion-radiale
				  length less de Leva's shoulder-to-elbow) */
	double stylion_z;      /* stylion ahead of the wrist's axis (wrist circumference / 2 pi) */
	double acromion_x;     /* acromion outside the shoulder joint (from span) */
	double seat;           /* seat below the hip joint centres, sitting */
	double midpatella_y;   /* midpatella above the knee joint centre */
	double suprapatella;   /* suprapatella ahead of the knee axis (above it, seated) */
	double popliteal;      /* popliteal behind the knee axis (below it, seated) */
	double buttock;        /* buttock behind the hip joint centres */
	double shoulder_blade; /* shoulder blades behind the shoulder joints */
	double trochanterion_x; /* hip breadth / 2 */
	double tibiale_y;      /* tibiale above the knee joint centre */
	double iliocristale_y; /* iliocristale above the hip joint centre */
	double iliocristale_x; /* bicristal breadth / 2 */
	double malleolus_x;    /* bimalleolar breadth / 2 */
	double tragion_y;      /* tragion below the vertex */
	double tragion_x;      /* head breadth / 2 */
};

static const struct human_lm_fractions lm_male = {
	0.0291, 0.0160, 0.0195, 0.0359, -0.0019, 0.0356, 0.0352, 0.0833,
	0.0876, 0.0985, -0.0134, 0.0915, 0.0784, 0.0213, 0.0748, 0.0440,
};

static const struct human_lm_fractions lm_female = {
	0.0325, 0.0151, 0.0123, 0.0452, -0.0104, 0.0278, 0.0477, 0.1019,
	0.0906, 0.1087, -0.0173, 0.0923, 0.0839, 0.0206, 0.0778, 0.0454,
};

/* each measure's ANSUR II mean ratio to stature (tools/ansur2_landmarks.py), measures.h's order */
static const double ratio_male[HUMAN_MEASURE_N] = {
	1.00000, 0.82026, 0.48252, 0.51285, 0.27799, 0.04152, 0.52306, 0.45823, 0.19087, 0.15252,
	0.11007, 0.15444, 0.35186, 0.31547, 0.24464, 0.23682, 0.19696, 1.03302, 0.46235, 0,
};

static const double ratio_female[HUMAN_MEASURE_N] = {
	1.00000, 0.81975, 0.48766, 0.51898, 0.27565, 0.03854, 0.52624, 0.45931, 0.19107, 0.14817,
	0.11121, 0.15126, 0.36264, 0.31388, 0.23829, 0.22445, 0.21737, 1.01947, 0.45689, 0,
};

/*
 * Assumptions (no single published value; fractions of stature): the
 * radiale a little outside the elbow joint centre (about half the elbow's
 * breadth); the pinch point of thumbtip reach (thumb tip on the index
 * finger) 0.6 hand lengths below the wrist and a little ahead of it; the
 * lateral femoral epicondyle and the tibiale about half the knee's breadth
 * out and in; the suprapatella a little above the knee axis standing; the
 * ischial tuberosities, buttocks, shoulder blades and cervicale where the
 * body's outline puts them (only their depth or height enters a measure).
 */
#define RADIALE_X 0.014
#define PINCH 0.6
#define THUMB_Z 0.01
#define EPICONDYLE_X 0.028
#define TIBIALE_X 0.025
#define SUPRAPATELLA_Y 0.02

/* bounds of what the measures leave free, fractions of stature (every ANSUR II subject within) */
#define SEAT_LO (-0.04)
#define SEAT_HI 0.12
#define KNEE_DEPTH_LO 0.005
#define SUPRAPATELLA_HI 0.08
#define POPLITEAL_HI 0.12
#define BUTTOCK_LO 0.01
#define BUTTOCK_HI 0.22
#define BLADE_LO 0.01
#define BLADE_HI 0.23
#define OVERHANG_LO (-0.05)
#define OVERHANG_HI 0.09
#define RADIALE_GAP_LO (-0.05)
#define RADIALE_GAP_HI 0.04

const struct human_landmark_info human_landmark_info[HUMAN_LM_N] = {
#define HUMAN_LM_INFO(e, name, seg, bilateral) { name, seg, bilateral },
	HUMAN_LANDMARKS(HUMAN_LM_INFO)
#undef HUMAN_LM_INFO
};

static const char *const measure_name[HUMAN_MEASURE_N] = {
#define HUMAN_MEASURE_NAME(e, s) s,
	HUMAN_MEASURES(HUMAN_MEASURE_NAME)
#undef HUMAN_MEASURE_NAME
};

/* a measure of the figure built from measures (m) */
#define M(L, x) ((L)->dim.v[HUMAN_M_##x])

static const struct human_lm_fractions *
fractions(const struct human_layout *L)
{
	return L->dl == &human_dl_female ? &lm_female : &lm_male;
}

static void
vset(double dest[3], double x, double y, double z)
{
	dest[0] = x;
	dest[1] = y;
	dest[2] = z;
}

static int refuse(char *err, size_t errlen, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

static int
refuse(char *err, size_t errlen, const char *fmt, ...)
{
	if (err && errlen) {
		va_list ap;
		va_start(ap, fmt);
		vsnprintf(err, errlen, fmt, ap);
		va_end(ap);
	}
	return -1;
}

/* 0 when v (m) lies in [lo, hi] stature fractions, else -1 saying what and from which measures */
static int
within(double v, double lo, double hi, double H, const char *what, const char *from, char *err,
       size_t errlen)
{
	if (v >= lo * H && v <= hi * H)
		return 0;
	return refuse(err, errlen,
		      "human: the measures put %s at %.0f mm (%s); the body allows %.0f to %.0f mm",
		      what, v * 1000, from, lo * H * 1000, hi * H * 1000);
}

void
human_dims_default(struct human_layout *L)
{
	struct human_dims *D = &L->dim;
	const struct human_lm_fractions *F = fractions(L);
	double H = L->H, k = L->k;
	memset(D, 0, sizeof *D);
	/* Hara et al.: the hip joint centres from the leg length ASIS to malleolus */
	double ll = (human_dc_hip - human_dc_ankle) * H + 0.009;
	ll /= 1 - 0.078;
	D->hx = 0.008 + 0.086 * ll;
	D->y_asis = human_dc_hip * H + 0.009 + 0.078 * ll;
	D->y_ankle = human_dc_ankle * H;
	D->y_knee = human_dc_knee * H;
	D->y_hip = human_dc_hip * H;
	D->lf = human_dc_foot_length * H;
	D->fw = human_dc_foot_width * H;
	D->hand_len = L->dl->seg[HUMAN_DL_HAND].len * k;
	D->gh_x = human_dc_shoulder_half * H;
	D->gh_y = human_dc_shoulder * H;
	D->y_elbow = human_dc_elbow * H;
	D->y_wrist = human_dc_wrist * H;
	D->y_tip = human_dc_fingertip * H;
	D->y_eye = human_dc_eye * H;
	D->trunk_from = D->y_hip;
	vset(D->acromion, D->gh_x + F->acromion_x * H, D->gh_y + F->acromion_y * H, 0);
	D->radiale_upper_y = D->radiale_y = D->y_elbow;
}

/* C7/T1: one de Leva head length below the vertex, whatever the measures */
static double
c7_height(const struct human_layout *L)
{
	return L->H - L->dl->seg[HUMAN_DL_HEAD].len * L->k;
}

double
human_trunk_map(const struct human_layout *L, double y)
{
	double top = c7_height(L), from = L->dim.trunk_from, to = L->dim.y_hip;
	return to + (y - from) * (top - to) / (top - from);
}

double
human_trunk_unmap(const struct human_layout *L, double y)
{
	double top = c7_height(L), from = L->dim.trunk_from, to = L->dim.y_hip;
	return from + (y - to) * (top - from) / (top - to);
}

static int
check_given(const struct human_def *d, char *err, size_t errlen)
{
	if (d->measure_given >> HUMAN_MEASURE_N)
		return refuse(err, errlen, "human: unknown measures given (bits %#x)", d->measure_given);
	for (int i = 0; i < HUMAN_MEASURE_N; i++) {
		double v = d->measure[i];
		if (((d->measure_given >> i) & 1u) && !(v > 0 && isfinite(v)))
			return refuse(err, errlen, "human: %s must be a positive number of %s, not %g",
				      measure_name[i], i == HUMAN_M_WEIGHTKG ? "kg" : "mm", v);
	}
	if ((d->measure_given >> HUMAN_M_STATURE & 1u) &&
	    fabs(d->measure[HUMAN_M_STATURE] / 1000 - d->stature) > 0.0005)
		return refuse(err, errlen, "human: stature %g m and stature=%g mm disagree", d->stature,
			      d->measure[HUMAN_M_STATURE]);
	if ((d->measure_given >> HUMAN_M_WEIGHTKG & 1u) &&
	    fabs(d->measure[HUMAN_M_WEIGHTKG] - d->mass) > 1e-9 * d->mass)
		return refuse(err, errlen, "human: mass %g kg and weightkg=%g disagree", d->mass,
			      d->measure[HUMAN_M_WEIGHTKG]);
	return 0;
}

/* the legs' joint heights */
static int
leg_heights(struct human_layout *L, char *err, size_t errlen)
{
	struct human_dims *D = &L->dim;
	double H = L->H;
	D->y_ankle = M(L, LATERALMALLEOLUSHEIGHT);
	D->y_knee = M(L, KNEEHEIGHTMIDPATELLA) - fractions(L)->midpatella_y * H;
	D->y_hip = M(L, TROCHANTERIONHEIGHT);
	if (within(D->y_ankle, 0.015, 0.08, H, "the ankle joint centre", "lateralmalleolusheight",
		   err, errlen) < 0 ||
	    within(D->y_knee - D->y_ankle, 0.15, 0.34, H, "the shank",
		   "kneeheightmidpatella against lateralmalleolusheight", err, errlen) < 0 ||
	    within(D->y_hip - D->y_knee, 0.13, 0.34, H, "the thigh",
		   "trochanterionheight against kneeheightmidpatella", err, errlen) < 0 ||
	    within(c7_height(L) - D->y_hip, 0.2, 0.5, H, "the trunk from the hips to C7/T1",
		   "stature against trochanterionheight", err, errlen) < 0)
		return -1;
	/* Hara et al. with this leg's length */
	double ll = (D->y_hip - D->y_ankle + 0.009) / (1 - 0.078);
	D->hx = 0.008 + 0.086 * ll;
	return 0;
}

/* sqrt(l^2 - h^2): the vertical part of a length l between points h apart sideways */
static int
drop(double l, double h, const char *name, double *dest, char *err, size_t errlen)
{
	if (l <= h)
		return refuse(err, errlen, "human: %s %.0f mm is shorter than its landmarks' %.0f mm "
			      "sideways offset", name, l * 1000, h * 1000);
	*dest = sqrt(l * l - h * h);
	return 0;
}

/* the arm's points along its length (heights) and its shoulder's breadth */
struct arm {
	double acromion_y, radiale_upper, radiale, wrist, tip;
	double acromion_x, gh_x, overhang;
};

/*
 * The arm hanging from the acromion and the shoulders' breadth; of the
 * acromion-to-wrist set and of span and biacromial breadth at most one
 * measure is NAN: the one that follows from the others.
 */
static int
arm_solve(const struct human_layout *L, double overhang, struct arm *a, char *err, size_t errlen)
{
	const struct human_lm_fractions *F = fractions(L);
	double H = L->H, rx = RADIALE_X * H, sz = F->stylion_z * H, a_y = F->acromion_y * H;
	double vAR = NAN, vRS = NAN, vSD = 0;
	if ((!isnan(M(L, ACROMIONRADIALELENGTH)) &&
	     drop(M(L, ACROMIONRADIALELENGTH), fabs(overhang - rx), "acromionradialelength", &vAR,
		  err, errlen) < 0) ||
	    (!isnan(M(L, RADIALESTYLIONLENGTH)) &&
	     drop(M(L, RADIALESTYLIONLENGTH), hypot(rx, sz), "radialestylionlength", &vRS, err,
		  errlen) < 0) ||
	    drop(M(L, HANDLENGTH), sz, "handlength", &vSD, err, errlen) < 0)
		return -1;
	double A = M(L, ACROMIALHEIGHT), W = M(L, WRISTHEIGHT);
	if (isnan(A))
		A = W + vRS + vAR;
	if (isnan(W)) {
		a->radiale_upper = a->radiale = A - vAR;
		W = a->radiale - vRS;
	} else if (isnan(vAR)) {
		a->radiale_upper = a->radiale = W + vRS;
	} else if (isnan(vRS)) {
		a->radiale_upper = a->radiale = A - vAR;
	} else {
		a->radiale_upper = A - vAR;
		a->radiale = W + vRS;
	}
	a->acromion_y = A;
	a->wrist = W;
	a->tip = W - vSD;
	/* span: the dactylions of arms held out sideways, each an arm's length outside its shoulder */
	double arm = A - a_y - a->tip;
	if (isnan(M(L, SPAN))) {
		a->overhang = F->acromion_x * H;
		a->acromion_x = M(L, BIACROMIALBREADTH) / 2;
		a->gh_x = a->acromion_x - a->overhang;
	} else if (isnan(M(L, BIACROMIALBREADTH))) {
		a->overhang = F->acromion_x * H;
		a->gh_x = M(L, SPAN) / 2 - arm;
		a->acromion_x = a->gh_x + a->overhang;
	} else {
		a->gh_x = M(L, SPAN) / 2 - arm;
		a->acromion_x = M(L, BIACROMIALBREADTH) / 2;
		a->overhang = a->acromion_x - a->gh_x;
	}
	return 0;
}

static int
arm_dims(struct human_layout *L, char *err, size_t errlen)
{
	struct human_dims *D = &L->dim;
	const struct human_lm_fractions *F = fractions(L);
	double H = L->H;
	struct arm a;
	/* the overhang changes the acromion-radiale length's slant a little: iterate to a fixed point */
	double overhang = F->acromion_x * H;
	for (int it = 0; it < 20; it++) {
		if (arm_solve(L, overhang, &a, err, errlen) < 0)
			return -1;
		if (within(a.overhang, OVERHANG_LO, OVERHANG_HI, H,
			   "the acromion outside the shoulder joint",
			   "span against biacromialbreadth and the arm", err, errlen) < 0 ||
		    within(a.gh_x, 0.035, 0.2, H, "the shoulder joints from the midline",
			   "biacromialbreadth or span against the arm", err, errlen) < 0)
			return -1;
		int done = fabs(a.overhang - overhang) < 1e-12;
		overhang = a.overhang;
		if (done)
			break;
	}
	double gh_y = a.acromion_y - F->acromion_y * H, elbow = (a.radiale_upper + a.radiale) / 2;
	if (within(gh_y - c7_height(L), -0.2, 0, H, "the shoulder joints (against C7/T1)",
		   "acromialheight against stature", err, errlen) < 0 ||
	    within(a.radiale_upper - a.radiale, RADIALE_GAP_LO, RADIALE_GAP_HI, H,
		   "the gap between the two radiales",
		   "acromialheight - wristheight against acromionradialelength + radialestylionlength",
		   err, errlen) < 0 ||
	    within(gh_y - elbow, 0.09, 0.23, H, "the upper arm",
		   "acromionradialelength", err, errlen) < 0 ||
	    within(elbow - a.wrist, 0.09, 0.23, H, "the forearm",
		   "radialestylionlength", err, errlen) < 0 ||
	    within(a.wrist - a.tip, 0.06, 0.16, H, "the hand", "handlength", err, errlen) < 0)
		return -1;
	D->gh_x = a.gh_x;
	D->gh_y = gh_y;
	D->y_elbow = elbow;
	D->y_wrist = a.wrist;
	D->y_tip = a.tip;
	vset(D->acromion, a.acromion_x, a.acromion_y, 0);
	D->radiale_upper_y = a.radiale_upper;
	D->radiale_y = a.radiale;
	/* de Leva's hand segment (to the third metacarpale) in proportion to the whole hand */
	D->hand_len = L->dl->seg[HUMAN_DL_HAND].len * L->k * (a.wrist - a.tip) /
		      ((human_dc_wrist - human_dc_fingertip) * H);
	return 0;
}

/* the seat's depth below the hip joint centres: sittingheight's, or the ANSUR mean */
static double
seat_depth(const struct human_layout *L)
{
	return L->dim.measured && !isnan(M(L, SITTINGHEIGHT))
		       ? M(L, SITTINGHEIGHT) - (L->H - L->dim.y_hip)
		       : fractions(L)->seat * L->H;
}

static const double *
ratios(const struct human_layout *L)
{
	return L->dl == &human_dl_female ? ratio_female : ratio_male;
}

/* measure k not given: the mean ratio's value */
static void
fill(struct human_layout *L, int k)
{
	if (isnan(L->dim.v[k]))
		L->dim.v[k] = ratios(L)[k] * L->H;
}

int
human_dims_measured(const struct human_def *d, struct human_layout *L, char *err, size_t errlen)
{
	if (check_given(d, err, errlen) < 0)
		return -1;
	struct human_dims *D = &L->dim;
	double H = L->H;
	D->measured = 1;
	for (int k = 0; k < HUMAN_MEASURE_N; k++)
		D->v[k] = (d->measure_given >> k & 1u) ? d->measure[k] / 1000 : NAN;
	D->v[HUMAN_M_STATURE] = H;
	D->v[HUMAN_M_WEIGHTKG] = d->mass;
	static const int plain[] = { HUMAN_M_LATERALMALLEOLUSHEIGHT, HUMAN_M_KNEEHEIGHTMIDPATELLA,
				     HUMAN_M_TROCHANTERIONHEIGHT, HUMAN_M_HANDLENGTH,
				     HUMAN_M_FOOTLENGTH };
	for (size_t i = 0; i < sizeof plain / sizeof *plain; i++)
		fill(L, plain[i]);
	/* the arm: the first of these not given follows, the others take their means */
	static const int arm[] = { HUMAN_M_WRISTHEIGHT, HUMAN_M_RADIALESTYLIONLENGTH,
				   HUMAN_M_ACROMIONRADIALELENGTH, HUMAN_M_ACROMIALHEIGHT };
	int follows = -1;
	for (int i = 0; i < 4; i++) {
		if (!isnan(D->v[arm[i]]))
			continue;
		if (follows < 0)
			follows = arm[i];
		else
			fill(L, arm[i]);
	}
	/* span follows biacromialbreadth, or biacromialbreadth span */
	if (isnan(D->v[HUMAN_M_SPAN]))
		fill(L, HUMAN_M_BIACROMIALBREADTH);
	if (leg_heights(L, err, errlen) < 0 || arm_dims(L, err, errlen) < 0)
		return -1;
	D->lf = M(L, FOOTLENGTH);
	if (isnan(M(L, EYEHEIGHTSITTING))) /* the eyes the mean depth below the vertex */
		D->y_eye = H - (ratios(L)[HUMAN_M_SITTINGHEIGHT] - ratios(L)[HUMAN_M_EYEHEIGHTSITTING]) * H;
	else
		D->y_eye = D->y_hip - seat_depth(L) + M(L, EYEHEIGHTSITTING);
	if (within(D->lf, 0.10, 0.21, H, "the foot", "footlength", err, errlen) < 0 ||
	    within(H - D->y_eye, 0.03, 0.11, H, "the eyes below the vertex",
		   "eyeheightsitting against sittingheight", err, errlen) < 0)
		return -1;
	return 0;
}

int
human_landmarks_place(struct human_layout *L, char *err, size_t errlen)
{
	const struct human_dims *D = &L->dim;
	const struct human_lm_fractions *F = fractions(L);
	double H = L->H, y_a = L->ankle[1];
	/* seated, the shank hangs straight below the knee and the foot is flat */
	double shank = hypot(L->knee[1] - L->ankle[1], L->knee[2] - L->ankle[2]);
	/* what a measure given sets; the ANSUR mean where none is */
#define SET(x) (D->measured && !isnan(M(L, x)))
	double seat = seat_depth(L);
	double supra = SET(KNEEHEIGHTSITTING) ? M(L, KNEEHEIGHTSITTING) - shank - y_a
					      : F->suprapatella * H;
	double popl = SET(POPLITEALHEIGHT) ? shank + y_a - M(L, POPLITEALHEIGHT) : F->popliteal * H;
	double butt = SET(BUTTOCKKNEELENGTH) ? M(L, BUTTOCKKNEELENGTH) - (L->hip[1] - L->knee[1]) - supra
					     : F->buttock * H;
	double sz = F->stylion_z * H, hand = hypot(L->wrist[1] - L->fingertip[1], sz);
	double thumb_y = L->wrist[1] - PINCH * hand;
	double blade = SET(THUMBTIPREACH) ? M(L, THUMBTIPREACH) - (L->gh[1] - thumb_y)
					  : F->shoulder_blade * H;
	double troch = SET(HIPBREADTH) ? M(L, HIPBREADTH) / 2 : F->trochanterion_x * H;
#undef SET
	if (within(seat, SEAT_LO, SEAT_HI, H, "the seat below the hip joint centres",
		   "sittingheight against stature and trochanterionheight", err, errlen) < 0 ||
	    within(supra, KNEE_DEPTH_LO, SUPRAPATELLA_HI, H, "the top of the knee above its axis, seated",
		   "kneeheightsitting against the leg's heights", err, errlen) < 0 ||
	    within(popl, KNEE_DEPTH_LO, POPLITEAL_HI, H, "the popliteal below the knee's axis, seated",
		   "poplitealheight against the leg's heights", err, errlen) < 0 ||
	    within(butt, BUTTOCK_LO, BUTTOCK_HI, H, "the buttocks behind the hip joint centres",
		   "buttockkneelength against the thigh and kneeheightsitting", err, errlen) < 0 ||
	    within(blade, BLADE_LO, BLADE_HI, H, "the shoulder blades behind the shoulder joints",
		   "thumbtipreach against the arm", err, errlen) < 0 ||
	    within(troch - D->hx, 0.005, 0.15, H, "the trochanterion outside the hip joint centre",
		   "hipbreadth", err, errlen) < 0)
		return -1;

	double(*lm)[3] = L->lm;
	const double *gh = L->gh, *knee = L->knee, *hip = L->hip;
	double hx = D->hx, top = c7_height(L), hw, hd;
	vset(lm[HUMAN_LM_ACROMION], D->acromion[0], D->acromion[1], D->acromion[2]);
	vset(lm[HUMAN_LM_SHOULDER_BLADE], gh[0] - 0.05 * H, gh[1] - 0.04 * H, gh[2] - blade);
	vset(lm[HUMAN_LM_RADIALE_UPPER], gh[0] + RADIALE_X * H, D->radiale_upper_y, 0);
	vset(lm[HUMAN_LM_RADIALE], gh[0] + RADIALE_X * H, D->radiale_y, 0);
	vset(lm[HUMAN_LM_STYLION], gh[0], L->wrist[1], sz);
	vset(lm[HUMAN_LM_DACTYLION], gh[0], L->fingertip[1], 0);
	vset(lm[HUMAN_LM_THUMBTIP], gh[0], thumb_y, sz + THUMB_Z * H);
	vset(lm[HUMAN_LM_TROCHANTERION], troch, hip[1], 0);
	vset(lm[HUMAN_LM_FEMORAL_EPICONDYLE], hx + EPICONDYLE_X * H, knee[1], 0);
	vset(lm[HUMAN_LM_MIDPATELLA], hx, knee[1] + F->midpatella_y * H, supra);
	vset(lm[HUMAN_LM_SUPRAPATELLA], hx, knee[1] + SUPRAPATELLA_Y * H, supra);
	/* the knee's front when it is bent square: on the thigh's axis, as far from the knee's as the top */
	vset(lm[HUMAN_LM_KNEE_FRONT], hx, knee[1] - supra, 0);
	vset(lm[HUMAN_LM_POPLITEAL], hx, knee[1], -popl);
	vset(lm[HUMAN_LM_TIBIALE], hx - TIBIALE_X * H, knee[1] + F->tibiale_y * H, 0);
	vset(lm[HUMAN_LM_LATERAL_MALLEOLUS], hx + F->malleolus_x * H, y_a, L->ankle[2]);
	vset(lm[HUMAN_LM_PTERNION], hx, 0.02 * H, L->heel[2]);
	vset(lm[HUMAN_LM_ACROPODION], hx, 0.008 * H, L->tip[2]);
	vset(lm[HUMAN_LM_ILIOCRISTALE], F->iliocristale_x * H, hip[1] + F->iliocristale_y * H, 0);
	vset(lm[HUMAN_LM_ISCHIAL_TUBEROSITY], 0.03 * H, hip[1] - seat, -0.03 * H);
	vset(lm[HUMAN_LM_BUTTOCK], 0.045 * H, hip[1] - 0.03 * H, -butt);
	vset(lm[HUMAN_LM_TRAGION], F->tragion_x * H, H - F->tragion_y * H, L->head_c[2] - 0.01 * H);
	vset(lm[HUMAN_LM_ECTOCANTHUS], L->eye[0] + L->eye_r, L->eye[1], L->eye[2] - 0.5 * L->eye_r);
	vset(lm[HUMAN_LM_SELLION], 0, L->eye[1], L->head_c[2] + L->head_semi[2]);
	vset(lm[HUMAN_LM_CERVICALE], 0, top, L->spine[HUMAN_NSLICE][2] - 0.035 * H);
	human_torso_semi(L, L->y_supr, &hw, &hd);
	vset(lm[HUMAN_LM_SUPRASTERNALE], 0, L->y_supr, hd);
	return 0;
}
