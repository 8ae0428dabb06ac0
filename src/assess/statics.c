/*
 * statics.c - the static equilibrium of a figure: support forces from the
 * whole body's balance of forces, then one backward pass over the segments
 * for the wrench every joint carries.
 *
 * The derivation. Every segment i carries its weight m_i g (0, -1, 0) at
 * its centre of mass, the loads on it, and the supports that push on it.
 * The supports' total wrench is what closes the whole body's equilibrium:
 * S = -(sum of weights and loads), force and moment. Each joint then
 * carries what keeps its distal part in equilibrium: the distal part's
 * weights, loads and supports, negated, taken about the joint centre.
 * Summing that over subtrees is Newton-Euler's backward pass with no
 * velocities (Featherstone, Rigid Body Dynamics Algorithms, 2008, §5.3,
 * RNEA's second pass; Winter, Biomechanics and Motor Control of Human
 * Movement, 4th ed. 2009, ch. 5, the link-segment model with v = a = 0).
 *
 * The support rule (how S is shared when more than one support touches):
 *   1. The centre of pressure c: where S's line of action crosses the
 *      horizontal plane through the supports (their mean height); what is
 *      left of S's moment there is about the vertical, a free moment.
 *   2. Each support k gets the share w_k of S's force (all supports'
 *      forces parallel: each foot's friction in proportion to the weight
 *      on it). The shares are those of a rigid plate on equal vertical
 *      springs at the supports: w_k = 1/n + (p_k - p)^T G^+ (c - p), p the
 *      supports' centroid and G = sum (p_k - p)(p_k - p)^T in the floor
 *      plane, the minimum-norm shares whose weighted mean of the p_k is
 *      nearest c; a support that would pull is dropped and the rest solved
 *      again. Between two feet that is the lever rule of c's place along
 *      the line joining their balance sites, clamped to the feet: 1 - x of
 *      balance.h, its weight_l. The net centre of pressure is then the
 *      force-weighted mean of the supports' points, as the two force
 *      plates' combined centre of pressure is (Winter 1995, Gait & Posture
 *      3:193-214, eq. 1).
 *   3. Where the shares cannot put the weighted mean at c (c off the line
 *      between two feet, or beyond a foot), every loaded support's point
 *      moves by the same horizontal offset, so that the mean is c: each
 *      foot's own centre of pressure moves forward or back under it.
 *   4. What remains of S's moment after the forces at those points (the
 *      free moment about the vertical on a flat floor, plus what different
 *      heights of seat and floor leave) is shared by the same w_k.
 * The sum of the supports' wrenches is S exactly (to rounding), whatever
 * the shares: the whole body's equilibrium closes by construction, and the
 * rule only decides how it is shared.
 */
#include "assess/statics.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "figure/mathx.h"
#include "pose/balance.h"

/* a wrench: force [0..2] and moment [3..5] about the solve's reference point */
typedef double wrench[6];

struct supports {
	int n;
	int kind[STATICS_MAX_SUPPORT], site[STATICS_MAX_SUPPORT], seg[STATICS_MAX_SUPPORT];
	int contacts;
	struct balance poly; /* the support polygon (only npoly and poly are used) */
};

static int
fail(char *err, size_t errlen, const char *what)
{
	if (err && errlen)
		snprintf(err, errlen, "statics: %s", what);
	return -1;
}

/* w += the wrench of force f at point x (relative to the reference) */
static void
add_force(double *w, const double x[3], const double f[3])
{
	double c[3];
	mathx_cross(x, f, c);
	for (int i = 0; i < 3; i++) {
		w[i] += f[i];
		w[3 + i] += c[i];
	}
}

/*
 * 1 when a segment's geometry comes within h of the floor (y = 0): the
 * lowest corner of each geom's bounding box, as balance.c and body_angles.c
 * test a foot
 */
