/*
 * mcubes.c - marching cubes by the Kuhn split of each cube (mcubes.h).
 *
 * The split's six tetrahedra are the monotone paths from corner 000 to 111,
 * one per order of the axes: 000, e_a, e_a + e_b, 111. Every edge of them
 * joins two corners whose difference is in {0,1}^3, so an edge is named by
 * its lower point and that difference (7 kinds), the key the vertices are
 * welded by. Each tetrahedron is stored positively oriented, and the table
 * is: one corner apart from the other three (a triangle, facing away from
 * the inside corner) or two and two (a quad), oriented by the parity of the
 * corners' order.
 */
#include "assess/mcubes.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* corner c of a cube: x + 2y + 4z; the tetrahedra positively oriented (odd axis orders
 * have their middle corners swapped) */
static const unsigned char kuhn[6][4] = {
	{ 0, 1, 3, 7 }, /* x y z */
	{ 0, 5, 1, 7 }, /* x z y, swapped */
	{ 0, 3, 2, 7 }, /* y x z, swapped */
	{ 0, 2, 6, 7 }, /* y z x */
	{ 0, 4, 5, 7 }, /* z x y */
	{ 0, 6, 4, 7 }, /* z y x, swapped */
};

/* open addressing from an edge's key to its vertex */
struct edge_map {
	long *key; /* -1 empty */
	int *vert;
	size_t cap, n;
};

static size_t
hash_long(long k)
{
	uint64_t x = (uint64_t)k * 0x9E3779B97F4A7C15ull;
	return (size_t)(x ^ (x >> 29));
}

static int
map_grow(struct edge_map *h)
{
	size_t cap = h->cap ? 2 * h->cap : 4096;
	long *key = malloc(cap * sizeof *key);
	int *vert = malloc(cap * sizeof *vert);
	if (!key || !vert) {
		free(key);
		free(vert);
		return -1;
	}
	memset(key, 0xff, cap * sizeof *key);
	for (size_t i = 0; i < h->cap; i++) {
		if (h->key[i] < 0)
			continue;
		size_t j = hash_long(h->key[i]) & (cap - 1);
		while (key[j] >= 0)
			j = (j + 1) & (cap - 1);
		key[j] = h->key[i];
		vert[j] = h->vert[i];
	}
	free(h->key);
	free(h->vert);
	h->key = key;
	h->vert = vert;
	h->cap = cap;
	return 0;
}

/* growable arrays of the mesh being built */
struct build {
	const struct mc_grid *g;
	struct edge_map map;
	float *vert;
	long *edge;
	int nvert, vcap;
	int *tri;
	int ntri, tcap;
};

/* the vertex on the edge between grid points a and b (one inside, one outside), made once */
static int
edge_vertex(struct build *B, long a, long b)
{
	long lo = a < b ? a : b, hi = a < b ? b : a;
	const struct mc_grid *g = B->g;
	/* hi - lo is dx + dy n0 + dz n0 n1 with d in {0,1}^3: a unique small code */
	long d = hi - lo, nx = g->n[0], nxy = (long)g->n[0] * g->n[1];
	int code = (int)(d / nxy) * 4 + (int)(d % nxy / nx) * 2 + (int)(d % nx);
	long key = lo * 8 + code;
	if (2 * (B->map.n + 1) > B->map.cap && map_grow(&B->map) < 0)
		return -1;
	size_t j = hash_long(key) & (B->map.cap - 1);
	while (B->map.key[j] >= 0) {
		if (B->map.key[j] == key)
			return B->map.vert[j];
		j = (j + 1) & (B->map.cap - 1);
	}
	if (B->nvert == B->vcap) {
		int cap = B->vcap ? 2 * B->vcap : 4096;
		float *v = realloc(B->vert, (size_t)cap * 3 * sizeof *v);
		if (!v)
			return -1;
		B->vert = v;
		long *e = realloc(B->edge, (size_t)cap * 2 * sizeof *e);
		if (!e)
			return -1;
		B->edge = e;
		B->vcap = cap;
	}
	long in = g->val[a] <= 0 ? a : b, out = in == a ? b : a;
	double vin = g->val[in], vout = g->val[out];
	double t = vout - vin > 0 ? -vin / (vout - vin) : 0.5;
	long pi[2] = { in, out };
	double p[2][3];
	for (int q = 0; q < 2; q++) {
		long r = pi[q];
		p[q][0] = g->origin[0] + g->step * (double)(r % nx);
		p[q][1] = g->origin[1] + g->step * (double)(r % nxy / nx);
		p[q][2] = g->origin[2] + g->step * (double)(r / nxy);
	}
	int v = B->nvert++;
	for (int c = 0; c < 3; c++)
		B->vert[3 * v + c] = (float)(p[0][c] + t * (p[1][c] - p[0][c]));
	B->edge[2 * v] = in;
	B->edge[2 * v + 1] = out;
	B->map.key[j] = key;
	B->map.vert[j] = v;
	B->map.n++;
	return v;
}

