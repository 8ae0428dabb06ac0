/* model.c - building, checking, copying and comparing figure models */
#include "figure/model.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct site_rec {
	int seg;
	char name[MODEL_NAME_MAX];
	double pos[3], quat[4];
};

struct geom_rec {
	int seg;
	struct geom_def def;
};

struct mesh_rec {
	char path[MODEL_PATH_MAX];
	float *vert;
	int *face;
	int nvert, nface;
};

struct seg_rec {
	struct segment_def def;
	char name[MODEL_NAME_MAX];
};

struct jnt_rec {
	struct joint_def def;
	char name[MODEL_NAME_MAX];
};

/* growable arrays: building happens at load time, never in a frame */
struct model_builder {
	char name[MODEL_NAME_MAX];
	struct seg_rec *seg;
	struct site_rec *site;
	struct jnt_rec *jnt;
	struct geom_rec *geom;
	struct mesh_rec *mesh;
	int nseg, nsite, njnt, ngeom, nmesh;
	int capseg, capsite, capjnt, capgeom, capmesh;
	int root_site;
	double root_pos[3], root_quat[4];
	char err[256];
};

struct segment_def
segment_default_def(void)
{
	struct segment_def d = { 0 };
	d.rgba[0] = d.rgba[1] = d.rgba[2] = 0.7f;
	d.rgba[3] = 1.0f;
	return d;
}

struct joint_def
joint_default_def(void)
{
	struct joint_def d = { 0 };
	d.site_from = d.site_to = -1;
	return d;
}

struct geom_def
geom_default_def(void)
{
	struct geom_def d = { 0 };
	d.quat[3] = 1;
	d.mesh = -1;
	return d;
}

static int
fail(struct model_builder *b, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(b->err, sizeof b->err, fmt, ap);
	va_end(ap);
	return -1;
}

static int
grow(void **arr, int *cap, int n, size_t elem)
{
	if (n < *cap)
		return 0;
	int ncap = *cap ? *cap * 2 : 16;
	void *p = realloc(*arr, (size_t)ncap * elem);
	if (!p)
		return -1;
	*arr = p;
	*cap = ncap;
	return 0;
}

static int
all_finite(const double *v, int n)
{
	for (int i = 0; i < n; i++)
		if (!isfinite(v[i]))
			return 0;
	return 1;
}

static int
check_name(struct model_builder *b, const char *what, const char *name)
{
	if (!name || !name[0])
		return fail(b, "%s needs a name", what);
	if (strlen(name) >= MODEL_NAME_MAX)
		return fail(b, "%s name '%.20s...' is longer than %d bytes", what, name,
			    MODEL_NAME_MAX - 1);
	/* names are identifiers: "segment.site" must split at the one dot */
	for (const char *c = name; *c; c++)
		if (!(isalnum((unsigned char)*c) || *c == '_') || (c == name && isdigit((unsigned char)*c)))
			return fail(b, "%s name '%s': use letters, digits and '_', not starting with a digit",
				    what, name);
	return 0;
}

/* unit quaternion check with a tolerance for values typed with few digits */
static int
check_quat(struct model_builder *b, const char *what, const double q[4])
{
	if (!all_finite(q, 4))
		return fail(b, "%s: orientation is not a finite number", what);
	double n = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
	if (fabs(n - 1) > 1e-6)
		return fail(b, "%s: orientation quaternion is not of unit length", what);
	return 0;
}

struct model_builder *
model_builder_create(const char *figure_name)
{
	struct model_builder *b = calloc(1, sizeof *b);
	if (!b)
		return NULL;
	snprintf(b->name, sizeof b->name, "%s", figure_name ? figure_name : "figure");
	b->root_site = -1;
	b->root_quat[3] = 1;
	return b;
}

void
model_builder_free(struct model_builder *b)
{
	if (!b)
		return;
	for (int i = 0; i < b->nmesh; i++) {
		free(b->mesh[i].vert);
		free(b->mesh[i].face);
	}
	free(b->seg);
	free(b->site);
	free(b->jnt);
	free(b->geom);
	free(b->mesh);
	free(b);
}

const char *
model_builder_error(const struct model_builder *b)
{
	return b->err;
}

int
model_builder_find_segment(const struct model_builder *b, const char *name)
{
	for (int i = 0; i < b->nseg; i++)
		if (!strcmp(b->seg[i].name, name))
			return i;
	return -1;
}

