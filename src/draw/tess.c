/* tess.c - primitive and mesh tessellation with per-vertex normals (see tess.h) */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "draw/tess.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static int
mesh_alloc(struct tess_mesh *dest, int nvert, int nidx)
{
	memset(dest, 0, sizeof *dest);
	dest->vn = malloc(sizeof(float) * 6 * (size_t)(nvert > 0 ? nvert : 1));
	dest->idx = malloc(sizeof(unsigned) * (size_t)(nidx > 0 ? nidx : 1));
	if (!dest->vn || !dest->idx) {
		tess_free(dest);
		return -1;
	}
	return 0;
}

static void
put_vert(struct tess_mesh *m, float x, float y, float z, float nx, float ny, float nz)
{
	float *v = m->vn + 6 * m->nvert++;
	v[0] = x, v[1] = y, v[2] = z, v[3] = nx, v[4] = ny, v[5] = nz;
}

static void
put_tri(struct tess_mesh *m, unsigned a, unsigned b, unsigned c)
{
	m->idx[m->nidx++] = a;
	m->idx[m->nidx++] = b;
	m->idx[m->nidx++] = c;
}

static void
bounds(struct tess_mesh *m)
{
	for (int k = 0; k < 3; k++)
		m->lo[k] = m->hi[k] = m->nvert ? m->vn[k] : 0;
	for (int i = 0; i < m->nvert; i++)
		for (int k = 0; k < 3; k++) {
			float v = m->vn[6 * i + k];
			m->lo[k] = v < m->lo[k] ? v : m->lo[k];
			m->hi[k] = v > m->hi[k] ? v : m->hi[k];
		}
}

/* a grid of rings from polar angle t0 to t1 (0 = +y pole), slices+1 vertices a ring */
static void
sphere_band(struct tess_mesh *m, int slices, int stacks, double t0, double t1)
{
	unsigned base = (unsigned)m->nvert;
	for (int i = 0; i <= stacks; i++) {
		double t = t0 + (t1 - t0) * i / stacks;
		for (int j = 0; j <= slices; j++) {
			double p = 2 * M_PI * j / slices;
			float x = (float)(sin(t) * sin(p)), y = (float)cos(t), z = (float)(sin(t) * cos(p));
			put_vert(m, x, y, z, x, y, z);
		}
	}
	/* quads between rings, split in two; skip the empty triangles at the poles */
	for (int i = 0; i < stacks; i++)
		for (int j = 0; j < slices; j++) {
			unsigned a = base + (unsigned)(i * (slices + 1) + j), b = a + 1;
			unsigned c = a + (unsigned)(slices + 1), d = c + 1;
			if (i > 0 || t0 > 0)
				put_tri(m, a, c, b);
			if (i < stacks - 1 || t1 < M_PI - 1e-9)
				put_tri(m, b, c, d);
		}
}

int
tess_sphere(int slices, int stacks, struct tess_mesh *dest)
{
	if (mesh_alloc(dest, (slices + 1) * (stacks + 1), 6 * slices * stacks))
		return -1;
	sphere_band(dest, slices, stacks, 0, M_PI);
	bounds(dest);
	return 0;
}

int
tess_hemisphere(int slices, int stacks, struct tess_mesh *dest)
{
	if (mesh_alloc(dest, (slices + 1) * (stacks + 1), 6 * slices * stacks))
		return -1;
	sphere_band(dest, slices, stacks, 0, M_PI / 2);
	bounds(dest);
	return 0;
}

/* a flat disk at height y facing ny (+1 or -1), radius 1 */
static void
disk(struct tess_mesh *m, int slices, float y, float ny)
{
	unsigned c = (unsigned)m->nvert;
	put_vert(m, 0, y, 0, 0, ny, 0);
	for (int j = 0; j <= slices; j++) {
		double p = 2 * M_PI * j / slices;
		put_vert(m, (float)sin(p), y, (float)cos(p), 0, ny, 0);
	}
	for (int j = 0; j < slices; j++) {
		unsigned a = c + 1 + (unsigned)j, b = a + 1;
		if (ny > 0)
			put_tri(m, c, a, b);
		else
			put_tri(m, c, b, a);
	}
}

int
tess_cylinder(int slices, int caps, struct tess_mesh *dest)
{
	int nv = 2 * (slices + 1) + (caps ? 2 * (slices + 2) : 0);
	int ni = 6 * slices + (caps ? 6 * slices : 0);
	if (mesh_alloc(dest, nv, ni))
		return -1;
	for (int j = 0; j <= slices; j++) {
		double p = 2 * M_PI * j / slices;
		float x = (float)sin(p), z = (float)cos(p);
		put_vert(dest, x, 0.5f, z, x, 0, z);
		put_vert(dest, x, -0.5f, z, x, 0, z);
	}
	for (int j = 0; j < slices; j++) {
		unsigned a = (unsigned)(2 * j), b = a + 1, c = a + 2, d = a + 3;
		put_tri(dest, a, b, c);
		put_tri(dest, c, b, d);
	}
	if (caps) {
		disk(dest, slices, 0.5f, 1);
		disk(dest, slices, -0.5f, -1);
	}
	bounds(dest);
	return 0;
}

