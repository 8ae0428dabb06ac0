/*
 * test_mesh_export.c - closed meshes written as STL and glTF
 * (export/mesh_export.h), read back here byte by byte against the formats'
 * layouts: binary STL's 84-byte head and 50-byte facets, GLB's chunks, the
 * .gltf's base64 buffer; a triangle soup with a zero-area facet written
 * welded. (The system tests read them with trimesh too.)
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "export/mesh_export.h"
#include "icosphere.h"

static char dir[] = "/tmp/mesh_export_XXXXXX";

static unsigned char *
slurp(const char *path, size_t *len)
{
	FILE *f = fopen(path, "rb");
	assert_non_null(f);
	fseek(f, 0, SEEK_END);
	*len = (size_t)ftell(f);
	fseek(f, 0, SEEK_SET);
	unsigned char *b = malloc(*len + 1);
	assert_int_equal(fread(b, 1, *len, f), *len);
	b[*len] = 0;
	fclose(f);
	return b;
}

static uint32_t
u32(const unsigned char *p)
{
	return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static float
f32(const unsigned char *p)
{
	uint32_t u = u32(p);
	float f;
	memcpy(&f, &u, sizeof f);
	return f;
}

static struct mesh_export
as_export(const struct icosphere *s, const char *name)
{
	struct mesh_export m = { .name = name, .nvert = s->nvert, .ntri = s->ntri, .vert = s->vert,
				 .normal = s->normal, .tri = s->tri, .rgba = { 0.2f, 0.5f, 0.9f, 0.3f } };
	return m;
}

static void
test_stl(void **unused)
{
	(void)unused;
	struct icosphere s;
	const double c[3] = { 0.1, 1.2, -0.3 };
	icosphere_make(&s, 3, 0.7, c);
	struct mesh_export m = as_export(&s, "ball");
	char path[256], err[256];
	snprintf(path, sizeof path, "%s/ball.stl", dir);
	assert_int_equal(mesh_export_write(&m, 1, path, err, sizeof err), 0);
	size_t len;
	unsigned char *b = slurp(path, &len);
	assert_int_equal(len, 84 + 50 * (size_t)s.ntri);
	assert_int_equal(u32(b + 80), (uint32_t)s.ntri);
	float *v = malloc(sizeof *v * 9 * (size_t)s.ntri);
	int *tri = malloc(sizeof *tri * 3 * (size_t)s.ntri);
	for (int t = 0; t < s.ntri; t++) {
		const unsigned char *r = b + 84 + 50 * (size_t)t;
		double n[3], dot = 0;
		for (int k = 0; k < 3; k++) {
			n[k] = f32(r + 4 * k);
			for (int j = 0; j < 3; j++) {
				v[9 * t + 3 * j + k] = f32(r + 12 + 12 * j + 4 * k);
				assert_true(v[9 * t + 3 * j + k] == s.vert[3 * s.tri[3 * t + j] + k]);
			}
			/* the facet normal points away from the centre: outward */
			dot += n[k] * (v[9 * t + k] - c[k]);
		}
		assert_true(fabs(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1) < 1e-5);
		assert_true(dot > 0);
		for (int j = 0; j < 3; j++)
			tri[3 * t + j] = 3 * t + j;
	}
	double vol = icosphere_volume(v, tri, s.ntri), sphere = 4.0 / 3 * M_PI * 0.7 * 0.7 * 0.7;
	assert_true(vol > 0.98 * sphere && vol < sphere);
	free(v);
	free(tri);
	free(b);
	unlink(path);
	icosphere_free(&s);
}

