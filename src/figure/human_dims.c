/*
 * human_dims.c - where the human's joint centres go when ANSUR II measures
 * are given (measures.h), so that pose/anthropometry.c measures them back,
 * and the landmark offsets (human_data.c places the landmarks; today's
 * figure, with no measures, keeps the stature fractions of human.c's
 * sources).
 *
 * Landmarks (sites by translation, left side; the right is mirrored) sit
 * at fixed offsets from the joint centres; the offsets are ANSUR II means
 * (fractions of stature, per sex; tools/ansur2_landmarks.py derives them
 * from data/ansur2), de Leva (1996), or assumptions (human_dims.h). With
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
#include "figure/human_dims.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static const struct human_lm_fractions lm_male = {
	0.0291, 0.0160, 0.0195, 0.0359, -0.0019, 0.0356, 0.0352, 0.0833,
	0.0876, 0.0985, -0.0134, 0.0915, 0.0784, 0.0213, 0.0748, 0.0440,
};

static const struct human_lm_fractions lm_female = {
	0.0325, 0.0151, 0.0123, 0.0452, -0.0104, 0.0278, 0.0477, 0.1019,
	0.0906, 0.1087, -0.0173, 0.0923, 0.0839, 0.0206, 0.0778, 0.0454,
};

const struct human_lm_fractions *
human_lm_fractions(int female)
{
	return female ? &lm_female : &lm_male;
}

/* each measure's ANSUR II mean ratio to stature (tools/ansur2_landmarks.py), measures.h's order */
static const double ratio_male[HUMAN_MEASURE_N] = {
	1.00000, 0.82026, 0.48252, 0.51285, 0.27799, 0.04152, 0.52306, 0.45823, 0.19087, 0.15252,
	0.11007, 0.15444, 0.35186, 0.31547, 0.24464, 0.23682, 0.19696, 1.03302, 0.46235, 0,
};

static const double ratio_female[HUMAN_MEASURE_N] = {
	1.00000, 0.81975, 0.48766, 0.51898, 0.27565, 0.03854, 0.52624, 0.45931, 0.19107, 0.14817,
	0.11121, 0.15126, 0.36264, 0.31388, 0.23829, 0.22445, 0.21737, 1.01947, 0.45689, 0,
};

static const char *const measure_name[HUMAN_MEASURE_N] = {
#define HUMAN_MEASURE_NAME(e, s) s,
	HUMAN_MEASURES(HUMAN_MEASURE_NAME)
#undef HUMAN_MEASURE_NAME
};

/* a measure of the figure built from measures (m) */
#define M(D, x) ((D)->v[HUMAN_M_##x])

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

int
human_dims_within(double v, double lo, double hi, double H, const char *what, const char *from,
		  char *err, size_t errlen)
{
	if (v >= lo * H && v <= hi * H)
		return 0;
	return refuse(err, errlen,
		      "human: the measures put %s at %.0f mm (%s); the body allows %.0f to %.0f mm",
		      what, v * 1000, from, lo * H * 1000, hi * H * 1000);
}

#define within human_dims_within

double
human_trunk_map(const struct human_dims *D, double c7, double y)
{
	return D->y_hip + (y - D->trunk_from) * (c7 - D->y_hip) / (c7 - D->trunk_from);
}

double
human_trunk_unmap(const struct human_dims *D, double c7, double y)
{
	return D->trunk_from + (y - D->y_hip) * (c7 - D->trunk_from) / (c7 - D->y_hip);
}

double
human_seat_depth(const struct human_dims *D, double H, int female)
{
	return D->measured && !isnan(M(D, SITTINGHEIGHT)) ? M(D, SITTINGHEIGHT) - (H - D->y_hip)
							  : human_lm_fractions(female)->seat * H;
}

static const double *
ratios(int female)
{
	return female ? ratio_female : ratio_male;
}

