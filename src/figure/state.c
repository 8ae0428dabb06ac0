/* state.c - making, resetting and re-rooting figure state (the frames are kin's) */
#include "figure/state.h"

#include <stdlib.h>
#include <string.h>

struct state *
state_make(const struct model *m)
{
	struct state *s = calloc(1, sizeof *s);
	if (!s)
		return NULL;
	size_t nd = (size_t)(m->ndof > 0 ? m->ndof : 1), ns = (size_t)m->nseg,
	       nj = (size_t)(m->njnt > 0 ? m->njnt : 1), nsite = (size_t)m->nsite;
	s->q = calloc(nd, sizeof *s->q);
	s->seg_order = calloc(ns, sizeof *s->seg_order);
	s->seg_parent = calloc(ns, sizeof *s->seg_parent);
	s->seg_root_site = calloc(ns, sizeof *s->seg_root_site);
	s->seg_root_joint = calloc(ns, sizeof *s->seg_root_joint);
	s->jnt_child_seg = calloc(nj, sizeof *s->jnt_child_seg);
	s->jnt_dir = calloc(nj, sizeof *s->jnt_dir);
	s->seg_xf = calloc(ns, sizeof *s->seg_xf);
	s->site_xf = calloc(nsite, sizeof *s->site_xf);
	s->dof_axis_w = calloc(3 * nd, sizeof *s->dof_axis_w);
	s->dof_pivot_w = calloc(3 * nd, sizeof *s->dof_pivot_w);
	s->seg_com_w = calloc(3 * ns, sizeof *s->seg_com_w);
	s->subtree_mass = calloc(ns, sizeof *s->subtree_mass);
	s->subtree_com = calloc(3 * ns, sizeof *s->subtree_com);
	if (!s->q || !s->seg_order || !s->seg_parent || !s->seg_root_site || !s->seg_root_joint ||
	    !s->jnt_child_seg || !s->jnt_dir || !s->seg_xf || !s->site_xf || !s->dof_axis_w ||
	    !s->dof_pivot_w || !s->seg_com_w || !s->subtree_mass || !s->subtree_com) {
		state_free(s);
		return NULL;
	}
	state_reset(m, s);
	return s;
}

void
state_free(struct state *s)
{
	if (!s)
		return;
	free(s->q);
	free(s->seg_order);
	free(s->seg_parent);
	free(s->seg_root_site);
	free(s->seg_root_joint);
	free(s->jnt_child_seg);
	free(s->jnt_dir);
	free(s->seg_xf);
	free(s->site_xf);
	free(s->dof_axis_w);
	free(s->dof_pivot_w);
	free(s->seg_com_w);
	free(s->subtree_mass);
	free(s->subtree_com);
	free(s);
}

/* breadth-first from the root segment: peabody's root fields (§A.4.2) */
static void
build_tree(const struct model *m, struct state *s)
{
	int rs = m->site_seg[s->root_site];
	for (int i = 0; i < m->nseg; i++)
		s->seg_parent[i] = -2; /* unvisited */
	s->seg_order[0] = rs;
	s->seg_parent[rs] = -1;
	s->seg_root_site[rs] = s->root_site;
	s->seg_root_joint[rs] = -1;
	int head = 0, tail = 1;
	while (head < tail) {
		int p = s->seg_order[head++];
		for (int j = 0; j < m->njnt; j++) {
			int from = m->jnt_site_from[j], to = m->jnt_site_to[j];
			int a = m->site_seg[from], b = m->site_seg[to], child, top;
			if (a == p && s->seg_parent[b] == -2) {
				child = b, top = to, s->jnt_dir[j] = 1;
			} else if (b == p && s->seg_parent[a] == -2) {
				child = a, top = from, s->jnt_dir[j] = -1;
			} else {
				continue;
			}
			s->seg_parent[child] = p;
			s->seg_root_site[child] = top;
			s->seg_root_joint[child] = j;
			s->jnt_child_seg[j] = child;
			s->seg_order[tail++] = child;
		}
	}
}

void
state_reset(const struct model *m, struct state *s)
{
	memcpy(s->q, m->dof_init, sizeof *s->q * (size_t)m->ndof);
	s->root_site = m->root_site;
	xform_from_pos_quat(m->root_pos, m->root_quat, &s->root_xf);
	build_tree(m, s);
}

void
state_copy(const struct model *m, const struct state *src, struct state *dest)
{
	size_t nd = (size_t)m->ndof, ns = (size_t)m->nseg, nj = (size_t)m->njnt;
	memcpy(dest->q, src->q, sizeof *dest->q * nd);
	dest->root_site = src->root_site;
	dest->root_xf = src->root_xf;
	memcpy(dest->seg_order, src->seg_order, sizeof(int) * ns);
	memcpy(dest->seg_parent, src->seg_parent, sizeof(int) * ns);
	memcpy(dest->seg_root_site, src->seg_root_site, sizeof(int) * ns);
	memcpy(dest->seg_root_joint, src->seg_root_joint, sizeof(int) * ns);
	memcpy(dest->jnt_child_seg, src->jnt_child_seg, sizeof(int) * nj);
	memcpy(dest->jnt_dir, src->jnt_dir, nj);
	memcpy(dest->seg_xf, src->seg_xf, sizeof *dest->seg_xf * ns);
	memcpy(dest->site_xf, src->site_xf, sizeof *dest->site_xf * (size_t)m->nsite);
	memcpy(dest->dof_axis_w, src->dof_axis_w, sizeof(double) * 3 * nd);
	memcpy(dest->dof_pivot_w, src->dof_pivot_w, sizeof(double) * 3 * nd);
	memcpy(dest->seg_com_w, src->seg_com_w, sizeof(double) * 3 * ns);
	memcpy(dest->subtree_mass, src->subtree_mass, sizeof(double) * ns);
	memcpy(dest->subtree_com, src->subtree_com, sizeof(double) * 3 * ns);
	memcpy(dest->com, src->com, sizeof dest->com);
}

int
state_root_at(const struct model *m, struct state *s, int site, const struct xform *root_xf)
{
	if (site < 0 || site >= m->nsite)
		return -1;
	s->root_xf = *root_xf;
	s->root_site = site;
	build_tree(m, s);
	return 0;
}

int
state_clamp(const struct model *m, struct state *s)
{
	int n = 0;
	for (int i = 0; i < m->ndof; i++) {
		if (s->q[i] < m->dof_lo[i]) {
			s->q[i] = m->dof_lo[i];
			n++;
		} else if (s->q[i] > m->dof_hi[i]) {
			s->q[i] = m->dof_hi[i];
			n++;
		}
	}
	return n;
}

static uint64_t
fnv1a(uint64_t h, const void *p, size_t n)
{
	const unsigned char *b = p;
	for (size_t i = 0; i < n; i++) {
		h ^= b[i];
		h *= 1099511628211ull;
	}
	return h;
}

uint64_t
state_hash(const struct model *m, const struct state *s)
{
	uint64_t h = 14695981039346656037ull;
	h = fnv1a(h, s->q, sizeof *s->q * (size_t)m->ndof);
	h = fnv1a(h, &s->root_site, sizeof s->root_site);
	h = fnv1a(h, &s->root_xf, sizeof s->root_xf);
	/* a site moved on its segment moves what hangs from it: part of the posture */
	for (int k = 0; k < m->nsite; k++)
		if (m->site_moved[k]) {
			h = fnv1a(h, &k, sizeof k);
			h = fnv1a(h, &m->site_pos[3 * k], sizeof(double) * 3);
			h = fnv1a(h, &m->site_quat[4 * k], sizeof(double) * 4);
		}
	return h;
}
