/*
 * human.c - the standard human figure from stature, mass and sex (§5.5.5,
 * Appendix D): 37 segments, 36 joints, 88 body dofs and 4 eye dofs.
 *
 * The figure is laid out in a "layout frame" (x left, y up, z forward, the
 * hip joint centres at z = 0) from stature fractions, then every segment
 * gets its origin at its proximal joint centre and every site and geom is
 * placed by the difference of layout points. All frames are parallel to the
 * world axes in the built posture, so that difference is the local
 * position. The right side is the left side mirrored (x -> -x).
 *
 * Sources (values and citations in human_data.c unless given here):
 *   de Leva (1996): segment masses, centres of mass, radii of gyration.
 *   Drillis & Contini (1966) in Winter (2009) Fig. 4.1: joint heights,
 *     limb lengths, hip, chest and foot breadths.
 *   Hara R, McGinley J, Briggs C, Baker R, Sangeux M (2016) Predicting the
 *     location of the hip joint centres, impact of age group and sex. Sci
 *     Rep 6:37707: hip joint centres 0.086 LL + 8 mm from the midline and
 *     0.078 LL + 9 mm below the anterior superior iliac spines (ASIS), LL =
 *     leg length ASIS to medial malleolus.
 *   Gray H, Anatomy of the Human Body (1918), II.3 "The vertebral column":
 *     lumbar part 18 cm, thoracic part 28 cm; used for the proportion of
 *     lumbar to thoracic levels between L5/S1 and C7/T1.
 *   Surface anatomy (e.g. Moore KL, Clinically Oriented Anatomy): the
 *     xiphisternal joint lies at T9, the umbilicus at the L3/L4 disc, which
 *     maps de Leva's trunk sub-segments onto vertebral levels.
 *   Carlsoo S (1972) How Man Moves ([20] in the spec): the line of gravity
 *     2-5 cm in front of the ankle joint in standing rest (§5.4.2.1).
 *   Dodgson NA (2004) Variation and extrema of human interpupillary
 *     distance, Proc SPIE 5291: adult mean 63 mm (0.036 H at 1.75 m).
 *   Bekerman I, Gottlieb P, Vaiman M (2014) Variations in eyeball diameters
 *     of the healthy adults, J Ophthalmol 2014:503645: ~24 mm diameter; with
 *     a density near water that is the usual 7.5 g eyeball mass.
 *   Anthropometric landmarks and the build from ANSUR II measures: their
 *     sources are in human_dims.c.
 * Documented assumptions (no single published value): L5/S1 at the height
 *   of the ASIS; the ankle joint above a point 1/4 of the foot length in
 *   front of the heel; the MTP joints 0.73 of the foot length from the heel
 *   (ANSUR ball-of-foot length / foot length); each clavicle (shoulder
 *   girdle) segment takes 5% of de Leva's upper trunk; the toes take the
 *   foot's mass in proportion to their box volume; the vertebral slices
 *   and the pelvis get elliptic-cylinder inertia from the torso outline;
 *   torso depths and limb radii are approximate stature fractions.
 */
#include "figure/human.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/human_data.h"

static void
vset(double dest[3], double x, double y, double z)
{
	dest[0] = x;
	dest[1] = y;
	dest[2] = z;
}

/* builder state: segment indices and origins, first error */
struct hb {
	struct model_builder *b;
	const struct human_layout *L;
	int seg[HUMAN_SEG_N];
	int failed;
};

static const float RGBA_SKIN[4] = { 0.87f, 0.70f, 0.58f, 1 };
static const float RGBA_SHIRT[4] = { 0.22f, 0.36f, 0.60f, 1 };
static const float RGBA_TROUSERS[4] = { 0.20f, 0.22f, 0.28f, 1 };
static const float RGBA_SHOES[4] = { 0.12f, 0.09f, 0.07f, 1 };
static const float RGBA_EYE[4] = { 0.96f, 0.96f, 0.94f, 1 };

static void
check(struct hb *h, int r)
{
	if (r < 0)
		h->failed = 1;
}

/* point p of the layout frame (left-side point, mirrored for side 1) */
static void
side_pt(const double p[3], int side, double dest[3])
{
	if (side)
		human_mirror(p, dest);
	else
		memcpy(dest, p, 3 * sizeof *dest);
}

