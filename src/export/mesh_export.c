/* mesh_export.c - closed triangle meshes as STL and glTF (see mesh_export.h) */
#include "export/mesh_export.h"

#include <jansson.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "export/export_file.h"

#define GL_FLOAT 5126
#define GL_UNSIGNED_INT 5125
#define GL_ARRAY_BUFFER 34962
#define GL_ELEMENT_ARRAY_BUFFER 34963
#define GLB_MAGIC 0x46546c67u /* "glTF" */
#define GLB_JSON 0x4e4f534au
#define GLB_BIN 0x004e4942u

static void
put_u32(unsigned char *p, uint32_t v)
{
	for (int i = 0; i < 4; i++)
		p[i] = (unsigned char)(v >> (8 * i));
}

/* little-endian IEEE 754 single, as STL and glTF both store them */
static void
put_f32(unsigned char *p, float f)
{
	uint32_t u;
	memcpy(&u, &f, sizeof u);
	put_u32(p, u);
}

static int
ends_with(const char *s, const char *ext)
{
	size_t n = strlen(s), e = strlen(ext);
	return n > e && !strcmp(s + n - e, ext);
}

static int
check(const struct mesh_export *m, int n, char *err, size_t errlen)
{
	if (n < 1) {
		snprintf(err, errlen, "no mesh to export");
		return -1;
	}
	for (int k = 0; k < n; k++) {
		if (m[k].ntri < 1 || m[k].nvert < 3) {
			snprintf(err, errlen, "%s: an empty mesh", m[k].name);
			return -1;
		}
		for (long i = 0; i < 3L * m[k].ntri; i++)
			if (m[k].tri[i] < 0 || m[k].tri[i] >= m[k].nvert) {
				snprintf(err, errlen, "%s: triangle %ld names vertex %d of %d", m[k].name,
					 i / 3, m[k].tri[i], m[k].nvert);
				return -1;
			}
	}
	return 0;
}

/*
 * A surface as written: vertices at the same position welded into one (the
 * first one's normal kept) and the triangles that then repeat a corner left
 * out. Those have no area, add nothing to the volume, and would leave edges
 * shared by more than two facets once a reader welds by position (every STL
 * reader does): a marching-cubes surface passing exactly through a grid point
 * makes them.
 */
struct welded {
	int nvert, ntri;
	float *vert, *normal;
	int *tri;
};

static const float *sort_vert; /* qsort has no context argument: the vertices being sorted */

static int
by_position(const void *a, const void *b)
{
	const float *p = sort_vert + 3 * *(const int *)a, *q = sort_vert + 3 * *(const int *)b;
	for (int k = 0; k < 3; k++)
		if (p[k] != q[k])
			return p[k] < q[k] ? -1 : 1;
	return *(const int *)a - *(const int *)b; /* the first of equals first */
}

static void
welded_free(struct welded *w)
{
	free(w->vert);
	free(w->normal);
	free(w->tri);
}

/* 0, or -1 when out of memory */
static int
weld(const struct mesh_export *m, struct welded *dest)
{
	memset(dest, 0, sizeof *dest);
	int *order = malloc(sizeof *order * (size_t)m->nvert);
	int *map = malloc(sizeof *map * (size_t)m->nvert);
	dest->vert = malloc(sizeof(float) * 3 * (size_t)m->nvert);
	dest->normal = malloc(sizeof(float) * 3 * (size_t)m->nvert);
	dest->tri = malloc(sizeof(int) * 3 * (size_t)m->ntri);
	if (!order || !map || !dest->vert || !dest->normal || !dest->tri) {
		free(order);
		free(map);
		welded_free(dest);
		return -1;
	}
	for (int i = 0; i < m->nvert; i++)
		order[i] = i;
	sort_vert = m->vert;
	qsort(order, (size_t)m->nvert, sizeof *order, by_position);
	/* each vertex's representative: the first (lowest index) at its position; order reused */
	for (int k = 0; k < m->nvert; k++) {
		int i = order[k];
		int same = k && !memcmp(m->vert + 3 * i, m->vert + 3 * order[k - 1], 3 * sizeof(float));
		map[i] = same ? map[order[k - 1]] : i;
	}
	/* numbered in the input's order, so a surface without duplicates stays as it was */
	for (int i = 0; i < m->nvert; i++) {
		if (map[i] != i) {
			map[i] = order[map[i]];
			continue;
		}
		order[i] = dest->nvert; /* order[i] now: vertex i's new number */
		map[i] = dest->nvert;
		memcpy(dest->vert + 3 * dest->nvert, m->vert + 3 * i, 3 * sizeof(float));
		memcpy(dest->normal + 3 * dest->nvert, m->normal + 3 * i, 3 * sizeof(float));
		dest->nvert++;
	}
	for (int t = 0; t < m->ntri; t++) {
		int a = map[m->tri[3 * t]], b = map[m->tri[3 * t + 1]], c = map[m->tri[3 * t + 2]];
		if (a == b || b == c || c == a)
			continue;
		int *d = dest->tri + 3 * dest->ntri++;
		d[0] = a;
		d[1] = b;
		d[2] = c;
	}
	free(order);
	free(map);
	return 0;
}

