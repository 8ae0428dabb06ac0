/*
 * body_angles.c - the angles RULA, REBA and OWAS score, measured on a human
 * figure's global frames and sites (body_angles.h).
 *
 * The methods are observational and define no coordinate frames; the
 * choices here follow the open implementations where they agree
 * (pyergonomics' body planes: up from the pelvis to the neck, the coronal
 * plane through the hip line, the trunk's bend against world vertical in
 * the vertical planes so made; ignc-research's trunk against a gravity
 * vector; the elbow as 180 deg less the angle at its joint centre) and the
 * human's own joint conventions (figure/human.h) elsewhere, so that a
 * single joint moved from the built posture reads back its value. Where a
 * method's plane projection is singular (the arm abducted to the side), a
 * decomposition without that singularity is used (upper_arm below).
 *
 * The right side is measured as the mirror image of the left: relative
 * rotations are conjugated by the reflection x -> -x, which turns the right
 * limb's joint axes into the left's (rotations about y and z change sign,
 * as the human mirrors them), and the left's formulas apply.
 */
#include "assess/body_angles.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "figure/mathx.h"
#include "pose/balance.h"

#define DEG (180.0 / M_PI)

/* the segments and sites measured, found by name for each figure */
struct body_sites {
	int pelvis, l5, t1, head;
	int thigh[2], shank[2], foot[2], toes[2];
	int clavicle[2], upperarm[2], forearm[2], hand[2];
	int palm[2], knee_front[2];
	int pronation_dof[2]; /* the wrist's third dof, for its range */
};

/*
 * segment `name`, tried first at `guess`, its index in the human as
 * human_build makes it (human.h lists the order), so that the built human
 * costs one comparison a segment; any other order is searched
 */
static int
find_segment(const struct model *m, const char *name, int guess)
{
	if (guess < m->nseg && !strcmp(m->seg_name[guess], name))
		return guess;
	return model_find_segment(m, name);
}

static int
find_site_on(const struct model *m, int seg, const char *name)
{
	if (seg < 0)
		return -1;
	for (int i = m->seg_site0[seg]; i < m->seg_site0[seg] + m->seg_nsite[seg]; i++)
		if (!strcmp(m->site_name[i], name))
			return i;
	return -1;
}

static int
fail(char *err, size_t errlen, const char *what, const char *name)
{
	if (err && errlen)
		snprintf(err, errlen,
			 "body angles: the figure has no %s '%s' (only a human figure is assessed)",
			 what, name);
	return -1;
}

static int
sites_find(const struct model *m, struct body_sites *d, char *err, size_t errlen)
{
	static const char *const side_sfx[2] = { "_l", "_r" };
	char name[MODEL_NAME_MAX];
	/* the built human: pelvis, L5 .. T1, head, two eyeballs, then eight limb segments a side */
	struct {
		int *dest;
		const char *name;
		int guess;
	} trunk[] = {
		{ &d->pelvis, "pelvis", 0 },
		{ &d->l5, "L5", 1 },
		{ &d->t1, "T1", 17 },
		{ &d->head, "head", 18 },
	};
	for (size_t i = 0; i < sizeof trunk / sizeof trunk[0]; i++)
		if ((*trunk[i].dest = find_segment(m, trunk[i].name, trunk[i].guess)) < 0)
			return fail(err, errlen, "segment", trunk[i].name);
	for (int s = 0; s < 2; s++) {
		struct {
			int *dest;
			const char *name;
		} limb[] = {
			{ &d->thigh[s], "thigh" },       { &d->shank[s], "shank" },
			{ &d->foot[s], "foot" },         { &d->toes[s], "toes" },
			{ &d->clavicle[s], "clavicle" }, { &d->upperarm[s], "upperarm" },
			{ &d->forearm[s], "forearm" },   { &d->hand[s], "hand" },
		};
		for (int l = 0; l < 8; l++) {
			snprintf(name, sizeof name, "%s%s", limb[l].name, side_sfx[s]);
			if ((*limb[l].dest = find_segment(m, name, 21 + 8 * s + l)) < 0)
				return fail(err, errlen, "segment", name);
		}
		if ((d->palm[s] = find_site_on(m, d->hand[s], "palm")) < 0)
			return fail(err, errlen, "site", s ? "hand_r.palm" : "hand_l.palm");
		if ((d->knee_front[s] = find_site_on(m, d->thigh[s], "knee_front")) < 0)
			return fail(err, errlen, "site", s ? "thigh_r.knee_front" : "thigh_l.knee_front");
		snprintf(name, sizeof name, "wrist%s", side_sfx[s]);
		int j = 25 + 8 * s;
		if (j >= m->njnt || strcmp(m->jnt_name[j], name))
			j = model_find_joint(m, name);
		if (j < 0 || m->jnt_ndof[j] != 3)
			return fail(err, errlen, "3-dof joint", name);
		d->pronation_dof[s] = m->jnt_dof0[j] + 2;
	}
	return 0;
}

