/* kin.c - forward kinematics, Jacobians and centres of mass (§A.4.1) */
#include "figure/kin.h"

#include <string.h>

/* dest = dest * elementary dof transform, updating only what changes */
static void
apply_dof(struct xform *f, int kind, int axis, int sign, double value)
{
	if (kind == DOF_TRANSLATION) {
		double d = sign * value;
		for (int r = 0; r < 3; r++)
			f->p[r] += f->r[3 * r + axis] * d;
		return;
	}
	double c = cos(value), sn = sign * sin(value);
	int i = (axis + 1) % 3, j = (axis + 2) % 3;
	for (int r = 0; r < 3; r++) {
		double fi = f->r[3 * r + i], fj = f->r[3 * r + j];
		f->r[3 * r + i] = c * fi + sn * fj;
		f->r[3 * r + j] = -sn * fi + c * fj;
	}
}

static void
record_axis(const struct model *m, struct state *s, int d, const struct xform *f)
{
	int a = m->dof_axis[d], sg = m->dof_sign[d];
	for (int r = 0; r < 3; r++) {
		s->dof_axis_w[3 * d + r] = sg * f->r[3 * r + a];
		s->dof_pivot_w[3 * d + r] = f->p[r];
	}
}

/* global frame of the site at the top of segment seg, from its parent */
static void
top_site_frame(const struct model *m, struct state *s, int seg, struct xform *dest)
{
	int j = s->seg_root_joint[seg];
	int d0 = m->jnt_dof0[j], n = m->jnt_ndof[j];
	if (s->jnt_dir[j] > 0) {
		/* from-site above: X_to = X_from * D_0 ... D_n-1 */
		*dest = s->site_xf[m->jnt_site_from[j]];
		for (int d = d0; d < d0 + n; d++) {
			record_axis(m, s, d, dest);
			apply_dof(dest, m->dof_kind[d], m->dof_axis[d], m->dof_sign[d], s->q[d]);
		}
	} else {
		/* inverted: X_from = X_to * D_n-1^-1 ... D_0^-1; after undoing
		 * dof d the frame is X_from * D_0 ... D_d-1, the frame of dof d */
		*dest = s->site_xf[m->jnt_site_to[j]];
		for (int d = d0 + n - 1; d >= d0; d--) {
			apply_dof(dest, m->dof_kind[d], m->dof_axis[d], m->dof_sign[d], -s->q[d]);
			record_axis(m, s, d, dest);
		}
	}
}

/* one segment from its parent's (already current) frames */
static void
forward_segment(const struct model *m, struct state *s, int seg)
{
	int top = s->seg_root_site[seg];
	struct xform xtop;
	if (s->seg_root_joint[seg] < 0)
		xtop = s->root_xf;
	else
		top_site_frame(m, s, seg, &xtop);
	struct xform *sx = &s->seg_xf[seg];
	if (m->site_pure[top]) { /* the common case: sites placed by translation */
		memcpy(sx->r, xtop.r, sizeof sx->r);
		xform_apply(&xtop, m->site_loc_inv[top].p, sx->p);
	} else {
		xform_mul(&xtop, &m->site_loc_inv[top], sx);
	}
	int k0 = m->seg_site0[seg], nk = m->seg_nsite[seg];
	for (int k = k0; k < k0 + nk; k++) {
		struct xform *kx = &s->site_xf[k];
		if (k == top) {
			*kx = xtop;
		} else if (m->site_pure[k]) {
			memcpy(kx->r, sx->r, sizeof kx->r);
			xform_apply(sx, m->site_loc[k].p, kx->p);
		} else {
			xform_mul(sx, &m->site_loc[k], kx);
		}
	}
}

void
kin_forward(const struct model *m, struct state *s)
{
	for (int i = 0; i < m->nseg; i++)
		forward_segment(m, s, s->seg_order[i]);
}

void
kin_forward_segments(const struct model *m, struct state *s, const int *segs, int n)
{
	for (int i = 0; i < n; i++)
		forward_segment(m, s, segs[i]);
}

void
kin_com(const struct model *m, struct state *s)
{
	for (int seg = 0; seg < m->nseg; seg++) {
		double *c = &s->seg_com_w[3 * seg];
		xform_apply(&s->seg_xf[seg], &m->seg_com[3 * seg], c);
		s->subtree_mass[seg] = m->seg_mass[seg];
		for (int r = 0; r < 3; r++)
			s->subtree_com[3 * seg + r] = m->seg_mass[seg] * c[r];
	}
	/* bottom-up: accumulate mass-weighted sums into parents */
	for (int i = m->nseg - 1; i > 0; i--) {
		int seg = s->seg_order[i], p = s->seg_parent[seg];
		s->subtree_mass[p] += s->subtree_mass[seg];
		for (int r = 0; r < 3; r++)
			s->subtree_com[3 * p + r] += s->subtree_com[3 * seg + r];
	}
	for (int seg = 0; seg < m->nseg; seg++) {
		double w = s->subtree_mass[seg] > 0 ? 1.0 / s->subtree_mass[seg] : 0;
		for (int r = 0; r < 3; r++) {
			if (w > 0)
				s->subtree_com[3 * seg + r] *= w;
			else /* massless sub-tree: use its segment frame origin */
				s->subtree_com[3 * seg + r] = s->seg_xf[seg].p[r];
		}
	}
	memcpy(s->com, &s->subtree_com[3 * s->seg_order[0]], sizeof s->com);
}

