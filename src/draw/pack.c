/* pack.c - the frame's instances as one vertex and index array by class (see pack.h) */
#include "draw/pack.h"

#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int
pack_init(struct pack *p)
{
	memset(p, 0, sizeof *p);
	p->pv = malloc(sizeof *p->pv * PACK_MAX_VERT);
	p->pi = malloc(sizeof *p->pi * PACK_MAX_IDX);
	return p->pv && p->pi ? 0 : -1;
}

void
pack_free(struct pack *p)
{
	free(p->pv);
	free(p->pi);
	p->pv = NULL;
	p->pi = NULL;
}

/* the class of an instance: opaque and casting a shadow, opaque, or transparent */
static enum pack_class
pack_class(const struct view_instance *in)
{
	if (in->rgba[3] < 1)
		return PACK_CLEAR;
	return in->shadow ? PACK_CAST : PACK_OPAQUE;
}

static uint8_t
to_byte(float v)
{
	return (uint8_t)(v <= 0 ? 0 : v >= 1 ? 255 : v * 255 + 0.5f);
}

/* one instance's vertices, in the world, and its indices; 0, 1 when it has no inverse
 * (nothing to draw), or -1 when it does not fit */
static int
pack_instance(struct pack *p, const struct view_instance *in, const struct tess_mesh *m, int *nv,
	      int *ni)
{
	if (*nv + m->nvert > PACK_MAX_VERT || *ni + m->nidx > PACK_MAX_IDX)
		return -1;
	/* normals by the inverse transpose of the linear part */
	mat3 a, inv;
	const float *t = in->mat;
	for (int j = 0; j < 3; j++)
		for (int i = 0; i < 3; i++)
			a[j][i] = t[4 * j + i];
	if (fabsf(glm_mat3_det(a)) < 1e-30f)
		return 1;
	glm_mat3_inv(a, inv);
	uint8_t c[4] = { to_byte(in->rgba[0]), to_byte(in->rgba[1]), to_byte(in->rgba[2]),
			 to_byte(in->rgba[3]) };
	struct pack_vertex *v = p->pv + *nv;
	for (int k = 0; k < m->nvert; k++, v++) {
		const float *s = m->vn + 6 * k;
		for (int i = 0; i < 3; i++) {
			v->p[i] = t[i] * s[0] + t[4 + i] * s[1] + t[8 + i] * s[2] + t[12 + i];
			/* (a^-1)^T n: row i of a^-1 transposed is column i of inv */
			v->n[i] = inv[i][0] * s[3] + inv[i][1] * s[4] + inv[i][2] * s[5];
		}
		memcpy(v->c, c, 4);
	}
	unsigned base = (unsigned)*nv;
	for (int k = 0; k < m->nidx; k++)
		p->pi[*ni + k] = m->idx[k] + base;
	*nv += m->nvert;
	*ni += m->nidx;
	return 0;
}

/* p->order: the instances sorted by distance along the line of sight, nearest first */
static void
sort_front_to_back(struct pack *p, const struct drawlist *dl, const float view[16])
{
	int n = dl->ninst;
	for (int i = 0; i < n; i++) {
		const float *t = dl->inst[i].mat + 12;
		p->key[i] = -(view[2] * t[0] + view[6] * t[1] + view[10] * t[2] + view[14]);
		p->order[i] = i;
	}
	/* insertion sort: a few hundred items, no allocation */
	for (int i = 1; i < n; i++) {
		int o = p->order[i];
		float k = p->key[o];
		int j = i;
		for (; j > 0 && p->key[p->order[j - 1]] > k; j--)
			p->order[j] = p->order[j - 1];
		p->order[j] = o;
	}
}

void
pack_drawlist(struct pack *p, const struct drawlist *dl, const float view[16],
	      const struct tess_mesh *mesh, const int *lod, int nmesh)
{
	int nv = 0, ni = 0;
	p->instances = p->triangles = 0;
	sort_front_to_back(p, dl, view);
	for (int c = 0; c < PACK_N; c++) {
		p->range[c][0] = ni;
		for (int o = 0; o < dl->ninst; o++) {
			int i = c == PACK_CLEAR ? p->order[dl->ninst - 1 - o] : p->order[o];
			const struct view_instance *in = &dl->inst[i];
			if (in->mesh < 0 || in->mesh >= nmesh)
				continue;
			if (c == PACK_SHADOW ? pack_class(in) != PACK_CAST
					     : pack_class(in) != (enum pack_class)c)
				continue;
			int m = c == PACK_SHADOW ? lod[in->mesh] : in->mesh;
			int rc = pack_instance(p, in, &mesh[m], &nv, &ni);
			if (rc < 0)
				break;
			if (rc == 0 && c != PACK_SHADOW) {
				p->instances++;
				p->triangles += mesh[m].nidx / 3;
			}
		}
		p->range[c][1] = ni - p->range[c][0];
	}
	p->nv = nv;
	p->ni = ni;
}