static void
sub(const double a[3], const double b[3], double dest[3])
{
	for (int i = 0; i < 3; i++)
		dest[i] = a[i] - b[i];
}

static double
norm(const double v[3])
{
	return sqrt(mathx_dot(v, v));
}

/* v scaled to unit length; 0 when it has none */
static double
unit(double v[3])
{
	double n = norm(v);
	if (n > 0)
		for (int i = 0; i < 3; i++)
			v[i] /= n;
	return n;
}

static double
clamp1(double x)
{
	return x > 1 ? 1 : x < -1 ? -1 : x;
}

/* angle between a and b, 0..180 deg */
static double
angle_between(const double a[3], const double b[3])
{
	double c[3];
	mathx_cross(a, b, c);
	return atan2(norm(c), mathx_dot(a, b)) * DEG;
}

/* v (world) in frame f's axes */
static void
to_frame(const struct xform *f, const double v[3], double dest[3])
{
	double t[3];
	for (int i = 0; i < 3; i++)
		t[i] = f->r[i] * v[0] + f->r[3 + i] * v[1] + f->r[6 + i] * v[2];
	memcpy(dest, t, sizeof t);
}

/* column k of a row-major rotation: the frame's axis k in the parent's coordinates */
static void
axis_of(const double r[9], int k, double dest[3])
{
	dest[0] = r[k], dest[1] = r[3 + k], dest[2] = r[6 + k];
}

/*
 * the rotation of segment b's frame in segment a's, for side `side`:
 * the right side's reflected into the left's (see the opening comment)
 */
static void
relative(const struct state *s, int a, int b, int side, double dest[9])
{
	mathx_mat3_tmul(s->seg_xf[a].r, s->seg_xf[b].r, dest);
	if (side == BODY_RIGHT) {
		/* S R S with S = diag(-1, 1, 1): the signs of row 0 and column 0 flip */
		dest[1] = -dest[1], dest[2] = -dest[2];
		dest[3] = -dest[3], dest[6] = -dest[6];
	}
}

/* the angle of a rotation about +y, or about -y when sign is -1, from its matrix */
static double
about_y(const double r[9], int sign)
{
	return sign * atan2(r[2] - r[6], r[0] + r[8]);
}

/*
 * The upper arm in the thorax (r: the upper arm's frame in T1's, left
 * side). Its long axis u (the frame's -y, shoulder to elbow) is reached
 * from the hanging arm (-y) by the swing of angle e, the elevation, about
 * the unit axis k = (-y x u) / |-y x u| = (-u_z, 0, u_x) / rho. That swing's
 * rotation vector e k has the component e u_z / rho about -x, the
 * shoulder's flexion axis, and e u_x / rho about +z, its abduction axis:
 * flexion e sin(p), abduction e cos(p) for the plane of elevation p
 * (0 = the coronal plane). What is left of r after the swing is a turn
 * about the arm's own axis: the axial rotation (internal = about -y).
 */