static int
touches_floor(const struct model *m, const struct state *s, int seg, double h)
{
	if (seg < 0)
		return 0;
	const struct xform *x = &s->seg_xf[seg];
	for (int g = m->seg_geom0[seg]; g < m->seg_geom0[seg] + m->seg_ngeom[seg]; g++) {
		const double *sz = &m->geom_size[3 * g];
		double half[3];
		switch ((enum geom_kind)m->geom_kind[g]) {
		case GEOM_BOX:
		case GEOM_MESH:
			half[0] = sz[0] / 2, half[1] = sz[1] / 2, half[2] = sz[2] / 2;
			break;
		case GEOM_ELLIPSOID:
			half[0] = sz[0], half[1] = sz[1], half[2] = sz[2];
			break;
		case GEOM_CYLINDER:
		case GEOM_CAPSULE:
			half[0] = half[2] = sz[0];
			half[1] = sz[1] / 2 + (m->geom_kind[g] == GEOM_CAPSULE ? sz[0] : 0);
			break;
		default:
			continue;
		}
		double gr[9], w[9], c[3];
		mathx_quat_to_mat(&m->geom_quat[4 * g], gr);
		mathx_mat3_mul(x->r, gr, w);
		xform_apply(x, &m->geom_pos[3 * g], c);
		double low = c[1];
		for (int k = 0; k < 3; k++)
			low -= fabs(w[3 + k]) * half[k];
		if (low < h)
			return 1;
	}
	return 0;
}

static void
support_add(struct supports *sp, int kind, int site, const struct model *m)
{
	sp->kind[sp->n] = kind;
	sp->site[sp->n] = site;
	sp->seg[sp->n] = m->site_seg[site];
	sp->n++;
}

/* the seat's outline for the tipping test: buttocks to the backs of the knees */
static void
seat_polygon(const struct model *m, const struct state *s, struct supports *sp)
{
	static const char *const outline[] = { "pelvis.buttock_l", "pelvis.buttock_r",
					       "thigh_l.popliteal", "thigh_r.popliteal" };
	double pts[BALANCE_POLY_MAX + 8][2], hull[BALANCE_POLY_MAX + 9][2];
	int n = 0;
	for (int i = 0; i < sp->poly.npoly; i++, n++)
		pts[n][0] = sp->poly.poly[i][0], pts[n][1] = sp->poly.poly[i][1];
	for (int k = 0; k < sp->n; k++)
		if (sp->kind[k] == STATICS_SEAT) {
			const double *p = s->site_xf[sp->site[k]].p;
			pts[n][0] = p[0], pts[n][1] = p[2], n++;
		}
	for (size_t i = 0; i < sizeof outline / sizeof *outline; i++) {
		int site = model_find_site(m, outline[i]);
		if (site >= 0) {
			const double *p = s->site_xf[site].p;
			pts[n][0] = p[0], pts[n][1] = p[2], n++;
		}
	}
	int nh = balance_hull(pts, n, hull);
	sp->poly.npoly = nh < BALANCE_POLY_MAX ? nh : BALANCE_POLY_MAX;
	memcpy(sp->poly.poly, hull, sizeof *hull * (size_t)sp->poly.npoly);
}

/*
 * Which supports bear: the feet on the floor (both as if on it when none
 * is, contacts then 0), the ischial tuberosities when seated, the root
 * site for a figure without feet; and the support polygon. 0 or -1 (said).
 */