void
kin_update(const struct model *m, struct state *s)
{
	kin_forward(m, s);
	kin_com(m, s);
}

int
kin_set_root(const struct model *m, struct state *s, int site)
{
	if (site < 0 || site >= m->nsite)
		return -1;
	struct xform at = s->site_xf[site];
	if (state_root_at(m, s, site, &at) < 0)
		return -1;
	kin_update(m, s);
	return 0;
}

/* column of dof d for a point x: rotation w x (x - p), translation w */
static void
dof_column(const struct model *m, const struct state *s, int d, int dir, const double x[3],
	   double col[3])
{
	const double *w = &s->dof_axis_w[3 * d];
	if (m->dof_kind[d] == DOF_TRANSLATION) {
		for (int r = 0; r < 3; r++)
			col[r] = dir * w[r];
		return;
	}
	const double *p = &s->dof_pivot_w[3 * d];
	double rel[3] = { x[0] - p[0], x[1] - p[1], x[2] - p[2] };
	mathx_cross(w, rel, col);
	for (int r = 0; r < 3; r++)
		col[r] *= dir;
}

void
kin_point_jacobian(const struct model *m, const struct state *s, int seg, const double point_w[3],
		   double *dest)
{
	int n = m->ndof;
	memset(dest, 0, sizeof(double) * 3 * (size_t)n);
	/* upward traversal: segment -> root joint -> parent (§A.4.2) */
	for (int t = seg; s->seg_root_joint[t] >= 0; t = s->seg_parent[t]) {
		int j = s->seg_root_joint[t], dir = s->jnt_dir[j];
		for (int d = m->jnt_dof0[j]; d < m->jnt_dof0[j] + m->jnt_ndof[j]; d++) {
			double col[3];
			dof_column(m, s, d, dir, point_w, col);
			for (int r = 0; r < 3; r++)
				dest[r * n + d] = col[r];
		}
	}
}

void
kin_site_jacobian(const struct model *m, const struct state *s, int site, double *dest)
{
	int n = m->ndof, seg = m->site_seg[site];
	kin_point_jacobian(m, s, seg, s->site_xf[site].p, dest);
	memset(dest + 3 * n, 0, sizeof(double) * 3 * (size_t)n);
	for (int t = seg; s->seg_root_joint[t] >= 0; t = s->seg_parent[t]) {
		int j = s->seg_root_joint[t], dir = s->jnt_dir[j];
		for (int d = m->jnt_dof0[j]; d < m->jnt_dof0[j] + m->jnt_ndof[j]; d++) {
			if (m->dof_kind[d] != DOF_ROTATION)
				continue;
			for (int r = 0; r < 3; r++)
				dest[(3 + r) * n + d] = dir * s->dof_axis_w[3 * d + r];
		}
	}
}

void
kin_com_jacobian(const struct model *m, const struct state *s, double *dest)
{
	int n = m->ndof;
	double total = s->subtree_mass[s->seg_order[0]];
	memset(dest, 0, sizeof(double) * 3 * (size_t)n);
	if (total <= 0)
		return;
	/* a dof moves the mass of the sub-tree below its joint, as one body */
	for (int j = 0; j < m->njnt; j++) {
		int c = s->jnt_child_seg[j];
		double frac = s->subtree_mass[c] / total;
		for (int d = m->jnt_dof0[j]; d < m->jnt_dof0[j] + m->jnt_ndof[j]; d++) {
			double col[3];
			dof_column(m, s, d, s->jnt_dir[j], &s->subtree_com[3 * c], col);
			for (int r = 0; r < 3; r++)
				dest[r * n + d] = frac * col[r];
		}
	}
}

int
kin_dof_moves(const struct model *m, const struct state *s, int dof, int seg)
{
	int c = s->jnt_child_seg[m->dof_jnt[dof]];
	for (int t = seg; t >= 0; t = s->seg_parent[t])
		if (t == c)
			return 1;
	return 0;
}

void
kin_joint_xform(const struct model *m, const struct state *s, int j, struct xform *dest)
{
	xform_identity(dest);
	for (int d = m->jnt_dof0[j]; d < m->jnt_dof0[j] + m->jnt_ndof[j]; d++)
		apply_dof(dest, m->dof_kind[d], m->dof_axis[d], m->dof_sign[d], s->q[d]);
}
