/* ik_energy.c - the potential energy of the constraints, its gradient, and the step factor */
#include <string.h>

#include "pose/ik_energy.h"
#include "figure/kin.h"

void
ik_con_frames(const struct ik_con *c, const struct model *m, const struct state *s,
	      struct xform *eff, struct xform *gpos, struct xform *gori)
{
	const struct ik_constraint_def *d = &c->def;
	const struct xform *site = &s->site_xf[d->effector_site];
	(void)m;
	if (d->com_effector) {
		eff->p[0] = eff->p[1] = eff->p[2] = 0;
		memcpy(eff->r, site->r, sizeof eff->r);
		xform_apply(site, c->com_local, eff->p);
	} else {
		xform_mul(site, &d->effector_offset, eff);
	}
	if (d->goal_site >= 0) {
		xform_mul(&s->site_xf[d->goal_site], &c->goal_pos, gpos);
		xform_mul(&s->site_xf[d->goal_site], &c->goal_ori, gori);
	} else {
		*gpos = c->goal_pos;
		*gori = c->goal_ori;
	}
}

/* velocity of a point fixed to the moving side, and angular velocity, per unit of dof d */
static void
dof_motion(const struct model *m, const struct state *s, int d, const double point[3],
	   double v[3], double w[3])
{
	int dir = s->jnt_dir[m->dof_jnt[d]];
	const double *axis = &s->dof_axis_w[3 * d];
	if (m->dof_kind[d] == DOF_TRANSLATION) {
		for (int r = 0; r < 3; r++) {
			v[r] = dir * axis[r];
			w[r] = 0;
		}
		return;
	}
	const double *pivot = &s->dof_pivot_w[3 * d];
	double rel[3] = { point[0] - pivot[0], point[1] - pivot[1], point[2] - pivot[2] };
	for (int r = 0; r < 3; r++)
		w[r] = dir * axis[r];
	mathx_cross(w, rel, v);
}

static void
rotate_vec(const double r[9], const double v[3], double dest[3])
{
	for (int i = 0; i < 3; i++)
		dest[i] = r[3 * i] * v[0] + r[3 * i + 1] * v[1] + r[3 * i + 2] * v[2];
}

static double
norm3(const double v[3])
{
	return sqrt(mathx_dot(v, v));
}

static void perpendicular(const double v[3], double dest[3]);

/*
 * A constraint's energy is a weighted sum of squares of a residual vector:
 * wp |r_pos|^2 + wo |r_ori|^2, r_pos the position residual (3 components,
 * or 1 for a plane), r_ori the orientation residual: for frame and
 * direction the rotation vector (angle times axis) still to turn, so the
 * energy is the squared angle and stays well shaped for large angles; for
 * aim the difference of the aim vector and the unit vector to the goal. The gradient and the
 * Gauss-Newton metric both come from the residual's derivatives.
 */
struct con_terms {
	double wp, wo;
	int np, no;       /* residual components: position, then orientation */
	double r[12];
	double a[3];      /* line direction or plane normal, world */
	double d0[3];     /* effector origin - goal origin */
	double u[3][3], v[3][3]; /* effector and goal axes (frame), or vectors (direction) */
	double t[3], len; /* aim: unit vector to the goal and distance */
};