static int
supports_find(const struct model *m, const struct state *s, int seated, struct supports *sp,
	      char *err, size_t errlen)
{
	static const char *const foot_site[2] = { "foot_l.balance", "foot_r.balance" };
	static const char *const foot_seg[2][2] = { { "foot_l", "toes_l" }, { "foot_r", "toes_r" } };
	static const char *const seat_site[2] = { "pelvis.ischial_tuberosity_l",
						  "pelvis.ischial_tuberosity_r" };
	memset(sp, 0, sizeof *sp);
	int feet[2] = { model_find_site(m, foot_site[0]), model_find_site(m, foot_site[1]) };
	int have_feet = feet[0] >= 0 && feet[1] >= 0;
	if (seated) {
		for (int k = 0; k < 2; k++) {
			int site = model_find_site(m, seat_site[k]);
			if (site < 0)
				return fail(err, errlen,
					    "seated needs the sites pelvis.ischial_tuberosity_l and _r");
			support_add(sp, STATICS_SEAT, site, m);
		}
		sp->contacts = 2;
	}
	if (have_feet) {
		int touch[2];
		for (int k = 0; k < 2; k++)
			touch[k] = touches_floor(m, s, m->site_seg[feet[k]], BALANCE_CONTACT) ||
				   touches_floor(m, s, model_find_segment(m, foot_seg[k][1]),
						 BALANCE_CONTACT);
		int any = touch[0] || touch[1];
		for (int k = 0; k < 2; k++)
			if (touch[k] || (!any && !seated)) {
				support_add(sp, STATICS_FOOT, feet[k], m);
				sp->contacts += touch[k];
			}
		if (balance_measure_feet(m, s, BALANCE_CONTACT, 0, &sp->poly) < 0)
			sp->poly.npoly = 0;
	}
	if (seated)
		seat_polygon(m, s, sp);
	if (!sp->n) {
		support_add(sp, STATICS_ROOT, m->root_site, m);
		sp->contacts = 1;
	}
	return 0;
}

/* the Moore-Penrose inverse of a symmetric positive semi-definite 2x2 matrix */
static void
pinv2(const double g[3], double dest[3])
{
	/* g = [a b; b d] stored as a, b, d */
	double a = g[0], b = g[1], d = g[2];
	double mean = (a + d) / 2, rad = sqrt((a - d) * (a - d) / 4 + b * b);
	double l1 = mean + rad, l2 = mean - rad;
	if (l1 <= 1e-18) { /* the points coincide: no direction to lean */
		dest[0] = dest[1] = dest[2] = 0;
		return;
	}
	if (l2 <= 1e-9 * l1) { /* on a line: only along it */
		double v[2] = { b, l1 - a };
		if (fabs(a - l1) + fabs(b) < fabs(d - l1) + fabs(b))
			v[0] = l1 - d, v[1] = b;
		double n2 = v[0] * v[0] + v[1] * v[1];
		dest[0] = v[0] * v[0] / (n2 * l1);
		dest[1] = v[0] * v[1] / (n2 * l1);
		dest[2] = v[1] * v[1] / (n2 * l1);
		return;
	}
	double det = a * d - b * b;
	dest[0] = d / det, dest[1] = -b / det, dest[2] = a / det;
}

/*
 * The shares w[0..n-1] (sum 1, none negative) of supports at floor points
 * p that put their weighted mean nearest c: equal springs under a rigid
 * plate, a support that would pull dropped (statics.c's opening comment).
 */
static void
share_points(int n, const double (*p)[2], const double c[2], double *w)
{
	int on[STATICS_MAX_SUPPORT];
	for (int k = 0; k < n; k++)
		on[k] = 1;
	for (int left = n; left > 0; left--) {
		double mid[2] = { 0, 0 }, g[3] = { 0, 0, 0 }, gi[3];
		for (int k = 0; k < n; k++)
			if (on[k])
				mid[0] += p[k][0] / left, mid[1] += p[k][1] / left;
		for (int k = 0; k < n; k++)
			if (on[k]) {
				double dx = p[k][0] - mid[0], dz = p[k][1] - mid[1];
				g[0] += dx * dx, g[1] += dx * dz, g[2] += dz * dz;
			}
		pinv2(g, gi);
		double e[2] = { c[0] - mid[0], c[1] - mid[1] };
		double h[2] = { gi[0] * e[0] + gi[1] * e[1], gi[1] * e[0] + gi[2] * e[1] };
		int worst = -1;
		for (int k = 0; k < n; k++) {
			w[k] = on[k] ? 1.0 / left + (p[k][0] - mid[0]) * h[0] + (p[k][1] - mid[1]) * h[1]
				     : 0;
			if (on[k] && w[k] < 0 && (worst < 0 || w[k] < w[worst]))
				worst = k;
		}
		if (worst < 0)
			return;
		on[worst] = 0;
	}
}

