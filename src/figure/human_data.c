/*
 * human_data.c - cited anthropometry and range-of-motion tables, and the
 * layout of the standing figure computed from them (sources of the layout:
 * the comment at the top of human.c).
 */
#include "figure/human_data.h"

#include <math.h>
#include <string.h>

const char *const human_slice_name[HUMAN_NSLICE] = { "L5",  "L4",  "L3",  "L2", "L1", "T12",
						     "T11", "T10", "T9",  "T8", "T7", "T6",
						     "T5",  "T4",  "T3",  "T2", "T1" };
const char *const human_limb_name[HUMAN_LIMB_N] = { "thigh",    "shank",    "foot",
						    "toes",     "clavicle", "upperarm",
						    "forearm",  "hand" };
const char *const human_side_sfx[2] = { "_l", "_r" };

const struct human_landmark_info human_landmark_info[HUMAN_LM_N] = {
#define HUMAN_LM_INFO(e, name, seg, bilateral) { name, seg, bilateral },
	HUMAN_LANDMARKS(HUMAN_LM_INFO)
#undef HUMAN_LM_INFO
};

/*
 * de Leva P (1996) Adjustments to Zatsiorsky-Seluyanov's segment inertia
 * parameters. J Biomech 29(9):1223-1230, Table 4. Reference subjects: men
 * 1.741 m / 73.0 kg, women 1.735 m / 61.9 kg. Columns: mass fraction; CM
 * position from the first endpoint (vertex, suprasternale, xiphion,
 * omphalion, shoulder, elbow, wrist, hip, knee, heel); radii of gyration
 * (sagittal, transverse, longitudinal) as fractions of the segment length;
 * segment length (m). The head row is the table's alternative
 * vertex-to-cervicale definition, since our head segment starts at C7/T1.
 * The women's masses sum to 0.9999 (rounding); human.c normalises them.
 */
const struct human_dl_table human_dl_male = {
	1.741,
	73.0,
	{
		[HUMAN_DL_HEAD] = { 0.0694, 0.5002, 0.303, 0.315, 0.261, 0.2429 },
		[HUMAN_DL_UPT] = { 0.1596, 0.2999, 0.716, 0.454, 0.659, 0.1707 },
		[HUMAN_DL_MPT] = { 0.1633, 0.4502, 0.482, 0.383, 0.468, 0.2155 },
		[HUMAN_DL_LPT] = { 0.1117, 0.6115, 0.615, 0.551, 0.587, 0.1457 },
		[HUMAN_DL_UPPERARM] = { 0.0271, 0.5772, 0.285, 0.269, 0.158, 0.2817 },
		[HUMAN_DL_FOREARM] = { 0.0162, 0.4574, 0.276, 0.265, 0.121, 0.2689 },
		[HUMAN_DL_HAND] = { 0.0061, 0.7900, 0.628, 0.513, 0.401, 0.0862 },
		[HUMAN_DL_THIGH] = { 0.1416, 0.4095, 0.329, 0.329, 0.149, 0.4222 },
		[HUMAN_DL_SHANK] = { 0.0433, 0.4459, 0.255, 0.249, 0.103, 0.4340 },
		[HUMAN_DL_FOOT] = { 0.0137, 0.4415, 0.257, 0.245, 0.124, 0.2581 },
	},
};

const struct human_dl_table human_dl_female = {
	1.735,
	61.9,
	{
		[HUMAN_DL_HEAD] = { 0.0668, 0.4841, 0.271, 0.295, 0.261, 0.2437 },
		[HUMAN_DL_UPT] = { 0.1545, 0.2077, 0.746, 0.502, 0.718, 0.1425 },
		[HUMAN_DL_MPT] = { 0.1465, 0.4512, 0.433, 0.354, 0.415, 0.2053 },
		[HUMAN_DL_LPT] = { 0.1247, 0.4920, 0.433, 0.402, 0.444, 0.1815 },
		[HUMAN_DL_UPPERARM] = { 0.0255, 0.5754, 0.278, 0.260, 0.148, 0.2751 },
		[HUMAN_DL_FOREARM] = { 0.0138, 0.4559, 0.261, 0.257, 0.094, 0.2643 },
		[HUMAN_DL_HAND] = { 0.0056, 0.7474, 0.531, 0.454, 0.335, 0.0780 },
		[HUMAN_DL_THIGH] = { 0.1478, 0.3612, 0.369, 0.364, 0.162, 0.3685 },
		[HUMAN_DL_SHANK] = { 0.0481, 0.4416, 0.271, 0.267, 0.093, 0.4323 },
		[HUMAN_DL_FOOT] = { 0.0129, 0.4014, 0.299, 0.279, 0.139, 0.2283 },
	},
};

/*
 * Drillis R, Contini R (1966) Body segment parameters. Report 1166-03,
 * New York University, as reproduced in Winter DA, Biomechanics and Motor
 * Control of Human Movement (4th ed. 2009), Fig. 4.1: heights above the
 * floor and breadths as fractions of stature H.
 */