int
model_builder_find_site(const struct model_builder *b, int seg, const char *name)
{
	for (int i = 0; i < b->nsite; i++)
		if (b->site[i].seg == seg && !strcmp(b->site[i].name, name))
			return i;
	return -1;
}

int
model_builder_find_joint(const struct model_builder *b, const char *name)
{
	for (int i = 0; i < b->njnt; i++)
		if (!strcmp(b->jnt[i].name, name))
			return i;
	return -1;
}

int
model_builder_segment(struct model_builder *b, const struct segment_def *d)
{
	if (check_name(b, "segment", d->name) < 0)
		return -1;
	if (model_builder_find_segment(b, d->name) >= 0)
		return fail(b, "segment '%s' is defined twice", d->name);
	if (!isfinite(d->mass) || d->mass < 0)
		return fail(b, "segment '%s': mass must be a finite number >= 0", d->name);
	if (!all_finite(d->com, 3) || !all_finite(d->inertia, 6))
		return fail(b, "segment '%s': centre of mass and inertia must be finite", d->name);
	if (d->inertia[0] < 0 || d->inertia[1] < 0 || d->inertia[2] < 0)
		return fail(b, "segment '%s': principal moments of inertia must be >= 0", d->name);
	for (int i = 0; i < 4; i++)
		if (!(d->rgba[i] >= 0 && d->rgba[i] <= 1))
			return fail(b, "segment '%s': colour components must lie in [0, 1]", d->name);
	if (grow((void **)&b->seg, &b->capseg, b->nseg, sizeof *b->seg) < 0)
		return fail(b, "out of memory");
	struct seg_rec *r = &b->seg[b->nseg];
	memset(r, 0, sizeof *r); /* names are compared bytewise, padding included */
	r->def = *d;
	snprintf(r->name, sizeof r->name, "%s", d->name);
	r->def.name = NULL;
	return b->nseg++;
}

int
model_builder_site(struct model_builder *b, int seg, const char *name, const double pos[3],
		   const double quat[4])
{
	if (seg < 0 || seg >= b->nseg)
		return fail(b, "site '%s': no such segment", name ? name : "");
	if (check_name(b, "site", name) < 0)
		return -1;
	if (model_builder_find_site(b, seg, name) >= 0)
		return fail(b, "site '%s.%s' is defined twice", b->seg[seg].name, name);
	if (!all_finite(pos, 3))
		return fail(b, "site '%s.%s': location is not a finite number", b->seg[seg].name, name);
	if (check_quat(b, "site", quat) < 0)
		return -1;
	if (grow((void **)&b->site, &b->capsite, b->nsite, sizeof *b->site) < 0)
		return fail(b, "out of memory");
	struct site_rec *r = &b->site[b->nsite];
	memset(r, 0, sizeof *r);
	r->seg = seg;
	snprintf(r->name, sizeof r->name, "%s", name);
	memcpy(r->pos, pos, sizeof r->pos);
	memcpy(r->quat, quat, sizeof r->quat);
	return b->nsite++;
}

int
model_builder_joint(struct model_builder *b, const struct joint_def *d)
{
	if (check_name(b, "joint", d->name) < 0)
		return -1;
	if (model_builder_find_joint(b, d->name) >= 0)
		return fail(b, "joint '%s' is defined twice", d->name);
	if (d->site_from < 0 || d->site_from >= b->nsite || d->site_to < 0 ||
	    d->site_to >= b->nsite)
		return fail(b, "joint '%s': connects a site that does not exist", d->name);
	if (b->site[d->site_from].seg == b->site[d->site_to].seg)
		return fail(b, "joint '%s': connects two sites of the same segment", d->name);
	if (d->ndof < 0 || d->ndof > MODEL_JOINT_DOF_MAX)
		return fail(b, "joint '%s': %d degrees of freedom (0 to %d allowed)", d->name, d->ndof,
			    MODEL_JOINT_DOF_MAX);
	for (int i = 0; i < d->ndof; i++) {
		const struct dof_def *f = &d->dof[i];
		if (f->kind != DOF_ROTATION && f->kind != DOF_TRANSLATION)
			return fail(b, "joint '%s': dof %d has an unknown kind", d->name, i);
		if (f->axis < 0 || f->axis > 2 || (f->sign != 1 && f->sign != -1))
			return fail(b, "joint '%s': dof %d has a bad axis", d->name, i);
		if (!isfinite(f->lo) || !isfinite(f->hi) || !isfinite(f->init))
			return fail(b, "joint '%s': dof %d limits must be finite", d->name, i);
		if (f->lo > f->hi)
			return fail(b, "joint '%s': dof %d lower limit is above its upper limit",
				    d->name, i);
		if (f->init < f->lo || f->init > f->hi)
			return fail(b, "joint '%s': dof %d displacement lies outside its limits",
				    d->name, i);
	}
	if (grow((void **)&b->jnt, &b->capjnt, b->njnt, sizeof *b->jnt) < 0)
		return fail(b, "out of memory");
	struct jnt_rec *r = &b->jnt[b->njnt];
	memset(r, 0, sizeof *r);
	r->def = *d;
	snprintf(r->name, sizeof r->name, "%s", d->name);
	r->def.name = NULL;
	return b->njnt++;
}