static int
check_given(const struct human_dims_in *in, char *err, size_t errlen)
{
	if (in->given >> HUMAN_MEASURE_N)
		return refuse(err, errlen, "human: unknown measures given (bits %#x)", in->given);
	for (int i = 0; i < HUMAN_MEASURE_N; i++) {
		double v = in->measure[i];
		if ((in->given >> i & 1u) && !(v > 0 && isfinite(v)))
			return refuse(err, errlen, "human: %s must be a positive number of %s, not %g",
				      measure_name[i], i == HUMAN_M_WEIGHTKG ? "kg" : "mm", v);
	}
	if ((in->given >> HUMAN_M_STATURE & 1u) &&
	    fabs(in->measure[HUMAN_M_STATURE] / 1000 - in->H) > 0.0005)
		return refuse(err, errlen, "human: stature %g m and stature=%g mm disagree", in->H,
			      in->measure[HUMAN_M_STATURE]);
	if ((in->given >> HUMAN_M_WEIGHTKG & 1u) &&
	    fabs(in->measure[HUMAN_M_WEIGHTKG] - in->mass) > 1e-9 * in->mass)
		return refuse(err, errlen, "human: mass %g kg and weightkg=%g disagree", in->mass,
			      in->measure[HUMAN_M_WEIGHTKG]);
	return 0;
}

