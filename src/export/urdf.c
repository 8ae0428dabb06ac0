/* urdf.c - URDF export: the figure as robotics tools see it */
#include "export/urdf.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "export/export_file.h"
#include "export/seg_mesh.h"

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
write_inertial(FILE *f, const double com[3], double mass, const double I[6])
{
	fprintf(f, "    <inertial>\n");
	fprintf(f, "      <origin xyz=\"%.17g %.17g %.17g\" rpy=\"0 0 0\"/>\n", com[0], com[1],
		com[2]);
	fprintf(f, "      <mass value=\"%.17g\"/>\n", mass);
	fprintf(f,
		"      <inertia ixx=\"%.17g\" iyy=\"%.17g\" izz=\"%.17g\" ixy=\"%.17g\" "
		"ixz=\"%.17g\" iyz=\"%.17g\"/>\n",
		I[0], I[1], I[2], I[3], I[4], I[5]);
	fprintf(f, "    </inertial>\n");
}

/* the segment's mesh file as its look and its collision shape, in its own colour */
static void
write_geometry(FILE *f, const struct model *m, int seg, const char *mesh_stem)
{
	const float *c = &m->seg_rgba[4 * seg];
	for (int k = 0; k < 2; k++) {
		fprintf(f, "    <%s>\n", k ? "collision" : "visual");
		fprintf(f, "      <origin xyz=\"0 0 0\" rpy=\"0 0 0\"/>\n");
		fprintf(f, "      <geometry><mesh filename=\"%s%s.stl\"/></geometry>\n", mesh_stem,
			m->seg_name[seg]);
		if (!k)
			fprintf(f,
				"      <material name=\"%s\"><color rgba=\"%.4g %.4g %.4g %.4g\"/>"
				"</material>\n",
				m->seg_name[seg], c[0], c[1], c[2], c[3]);
		fprintf(f, "    </%s>\n", k ? "collision" : "visual");
	}
}

static void
write_link(FILE *f, const struct model *m, int seg, const char *mesh_stem)
{
	fprintf(f, "  <link name=\"%s\">\n", m->seg_name[seg]);
	write_inertial(f, &m->seg_com[3 * seg], m->seg_mass[seg], &m->seg_inertia[6 * seg]);
	if (mesh_stem && m->seg_ngeom[seg] > 0)
		write_geometry(f, m, seg, mesh_stem);
	fprintf(f, "  </link>\n");
}