int
model_builder_geom(struct model_builder *b, int seg, const struct geom_def *d)
{
	if (seg < 0 || seg >= b->nseg)
		return fail(b, "geometry on a segment that does not exist");
	const char *sn = b->seg[seg].name;
	if ((int)d->kind < GEOM_BOX || d->kind > GEOM_MESH)
		return fail(b, "segment '%s': unknown geometry kind", sn);
	if (!all_finite(d->size, 3) || !all_finite(d->pos, 3))
		return fail(b, "segment '%s': geometry sizes must be finite", sn);
	if (check_quat(b, "geometry", d->quat) < 0)
		return -1;
	int nsize = d->kind == GEOM_CYLINDER || d->kind == GEOM_CAPSULE ? 2 : 3;
	for (int i = 0; i < nsize; i++)
		if (!(d->size[i] > 0) && !(d->kind == GEOM_CAPSULE && i == 1 && d->size[i] == 0))
			return fail(b, "segment '%s': geometry sizes must be > 0", sn);
	if (d->kind == GEOM_MESH && (d->mesh < 0 || d->mesh >= b->nmesh))
		return fail(b, "segment '%s': mesh geometry without a mesh", sn);
	if (grow((void **)&b->geom, &b->capgeom, b->ngeom, sizeof *b->geom) < 0)
		return fail(b, "out of memory");
	b->geom[b->ngeom].seg = seg;
	b->geom[b->ngeom].def = *d;
	if (nsize == 2) /* the third size means nothing for these shapes */
		b->geom[b->ngeom].def.size[2] = 0;
	if (d->kind != GEOM_MESH)
		b->geom[b->ngeom].def.mesh = -1;
	return b->ngeom++;
}

int
model_builder_mesh(struct model_builder *b, const char *path, const float *vert, int nvert,
		   const int *face, int nface)
{
	if (!path || strlen(path) >= MODEL_PATH_MAX)
		return fail(b, "mesh path is missing or longer than %d bytes", MODEL_PATH_MAX - 1);
	if (nvert <= 0 || nface <= 0)
		return fail(b, "mesh '%s' has no triangles", path);
	for (int i = 0; i < 3 * nvert; i++)
		if (!isfinite(vert[i]))
			return fail(b, "mesh '%s': vertex coordinates must be finite", path);
	for (int i = 0; i < 3 * nface; i++)
		if (face[i] < 0 || face[i] >= nvert)
			return fail(b, "mesh '%s': face refers to vertex %d of %d", path, face[i] + 1,
				    nvert);
	if (grow((void **)&b->mesh, &b->capmesh, b->nmesh, sizeof *b->mesh) < 0)
		return fail(b, "out of memory");
	struct mesh_rec *r = &b->mesh[b->nmesh];
	memset(r, 0, sizeof *r);
	r->vert = malloc(sizeof(float) * 3 * (size_t)nvert);
	r->face = malloc(sizeof(int) * 3 * (size_t)nface);
	if (!r->vert || !r->face) {
		free(r->vert);
		free(r->face);
		return fail(b, "out of memory");
	}
	memcpy(r->vert, vert, sizeof(float) * 3 * (size_t)nvert);
	memcpy(r->face, face, sizeof(int) * 3 * (size_t)nface);
	r->nvert = nvert;
	r->nface = nface;
	snprintf(r->path, sizeof r->path, "%s", path);
	return b->nmesh++;
}

int
model_builder_root(struct model_builder *b, int site, const double pos[3], const double quat[4])
{
	if (site < 0 || site >= b->nsite)
		return fail(b, "root: no such site");
	if (!all_finite(pos, 3))
		return fail(b, "root location is not a finite number");
	if (check_quat(b, "root location", quat) < 0)
		return -1;
	b->root_site = site;
	memcpy(b->root_pos, pos, sizeof b->root_pos);
	memcpy(b->root_quat, quat, sizeof b->root_quat);
	return 0;
}