/* the corners of a left-side box on side s */
static void
side_box(const double box[2][3], int s, double lo[3], double hi[3])
{
	memcpy(lo, box[0], 3 * sizeof *lo);
	memcpy(hi, box[1], 3 * sizeof *hi);
	if (s) {
		lo[0] = -box[1][0];
		hi[0] = -box[0][0];
	}
}

static void
add_segment(struct hb *h, int i, const char *name, const float rgba[4])
{
	const struct human_layout *L = h->L;
	struct segment_def sd = segment_default_def();
	sd.name = name;
	sd.mass = L->mass[i];
	for (int r = 0; r < 3; r++)
		sd.com[r] = L->com[i][r] - L->org[i][r];
	memcpy(sd.inertia, L->inertia[i], sizeof sd.inertia);
	memcpy(sd.rgba, rgba, sizeof sd.rgba);
	h->seg[i] = model_builder_segment(h->b, &sd);
	check(h, h->seg[i]);
	if (h->seg[i] < 0)
		return;
	double o[3] = { 0, 0, 0 }, q[4] = { 0, 0, 0, 1 };
	check(h, model_builder_site(h->b, h->seg[i], "origin", o, q));
}

/* a site at layout point p on segment i */
static int
add_site(struct hb *h, int i, const char *name, const double p[3])
{
	if (h->seg[i] < 0)
		return -1;
	double pos[3], q[4] = { 0, 0, 0, 1 };
	for (int r = 0; r < 3; r++)
		pos[r] = p[r] - h->L->org[i][r];
	int s = model_builder_site(h->b, h->seg[i], name, pos, q);
	check(h, s);
	return s;
}

/* a geom centred at layout point c, orientation q (NULL: identity) */
static void
add_geom(struct hb *h, int i, enum geom_kind kind, double s0, double s1, double s2,
	 const double c[3], const double q[4])
{
	if (h->seg[i] < 0)
		return;
	struct geom_def g = geom_default_def();
	g.kind = kind;
	vset(g.size, s0, s1, s2);
	for (int r = 0; r < 3; r++)
		g.pos[r] = c[r] - h->L->org[i][r];
	if (q)
		memcpy(g.quat, q, sizeof g.quat);
	check(h, model_builder_geom(h->b, h->seg[i], &g));
}

/* a capsule of radius rad whose straight part runs from a to b */
static void
add_capsule(struct hb *h, int i, const double a[3], const double b[3], double rad)
{
	double c[3], q[4], len = 0;
	for (int r = 0; r < 3; r++) {
		c[r] = (a[r] + b[r]) / 2;
		len += (b[r] - a[r]) * (b[r] - a[r]);
	}
	human_quat_y_to(a, b, q);
	add_geom(h, i, GEOM_CAPSULE, rad, sqrt(len), 0, c, q);
}

/* an ellipsoid around the fraction f of the way from a to b, aligned with a -> b */
static void
add_muscle(struct hb *h, int i, const double a[3], const double b[3], double f, double sx,
	   double sy, double sz)
{
	double c[3], q[4];
	for (int r = 0; r < 3; r++)
		c[r] = a[r] + f * (b[r] - a[r]);
	human_quat_y_to(a, b, q);
	add_geom(h, i, GEOM_ELLIPSOID, sx, sy, sz, c, q);
}

static void
add_box(struct hb *h, int i, const double lo[3], const double hi[3])
{
	double c[3];
	for (int r = 0; r < 3; r++)
		c[r] = (lo[r] + hi[r]) / 2;
	add_geom(h, i, GEOM_BOX, hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], c, NULL);
}