static int
add_tri(struct build *B, int a, int b, int c)
{
	if (a < 0 || b < 0 || c < 0)
		return -1;
	if (B->ntri == B->tcap) {
		int cap = B->tcap ? 2 * B->tcap : 8192;
		int *t = realloc(B->tri, (size_t)cap * 3 * sizeof *t);
		if (!t)
			return -1;
		B->tri = t;
		B->tcap = cap;
	}
	B->tri[3 * B->ntri] = a;
	B->tri[3 * B->ntri + 1] = b;
	B->tri[3 * B->ntri + 2] = c;
	B->ntri++;
	return 0;
}

/* the surface in one positively oriented tetrahedron with grid points p[4] */
static int
tetra(struct build *B, const long p[4])
{
	const float *val = B->g->val;
	int in[4], nin = 0, out[4], nout = 0;
	for (int i = 0; i < 4; i++) {
		if (val[p[i]] <= 0)
			in[nin++] = i;
		else
			out[nout++] = i;
	}
	if (nin == 0 || nout == 0)
		return 0;
	if (nin == 1 || nout == 1) {
		/* the lone corner i and the others in an order making (i j k l) even: the
		 * triangle on edges i-j, i-k, i-l faces away from i */
		int i = nin == 1 ? in[0] : out[0], o[3], n = 0;
		for (int c = 0; c < 4; c++)
			if (c != i)
				o[n++] = c;
		if (i & 1) {
			int t = o[1];
			o[1] = o[2];
			o[2] = t;
		}
		int e0 = edge_vertex(B, p[i], p[o[0]]), e1 = edge_vertex(B, p[i], p[o[1]]),
		    e2 = edge_vertex(B, p[i], p[o[2]]);
		return nin == 1 ? add_tri(B, e0, e1, e2) : add_tri(B, e0, e2, e1);
	}
	/* two in (i < j), two out (k, l) ordered so that (i j k l) is even: the quad
	 * i-k, i-l, j-l, j-k faces the outside */
	int i = in[0], j = in[1], k = out[0], l = out[1];
	int perm[4] = { i, j, k, l }, inv = 0;
	for (int a = 0; a < 4; a++)
		for (int b = a + 1; b < 4; b++)
			inv += perm[a] > perm[b];
	if (inv & 1) {
		k = out[1];
		l = out[0];
	}
	int ik = edge_vertex(B, p[i], p[k]), il = edge_vertex(B, p[i], p[l]),
	    jl = edge_vertex(B, p[j], p[l]), jk = edge_vertex(B, p[j], p[k]);
	if (add_tri(B, ik, il, jl) < 0)
		return -1;
	return add_tri(B, ik, jl, jk);
}

int
mc_extract(const struct mc_grid *g, struct mc_mesh *dest, long **edges)
{
	memset(dest, 0, sizeof *dest);
	if (edges)
		*edges = NULL;
	struct build B = { .g = g };
	long nx = g->n[0], nxy = (long)g->n[0] * g->n[1];
	long off[8];
	for (int c = 0; c < 8; c++)
		off[c] = (c & 1) + ((c >> 1) & 1) * nx + ((c >> 2) & 1) * nxy;
	int fail = 0;
	for (int k = 0; k + 1 < g->n[2] && !fail; k++)
		for (int j = 0; j + 1 < g->n[1] && !fail; j++)
			for (int i = 0; i + 1 < g->n[0] && !fail; i++) {
				long base = mc_index(g, i, j, k);
				int nin = 0;
				for (int c = 0; c < 8; c++)
					nin += g->val[base + off[c]] <= 0;
				if (nin == 0 || nin == 8)
					continue;
				for (int t = 0; t < 6 && !fail; t++) {
					long p[4];
					for (int c = 0; c < 4; c++)
						p[c] = base + off[kuhn[t][c]];
					fail = tetra(&B, p) < 0;
				}
			}
	free(B.map.key);
	free(B.map.vert);
	if (fail) {
		free(B.vert);
		free(B.edge);
		free(B.tri);
		return -1;
	}
	dest->nvert = B.nvert;
	dest->ntri = B.ntri;
	dest->vert = B.vert;
	dest->tri = B.tri;
	dest->normal = malloc((size_t)(B.nvert ? B.nvert : 1) * 3 * sizeof *dest->normal);
	if (!dest->normal) {
		free(B.edge);
		mc_mesh_free(dest);
		return -1;
	}
	if (edges)
		*edges = B.edge;
	else
		free(B.edge);
	mc_mesh_finish(dest);
	return 0;
}