/* union-find over segments, to check that joints form a spanning tree */
static int
uf_find(int *parent, int i)
{
	while (parent[i] != i) {
		parent[i] = parent[parent[i]];
		i = parent[i];
	}
	return i;
}

static int
check_tree(struct model_builder *b)
{
	if (b->nseg == 0)
		return fail(b, "figure '%s' has no segments", b->name);
	if (b->njnt != b->nseg - 1)
		return fail(b, "figure '%s': %d segments need %d joints to form one tree, found %d",
			    b->name, b->nseg, b->nseg - 1, b->njnt);
	int *parent = malloc(sizeof(int) * (size_t)b->nseg);
	if (!parent)
		return fail(b, "out of memory");
	for (int i = 0; i < b->nseg; i++)
		parent[i] = i;
	for (int j = 0; j < b->njnt; j++) {
		int a = uf_find(parent, b->site[b->jnt[j].def.site_from].seg);
		int c = uf_find(parent, b->site[b->jnt[j].def.site_to].seg);
		if (a == c) {
			free(parent);
			return fail(b, "joint '%s' closes a loop; figures must be trees",
				    b->jnt[j].name);
		}
		parent[a] = c;
	}
	free(parent);
	return 0;
}

/* every array of the model with its element count, for allocation, copy and compare */
#define MODEL_ARRAYS(X)                                                        \
	X(seg_name, m->nseg) X(seg_mass, m->nseg) X(seg_com, 3 * m->nseg)      \
	X(seg_inertia, 6 * m->nseg) X(seg_rgba, 4 * m->nseg)                   \
	X(seg_site0, m->nseg) X(seg_nsite, m->nseg) X(seg_geom0, m->nseg)      \
	X(seg_ngeom, m->nseg) X(site_name, m->nsite) X(site_seg, m->nsite)     \
	X(site_pos, 3 * m->nsite) X(site_quat, 4 * m->nsite)                   \
	X(site_loc, m->nsite) X(site_loc_inv, m->nsite) X(site_pure, m->nsite)             \
	X(site_moved, m->nsite)                                                \
	X(jnt_name, m->njnt) X(jnt_site_from, m->njnt)   \
	X(jnt_site_to, m->njnt) X(jnt_dof0, m->njnt) X(jnt_ndof, m->njnt)      \
	X(dof_jnt, m->ndof) X(dof_kind, m->ndof) X(dof_axis, m->ndof)          \
	X(dof_sign, m->ndof) X(dof_lo, m->ndof) X(dof_hi, m->ndof)             \
	X(dof_init, m->ndof) X(geom_seg, m->ngeom) X(geom_kind, m->ngeom)      \
	X(geom_size, 3 * m->ngeom) X(geom_pos, 3 * m->ngeom)                   \
	X(geom_quat, 4 * m->ngeom) X(geom_mesh, m->ngeom)                      \
	X(mesh_path, m->nmesh) X(mesh_vert0, m->nmesh) X(mesh_nvert, m->nmesh) \
	X(mesh_face0, m->nmesh) X(mesh_nface, m->nmesh)                        \
	X(mesh_vert, 3 * m->nvert) X(mesh_face, 3 * m->nface)

/* site k's location and what is derived from it */
static void
place_site(struct model *m, int k, const double pos[3], const double quat[4])
{
	memcpy(&m->site_pos[3 * k], pos, sizeof(double) * 3);
	memcpy(&m->site_quat[4 * k], quat, sizeof(double) * 4);
	xform_from_pos_quat(pos, quat, &m->site_loc[k]);
	xform_inv(&m->site_loc[k], &m->site_loc_inv[k]);
	m->site_pure[k] = quat[0] == 0 && quat[1] == 0 && quat[2] == 0;
}

void
model_set_site(struct model *m, int site, const double pos[3], const double quat[4])
{
	place_site(m, site, pos, quat);
	m->site_moved[site] = 1;
}

