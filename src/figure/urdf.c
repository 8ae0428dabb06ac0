/* urdf.c - URDF export: the figure as robotics tools see it */
#include "figure/urdf.h"

#include <math.h>

/* fixed-axis roll-pitch-yaw of a rotation matrix, R = Rz(y) Ry(p) Rx(r) */
static void
rpy_of(const double r[9], double dest[3])
{
	double cp = hypot(r[0], r[3]);
	dest[1] = atan2(-r[6], cp);
	if (cp > 1e-12) {
		dest[0] = atan2(r[7], r[8]);
		dest[2] = atan2(r[3], r[0]);
	} else { /* gimbal lock: put all of the remaining rotation in roll */
		dest[0] = atan2(-r[5], r[4]);
		dest[2] = 0;
	}
}

static void
write_origin(FILE *f, const struct xform *x)
{
	double rpy[3];
	rpy_of(x->r, rpy);
	fprintf(f, "    <origin xyz=\"%.17g %.17g %.17g\" rpy=\"%.17g %.17g %.17g\"/>\n", x->p[0],
		x->p[1], x->p[2], rpy[0], rpy[1], rpy[2]);
}

static void
write_link(FILE *f, const struct model *m, int seg)
{
	fprintf(f, "  <link name=\"%s\">\n", m->seg_name[seg]);
	const double *c = &m->seg_com[3 * seg], *I = &m->seg_inertia[6 * seg];
	fprintf(f, "    <inertial>\n");
	fprintf(f, "      <origin xyz=\"%.17g %.17g %.17g\" rpy=\"0 0 0\"/>\n", c[0], c[1], c[2]);
	fprintf(f, "      <mass value=\"%.17g\"/>\n", m->seg_mass[seg]);
	fprintf(f,
		"      <inertia ixx=\"%.17g\" iyy=\"%.17g\" izz=\"%.17g\" ixy=\"%.17g\" "
		"ixz=\"%.17g\" iyz=\"%.17g\"/>\n",
		I[0], I[1], I[2], I[3], I[4], I[5]);
	fprintf(f, "    </inertial>\n  </link>\n");
}

static void
write_fixed(FILE *f, const char *name, const char *parent, const char *child,
	    const struct xform *origin)
{
	fprintf(f, "  <joint name=\"%s\" type=\"fixed\">\n", name);
	fprintf(f, "    <parent link=\"%s\"/>\n    <child link=\"%s\"/>\n", parent, child);
	write_origin(f, origin);
	fprintf(f, "  </joint>\n");
}

/*
 * One URDF joint per dof. Walking down the tree through an inverted joint
 * undoes its dofs last to first, each about its negated axis (§A.4.1).
 */
static void
write_joint_chain(FILE *f, const struct model *m, const struct state *s, int seg)
{
	int j = s->seg_root_joint[seg], parent = s->seg_parent[seg], dir = s->jnt_dir[j];
	int above = dir > 0 ? m->jnt_site_from[j] : m->jnt_site_to[j];
	int below = dir > 0 ? m->jnt_site_to[j] : m->jnt_site_from[j];
	int n = m->jnt_ndof[j], d0 = m->jnt_dof0[j];
	char prev[2 * MODEL_NAME_MAX + 16], cur[2 * MODEL_NAME_MAX + 16];
	snprintf(prev, sizeof prev, "%s", m->seg_name[parent]);
	struct xform origin = m->site_loc[above];
	for (int i = 0; i < n; i++) {
		int k = dir > 0 ? i : n - 1 - i, d = d0 + k;
		double axis[3] = { 0, 0, 0 };
		axis[m->dof_axis[d]] = dir * m->dof_sign[d];
		snprintf(cur, sizeof cur, "%s__%d_link", m->jnt_name[j], k);
		fprintf(f, "  <link name=\"%s\"/>\n", cur);
		fprintf(f, "  <joint name=\"%s__%d\" type=\"%s\">\n", m->jnt_name[j], k,
			m->dof_kind[d] == DOF_ROTATION ? "revolute" : "prismatic");
		fprintf(f, "    <parent link=\"%s\"/>\n    <child link=\"%s\"/>\n", prev, cur);
		write_origin(f, &origin);
		fprintf(f, "    <axis xyz=\"%g %g %g\"/>\n", axis[0], axis[1], axis[2]);
		fprintf(f,
			"    <limit lower=\"%.17g\" upper=\"%.17g\" effort=\"1000\" "
			"velocity=\"10\"/>\n",
			m->dof_lo[d], m->dof_hi[d]);
		fprintf(f, "  </joint>\n");
		xform_identity(&origin);
		snprintf(prev, sizeof prev, "%s", cur);
	}
	/* from the last dof frame to the child's segment frame */
	struct xform to_child;
	xform_mul_inv(&origin, &m->site_loc[below], &to_child);
	snprintf(cur, sizeof cur, "%s__fixed", m->jnt_name[j]);
	write_fixed(f, cur, prev, m->seg_name[seg], &to_child);
}

int
urdf_write(const struct model *m, const struct state *s, FILE *f)
{
	fprintf(f, "<?xml version=\"1.0\"?>\n");
	fprintf(f, "<!-- exported by posture: %d segments, %d joints, %d dofs; root %s.%s -->\n",
		m->nseg, m->njnt, m->ndof, m->seg_name[m->site_seg[s->root_site]],
		m->site_name[s->root_site]);
	fprintf(f, "<robot name=\"%s\">\n", m->name);
	fprintf(f, "  <link name=\"world\"/>\n");
	for (int i = 0; i < m->nseg; i++) {
		int seg = s->seg_order[i];
		write_link(f, m, seg);
		if (i == 0)
			write_fixed(f, "world__root", "world", m->seg_name[seg], &s->seg_xf[seg]);
		else
			write_joint_chain(f, m, s, seg);
	}
	/* sites as massless links on fixed joints */
	for (int k = 0; k < m->nsite; k++) {
		char link[2 * MODEL_NAME_MAX + 8], joint[2 * MODEL_NAME_MAX + 16];
		const char *seg = m->seg_name[m->site_seg[k]];
		snprintf(link, sizeof link, "%s__%s", seg, m->site_name[k]);
		snprintf(joint, sizeof joint, "%s__joint", link);
		fprintf(f, "  <link name=\"%s\"/>\n", link);
		write_fixed(f, joint, seg, link, &m->site_loc[k]);
	}
	fprintf(f, "</robot>\n");
	return ferror(f) ? -1 : 0;
}
