/*
 * lowback.c - Chaffin's single-equivalent-muscle sagittal model of the
 * L5/S1 disc (Chaffin, Andersson & Martin, Occupational Biomechanics,
 * ch. 6, the "simple" static sagittal low-back model), derivation in
 * lowback.h.
 *
 * Its one constant, the equivalent extensor's moment arm E = 5 cm behind
 * the disc centre, is the textbook's value as the project's research notes
 * record it (human-factors §5.2); the textbook's page was not seen, so the
 * value is marked unconfirmed there and in docs/loads.md. A lifting-lab
 * report that applies the same model (freeonlineresearchpapers.com,
 * "Ergonomics Lifting Lab") divides its L4/L5 moments by the same arm
 * (250.3 N m -> 5006 N; 273.4 N m -> 5470.2 N). Other authors use about
 * 6 cm, and van Dieen & de Looze give E as a regression on trunk flexion
 * (used by the planar model of Appl. Sci. 10(19):6700, 2020); their
 * coefficients were not retrieved, so lowback_compute_arm takes another E.
 *
 * Left out, each for want of a sourced constant:
 * - the abdominal pressure's relief (Chaffin's regression of the pressure
 *   on the hip and trunk angles and the moment, the diaphragm's area and
 *   the force's moment arm): without it the compression is the higher
 *   (conservative) figure;
 * - the disc's inclination by regression on the trunk and knee angles
 *   (Anderson, Chaffin, Herrin & Matthews 1985, as 3DSSPP uses it): the
 *   caller gives the figure's own disc normal instead;
 * - the extensor's line of action other than along the disc normal, and
 *   the flexors' moment arm (LOWBACK_FLEXOR_UNMODELLED);
 * - lateral bending and twisting moments (reported, not turned into force).
 */
#include <math.h>
#include <stdio.h>

#include "assess/lowback.h"

/* E, m: Chaffin et al. ch. 6 via research human-factors §5.2 (unconfirmed) */
static const double extensor_arm_m = 0.05;

const char *const lowback_unmodelled[] = { "abdominal_pressure", "disc_angle_regression",
					    "lateral_and_axial_moments" };
const int lowback_nunmodelled = sizeof lowback_unmodelled / sizeof lowback_unmodelled[0];

double
lowback_moment_arm(void)
{
	return extensor_arm_m;
}

const char *
lowback_zone_name(enum lowback_zone z)
{
	switch (z) {
	case LOWBACK_BELOW_ACTION:
		return "below_action";
	case LOWBACK_ABOVE_ACTION:
		return "above_action";
	case LOWBACK_ABOVE_MAX:
		return "above_max";
	}
	return "?";
}

static double
dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static int
finite3(const double v[3])
{
	return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

int
lowback_compute_arm(const struct lowback_input *in, double e_m, struct lowback_result *dest,
		    char *err, size_t errlen)
{
	if (!finite3(in->load_force) || !finite3(in->load_moment) || !finite3(in->disc_normal) ||
	    !finite3(in->anterior)) {
		snprintf(err, errlen, "low back: a load or direction is not finite");
		return -1;
	}
	if (!(isfinite(e_m) && e_m > 0)) {
		snprintf(err, errlen, "low back: the extensor's moment arm must be > 0 m");
		return -1;
	}
	const double *n = in->disc_normal;
	if (fabs(dot(n, n) - 1) > 1e-6) {
		snprintf(err, errlen, "low back: the disc normal is not a unit vector");
		return -1;
	}
	/* a: the forward direction's part in the disc plane */
	double k = dot(in->anterior, n);
	double a[3] = { in->anterior[0] - k * n[0], in->anterior[1] - k * n[1],
			in->anterior[2] - k * n[2] };
	double alen = sqrt(dot(a, a));
	if (!(alen > 1e-9 * sqrt(dot(in->anterior, in->anterior)))) {
		snprintf(err, errlen, "low back: the forward direction lies along the disc normal");
		return -1;
	}
	for (int i = 0; i < 3; i++)
		a[i] /= alen;
	double l[3] = { n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2],
			n[0] * a[1] - n[1] * a[0] };

	struct lowback_result r = { 0 };
	r.level = "L5/S1";
	r.model = "chaffin-sagittal";
	r.moment_arm = e_m;
	r.moment_sagittal = dot(in->load_moment, l);
	r.moment_lateral = dot(in->load_moment, a);
	r.moment_axial = dot(in->load_moment, n);
	if (r.moment_sagittal >= 0) {
		r.muscle_force = r.moment_sagittal / e_m;
	} else {
		r.muscle_force = 0;
		r.flags |= LOWBACK_FLEXOR_UNMODELLED;
	}
	r.compression = r.muscle_force - dot(in->load_force, n);
	r.shear_ap = dot(in->load_force, a);
	r.shear_lat = dot(in->load_force, l);
	r.action_limit = LOWBACK_ACTION_LIMIT;
	r.max_limit = LOWBACK_MAX_LIMIT;
	r.zone = r.compression > LOWBACK_MAX_LIMIT      ? LOWBACK_ABOVE_MAX
		 : r.compression > LOWBACK_ACTION_LIMIT ? LOWBACK_ABOVE_ACTION
							: LOWBACK_BELOW_ACTION;
	*dest = r;
	return 0;
}

int
lowback_compute(const struct lowback_input *in, struct lowback_result *dest, char *err,
		size_t errlen)
{
	return lowback_compute_arm(in, extensor_arm_m, dest, err, errlen);
}
