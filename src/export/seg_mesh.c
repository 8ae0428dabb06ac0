/* seg_mesh.c - a segment's geoms as one mesh, and that mesh as STL */
#include "export/seg_mesh.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "draw/tess.h"
#include "draw/view.h"

/* the part's mesh: a built-in primitive, or the model's own mesh with smooth normals */
static int
part_tess(const struct model *m, const struct view_part *p, struct tess_mesh *dest)
{
	if (p->model_mesh < 0)
		return view_mesh_tess((enum view_mesh)p->mesh, 1, dest);
	int k = p->model_mesh;
	/* the renderer's rule: smooth normals, creases above 40 deg kept sharp */
	return tess_mesh_from_triangles(m->mesh_vert + 3 * m->mesh_vert0[k], m->mesh_nvert[k],
					m->mesh_face + 3 * m->mesh_face0[k], m->mesh_nface[k], 40,
					dest);
}

/* appends t placed by p (scaled, then moved to the segment frame) to dest's arrays */
static void
append(struct seg_mesh *dest, const struct tess_mesh *t, const struct view_part *p)
{
	const double *s = p->scale;
	for (int v = 0; v < t->nvert; v++) {
		const float *vn = t->vn + 6 * v;
		double local[3] = { vn[0] * s[0], vn[1] * s[1], vn[2] * s[2] }, at[3];
		/*
		 * normals go by the inverse transpose of the scale, taken as its
		 * cofactors (the same direction, signed by the determinant) so a
		 * scale of 0, a geom flattened to a disc, still turns them right;
		 * where even that leaves none (the rim of such a disc), the unscaled
		 * normal stands in, so every normal is unit as glTF requires
		 */
		double sg = s[0] * s[1] * s[2] < 0 ? -1 : 1, rn[3];
		double n[3] = { sg * vn[3] * s[1] * s[2], sg * vn[4] * s[0] * s[2],
				sg * vn[5] * s[0] * s[1] };
		xform_apply(&p->xf, local, at);
		xform_rotate(&p->xf, n, rn);
		double len = sqrt(rn[0] * rn[0] + rn[1] * rn[1] + rn[2] * rn[2]);
		if (!(len > 1e-12)) {
			double raw[3] = { vn[3], vn[4], vn[5] };
			xform_rotate(&p->xf, raw, rn);
			len = sqrt(rn[0] * rn[0] + rn[1] * rn[1] + rn[2] * rn[2]);
		}
		float *dp = dest->pos + 3 * (dest->nvert + v), *dn = dest->nrm + 3 * (dest->nvert + v);
		for (int i = 0; i < 3; i++) {
			dp[i] = (float)at[i];
			dn[i] = (float)(rn[i] / len);
		}
	}
	for (int i = 0; i < t->nidx; i++)
		dest->idx[3 * dest->ntri + i] = (unsigned)dest->nvert + t->idx[i];
	dest->nvert += t->nvert;
	dest->ntri += t->nidx / 3;
}

static int
grow(struct seg_mesh *d, int nvert, int nidx)
{
	float *pos = realloc(d->pos, sizeof *pos * 3 * (size_t)(d->nvert + nvert));
	if (pos)
		d->pos = pos;
	float *nrm = realloc(d->nrm, sizeof *nrm * 3 * (size_t)(d->nvert + nvert));
	if (nrm)
		d->nrm = nrm;
	unsigned *idx = realloc(d->idx, sizeof *idx * (size_t)(3 * d->ntri + nidx));
	if (idx)
		d->idx = idx;
	return pos && nrm && idx ? 0 : -1;
}

int
seg_mesh_build(const struct model *m, int seg, struct seg_mesh *dest)
{
	memset(dest, 0, sizeof *dest);
	for (int g = m->seg_geom0[seg]; g < m->seg_geom0[seg] + m->seg_ngeom[seg]; g++) {
		struct view_part part[VIEW_GEOM_PARTS_MAX];
		int n = view_geom_parts(m, g, part);
		for (int k = 0; k < n; k++) {
			struct tess_mesh t;
			if (part_tess(m, &part[k], &t) < 0)
				goto oom;
			int ok = grow(dest, t.nvert, t.nidx) == 0;
			if (ok)
				append(dest, &t, &part[k]);
			tess_free(&t);
			if (!ok)
				goto oom;
		}
	}
	for (int v = 0; v < dest->nvert; v++)
		for (int i = 0; i < 3; i++) {
			float x = dest->pos[3 * v + i];
			dest->lo[i] = v ? fminf(dest->lo[i], x) : x;
			dest->hi[i] = v ? fmaxf(dest->hi[i], x) : x;
		}
	return 0;
oom:
	seg_mesh_free(dest);
	return -1;
}

void
seg_mesh_free(struct seg_mesh *mesh)
{
	free(mesh->pos);
	free(mesh->nrm);
	free(mesh->idx);
	memset(mesh, 0, sizeof *mesh);
}

static void
put_f32(uint8_t *p, float v)
{
	uint32_t u;
	memcpy(&u, &v, 4);
	for (int i = 0; i < 4; i++)
		p[i] = (uint8_t)(u >> (8 * i));
}

int
seg_mesh_write_stl(const struct seg_mesh *mesh, const char *name, FILE *f)
{
	/* an 80-byte header that must not start with "solid" (readers would take it for ASCII) */
	uint8_t head[84] = { 0 };
	snprintf((char *)head, 80, "posture segment %s", name);
	uint32_t n = (uint32_t)mesh->ntri;
	for (int i = 0; i < 4; i++)
		head[80 + i] = (uint8_t)(n >> (8 * i));
	fwrite(head, 1, sizeof head, f);
	for (int t = 0; t < mesh->ntri; t++) {
		const float *a = mesh->pos + 3 * mesh->idx[3 * t], *b = mesh->pos + 3 * mesh->idx[3 * t + 1],
			    *c = mesh->pos + 3 * mesh->idx[3 * t + 2];
		double u[3], v[3], nn[3];
		for (int i = 0; i < 3; i++) {
			u[i] = (double)b[i] - a[i];
			v[i] = (double)c[i] - a[i];
		}
		nn[0] = u[1] * v[2] - u[2] * v[1];
		nn[1] = u[2] * v[0] - u[0] * v[2];
		nn[2] = u[0] * v[1] - u[1] * v[0];
		double len = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
		uint8_t rec[50] = { 0 };
		for (int i = 0; i < 3; i++) {
			put_f32(rec + 4 * i, (float)(len > 0 ? nn[i] / len : 0));
			put_f32(rec + 12 + 4 * i, a[i]);
			put_f32(rec + 24 + 4 * i, b[i]);
			put_f32(rec + 36 + 4 * i, c[i]);
		}
		fwrite(rec, 1, sizeof rec, f);
	}
	return ferror(f) ? -1 : 0;
}