/* binary STL: an 80-byte header, the count, then 50 bytes a facet (its normal, 3 corners) */
static int
write_stl(const struct mesh_export *m, FILE *f)
{
	unsigned char head[84] = { 0 }, rec[50];
	snprintf((char *)head, 80, "posture %s", m->name);
	put_u32(head + 80, (uint32_t)m->ntri);
	if (fwrite(head, 1, sizeof head, f) != sizeof head)
		return -1;
	for (int t = 0; t < m->ntri; t++) {
		const float *a = m->vert + 3 * m->tri[3 * t], *b = m->vert + 3 * m->tri[3 * t + 1],
			    *c = m->vert + 3 * m->tri[3 * t + 2];
		/* the facet's own normal: (b - a) x (c - a), unit */
		double u[3], v[3], nrm[3];
		for (int i = 0; i < 3; i++) {
			u[i] = (double)b[i] - a[i];
			v[i] = (double)c[i] - a[i];
		}
		nrm[0] = u[1] * v[2] - u[2] * v[1];
		nrm[1] = u[2] * v[0] - u[0] * v[2];
		nrm[2] = u[0] * v[1] - u[1] * v[0];
		double len = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
		for (int i = 0; i < 3; i++) {
			put_f32(rec + 4 * i, len > 0 ? (float)(nrm[i] / len) : 0.0f);
			put_f32(rec + 12 + 4 * i, a[i]);
			put_f32(rec + 24 + 4 * i, b[i]);
			put_f32(rec + 36 + 4 * i, c[i]);
		}
		rec[48] = rec[49] = 0;
		if (fwrite(rec, 1, sizeof rec, f) != sizeof rec)
			return -1;
	}
	return 0;
}

/* the binary buffer: each mesh's positions, normals and indices, in that order */
static size_t
mesh_bytes(const struct mesh_export *m)
{
	return 24 * (size_t)m->nvert + 12 * (size_t)m->ntri;
}

static unsigned char *
make_bin(const struct mesh_export *m, int n, size_t *len)
{
	size_t total = 0;
	for (int k = 0; k < n; k++)
		total += mesh_bytes(&m[k]);
	unsigned char *bin = malloc(total ? total : 1), *p = bin;
	if (!bin)
		return NULL;
	for (int k = 0; k < n; k++) {
		for (long i = 0; i < 3L * m[k].nvert; i++, p += 4)
			put_f32(p, m[k].vert[i]);
		for (long i = 0; i < 3L * m[k].nvert; i++, p += 4)
			put_f32(p, m[k].normal[i]);
		for (long i = 0; i < 3L * m[k].ntri; i++, p += 4)
			put_u32(p, (uint32_t)m[k].tri[i]);
	}
	*len = total;
	return bin;
}

static const char b64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/* "data:application/octet-stream;base64,..." for bin; malloc'd, NULL when out of memory */
static char *
data_uri(const unsigned char *bin, size_t len)
{
	static const char head[] = "data:application/octet-stream;base64,";
	char *s = malloc(sizeof head + (len + 2) / 3 * 4), *p;
	if (!s)
		return NULL;
	memcpy(s, head, sizeof head - 1);
	p = s + sizeof head - 1;
	for (size_t i = 0; i < len; i += 3) {
		uint32_t v = (uint32_t)bin[i] << 16;
		if (i + 1 < len)
			v |= (uint32_t)bin[i + 1] << 8;
		if (i + 2 < len)
			v |= bin[i + 2];
		*p++ = b64[(v >> 18) & 63];
		*p++ = b64[(v >> 12) & 63];
		*p++ = i + 1 < len ? b64[(v >> 6) & 63] : '=';
		*p++ = i + 2 < len ? b64[v & 63] : '=';
	}
	*p = '\0';
	return s;
}

