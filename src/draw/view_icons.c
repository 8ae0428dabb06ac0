/*
 * view_icons.c - the icons of the dissertation as draw-list lines and
 * triangles: the manipulation frame, the translation arrow, the rotation
 * wheel with its limit sectors (§3.8.1), rotation fans (Figure 4.1), goal
 * icons, balance (§5.4.2.1), and the loads on the body as arrows. No GL here.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pose/balance.h"
#include "draw/view_internal.h"

/* ---- icons ------------------------------------------------------------------- */

void
view_add_frame_icon(struct drawlist *dl, const struct xform *xf, double size, int labels)
{
	static const char *const pos[3] = { "x", "y", "z" }, *const neg[3] = { "-x", "-y", "-z" };
	double a[3], e[3];
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, THICK_WIDTH, 1);
	for (int k = 0; k < 3; k++) {
		r_col(xf->r, k, a);
		v_madd(xf->p, size, a, e);
		view_line(dl, xf->p, e, C_AXIS[k]);
	}
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
	for (int k = 0; k < 3; k++) {
		r_col(xf->r, k, a);
		v_madd(xf->p, -size, a, e);
		view_line(dl, xf->p, e, C_AXIS_NEG[k]);
	}
	if (!labels)
		return;
	for (int k = 0; k < 3; k++) {
		r_col(xf->r, k, a);
		v_madd(xf->p, 1.18 * size, a, e);
		view_world_label(dl, e, pos[k], C_AXIS[k]);
		v_madd(xf->p, -1.18 * size, a, e);
		view_world_label(dl, e, neg[k], C_AXIS_NEG[k]);
	}
}

/* a frame whose y axis is dir (unit), origin at p */
static void
frame_along(const double p[3], const double dir[3], struct xform *dest)
{
	double x[3], z[3];
	v_perp(dir, x);
	v_cross(x, dir, z);
	for (int i = 0; i < 3; i++) {
		dest->r[3 * i + 0] = x[i];
		dest->r[3 * i + 1] = dir[i];
		dest->r[3 * i + 2] = z[i];
		dest->p[i] = p[i];
	}
}

void
view_add_translation_arrow(struct drawlist *dl, const double origin[3], const double dir[3],
			   double length)
{
	static const float rgba[4] = { 1.0f, 0.82f, 0.2f, 0.45f };
	double d[3], head = 0.18 * length, r = 0.025 * length;
	if (v_unit(dir, d) <= 0)
		return;
	struct xform x;
	/* the shaft between the heads, then a cone at each end pointing outwards */
	frame_along(origin, d, &x);
	double shaft[3] = { r, length - 2 * head, r };
	float mat[16];
	view_mat_from_xform(&x, shaft, mat);
	view_add_instance(dl, VIEW_MESH_CYLINDER, mat, rgba, 0);
	for (int s = -1; s <= 1; s += 2) {
		double nd[3] = { s * d[0], s * d[1], s * d[2] }, base[3];
		v_madd(origin, length / 2 - head, nd, base);
		frame_along(base, nd, &x);
		double cone[3] = { 2.6 * r, head, 2.6 * r };
		view_mat_from_xform(&x, cone, mat);
		view_add_instance(dl, VIEW_MESH_CONE, mat, rgba, 0);
	}
}

/* direction at angle t from unit u about unit a (right hand): u cos t + (a x u) sin t */
static void
turn(const double a[3], const double u[3], double t, double dest[3])
{
	double v[3];
	v_cross(a, u, v);
	for (int k = 0; k < 3; k++)
		dest[k] = cos(t) * u[k] + sin(t) * v[k];
}

