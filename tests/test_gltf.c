/*
 * test_gltf.c - the glTF export of what the tool never gives it: several
 * figures in one file, one animated and one not, and frames where a figure
 * is absent; and every refusal leaving nothing on disk. (The tests in
 * tests/system/test_export_gltf.py take single figures through the Khronos
 * validator and trimesh.)
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "export/gltf.h"
#include "figure/figure.h"
#include "figure/kin.h"
#include "test_human.h"

struct glb {
	json_t *doc;
	unsigned char *bin;
	size_t binlen;
	unsigned char *file;
};

static uint32_t
u32(const unsigned char *p)
{
	return p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* reads a .glb, checking its container: header, JSON chunk, BIN chunk, 4-byte padding */
static void
glb_read(const char *path, struct glb *g)
{
	FILE *f = fopen(path, "rb");
	assert_non_null(f);
	fseek(f, 0, SEEK_END);
	long n = ftell(f);
	rewind(f);
	g->file = malloc((size_t)n);
	assert_non_null(g->file);
	assert_int_equal(fread(g->file, 1, (size_t)n, f), (size_t)n);
	fclose(f);
	assert_int_equal(u32(g->file), 0x46546C67);
	assert_int_equal(u32(g->file + 4), 2);
	assert_int_equal(u32(g->file + 8), (uint32_t)n);
	uint32_t jlen = u32(g->file + 12);
	assert_int_equal(u32(g->file + 16), 0x4E4F534A);
	assert_int_equal(jlen % 4, 0);
	json_error_t err;
	g->doc = json_loadb((const char *)g->file + 20, jlen, 0, &err);
	assert_non_null(g->doc);
	unsigned char *bin = g->file + 20 + jlen;
	assert_int_equal(u32(bin + 4), 0x004E4942);
	g->binlen = u32(bin);
	g->bin = bin + 8;
	assert_int_equal(g->binlen % 4, 0);
	assert_int_equal(20 + jlen + 8 + g->binlen, (size_t)n);
}

static void
glb_free(struct glb *g)
{
	json_decref(g->doc);
	free(g->file);
}

static json_t *
at(json_t *doc, const char *array, size_t i)
{
	json_t *v = json_array_get(json_object_get(doc, array), i);
	assert_non_null(v);
	return v;
}

/* an accessor's floats (copied out: the BIN chunk promises only 4-byte alignment) */
static float *
floats(const struct glb *g, int accessor, int *count, int ncomp)
{
	json_t *acc = at(g->doc, "accessors", (size_t)accessor);
	json_t *view = at(g->doc, "bufferViews",
			  (size_t)json_integer_value(json_object_get(acc, "bufferView")));
	*count = (int)json_integer_value(json_object_get(acc, "count"));
	size_t off = (size_t)json_integer_value(json_object_get(view, "byteOffset"));
	size_t len = sizeof(float) * (size_t)*count * (size_t)ncomp;
	assert_true(off + len <= g->binlen);
	float *v = malloc(len);
	assert_non_null(v);
	memcpy(v, g->bin + off, len);
	return v;
}

static int
dir_is_empty(const char *dir)
{
	DIR *d = opendir(dir);
	assert_non_null(d);
	int n = 0;
	for (struct dirent *e; (e = readdir(d));)
		n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
	closedir(d);
	return n == 0;
}

/* a posture of m: its root site moved dx along x, with a joint turned, frames computed */
static struct state *
posture(const struct model *m, double dx)
{
	struct state *s = state_make(m);
	assert_non_null(s);
	kin_update(m, s);
	struct xform root = s->root_xf;
	root.p[0] += dx;
	assert_int_equal(state_root_at(m, s, s->root_site, &root), 0);
	for (int d = 0; d < m->ndof; d++)
		s->q[d] = m->dof_lo[d] + 0.3 * (m->dof_hi[d] - m->dof_lo[d]);
	kin_update(m, s);
	return s;
}

/*
 * The human animated over five frames, absent from three, beside a table
 * that has none: both figures in the scene, one shared time accessor, the
 * table without channels, and each absent frame holding the nearest one
 * (ties to the earlier).
 */
