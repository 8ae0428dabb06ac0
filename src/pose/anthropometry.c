/* anthropometry.c - a human figure measured in ANSUR II's postures (anthropometry.h) */
#include "pose/anthropometry.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "figure/kin.h"
#include "figure/state.h"

static const char *const names[HUMAN_MEASURE_N] = {
#define ANTHRO_NAME(e, s) s,
	HUMAN_MEASURES(ANTHRO_NAME)
#undef ANTHRO_NAME
};

const char *
anthro_name(enum human_measure i)
{
	return (unsigned)i < HUMAN_MEASURE_N ? names[i] : NULL;
}

int
anthro_find(const char *name)
{
	for (int i = 0; i < HUMAN_MEASURE_N; i++)
		if (!strcmp(names[i], name))
			return i;
	return -1;
}

/* the sites and joints measured; _l and _r where both sides are needed */
enum {
	S_VERTEX,
	S_HEEL_R,
	S_TOETIP_R,
	S_ACROMION_L,
	S_ACROMION_R,
	S_RADIALE_UPPER_R,
	S_RADIALE_R,
	S_STYLION_R,
	S_DACTYLION_L,
	S_DACTYLION_R,
	S_THUMBTIP_R,
	S_BLADE_L,
	S_BLADE_R,
	S_TROCH_L,
	S_TROCH_R,
	S_MIDPATELLA_R,
	S_SUPRAPATELLA_R,
	S_KNEE_FRONT_R,
	S_POPLITEAL_R,
	S_MALLEOLUS_R,
	S_PTERNION_R,
	S_ACROPODION_R,
	S_ISCHIAL_L,
	S_ISCHIAL_R,
	S_BUTTOCK_L,
	S_BUTTOCK_R,
	S_ECTOCANTHUS_R,
	S_HIP_L, /* joint centres: the child segments' origins */
	S_HIP_R,
	S_KNEE_L,
	S_KNEE_R,
	S_ANKLE_L,
	S_ANKLE_R,
	S_SHOULDER_L,
	S_SHOULDER_R,
	S_N,
};

static const char *const site_names[S_N] = {
	"head.vertex",
	"foot_r.heel",
	"toes_r.tip",
	"clavicle_l.acromion",
	"clavicle_r.acromion",
	"upperarm_r.radiale",
	"forearm_r.radiale",
	"forearm_r.stylion",
	"hand_l.dactylion",
	"hand_r.dactylion",
	"hand_r.thumbtip",
	"clavicle_l.shoulder_blade",
	"clavicle_r.shoulder_blade",
	"thigh_l.trochanterion",
	"thigh_r.trochanterion",
	"thigh_r.midpatella",
	"thigh_r.suprapatella",
	"thigh_r.knee_front",
	"thigh_r.popliteal",
	"shank_r.lateral_malleolus",
	"foot_r.pternion",
	"toes_r.acropodion",
	"pelvis.ischial_tuberosity_l",
	"pelvis.ischial_tuberosity_r",
	"pelvis.buttock_l",
	"pelvis.buttock_r",
	"head.ectocanthus_r",
	"thigh_l.origin",
	"thigh_r.origin",
	"shank_l.origin",
	"shank_r.origin",
	"foot_l.origin",
	"foot_r.origin",
	"upperarm_l.origin",
	"upperarm_r.origin",
};

enum { J_HIP, J_KNEE, J_ANKLE, J_SHOULDER, J_N };
static const char *const joint_names[J_N] = { "hip", "knee", "ankle", "shoulder" };

struct anthro {
	const struct model *m;
	struct state *s;
	int site[S_N];
	int dof0[J_N][2]; /* first dof of each joint, left and right */
};

static const double *
at(const struct anthro *a, int k)
{
	return a->s->site_xf[a->site[k]].p;
}

static double
dist(const double *p, const double *q)
{
	return sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
		    (p[2] - q[2]) * (p[2] - q[2]));
}

/* angle in (-pi, pi] */
static double
wrap(double a)
{
	while (a > M_PI)
		a -= 2 * M_PI;
	while (a <= -M_PI)
		a += 2 * M_PI;
	return a;
}

/*
 * The signed rotation a unit of dof d gives about world axis `axis` (0 x,
 * 2 z) in the current posture: its world axis's component along it (the
 * figure's built frames are parallel to the world's, so it is +-1).
 */