const double human_dc_ankle = 0.039;          /* ankle joint height */
const double human_dc_knee = 0.285;           /* knee joint height */
const double human_dc_hip = 0.530;            /* hip joint (greater trochanter) height */
const double human_dc_wrist = 0.485;          /* wrist joint height */
const double human_dc_fingertip = 0.377;      /* fingertip height, arm hanging */
const double human_dc_elbow = 0.630;          /* elbow joint height */
const double human_dc_shoulder = 0.818;       /* shoulder joint height */
const double human_dc_chin = 0.870;           /* chin height */
const double human_dc_eye = 0.936;            /* eye height */
const double human_dc_shoulder_half = 0.129;  /* mid-chest to shoulder joint */
const double human_dc_hip_width = 0.191;      /* hip breadth */
const double human_dc_chest_width = 0.174;    /* chest (nipple) breadth */
const double human_dc_foot_length = 0.152;    /* heel to toe tip */
const double human_dc_foot_width = 0.055;     /* foot breadth */

/*
 * White AA, Panjabi MM (1990) Clinical Biomechanics of the Spine, 2nd ed.,
 * Lippincott, ch. 2, the table of "representative values" of the range of
 * motion of each thoracic and lumbar motion segment (degrees): combined flexion +
 * extension, lateral bending to one side, axial rotation to one side.
 * The split of flexion and extension (2/3 flexion) is our assumption: the
 * table gives the combined value, and flexion dominates in the lumbar spine.
 */
const struct human_spine_rom human_spine_rom[17] = {
	{ 17, 3, 1 }, /* spine_0  L5/S1 */
	{ 16, 6, 2 }, /* spine_1  L4/L5 */
	{ 15, 8, 2 }, /* spine_2  L3/L4 */
	{ 14, 6, 2 }, /* spine_3  L2/L3 */
	{ 12, 6, 2 }, /* spine_4  L1/L2 */
	{ 12, 8, 2 }, /* spine_5  T12/L1 */
	{ 12, 9, 2 }, /* spine_6  T11/T12 */
	{ 9, 7, 2 },  /* spine_7  T10/T11 */
	{ 6, 6, 4 },  /* spine_8  T9/T10 */
	{ 6, 6, 7 },  /* spine_9  T8/T9 */
	{ 6, 6, 8 },  /* spine_10 T7/T8 */
	{ 5, 6, 8 },  /* spine_11 T6/T7 */
	{ 4, 6, 8 },  /* spine_12 T5/T6 */
	{ 4, 6, 8 },  /* spine_13 T4/T5 */
	{ 4, 6, 8 },  /* spine_14 T3/T4 */
	{ 4, 6, 8 },  /* spine_15 T2/T3 */
	{ 4, 6, 9 },  /* spine_16 T1/T2 */
};

const double human_spine_flex_share = 2.0 / 3.0;

/*
 * Cervical spine as a whole (occiput to T1): American Academy of
 * Orthopaedic Surgeons (1965) Joint Motion: Method of Measuring and
 * Recording; Greene WB, Heckman JD (eds., 1994) The Clinical Measurement
 * of Joint Motion, AAOS: flexion 45, extension 45, lateral bending 45,
 * rotation 60 degrees.
 */
const double human_neck_flex = 45, human_neck_ext = 45, human_neck_lat = 45, human_neck_rot = 60;

/*
 * Limb joints, left side; dof order as the ISB joint coordinate systems
 * (Wu et al. 2002, J Biomech 35:543-548, lower limb and spine; Wu et al.
 * 2005, J Biomech 38:981-992, upper limb): flexion/extension, then
 * ab/adduction (or its analogue), then axial rotation. The figure stands
 * with the palms facing the thighs (thumbs forward), so wrist flexion is
 * about the world z axis and radial deviation about x there.
 *
 * Limits, degrees, normal adult active ranges:
 *   hip, knee, ankle, toe (first MTP), shoulder, elbow, forearm, wrist:
 *     AAOS (1965) / Greene & Heckman (1994), as above. Hip flexion 120,
 *     extension 30, abduction 45, adduction 30, rotation 45 each way; knee
 *     0-135; ankle dorsiflexion 20, plantarflexion 50, inversion 35,
 *     eversion 15; first MTP flexion 45, extension 70; shoulder flexion
 *     180, extension 60, abduction 180, internal 70, external 90 rotation;
 *     elbow 0-150; pronation and supination 80; wrist flexion 80,
 *     extension 70, radial 20, ulnar 30 deviation.
 *   shoulder adduction 50: clinical tables (e.g. Magee, Orthopedic Physical
 *     Assessment) give 50; AAOS lists none from the hanging arm.
 *   foot rotation about the vertical (ab/adduction of the foot): +-20, within
 *     the 35-45 degree total given by Kapandji, The Physiology of the
 *     Joints, vol. 2 (lower limb).
 *   clavicle at the sternoclavicular joint: elevation 45, depression 10,
 *     protraction 20, retraction 30 (Neumann DA, Kinesiology of the
 *     Musculoskeletal System, 2nd ed. 2010, ch. 5: elevation ~45,
 *     depression ~10, protraction 15-20, retraction 15-30). ISB order for
 *     the SC joint: protraction/retraction first, then elevation.
 *   eye: +-45 horizontal (oculomotor range, Guitton D, Volle M 1987,
 *     J Neurophysiol 58:427-459), 35 up and 45 down.
 */