static void
build_trunk(struct hb *h)
{
	const struct human_layout *L = h->L;
	double H = L->H, p[3], hw, hd;
	add_segment(h, HUMAN_SEG_PELVIS, "pelvis", RGBA_TROUSERS);
	vset(p, 0, L->hip[1], 0);
	add_site(h, HUMAN_SEG_PELVIS, "root", p);
	vset(p, 0, (L->hip[1] + L->spine[0][1]) / 2, 0);
	add_site(h, HUMAN_SEG_PELVIS, "center", p);
	add_site(h, HUMAN_SEG_PELVIS, "spine_0", L->spine[0]);
	for (int s = 0; s < 2; s++) {
		char name[16];
		snprintf(name, sizeof name, "hip%s", human_side_sfx[s]);
		side_pt(L->hip, s, p);
		add_site(h, HUMAN_SEG_PELVIS, name, p);
	}
	human_torso_semi(L, L->hip[1], &hw, &hd);
	vset(p, 0, L->hip[1] + 0.015 * H, 0);
	add_geom(h, HUMAN_SEG_PELVIS, GEOM_ELLIPSOID, hw, 0.055 * H, hd, p, NULL);

	for (int k = 0; k < HUMAN_NSLICE; k++) {
		int i = HUMAN_SEG_SLICE0 + k;
		char name[16];
		add_segment(h, i, human_slice_name[k], k < 1 ? RGBA_TROUSERS : RGBA_SHIRT);
		snprintf(name, sizeof name, "spine_%d", k + 1);
		add_site(h, i, name, L->spine[k + 1]);
		double y0 = L->spine[k][1], y1 = L->spine[k + 1][1];
		vset(p, 0, (y0 + y1) / 2, 0);
		if (k == HUMAN_SLICE_CHEST)
			add_site(h, i, "chest", p);
		/* one flattened ellipsoid per slice, tall enough that neighbours
		 * blend into one smooth torso rather than a stack of rings (the
		 * outermost slices less, so that they stay inside the outline) */
		human_torso_semi(L, p[1], &hw, &hd);
		double reach = k == 0 || k == HUMAN_NSLICE - 1 ? 1.5 : 3.0;
		add_geom(h, i, GEOM_ELLIPSOID, hw, reach * (y1 - y0), hd, p, NULL);
	}
	for (int s = 0; s < 2; s++) {
		char name[16];
		snprintf(name, sizeof name, "clavicle%s", human_side_sfx[s]);
		side_pt(L->sc, s, p);
		add_site(h, HUMAN_SEG_SLICE0 + HUMAN_NSLICE - 1, name, p);
	}
}

static void
build_head(struct hb *h)
{
	const struct human_layout *L = h->L;
	double H = L->H, p[3], q[3];
	add_segment(h, HUMAN_SEG_HEAD, "head", RGBA_SKIN);
	vset(p, 0, L->eye[1], L->eye[2]);
	add_site(h, HUMAN_SEG_HEAD, "between_eyes", p);
	vset(p, 0, H, L->head_c[2]);
	add_site(h, HUMAN_SEG_HEAD, "vertex", p);
	add_geom(h, HUMAN_SEG_HEAD, GEOM_ELLIPSOID, L->head_semi[0], L->head_semi[1], L->head_semi[2],
		 L->head_c, NULL);
	vset(q, 0, 0.905 * H, 0);
	add_capsule(h, HUMAN_SEG_HEAD, L->spine[HUMAN_NSLICE], q, 0.030 * H);
	/* a nose, so that the face reads as a face from any side */
	vset(p, 0, L->eye[1] - 0.016 * H, L->head_c[2] + 0.97 * L->head_semi[2]);
	add_geom(h, HUMAN_SEG_HEAD, GEOM_ELLIPSOID, 0.008 * H, 0.014 * H, 0.010 * H, p, NULL);
	for (int s = 0; s < 2; s++) {
		char name[16];
		int i = HUMAN_SEG_EYE + s;
		snprintf(name, sizeof name, "eye%s", human_side_sfx[s]);
		side_pt(L->eye, s, p);
		add_site(h, HUMAN_SEG_HEAD, name, p);
		snprintf(name, sizeof name, "eyeball%s", human_side_sfx[s]);
		add_segment(h, i, name, RGBA_EYE);
		add_site(h, i, "gaze", p);
		add_geom(h, i, GEOM_ELLIPSOID, L->eye_r, L->eye_r, L->eye_r, p, NULL);
	}
}