int
tess_cone(int slices, struct tess_mesh *dest)
{
	/* side normals lean up by 45 deg (radius 1, height 1); apex split per slice */
	const float k = (float)(1 / sqrt(2.0));
	if (mesh_alloc(dest, 2 * (slices + 1) + slices + 2, 3 * slices + 3 * slices))
		return -1;
	for (int j = 0; j <= slices; j++) {
		double p = 2 * M_PI * j / slices, pm = 2 * M_PI * (j + 0.5) / slices;
		float x = (float)sin(p), z = (float)cos(p);
		put_vert(dest, x, 0, z, x * k, k, z * k);
		put_vert(dest, 0, 1, 0, (float)sin(pm) * k, k, (float)cos(pm) * k);
	}
	for (int j = 0; j < slices; j++) {
		unsigned a = (unsigned)(2 * j);
		put_tri(dest, a, a + 2, a + 1);
	}
	disk(dest, slices, 0, -1);
	bounds(dest);
	return 0;
}

int
tess_box(struct tess_mesh *dest)
{
	/* per face: normal axis n, sign s; two tangent axes u, v with u x v = s n */
	if (mesh_alloc(dest, 24, 36))
		return -1;
	for (int n = 0; n < 3; n++)
		for (int s = -1; s <= 1; s += 2) {
			int u = (n + 1) % 3, v = (n + 2) % 3;
			unsigned base = (unsigned)dest->nvert;
			static const float cu[4] = { -1, 1, 1, -1 }, cv[4] = { -1, -1, 1, 1 };
			for (int c = 0; c < 4; c++) {
				float p[3], nn[3] = { 0, 0, 0 };
				p[n] = 0.5f * (float)s;
				p[u] = 0.5f * cu[c] * (float)s;
				p[v] = 0.5f * cv[c];
				nn[n] = (float)s;
				put_vert(dest, p[0], p[1], p[2], nn[0], nn[1], nn[2]);
			}
			put_tri(dest, base, base + 1, base + 2);
			put_tri(dest, base, base + 2, base + 3);
		}
	bounds(dest);
	return 0;
}

static void
face_normal(const float *vert, const int *f, double dest[3])
{
	const float *a = vert + 3 * f[0], *b = vert + 3 * f[1], *c = vert + 3 * f[2];
	double u[3], v[3];
	for (int k = 0; k < 3; k++) {
		u[k] = b[k] - a[k];
		v[k] = c[k] - a[k];
	}
	/* length = twice the area: the mean below is area-weighted */
	dest[0] = u[1] * v[2] - u[2] * v[1];
	dest[1] = u[2] * v[0] - u[0] * v[2];
	dest[2] = u[0] * v[1] - u[1] * v[0];
}

int
tess_mesh_from_triangles(const float *vert, int nvert, const int *face, int nface,
			 double crease_deg, struct tess_mesh *dest)
{
	double *fn = malloc(sizeof(double) * 3 * (size_t)(nface > 0 ? nface : 1));
	int *cnt = calloc((size_t)nvert + 1, sizeof(int));
	int *adj = malloc(sizeof(int) * 3 * (size_t)(nface > 0 ? nface : 1));
	int *fill = calloc((size_t)nvert + 1, sizeof(int));
	int rc = -1;
	if (!fn || !cnt || !adj || !fill || mesh_alloc(dest, 3 * nface, 3 * nface))
		goto out;

	/* face normals and vertex -> faces adjacency (counting sort) */
	for (int f = 0; f < nface; f++) {
		face_normal(vert, face + 3 * f, fn + 3 * f);
		for (int k = 0; k < 3; k++)
			cnt[face[3 * f + k] + 1]++;
	}
	for (int v = 0; v < nvert; v++)
		cnt[v + 1] += cnt[v];
	for (int f = 0; f < nface; f++)
		for (int k = 0; k < 3; k++) {
			int v = face[3 * f + k];
			adj[cnt[v] + fill[v]++] = f;
		}

	/* one vertex per corner; blend the neighbours within the crease angle */
	double cosc = cos(crease_deg * M_PI / 180);
	for (int f = 0; f < nface; f++) {
		double *n0 = fn + 3 * f, l0 = sqrt(n0[0] * n0[0] + n0[1] * n0[1] + n0[2] * n0[2]);
		if (l0 <= 0)
			continue;
		unsigned base = (unsigned)dest->nvert;
		for (int k = 0; k < 3; k++) {
			int v = face[3 * f + k];
			double s[3] = { 0, 0, 0 };
			for (int a = cnt[v]; a < cnt[v + 1]; a++) {
				double *n1 = fn + 3 * adj[a];
				double l1 = sqrt(n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2]);
				if (l1 <= 0 || (n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2]) < cosc * l0 * l1)
					continue;
				for (int r = 0; r < 3; r++)
					s[r] += n1[r];
			}
			double l = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
			const float *p = vert + 3 * v;
			put_vert(dest, p[0], p[1], p[2], (float)(s[0] / l), (float)(s[1] / l),
				 (float)(s[2] / l));
		}
		put_tri(dest, base, base + 1, base + 2);
	}
	bounds(dest);
	rc = 0;
out:
	free(fn);
	free(cnt);
	free(adj);
	free(fill);
	return rc;
}

void
tess_free(struct tess_mesh *mesh)
{
	free(mesh->vn);
	free(mesh->idx);
	memset(mesh, 0, sizeof *mesh);
}