/* a link of no mass in the figure: the least mass the simulators take (urdf.h) */
static void
write_negligible_link(FILE *f, const char *name)
{
	static const double at[3] = { 0, 0, 0 };
	static const double inertia[6] = { URDF_NEGLIGIBLE_INERTIA, URDF_NEGLIGIBLE_INERTIA,
					   URDF_NEGLIGIBLE_INERTIA, 0, 0, 0 };
	fprintf(f, "  <link name=\"%s\">\n", name);
	write_inertial(f, at, URDF_NEGLIGIBLE_MASS, inertia);
	fprintf(f, "  </link>\n");
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
		write_negligible_link(f, cur);
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

/* the state's posture, which URDF has no element for: a comment a person can read */
static void
write_posture(FILE *f, const struct model *m, const struct state *s)
{
	fprintf(f, "<!-- posture at export (radians, metres):");
	for (int d = 0; d < m->ndof; d++)
		fprintf(f, "%s %s__%d=%.17g", d % 4 ? "" : "\n    ", m->jnt_name[m->dof_jnt[d]],
			d - m->jnt_dof0[m->dof_jnt[d]], s->q[d]);
	fprintf(f, " -->\n");
}

int
urdf_write(const struct model *m, const struct state *s, const char *mesh_stem, FILE *f)
{
	fprintf(f, "<?xml version=\"1.0\"?>\n");
	fprintf(f, "<!-- exported by posture: %d segments, %d joints, %d dofs; root %s.%s -->\n",
		m->nseg, m->njnt, m->ndof, m->seg_name[m->site_seg[s->root_site]],
		m->site_name[s->root_site]);
	if (m->ndof)
		write_posture(f, m, s);
	fprintf(f, "<robot name=\"%s\">\n", m->name);
	/* MuJoCo's reading of URDF: keep fixed links (sites) as bodies and the visuals */
	fprintf(f, "  <mujoco><compiler fusestatic=\"false\" discardvisual=\"false\" "
		   "strippath=\"false\"/></mujoco>\n");
	write_negligible_link(f, "world");
	for (int i = 0; i < m->nseg; i++) {
		int seg = s->seg_order[i];
		write_link(f, m, seg, mesh_stem);
		if (i == 0)
			write_fixed(f, "world__root", "world", m->seg_name[seg], &s->seg_xf[seg]);
		else
			write_joint_chain(f, m, s, seg);
	}
	/*
	 * sites as massless links on fixed joints; the mass of 0 is written out,
	 * as PyBullet gives a link without <inertial> 1 kg
	 */
	static const double none[6] = { 0, 0, 0, 0, 0, 0 };
	for (int k = 0; k < m->nsite; k++) {
		char link[2 * MODEL_NAME_MAX + 8], joint[2 * MODEL_NAME_MAX + 16];
		const char *seg = m->seg_name[m->site_seg[k]];
		snprintf(link, sizeof link, "%s__%s", seg, m->site_name[k]);
		snprintf(joint, sizeof joint, "%s__joint", link);
		fprintf(f, "  <link name=\"%s\">\n", link);
		write_inertial(f, none, 0, none);
		fprintf(f, "  </link>\n");
		write_fixed(f, joint, seg, link, &m->site_loc[k]);
	}
	fprintf(f, "</robot>\n");
	return ferror(f) ? -1 : 0;
}

/* one segment's STL beside the URDF; 0, or -1 with why in err */
static int
write_mesh_file(const struct model *m, int seg, const char *path, char *err, size_t errlen)
{
	struct seg_mesh mesh;
	if (seg_mesh_build(m, seg, &mesh) < 0) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	FILE *f = export_fopen(path);
	int rc = f ? seg_mesh_write_stl(&mesh, m->seg_name[seg], f) : -1;
	if (f && fclose(f) != 0)
		rc = -1;
	if (rc < 0)
		snprintf(err, errlen, "%s: %s", path, strerror(errno));
	seg_mesh_free(&mesh);
	return rc;
}

/* segment seg's mesh file beside the URDF: 0, or -1 when the path is too long */
static int
mesh_path_of(const struct model *m, int seg, const char *dir, const char *stem, char *dest,
	     size_t len)
{
	return (size_t)snprintf(dest, len, "%s%s_%s.stl", dir, stem, m->seg_name[seg]) < len ? 0 : -1;
}

/* the mesh files of the segments before seg removed: a failed export leaves nothing */
static void
remove_meshes(const struct model *m, int seg, const char *dir, const char *stem)
{
	char path[4096 + 2 * MODEL_NAME_MAX];
	for (int k = 0; k < seg; k++)
		if (m->seg_ngeom[k] && mesh_path_of(m, k, dir, stem, path, sizeof path) == 0)
			unlink(path);
}

int
urdf_export(const struct model *m, const struct state *s, const char *path, char *err,
	    size_t errlen)
{
	char dir[4096], stem[4096], mesh_path[4096 + 2 * MODEL_NAME_MAX];
	if (export_split_path(path, ".urdf", dir, sizeof dir, stem, sizeof stem, err, errlen) < 0)
		return -1;
	int files = 0;
	for (int seg = 0; seg < m->nseg; seg++) {
		if (!m->seg_ngeom[seg])
			continue;
		if (mesh_path_of(m, seg, dir, stem, mesh_path, sizeof mesh_path) < 0) {
			snprintf(err, errlen, "path too long");
			remove_meshes(m, seg, dir, stem);
			return -1;
		}
		if (write_mesh_file(m, seg, mesh_path, err, errlen) < 0) {
			remove_meshes(m, seg + 1, dir, stem);
			return -1;
		}
		files++;
	}
	char mesh_stem[4096 + 2];
	snprintf(mesh_stem, sizeof mesh_stem, "%s_", stem);
	struct export_file out;
	FILE *f = export_file_open(&out, path, err, errlen);
	if (f)
		urdf_write(m, s, mesh_stem, f);
	if (!f || export_file_commit(&out, err, errlen) < 0) {
		remove_meshes(m, m->nseg, dir, stem);
		return -1;
	}
	return files + 1;
}