static void
build_limbs(struct hb *h, int s)
{
	const struct human_layout *L = h->L;
	double H = L->H, hip[3], knee[3], ankle[3], mtp[3], sc[3], gh[3], elb[3], wri[3], tip[3];
	double p[3], q[3], lo[3], hi[3];
	side_pt(L->hip, s, hip);
	side_pt(L->knee, s, knee);
	side_pt(L->ankle, s, ankle);
	side_pt(L->mtp, s, mtp);
	side_pt(L->sc, s, sc);
	side_pt(L->gh, s, gh);
	side_pt(L->elbow, s, elb);
	side_pt(L->wrist, s, wri);
	side_pt(L->fingertip, s, tip);
	int b = HUMAN_SEG_LIMB + HUMAN_LIMB_N * s;
	double sx = s ? -1 : 1; /* towards the figure's left on this side */
	char name[24];
	static const float *const rgba[HUMAN_LIMB_N] = { RGBA_TROUSERS, RGBA_TROUSERS, RGBA_SHOES,
						   RGBA_SHOES, RGBA_SHIRT, RGBA_SHIRT,
						   RGBA_SKIN, RGBA_SKIN };
	for (int l = 0; l < HUMAN_LIMB_N; l++) {
		snprintf(name, sizeof name, "%s%s", human_limb_name[l], human_side_sfx[s]);
		add_segment(h, b + l, name, rgba[l]);
	}
#define SITE(l, nm, pt)                                                   \
	do {                                                              \
		snprintf(name, sizeof name, "%s%s", nm, human_side_sfx[s]);     \
		add_site(h, b + (l), name, pt);                           \
	} while (0)
	/* thigh: tapering from the buttock to the knee */
	SITE(HUMAN_LIMB_THIGH, "knee", knee);
	add_capsule(h, b + HUMAN_LIMB_THIGH, hip, knee, 0.033 * H);
	add_muscle(h, b + HUMAN_LIMB_THIGH, hip, knee, 0.40, 0.050 * H, 0.55 * (hip[1] - knee[1]),
		   0.052 * H);
	/* shank: calf muscle behind the upper half */
	vset(p, knee[0], knee[1], 0.030 * H);
	add_site(h, b + HUMAN_LIMB_SHANK, "knee", p);
	SITE(HUMAN_LIMB_SHANK, "ankle", ankle);
	add_capsule(h, b + HUMAN_LIMB_SHANK, knee, ankle, 0.022 * H);
	double calf[3] = { knee[0], knee[1], -0.008 * H }, ank_back[3] = { ankle[0], ankle[1],
									  ankle[2] - 0.008 * H };
	add_muscle(h, b + HUMAN_LIMB_SHANK, calf, ank_back, 0.30, 0.034 * H, 0.36 * (knee[1] - ankle[1]),
		   0.036 * H);
	/* foot and toes: boxes standing on the floor */
	add_site(h, b + HUMAN_LIMB_FOOT, "ankle", ankle);
	side_pt(L->heel, s, p);
	add_site(h, b + HUMAN_LIMB_FOOT, "heel", p);
	side_pt(L->balance, s, p);
	add_site(h, b + HUMAN_LIMB_FOOT, "balance", p);
	SITE(HUMAN_LIMB_FOOT, "toe", mtp);
	side_box(L->foot_box, s, lo, hi);
	add_box(h, b + HUMAN_LIMB_FOOT, lo, hi);
	vset(p, mtp[0], 0, mtp[2]);
	add_site(h, b + HUMAN_LIMB_TOES, "toe", p);
	side_pt(L->tip, s, p);
	add_site(h, b + HUMAN_LIMB_TOES, "tip", p);
	side_box(L->toes_box, s, lo, hi);
	add_box(h, b + HUMAN_LIMB_TOES, lo, hi);
	/* clavicle: the bone and the shoulder's top (trapezius to acromion) */
	SITE(HUMAN_LIMB_CLAVICLE, "shoulder", gh);
	add_capsule(h, b + HUMAN_LIMB_CLAVICLE, sc, gh, 0.008 * H);
	double dx = fabs(gh[0] - sc[0]);
	vset(p, sc[0] + 0.55 * (gh[0] - sc[0]), gh[1] + 0.012 * H, gh[2] + 0.004 * H);
	add_geom(h, b + HUMAN_LIMB_CLAVICLE, GEOM_ELLIPSOID, 0.5 * dx + 0.01 * H, 0.024 * H,
		 0.040 * H, p, NULL);
	/* upper arm: deltoid and biceps over the humerus */
	SITE(HUMAN_LIMB_UPPERARM, "elbow", elb);
	add_site(h, b + HUMAN_LIMB_UPPERARM, "elbow", elb);
	add_capsule(h, b + HUMAN_LIMB_UPPERARM, gh, elb, 0.024 * H);
	add_muscle(h, b + HUMAN_LIMB_UPPERARM, gh, elb, 0.35, 0.031 * H, 0.45 * (gh[1] - elb[1]),
		   0.032 * H);
	/* forearm: flexor mass below the elbow */
	SITE(HUMAN_LIMB_FOREARM, "wrist", wri);
	vset(p, wri[0], wri[1] + 0.01 * H, wri[2]);
	add_site(h, b + HUMAN_LIMB_FOREARM, "wrist_ref", p);
	add_capsule(h, b + HUMAN_LIMB_FOREARM, elb, wri, 0.017 * H);
	add_muscle(h, b + HUMAN_LIMB_FOREARM, elb, wri, 0.30, 0.025 * H, 0.40 * (elb[1] - wri[1]),
		   0.027 * H);
	/* hand: palm facing the thigh (-x on the left), thumb forward */
	vset(p, wri[0], wri[1] - 0.030 * H, wri[2]);
	add_site(h, b + HUMAN_LIMB_HAND, "palm", p);
	add_site(h, b + HUMAN_LIMB_HAND, "fingertip", tip);
	vset(lo, wri[0] - 0.0085 * H, wri[1] - 0.055 * H, wri[2] - 0.024 * H);
	vset(hi, wri[0] + 0.0085 * H, wri[1], wri[2] + 0.024 * H);
	add_box(h, b + HUMAN_LIMB_HAND, lo, hi);
	vset(lo, wri[0] - 0.006 * H, tip[1], wri[2] - 0.021 * H);
	vset(hi, wri[0] + 0.006 * H, wri[1] - 0.050 * H, wri[2] + 0.021 * H);
	add_box(h, b + HUMAN_LIMB_HAND, lo, hi);
	vset(p, wri[0] - sx * 0.004 * H, wri[1] - 0.020 * H, wri[2] + 0.022 * H);
	vset(q, wri[0] - sx * 0.005 * H, wri[1] - 0.058 * H, wri[2] + 0.030 * H);
	add_capsule(h, b + HUMAN_LIMB_HAND, p, q, 0.007 * H);
#undef SITE
}