static struct model *
model_alloc(int nseg, int nsite, int njnt, int ndof, int ngeom, int nmesh, int nvert, int nface)
{
	struct model *m = calloc(1, sizeof *m);
	if (!m)
		return NULL;
	m->nseg = nseg;
	m->nsite = nsite;
	m->njnt = njnt;
	m->ndof = ndof;
	m->ngeom = ngeom;
	m->nmesh = nmesh;
	m->nvert = nvert;
	m->nface = nface;
	/* at least one element each, so an empty array is not a NULL */
#define ALLOC(field, n)                                                        \
	m->field = calloc((size_t)(n) > 0 ? (size_t)(n) : 1, sizeof *m->field); \
	if (!m->field) {                                                       \
		model_free(m);                                                 \
		return NULL;                                                   \
	}
	MODEL_ARRAYS(ALLOC)
#undef ALLOC
	return m;
}

struct model *
model_builder_finish(struct model_builder *b)
{
	b->err[0] = 0;
	if (check_tree(b) < 0)
		return NULL;
	if (b->root_site < 0)
		return fail(b, "figure '%s' has no root site", b->name), NULL;
	int ndof = 0, nvert = 0, nface = 0;
	for (int j = 0; j < b->njnt; j++)
		ndof += b->jnt[j].def.ndof;
	for (int i = 0; i < b->nmesh; i++) {
		nvert += b->mesh[i].nvert;
		nface += b->mesh[i].nface;
	}
	struct model *m = model_alloc(b->nseg, b->nsite, b->njnt, ndof, b->ngeom, b->nmesh, nvert,
				      nface);
	int *site_map = malloc(sizeof(int) * (size_t)(b->nsite > 0 ? b->nsite : 1));
	if (!m || !site_map) {
		model_free(m);
		free(site_map);
		return fail(b, "out of memory"), NULL;
	}
	snprintf(m->name, sizeof m->name, "%s", b->name);

	/* segments, with their sites and geoms gathered contiguously in order */
	int ns = 0, ng = 0;
	for (int s = 0; s < b->nseg; s++) {
		const struct seg_rec *r = &b->seg[s];
		memcpy(m->seg_name[s], r->name, MODEL_NAME_MAX);
		m->seg_mass[s] = r->def.mass;
		memcpy(&m->seg_com[3 * s], r->def.com, sizeof r->def.com);
		memcpy(&m->seg_inertia[6 * s], r->def.inertia, sizeof r->def.inertia);
		memcpy(&m->seg_rgba[4 * s], r->def.rgba, sizeof r->def.rgba);
		m->total_mass += r->def.mass;
		m->seg_site0[s] = ns;
		for (int i = 0; i < b->nsite; i++) {
			if (b->site[i].seg != s)
				continue;
			site_map[i] = ns;
			memcpy(m->site_name[ns], b->site[i].name, MODEL_NAME_MAX);
			m->site_seg[ns] = s;
			place_site(m, ns, b->site[i].pos, b->site[i].quat);
			ns++;
		}
		m->seg_nsite[s] = ns - m->seg_site0[s];
		m->seg_geom0[s] = ng;
		for (int i = 0; i < b->ngeom; i++) {
			if (b->geom[i].seg != s)
				continue;
			const struct geom_def *g = &b->geom[i].def;
			m->geom_seg[ng] = s;
			m->geom_kind[ng] = (unsigned char)g->kind;
			memcpy(&m->geom_size[3 * ng], g->size, sizeof g->size);
			memcpy(&m->geom_pos[3 * ng], g->pos, sizeof g->pos);
			memcpy(&m->geom_quat[4 * ng], g->quat, sizeof g->quat);
			m->geom_mesh[ng] = g->mesh;
			ng++;
		}
		m->seg_ngeom[s] = ng - m->seg_geom0[s];
	}

	/* joints and their dofs */
	int nd = 0;
	for (int j = 0; j < b->njnt; j++) {
		const struct joint_def *d = &b->jnt[j].def;
		memcpy(m->jnt_name[j], b->jnt[j].name, MODEL_NAME_MAX);
		m->jnt_site_from[j] = site_map[d->site_from];
		m->jnt_site_to[j] = site_map[d->site_to];
		m->jnt_dof0[j] = nd;
		m->jnt_ndof[j] = d->ndof;
		for (int k = 0; k < d->ndof; k++, nd++) {
			m->dof_jnt[nd] = j;
			m->dof_kind[nd] = (unsigned char)d->dof[k].kind;
			m->dof_axis[nd] = (unsigned char)d->dof[k].axis;
			m->dof_sign[nd] = (signed char)d->dof[k].sign;
			m->dof_lo[nd] = d->dof[k].lo;
			m->dof_hi[nd] = d->dof[k].hi;
			m->dof_init[nd] = d->dof[k].init;
		}
	}

	/* meshes */
	int nv = 0, nf = 0;
	for (int i = 0; i < b->nmesh; i++) {
		const struct mesh_rec *r = &b->mesh[i];
		memcpy(m->mesh_path[i], r->path, MODEL_PATH_MAX);
		m->mesh_vert0[i] = nv;
		m->mesh_nvert[i] = r->nvert;
		m->mesh_face0[i] = nf;
		m->mesh_nface[i] = r->nface;
		memcpy(&m->mesh_vert[3 * nv], r->vert, sizeof(float) * 3 * (size_t)r->nvert);
		memcpy(&m->mesh_face[3 * nf], r->face, sizeof(int) * 3 * (size_t)r->nface);
		nv += r->nvert;
		nf += r->nface;
	}

	m->root_site = site_map[b->root_site];
	memcpy(m->root_pos, b->root_pos, sizeof m->root_pos);
	memcpy(m->root_quat, b->root_quat, sizeof m->root_quat);
	free(site_map);
	return m;
}