/* residual of one constraint; fills the terms its derivatives need and its errors */
static double
con_residual(struct ik_con *c, const struct xform *E, const struct xform *Gp,
	     const struct xform *Go, struct con_terms *k)
{
	const struct ik_constraint_def *d = &c->def;
	k->wp = d->pos == IK_POS_NONE ? 0 : d->weight * d->pos_weight;
	k->wo = d->ori == IK_ORI_NONE ? 0 : d->weight * (1 - d->pos_weight);
	k->np = k->no = 0;
	c->pos_err = c->ori_err = 0;
	for (int i = 0; i < 3; i++)
		k->d0[i] = E->p[i] - Gp->p[i];
	switch (d->pos) {
	case IK_POS_NONE:
		break;
	case IK_POINT:
		memcpy(k->r, k->d0, sizeof k->d0);
		k->np = 3;
		break;
	case IK_LINE: {
		rotate_vec(Gp->r, d->goal_axis, k->a);
		double along = mathx_dot(k->a, k->d0);
		for (int i = 0; i < 3; i++)
			k->r[i] = k->d0[i] - along * k->a[i];
		k->np = 3;
		break;
	}
	case IK_PLANE:
		rotate_vec(Gp->r, d->goal_axis, k->a);
		k->r[0] = mathx_dot(k->a, k->d0);
		k->np = 1;
		break;
	}
	double *ro = &k->r[k->np];
	switch (d->ori) {
	case IK_ORI_NONE:
		break;
	case IK_FRAME: {
		/* the rotation vector of goal * effector^T: angle times world axis */
		double et[9], rel[9], q[4];
		for (int i = 0; i < 3; i++)
			for (int j = 0; j < 3; j++)
				et[3 * i + j] = E->r[3 * j + i];
		mathx_mat3_mul(Go->r, et, rel);
		mathx_mat_to_quat(rel, q);
		double sn = norm3(q), angle = 2 * atan2(sn, q[3]);
		double scale = sn > 1e-12 ? angle / sn : 2; /* 2 q_v as the angle vanishes */
		for (int r = 0; r < 3; r++)
			ro[r] = scale * q[r];
		k->no = 3;
		c->ori_err = angle;
		break;
	}
	case IK_DIRECTION: {
		/* angle times the unit axis that turns the effector vector onto the goal's */
		double x[3];
		rotate_vec(E->r, d->effector_axis, k->u[0]);
		rotate_vec(Go->r, d->goal_axis, k->v[0]);
		mathx_cross(k->u[0], k->v[0], x);
		double sn = norm3(x), angle = atan2(sn, mathx_dot(k->u[0], k->v[0]));
		if (sn < 1e-12 && angle > 1) /* opposite: any axis across u */
			perpendicular(k->u[0], x), sn = 1;
		double scale = sn > 1e-12 ? angle / sn : 1;
		for (int r = 0; r < 3; r++)
			ro[r] = scale * x[r];
		k->no = 3;
		c->ori_err = angle;
		break;
	}
	case IK_AIM: {
		double to[3] = { Go->p[0] - E->p[0], Go->p[1] - E->p[1], Go->p[2] - E->p[2] }, x[3];
		rotate_vec(E->r, d->effector_axis, k->u[0]);
		k->len = norm3(to);
		if (k->len < 1e-9) /* goal at the eye: any direction aims at it */
			break;
		for (int r = 0; r < 3; r++) {
			k->t[r] = to[r] / k->len;
			ro[r] = k->u[0][r] - k->t[r];
		}
		k->no = 3;
		mathx_cross(k->u[0], k->t, x);
		c->ori_err = atan2(norm3(x), mathx_dot(k->u[0], k->t));
		break;
	}
	}
	double ep = 0, eo = 0;
	for (int i = 0; i < k->np; i++)
		ep += k->r[i] * k->r[i];
	for (int i = 0; i < k->no; i++)
		eo += ro[i] * ro[i];
	if (k->np)
		c->pos_err = sqrt(ep);
	return k->wp * ep + k->wo * eo;
}

/*
 * Derivative of the residual for one variable, from the motion it causes:
 * ve, we at the effector; vg, wg at the position goal; vgo at the
 * orientation goal's origin (aim).
 */