/* the wheel from angle t0 to t1: a filled sector (fill) or its rim as lines */
static void
wheel_part(struct drawlist *dl, const double c[3], const double a[3], const double u[3], double r,
	   double t0, double t1, const uint8_t col[4], int fill)
{
	int n = (int)ceil(fabs(t1 - t0) / (2 * M_PI) * (fill ? 48 : 64));
	n = n < 1 ? 1 : n;
	double d0[3], d1[3], p0[3], p1[3];
	for (int i = 0; i < n; i++) {
		turn(a, u, t0 + (t1 - t0) * i / n, d0);
		turn(a, u, t0 + (t1 - t0) * (i + 1) / n, d1);
		v_madd(c, r, d0, p0);
		v_madd(c, r, d1, p1);
		if (fill)
			view_triangle(dl, c, p0, p1, col);
		else
			view_line(dl, p0, p1, col);
	}
}

void
view_add_rotation_wheel(struct drawlist *dl, const struct view_wheel *w)
{
	double a[3], u[3], e[3];
	uint8_t tc[4];
	if (v_unit(w->axis, a) <= 0)
		return;
	/* the initial spoke in the wheel's plane */
	v_madd(w->spoke, -v_dot(w->spoke, a), a, u);
	if (v_unit(u, u) < 1e-9)
		v_perp(a, u);
	double r = w->radius;
	double lo = w->lo - w->current, hi = w->hi - w->current;
	int sectors = w->limited && hi - lo < 2 * M_PI;

	/* translucent sectors: green where the spoke may go, red beyond the limits */
	if (sectors) {
		view_batch_begin(dl, VIEW_TRIANGLES, VIEW_WORLD, 1, 1);
		wheel_part(dl, w->center, a, u, r, lo, hi, with_alpha(C_GREEN, 80, tc), 1);
		wheel_part(dl, w->center, a, u, r, hi, lo + 2 * M_PI, with_alpha(C_RED, 80, tc), 1);
	}
	/* the rim, coloured by sector, and eight spokes */
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, THICK_WIDTH, 1);
	if (sectors) {
		wheel_part(dl, w->center, a, u, r, lo, hi, C_GREEN, 0);
		wheel_part(dl, w->center, a, u, r, hi, lo + 2 * M_PI, C_RED, 0);
	} else {
		wheel_part(dl, w->center, a, u, r, 0, 2 * M_PI, C_WHEEL, 0);
	}
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
	for (int i = 1; i < 8; i++) {
		double d[3];
		turn(a, u, i * M_PI / 4, d);
		v_madd(w->center, r, d, e);
		view_line(dl, w->center, e, with_alpha(C_WHEEL, 200, tc));
	}
	/* the spoke, extended past the rim (§3.5) */
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, THICK_WIDTH + 1, 1);
	v_madd(w->center, 1.3 * r, u, e);
	view_line(dl, w->center, e, C_WHEEL);
	/* the limits as short ticks outside the rim */
	if (sectors) {
		view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, THICK_WIDTH, 1);
		for (int k = 0; k < 2; k++) {
			double d[3], p0[3];
			turn(a, u, k ? hi : lo, d);
			v_madd(w->center, 0.85 * r, d, p0);
			v_madd(w->center, 1.15 * r, d, e);
			view_line(dl, p0, e, C_WHITE);
		}
	}
}

int
view_add_joint_wheel(struct drawlist *dl, const struct model *m, const struct state *s, int dof,
		     double radius)
{
	if (dof < 0 || dof >= m->ndof || m->dof_kind[dof] != DOF_ROTATION)
		return -1;
	int j = m->dof_jnt[dof], child = s->jnt_child_seg[j];
	struct view_wheel w;
	double com[3];
	/* the child turns by jnt_dir * q about the dof's world axis */
	for (int k = 0; k < 3; k++) {
		w.axis[k] = s->jnt_dir[j] * s->dof_axis_w[3 * dof + k];
		w.center[k] = s->dof_pivot_w[3 * dof + k];
	}
	xform_apply(&s->seg_xf[child], &m->seg_com[3 * child], com);
	for (int k = 0; k < 3; k++)
		w.spoke[k] = com[k] - w.center[k];
	w.radius = radius;
	w.limited = 1;
	w.lo = m->dof_lo[dof];
	w.hi = m->dof_hi[dof];
	w.current = s->q[dof];
	if (s->jnt_dir[j] < 0) {
		/* seen from the other side, the limits swap */
		w.lo = -m->dof_hi[dof];
		w.hi = -m->dof_lo[dof];
		w.current = -s->q[dof];
	}
	view_add_rotation_wheel(dl, &w);
	return 0;
}