/* the anthropometric landmarks (human_dims.c placed them), after each segment's other sites */
static void
build_landmarks(struct hb *h)
{
	static const int limb[] = {
		[HUMAN_LM_THIGH] = HUMAN_LIMB_THIGH,       [HUMAN_LM_SHANK] = HUMAN_LIMB_SHANK,
		[HUMAN_LM_FOOT] = HUMAN_LIMB_FOOT,         [HUMAN_LM_TOES] = HUMAN_LIMB_TOES,
		[HUMAN_LM_CLAVICLE] = HUMAN_LIMB_CLAVICLE, [HUMAN_LM_UPPERARM] = HUMAN_LIMB_UPPERARM,
		[HUMAN_LM_FOREARM] = HUMAN_LIMB_FOREARM,   [HUMAN_LM_HAND] = HUMAN_LIMB_HAND,
	};
	for (int i = 0; i < HUMAN_LM_N; i++) {
		const struct human_landmark_info *lm = &human_landmark_info[i];
		for (int s = 0; s < (lm->bilateral ? 2 : 1); s++) {
			int seg;
			char name[MODEL_NAME_MAX];
			if (lm->seg == HUMAN_LM_PELVIS)
				seg = HUMAN_SEG_PELVIS;
			else if (lm->seg == HUMAN_LM_T1)
				seg = HUMAN_SEG_SLICE0 + HUMAN_NSLICE - 1;
			else if (lm->seg == HUMAN_LM_HEAD)
				seg = HUMAN_SEG_HEAD;
			else
				seg = HUMAN_SEG_LIMB + HUMAN_LIMB_N * s + limb[lm->seg];
			/* a limb segment is one side's: its sites need no suffix */
			int suffix = lm->bilateral && lm->seg < HUMAN_LM_THIGH;
			snprintf(name, sizeof name, "%s%s", lm->name, suffix ? human_side_sfx[s] : "");
			double p[3];
			side_pt(h->L->lm[i], s, p);
			add_site(h, seg, name, p);
		}
	}
}