static double
turn(const struct anthro *a, int d, int axis)
{
	return a->s->dof_axis_w[3 * d + axis];
}

/*
 * Angle of the vector from p to q about the x axis (in the y-z plane: 0 up,
 * pi/2 forward, pi down) and about the z axis (in the x-y plane: 0 to the
 * left, pi to the right); a rotation by t about +x or +z adds t to it.
 */
static double
pitch(const double *p, const double *q)
{
	return atan2(q[2] - p[2], q[1] - p[1]);
}

static double
roll(const double *p, const double *q)
{
	return atan2(q[1] - p[1], q[0] - p[0]);
}

static void
pose(struct anthro *a)
{
	memset(a->s->q, 0, sizeof *a->s->q * (size_t)a->m->ndof);
}

/* sitting: thighs horizontal forward, shanks vertical, feet as flat as standing */
static void
sit(struct anthro *a)
{
	double *q = a->s->q;
	for (int side = 0; side < 2; side++) {
		int hip = a->dof0[J_HIP][side], knee = a->dof0[J_KNEE][side];
		int ankle = a->dof0[J_ANKLE][side];
		const double *h = at(a, S_HIP_L + side), *k = at(a, S_KNEE_L + side);
		const double *f = at(a, S_ANKLE_L + side);
		double sh = turn(a, hip, 0), sk = turn(a, knee, 0), sa = turn(a, ankle, 0);
		double qh = wrap(M_PI / 2 - pitch(h, k)) / sh;
		double qk = wrap(M_PI - pitch(k, f) - sh * qh) / sk;
		q[hip] = qh;
		q[knee] = qk;
		q[ankle] = -(sh * qh + sk * qk) / sa;
	}
}