void
view_add_fan(struct drawlist *dl, const double origin[3], const double from[3], const double to[3],
	     double radius, const uint8_t rgba[4])
{
	double u[3], v[3] = { 0, 0, 0 }, a[3], e[3];
	uint8_t fill[4];
	if (v_unit(from, u) <= 0 || v_unit(to, v) <= 0)
		return;
	v_cross(u, v, a);
	double sn = v_unit(a, a), t = atan2(sn, v_dot(u, v));
	if (sn < 1e-9)
		return;
	view_batch_begin(dl, VIEW_TRIANGLES, VIEW_WORLD, 1, 1);
	wheel_part(dl, origin, a, u, radius, 0, t, with_alpha(rgba, 90, fill), 1);
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
	wheel_part(dl, origin, a, u, radius, 0, t, rgba, 0);
	v_madd(origin, radius, u, e);
	view_line(dl, origin, e, rgba);
	v_madd(origin, radius, v, e);
	view_line(dl, origin, e, rgba);
}

void
view_add_orientation_fans(struct drawlist *dl, const struct xform *effector,
			  const struct xform *goal, double radius)
{
	for (int k = 0; k < 3; k++) {
		double a[3], b[3];
		r_col(effector->r, k, a);
		r_col(goal->r, k, b);
		view_add_fan(dl, effector->p, a, b, radius, C_AXIS[k]);
	}
}

/* a small three-axis cross at x, no labels */
static void
small_frame(struct drawlist *dl, const struct xform *x, double size)
{
	double a[3], e[3];
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
	for (int k = 0; k < 3; k++) {
		r_col(x->r, k, a);
		v_madd(x->p, size, a, e);
		view_line(dl, x->p, e, C_AXIS[k]);
	}
}

/* an octahedron outline of radius r at p */
static void
diamond(struct drawlist *dl, const double p[3], double r, const uint8_t c[4])
{
	double v[6][3];
	for (int k = 0; k < 6; k++) {
		memcpy(v[k], p, sizeof v[k]);
		v[k][k / 2] += (k % 2 ? -r : r);
	}
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
	for (int i = 0; i < 6; i++)
		for (int j = i + 1; j < 6; j++)
			if (i / 2 != j / 2)
				view_line(dl, v[i], v[j], c);
}