/* adds joint `name` from site `from` (segment.site) to segment `to_seg`'s origin */
static void
add_joint(struct hb *h, const char *name, const char *from_seg, const char *from_site,
	  int to_seg, int ndof, const struct dof_def *dof)
{
	int fs = model_builder_find_segment(h->b, from_seg);
	int from = fs < 0 ? -1 : model_builder_find_site(h->b, fs, from_site);
	int to = h->seg[to_seg] < 0 ? -1 : model_builder_find_site(h->b, h->seg[to_seg], "origin");
	if (from < 0 || to < 0) {
		h->failed = 1;
		return;
	}
	struct joint_def jd = joint_default_def();
	jd.name = name;
	jd.site_from = from;
	jd.site_to = to;
	jd.ndof = ndof;
	memcpy(jd.dof, dof, (size_t)ndof * sizeof *dof);
	check(h, model_builder_joint(h->b, &jd));
}

static struct dof_def
rot_dof(int axis, int sign, double lo_deg, double hi_deg)
{
	struct dof_def d = { DOF_ROTATION, axis, sign, lo_deg * M_PI / 180, hi_deg * M_PI / 180, 0 };
	return d;
}

static void
build_joints(struct hb *h)
{
	char name[24], from[24];
	struct dof_def dof[3];
	/* spine: flexion about +x, left bend about -z, left turn about +y */
	for (int k = 0; k <= HUMAN_NSLICE; k++) {
		double fl, ex, lat, rot;
		if (k < HUMAN_NSLICE) {
			const struct human_spine_rom *r = &human_spine_rom[k];
			fl = r->flex_ext * human_spine_flex_share;
			ex = r->flex_ext - fl;
			lat = r->lat;
			rot = r->rot;
		} else {
			fl = human_neck_flex, ex = human_neck_ext;
			lat = human_neck_lat, rot = human_neck_rot;
		}
		dof[0] = rot_dof(0, 1, -ex, fl);
		dof[1] = rot_dof(2, -1, -lat, lat);
		dof[2] = rot_dof(1, 1, -rot, rot);
		snprintf(name, sizeof name, "spine_%d", k);
		add_joint(h, name, k == 0 ? "pelvis" : human_slice_name[k - 1], name,
			  k == HUMAN_NSLICE ? HUMAN_SEG_HEAD : HUMAN_SEG_SLICE0 + k, 3, dof);
	}
	/* limbs, then the eyes last so the first 88 dofs are the body's */
	static const struct {
		int spec, limb;
		const char *from_seg; /* NULL: the limb segment before */
	} lj[] = {
		{ HUMAN_LJ_HIP, HUMAN_LIMB_THIGH, "pelvis" },   { HUMAN_LJ_KNEE, HUMAN_LIMB_SHANK, NULL },
		{ HUMAN_LJ_ANKLE, HUMAN_LIMB_FOOT, NULL },      { HUMAN_LJ_TOE, HUMAN_LIMB_TOES, NULL },
		{ HUMAN_LJ_CLAVICLE, HUMAN_LIMB_CLAVICLE, "T1" }, { HUMAN_LJ_SHOULDER, HUMAN_LIMB_UPPERARM, NULL },
		{ HUMAN_LJ_ELBOW, HUMAN_LIMB_FOREARM, NULL },   { HUMAN_LJ_WRIST, HUMAN_LIMB_HAND, NULL },
	};
	for (int s = 0; s < 3 * 2; s++) {
		int side = s % 2, eyes = s >= 4;
		if (s >= 2 && !eyes)
			continue;
		int n = eyes ? 1 : (int)(sizeof lj / sizeof lj[0]);
		for (int j = 0; j < n; j++) {
			const struct human_joint_spec *sp =
				&human_limb_joints[eyes ? HUMAN_LJ_EYE : lj[j].spec];
			for (int d = 0; d < sp->ndof; d++) {
				const struct human_dof_spec *ds = &sp->dof[d];
				int sign = side && ds->axis != 0 ? -ds->sign : ds->sign;
				dof[d] = rot_dof(ds->axis, sign, ds->lo, ds->hi);
			}
			snprintf(name, sizeof name, "%s%s", sp->name, human_side_sfx[side]);
			int to = eyes ? HUMAN_SEG_EYE + side : HUMAN_SEG_LIMB + HUMAN_LIMB_N * side + lj[j].limb;
			if (eyes)
				snprintf(from, sizeof from, "head");
			else if (lj[j].from_seg)
				snprintf(from, sizeof from, "%s", lj[j].from_seg);
			else
				snprintf(from, sizeof from, "%s%s", human_limb_name[lj[j].limb - 1],
					 human_side_sfx[side]);
			add_joint(h, name, from, name, to, sp->ndof, dof);
		}
	}
}