int
anthro_measure(const struct model *m, double dest[HUMAN_MEASURE_N], char *err, size_t errlen)
{
	struct anthro a = { .m = m };
	for (int k = 0; k < S_N; k++) {
		if ((a.site[k] = model_find_site(m, site_names[k])) < 0) {
			snprintf(err, errlen, "figure %s has no site %s: only the built-in human has the "
				 "landmarks measured", m->name, site_names[k]);
			return -1;
		}
	}
	for (int j = 0; j < J_N; j++) {
		for (int side = 0; side < 2; side++) {
			char name[32];
			snprintf(name, sizeof name, "%s_%c", joint_names[j], side ? 'r' : 'l');
			int jj = model_find_joint(m, name);
			if (jj < 0 || m->jnt_ndof[jj] < (j == J_SHOULDER ? 2 : 1)) {
				snprintf(err, errlen, "figure %s has no joint %s as the built-in human's",
					 m->name, name);
				return -1;
			}
			a.dof0[j][side] = m->jnt_dof0[jj];
		}
	}
	if (!(a.s = state_make(m))) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	double *v = dest, mm = 1000;

	/* standing erect: the built posture */
	pose(&a);
	kin_update(m, a.s);
	double floor = at(&a, S_HEEL_R)[1];
#define HEIGHT(k) ((at(&a, k)[1] - floor) * mm)
	v[HUMAN_M_STATURE] = HEIGHT(S_VERTEX);
	v[HUMAN_M_ACROMIALHEIGHT] = HEIGHT(S_ACROMION_R);
	v[HUMAN_M_WRISTHEIGHT] = HEIGHT(S_STYLION_R);
	v[HUMAN_M_TROCHANTERIONHEIGHT] = HEIGHT(S_TROCH_R);
	v[HUMAN_M_KNEEHEIGHTMIDPATELLA] = HEIGHT(S_MIDPATELLA_R);
	v[HUMAN_M_LATERALMALLEOLUSHEIGHT] = HEIGHT(S_MALLEOLUS_R);
#undef HEIGHT
	v[HUMAN_M_ACROMIONRADIALELENGTH] = dist(at(&a, S_ACROMION_R), at(&a, S_RADIALE_UPPER_R)) * mm;
	v[HUMAN_M_RADIALESTYLIONLENGTH] = dist(at(&a, S_RADIALE_R), at(&a, S_STYLION_R)) * mm;
	v[HUMAN_M_HANDLENGTH] = dist(at(&a, S_STYLION_R), at(&a, S_DACTYLION_R)) * mm;
	v[HUMAN_M_BIACROMIALBREADTH] = dist(at(&a, S_ACROMION_L), at(&a, S_ACROMION_R)) * mm;
	v[HUMAN_M_HIPBREADTH] = dist(at(&a, S_TROCH_L), at(&a, S_TROCH_R)) * mm;
	/* foot length along the foot's axis: the heel-to-toe-tip direction, level */
	{
		const double *h = at(&a, S_HEEL_R), *t = at(&a, S_TOETIP_R);
		const double *p = at(&a, S_PTERNION_R), *c = at(&a, S_ACROPODION_R);
		double ax = t[0] - h[0], az = t[2] - h[2], n = hypot(ax, az);
		v[HUMAN_M_FOOTLENGTH] = ((c[0] - p[0]) * ax + (c[2] - p[2]) * az) / n * mm;
	}
	v[HUMAN_M_WEIGHTKG] = m->total_mass;

	/* the arms held out sideways and (the right) forward, from the built posture's directions */
	double *q = a.s->q;
	double span_q[2], reach_q;
	for (int side = 0; side < 2; side++) {
		int d = a.dof0[J_SHOULDER][side] + 1; /* abduction, about z */
		double target = side ? M_PI : 0;
		span_q[side] = wrap(target - roll(at(&a, S_SHOULDER_L + side), at(&a, S_DACTYLION_L + side))) /
			       turn(&a, d, 2);
	}
	reach_q = wrap(M_PI / 2 - pitch(at(&a, S_SHOULDER_R), at(&a, S_DACTYLION_R))) /
		  turn(&a, a.dof0[J_SHOULDER][1], 0);

	/* sitting erect */
	sit(&a);
	kin_update(m, a.s);
	double seat = fmin(at(&a, S_ISCHIAL_L)[1], at(&a, S_ISCHIAL_R)[1]);
	double footrest = at(&a, S_HEEL_R)[1];
	v[HUMAN_M_SITTINGHEIGHT] = (at(&a, S_VERTEX)[1] - seat) * mm;
	v[HUMAN_M_EYEHEIGHTSITTING] = (at(&a, S_ECTOCANTHUS_R)[1] - seat) * mm;
	v[HUMAN_M_KNEEHEIGHTSITTING] = (at(&a, S_SUPRAPATELLA_R)[1] - footrest) * mm;
	v[HUMAN_M_POPLITEALHEIGHT] = (at(&a, S_POPLITEAL_R)[1] - footrest) * mm;
	v[HUMAN_M_BUTTOCKKNEELENGTH] =
		(at(&a, S_KNEE_FRONT_R)[2] - fmin(at(&a, S_BUTTOCK_L)[2], at(&a, S_BUTTOCK_R)[2])) * mm;

	/* span */
	pose(&a);
	q[a.dof0[J_SHOULDER][0] + 1] = span_q[0];
	q[a.dof0[J_SHOULDER][1] + 1] = span_q[1];
	kin_update(m, a.s);
	v[HUMAN_M_SPAN] = dist(at(&a, S_DACTYLION_L), at(&a, S_DACTYLION_R)) * mm;

	/* thumbtip reach: from the wall behind the shoulder blades */
	pose(&a);
	q[a.dof0[J_SHOULDER][1]] = reach_q;
	kin_update(m, a.s);
	double wall = fmin(at(&a, S_BLADE_L)[2], at(&a, S_BLADE_R)[2]);
	v[HUMAN_M_THUMBTIPREACH] = (at(&a, S_THUMBTIP_R)[2] - wall) * mm;

	state_free(a.s);
	return 0;
}

int
anthro_measure_figure(const struct model *m, const struct human_def *d,
		      double dest[HUMAN_MEASURE_N], char *err, size_t errlen)
{
	/* the built-in human without measures has no landmark sites (figure/human.h) */
	if (!d || model_find_site(m, site_names[S_ACROMION_R]) >= 0)
		return anthro_measure(m, dest, err, errlen);
	struct model *twin = human_build_landmarked(d, err, errlen);
	if (!twin)
		return -1;
	int r = anthro_measure(twin, dest, err, errlen);
	model_free(twin);
	return r;
}