const struct human_joint_spec human_limb_joints[HUMAN_LJ_N] = {
	/* flexion about -x (thigh forward), abduction about +z, internal rotation about -y */
	[HUMAN_LJ_HIP] = { "hip", 3, { { 0, -1, -30, 120 }, { 2, 1, -30, 45 }, { 1, -1, -45, 45 } } },
	/* flexion about +x (shank backwards) */
	[HUMAN_LJ_KNEE] = { "knee", 1, { { 0, 1, 0, 135 } } },
	/* dorsiflexion about -x, inversion about -z, internal rotation about -y */
	[HUMAN_LJ_ANKLE] = { "ankle", 3, { { 0, -1, -50, 20 }, { 2, -1, -15, 35 }, { 1, -1, -20, 20 } } },
	/* flexion of the toes (downwards) about +x */
	[HUMAN_LJ_TOE] = { "toe", 1, { { 0, 1, -70, 45 } } },
	/* protraction (lateral end forward) about -y, elevation about +z */
	[HUMAN_LJ_CLAVICLE] = { "clavicle", 2, { { 1, -1, -30, 20 }, { 2, 1, -10, 45 } } },
	/* flexion about -x (arm forward), abduction about +z, internal rotation about -y */
	[HUMAN_LJ_SHOULDER] = { "shoulder", 3,
				{ { 0, -1, -60, 180 }, { 2, 1, -50, 180 }, { 1, -1, -90, 70 } } },
	/* flexion about -x (forearm forward) */
	[HUMAN_LJ_ELBOW] = { "elbow", 1, { { 0, -1, 0, 150 } } },
	/* flexion (towards the palm, -x) about -z, radial deviation about -x, pronation about -y */
	[HUMAN_LJ_WRIST] = { "wrist", 3, { { 2, -1, -70, 80 }, { 0, -1, -30, 20 }, { 1, -1, -80, 80 } } },
	/* abduction (temporal gaze) about +y, then elevation (looking up) about -x */
	[HUMAN_LJ_EYE] = { "eye", 2, { { 1, 1, -45, 45 }, { 0, -1, -45, 35 } } },
};

static void
vset(double dest[3], double x, double y, double z)
{
	dest[0] = x;
	dest[1] = y;
	dest[2] = z;
}

/* the right side's copy of a left point */
void
human_mirror(const double p[3], double dest[3])
{
	vset(dest, -p[0], p[1], p[2]);
}

static double
dl_mass(const struct human_layout *L, int s)
{
	return L->dl->seg[s].mass * L->norm * L->M;
}

/* C7/T1: one de Leva head length below the vertex, whatever the measures */
static double
c7_height(const struct human_layout *L)
{
	return L->H - L->dl->seg[HUMAN_DL_HEAD].len * L->k;
}

/*
 * Torso outline: half-width and half-depth (fractions of stature) against
 * height. Hip breadth 0.191 H and chest breadth 0.174 H from Drillis &
 * Contini; the depths and the waist and shoulder-root widths are
 * approximate adult proportions.
 */
void
human_torso_semi(const struct human_layout *L, double y, double *hw, double *hd)
{
	static const double tab[][3] = {
		{ 0.470, 0.090, 0.060 }, { 0.530, 0.0955, 0.063 }, { 0.600, 0.083, 0.057 },
		{ 0.660, 0.083, 0.057 }, { 0.720, 0.087, 0.062 }, { 0.790, 0.088, 0.058 },
		{ 0.835, 0.072, 0.050 }, { 0.870, 0.040, 0.040 },
	};
	int n = (int)(sizeof tab / sizeof tab[0]);
	/* the outline is today's figure's: a moved trunk looks it up where today's is */
	double f = (L->dim.measured ? human_trunk_unmap(&L->dim, c7_height(L), y) : y) / L->H;
	int i = 0;
	while (i < n - 2 && f > tab[i + 1][0])
		i++;
	double t = (f - tab[i][0]) / (tab[i + 1][0] - tab[i][0]);
	t = t < 0 ? 0 : t > 1 ? 1 : t;
	*hw = L->H * (tab[i][1] + t * (tab[i + 1][1] - tab[i][1]));
	*hd = L->H * (tab[i][2] + t * (tab[i + 1][2] - tab[i][2]));
}

/*
 * Exponential mass density along a trunk sub-segment, rho(t) ~ exp(kappa t)
 * with t from 0 (top) to 1 (bottom): positive for any centre-of-mass
 * fraction c in (0, 1), which a linear density is not for de Leva's upper
 * trunk (c = 0.30 / 0.21).
 */
static double
exp_com(double kappa)
{
	if (fabs(kappa) < 1e-6)
		return 0.5 + kappa / 12;
	return 1 / (-expm1(-kappa)) - 1 / kappa;
}

static double
exp_kappa(double c)
{
	double lo = -200, hi = 200;
	for (int i = 0; i < 200; i++) {
		double mid = (lo + hi) / 2;
		if (exp_com(mid) < c)
			lo = mid;
		else
			hi = mid;
	}
	return (lo + hi) / 2;
}

/* integral of rho and of t * rho over [t0, t1] */
static void
exp_integrals(double kappa, double t0, double t1, double *mass, double *moment)
{
	if (fabs(kappa) < 1e-6) {
		*mass = t1 - t0;
		*moment = (t1 * t1 - t0 * t0) / 2;
		return;
	}
	double e0 = exp(kappa * t0), e1 = exp(kappa * t1);
	*mass = (e1 - e0) / kappa;
	*moment = e1 * (t1 / kappa - 1 / (kappa * kappa)) - e0 * (t0 / kappa - 1 / (kappa * kappa));
}

/*
 * Spreads mass m between heights ytop and ybot, with its centre of mass a
 * fraction c of the way down, over the segments first..last whose heights
 * [ylo[i], yhi[i]] tile that span; writes their masses and com heights.
 */