struct human_def
human_default_def(enum human_sex sex)
{
	struct human_def d = { .stature = 1.75, .mass = 75.0, .sex = HUMAN_MALE };
	if (sex == HUMAN_FEMALE) {
		d.stature = 1.628;
		d.mass = 67.7;
		d.sex = HUMAN_FEMALE;
	}
	return d;
}

/* NULL, with the message (a format with one number) in err */
static struct model *
reject(char *err, size_t errlen, const char *fmt, double v)
{
	if (err && errlen)
		snprintf(err, errlen, fmt, v);
	return NULL;
}

static struct model *
reject_msg(char *err, size_t errlen, const char *msg)
{
	if (err && errlen)
		snprintf(err, errlen, "%s", msg);
	return NULL;
}

static struct model *
build(const struct human_def *d, int landmarks, char *err, size_t errlen)
{
	if (!d)
		return reject_msg(err, errlen, "human: no definition");
	/* written so NaN fails too */
	if (!(d->stature >= HUMAN_STATURE_MIN && d->stature <= HUMAN_STATURE_MAX))
		return reject(err, errlen, "human: stature %g m is outside [1.0, 2.5] m", d->stature);
	if (!(d->mass >= HUMAN_MASS_MIN && d->mass <= HUMAN_MASS_MAX))
		return reject(err, errlen, "human: body mass %g kg is outside [20, 300] kg", d->mass);
	if (d->sex != HUMAN_MALE && d->sex != HUMAN_FEMALE)
		return reject(err, errlen, "human: unknown sex %g", (double)d->sex);

	static struct human_layout L_zero;
	struct human_layout *L = malloc(sizeof *L);
	if (!L)
		return reject_msg(err, errlen, "human: out of memory");
	*L = L_zero;
	if (human_layout_make(d, L, err, errlen) < 0) {
		free(L);
		return NULL;
	}
	struct hb h = { model_builder_create(d->sex == HUMAN_FEMALE ? "human_female" : "human_male"),
			L, { 0 }, 0 };
	if (!h.b) {
		free(L);
		return reject_msg(err, errlen, "human: out of memory");
	}
	for (int i = 0; i < HUMAN_SEG_N; i++)
		h.seg[i] = -1;

	/* segments with their sites and geometry, then the joints */
	build_trunk(&h);
	build_head(&h);
	build_limbs(&h, 0);
	build_limbs(&h, 1);
	if (landmarks)
		build_landmarks(&h);
	build_joints(&h);
	double com[3];
	human_layout_com(L, com);
	add_site(&h, HUMAN_SEG_PELVIS, "lower_torso", com);

	/* root: the balance references' midpoint at the world origin */
	double pos[3] = { 0, L->hip[1], -(L->za + HUMAN_BALANCE_AHEAD * L->H) }, q[4] = { 0, 0, 0, 1 };
	struct model *m = NULL;
	if (!h.failed) {
		int root = model_builder_find_site(h.b, h.seg[HUMAN_SEG_PELVIS], "root");
		if (model_builder_root(h.b, root, pos, q) == 0)
			m = model_builder_finish(h.b);
	}
	if (!m && err && errlen)
		snprintf(err, errlen, "human: %s", model_builder_error(h.b));
	model_builder_free(h.b);
	free(L);
	return m;
}

struct model *
human_build(const struct human_def *d, char *err, size_t errlen)
{
	return build(d, d && d->measure_given, err, errlen);
}

struct model *
human_build_landmarked(const struct human_def *d, char *err, size_t errlen)
{
	return build(d, 1, err, errlen);
}