static void
upper_arm(const double r[9], struct body_arm *dest)
{
	double u[3] = { -r[1], -r[4], -r[7] };
	double rho = sqrt(u[0] * u[0] + u[2] * u[2]);
	double e = atan2(rho, -u[1]);
	double k[3];
	if (rho > 1e-9) {
		k[0] = -u[2] / rho, k[1] = 0, k[2] = u[0] / rho;
	} else {
		/* hanging: no swing; straight up: taken as reached by flexion */
		k[0] = -1, k[1] = 0, k[2] = 0;
	}
	dest->upper_arm_flexion = -e * k[0] * DEG;
	dest->upper_arm_abduction = e * k[2] * DEG;
	/* the swing's matrix (Rodrigues), then the twist t = swing^T r about y */
	double c = cos(e), sn = sin(e), v = 1 - c;
	double sw[9] = {
		c + v * k[0] * k[0],        v * k[0] * k[1] - sn * k[2], v * k[0] * k[2] + sn * k[1],
		v * k[1] * k[0] + sn * k[2], c + v * k[1] * k[1],        v * k[1] * k[2] - sn * k[0],
		v * k[2] * k[0] - sn * k[1], v * k[2] * k[1] + sn * k[0], c + v * k[2] * k[2],
	};
	double t[9];
	mathx_mat3_tmul(sw, r, t);
	dest->upper_arm_rotation = about_y(t, -1) * DEG;
}

/*
 * The hand in the forearm (r, left side), as the wrist's anatomy orders
 * it: pronation about the forearm's long axis (-y) first, then flexion
 * towards the palm (about -z) and radial deviation (about -x) in the
 * pronated frame. The forearm's axis seen from the hand, b = r^T (0,-1,0),
 * is (sin f, -cos f cos d, -cos f sin d) whatever the pronation, which
 * gives f and d; the pronation is what remains about -y. The human's own
 * wrist applies pronation last; the two orders agree whenever one of the
 * three is zero, and the one here keeps flexion towards the palm however
 * far the forearm is turned.
 */
static void
wrist(const double r[9], double *flex, double *dev, double *pron)
{
	double b[3] = { -r[3], -r[4], -r[5] };
	double f = asin(clamp1(b[0])), d = atan2(-b[2], -b[1]);
	struct xform rd, rf;
	xform_elementary(0, 0, -1, -d, &rd);
	xform_elementary(0, 2, -1, -f, &rf);
	double m[9];
	mathx_mat3_mul(r, rd.r, m);
	mathx_mat3_mul(m, rf.r, m);
	*flex = f * DEG;
	*dev = d * DEG;
	*pron = about_y(m, -1) * DEG;
}

/*
 * The head in the thorax (r), in the spine's dof order (human.h): flexion
 * (about +x) of the head's up axis n in the sagittal plane, lateral bend
 * (about -z) out of it, then axial rotation (about +y, + turning left).
 */
static void
neck(const double r[9], struct body_angles *dest)
{
	double n[3];
	axis_of(r, 1, n);
	double f = atan2(n[2], n[1]), b = asin(clamp1(n[0]));
	struct xform rb, rf;
	xform_elementary(0, 2, -1, -b, &rb);
	xform_elementary(0, 0, 1, -f, &rf);
	double m[9];
	mathx_mat3_mul(rb.r, rf.r, m);
	mathx_mat3_mul(m, r, m);
	dest->neck_flexion = f * DEG;
	dest->neck_side_bend = b * DEG;
	dest->neck_twist = about_y(m, 1) * DEG;
}

/*
 * The body's horizontal axes: lat along the hip line (right to left hip),
 * fwd = lat x up the way the pelvis faces. A hip line that stands vertical
 * (lying on one side) has no horizontal direction: the pelvis's forward
 * axis gives it then.
 */
static void
body_axes(const struct state *s, const struct body_sites *bs, double lat[3], double fwd[3])
{
	sub(s->seg_xf[bs->thigh[BODY_LEFT]].p, s->seg_xf[bs->thigh[BODY_RIGHT]].p, lat);
	lat[1] = 0;
	if (unit(lat) < 1e-6) {
		double f[3];
		axis_of(s->seg_xf[bs->pelvis].r, 2, f);
		f[1] = 0;
		unit(f);
		lat[0] = f[2], lat[1] = 0, lat[2] = -f[0];
	}
	fwd[0] = -lat[2], fwd[1] = 0, fwd[2] = lat[0];
}