void
mc_mesh_finish(struct mc_mesh *mesh)
{
	double vol = 0;
	memset(mesh->normal, 0, (size_t)mesh->nvert * 3 * sizeof *mesh->normal);
	for (int t = 0; t < mesh->ntri; t++) {
		const int *v = &mesh->tri[3 * t];
		double a[3], b[3], c[3], e1[3], e2[3], n[3];
		for (int i = 0; i < 3; i++) {
			a[i] = mesh->vert[3 * v[0] + i];
			b[i] = mesh->vert[3 * v[1] + i];
			c[i] = mesh->vert[3 * v[2] + i];
			e1[i] = b[i] - a[i];
			e2[i] = c[i] - a[i];
		}
		n[0] = e1[1] * e2[2] - e1[2] * e2[1];
		n[1] = e1[2] * e2[0] - e1[0] * e2[2];
		n[2] = e1[0] * e2[1] - e1[1] * e2[0];
		/* the signed volume of the tetrahedron from the origin (divergence theorem) */
		vol += (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
			a[2] * (b[0] * c[1] - b[1] * c[0])) /
		       6;
		for (int k = 0; k < 3; k++)
			for (int i = 0; i < 3; i++)
				mesh->normal[3 * v[k] + i] += (float)n[i];
	}
	for (int v = 0; v < mesh->nvert; v++) {
		float *n = &mesh->normal[3 * v];
		double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
		for (int i = 0; i < 3; i++)
			n[i] = len > 0 ? (float)(n[i] / len) : (i == 2);
	}
	mesh->volume = vol;
	for (int i = 0; i < 3; i++) {
		mesh->lo[i] = mesh->nvert ? INFINITY : 0;
		mesh->hi[i] = mesh->nvert ? -INFINITY : 0;
	}
	for (int v = 0; v < mesh->nvert; v++)
		for (int i = 0; i < 3; i++) {
			mesh->lo[i] = fmin(mesh->lo[i], mesh->vert[3 * v + i]);
			mesh->hi[i] = fmax(mesh->hi[i], mesh->vert[3 * v + i]);
		}
}

void
mc_mesh_free(struct mc_mesh *mesh)
{
	free(mesh->vert);
	free(mesh->normal);
	free(mesh->tri);
	memset(mesh, 0, sizeof *mesh);
}

int
mc_mesh_contains(const struct mc_mesh *mesh, const double p[3])
{
	if (!mesh->ntri || p[0] < mesh->lo[0] || p[0] > mesh->hi[0] || p[1] < mesh->lo[1] ||
	    p[1] > mesh->hi[1] || p[2] < mesh->lo[2] || p[2] > mesh->hi[2])
		return 0;
	/* a direction no grid-aligned face or edge is parallel to */
	const double d[3] = { 0.3162277660, 0.7071067812, 0.6324555320 };
	int crossings = 0;
	for (int t = 0; t < mesh->ntri; t++) {
		const int *v = &mesh->tri[3 * t];
		double a[3], e1[3], e2[3], s[3], h[3], q[3];
		for (int i = 0; i < 3; i++) {
			a[i] = mesh->vert[3 * v[0] + i];
			e1[i] = mesh->vert[3 * v[1] + i] - a[i];
			e2[i] = mesh->vert[3 * v[2] + i] - a[i];
			s[i] = p[i] - a[i];
		}
		/* Moller-Trumbore: the ray p + t d against the triangle, t > 0 */
		h[0] = d[1] * e2[2] - d[2] * e2[1];
		h[1] = d[2] * e2[0] - d[0] * e2[2];
		h[2] = d[0] * e2[1] - d[1] * e2[0];
		double det = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
		if (det == 0)
			continue;
		double u = (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]) / det;
		if (u < 0 || u > 1)
			continue;
		q[0] = s[1] * e1[2] - s[2] * e1[1];
		q[1] = s[2] * e1[0] - s[0] * e1[2];
		q[2] = s[0] * e1[1] - s[1] * e1[0];
		double w = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
		if (w < 0 || u + w > 1)
			continue;
		double along = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
		crossings += along > 0;
	}
	return crossings & 1;
}