/*
 * Shares the support wrench S (about o) between the supports by the rule
 * of the opening comment, filling dest's supports, cop, margin, lifts and
 * tips.
 */
static void
supports_share(const struct state *s, const struct supports *sp, const double o[3],
	       const wrench S, struct statics_result *dest)
{
	int n = sp->n;
	double p[STATICS_MAX_SUPPORT][3], flat[STATICS_MAX_SUPPORT][2], w[STATICS_MAX_SUPPORT];
	double h = 0;
	for (int k = 0; k < n; k++) {
		for (int i = 0; i < 3; i++)
			p[k][i] = s->site_xf[sp->site[k]].p[i] - o[i];
		flat[k][0] = p[k][0], flat[k][1] = p[k][2];
		h += p[k][1] / n;
	}
	/* the centre of pressure on the plane y = h (relative to o) */
	double c[3] = { p[0][0], h, p[0][2] };
	double scale = fabs(S[0]) + fabs(S[1]) + fabs(S[2]);
	int held = sp->kind[0] == STATICS_ROOT; /* one support: it takes everything */
	dest->lifts = !held && !(S[1] > 1e-9 * scale);
	if (held) {
		w[0] = 1;
	} else if (dest->lifts) { /* no centre of pressure: equal shares, the supports' middle */
		c[0] = c[2] = 0;
		for (int k = 0; k < n; k++) {
			w[k] = 1.0 / n;
			c[0] += flat[k][0] / n, c[2] += flat[k][1] / n;
		}
	} else {
		c[0] = (S[5] + h * S[0]) / S[1];
		c[2] = (h * S[2] - S[3]) / S[1];
		double cf[2] = { c[0], c[2] };
		share_points(n, (const double(*)[2])flat, cf, w);
	}
	/* the loaded supports' points move together so that their weighted mean is c */
	double off[2] = { c[0], c[2] };
	for (int k = 0; k < n; k++)
		off[0] -= w[k] * flat[k][0], off[1] -= w[k] * flat[k][1];
	double rest[3] = { S[3], S[4], S[5] };
	dest->nsupport = n;
	for (int k = 0; k < n; k++) {
		struct statics_support *u = &dest->support[k];
		u->kind = sp->kind[k];
		u->site = sp->site[k];
		u->seg = sp->seg[k];
		u->share = w[k];
		double x[3] = { p[k][0], p[k][1], p[k][2] };
		if (w[k] > 0)
			x[0] += off[0], x[2] += off[1];
		double f[3] = { w[k] * S[0], w[k] * S[1], w[k] * S[2] }, mx[3];
		mathx_cross(x, f, mx);
		for (int i = 0; i < 3; i++) {
			rest[i] -= mx[i];
			u->force[i] = f[i];
			u->point[i] = x[i] + o[i];
		}
	}
	for (int k = 0; k < n; k++)
		for (int i = 0; i < 3; i++)
			dest->support[k].moment[i] = w[k] * rest[i];
	for (int i = 0; i < 3; i++)
		dest->cop[i] = c[i] + o[i];
	if (held) {
		dest->margin = 0;
		dest->tips = 0;
		return;
	}
	double cp[2] = { dest->cop[0], dest->cop[2] };
	dest->margin = balance_margin(&sp->poly, cp);
	dest->tips = dest->lifts || dest->margin < 0;
}

/* the anatomical joints of the human, by the name before the side */
enum anat_kind {
	ANAT_NONE,
	ANAT_HINGE,     /* knee, elbow: one dof */
	ANAT_BALL,      /* hip, shoulder */
	ANAT_ANKLE,
	ANAT_WRIST,
	ANAT_LUMBOSACRAL,
};