/* appends v to array a; 0, or -1 (v is released either way) */
static int
push(json_t *a, json_t *v)
{
	return v && json_array_append_new(a, v) == 0 ? 0 : -1;
}

static json_t *
vec3(const double v[3])
{
	return json_pack("[f,f,f]", v[0], v[1], v[2]);
}

/* the glTF document of n meshes over a buffer of len bytes (uri NULL: a .glb's own) */
static json_t *
document(const struct mesh_export *m, int n, size_t len, const char *uri)
{
	json_t *root = json_pack("{s:{s:s, s:s}, s:i, s:[{s:[]}], s:[], s:[], s:[], s:[], s:[]}",
				 "asset", "version", "2.0", "generator", "posture", "scene", 0,
				 "scenes", "nodes", "nodes", "meshes", "materials", "accessors",
				 "bufferViews");
	if (!root)
		return NULL;
	json_t *nodes = json_object_get(root, "nodes"), *meshes = json_object_get(root, "meshes"),
	       *mats = json_object_get(root, "materials"),
	       *acc = json_object_get(root, "accessors"), *views = json_object_get(root, "bufferViews"),
	       *scene = json_object_get(json_array_get(json_object_get(root, "scenes"), 0), "nodes");
	int bad = 0;
	size_t off = 0;
	for (int k = 0; k < n; k++) {
		const struct mesh_export *x = &m[k];
		double lo[3], hi[3];
		for (int i = 0; i < 3; i++)
			lo[i] = hi[i] = x->vert[i];
		for (int v = 0; v < x->nvert; v++)
			for (int i = 0; i < 3; i++) {
				lo[i] = fmin(lo[i], x->vert[3 * v + i]);
				hi[i] = fmax(hi[i], x->vert[3 * v + i]);
			}
		size_t vb = 12 * (size_t)x->nvert, ib = 12 * (size_t)x->ntri;
		int v0 = (int)json_array_size(views), a0 = (int)json_array_size(acc);
		bad |= push(views, json_pack("{s:i, s:I, s:I, s:i}", "buffer", 0, "byteOffset",
					     (json_int_t)off, "byteLength", (json_int_t)vb, "target",
					     GL_ARRAY_BUFFER));
		bad |= push(views, json_pack("{s:i, s:I, s:I, s:i}", "buffer", 0, "byteOffset",
					     (json_int_t)(off + vb), "byteLength", (json_int_t)vb,
					     "target", GL_ARRAY_BUFFER));
		bad |= push(views, json_pack("{s:i, s:I, s:I, s:i}", "buffer", 0, "byteOffset",
					     (json_int_t)(off + 2 * vb), "byteLength", (json_int_t)ib,
					     "target", GL_ELEMENT_ARRAY_BUFFER));
		off += vb + vb + ib;
		/* glTF requires a position accessor's bounds */
		bad |= push(acc, json_pack("{s:i, s:i, s:i, s:s, s:o, s:o}", "bufferView", v0,
					   "componentType", GL_FLOAT, "count", x->nvert, "type",
					   "VEC3", "min", vec3(lo), "max", vec3(hi)));
		bad |= push(acc, json_pack("{s:i, s:i, s:i, s:s}", "bufferView", v0 + 1,
					   "componentType", GL_FLOAT, "count", x->nvert, "type",
					   "VEC3"));
		bad |= push(acc, json_pack("{s:i, s:i, s:i, s:s}", "bufferView", v0 + 2,
					   "componentType", GL_UNSIGNED_INT, "count", 3 * x->ntri,
					   "type", "SCALAR"));
		json_t *mat = json_pack("{s:s, s:{s:[f,f,f,f], s:f, s:f}}", "name", x->name,
					"pbrMetallicRoughness", "baseColorFactor", (double)x->rgba[0],
					(double)x->rgba[1], (double)x->rgba[2], (double)x->rgba[3],
					"metallicFactor", 0.0, "roughnessFactor", 0.8);
		if (mat && x->rgba[3] < 1)
			json_object_set_new(mat, "alphaMode", json_string("BLEND"));
		bad |= push(mats, mat);
		bad |= push(meshes, json_pack("{s:s, s:[{s:{s:i, s:i}, s:i, s:i, s:i}]}", "name",
					      x->name, "primitives", "attributes", "POSITION", a0,
					      "NORMAL", a0 + 1, "indices", a0 + 2, "material", k,
					      "mode", 4));
		bad |= push(nodes, json_pack("{s:s, s:i}", "name", x->name, "mesh", k));
		bad |= push(scene, json_integer(k));
	}
	json_t *buf = json_pack("{s:I}", "byteLength", (json_int_t)len);
	if (buf && uri)
		json_object_set_new(buf, "uri", json_string(uri));
	bad |= json_object_set_new(root, "buffers", json_pack("[o]", buf)) < 0;
	if (bad) {
		json_decref(root);
		return NULL;
	}
	return root;
}