static void
trunk(const struct state *s, const struct body_sites *bs, struct body_angles *dest)
{
	static const double up[3] = { 0, 1, 0 };
	double lat[3], fwd[3], t[3];
	body_axes(s, bs, lat, fwd);
	sub(s->seg_xf[bs->head].p, s->seg_xf[bs->l5].p, t);
	unit(t);
	dest->trunk_flexion = atan2(mathx_dot(t, fwd), mathx_dot(t, up)) * DEG;
	dest->trunk_side_bend = asin(clamp1(mathx_dot(t, lat))) * DEG;

	/* twist: the thorax's left-right axis against the hip line, both seen down the trunk axis */
	double h[3], sh[3], c[3];
	sub(s->seg_xf[bs->thigh[BODY_LEFT]].p, s->seg_xf[bs->thigh[BODY_RIGHT]].p, h);
	axis_of(s->seg_xf[bs->t1].r, 0, sh);
	double kh = mathx_dot(h, t), ks = mathx_dot(sh, t);
	for (int i = 0; i < 3; i++)
		h[i] -= kh * t[i], sh[i] -= ks * t[i];
	mathx_cross(h, sh, c);
	dest->trunk_twist = atan2(mathx_dot(c, t), mathx_dot(h, sh)) * DEG;

	/* hip-trunk: the trunk axis against the mean of the thighs' (hip to knee) directions */
	double th[3] = { 0, 0, 0 };
	for (int side = 0; side < 2; side++) {
		double d[3];
		sub(s->seg_xf[bs->shank[side]].p, s->seg_xf[bs->thigh[side]].p, d);
		unit(d);
		for (int i = 0; i < 3; i++)
			th[i] += d[i];
	}
	unit(th);
	dest->hip_trunk_angle = angle_between(t, th);
}

static void
arm(const struct model *m, const struct state *s, const struct body_sites *bs, int side,
    struct body_arm *dest)
{
	double r[9];
	relative(s, bs->t1, bs->upperarm[side], side, r);
	upper_arm(r, dest);

	/* the clavicle's lateral axis (x, mirrored) above the thorax's x-z plane */
	relative(s, bs->t1, bs->clavicle[side], side, r);
	dest->shoulder_elevation = asin(clamp1(r[3])) * DEG;

	/* elbow: 180 - the angle shoulder-elbow-wrist at the joint centres */
	const double *gh = s->seg_xf[bs->upperarm[side]].p, *el = s->seg_xf[bs->forearm[side]].p;
	const double *wr = s->seg_xf[bs->hand[side]].p;
	double a[3], b[3];
	sub(el, gh, a);
	sub(wr, el, b);
	dest->elbow_flexion = angle_between(a, b);

	relative(s, bs->forearm[side], bs->hand[side], side, r);
	wrist(r, &dest->wrist_flexion, &dest->wrist_deviation, &dest->wrist_twist);
	int pd = bs->pronation_dof[side];
	double end = (dest->wrist_twist >= 0 ? m->dof_hi[pd] : -m->dof_lo[pd]) * DEG;
	dest->wrist_twist_fraction = end > 0 ? fabs(dest->wrist_twist) / end : 1;

	/*
	 * the palm against the thorax's midsagittal plane (through C7/T1,
	 * across T1's left-right axis) and the shoulder; heights against world
	 * vertical, as "at or above shoulder level" means
	 */
	double x[3], p[3];
	axis_of(s->seg_xf[bs->t1].r, 0, x);
	double out = side == BODY_LEFT ? 1 : -1; /* the side's outward direction along x */
	const double *palm = s->site_xf[bs->palm[side]].p;
	sub(palm, s->seg_xf[bs->head].p, p);
	dest->hand_across_midline = -out * mathx_dot(p, x);
	sub(palm, gh, p);
	dest->hand_out_to_side = out * mathx_dot(p, x);
	dest->elbow_above_shoulder = el[1] - gh[1];
	dest->hand_above_shoulder = palm[1] - gh[1];
}