static const char *const anat_names[][3] = {
	[ANAT_HINGE] = { "flexion", "abduction", "rotation" },
	[ANAT_BALL] = { "flexion", "abduction", "rotation" },
	[ANAT_ANKLE] = { "dorsiflexion", "inversion", "rotation" },
	[ANAT_WRIST] = { "flexion", "radial_deviation", "pronation" },
	[ANAT_LUMBOSACRAL] = { "flexion", "lateral_bend", "axial_rotation" },
};

/* the kind of joint j, and its side (+1 left, -1 right, 0 midline) */
static enum anat_kind
anat_kind(const struct model *m, int j, int *side)
{
	static const struct {
		const char *stem;
		enum anat_kind kind;
		int ndof;
	} table[] = {
		{ "knee", ANAT_HINGE, 1 },  { "elbow", ANAT_HINGE, 1 }, { "hip", ANAT_BALL, 3 },
		{ "shoulder", ANAT_BALL, 3 }, { "ankle", ANAT_ANKLE, 3 }, { "wrist", ANAT_WRIST, 3 },
	};
	const char *name = m->jnt_name[j];
	*side = 0;
	if (j < 0 || j >= m->njnt)
		return ANAT_NONE;
	if (!strcmp(name, "spine_0"))
		return m->jnt_ndof[j] == 3 && !model_joint_has(m, j, DOF_TRANSLATION) ? ANAT_LUMBOSACRAL
										: ANAT_NONE;
	size_t len = strlen(name);
	if (len < 3 || name[len - 2] != '_' || (name[len - 1] != 'l' && name[len - 1] != 'r'))
		return ANAT_NONE;
	for (size_t i = 0; i < sizeof table / sizeof *table; i++) {
		size_t sl = strlen(table[i].stem);
		if (sl == len - 2 && !strncmp(name, table[i].stem, sl) &&
		    m->jnt_ndof[j] == table[i].ndof && !model_joint_has(m, j, DOF_TRANSLATION)) {
			*side = name[len - 1] == 'l' ? 1 : -1;
			return table[i].kind;
		}
	}
	return ANAT_NONE;
}

int
statics_anatomical_joint(const struct model *m, int j)
{
	int side;
	return j >= 0 && j < m->njnt && anat_kind(m, j, &side) != ANAT_NONE;
}

const char *const *
statics_axis_names(const struct model *m, int j)
{
	int side;
	if (j < 0 || j >= m->njnt)
		return NULL;
	enum anat_kind k = anat_kind(m, j, &side);
	return k == ANAT_NONE ? NULL : anat_names[k];
}

/*
 * The anatomical moments of joint j (moment about its centre, proximal
 * onto distal): the generalised torques of its three dofs, or for a hinge
 * its dof's and the moments about the distal segment's forward and long
 * axes, signed as the hip's and shoulder's abduction (+z left, -z right)
 * and internal rotation (-y left, +y right).
 */
static void
anat_moments(const struct model *m, const struct state *s, int j, enum anat_kind kind, int side,
	     int distal, const double mom[3], const double *dof_torque, double dest[3])
{
	int d0 = m->jnt_dof0[j];
	if (kind != ANAT_HINGE) {
		for (int k = 0; k < 3; k++)
			dest[k] = dof_torque[d0 + k];
		return;
	}
	const double *r = s->seg_xf[distal].r;
	double fwd[3] = { side * r[2], side * r[5], side * r[8] };
	double along[3] = { -side * r[1], -side * r[4], -side * r[7] };
	dest[0] = dof_torque[d0];
	dest[1] = mathx_dot(mom, fwd);
	dest[2] = mathx_dot(mom, along);
}