static int
write_glb(FILE *f, const char *json, const unsigned char *bin, size_t binlen)
{
	size_t jlen = strlen(json), jpad = (4 - jlen % 4) % 4, bpad = (4 - binlen % 4) % 4;
	unsigned char h[20];
	put_u32(h, GLB_MAGIC);
	put_u32(h + 4, 2);
	put_u32(h + 8, (uint32_t)(12 + 8 + jlen + jpad + 8 + binlen + bpad));
	put_u32(h + 12, (uint32_t)(jlen + jpad));
	put_u32(h + 16, GLB_JSON);
	unsigned char b[8];
	put_u32(b, (uint32_t)(binlen + bpad));
	put_u32(b + 4, GLB_BIN);
	int ok = fwrite(h, 1, 20, f) == 20 && fwrite(json, 1, jlen, f) == jlen &&
		 fwrite("   ", 1, jpad, f) == jpad && fwrite(b, 1, 8, f) == 8 &&
		 fwrite(bin, 1, binlen, f) == binlen && fwrite("\0\0\0", 1, bpad, f) == bpad;
	return ok ? 0 : -1;
}

static int
write_gltf(const struct mesh_export *m, int n, int binary, FILE *f)
{
	size_t len = 0;
	unsigned char *bin = make_bin(m, n, &len);
	char *uri = bin && !binary ? data_uri(bin, len) : NULL;
	json_t *doc = bin && (binary || uri) ? document(m, n, len, uri) : NULL;
	char *json = doc ? json_dumps(doc, JSON_COMPACT | JSON_REAL_PRECISION(9)) : NULL;
	int rc = -1;
	if (json)
		rc = binary ? write_glb(f, json, bin, len) : (fputs(json, f) < 0 ? -1 : 0);
	free(json);
	json_decref(doc);
	free(uri);
	free(bin);
	return rc;
}

int
mesh_export_write(const struct mesh_export *m, int n, const char *path, char *err, size_t errlen)
{
	int stl = ends_with(path, ".stl"), glb = ends_with(path, ".glb"),
	    gltf = ends_with(path, ".gltf");
	if (!stl && !glb && !gltf) {
		snprintf(err, errlen, "'%.200s' must end in .stl, .glb or .gltf", path);
		return -1;
	}
	if (check(m, stl ? 1 : n, err, errlen) < 0)
		return -1;
	if (stl)
		n = 1;
	struct welded *w = calloc((size_t)n, sizeof *w);
	struct mesh_export *clean = calloc((size_t)n, sizeof *clean);
	int made = 0;
	for (; w && clean && made < n; made++) {
		if (weld(&m[made], &w[made]) < 0)
			break;
		clean[made] = m[made];
		clean[made].nvert = w[made].nvert;
		clean[made].ntri = w[made].ntri;
		clean[made].vert = w[made].vert;
		clean[made].normal = w[made].normal;
		clean[made].tri = w[made].tri;
	}
	int rc = -1;
	if (made < n)
		snprintf(err, errlen, "out of memory");
	else if (check(clean, n, err, errlen) == 0) {
		struct export_file out;
		FILE *f = export_file_open(&out, path, err, errlen);
		if (f && (stl ? write_stl(clean, f) : write_gltf(clean, n, glb, f)) < 0) {
			export_file_abandon(&out);
			snprintf(err, errlen, "%s: could not write (out of memory or disk)", path);
		} else if (f) {
			rc = export_file_commit(&out, err, errlen);
		}
	}
	for (int k = 0; k < made; k++)
		welded_free(&w[k]);
	free(w);
	free(clean);
	return rc;
}