static void
test_two_figures_and_gaps(void **unused)
{
	(void)unused;
	char err[512], dir[] = "/tmp/posture_gltfXXXXXX", path[600];
	assert_non_null(mkdtemp(dir));
	snprintf(path, sizeof path, "%s/env.glb", dir);
	struct model *human = test_human();
	struct model *table = figure_read_file("src/figure/library/table.fig", err, sizeof err);
	assert_non_null(table);
	struct state *now = posture(human, 0), *one = posture(human, 1), *two = posture(human, 2);
	struct state *table_now = posture(table, 0.5);
	const struct state *frames[5] = { NULL, one, NULL, two, NULL };
	/* the frame each key holds: 0 -> 1, 2 -> 1 (1 and 3 are as near: the earlier), 4 -> 3 */
	const double want_dx[5] = { 1, 1, 1, 2, 2 };
	struct motion figs[2] = {
		{ .name = "jack", .m = human, .now = now, .frames = frames, .nframes = 5 },
		{ .name = "table", .m = table, .now = table_now },
	};
	assert_int_equal(gltf_export(figs, 2, 0.25, path, err, sizeof err), 0);

	struct glb g;
	glb_read(path, &g);
	json_t *scene = json_object_get(at(g.doc, "scenes", 0), "nodes");
	assert_int_equal(json_array_size(scene), 2);
	size_t jack = (size_t)json_integer_value(json_array_get(scene, 0));
	size_t tab = (size_t)json_integer_value(json_array_get(scene, 1));
	assert_string_equal(json_string_value(json_object_get(at(g.doc, "nodes", jack), "name")), "jack");
	assert_string_equal(json_string_value(json_object_get(at(g.doc, "nodes", tab), "name")), "table");
	assert_int_equal(json_array_size(json_object_get(g.doc, "nodes")),
			 2 + human->nseg + human->njnt + table->nseg + table->njnt);
	/* the table's top node at its root site now */
	json_t *t = json_object_get(at(g.doc, "nodes", tab), "translation");
	for (int i = 0; i < 3; i++)
		assert_float_equal(json_real_value(json_array_get(t, (size_t)i)),
				   table_now->site_xf[table_now->root_site].p[i], 1e-12);

	json_t *anim = at(g.doc, "animations", 0);
	assert_int_equal(json_array_size(json_object_get(g.doc, "animations")), 1);
	json_t *samplers = json_object_get(anim, "samplers");
	json_t *channels = json_object_get(anim, "channels");
	int input = (int)json_integer_value(json_object_get(json_array_get(samplers, 0), "input"));
	for (size_t i = 0; i < json_array_size(samplers); i++)
		assert_int_equal(json_integer_value(json_object_get(json_array_get(samplers, i), "input")),
				 input);
	int n;
	float *times = floats(&g, input, &n, 1);
	assert_int_equal(n, 5);
	for (int k = 0; k < 5; k++)
		assert_float_equal(times[k], 0.25 * k, 1e-7);
	free(times);
	int found = 0;
	for (size_t i = 0; i < json_array_size(channels); i++) {
		json_t *ch = json_array_get(channels, i), *target = json_object_get(ch, "target");
		size_t node = (size_t)json_integer_value(json_object_get(target, "node"));
		/* the table's nodes follow the human's: none of them animated */
		assert_true(node < tab);
		if (node != jack || strcmp(json_string_value(json_object_get(target, "path")), "translation"))
			continue;
		json_t *s = json_array_get(samplers, (size_t)json_integer_value(json_object_get(ch, "sampler")));
		float *p = floats(&g, (int)json_integer_value(json_object_get(s, "output")), &n, 3);
		assert_int_equal(n, 5);
		for (int k = 0; k < 5; k++)
			assert_float_equal(p[3 * k], now->site_xf[now->root_site].p[0] + want_dx[k], 1e-6);
		free(p);
		found++;
	}
	assert_int_equal(found, 1);
	glb_free(&g);
	unlink(path);
	rmdir(dir);
	state_free(now);
	state_free(one);
	state_free(two);
	state_free(table_now);
	model_free(human);
	model_free(table);
}

static void
expect_refusal(const struct motion *figs, int nfig, double seconds, const char *path,
	       const char *says)
{
	char err[512] = "";
	assert_int_equal(gltf_export(figs, nfig, seconds, path, err, sizeof err), -1);
	if (!strstr(err, says))
		fail_msg("expected '%s' in '%s'", says, err);
}

/* every refusal says why and leaves the directory as it was */
static void
test_refusals_write_nothing(void **unused)
{
	(void)unused;
	char dir[] = "/tmp/posture_gltfXXXXXX", path[600], other[600];
	assert_non_null(mkdtemp(dir));
	snprintf(path, sizeof path, "%s/x.glb", dir);
	struct model *m = test_human();
	struct state *s = posture(m, 0);
	const struct state *frames[1] = { s };
	struct motion fig = { .name = "jack", .m = m, .now = s, .frames = frames, .nframes = 1 };

	snprintf(other, sizeof other, "%s/x.gltf", dir);
	expect_refusal(&fig, 1, 0.5, other, "ending in .glb");
	expect_refusal(&fig, 0, 0.5, path, "no figure");
	expect_refusal(&fig, 1, 0, path, "time between frames");
	expect_refusal(&fig, 1, NAN, path, "time between frames");
	snprintf(other, sizeof other, "%s/missing/x.glb", dir);
	expect_refusal(&fig, 1, 0.5, other, "No such file or directory");
	struct state *bad = posture(m, 0);
	bad->q[0] = NAN;
	kin_update(m, bad);
	frames[0] = bad;
	expect_refusal(&fig, 1, 0.5, path, "not at a finite place");
	assert_true(dir_is_empty(dir));

	/* and the same figure exports once the bad frame is gone */
	fig.nframes = 0;
	char err[512];
	assert_int_equal(gltf_export(&fig, 1, 0.5, path, err, sizeof err), 0);
	unlink(path);
	rmdir(dir);
	state_free(bad);
	state_free(s);
	model_free(m);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_two_figures_and_gaps),
		cmocka_unit_test(test_refusals_write_nothing),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
