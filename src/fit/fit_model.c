/* fit_model.c - a figure's segments as collision meshes; the self pairs left out */
#include "fit/fit_model.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "export/seg_mesh.h"
#include "fit/fit_touch.h"

static void
mark(struct fit_model *f, int a, int b, enum fit_skip k)
{
	if (a < 0 || b < 0 || a == b)
		return;
	if (f->skip[a * f->nseg + b] == FIT_CHECKED) {
		f->skip[a * f->nseg + b] = (unsigned char)k;
		f->skip[b * f->nseg + a] = (unsigned char)k;
	}
}

static void
mark_skips(struct fit_model *f)
{
	const struct model *m = f->m;
	for (int a = 0; a < f->nseg; a++) {
		f->skip[a * f->nseg + a] = FIT_SAME;
		for (int b = 0; b < f->nseg; b++)
			if (!f->mesh[a] || !f->mesh[b])
				mark(f, a, b, FIT_NO_MESH);
	}
	for (int j = 0; j < m->njnt; j++)
		mark(f, m->site_seg[m->jnt_site_from[j]], m->site_seg[m->jnt_site_to[j]], FIT_JOINTED);
	for (int a = 0; a < f->nseg; a++)
		for (int b = a + 1; b < f->nseg; b++)
			if (fit_touch(m, a, b))
				mark(f, a, b, FIT_TOUCHING);
}

/* one segment's collision mesh: 0, or -1 with err set */
static int
build_segment(struct fit_model *f, int s, char *err, size_t errlen)
{
	const struct model *m = f->m;
	struct seg_mesh sm;
	if (seg_mesh_build(m, s, &sm) < 0) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	if (sm.ntri > 0) {
		char why[128];
		f->mesh[s] = collide_mesh_make(sm.pos, sm.nvert, sm.idx, sm.ntri, why, sizeof why);
		if (!f->mesh[s]) {
			snprintf(err, errlen, "segment %s: %s", m->seg_name[s], why);
			seg_mesh_free(&sm);
			return -1;
		}
		collide_mesh_bounds(f->mesh[s], f->lo + 3 * s, f->hi + 3 * s);
		for (int v = 0; v < sm.nvert; v++) {
			const float *x = sm.pos + 3 * v;
			double r = sqrt((double)x[0] * x[0] + (double)x[1] * x[1] + (double)x[2] * x[2]);
			f->radius[s] = r > f->radius[s] ? r : f->radius[s];
		}
	}
	seg_mesh_free(&sm);
	return 0;
}

#define BUILD_THREADS_MAX 4

struct builder {
	struct fit_model *f;
	int first, step; /* the segments first, first + step, ... */
	int failed;
	char err[192];
};

static void *
build_some(void *arg)
{
	struct builder *b = arg;
	for (int s = b->first; s < b->f->nseg && !b->failed; s += b->step)
		if (build_segment(b->f, s, b->err, sizeof b->err) < 0)
			b->failed = 1;
	return NULL;
}

/* every segment's mesh, the hierarchies built on up to BUILD_THREADS_MAX cores */
static int
build_all(struct fit_model *f, char *err, size_t errlen)
{
	long cores = sysconf(_SC_NPROCESSORS_ONLN);
	int n = cores < 1 ? 1 : cores > BUILD_THREADS_MAX ? BUILD_THREADS_MAX : (int)cores;
	if (n > f->nseg)
		n = f->nseg > 0 ? f->nseg : 1;
	struct builder b[BUILD_THREADS_MAX];
	pthread_t t[BUILD_THREADS_MAX];
	int started[BUILD_THREADS_MAX] = { 0 };
	for (int k = 0; k < n; k++) {
		b[k] = (struct builder){ f, k, n, 0, "" };
		if (k > 0)
			started[k] = pthread_create(&t[k], NULL, build_some, &b[k]) == 0;
	}
	for (int k = 1; k < n; k++) /* what a thread could not start, this one does */
		if (!started[k])
			build_some(&b[k]);
	build_some(&b[0]);
	for (int k = 1; k < n; k++)
		if (started[k])
			pthread_join(t[k], NULL);
	for (int k = 0; k < n; k++) {
		if (b[k].failed) {
			snprintf(err, errlen, "%s", b[k].err);
			return -1;
		}
	}
	return 0;
}

struct fit_model *
fit_model_make(const struct model *m, char *err, size_t errlen)
{
	struct fit_model *f = calloc(1, sizeof *f);
	if (!f)
		goto oom;
	f->m = m;
	f->nseg = m->nseg;
	f->mesh = calloc((size_t)m->nseg + 1, sizeof *f->mesh);
	f->lo = calloc(3 * (size_t)m->nseg + 1, sizeof *f->lo);
	f->hi = calloc(3 * (size_t)m->nseg + 1, sizeof *f->hi);
	f->radius = calloc((size_t)m->nseg + 1, sizeof *f->radius);
	f->skip = calloc((size_t)m->nseg * (size_t)m->nseg + 1, 1);
	if (!f->mesh || !f->lo || !f->hi || !f->radius || !f->skip)
		goto oom;
	if (build_all(f, err, errlen) < 0) {
		fit_model_free(f);
		return NULL;
	}
	for (int s = 0; s < f->nseg; s++)
		f->ntri += f->mesh[s] ? collide_mesh_triangles(f->mesh[s]) : 0;
	mark_skips(f);
	return f;
oom:
	snprintf(err, errlen, "out of memory");
	fit_model_free(f);
	return NULL;
}

void
fit_model_free(struct fit_model *f)
{
	if (!f)
		return;
	if (f->mesh)
		for (int s = 0; s < f->nseg; s++)
			collide_mesh_free(f->mesh[s]);
	free(f->mesh);
	free(f->lo);
	free(f->hi);
	free(f->radius);
	free(f->skip);
	free(f);
}

enum fit_skip
fit_model_skip(const struct fit_model *f, int a, int b)
{
	if (a < 0 || b < 0 || a >= f->nseg || b >= f->nseg)
		return FIT_NO_MESH;
	return (enum fit_skip)f->skip[a * f->nseg + b];
}

const char *
fit_skip_str(enum fit_skip k)
{
	switch (k) {
	case FIT_CHECKED:
		return "checked";
	case FIT_SAME:
		return "the same segment";
	case FIT_JOINTED:
		return "jointed to each other";
	case FIT_TOUCHING:
		return "touching in a normal posture";
	case FIT_NO_MESH:
		return "no geometry";
	}
	return "?";
}

void
fit_model_world_box(const struct fit_model *f, int seg, const struct xform *xf, double lo[3],
		    double hi[3])
{
	const double *l = f->lo + 3 * seg, *h = f->hi + 3 * seg;
	for (int i = 0; i < 3; i++) {
		double c = xf->p[i], r = 0;
		for (int j = 0; j < 3; j++) {
			double mid = (l[j] + h[j]) / 2, half = (h[j] - l[j]) / 2;
			c += xf->r[3 * i + j] * mid;
			r += fabs(xf->r[3 * i + j]) * half;
		}
		lo[i] = c - r;
		hi[i] = c + r;
	}
}