static void
con_residual_deriv(const struct ik_con *c, const struct con_terms *k, const double ve[3],
		   const double we[3], const double vg[3], const double wg[3],
		   const double vgo[3], double *dr)
{
	const struct ik_constraint_def *d = &c->def;
	double dlt[3] = { ve[0] - vg[0], ve[1] - vg[1], ve[2] - vg[2] }, da[3];
	switch (d->pos) {
	case IK_POS_NONE:
		break;
	case IK_POINT:
		memcpy(dr, dlt, sizeof dlt);
		break;
	case IK_LINE: {
		/* r = (I - a a^T) d0 with a turning with the goal */
		mathx_cross(wg, k->a, da);
		double ad = mathx_dot(k->a, dlt), a0 = mathx_dot(k->a, k->d0), dd = mathx_dot(da, k->d0);
		for (int r = 0; r < 3; r++)
			dr[r] = dlt[r] - ad * k->a[r] - a0 * da[r] - dd * k->a[r];
		break;
	}
	case IK_PLANE:
		mathx_cross(wg, k->a, da);
		dr[0] = mathx_dot(k->a, dlt) + mathx_dot(da, k->d0);
		break;
	}
	double *dro = dr + k->np, x[3];
	switch (d->ori) {
	case IK_ORI_NONE:
		break;
	case IK_FRAME:
		/* d r = J^-1 (wg - we) with r^T J^-1 = r^T: exact for the gradient,
		 * the small-angle metric for Gauss-Newton */
		for (int r = 0; r < 3; r++)
			dro[r] = wg[r] - we[r];
		break;
	case IK_DIRECTION: {
		/* turning about the effector vector itself changes nothing */
		double w[3] = { wg[0] - we[0], wg[1] - we[1], wg[2] - we[2] };
		double along = mathx_dot(w, k->u[0]);
		for (int r = 0; r < 3; r++)
			dro[r] = w[r] - along * k->u[0][r];
		break;
	}
	case IK_AIM: {
		if (!k->no)
			break;
		/* d t = (I - t t^T) d(goal - effector) / len */
		double rel[3] = { vgo[0] - ve[0], vgo[1] - ve[1], vgo[2] - ve[2] };
		double tr = mathx_dot(k->t, rel);
		mathx_cross(we, k->u[0], x);
		for (int r = 0; r < 3; r++)
			dro[r] = x[r] - (rel[r] - tr * k->t[r]) / k->len;
		break;
	}
	}
}

/* limit spring of variable v (§D.1.6): zero until within its angle of the limit */
static double
spring_energy(const struct ik_terms *e, int v, double q, double *grad, double *metric)
{
	int d = e->var_dof[v];
	double a = e->spring_angle[d], w = e->spring_weight[d], z;
	*grad = *metric = 0;
	if (w <= 0)
		return 0;
	if (e->spring_side[d] < 0) {
		z = (e->lo[v] + a - q) / a;
		if (z <= 0)
			return 0;
		*grad = -2 * w * z / a;
		*metric = 2 * w / (a * a);
	} else {
		z = (q - (e->hi[v] - a)) / a;
		if (z <= 0)
			return 0;
		*grad = 2 * w * z / a;
		*metric = 2 * w / (a * a);
	}
	return w * z * z;
}

void
ik_con_errors(struct ik_con *c, const struct xform *E, const struct xform *Gp,
	      const struct xform *Go)
{
	struct con_terms k;
	con_residual(c, E, Gp, Go, &k);
}

