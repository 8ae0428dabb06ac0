/* niosh_measure.c - H, V and A of a lift measured on a human (niosh_measure.h) */
#include "assess/niosh_measure.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "figure/mathx.h"

static int
fail(char *err, size_t errlen, const char *name)
{
	if (err && errlen)
		snprintf(err, errlen, "niosh: the figure has no '%s' (only a human figure is measured)",
			 name);
	return -1;
}

int
niosh_measure(const struct model *m, const struct state *s, struct niosh_geometry *dest,
	      char *err, size_t errlen)
{
	static const char *const foot[2] = { "foot_l", "foot_r" };
	static const char *const malleolus[2] = { "shank_l.lateral_malleolus",
						  "shank_r.lateral_malleolus" };
	static const char *const palm[2] = { "hand_l.palm", "hand_r.palm" };
	struct niosh_geometry g;
	memset(&g, 0, sizeof g);
	double fwd[3] = { 0, 0, 0 };
	for (int side = 0; side < 2; side++) {
		int f = model_find_segment(m, foot[side]);
		int lm = model_find_site(m, malleolus[side]), p = model_find_site(m, palm[side]);
		if (f < 0)
			return fail(err, errlen, foot[side]);
		if (lm < 0)
			return fail(err, errlen, malleolus[side]);
		if (p < 0)
			return fail(err, errlen, palm[side]);
		/* the medial malleolus: the lateral one reflected through the ankle joint centre */
		const double *ankle = s->seg_xf[f].p, *lat = s->site_xf[lm].p;
		for (int i = 0; i < 3; i++) {
			g.ankles_mid[i] += (2 * ankle[i] - lat[i]) / 2;
			g.hands_mid[i] += s->site_xf[p].p[i] / 2;
		}
		/* the foot's heel-to-toe direction (its frame's z) on the floor, as a unit */
		double z[3] = { s->seg_xf[f].r[2], 0, s->seg_xf[f].r[8] };
		double n = sqrt(mathx_dot(z, z));
		if (n > 1e-9)
			for (int i = 0; i < 3; i += 2)
				fwd[i] += z[i] / n;
	}
	double n = sqrt(mathx_dot(fwd, fwd));
	if (n < 1e-9) {
		/* feet pointing opposite ways (no human ankle turns so far): across the ankles' line */
		const double *l = s->seg_xf[model_find_segment(m, foot[0])].p;
		const double *r = s->seg_xf[model_find_segment(m, foot[1])].p;
		fwd[0] = -(l[2] - r[2]), fwd[2] = l[0] - r[0];
		n = sqrt(mathx_dot(fwd, fwd));
	}
	if (n < 1e-12) {
		if (err && errlen)
			snprintf(err, errlen, "niosh: the feet give no mid-sagittal line");
		return -1;
	}
	for (int i = 0; i < 3; i += 2)
		g.forward[i] = fwd[i] / n;

	double d[3] = { g.hands_mid[0] - g.ankles_mid[0], 0, g.hands_mid[2] - g.ankles_mid[2] };
	double h = sqrt(mathx_dot(d, d));
	g.h_cm = 100 * h;
	g.v_cm = 100 * g.hands_mid[1];
	g.h_in = g.h_cm / NIOSH_CM_PER_IN;
	g.v_in = g.v_cm / NIOSH_CM_PER_IN;
	/* A: the angle on the floor between the asymmetry line and the mid-sagittal line */
	double along = mathx_dot(d, g.forward);
	double across = d[0] * g.forward[2] - d[2] * g.forward[0];
	g.a_deg = h > 1e-9 ? atan2(fabs(across), along) * 180 / M_PI : 0;
	*dest = g;
	return 0;
}

double
niosh_travel_cm(const struct niosh_geometry *origin, const struct niosh_geometry *dest)
{
	return fabs(dest->v_cm - origin->v_cm);
}