void
view_add_goals(struct drawlist *dl, const struct ik *ik, const struct model *m,
	       const struct state *s)
{
	uint8_t tc[4];
	for (int c = 0; c < ik_count(ik); c++) {
		const struct ik_constraint_def *d = ik_get(ik, c);
		if (!d || !d->enabled || d->effector_site >= m->nsite || d->goal_site >= m->nsite)
			continue;
		/* goal and effector frames in the world */
		struct xform g, e;
		if (d->goal_site >= 0)
			xform_mul(&s->site_xf[d->goal_site], &d->goal_xf, &g);
		else
			g = d->goal_xf;
		if (d->com_effector) { /* with the weights the figure carries */
			xform_identity(&e);
			ik_com(ik, s, e.p);
		} else {
			xform_mul(&s->site_xf[d->effector_site], &d->effector_offset, &e);
		}
		double ga[3], ea[3], p0[3], p1[3], u[3], v[3];
		xform_rotate(&g, d->goal_axis, ga);
		xform_rotate(&e, d->effector_axis, ea);
		switch (d->pos) {
		case IK_POS_NONE:
			break;
		case IK_POINT:
			diamond(dl, g.p, 0.03, C_GOAL);
			break;
		case IK_LINE:
			v_unit(ga, ga);
			v_madd(g.p, -0.5, ga, p0);
			v_madd(g.p, 0.5, ga, p1);
			view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
			view_line(dl, p0, p1, C_GOAL);
			break;
		case IK_PLANE: {
			double q[4][3];
			v_unit(ga, ga);
			v_perp(ga, u);
			v_cross(ga, u, v);
			for (int k = 0; k < 4; k++) {
				double su = (k == 0 || k == 3) ? -0.2 : 0.2, sv = k < 2 ? -0.2 : 0.2;
				for (int i = 0; i < 3; i++)
					q[k][i] = g.p[i] + su * u[i] + sv * v[i];
			}
			view_batch_begin(dl, VIEW_TRIANGLES, VIEW_WORLD, 1, 1);
			view_triangle(dl, q[0], q[1], q[2], with_alpha(C_GOAL, 60, tc));
			view_triangle(dl, q[0], q[2], q[3], with_alpha(C_GOAL, 60, tc));
			view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
			for (int k = 0; k < 4; k++)
				view_line(dl, q[k], q[(k + 1) % 4], C_GOAL);
			break;
		}
		}
		switch (d->ori) {
		case IK_ORI_NONE:
			break;
		case IK_FRAME:
			small_frame(dl, &g, 0.08);
			view_add_orientation_fans(dl, &e, &g, 0.07);
			break;
		case IK_DIRECTION:
			view_add_fan(dl, e.p, ea, ga, 0.08, C_GOAL);
			break;
		case IK_AIM:
			view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, 1.5f, 1);
			view_line(dl, e.p, g.p, with_alpha(C_GOAL, 160, tc));
			break;
		}
		/* the rubber band from the effector to a positional goal it has not reached */
		double gap[3] = { g.p[0] - e.p[0], g.p[1] - e.p[1], g.p[2] - e.p[2] };
		if (d->pos == IK_POINT && v_norm(gap) > 0.005) {
			view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, 1.5f, 1);
			view_line(dl, e.p, g.p, with_alpha(C_GOAL, 200, tc));
		}
	}
}

/* ---- balance ------------------------------------------------------------- */

int
view_add_balance(struct drawlist *dl, const struct model *m, const struct state *s,
		 const double com_held[3])
{
	static const uint8_t c_poly[4] = { 60, 120, 200, 255 }, c_line[4] = { 30, 60, 160, 255 };
	uint8_t tc[4];
	struct balance bal; /* the support polygon and balance line, as balance.c measures them */
	if (balance_measure_com(m, s, BALANCE_CONTACT, 0, com_held ? com_held : s->com, &bal) < 0)
		return -1;
	const double *com = bal.com;
	int nh = bal.npoly;
	double (*hull)[2] = bal.poly;
	const double y = 0.002; /* just above the floor */

	/* the support polygon: a translucent fill and its outline */
	if (nh >= 3) {
		view_batch_begin(dl, VIEW_TRIANGLES, VIEW_WORLD, 1, 1);
		for (int i = 1; i + 1 < nh; i++) {
			double a[3] = { hull[0][0], y, hull[0][1] }, b[3] = { hull[i][0], y, hull[i][1] },
			       c[3] = { hull[i + 1][0], y, hull[i + 1][1] };
			view_triangle(dl, a, b, c, with_alpha(c_poly, 70, tc));
		}
		view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
		for (int i = 0; i < nh; i++) {
			int j = (i + 1) % nh;
			double a[3] = { hull[i][0], y, hull[i][1] }, b[3] = { hull[j][0], y, hull[j][1] };
			view_line(dl, a, b, c_poly);
		}
	}

	/* the balance line between the feet's reference points */
	double pl[3] = { bal.ref_l[0], y, bal.ref_l[1] };
	double pr[3] = { bal.ref_r[0], y, bal.ref_r[1] };
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, THICK_WIDTH, 1);
	view_line(dl, pl, pr, c_line);

	/* the centre of mass: a plumb line, a ring at its height and the balance point */
	const uint8_t *cb = bal.margin > 0 ? C_GREEN : C_RED;
	double bp[3] = { com[0], y, com[2] }, up[3] = { 0, 1, 0 }, ux[3] = { 1, 0, 0 };
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, 1.5f, 1);
	int dashes = 24;
	for (int i = 0; i < dashes; i += 2) {
		double a[3] = { bp[0], y + com[1] * i / dashes, bp[2] };
		double b[3] = { bp[0], y + com[1] * (i + 1) / dashes, bp[2] };
		view_line(dl, a, b, with_alpha(C_BLACK, 150, tc));
	}
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, THICK_WIDTH, 1);
	view_circle(dl, com, up, ux, 0.045, 32, C_BLACK);
	double e0[3], e1[3];
	for (int k = 0; k < 3; k += 2) {
		double d[3] = { k == 0, 0, k == 2 };
		v_madd(com, -0.06, d, e0);
		v_madd(com, 0.06, d, e1);
		view_line(dl, e0, e1, C_BLACK);
	}
	view_circle(dl, bp, up, ux, 0.035, 32, cb);
	for (int k = 0; k < 3; k += 2) {
		double d[3] = { k == 0, 0, k == 2 };
		v_madd(bp, -0.05, d, e0);
		v_madd(bp, 0.05, d, e1);
		view_line(dl, e0, e1, cb);
	}
	return 0;
}