/* checks the figure's size, its frames and the loads; 0 or -1 (said) */
static int
check_input(const struct model *m, const struct state *s, const struct ext_load *loads,
	    int nloads, char *err, size_t errlen)
{
	char why[160];
	if (m->nseg > STATICS_MAX_SEG || m->ndof > STATICS_MAX_DOF) {
		snprintf(why, sizeof why, "a figure of %d segments and %d dofs is larger than %d and %d",
			 m->nseg, m->ndof, STATICS_MAX_SEG, STATICS_MAX_DOF);
		return fail(err, errlen, why);
	}
	if (nloads < 0 || nloads > STATICS_MAX_LOADS || (nloads && !loads)) {
		snprintf(why, sizeof why, "%d loads: 0 to %d are solved", nloads, STATICS_MAX_LOADS);
		return fail(err, errlen, why);
	}
	for (int i = 0; i < m->nseg; i++)
		if (!xform_finite(&s->seg_xf[i]))
			return fail(err, errlen, "the posture's frames are not finite");
	for (int i = 0; i < nloads; i++) {
		const struct ext_load *l = &loads[i];
		int finite = isfinite(l->mass) && l->mass >= 0;
		for (int k = 0; k < 3; k++)
			finite = finite && isfinite(l->local[k]) && isfinite(l->force[k]) &&
				 isfinite(l->torque[k]);
		if (l->seg < 0 || l->seg >= m->nseg)
			snprintf(why, sizeof why, "load %d: no segment %d", i, l->seg);
		else if (!finite)
			snprintf(why, sizeof why, "load %d: a number is not finite (or a mass below 0)", i);
		else if (l->mass > 0 &&
			 (fabs(l->force[0]) + fabs(l->force[2]) +
			  fabs(l->force[1] + l->mass * LOAD_GRAVITY)) > 1e-9 * l->mass * LOAD_GRAVITY)
			snprintf(why, sizeof why, "load %d: a weight of %g kg pulls (0, %g, 0) N, not (%g, %g, %g)",
				 i, l->mass, -l->mass * LOAD_GRAVITY, l->force[0], l->force[1],
				 l->force[2]);
		else
			continue;
		return fail(err, errlen, why);
	}
	return 0;
}