static void
leg(const struct state *s, const struct body_sites *bs, int side, double kneel_height,
    struct body_leg *dest)
{
	/* hip: the thigh (hip to knee) in the pelvis's frame, its angle in the y-z plane (+ forward) */
	double d[3], t[3];
	sub(s->seg_xf[bs->shank[side]].p, s->seg_xf[bs->thigh[side]].p, d);
	to_frame(&s->seg_xf[bs->pelvis], d, t);
	dest->hip_flexion = atan2(t[2], -t[1]) * DEG;

	/*
	 * knee: the shank's long axis (its frame's y) against the thigh's, about
	 * the thigh's x (+ = shank backwards). Not the hip-knee-ankle angle: the
	 * built shank leans its ankle behind the knee (4.5 deg for the default
	 * man, so that the standing figure balances) with the knee straight
	 */
	double yt[3], ys[3], xt[3], c[3];
	axis_of(s->seg_xf[bs->thigh[side]].r, 1, yt);
	axis_of(s->seg_xf[bs->shank[side]].r, 1, ys);
	axis_of(s->seg_xf[bs->thigh[side]].r, 0, xt);
	mathx_cross(yt, ys, c);
	dest->knee_flexion = atan2(mathx_dot(c, xt), mathx_dot(yt, ys)) * DEG;

	dest->kneeling = s->site_xf[bs->knee_front[side]].p[1] < kneel_height;
}

int
body_angles_measure(const struct model *m, const struct state *s, int seated, double kneel_height,
		    struct body_angles *dest, char *err, size_t errlen)
{
	struct body_sites bs;
	struct balance bal;
	if (sites_find(m, &bs, err, errlen) < 0)
		return -1;
	if (balance_measure(m, s, BALANCE_CONTACT, &bal) < 0)
		return fail(err, errlen, "site", "foot_l.balance");
	struct body_angles a;
	memset(&a, 0, sizeof a);
	trunk(s, &bs, &a);
	double r[9];
	mathx_mat3_tmul(s->seg_xf[bs.t1].r, s->seg_xf[bs.head].r, r);
	neck(r, &a);
	for (int side = 0; side < 2; side++) {
		arm(m, s, &bs, side, &a.arm[side]);
		leg(s, &bs, side, kneel_height, &a.leg[side]);
		a.leg[side].foot_on_floor =
			balance_touches_floor(m, s, bs.foot[side], BALANCE_CONTACT) ||
			balance_touches_floor(m, s, bs.toes[side], BALANCE_CONTACT);
		a.legs_on_floor += a.leg[side].foot_on_floor;
	}
	/*
	 * the weight over each foot: balance's share when both stand, all of it
	 * on the one that does, none when neither touches the floor
	 */
	if (a.legs_on_floor == 2) {
		a.leg[BODY_LEFT].weight_share = bal.weight_l;
		a.leg[BODY_RIGHT].weight_share = 1 - bal.weight_l;
	} else {
		for (int side = 0; side < 2; side++)
			a.leg[side].weight_share = a.leg[side].foot_on_floor;
	}
	a.seated = !!seated;
	for (size_t i = 0; i < body_angle_count; i++)
		if (!isfinite(body_angle_value(&a, i))) {
			if (err && errlen)
				snprintf(err, errlen, "body angles: %s is not finite (the posture is not)",
					 body_angle_names[i].name);
			return -1;
		}
	*dest = a;
	return 0;
}