/* ---- loads ----------------------------------------------------------------- */

static const uint8_t C_LOAD[4] = { 200, 40, 180, 255 };

double
view_load_length(double newtons)
{
	double len = VIEW_LOAD_M_PER_N * newtons;
	return len < VIEW_LOAD_LEN_MIN ? VIEW_LOAD_LEN_MIN : len > VIEW_LOAD_LEN_MAX ? VIEW_LOAD_LEN_MAX : len;
}

/* a torque: a ring about its axis at p, turning the right-hand way, with an arrowhead */
static void
torque_ring(struct drawlist *dl, const double p[3], const double axis[3])
{
	const double r = VIEW_LOAD_RING, sweep = 1.6 * M_PI;
	double u[3], a0[3], a1[3];
	v_perp(axis, u);
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, THICK_WIDTH, 1);
	int n = 40;
	for (int i = 0; i < n; i++) {
		turn(axis, u, sweep * i / n, a0);
		turn(axis, u, sweep * (i + 1) / n, a1);
		double p0[3], p1[3];
		v_madd(p, r, a0, p0);
		v_madd(p, r, a1, p1);
		view_line(dl, p0, p1, C_LOAD);
	}
	/* the head at the ring's end: two barbs back along the way it turns */
	double end[3], dir[3], out[3], tip[3], barb[3];
	turn(axis, u, sweep, out);
	v_madd(p, r, out, tip);
	turn(axis, u, sweep + M_PI / 2, dir); /* the tangent at the end */
	for (int s = -1; s <= 1; s += 2) {
		for (int k = 0; k < 3; k++)
			barb[k] = -dir[k] + 0.6 * s * out[k];
		v_madd(tip, 0.35 * r, barb, end);
		view_line(dl, tip, end, C_LOAD);
	}
}

/* the cones' colours by rank: the central spot red, then yellow, green, blue */
static const uint8_t C_CONE[4][4] = {
	{ 235, 60, 50, 255 }, { 245, 200, 20, 255 }, { 40, 190, 80, 255 }, { 50, 140, 245, 255 }
};
#define SIGHT_FILL_ALPHA 50 /* a sight cone's side: four nested still let the scene through */