double
ik_energy_eval(struct ik_terms *e, const struct model *m, struct state *s, const double *x,
	       double *grad, double *metric)
{
	int n = e->nvar;
	for (int i = 0; i < n; i++)
		s->q[e->var_dof[i]] = x[i];
	kin_forward_segments(m, s, e->dyn_seg, e->ndyn);
	double f = 0;
	if (grad)
		memset(grad, 0, sizeof *grad * (size_t)n);
	if (metric)
		memset(metric, 0, sizeof *metric * (size_t)n * (size_t)n);
	for (int ci = 0; ci < e->n; ci++) {
		if (!e->in_group[ci])
			continue;
		struct ik_con *c = &e->con[ci];
		struct xform E, Gp, Go;
		struct con_terms k;
		ik_con_frames(c, m, s, &E, &Gp, &Go);
		f += con_residual(c, &E, &Gp, &Go, &k);
		if (!grad || k.np + k.no == 0)
			continue;
		const unsigned char *me = &e->moves_eff[ci * e->ndof];
		const unsigned char *mg = &e->moves_goal[ci * e->ndof];
		int nr = k.np + k.no;
		double w[12];
		for (int i = 0; i < nr; i++)
			w[i] = i < k.np ? k.wp : k.wo;
		for (int v = 0; v < n; v++) {
			double *dr = &e->jr[v * IK_RESIDUAL_MAX];
			if (!me[v] && !mg[v]) {
				memset(dr, 0, sizeof *dr * IK_RESIDUAL_MAX);
				continue;
			}
			int d = e->var_dof[v];
			double ve[3] = { 0 }, we[3] = { 0 }, vg[3] = { 0 }, wg[3] = { 0 }, vgo[3] = { 0 };
			if (me[v])
				dof_motion(m, s, d, E.p, ve, we);
			if (mg[v]) {
				dof_motion(m, s, d, Gp.p, vg, wg);
				if (c->def.ori == IK_AIM)
					dof_motion(m, s, d, Go.p, vgo, wg);
			}
			con_residual_deriv(c, &k, ve, we, vg, wg, vgo, dr);
			double gk = 0;
			for (int i = 0; i < nr; i++)
				gk += w[i] * k.r[i] * dr[i];
			grad[v] += 2 * gk;
		}
		if (!metric)
			continue;
		/* Gauss-Newton: 2 J^T W J over this constraint's residual */
		for (int a = 0; a < n; a++) {
			const double *ja = &e->jr[a * IK_RESIDUAL_MAX];
			for (int b = a; b < n; b++) {
				const double *jb = &e->jr[b * IK_RESIDUAL_MAX];
				double acc = 0;
				for (int i = 0; i < nr; i++)
					acc += w[i] * ja[i] * jb[i];
				metric[a * n + b] += 2 * acc;
			}
		}
	}
	e->spring_f = 0;
	for (int v = 0; v < n; v++) {
		double gs, hs, fs = spring_energy(e, v, x[v], &gs, &hs);
		f += fs;
		e->spring_f += fs;
		if (grad)
			grad[v] += gs;
		if (metric)
			metric[v * n + v] += hs;
	}
	if (metric) /* symmetric: fill the lower triangle */
		for (int a = 0; a < n; a++)
			for (int b = 0; b < a; b++)
				metric[a * n + b] = metric[b * n + a];
	return f;
}

int
ik_energy_met(const struct ik_terms *e, double tol_pos, double tol_ori)
{
	/* a spring under tension is still working: only stationarity ends it */
	if (e->spring_f > 0)
		return 0;
	for (int ci = 0; ci < e->n; ci++) {
		if (!e->in_group[ci])
			continue;
		const struct ik_con *c = &e->con[ci];
		const struct ik_constraint_def *d = &c->def;
		if (d->pos != IK_POS_NONE && d->pos_weight > 0 && c->pos_err > tol_pos)
			return 0;
		if (d->ori != IK_ORI_NONE && d->pos_weight < 1 && c->ori_err > tol_ori)
			return 0;
	}
	return 1;
}

/* rotation matrix about a unit axis */
static void
axis_rotation(const double axis[3], double angle, double dest[9])
{
	double q[4];
	mathx_quat_axis_angle(axis, angle, q);
	mathx_quat_to_mat(q, dest);
}

/* any unit vector perpendicular to v */
static void
perpendicular(const double v[3], double dest[3])
{
	double e[3] = { 0, 0, 0 };
	e[fabs(v[0]) < 0.6 ? 0 : 1] = 1;
	mathx_cross(v, e, dest);
	double n = norm3(dest);
	for (int r = 0; r < 3; r++)
		dest[r] /= n;
}

/* unit axis of the rotation taking a to b (both unit), or a perpendicular when opposite */
static void
turn_axis(const double a[3], const double b[3], double dest[3])
{
	mathx_cross(a, b, dest);
	double n = norm3(dest);
	if (n < 1e-12) {
		perpendicular(a, dest);
		return;
	}
	for (int r = 0; r < 3; r++)
		dest[r] /= n;
}

/* shortens the position goal to step metres from the effector; 1 when it did */
static int
step_position(const struct ik_constraint_def *d, const struct xform *E, struct xform *G,
	      double step)
{
	double target[3], a[3], d0[3];
	for (int r = 0; r < 3; r++)
		d0[r] = G->p[r] - E->p[r];
	switch (d->pos) {
	case IK_POS_NONE:
		return 0;
	case IK_POINT:
		memcpy(target, G->p, sizeof target);
		break;
	case IK_LINE: {
		rotate_vec(G->r, d->goal_axis, a);
		double along = mathx_dot(a, d0);
		for (int r = 0; r < 3; r++)
			target[r] = G->p[r] - along * a[r];
		break;
	}
	case IK_PLANE: {
		rotate_vec(G->r, d->goal_axis, a);
		double dist = mathx_dot(a, d0);
		for (int r = 0; r < 3; r++)
			target[r] = E->p[r] + dist * a[r];
		break;
	}
	}
	double gap[3] = { target[0] - E->p[0], target[1] - E->p[1], target[2] - E->p[2] };
	double dist = norm3(gap);
	if (dist <= step)
		return 0;
	/* slide the whole goal (line, plane) so its nearest point is step away */
	for (int r = 0; r < 3; r++)
		G->p[r] -= gap[r] * (1 - step / dist);
	return 1;
}

