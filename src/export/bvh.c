/* bvh.c - BVH: a skeleton from the figure's sites, its postures as motion frames */
#include "export/bvh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "export/export_file.h"

/* the parent-side site of the joint above seg */
static int
pivot_site(const struct model *m, const struct state *s, int seg)
{
	int j = s->seg_root_joint[seg];
	return s->jnt_dir[j] > 0 ? m->jnt_site_from[j] : m->jnt_site_to[j];
}

/* joint j's rotation channels' axes: its rotation dofs' in order, then the rest (root: x y z) */
static void
channel_axes(const struct model *m, int j, int axes[3])
{
	int n = 0, used[3] = { 0, 0, 0 };
	int d0 = j >= 0 ? m->jnt_dof0[j] : 0, d1 = j >= 0 ? d0 + m->jnt_ndof[j] : 0;
	for (int d = d0; d < d1; d++) {
		int a = m->dof_axis[d];
		if (m->dof_kind[d] != DOF_ROTATION)
			continue;
		if (used[a]) { /* an axis twice: no three-angle order matches; BVH's usual one */
			static const int zxy[3] = { 2, 0, 1 };
			memcpy(axes, zxy, sizeof zxy);
			return;
		}
		used[a] = 1;
		axes[n++] = a;
	}
	for (int a = 0; a < 3; a++)
		if (!used[a])
			axes[n++] = a;
}

/*
 * Angles (degrees) with r = R_a(t0) R_b(t1) R_c(t2), a b c the three axes
 * in some order: s = +1 for an even permutation of x y z, -1 for odd.
 */
static void
euler_of(const double r[9], const int ax[3], double deg[3])
{
	int a = ax[0], b = ax[1], c = ax[2];
	double s = (b - a + 3) % 3 == 1 ? 1 : -1;
	double sb = fmax(-1, fmin(1, s * r[3 * a + c]));
	double t0, t1 = asin(sb), t2;
	if (fabs(sb) < 1 - 1e-12) {
		t0 = atan2(-s * r[3 * b + c], r[3 * c + c]);
		t2 = atan2(-s * r[3 * a + b], r[3 * a + a]);
	} else { /* the middle axis at +-90 deg: the first angle takes the whole turn */
		t0 = atan2(s * r[3 * c + b], r[3 * b + b]);
		t2 = 0;
	}
	deg[0] = t0 * 180 / M_PI;
	deg[1] = t1 * 180 / M_PI;
	deg[2] = t2 * 180 / M_PI;
}

static void
indent(FILE *f, int depth)
{
	for (int i = 0; i < depth; i++)
		fputc('\t', f);
}

/* the site of seg farthest from its node site: where its End Site goes */
static int
far_site(const struct model *m, int seg, int from)
{
	int best = from;
	double far = -1;
	for (int k = m->seg_site0[seg]; k < m->seg_site0[seg] + m->seg_nsite[seg]; k++) {
		double d = 0;
		for (int i = 0; i < 3; i++)
			d += pow(m->site_pos[3 * k + i] - m->site_pos[3 * from + i], 2);
		if (d > far) {
			far = d;
			best = k;
		}
	}
	return best;
}

/* offset of site b from site a (same segment or a joint's two sides), in a's frame */
static void
offset_between(const struct model *m, int a, int b, double dest[3])
{
	struct xform rel;
	xform_mul(&m->site_loc_inv[a], &m->site_loc[b], &rel);
	memcpy(dest, rel.p, sizeof rel.p);
}

/*
 * The segments depth first, children in seg_order's order: the order the
 * hierarchy is written in, and so the order of each frame's channels.
 * Returns the next free place in order.
 */
static int
depth_first(const struct model *m, const struct state *s, int seg, int *order, int at)
{
	order[at++] = seg;
	for (int i = 0; i < m->nseg; i++)
		if (s->seg_parent[s->seg_order[i]] == seg)
			at = depth_first(m, s, s->seg_order[i], order, at);
	return at;
}