/* the glTF document's checks shared by .glb and .gltf: one mesh, the buffer's bytes equal */
static void
check_gltf(json_t *doc, const unsigned char *bin, size_t binlen, const struct icosphere *s)
{
	assert_string_equal(json_string_value(json_object_get(json_object_get(doc, "asset"), "version")),
			    "2.0");
	json_t *acc = json_object_get(doc, "accessors"), *views = json_object_get(doc, "bufferViews");
	assert_int_equal(json_array_size(acc), 3);
	json_t *pos = json_array_get(acc, 0), *idx = json_array_get(acc, 2);
	assert_int_equal(json_integer_value(json_object_get(pos, "count")), s->nvert);
	assert_int_equal(json_integer_value(json_object_get(idx, "count")), 3 * s->ntri);
	assert_int_equal(json_array_size(json_object_get(pos, "min")), 3);
	json_t *pv = json_array_get(views, 0), *iv = json_array_get(views, 2);
	size_t po = (size_t)json_integer_value(json_object_get(pv, "byteOffset"));
	size_t io = (size_t)json_integer_value(json_object_get(iv, "byteOffset"));
	assert_true(io + 12 * (size_t)s->ntri <= binlen);
	for (int i = 0; i < 3 * s->nvert; i++)
		assert_true(f32(bin + po + 4 * (size_t)i) == s->vert[i]);
	for (int i = 0; i < 3 * s->ntri; i++)
		assert_int_equal(u32(bin + io + 4 * (size_t)i), (uint32_t)s->tri[i]);
	json_t *mat = json_array_get(json_object_get(doc, "materials"), 0);
	assert_string_equal(json_string_value(json_object_get(mat, "alphaMode")), "BLEND");
}

static void
test_glb(void **unused)
{
	(void)unused;
	struct icosphere s;
	const double c[3] = { 0, 1, 0 };
	icosphere_make(&s, 2, 0.5, c);
	struct mesh_export m = as_export(&s, "ball");
	char path[256], err[256];
	snprintf(path, sizeof path, "%s/ball.glb", dir);
	assert_int_equal(mesh_export_write(&m, 1, path, err, sizeof err), 0);
	size_t len;
	unsigned char *b = slurp(path, &len);
	assert_int_equal(u32(b), 0x46546c67u);
	assert_int_equal(u32(b + 4), 2);
	assert_int_equal(u32(b + 8), len);
	uint32_t jlen = u32(b + 12);
	assert_int_equal(u32(b + 16), 0x4e4f534au);
	assert_int_equal(jlen % 4, 0);
	json_t *doc = json_loadb((const char *)b + 20, jlen, 0, NULL);
	assert_non_null(doc);
	const unsigned char *bin = b + 20 + jlen;
	assert_int_equal(u32(bin + 4), 0x004e4942u);
	check_gltf(doc, bin + 8, u32(bin), &s);
	json_decref(doc);
	free(b);
	unlink(path);
	icosphere_free(&s);
}

static int
unb64(int ch)
{
	const char *a = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
	const char *p = strchr(a, ch);
	return p && ch ? (int)(p - a) : -1;
}

static void
test_gltf_text(void **unused)
{
	(void)unused;
	struct icosphere s;
	const double c[3] = { 0, 1, 0 };
	icosphere_make(&s, 1, 0.5, c);
	struct mesh_export m = as_export(&s, "ball");
	char path[256], err[256];
	snprintf(path, sizeof path, "%s/ball.gltf", dir);
	assert_int_equal(mesh_export_write(&m, 1, path, err, sizeof err), 0);
	size_t len;
	unsigned char *b = slurp(path, &len);
	json_t *doc = json_loadb((const char *)b, len, 0, NULL);
	assert_non_null(doc);
	json_t *buf = json_array_get(json_object_get(doc, "buffers"), 0);
	const char *uri = json_string_value(json_object_get(buf, "uri"));
	const char *head = "data:application/octet-stream;base64,";
	assert_non_null(uri);
	assert_memory_equal(uri, head, strlen(head));
	const char *p = uri + strlen(head);
	size_t n = strlen(p), out = 0;
	unsigned char *bin = malloc(n);
	for (size_t i = 0; i + 3 < n + 1 && i < n; i += 4) {
		int q[4];
		for (int k = 0; k < 4; k++)
			q[k] = p[i + k] == '=' ? 0 : unb64(p[i + k]);
		uint32_t v = (uint32_t)q[0] << 18 | (uint32_t)q[1] << 12 | (uint32_t)q[2] << 6 | (uint32_t)q[3];
		bin[out++] = (unsigned char)(v >> 16);
		if (p[i + 2] != '=')
			bin[out++] = (unsigned char)(v >> 8);
		if (p[i + 3] != '=')
			bin[out++] = (unsigned char)v;
	}
	assert_int_equal(out, (size_t)json_integer_value(json_object_get(buf, "byteLength")));
	check_gltf(doc, bin, out, &s);
	free(bin);
	json_decref(doc);
	free(b);
	unlink(path);
	icosphere_free(&s);
}