void
view_add_sight_cones(struct drawlist *dl, const double eye[3], const double dir[3],
		     const double *deg, int n, double length)
{
	double d[3], u[3], v[3];
	uint8_t fill[4];
	if (!(v_unit(dir, d) > 0) || !isfinite(d[0] + d[1] + d[2]))
		return;
	v_perp(d, u);
	v_cross(d, u, v);
	for (int i = 0; i < n; i++) {
		/* the rim: at half the full angle from the line of sight, length from the eye */
		double h = deg[i] * M_PI / 360, ax = length * cos(h), rad = length * sin(h);
		double rim[VIEW_SIGHT_SEGMENTS][3];
		for (int k = 0; k < VIEW_SIGHT_SEGMENTS; k++) {
			double t = 2 * M_PI * k / VIEW_SIGHT_SEGMENTS, c = cos(t), s = sin(t);
			for (int j = 0; j < 3; j++)
				rim[k][j] = eye[j] + ax * d[j] + rad * (c * u[j] + s * v[j]);
		}
		view_batch_begin(dl, VIEW_TRIANGLES, VIEW_WORLD, 1, 0);
		for (int k = 0; k < VIEW_SIGHT_SEGMENTS; k++)
			view_triangle(dl, eye, rim[k], rim[(k + 1) % VIEW_SIGHT_SEGMENTS],
				      with_alpha(C_CONE[i & 3], SIGHT_FILL_ALPHA, fill));
		view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
		for (int k = 0; k < VIEW_SIGHT_SEGMENTS; k++)
			view_line(dl, rim[k], rim[(k + 1) % VIEW_SIGHT_SEGMENTS], C_CONE[i & 3]);
	}
}

void
view_add_cone_marks(struct drawlist *dl, const double *deg, int n)
{
	const uint8_t (*rgba)[4] = C_CONE;
	double cx = dl->width / 2.0, cy = dl->height / 2.0;
	double f = cy / tan(dl->cam.fovy / 2); /* pixels per unit of tan of the angle off the axis */
	view_batch_begin(dl, VIEW_LINES, VIEW_SCREEN, 1.5f, 0);
	for (int i = 0; i < n; i++) {
		double r = f * tan(deg[i] * M_PI / 360);
		for (int k = 0; k < VIEW_CONE_SEGMENTS; k++) {
			double t0 = 2 * M_PI * k / VIEW_CONE_SEGMENTS;
			double t1 = 2 * M_PI * (k + 1) / VIEW_CONE_SEGMENTS;
			double a[3] = { cx + r * cos(t0), cy + r * sin(t0), 0 };
			double b[3] = { cx + r * cos(t1), cy + r * sin(t1), 0 };
			view_line(dl, a, b, rgba[i & 3]);
		}
	}
}

void
view_add_load(struct drawlist *dl, const double p[3], const double force[3], const double torque[3],
	      const char *label)
{
	double d[3] = { 0, 0, 0 }, tip[3];
	memcpy(tip, p, sizeof tip);
	double f = force ? v_unit(force, d) : 0;
	if (f > 0) {
		/* flat, as the other icons: a thick shaft from the point the load acts at, the
		 * way it pulls, and a head facing the camera */
		double len = view_load_length(f), head = fmin(0.3 * len, VIEW_LOAD_HEAD);
		double base[3], side[3], to_cam[3], a[3], b[3];
		v_madd(p, len, d, tip);
		v_madd(p, len - head, d, base);
		v_madd(dl->cam.xf.p, -1, base, to_cam);
		v_cross(d, to_cam, side);
		if (v_unit(side, side) < 1e-9) /* end on to the camera */
			v_perp(d, side);
		view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, THICK_WIDTH, 1);
		view_line(dl, p, base, C_LOAD);
		view_batch_begin(dl, VIEW_TRIANGLES, VIEW_WORLD, 1, 1);
		v_madd(base, 0.4 * head, side, a);
		v_madd(base, -0.4 * head, side, b);
		view_triangle(dl, tip, a, b, C_LOAD);
	}
	double axis[3];
	if (torque && v_unit(torque, axis) > 0)
		torque_ring(dl, p, axis);
	if (label && label[0]) {
		static const double up[3] = { 0, 1, 0 };
		double at[3];
		if (f > 0)
			v_madd(tip, 0.04, d, at);
		else
			v_madd(p, VIEW_LOAD_RING + 0.04, up, at);
		view_world_label(dl, at, label, C_LOAD);
	}
}