/* turns the orientation goal to step radians from the effector; 1 when it did */
static int
step_orientation(const struct ik_constraint_def *d, const struct xform *E, struct xform *G,
		 double step)
{
	switch (d->ori) {
	case IK_ORI_NONE:
		return 0;
	case IK_FRAME: {
		double rel[9], q[4], et[9];
		for (int i = 0; i < 3; i++)
			for (int j = 0; j < 3; j++)
				et[3 * i + j] = E->r[3 * j + i];
		mathx_mat3_mul(et, G->r, rel);
		mathx_mat_to_quat(rel, q);
		double sn = norm3(q), angle = 2 * atan2(sn, q[3]);
		if (angle <= step || sn < 1e-15)
			return 0;
		double axis[3] = { q[0] / sn, q[1] / sn, q[2] / sn }, part[9];
		axis_rotation(axis, step, part);
		mathx_mat3_mul(E->r, part, G->r);
		return 1;
	}
	case IK_DIRECTION: {
		double u[3], v[3], axis[3], turn[9], r[9];
		rotate_vec(E->r, d->effector_axis, u);
		rotate_vec(G->r, d->goal_axis, v);
		double x[3];
		mathx_cross(v, u, x);
		double angle = atan2(norm3(x), mathx_dot(u, v));
		if (angle <= step)
			return 0;
		turn_axis(v, u, axis);
		axis_rotation(axis, angle - step, turn);
		mathx_mat3_mul(turn, G->r, r);
		memcpy(G->r, r, sizeof r);
		return 1;
	}
	case IK_AIM: {
		double u[3], t[3], axis[3], turn[9], x[3];
		rotate_vec(E->r, d->effector_axis, u);
		for (int r = 0; r < 3; r++)
			t[r] = G->p[r] - E->p[r];
		double len = norm3(t);
		if (len < 1e-9)
			return 0;
		for (int r = 0; r < 3; r++)
			t[r] /= len;
		mathx_cross(t, u, x);
		double angle = atan2(norm3(x), mathx_dot(u, t));
		if (angle <= step)
			return 0;
		turn_axis(t, u, axis);
		axis_rotation(axis, angle - step, turn);
		rotate_vec(turn, t, x);
		for (int r = 0; r < 3; r++)
			G->p[r] = E->p[r] + len * x[r];
		return 1;
	}
	}
	return 0;
}

int
ik_energy_step_factor(struct ik_terms *e, const struct model *m, const struct state *s,
		      double step_pos, double step_ori)
{
	int stepped = 0;
	for (int ci = 0; ci < e->n; ci++) {
		struct ik_con *c = &e->con[ci];
		const struct ik_constraint_def *d = &c->def;
		c->goal_pos = c->goal_ori = d->goal_xf;
		if (!d->enabled)
			continue;
		struct xform E, Gp, Go;
		ik_con_frames(c, m, s, &E, &Gp, &Go);
		int sp = step_pos > 0 && step_position(d, &E, &Gp, step_pos);
		int so = step_ori > 0 && step_orientation(d, &E, &Go, step_ori);
		/* intermediate goals of a site goal stay relative to that site */
		if (d->goal_site >= 0) {
			struct xform inv;
			xform_inv(&s->site_xf[d->goal_site], &inv);
			if (sp)
				xform_mul(&inv, &Gp, &c->goal_pos);
			if (so)
				xform_mul(&inv, &Go, &c->goal_ori);
		} else {
			if (sp)
				c->goal_pos = Gp;
			if (so)
				c->goal_ori = Go;
		}
		stepped |= sp | so;
	}
	return stepped;
}