void
model_free(struct model *m)
{
	if (!m)
		return;
#define FREE(field, n) free(m->field);
	MODEL_ARRAYS(FREE)
#undef FREE
	free(m);
}

struct model *
model_copy(const struct model *m)
{
	struct model *c = model_alloc(m->nseg, m->nsite, m->njnt, m->ndof, m->ngeom, m->nmesh,
				      m->nvert, m->nface);
	if (!c)
		return NULL;
	memcpy(c->name, m->name, sizeof c->name);
	c->root_site = m->root_site;
	memcpy(c->root_pos, m->root_pos, sizeof c->root_pos);
	memcpy(c->root_quat, m->root_quat, sizeof c->root_quat);
	c->total_mass = m->total_mass;
#define COPY(field, n) memcpy(c->field, m->field, sizeof *m->field * (size_t)(n));
	MODEL_ARRAYS(COPY)
#undef COPY
	return c;
}

int
model_equal(const struct model *a, const struct model *b)
{
	const struct model *m = a;
	if (a->nseg != b->nseg || a->nsite != b->nsite || a->njnt != b->njnt ||
	    a->ndof != b->ndof || a->ngeom != b->ngeom || a->nmesh != b->nmesh ||
	    a->nvert != b->nvert || a->nface != b->nface || a->root_site != b->root_site)
		return 0;
	if (strcmp(a->name, b->name) || memcmp(a->root_pos, b->root_pos, sizeof a->root_pos) ||
	    memcmp(a->root_quat, b->root_quat, sizeof a->root_quat) ||
	    memcmp(&a->total_mass, &b->total_mass, sizeof a->total_mass))
		return 0;
#define CMP(field, n)                                                          \
	if (memcmp(a->field, b->field, sizeof *a->field * (size_t)(n)))        \
		return 0;
	MODEL_ARRAYS(CMP)
#undef CMP
	return 1;
}

int
model_find_segment(const struct model *m, const char *name)
{
	for (int i = 0; i < m->nseg; i++)
		if (!strcmp(m->seg_name[i], name))
			return i;
	return -1;
}

int
model_find_site(const struct model *m, const char *seg_dot_site)
{
	const char *dot = strchr(seg_dot_site, '.');
	if (!dot || (size_t)(dot - seg_dot_site) >= MODEL_NAME_MAX)
		return -1;
	char seg[MODEL_NAME_MAX];
	memcpy(seg, seg_dot_site, (size_t)(dot - seg_dot_site));
	seg[dot - seg_dot_site] = 0;
	int s = model_find_segment(m, seg);
	if (s < 0)
		return -1;
	for (int i = m->seg_site0[s]; i < m->seg_site0[s] + m->seg_nsite[s]; i++)
		if (!strcmp(m->site_name[i], dot + 1))
			return i;
	return -1;
}

int
model_find_joint(const struct model *m, const char *name)
{
	for (int i = 0; i < m->njnt; i++)
		if (!strcmp(m->jnt_name[i], name))
			return i;
	return -1;
}

char *
model_site_fullname(const struct model *m, int site, char *dest, size_t len)
{
	snprintf(dest, len, "%s.%s", m->seg_name[m->site_seg[site]], m->site_name[site]);
	return dest;
}

int
model_joint_has(const struct model *m, int j, enum dof_kind kind)
{
	for (int d = m->jnt_dof0[j]; d < m->jnt_dof0[j] + m->jnt_ndof[j]; d++)
		if (m->dof_kind[d] == kind)
			return 1;
	return 0;
}