static void
write_node(FILE *f, const struct model *m, const struct state *s, int seg, int depth)
{
	int j = s->seg_root_joint[seg], site = s->seg_root_site[seg], axes[3];
	channel_axes(m, j, axes);
	double off[3] = { 0, 0, 0 };
	if (j >= 0) /* from the parent's node site to the joint, both on the parent segment */
		offset_between(m, s->seg_root_site[s->seg_parent[seg]], pivot_site(m, s, seg), off);
	indent(f, depth);
	fprintf(f, j < 0 ? "ROOT %s\n" : "JOINT %s\n", j < 0 ? m->seg_name[seg] : m->jnt_name[j]);
	indent(f, depth);
	fprintf(f, "{\n");
	indent(f, depth + 1);
	fprintf(f, "OFFSET %.9f %.9f %.9f\n", off[0], off[1], off[2]);
	indent(f, depth + 1);
	if (j < 0 || model_joint_has(m, j, DOF_TRANSLATION))
		fprintf(f, "CHANNELS 6 Xposition Yposition Zposition %crotation %crotation %crotation\n",
			"XYZ"[axes[0]], "XYZ"[axes[1]], "XYZ"[axes[2]]);
	else
		fprintf(f, "CHANNELS 3 %crotation %crotation %crotation\n", "XYZ"[axes[0]],
			"XYZ"[axes[1]], "XYZ"[axes[2]]);
	int children = 0;
	for (int i = 0; i < m->nseg; i++) {
		int c = s->seg_order[i];
		if (s->seg_parent[c] == seg) {
			write_node(f, m, s, c, depth + 1);
			children++;
		}
	}
	if (!children) {
		double end[3];
		offset_between(m, site, far_site(m, seg, site), end);
		indent(f, depth + 1);
		fprintf(f, "End Site\n");
		indent(f, depth + 1);
		fprintf(f, "{\n");
		indent(f, depth + 2);
		fprintf(f, "OFFSET %.9f %.9f %.9f\n", end[0], end[1], end[2]);
		indent(f, depth + 1);
		fprintf(f, "}\n");
	}
	indent(f, depth);
	fprintf(f, "}\n");
}

/* one frame's channel values, in the hierarchy's order (order: depth_first of `tree`) */
static void
write_frame(FILE *f, const struct model *m, const struct state *tree, const int *order,
	    const struct state *pose)
{
	for (int i = 0; i < m->nseg; i++) {
		int seg = order[i], j = tree->seg_root_joint[seg], axes[3];
		channel_axes(m, j, axes);
		const struct xform *node = &pose->site_xf[tree->seg_root_site[seg]];
		struct xform rel = *node;
		if (j >= 0) {
			struct xform inv;
			xform_inv(&pose->site_xf[tree->seg_root_site[tree->seg_parent[seg]]], &inv);
			xform_mul(&inv, node, &rel);
		}
		double deg[3];
		euler_of(rel.r, axes, deg);
		/* position channels place the joint in its parent: they stand for its OFFSET
		 * (as Blender's and bvhio's readers take them), they do not add to it */
		if (j < 0 || model_joint_has(m, j, DOF_TRANSLATION))
			fprintf(f, "%.9f %.9f %.9f ", rel.p[0], rel.p[1], rel.p[2]);
		fprintf(f, "%.9f %.9f %.9f%s", deg[0], deg[1], deg[2], i + 1 < m->nseg ? " " : "\n");
	}
}

int
bvh_write(const struct motion *mo, double frame_seconds, FILE *f, char *err, size_t errlen)
{
	const struct model *m = mo->m;
	int some = 0;
	for (int k = 0; k < mo->nframes; k++)
		some |= mo->frames[k] != NULL;
	if (!some) {
		snprintf(err, errlen, "%s has no postures to write", mo->name);
		return -1;
	}
	int *order = malloc(sizeof *order * (size_t)m->nseg);
	if (!order) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	int root = m->site_seg[mo->now->root_site];
	depth_first(m, mo->now, root, order, 0);
	fprintf(f, "HIERARCHY\n");
	write_node(f, m, mo->now, root, 0);
	fprintf(f, "MOTION\nFrames: %d\nFrame Time: %.9f\n", mo->nframes, frame_seconds);
	for (int k = 0; k < mo->nframes; k++)
		write_frame(f, m, mo->now, order, motion_frame(mo, k));
	free(order);
	if (ferror(f)) {
		snprintf(err, errlen, "write error");
		return -1;
	}
	return 0;
}

int
bvh_export(const struct motion *mo, double frame_seconds, const char *path, char *err,
	   size_t errlen)
{
	char dir[4096], stem[4096];
	if (export_split_path(path, ".bvh", dir, sizeof dir, stem, sizeof stem, err, errlen) < 0)
		return -1;
	struct export_file out;
	FILE *f = export_file_open(&out, path, err, errlen);
	if (!f)
		return -1;
	if (bvh_write(mo, frame_seconds, f, err, errlen) < 0) {
		export_file_abandon(&out);
		return -1;
	}
	return export_file_commit(&out, err, errlen);
}