/* the legs' joint heights */
static int
leg_heights(const struct human_dims_in *in, struct human_dims *D, char *err, size_t errlen)
{
	double H = in->H;
	D->y_ankle = M(D, LATERALMALLEOLUSHEIGHT);
	D->y_knee = M(D, KNEEHEIGHTMIDPATELLA) - human_lm_fractions(in->female)->midpatella_y * H;
	D->y_hip = M(D, TROCHANTERIONHEIGHT);
	if (within(D->y_ankle, 0.015, 0.08, H, "the ankle joint centre", "lateralmalleolusheight",
		   err, errlen) < 0 ||
	    within(D->y_knee - D->y_ankle, 0.15, 0.34, H, "the shank",
		   "kneeheightmidpatella against lateralmalleolusheight", err, errlen) < 0 ||
	    within(D->y_hip - D->y_knee, 0.13, 0.34, H, "the thigh",
		   "trochanterionheight against kneeheightmidpatella", err, errlen) < 0 ||
	    within(in->c7 - D->y_hip, 0.2, 0.5, H, "the trunk from the hips to C7/T1",
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
arm_solve(const struct human_dims_in *in, const struct human_dims *D, double overhang,
	  struct arm *a, char *err, size_t errlen)
{
	const struct human_lm_fractions *F = human_lm_fractions(in->female);
	double H = in->H, rx = HUMAN_LM_RADIALE_X * H, sz = F->stylion_z * H, a_y = F->acromion_y * H;
	double vAR = NAN, vRS = NAN, vSD = 0;
	if ((!isnan(M(D, ACROMIONRADIALELENGTH)) &&
	     drop(M(D, ACROMIONRADIALELENGTH), fabs(overhang - rx), "acromionradialelength", &vAR,
		  err, errlen) < 0) ||
	    (!isnan(M(D, RADIALESTYLIONLENGTH)) &&
	     drop(M(D, RADIALESTYLIONLENGTH), hypot(rx, sz), "radialestylionlength", &vRS, err,
		  errlen) < 0) ||
	    drop(M(D, HANDLENGTH), sz, "handlength", &vSD, err, errlen) < 0)
		return -1;
	double A = M(D, ACROMIALHEIGHT), W = M(D, WRISTHEIGHT);
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
	if (isnan(M(D, SPAN))) {
		a->overhang = F->acromion_x * H;
		a->acromion_x = M(D, BIACROMIALBREADTH) / 2;
		a->gh_x = a->acromion_x - a->overhang;
	} else if (isnan(M(D, BIACROMIALBREADTH))) {
		a->overhang = F->acromion_x * H;
		a->gh_x = M(D, SPAN) / 2 - arm;
		a->acromion_x = a->gh_x + a->overhang;
	} else {
		a->gh_x = M(D, SPAN) / 2 - arm;
		a->acromion_x = M(D, BIACROMIALBREADTH) / 2;
		a->overhang = a->acromion_x - a->gh_x;
	}
	return 0;
}

static int
arm_dims(const struct human_dims_in *in, struct human_dims *D, char *err, size_t errlen)
{
	const struct human_lm_fractions *F = human_lm_fractions(in->female);
	double H = in->H;
	struct arm a;
	/* the overhang changes the acromion-radiale length's slant a little: iterate to a fixed point */
	double overhang = F->acromion_x * H;
	for (int it = 0; it < 20; it++) {
		if (arm_solve(in, D, overhang, &a, err, errlen) < 0)
			return -1;
		if (within(a.overhang, HUMAN_LM_OVERHANG_LO, HUMAN_LM_OVERHANG_HI, H,
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
	if (within(gh_y - in->c7, -0.2, 0, H, "the shoulder joints (against C7/T1)",
		   "acromialheight against stature", err, errlen) < 0 ||
	    within(a.radiale_upper - a.radiale, HUMAN_LM_RADIALE_GAP_LO, HUMAN_LM_RADIALE_GAP_HI, H,
		   "the gap between the two radiales",
		   "acromialheight - wristheight against acromionradialelength + radialestylionlength",
		   err, errlen) < 0 ||
	    within(gh_y - elbow, 0.09, 0.23, H, "the upper arm", "acromionradialelength", err,
		   errlen) < 0 ||
	    within(elbow - a.wrist, 0.09, 0.23, H, "the forearm", "radialestylionlength", err,
		   errlen) < 0 ||
	    within(a.wrist - a.tip, 0.06, 0.16, H, "the hand", "handlength", err, errlen) < 0)
		return -1;
	/* de Leva's hand segment (to the third metacarpale) in proportion to the whole hand */
	D->hand_len *= (a.wrist - a.tip) / (D->y_wrist - D->y_tip);
	D->gh_x = a.gh_x;
	D->gh_y = gh_y;
	D->y_elbow = elbow;
	D->y_wrist = a.wrist;
	D->y_tip = a.tip;
	D->acromion[0] = a.acromion_x;
	D->acromion[1] = a.acromion_y;
	D->acromion[2] = 0;
	D->radiale_upper_y = a.radiale_upper;
	D->radiale_y = a.radiale;
	return 0;
}

/* measure k not given: the mean ratio's value */
static void
fill(const struct human_dims_in *in, struct human_dims *D, int k)
{
	if (isnan(D->v[k]))
		D->v[k] = ratios(in->female)[k] * in->H;
}

int
human_dims_measured(const struct human_dims_in *in, struct human_dims *D, char *err, size_t errlen)
{
	if (check_given(in, err, errlen) < 0)
		return -1;
	double H = in->H;
	D->measured = 1;
	for (int k = 0; k < HUMAN_MEASURE_N; k++)
		D->v[k] = (in->given >> k & 1u) ? in->measure[k] / 1000 : NAN;
	D->v[HUMAN_M_STATURE] = H;
	D->v[HUMAN_M_WEIGHTKG] = in->mass;
	static const int plain[] = { HUMAN_M_LATERALMALLEOLUSHEIGHT, HUMAN_M_KNEEHEIGHTMIDPATELLA,
				     HUMAN_M_TROCHANTERIONHEIGHT, HUMAN_M_HANDLENGTH,
				     HUMAN_M_FOOTLENGTH };
	for (size_t i = 0; i < sizeof plain / sizeof *plain; i++)
		fill(in, D, plain[i]);
	/* the arm: the first of these not given follows, the others take their means */
	static const int arm[] = { HUMAN_M_WRISTHEIGHT, HUMAN_M_RADIALESTYLIONLENGTH,
				   HUMAN_M_ACROMIONRADIALELENGTH, HUMAN_M_ACROMIALHEIGHT };
	int follows = 0;
	for (int i = 0; i < 4; i++) {
		if (!isnan(D->v[arm[i]]))
			continue;
		if (follows++)
			fill(in, D, arm[i]);
	}
	/* span follows biacromialbreadth, or biacromialbreadth span */
	if (isnan(D->v[HUMAN_M_SPAN]))
		fill(in, D, HUMAN_M_BIACROMIALBREADTH);
	if (leg_heights(in, D, err, errlen) < 0 || arm_dims(in, D, err, errlen) < 0)
		return -1;
	D->lf = M(D, FOOTLENGTH);
	if (isnan(M(D, EYEHEIGHTSITTING))) /* the eyes the mean depth below the vertex */
		D->y_eye = H - (ratios(in->female)[HUMAN_M_SITTINGHEIGHT] -
				ratios(in->female)[HUMAN_M_EYEHEIGHTSITTING]) * H;
	else
		D->y_eye = D->y_hip - human_seat_depth(D, H, in->female) + M(D, EYEHEIGHTSITTING);
	if (within(D->lf, 0.10, 0.21, H, "the foot", "footlength", err, errlen) < 0 ||
	    within(H - D->y_eye, 0.03, 0.11, H, "the eyes below the vertex",
		   "eyeheightsitting against sittingheight", err, errlen) < 0)
		return -1;
	return 0;
}