/*
 * A triangle soup (each facet its own three vertices) with a zero-area facet
 * (two corners at one position): written welded, its facets without the
 * degenerate one, the sphere it was.
 */
static void
test_welded(void **unused)
{
	(void)unused;
	struct icosphere s;
	const double c[3] = { 0, 1, 0 };
	icosphere_make(&s, 2, 0.5, c);
	int nt = s.ntri + 1, nv = 3 * nt;
	float *v = malloc(sizeof *v * 3 * (size_t)nv), *n = malloc(sizeof *n * 3 * (size_t)nv);
	int *tri = malloc(sizeof *tri * 3 * (size_t)nt);
	for (int t = 0; t < s.ntri; t++)
		for (int j = 0; j < 3; j++) {
			memcpy(v + 3 * (3 * t + j), s.vert + 3 * s.tri[3 * t + j], 3 * sizeof *v);
			memcpy(n + 3 * (3 * t + j), s.normal + 3 * s.tri[3 * t + j], 3 * sizeof *n);
			tri[3 * t + j] = 3 * t + j;
		}
	/* the extra facet: corners 0 and 1 of facet 0 with corner 0 again, at its own vertices */
	for (int j = 0; j < 3; j++) {
		memcpy(v + 3 * (3 * s.ntri + j), s.vert + 3 * s.tri[j == 1 ? 1 : 0], 3 * sizeof *v);
		memcpy(n + 3 * (3 * s.ntri + j), s.normal + 3 * s.tri[0], 3 * sizeof *n);
		tri[3 * s.ntri + j] = 3 * s.ntri + j;
	}
	struct mesh_export m = { .name = "soup", .nvert = nv, .ntri = nt, .vert = v, .normal = n,
				 .tri = tri, .rgba = { 1, 1, 1, 1 } };
	char path[256], err[256];
	snprintf(path, sizeof path, "%s/soup.glb", dir);
	assert_int_equal(mesh_export_write(&m, 1, path, err, sizeof err), 0);
	size_t len;
	unsigned char *b = slurp(path, &len);
	json_t *doc = json_loadb((const char *)b + 20, u32(b + 12), 0, NULL);
	json_t *acc = json_object_get(doc, "accessors");
	assert_int_equal(json_integer_value(json_object_get(json_array_get(acc, 0), "count")), s.nvert);
	assert_int_equal(json_integer_value(json_object_get(json_array_get(acc, 2), "count")),
			 3 * s.ntri);
	json_decref(doc);
	free(b);
	unlink(path);
	snprintf(path, sizeof path, "%s/soup.stl", dir);
	assert_int_equal(mesh_export_write(&m, 1, path, err, sizeof err), 0);
	b = slurp(path, &len);
	assert_int_equal(u32(b + 80), (uint32_t)s.ntri);
	free(b);
	unlink(path);
	free(v);
	free(n);
	free(tri);
	icosphere_free(&s);
}

static void
test_refused(void **unused)
{
	(void)unused;
	struct icosphere s;
	const double c[3] = { 0, 0, 0 };
	icosphere_make(&s, 0, 1, c);
	struct mesh_export m = as_export(&s, "ball");
	char path[256], err[256];
	snprintf(path, sizeof path, "%s/ball.obj", dir);
	assert_int_equal(mesh_export_write(&m, 1, path, err, sizeof err), -1);
	assert_non_null(strstr(err, ".stl"));
	snprintf(path, sizeof path, "%s/bad.stl", dir);
	s.tri[5] = s.nvert; /* a vertex past the end */
	assert_int_equal(mesh_export_write(&m, 1, path, err, sizeof err), -1);
	assert_int_equal(access(path, F_OK), -1); /* nothing written */
	m.ntri = 0;
	assert_int_equal(mesh_export_write(&m, 1, path, err, sizeof err), -1);
	assert_int_equal(access(path, F_OK), -1);
	icosphere_free(&s);
}

int
main(void)
{
	if (!mkdtemp(dir))
		return 1;
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_stl),
		cmocka_unit_test(test_glb),
		cmocka_unit_test(test_gltf_text),
		cmocka_unit_test(test_welded),
		cmocka_unit_test(test_refused),
	};
	int rc = cmocka_run_group_tests(tests, NULL, NULL);
	rmdir(dir);
	return rc;
}
