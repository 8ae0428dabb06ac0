/*
 * icosphere.h - a closed, outward-wound triangle mesh for tests: the
 * icosahedron subdivided `levels` times, its vertices pushed onto the
 * sphere of radius r about c. Its volume tends to 4/3 pi r^3 from below.
 */
#ifndef POSTURE_TEST_ICOSPHERE_H
#define POSTURE_TEST_ICOSPHERE_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct icosphere {
	int nvert, ntri;
	float *vert, *normal;
	int *tri;
};

/* the midpoint vertex of edge (a, b), made once: a linear search is fine at test sizes */
static inline int
ico_mid(struct icosphere *s, int *edges, int *nedge, int a, int b)
{
	int lo = a < b ? a : b, hi = a < b ? b : a;
	for (int i = 0; i < *nedge; i++)
		if (edges[3 * i] == lo && edges[3 * i + 1] == hi)
			return edges[3 * i + 2];
	float *p = s->vert + 3 * s->nvert;
	for (int k = 0; k < 3; k++)
		p[k] = (s->vert[3 * a + k] + s->vert[3 * b + k]) / 2;
	float n = sqrtf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
	for (int k = 0; k < 3; k++)
		p[k] /= n;
	edges[3 * *nedge] = lo;
	edges[3 * *nedge + 1] = hi;
	edges[3 * *nedge + 2] = s->nvert;
	++*nedge;
	return s->nvert++;
}

static inline void
icosphere_make(struct icosphere *s, int levels, double r, const double c[3])
{
	const float t = (1 + sqrtf(5)) / 2;
	const float v0[12][3] = { { -1, t, 0 }, { 1, t, 0 },  { -1, -t, 0 }, { 1, -t, 0 },
				  { 0, -1, t }, { 0, 1, t },  { 0, -1, -t }, { 0, 1, -t },
				  { t, 0, -1 }, { t, 0, 1 },  { -t, 0, -1 }, { -t, 0, 1 } };
	const int f0[20][3] = { { 0, 11, 5 }, { 0, 5, 1 },  { 0, 1, 7 },   { 0, 7, 10 }, { 0, 10, 11 },
				{ 1, 5, 9 },  { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 },
				{ 3, 9, 4 },  { 3, 4, 2 },  { 3, 2, 6 },   { 3, 6, 8 },  { 3, 8, 9 },
				{ 4, 9, 5 },  { 2, 4, 11 }, { 6, 2, 10 },  { 8, 6, 7 },  { 9, 8, 1 } };
	int maxv = 12, maxt = 20;
	for (int l = 0; l < levels; l++) {
		maxv += maxt * 3 / 2;
		maxt *= 4;
	}
	s->vert = malloc(sizeof(float) * 3 * (size_t)maxv);
	s->normal = malloc(sizeof(float) * 3 * (size_t)maxv);
	s->tri = malloc(sizeof(int) * 3 * (size_t)maxt);
	int *tmp = malloc(sizeof(int) * 3 * (size_t)maxt);
	int *edges = malloc(sizeof(int) * 3 * (size_t)maxt * 2);
	s->nvert = 12;
	s->ntri = 20;
	for (int i = 0; i < 12; i++) {
		float n = sqrtf(v0[i][0] * v0[i][0] + v0[i][1] * v0[i][1] + v0[i][2] * v0[i][2]);
		for (int k = 0; k < 3; k++)
			s->vert[3 * i + k] = v0[i][k] / n;
	}
	memcpy(s->tri, f0, sizeof f0);
	for (int l = 0; l < levels; l++) {
		int nedge = 0, nt = 0;
		for (int f = 0; f < s->ntri; f++) {
			int a = s->tri[3 * f], b = s->tri[3 * f + 1], cc = s->tri[3 * f + 2];
			int ab = ico_mid(s, edges, &nedge, a, b), bc = ico_mid(s, edges, &nedge, b, cc),
			    ca = ico_mid(s, edges, &nedge, cc, a);
			int q[4][3] = { { a, ab, ca }, { b, bc, ab }, { cc, ca, bc }, { ab, bc, ca } };
			memcpy(tmp + 3 * nt, q, sizeof q);
			nt += 4;
		}
		memcpy(s->tri, tmp, sizeof(int) * 3 * (size_t)nt);
		s->ntri = nt;
	}
	for (int i = 0; i < s->nvert; i++)
		for (int k = 0; k < 3; k++) {
			s->normal[3 * i + k] = s->vert[3 * i + k];
			s->vert[3 * i + k] = (float)(c[k] + r * s->vert[3 * i + k]);
		}
	free(tmp);
	free(edges);
}

/* the enclosed volume by the divergence theorem: a sum of signed tetrahedra */
static inline double
icosphere_volume(const float *v, const int *tri, int ntri)
{
	double vol = 0;
	for (int f = 0; f < ntri; f++) {
		const float *a = v + 3 * tri[3 * f], *b = v + 3 * tri[3 * f + 1], *c = v + 3 * tri[3 * f + 2];
		vol += (a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) -
			a[1] * ((double)b[0] * c[2] - (double)b[2] * c[0]) +
			a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0])) / 6;
	}
	return vol;
}

static inline void
icosphere_free(struct icosphere *s)
{
	free(s->vert);
	free(s->normal);
	free(s->tri);
}

#endif