int
statics_solve(const struct model *m, const struct state *s, const struct ext_load *loads,
	      int nloads, int seated, struct statics_result *dest, char *err, size_t errlen)
{
	if (check_input(m, s, loads, nloads, err, errlen) < 0)
		return -1;
	struct supports sp;
	if (supports_find(m, s, seated, &sp, err, errlen) < 0)
		return -1;
	int root = m->site_seg[m->root_site];
	/* moments about the root segment's origin: small lever arms wherever the figure stands */
	const double *o = s->seg_xf[root].p;

	/* each segment's own wrench: its weight and its loads */
	wrench own[STATICS_MAX_SEG], total = { 0 };
	double weight = 0, load_mass = 0;
	for (int i = 0; i < m->nseg; i++) {
		double c[3], f[3] = { 0, -m->seg_mass[i] * LOAD_GRAVITY, 0 };
		xform_apply(&s->seg_xf[i], &m->seg_com[3 * i], c);
		for (int k = 0; k < 3; k++)
			c[k] -= o[k];
		memset(own[i], 0, sizeof own[i]);
		add_force(own[i], c, f);
		weight -= f[1];
	}
	for (int i = 0; i < nloads; i++) {
		const struct ext_load *l = &loads[i];
		double x[3];
		xform_apply(&s->seg_xf[l->seg], l->local, x);
		for (int k = 0; k < 3; k++)
			x[k] -= o[k];
		add_force(own[l->seg], x, l->force);
		for (int k = 0; k < 3; k++)
			own[l->seg][3 + k] += l->torque[k];
		load_mass += l->mass;
	}
	for (int i = 0; i < m->nseg; i++)
		for (int k = 0; k < 6; k++)
			total[k] += own[i][k];

	/* the supports close the whole body's equilibrium */
	wrench S;
	for (int k = 0; k < 6; k++)
		S[k] = -total[k];
	supports_share(s, &sp, o, S, dest);
	for (int k = 0; k < dest->nsupport; k++) {
		const struct statics_support *u = &dest->support[k];
		double x[3] = { u->point[0] - o[0], u->point[1] - o[1], u->point[2] - o[2] };
		add_force(own[u->seg], x, u->force);
		for (int i = 0; i < 3; i++)
			own[u->seg][3 + i] += u->moment[i];
	}
	for (int k = 0; k < 6; k++)
		total[k] = 0;
	for (int i = 0; i < m->nseg; i++)
		for (int k = 0; k < 6; k++)
			total[k] += own[i][k];

	/*
	 * subtree sums in the state's tree, leaves first; a joint whose distal
	 * side from the root segment is the state's parent side (the state is
	 * rooted elsewhere, beyond it) carries the rest of the figure instead
	 */
	wrench sub[STATICS_MAX_SEG];
	memcpy(sub, own, sizeof(wrench) * (size_t)m->nseg);
	for (int n = m->nseg - 1; n > 0; n--) {
		int seg = s->seg_order[n], par = s->seg_parent[seg];
		for (int k = 0; k < 6; k++)
			sub[par][k] += sub[seg][k];
	}
	unsigned char above_root[STATICS_MAX_SEG] = { 0 };
	for (int seg = root; seg >= 0; seg = s->seg_parent[seg])
		above_root[seg] = 1;

	dest->njoint = m->njnt;
	dest->ndof = m->ndof;
	dest->root_seg = root;
	for (int j = 0; j < m->njnt; j++) {
		int below = s->jnt_child_seg[j];
		int flipped = above_root[below];
		int distal = flipped ? s->seg_parent[below] : below;
		double D[6];
		for (int k = 0; k < 6; k++)
			D[k] = flipped ? total[k] - sub[below][k] : sub[below][k];
		int to_distal = m->site_seg[m->jnt_site_to[j]] == distal;
		const double *pw = s->site_xf[to_distal ? m->jnt_site_to[j] : m->jnt_site_from[j]].p;
		double x[3] = { pw[0] - o[0], pw[1] - o[1], pw[2] - o[2] }, xf[3];
		/* what holds the distal part: its wrench negated, about the joint centre */
		mathx_cross(x, D, xf);
		for (int k = 0; k < 3; k++) {
			dest->point[j][k] = pw[k];
			dest->force[j][k] = -D[k];
			dest->moment[j][k] = xf[k] - D[3 + k];
		}
		dest->distal_seg[j] = distal;
		/* each dof's share: about its own pivot, as the dof moves the to-side */
		int dir = to_distal ? 1 : -1;
		for (int d = m->jnt_dof0[j]; d < m->jnt_dof0[j] + m->jnt_ndof[j]; d++) {
			const double *a = &s->dof_axis_w[3 * d];
			if (m->dof_kind[d] == DOF_TRANSLATION) {
				dest->dof_torque[d] = dir * mathx_dot(dest->force[j], a);
				continue;
			}
			const double *c = &s->dof_pivot_w[3 * d];
			double r[3] = { pw[0] - c[0], pw[1] - c[1], pw[2] - c[2] }, rf[3];
			mathx_cross(r, dest->force[j], rf);
			double mc[3] = { dest->moment[j][0] + rf[0], dest->moment[j][1] + rf[1],
					 dest->moment[j][2] + rf[2] };
			dest->dof_torque[d] = dir * mathx_dot(mc, a);
		}
	}
	for (int j = 0; j < m->njnt; j++) {
		int side;
		enum anat_kind kind = anat_kind(m, j, &side);
		dest->anatomical[j] = kind != ANAT_NONE;
		if (kind == ANAT_NONE)
			memset(dest->anat[j], 0, sizeof dest->anat[j]);
		else
			anat_moments(m, s, j, kind, side, dest->distal_seg[j], dest->moment[j],
				     dest->dof_torque, dest->anat[j]);
	}
	dest->weight_n = weight;
	dest->load_mass = load_mass;
	dest->seated = !!seated;
	dest->contacts = sp.contacts;
	return 0;
}