/* the table `get angles` replies: the trunk and neck, each arm field left then right, the legs */
#define ONE(f, unit, what) { #f, unit, what, offsetof(struct body_angles, f), 0 }
#define ONE_INT(f, unit, what) { #f, unit, what, offsetof(struct body_angles, f), 1 }
#define ARM(f, unit, what)                                                           \
	{ #f "_l", unit, what, offsetof(struct body_angles, arm[BODY_LEFT].f), 0 },   \
	{                                                                            \
		#f "_r", unit, what, offsetof(struct body_angles, arm[BODY_RIGHT].f), 0 \
	}
#define LEG(f, unit, what, integer)                                                       \
	{ #f "_l", unit, what, offsetof(struct body_angles, leg[BODY_LEFT].f), integer },  \
	{                                                                                 \
		#f "_r", unit, what, offsetof(struct body_angles, leg[BODY_RIGHT].f), integer \
	}

const struct body_angle_name body_angle_names[] = {
	ONE(trunk_flexion, "deg",
	    "trunk axis (L5/S1 to C7/T1) against vertical in the vertical plane across the hip line; + forward"),
	ONE(trunk_side_bend, "deg", "trunk axis's angle out of that plane; + to the left"),
	ONE(trunk_twist, "deg",
	    "thorax's (T1) left-right axis against the hip line, about the trunk axis; + turned left"),
	ONE(hip_trunk_angle, "deg",
	    "trunk axis against the thighs' mean direction (hip to knee); 180 standing, 90 sitting upright"),
	ONE(neck_flexion, "deg", "head's up axis in the thorax's (T1) sagittal plane; + forward"),
	ONE(neck_side_bend, "deg", "head's up axis out of the thorax's sagittal plane; + to the left"),
	ONE(neck_twist, "deg", "head's turn about its up axis relative to the thorax; + to the left"),
	ARM(upper_arm_flexion, "deg",
	    "upper arm's swing from hanging in the thorax (T1), its part about the flexion axis; + forward"),
	ARM(upper_arm_abduction, "deg", "the same swing's part about the abduction axis; + away from the body"),
	ARM(upper_arm_rotation, "deg", "upper arm's turn about its own axis after that swing; + internal"),
	ARM(shoulder_elevation, "deg", "clavicle's lateral axis above the thorax's horizontal plane; + raised"),
	ARM(elbow_flexion, "deg", "180 - the angle shoulder-elbow-wrist at the joint centres; 0 straight"),
	ARM(wrist_flexion, "deg",
	    "hand's axis against the forearm's, towards the palm (after pronation); + flexion, - extension"),
	ARM(wrist_deviation, "deg", "hand's axis out of the flexion plane; + radial, - ulnar"),
	ARM(wrist_twist, "deg", "hand's turn about the forearm's axis; + pronation, - supination"),
	ARM(wrist_twist_fraction, "fraction",
	    "wrist_twist over the joint's limit on its side; 0 mid-range, 1 at the end"),
	ARM(hand_across_midline, "m",
	    "palm past the thorax's midsagittal plane (through C7/T1); + crossed to the other side"),
	ARM(hand_out_to_side, "m",
	    "palm outside the shoulder joint centre along the thorax's left-right axis; + outwards"),
	ARM(elbow_above_shoulder, "m", "elbow joint centre's height above the shoulder joint centre's"),
	ARM(hand_above_shoulder, "m", "palm's height above the shoulder joint centre's"),
	LEG(hip_flexion, "deg", "thigh (hip to knee) in the pelvis's sagittal plane; + forward", 0),
	LEG(knee_flexion, "deg", "shank's long axis against the thigh's; 0 straight", 0),
	LEG(weight_share, "fraction",
	    "of the body's weight over this foot, from the balance point between the feet", 0),
	LEG(foot_on_floor, "flag", "the foot's or toes' geometry within 2 cm of the floor", 1),
	LEG(kneeling, "flag", "the knee's front (thigh's knee_front site) within kneel_height of the floor",
	    1),
	ONE_INT(seated, "flag", "sitting, as the figure's behaviour says"),
	ONE_INT(legs_on_floor, "count", "feet on the floor"),
};
#undef ONE
#undef ONE_INT
#undef ARM
#undef LEG

const size_t body_angle_count = sizeof body_angle_names / sizeof body_angle_names[0];

double
body_angle_value(const struct body_angles *a, size_t i)
{
	if (i >= body_angle_count)
		return NAN;
	const char *p = (const char *)a + body_angle_names[i].offset;
	if (body_angle_names[i].integer) {
		int v;
		memcpy(&v, p, sizeof v);
		return v;
	}
	double v;
	memcpy(&v, p, sizeof v);
	return v;
}

int
body_angle_find(const char *name)
{
	for (size_t i = 0; i < body_angle_count; i++)
		if (!strcmp(body_angle_names[i].name, name))
			return (int)i;
	return -1;
}