static void
trunk_spread(double m, double c, double ytop, double ybot, int first, int last,
	     const double *ylo, const double *yhi, double *mass, double *ycom)
{
	double kappa = exp_kappa(c), span = ytop - ybot, total = 0, w[HUMAN_NSLICE + 1], mo[HUMAN_NSLICE + 1];
	for (int i = first; i <= last; i++) {
		exp_integrals(kappa, (ytop - yhi[i]) / span, (ytop - ylo[i]) / span, &w[i], &mo[i]);
		total += w[i];
	}
	for (int i = first; i <= last; i++) {
		mass[i] = m * w[i] / total;
		ycom[i] = ytop - mo[i] / w[i] * span;
	}
}

/* dest = R diag(d) R^T as ixx iyy izz ixy ixz iyz */
static void
inertia_rotated(const double d[3], const double R[9], double dest[6])
{
	double I[9];
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			I[3 * i + j] = R[3 * i] * d[0] * R[3 * j] + R[3 * i + 1] * d[1] * R[3 * j + 1] +
				       R[3 * i + 2] * d[2] * R[3 * j + 2];
	dest[0] = I[0], dest[1] = I[4], dest[2] = I[8];
	dest[3] = I[1], dest[4] = I[2], dest[5] = I[5];
}

/* unit quaternion rotating +y onto the line through a and b */
void
human_quat_y_to(const double a[3], const double b[3], double q[4])
{
	double v[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
	double n = sqrt(mathx_dot(v, v));
	for (int r = 0; r < 3; r++)
		v[r] = (v[1] < 0 ? -v[r] : v[r]) / n;
	/* half-way vector between y and v: a rotation of twice its angle */
	double h[3] = { v[0], v[1] + 1, v[2] }, y[3] = { 0, 1, 0 }, ax[3];
	double hn = sqrt(mathx_dot(h, h));
	mathx_cross(y, h, ax);
	for (int r = 0; r < 3; r++)
		q[r] = ax[r] / hn;
	q[3] = h[1] / hn;
}

/* rotation matrix of a rod's frame: local y along a -> b */
static void
rod_frame(const double a[3], const double b[3], double R[9])
{
	double q[4];
	human_quat_y_to(a, b, q);
	mathx_quat_to_mat(q, R);
}

/* principal inertia (sagittal about x, longitudinal about y, transverse about z) of a de Leva row */
static void
dl_inertia(const struct human_dl_row *row, double m, double len, int sag_axis, int trans_axis,
	   int long_axis, const double R[9], double dest[6])
{
	double d[3];
	d[sag_axis] = m * pow(row->r_sag * len, 2);
	d[trans_axis] = m * pow(row->r_trans * len, 2);
	d[long_axis] = m * pow(row->r_long * len, 2);
	static const double id[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
	inertia_rotated(d, R ? R : id, dest);
}

/* joint centres for ankle offset za */
static void
lay_points(struct human_layout *L, double za)
{
	const struct human_dims *D = &L->dim;
	double H = L->H, k = L->k;
	const struct human_dl_row *dl = L->dl->seg;
	L->za = za;
	/* legs: Drillis & Contini heights, Hara et al. hip joint centres (human_dims.c) */
	double hx = D->hx, y_asis = D->y_asis;
	vset(L->hip, hx, D->y_hip, 0);
	vset(L->knee, hx, D->y_knee, 0);
	vset(L->ankle, hx, D->y_ankle, za);
	double lf = D->lf, heel_z = za - 0.25 * lf;
	vset(L->heel, hx, 0, heel_z);
	vset(L->mtp, hx, 0.011 * H, heel_z + 0.73 * lf);
	vset(L->tip, hx, 0, heel_z + lf);
	vset(L->balance, hx, 0, za + HUMAN_BALANCE_AHEAD * H);
	double fw = D->fw;
	vset(L->foot_box[0], hx - fw / 2, 0, heel_z);
	vset(L->foot_box[1], hx + fw / 2, L->ankle[1] + 0.010 * H, L->mtp[2]);
	vset(L->toes_box[0], hx - 0.45 * fw, 0, L->mtp[2] - 0.004 * H);
	vset(L->toes_box[1], hx + 0.45 * fw, 0.018 * H, L->tip[2]);

	/* spine: L5/S1 at the ASIS, C7/T1 one de Leva head length below the vertex */
	double y0 = y_asis, y17 = H - dl[HUMAN_DL_HEAD].len * k, sl = 18.0 / 46.0;
	double wsum = 5 * (18.0 / 5) + 12 * (28.0 / 12), y = y0;
	for (int i = 0; i <= HUMAN_NSLICE; i++) {
		double s = (y - y0) / (y17 - y0), d;
		/* lumbar lordosis, thoracic kyphosis: vertebral bodies behind the torso's mid-line */
		if (s <= sl)
			d = 0.017 - 0.003 * sin(M_PI * s / sl);
		else
			d = 0.017 + 0.012 * sin(M_PI * (s - sl) / (1 - sl));
		vset(L->spine[i], 0, i == HUMAN_NSLICE ? y17 : y, -d * H);
		if (i < HUMAN_NSLICE)
			y += (y17 - y0) * (i < 5 ? 18.0 / 5 : 28.0 / 12) / wsum;
	}
	L->y_supr = human_dc_hip * H + (dl[HUMAN_DL_LPT].len + dl[HUMAN_DL_MPT].len +
					dl[HUMAN_DL_UPT].len) * k;
	if (D->measured) {
		for (int i = 0; i < HUMAN_NSLICE; i++)
			L->spine[i][1] = human_trunk_map(D, y17, L->spine[i][1]);
		L->y_supr = human_trunk_map(D, y17, L->y_supr);
	}

	/* shoulder girdle and arm, hanging with the palms facing the thighs */
	double hw, hd;
	human_torso_semi(L, L->y_supr, &hw, &hd);
	vset(L->sc, 0.012 * H, L->y_supr, hd - 0.010 * H);
	double ax = D->gh_x;
	vset(L->gh, ax, D->gh_y, 0);
	vset(L->elbow, ax, D->y_elbow, 0);
	vset(L->wrist, ax, D->y_wrist, 0);
	vset(L->fingertip, ax, D->y_tip, 0);

	/* head: skull from chin to vertex, eyes at eye height */
	vset(L->head_semi, 0.044 * H, (1 - human_dc_chin) * H / 2, 0.056 * H);
	vset(L->head_c, 0, H - L->head_semi[1], 0.010 * H);
	double ex = 0.018 * H;
	L->eye_r = 0.0069 * H;
	double front = L->head_c[2] +
		       L->head_semi[2] * sqrt(1 - (ex / L->head_semi[0]) * (ex / L->head_semi[0]));
	vset(L->eye, ex, D->y_eye, front - 0.4 * L->eye_r);
}

/* masses, centres of mass (layout frame) and inertia of every segment */
static void
lay_masses(struct human_layout *L)
{
	double H = L->H, k = L->k;
	const struct human_dl_row *dl = L->dl->seg;
	static const double id[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
	memset(L->inertia, 0, sizeof L->inertia);

	/* origins */
	vset(L->org[HUMAN_SEG_PELVIS], 0, L->hip[1], 0);
	for (int i = 0; i < HUMAN_NSLICE; i++)
		memcpy(L->org[HUMAN_SEG_SLICE0 + i], L->spine[i], sizeof L->spine[i]);
	memcpy(L->org[HUMAN_SEG_HEAD], L->spine[HUMAN_NSLICE], sizeof L->spine[HUMAN_NSLICE]);
	const double *lorg[HUMAN_LIMB_N] = { L->hip, L->knee, L->ankle, L->mtp,
				       L->sc, L->gh, L->elbow, L->wrist };
	for (int s = 0; s < 2; s++) {
		if (s == 0)
			memcpy(L->org[HUMAN_SEG_EYE], L->eye, sizeof L->eye);
		else
			human_mirror(L->eye, L->org[HUMAN_SEG_EYE + 1]);
		for (int l = 0; l < HUMAN_LIMB_N; l++) {
			double *o = L->org[HUMAN_SEG_LIMB + HUMAN_LIMB_N * s + l];
			if (s == 0)
				memcpy(o, lorg[l], sizeof L->hip);
			else
				human_mirror(lorg[l], o);
		}
	}

	/* left limbs; the right side is mirrored below */
	int b = HUMAN_SEG_LIMB;
	double R[9], len, m;
	/* thigh: hip -> knee, vertical */
	m = L->mass[b + HUMAN_LIMB_THIGH] = dl_mass(L, HUMAN_DL_THIGH);
	len = L->hip[1] - L->knee[1];
	vset(L->com[b + HUMAN_LIMB_THIGH], L->hip[0], L->hip[1] - dl[HUMAN_DL_THIGH].com * len, 0);
	dl_inertia(&dl[HUMAN_DL_THIGH], m, len, 0, 2, 1, id, L->inertia[b + HUMAN_LIMB_THIGH]);
	/* shank: knee -> ankle, leaning */
	m = L->mass[b + HUMAN_LIMB_SHANK] = dl_mass(L, HUMAN_DL_SHANK);
	double c = dl[HUMAN_DL_SHANK].com;
	for (int r = 0; r < 3; r++)
		L->com[b + HUMAN_LIMB_SHANK][r] = L->knee[r] + c * (L->ankle[r] - L->knee[r]);
	len = hypot(L->knee[1] - L->ankle[1], L->knee[2] - L->ankle[2]);
	rod_frame(L->ankle, L->knee, R);
	dl_inertia(&dl[HUMAN_DL_SHANK], m, len, 0, 2, 1, R, L->inertia[b + HUMAN_LIMB_SHANK]);
	/* foot + toes: de Leva's foot, split by box volume; CoM at half ankle height */
	double mf = dl_mass(L, HUMAN_DL_FOOT), lf = L->dim.lf, vol[2];
	for (int i = 0; i < 2; i++) {
		const double(*bx)[3] = i ? L->toes_box : L->foot_box;
		vol[i] = (bx[1][0] - bx[0][0]) * (bx[1][1] - bx[0][1]) * (bx[1][2] - bx[0][2]);
	}
	double mt = mf * vol[1] / (vol[0] + vol[1]), cf[3], ct[3];
	vset(cf, L->hip[0], L->ankle[1] / 2, L->heel[2] + dl[HUMAN_DL_FOOT].com * lf);
	for (int r = 0; r < 3; r++)
		ct[r] = (L->toes_box[0][r] + L->toes_box[1][r]) / 2;
	L->mass[b + HUMAN_LIMB_TOES] = mt;
	memcpy(L->com[b + HUMAN_LIMB_TOES], ct, sizeof ct);
	m = L->mass[b + HUMAN_LIMB_FOOT] = mf - mt;
	for (int r = 0; r < 3; r++)
		L->com[b + HUMAN_LIMB_FOOT][r] = (mf * cf[r] - mt * ct[r]) / m;
	dl_inertia(&dl[HUMAN_DL_FOOT], m, lf, 0, 1, 2, id, L->inertia[b + HUMAN_LIMB_FOOT]);
	double ex = L->toes_box[1][0] - L->toes_box[0][0], ey = L->toes_box[1][1] - L->toes_box[0][1],
	       ez = L->toes_box[1][2] - L->toes_box[0][2];
	double dt[3] = { mt * (ey * ey + ez * ez) / 12, mt * (ex * ex + ez * ez) / 12,
			 mt * (ex * ex + ey * ey) / 12 };
	inertia_rotated(dt, id, L->inertia[b + HUMAN_LIMB_TOES]);
	/* clavicle (shoulder girdle): a rod from the SC joint to the shoulder joint */
	double mcl = L->mass[b + HUMAN_LIMB_CLAVICLE] = HUMAN_CLAVICLE_SHARE * dl_mass(L, HUMAN_DL_UPT);
	for (int r = 0; r < 3; r++)
		L->com[b + HUMAN_LIMB_CLAVICLE][r] = (L->sc[r] + L->gh[r]) / 2;
	len = sqrt(pow(L->gh[0] - L->sc[0], 2) + pow(L->gh[1] - L->sc[1], 2) +
		   pow(L->gh[2] - L->sc[2], 2));
	double rr = 0.02 * H, perp = mcl * (3 * rr * rr + len * len) / 12;
	double dcl[3] = { perp, mcl * rr * rr / 2, perp };
	rod_frame(L->sc, L->gh, R);
	inertia_rotated(dcl, R, L->inertia[b + HUMAN_LIMB_CLAVICLE]);
	/* upper arm: shoulder -> elbow */
	m = L->mass[b + HUMAN_LIMB_UPPERARM] = dl_mass(L, HUMAN_DL_UPPERARM);
	len = L->gh[1] - L->elbow[1];
	vset(L->com[b + HUMAN_LIMB_UPPERARM], L->gh[0], L->gh[1] - dl[HUMAN_DL_UPPERARM].com * len, 0);
	dl_inertia(&dl[HUMAN_DL_UPPERARM], m, len, 0, 2, 1, id, L->inertia[b + HUMAN_LIMB_UPPERARM]);
	/* forearm and hand are mid-prone: their sagittal (flexion) axis is world z */
	m = L->mass[b + HUMAN_LIMB_FOREARM] = dl_mass(L, HUMAN_DL_FOREARM);
	len = L->elbow[1] - L->wrist[1];
	vset(L->com[b + HUMAN_LIMB_FOREARM], L->gh[0], L->elbow[1] - dl[HUMAN_DL_FOREARM].com * len, 0);
	dl_inertia(&dl[HUMAN_DL_FOREARM], m, len, 2, 0, 1, id, L->inertia[b + HUMAN_LIMB_FOREARM]);
	m = L->mass[b + HUMAN_LIMB_HAND] = dl_mass(L, HUMAN_DL_HAND);
	len = L->dim.hand_len; /* wrist to third metacarpale */
	vset(L->com[b + HUMAN_LIMB_HAND], L->gh[0], L->wrist[1] - dl[HUMAN_DL_HAND].com * len, 0);
	dl_inertia(&dl[HUMAN_DL_HAND], m, len, 2, 0, 1, id, L->inertia[b + HUMAN_LIMB_HAND]);
	for (int l = 0; l < HUMAN_LIMB_N; l++) {
		int sl = HUMAN_SEG_LIMB + l, sr = HUMAN_SEG_LIMB + HUMAN_LIMB_N + l;
		L->mass[sr] = L->mass[sl];
		human_mirror(L->com[sl], L->com[sr]);
		memcpy(L->inertia[sr], L->inertia[sl], sizeof L->inertia[sl]);
		L->inertia[sr][3] = -L->inertia[sl][3];
		L->inertia[sr][4] = -L->inertia[sl][4];
	}

	/* head and eyes: the two together keep de Leva's head mass and CoM */
	double mh = dl_mass(L, HUMAN_DL_HEAD), lh = dl[HUMAN_DL_HEAD].len * k, ch[3];
	vset(ch, 0, H - dl[HUMAN_DL_HEAD].com * lh, L->head_c[2]);
	for (int s = 0; s < 2; s++) {
		L->mass[HUMAN_SEG_EYE + s] = HUMAN_EYE_MASS;
		memcpy(L->com[HUMAN_SEG_EYE + s], L->org[HUMAN_SEG_EYE + s], sizeof ch);
		double ie = 0.4 * HUMAN_EYE_MASS * L->eye_r * L->eye_r, de[3] = { ie, ie, ie };
		inertia_rotated(de, id, L->inertia[HUMAN_SEG_EYE + s]);
	}
	m = L->mass[HUMAN_SEG_HEAD] = mh - 2 * HUMAN_EYE_MASS;
	for (int r = 0; r < 3; r++)
		L->com[HUMAN_SEG_HEAD][r] = (mh * ch[r] - HUMAN_EYE_MASS * (L->com[HUMAN_SEG_EYE][r] +
								L->com[HUMAN_SEG_EYE + 1][r])) / m;
	dl_inertia(&dl[HUMAN_DL_HEAD], m, lh, 0, 2, 1, id, L->inertia[HUMAN_SEG_HEAD]);

	/* trunk: pelvis (index 0 here) and slices 1..17, de Leva's lower,
	 * middle and upper trunk mapped onto hip-L3/L4, L3/L4-T9/T10 and
	 * T9/T10-C7/T1 (umbilicus at L3/L4, xiphisternum at T9) */
	double ylo[HUMAN_NSLICE + 1], yhi[HUMAN_NSLICE + 1], tm[HUMAN_NSLICE + 1], ty[HUMAN_NSLICE + 1];
	ylo[0] = L->hip[1];
	yhi[0] = L->spine[0][1];
	for (int i = 0; i < HUMAN_NSLICE; i++) {
		ylo[i + 1] = L->spine[i][1];
		yhi[i + 1] = L->spine[i + 1][1];
	}
	trunk_spread(dl_mass(L, HUMAN_DL_LPT), dl[HUMAN_DL_LPT].com, L->spine[2][1], L->hip[1], 0, 2,
		     ylo, yhi, tm, ty);
	trunk_spread(dl_mass(L, HUMAN_DL_MPT), dl[HUMAN_DL_MPT].com, L->spine[8][1],
		     L->spine[2][1], 3, 8, ylo, yhi, tm, ty);
	/* the clavicles carry part of the upper trunk: the slices keep the rest's CoM */
	double mu = dl_mass(L, HUMAN_DL_UPT), top = L->spine[HUMAN_NSLICE][1], bot = L->spine[8][1];
	double yu = top - dl[HUMAN_DL_UPT].com * (top - bot);
	double mrest = mu - 2 * mcl, yrest = (mu * yu - 2 * mcl * L->com[HUMAN_SEG_LIMB + HUMAN_LIMB_CLAVICLE][1]) / mrest;
	trunk_spread(mrest, (top - yrest) / (top - bot), top, bot, 9, HUMAN_NSLICE, ylo, yhi, tm, ty);
	/* the rest of the body mass goes to the pelvis so the sum is exact */
	double others = 0;
	for (int i = HUMAN_SEG_HEAD; i < HUMAN_SEG_N; i++)
		others += L->mass[i];
	for (int i = 1; i <= HUMAN_NSLICE; i++)
		others += tm[i];
	tm[0] = L->M - others;
	for (int i = 0; i <= HUMAN_NSLICE; i++) {
		int seg = HUMAN_SEG_PELVIS + i;
		L->mass[seg] = tm[i];
		vset(L->com[seg], 0, ty[i], 0);
		/* elliptic cylinder of the torso outline; the pelvis reaches below the hips */
		double h = yhi[i] - ylo[i] + (i == 0 ? 0.06 * H : 0), hw, hd;
		human_torso_semi(L, ty[i], &hw, &hd);
		double dc[3] = { tm[i] * (hd * hd / 4 + h * h / 12), tm[i] * (hw * hw + hd * hd) / 4,
				 tm[i] * (hw * hw / 4 + h * h / 12) };
		inertia_rotated(dc, id, L->inertia[seg]);
	}
}

void
human_layout_com(const struct human_layout *L, double dest[3])
{
	double sum[3] = { 0, 0, 0 }, mt = 0;
	for (int i = 0; i < HUMAN_SEG_N; i++) {
		mt += L->mass[i];
		for (int r = 0; r < 3; r++)
			sum[r] += L->mass[i] * L->com[i][r];
	}
	for (int r = 0; r < 3; r++)
		dest[r] = sum[r] / mt;
}

#define within human_dims_within

/* today's figure: the stature fractions (human.c's sources) */
static void
dims_default(struct human_layout *L)
{
	struct human_dims *D = &L->dim;
	const struct human_lm_fractions *F = human_lm_fractions(L->dl == &human_dl_female);
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

/* places the landmarks on the laid-out figure; 0, or -1 with why in err */
static int
landmarks_place(struct human_layout *L, char *err, size_t errlen)
{
	const struct human_dims *D = &L->dim;
	const struct human_lm_fractions *F = human_lm_fractions(L->dl == &human_dl_female);
	double H = L->H, y_a = L->ankle[1];
	/* seated, the shank hangs straight below the knee and the foot is flat */
	double shank = hypot(L->knee[1] - L->ankle[1], L->knee[2] - L->ankle[2]);
	/* what a measure given sets; the ANSUR mean where none is */
#define M(L, x) ((L)->dim.v[HUMAN_M_##x])
#define SET(x) (D->measured && !isnan(M(L, x)))
	double seat = human_seat_depth(D, H, L->dl == &human_dl_female);
	double supra = SET(KNEEHEIGHTSITTING) ? M(L, KNEEHEIGHTSITTING) - shank - y_a
					      : F->suprapatella * H;
	double popl = SET(POPLITEALHEIGHT) ? shank + y_a - M(L, POPLITEALHEIGHT) : F->popliteal * H;
	double thigh = L->hip[1] - L->knee[1];
	double butt = SET(BUTTOCKKNEELENGTH) ? M(L, BUTTOCKKNEELENGTH) - thigh - supra
					     : F->buttock * H;
	double sz = F->stylion_z * H, hand = hypot(L->wrist[1] - L->fingertip[1], sz);
	double thumb_y = L->wrist[1] - HUMAN_LM_PINCH * hand;
	double blade = SET(THUMBTIPREACH) ? M(L, THUMBTIPREACH) - (L->gh[1] - thumb_y)
					  : F->shoulder_blade * H;
	double troch = SET(HIPBREADTH) ? M(L, HIPBREADTH) / 2 : F->trochanterion_x * H;
#undef SET
#undef M
	if (within(seat, HUMAN_LM_SEAT_LO, HUMAN_LM_SEAT_HI, H,
		   "the seat below the hip joint centres",
		   "sittingheight against stature and trochanterionheight", err, errlen) < 0 ||
	    within(supra, HUMAN_LM_KNEE_DEPTH_LO, HUMAN_LM_SUPRAPATELLA_HI, H,
		   "the top of the knee above its axis, seated",
		   "kneeheightsitting against the leg's heights", err, errlen) < 0 ||
	    within(popl, HUMAN_LM_KNEE_DEPTH_LO, HUMAN_LM_POPLITEAL_HI, H,
		   "the popliteal below the knee's axis, seated",
		   "poplitealheight against the leg's heights", err, errlen) < 0 ||
	    within(butt, HUMAN_LM_BUTTOCK_LO, HUMAN_LM_BUTTOCK_HI, H,
		   "the buttocks behind the hip joint centres",
		   "buttockkneelength against the thigh and kneeheightsitting", err, errlen) < 0 ||
	    within(blade, HUMAN_LM_BLADE_LO, HUMAN_LM_BLADE_HI, H,
		   "the shoulder blades behind the shoulder joints", "thumbtipreach against the arm",
		   err, errlen) < 0 ||
	    within(troch - D->hx, 0.005, 0.15, H, "the trochanterion outside the hip joint centre",
		   "hipbreadth", err, errlen) < 0)
		return -1;

	double(*lm)[3] = L->lm;
	const double *gh = L->gh, *knee = L->knee, *hip = L->hip;
	double hx = D->hx, top = c7_height(L), hw, hd;
	vset(lm[HUMAN_LM_ACROMION], D->acromion[0], D->acromion[1], D->acromion[2]);
	vset(lm[HUMAN_LM_SHOULDER_BLADE], gh[0] - 0.05 * H, gh[1] - 0.04 * H, gh[2] - blade);
	vset(lm[HUMAN_LM_RADIALE_UPPER], gh[0] + HUMAN_LM_RADIALE_X * H, D->radiale_upper_y, 0);
	vset(lm[HUMAN_LM_RADIALE], gh[0] + HUMAN_LM_RADIALE_X * H, D->radiale_y, 0);
	vset(lm[HUMAN_LM_STYLION], gh[0], L->wrist[1], sz);
	vset(lm[HUMAN_LM_DACTYLION], gh[0], L->fingertip[1], 0);
	vset(lm[HUMAN_LM_THUMBTIP], gh[0], thumb_y, sz + HUMAN_LM_THUMB_Z * H);
	vset(lm[HUMAN_LM_TROCHANTERION], troch, hip[1], 0);
	vset(lm[HUMAN_LM_FEMORAL_EPICONDYLE], hx + HUMAN_LM_EPICONDYLE_X * H, knee[1], 0);
	vset(lm[HUMAN_LM_MIDPATELLA], hx, knee[1] + F->midpatella_y * H, supra);
	vset(lm[HUMAN_LM_SUPRAPATELLA], hx, knee[1] + HUMAN_LM_SUPRAPATELLA_Y * H, supra);
	/* the knee's front when bent square: on the thigh's axis, as far from the knee's as its top */
	vset(lm[HUMAN_LM_KNEE_FRONT], hx, knee[1] - supra, 0);
	vset(lm[HUMAN_LM_POPLITEAL], hx, knee[1], -popl);
	vset(lm[HUMAN_LM_TIBIALE], hx - HUMAN_LM_TIBIALE_X * H, knee[1] + F->tibiale_y * H, 0);
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

#undef within

/*
 * Lays out the figure in its standing rest posture: the ankle offset za is
 * solved so that the centre of mass lies above the balance references
 * (the centre of mass moves linearly with za: only the shanks and feet move).
 */
int
human_layout_make(const struct human_def *d, struct human_layout *L, char *err, size_t errlen)
{
	L->H = d->stature;
	L->M = d->mass;
	L->dl = d->sex == HUMAN_FEMALE ? &human_dl_female : &human_dl_male;
	L->k = L->H / L->dl->stature;
	double sum = 0;
	for (int s = 0; s < HUMAN_DL_N; s++)
		sum += L->dl->seg[s].mass * (s >= HUMAN_DL_UPPERARM ? 2 : 1);
	L->norm = 1 / sum;
	dims_default(L);
	if (d->measure_given) {
		struct human_dims_in in = { d->stature, d->mass, d->sex == HUMAN_FEMALE, d->measure,
					    d->measure_given, c7_height(L) };
		if (human_dims_measured(&in, &L->dim, err, errlen) < 0)
			return -1;
	}
	double c0[3], c1[3], dz = -0.05;
	lay_points(L, 0);
	lay_masses(L);
	human_layout_com(L, c0);
	lay_points(L, dz);
	lay_masses(L);
	human_layout_com(L, c1);
	double slope = (c1[2] - c0[2]) / dz, ahead = HUMAN_BALANCE_AHEAD * L->H;
	lay_points(L, (c0[2] - ahead) / (1 - slope));
	lay_masses(L);
	return landmarks_place(L, err, errlen);
}
