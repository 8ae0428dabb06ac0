/* test_figure.c - the peabody figure language: reading, writing, OBJ meshes */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "test_util.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "figure/figure.h"
#include "figure/model.h"
#include "figure/obj.h"

/* the tests run from the top of the repository, as `make unit-test` does */
#define FIG_DIR "tests/figures"
#define ENV_DIR "src/figure/library"

static const double QID[4] = { 0, 0, 0, 1 };

static struct model *
read_ok(const char *path)
{
	char err[1024];
	struct model *m = figure_read_file(path, err, sizeof err);
	if (!m)
		fail_msg("%s", err);
	return m;
}

static struct model *
read_text_ok(const char *text, const char *base_dir)
{
	char err[1024];
	struct model *m =
		figure_read_string(text, strlen(text), "inline", base_dir, err, sizeof err);
	if (!m)
		fail_msg("%s", err);
	return m;
}

/* m written into a new string */
static char *
write_string(const struct model *m, size_t *len)
{
	char *buf = NULL;
	size_t n = 0;
	FILE *f = open_memstream(&buf, &n);
	assert_non_null(f);
	assert_int_equal(figure_write(m, f), 0);
	assert_int_equal(fclose(f), 0);
	*len = n;
	return buf;
}

/* write -> read gives an identical model, and write -> read -> write identical text */
static void
check_round_trip(const struct model *m, const char *base_dir)
{
	char err[1024];
	size_t n1, n2;
	char *t1 = write_string(m, &n1);
	struct model *m2 = figure_read_string(t1, n1, "written", base_dir, err, sizeof err);
	if (!m2)
		fail_msg("%s\n%s", err, t1);
	if (!model_equal(m, m2))
		fail_msg("model '%s' changed in a write -> read round trip:\n%s", m->name, t1);
	char *t2 = write_string(m2, &n2);
	assert_int_equal(n1, n2);
	assert_memory_equal(t1, t2, n1);
	free(t1);
	free(t2);
	model_free(m2);
}

static int
site_of(const struct model *m, const char *name)
{
	int i = model_find_site(m, name);
	if (i < 0)
		fail_msg("no site %s", name);
	return i;
}

static void
assert_vec_near(const double *v, double x, double y, double z, double tol)
{
	assert_near(v[0], x, tol);
	assert_near(v[1], y, tol);
	assert_near(v[2], z, tol);
}

static void
test_figure_a1(void **unused)
{
	(void)unused;
	struct model *m = read_ok(FIG_DIR "/figure_a1.fig");
	char name[2 * MODEL_NAME_MAX];
	assert_string_equal(m->name, "table");
	assert_int_equal(m->nseg, 5);
	assert_int_equal(m->njnt, 4);
	assert_int_equal(m->ndof, 4);
	assert_int_equal(m->nsite, 13);
	assert_string_equal(model_site_fullname(m, m->root_site, name, sizeof name), "top.base");
	assert_vec_near(m->root_pos, 0, 0.75, 0, 1e-15);
	assert_memory_equal(m->root_quat, QID, sizeof QID);
	for (int k = 1; k <= 4; k++) {
		char s[64];
		snprintf(s, sizeof s, "leg%d.top", k);
		int top = site_of(m, s);
		assert_vec_near(&m->site_pos[3 * top], 0.075, 0.75, 0.075, 1e-15);
		assert_memory_equal(&m->site_quat[4 * top], QID, sizeof QID);
		snprintf(s, sizeof s, "leg%d.base", k);
		assert_vec_near(&m->site_pos[3 * site_of(m, s)], 0, 0, 0, 0);
		snprintf(s, sizeof s, "top.leg%d", k);
		int on_top = site_of(m, s);
		assert_vec_near(&m->site_pos[3 * on_top], k <= 2 ? -0.25 : 0.25, 0,
				k % 2 ? -0.25 : 0.25, 1e-15);
		/* connect top.legK to legK.top, type = R(z) with the default limits */
		snprintf(s, sizeof s, "leg%djoint", k);
		int j = model_find_joint(m, s);
		assert_true(j >= 0);
		assert_int_equal(m->jnt_site_from[j], on_top);
		assert_int_equal(m->jnt_site_to[j], top);
		assert_int_equal(m->jnt_ndof[j], 1);
		int d = m->jnt_dof0[j];
		assert_int_equal(m->dof_kind[d], DOF_ROTATION);
		assert_int_equal(m->dof_axis[d], 2);
		assert_int_equal(m->dof_sign[d], 1);
		assert_true(m->dof_lo[d] == -M_PI && m->dof_hi[d] == M_PI && m->dof_init[d] == 0);
	}
	/* psurf: one mesh per path, shared by the four legs */
	assert_int_equal(m->nmesh, 2);
	assert_string_equal(m->mesh_path[0], "leg.obj");
	assert_string_equal(m->mesh_path[1], "top.obj");
	assert_int_equal(m->mesh_nface[0], 12);
	assert_int_equal(m->ngeom, 5);
	for (int g = 0; g < 4; g++) {
		assert_int_equal(m->geom_kind[g], GEOM_MESH);
		assert_int_equal(m->geom_mesh[g], 0);
	}
	assert_int_equal(m->geom_mesh[4], 1);
	model_free(m);
}

static void
test_units_and_transforms(void **unused)
{
	(void)unused;
	const char *text =
		"# a comment\n"
		"figure u {   // another\n"
		"  /* a block\n     comment */\n"
		"  segment a {\n"
		"    mass = 500g;\n"
		"    site inch->location = trans(1in, 2.54cm, 25.4mm);\n"
		"    site rx->location = rot(x, 90deg);\n"
		"    site chain->location = trans(1m, 0, 0) rot(z, 90deg) trans(1m, 0, 0);\n"
		"    site axis->location = rot(0, 2, 0, 90deg);\n"
		"    site yaxis->location = rot(y, 1.5707963267948966);\n"
		"    site exact->location = trans(0.1m, -0m, 3e-300m) quat(0.5, -0.5, 0.5, -0.5);\n"
		"  }\n"
		"  segment b { mass = 2kg; site s->location = trans(0, 0, 0); }\n"
		"  joint j {\n"
		"    connect a.rx to b.s; type = R(x), T(-y);\n"
		"    limits = (-90deg, 90deg), (-1in, 1in); displacement = (45deg, 0.5in);\n"
		"  }\n"
		"  root = a.inch;\n"
		"}\n";
	struct model *m = read_text_ok(text, NULL);
	const double *p = &m->site_pos[3 * site_of(m, "a.inch")];
	assert_true(p[0] == 0.0254); /* 1in is 0.0254 m exactly */
	assert_near(p[1], 0.0254, 1e-17);
	assert_near(p[2], 0.0254, 1e-17);
	assert_true(m->seg_mass[0] == 0.5); /* 500g */
	assert_true(m->total_mass == 2.5);
	assert_true(m->dof_hi[0] == M_PI / 2 && m->dof_lo[0] == -M_PI / 2); /* 90deg */
	assert_true(m->dof_init[0] == M_PI / 4);
	assert_true(m->dof_hi[1] == 0.0254 && m->dof_init[1] == 0.0127);
	assert_int_equal(m->dof_sign[1], -1);
	assert_int_equal(m->dof_kind[1], DOF_TRANSLATION);
	assert_int_equal(m->dof_axis[1], 1);

	/* rot(x, 90deg) maps y to z */
	double r[9], y[3] = { 0, 1, 0 }, out[3];
	mathx_quat_to_mat(&m->site_quat[4 * site_of(m, "a.rx")], r);
	for (int i = 0; i < 3; i++)
		out[i] = r[3 * i] * y[0] + r[3 * i + 1] * y[1] + r[3 * i + 2] * y[2];
	assert_vec_near(out, 0, 0, 1, 1e-15);

	/* factors apply in the frame of the ones before: the second trans runs along y */
	assert_vec_near(&m->site_pos[3 * site_of(m, "a.chain")], 1, 1, 0, 1e-15);

	/* an axis is normalised: rot(0, 2, 0, a) is rot(y, a) bit for bit */
	assert_memory_equal(&m->site_quat[4 * site_of(m, "a.axis")],
			    &m->site_quat[4 * site_of(m, "a.yaxis")], 4 * sizeof(double));

	/* trans(p) quat(q) is kept exactly, down to -0 and subnormal values */
	int e = site_of(m, "a.exact");
	double q[4] = { 0.5, -0.5, 0.5, -0.5 }, pos[3] = { 0.1, -0.0, 3e-300 };
	assert_memory_equal(&m->site_pos[3 * e], pos, sizeof pos);
	assert_memory_equal(&m->site_quat[4 * e], q, sizeof q);
	model_free(m);

	/* default limits: (-180deg, 180deg) for R, (-1m, 1m) for T; no type: a rigid joint */
	const char *defaults = "figure d {\n"
			       "  segment a { site s->location = trans(0, 0, 0); }\n"
			       "  segment b { site s->location = trans(0, 0, 0); }\n"
			       "  segment c { site s->location = trans(0, 0, 0); }\n"
			       "  joint j { connect a.s to b.s; type = T(z), R(y); }\n"
			       "  joint weld { connect b.s to c.s; }\n"
			       "  root = a.s;\n"
			       "}\n";
	m = read_text_ok(defaults, NULL);
	assert_int_equal(m->ndof, 2);
	assert_true(m->dof_lo[0] == -1 && m->dof_hi[0] == 1 && m->dof_init[0] == 0);
	assert_true(m->dof_lo[1] == -M_PI && m->dof_hi[1] == M_PI && m->dof_init[1] == 0);
	assert_int_equal(m->jnt_ndof[model_find_joint(m, "weld")], 0);
	check_round_trip(m, NULL);
	model_free(m);
}

static void
test_crlf_and_exact_message(void **unused)
{
	(void)unused;
	const char *crlf =
		"figure c {\r\n  segment a {\r\n    site s->location = trans(1m, 0, 0);\r\n"
		"  }\r\n  root = a.s;\r\n}\r\n";
	struct model *m = read_text_ok(crlf, NULL);
	assert_int_equal(m->nseg, 1);
	model_free(m);

	const char *bad = "figure f {\n"
			  "\tsegment a {\n"
			  "\t\tsite s->location = trans(0m, 0m, 0m)\n"
			  "\t}\n"
			  "}\n";
	char err[256];
	m = figure_read_string(bad, strlen(bad), "bad.fig", NULL, err, sizeof err);
	assert_null(m);
	assert_string_equal(err, "bad.fig:4:2: expected ';' after the site location, found '}'");
}

static void
test_round_trip_files(void **unused)
{
	(void)unused;
	static const char *const files[][2] = {
		{ ENV_DIR "/table.fig", ENV_DIR },	  { ENV_DIR "/chair.fig", ENV_DIR },
		{ ENV_DIR "/vehicle_seat.fig", ENV_DIR }, { FIG_DIR "/figure_a1.fig", FIG_DIR },
		{ FIG_DIR "/meshfig.fig", FIG_DIR },
	};
	for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
		struct model *m = read_ok(files[i][0]);
		check_round_trip(m, files[i][1]);
		model_free(m);
	}
}

/*
 * Meshes at the segment's origin, unscaled: the first is written as its
 * psurf, the others as geometry (psurf may appear once a segment; found
 * by the figure fuzzer, whose seed had a psurf and a mesh() at identity)
 */
static void
test_round_trip_two_meshes_at_identity(void **unused)
{
	(void)unused;
	static const char *const texts[] = {
		"figure two { segment base { psurf = \"quad.obj\"; geometry = mesh(\"leg.obj\"); "
		"site o->location = trans(0, 0, 0); } root = base.o; }",
		"figure same { segment base { geometry = mesh(\"quad.obj\"); geometry = box(1, 1, 1); "
		"geometry = mesh(\"quad.obj\", 1, 1, 1) at trans(0, 0, 0); "
		"site o->location = trans(0, 0, 0); } root = base.o; }",
	};
	for (size_t i = 0; i < sizeof texts / sizeof texts[0]; i++) {
		struct model *m = read_text_ok(texts[i], FIG_DIR);
		check_round_trip(m, FIG_DIR);
		model_free(m);
	}
}

static void
test_environment_figures(void **unused)
{
	(void)unused;
	struct model *m = read_ok(ENV_DIR "/table.fig");
	assert_near(m->site_pos[3 * site_of(m, "table.surface") + 1], 0.74, 1e-12);
	assert_near(m->root_pos[2], 0.60, 1e-12);
	model_free(m);

	m = read_ok(ENV_DIR "/chair.fig");
	assert_near(m->site_pos[3 * site_of(m, "chair.seat") + 1], 0.45, 1e-12);
	model_free(m);

	m = read_ok(ENV_DIR "/vehicle_seat.fig");
	assert_int_equal(m->nseg, 7);
	static const char *const joints[] = {
		"seat_track", "recline", "steering", "accelerator_pedal", "brake_pedal", "clutch_pedal",
	};
	for (size_t i = 0; i < sizeof joints / sizeof joints[0]; i++) {
		int j = model_find_joint(m, joints[i]);
		assert_true(j >= 0);
		assert_int_equal(m->jnt_ndof[j], 1);
	}
	/* H-point 27 cm over the heel plane; wheel centre 60-70 cm from it */
	const double *h = &m->site_pos[3 * site_of(m, "body.seat_track")];
	const double *w = &m->site_pos[3 * site_of(m, "body.wheel_mount")];
	assert_near(h[1], 0.27, 1e-12);
	double d = sqrt((w[0] - h[0]) * (w[0] - h[0]) + (w[1] - h[1]) * (w[1] - h[1]) +
			(w[2] - h[2]) * (w[2] - h[2]));
	assert_true(d > 0.60 && d < 0.70);
	int recline = m->jnt_dof0[model_find_joint(m, "recline")];
	assert_near(m->dof_init[recline], 23 * M_PI / 180, 1e-15);
	model_free(m);
}

/* xorshift64*: a small deterministic generator for random figures */
static double
rnd(uint64_t *s)
{
	*s ^= *s >> 12;
	*s ^= *s << 25;
	*s ^= *s >> 27;
	return (double)((*s * 2685821657736338717ULL) >> 11) / 9007199254740992.0;
}

static void
rnd_quat(uint64_t *s, double q[4])
{
	double n = 0;
	while (n < 1e-3) {
		n = 0;
		for (int i = 0; i < 4; i++) {
			q[i] = 2 * rnd(s) - 1;
			n += q[i] * q[i];
		}
	}
	n = sqrt(n);
	for (int i = 0; i < 4; i++)
		q[i] /= n;
}

/* a random tree figure made with the builder; with_mesh adds mesh geometry */
static struct model *
random_model(uint64_t seed, int with_mesh)
{
	uint64_t s = seed * 0x9E3779B97F4A7C15ULL + 1;
	struct model_builder *b = model_builder_create("random_figure");
	assert_non_null(b);
	int mesh = -1;
	if (with_mesh) {
		struct obj_mesh om;
		char err[256];
		if (obj_read_file(FIG_DIR "/quad.obj", &om, err, sizeof err) < 0)
			fail_msg("%s", err);
		mesh = model_builder_mesh(b, "quad.obj", om.vert, om.nvert, om.face, om.nface);
		obj_mesh_free(&om);
		assert_int_equal(mesh, 0);
	}
	int nseg = 2 + (int)(rnd(&s) * 10), site0[16], nsite[16];
	for (int i = 0; i < nseg; i++) {
		char name[32];
		struct segment_def sd = segment_default_def();
		snprintf(name, sizeof name, "seg%d", i);
		sd.name = name;
		sd.mass = rnd(&s) * 10;
		for (int k = 0; k < 3; k++) {
			sd.com[k] = rnd(&s) - 0.5;
			sd.inertia[k] = rnd(&s);
			sd.inertia[3 + k] = (rnd(&s) - 0.5) * 0.1;
		}
		for (int k = 0; k < 4; k++)
			sd.rgba[k] = (float)rnd(&s);
		int seg = model_builder_segment(b, &sd);
		assert_int_equal(seg, i);
		nsite[i] = 1 + (int)(rnd(&s) * 3);
		for (int k = 0; k < nsite[i]; k++) {
			double pos[3] = { rnd(&s) * 2 - 1, rnd(&s) * 2 - 1, rnd(&s) * 2 - 1 }, q[4];
			rnd_quat(&s, q);
			snprintf(name, sizeof name, "site%d", k);
			int st = model_builder_site(b, seg, name, pos, k == 0 ? QID : q);
			assert_true(st >= 0);
			if (k == 0)
				site0[i] = st;
		}
		int ngeom = (int)(rnd(&s) * 4) + (with_mesh && i == 0);
		for (int k = 0; k < ngeom; k++) {
			struct geom_def g = geom_default_def();
			g.kind = (enum geom_kind)(int)(rnd(&s) * (with_mesh ? 5 : 4));
			if (with_mesh && i == 0 && k == 0)
				g.kind = GEOM_MESH; /* a mesh nothing uses is not written */
			for (int c = 0; c < 3; c++) {
				g.size[c] = 0.01 + rnd(&s);
				g.pos[c] = rnd(&s) - 0.5;
			}
			if (g.kind == GEOM_CYLINDER || g.kind == GEOM_CAPSULE)
				g.size[2] = 0; /* unused, and not written */
			if (g.kind == GEOM_MESH)
				g.mesh = mesh;
			if (rnd(&s) < 0.7)
				rnd_quat(&s, g.quat);
			assert_true(model_builder_geom(b, seg, &g) >= 0);
		}
	}
	for (int i = 1; i < nseg; i++) {
		char name[32];
		struct joint_def jd = joint_default_def();
		int parent = (int)(rnd(&s) * i);
		int a = site0[parent] + (int)(rnd(&s) * nsite[parent]);
		int c = site0[i] + (int)(rnd(&s) * nsite[i]);
		snprintf(name, sizeof name, "joint%d", i);
		jd.name = name;
		jd.site_from = rnd(&s) < 0.5 ? a : c; /* either direction */
		jd.site_to = jd.site_from == a ? c : a;
		jd.ndof = (int)(rnd(&s) * (MODEL_JOINT_DOF_MAX + 1));
		for (int k = 0; k < jd.ndof; k++) {
			struct dof_def *f = &jd.dof[k];
			f->kind = rnd(&s) < 0.7 ? DOF_ROTATION : DOF_TRANSLATION;
			f->axis = (int)(rnd(&s) * 3);
			f->sign = rnd(&s) < 0.5 ? -1 : 1;
			f->lo = -rnd(&s) * 3;
			f->hi = rnd(&s) * 3;
			f->init = f->lo + rnd(&s) * (f->hi - f->lo);
		}
		assert_true(model_builder_joint(b, &jd) >= 0);
	}
	double rp[3] = { rnd(&s), rnd(&s), rnd(&s) }, rq[4];
	rnd_quat(&s, rq);
	assert_int_equal(model_builder_root(b, (int)(rnd(&s) * site0[nseg - 1]), rp, rq), 0);
	struct model *m = model_builder_finish(b);
	if (!m)
		fail_msg("%s", model_builder_error(b));
	model_builder_free(b);
	return m;
}

static void
test_round_trip_random(void **unused)
{
	(void)unused;
	for (uint64_t seed = 1; seed <= 40; seed++) {
		struct model *m = random_model(seed, (int)(seed % 2));
		check_round_trip(m, FIG_DIR);
		model_free(m);
	}
}

/* the expectation recorded on the first line: "# expect LINE[:COL] TEXT" */
static int
read_expectation(const char *path, int *line, int *col, char *frag, size_t fraglen)
{
	char first[512];
	FILE *f = fopen(path, "r");
	if (!f)
		return -1;
	char *ok = fgets(first, sizeof first, f);
	fclose(f);
	int n = 0;
	*col = 0;
	if (!ok ||
	    (sscanf(first, "# expect %d:%d %n", line, col, &n) < 2 &&
	     sscanf(first, "# expect %d %n", line, &n) < 1) ||
	    n == 0)
		return -1;
	snprintf(frag, fraglen, "%s", first + n);
	frag[strcspn(frag, "\n")] = 0;
	return 0;
}

static int
cmp_names(const void *a, const void *b)
{
	return strcmp(*(char *const *)a, *(char *const *)b);
}

static void
test_bad_files(void **unused)
{
	(void)unused;
	DIR *d = opendir(FIG_DIR "/bad");
	assert_non_null(d);
	char *names[256];
	int n = 0, failures = 0;
	for (struct dirent *e; (e = readdir(d)) && n < 256;) {
		size_t len = strlen(e->d_name);
		if (len > 4 && !strcmp(e->d_name + len - 4, ".fig"))
			names[n++] = strdup(e->d_name);
	}
	closedir(d);
	qsort(names, (size_t)n, sizeof names[0], cmp_names);
	for (int i = 0; i < n; i++) {
		char path[512], prefix[600], frag[512], err[2048];
		int line, col;
		snprintf(path, sizeof path, FIG_DIR "/bad/%s", names[i]);
		if (read_expectation(path, &line, &col, frag, sizeof frag) < 0) {
			print_error("%s: no '# expect LINE:COL TEXT' first line\n", path);
			failures++;
			continue;
		}
		struct model *m = figure_read_file(path, err, sizeof err);
		if (col)
			snprintf(prefix, sizeof prefix, "%s:%d:%d: ", path, line, col);
		else
			snprintf(prefix, sizeof prefix, "%s:%d:", path, line);
		if (m) {
			print_error("%s: accepted\n", path);
			model_free(m);
			failures++;
		} else if (strncmp(err, prefix, strlen(prefix)) || !strstr(err, frag)) {
			print_error("%s:\n  expected '%s...%s'\n  got      '%s'\n", path, prefix,
				    frag, err);
			failures++;
		}
		free(names[i]);
	}
	assert_int_equal(failures, 0);
	assert_true(n >= 25);
}

/* writes len bytes to dir/name and returns the path in dest */
static void
put_file(const char *dir, const char *name, const char *bytes, size_t len, char *dest,
	 size_t destlen)
{
	snprintf(dest, destlen, "%s/%s", dir, name);
	FILE *f = fopen(dest, "wb");
	assert_non_null(f);
	assert_int_equal(fwrite(bytes, 1, len, f), len);
	assert_int_equal(fclose(f), 0);
}

static void
expect_file_error(const char *path, const char *where, const char *frag)
{
	char err[1024], prefix[600];
	struct model *m = figure_read_file(path, err, sizeof err);
	if (m)
		fail_msg("%s: accepted", path);
	snprintf(prefix, sizeof prefix, "%s:%s: ", path, where);
	if (strncmp(err, prefix, strlen(prefix)) || !strstr(err, frag))
		fail_msg("%s: expected '%s...%s', got '%s'", path, prefix, frag, err);
}

static void
test_bad_generated(void **unused)
{
	(void)unused;
	char dir[] = "/tmp/posture_figXXXXXX", path[600];
	assert_non_null(mkdtemp(dir));

	put_file(dir, "empty.fig", "", 0, path, sizeof path);
	expect_file_error(path, "1:1", "expected 'figure' to start the file, found end of file");
	unlink(path);

	static const char nul[] = "figure f {\n\tsegment a {\0}\n}\n";
	put_file(dir, "nul.fig", nul, sizeof nul - 1, path, sizeof path);
	expect_file_error(path, "2:13", "binary data (byte 0x00)");
	unlink(path);

	static const char ctrl[] = "# hi \x01\nfigure f {}\n";
	put_file(dir, "ctrl.fig", ctrl, sizeof ctrl - 1, path, sizeof path);
	expect_file_error(path, "1:6", "binary data (byte 0x01)");
	unlink(path);

	/* a 4096-byte line is fine, a 4097-byte one is not */
	const char *head = "figure f { segment a { site s->location = trans(0, 0, 0); }\n";
	const char *tail = "\nroot = a.s; }\n";
	size_t hl = strlen(head), tl = strlen(tail);
	char *text = malloc(hl + 4097 + tl);
	assert_non_null(text);
	memcpy(text, head, hl);
	memset(text + hl, 'x', 4097);
	text[hl] = '#';
	memcpy(text + hl + 4096, tail, tl);
	put_file(dir, "line4096.fig", text, hl + 4096 + tl, path, sizeof path);
	struct model *m = read_ok(path);
	model_free(m);
	unlink(path);
	memcpy(text + hl + 4097, tail, tl);
	text[hl + 4096] = 'x';
	put_file(dir, "line4097.fig", text, hl + 4097 + tl, path, sizeof path);
	expect_file_error(path, "2:4097", "line is longer than 4096 bytes");
	unlink(path);
	free(text);

	/* larger than 16 MiB: refused before anything is parsed */
	snprintf(path, sizeof path, "%s/huge.fig", dir);
	int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
	assert_true(fd >= 0);
	assert_int_equal(ftruncate(fd, (16 << 20) + 1), 0);
	close(fd);
	expect_file_error(path, "1:1", "larger than 16 MiB");
	unlink(path);

	/* an OBJ with binary data: the figure error carries the OBJ's own place */
	char obj[600];
	static const char binobj[] = "v 0 0 0\n\x02\n";
	put_file(dir, "bin.obj", binobj, sizeof binobj - 1, obj, sizeof obj);
	static const char usesbin[] = "figure f {\n segment a { psurf = \"bin.obj\"; }\n}\n";
	put_file(dir, "usesbin.fig", usesbin, sizeof usesbin - 1, path, sizeof path);
	char frag[700];
	snprintf(frag, sizeof frag, "%s:2:1: binary data (byte 0x02)", obj);
	expect_file_error(path, "2:22", frag);
	unlink(path);
	unlink(obj);

	assert_int_equal(rmdir(dir), 0);
}

static void
test_obj_forms(void **unused)
{
	(void)unused;
	struct obj_mesh om;
	char err[512];
	if (obj_read_file(FIG_DIR "/quad.obj", &om, err, sizeof err) < 0)
		fail_msg("%s", err);
	/* a quad, a triangle with negative indices, v//n and a pentagon, as fans */
	static const int want[][3] = { { 0, 1, 2 }, { 0, 2, 3 }, { 4, 5, 6 }, { 0, 1, 4 },
				       { 0, 1, 2 }, { 0, 2, 3 }, { 0, 3, 4 } };
	assert_int_equal(om.nvert, 7);
	assert_int_equal(om.nface, 7);
	assert_memory_equal(om.face, want, sizeof want);
	assert_true(om.vert[18] == 1.0f && om.vert[19] == 1.0f && om.vert[20] == 1.0f);
	obj_mesh_free(&om);
	assert_null(om.vert);

	static const char crlf[] = "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n";
	assert_int_equal(obj_read_string(crlf, sizeof crlf - 1, "crlf.obj", &om, err, sizeof err),
			 0);
	assert_int_equal(om.nface, 1);
	obj_mesh_free(&om);
}

static void
test_obj_errors(void **unused)
{
	(void)unused;
	static const struct {
		const char *text, *where, *frag;
	} cases[] = {
		{ "v 0 0 0\nv 1 0 0\nf 1 2 3\n", "3:7",
		  "face refers to vertex 3, but only 2 vertices are defined so far" },
		{ "v 0 0 0\nf 0 1 1\n", "2:3", "vertex index 0" },
		{ "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n", "4:3", "face refers to vertex -4" },
		{ "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", "4:6",
		  "a face needs at least 3 corners, found 2" },
		{ "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/x 2 3\n", "4:3", "expected a face corner" },
		{ "v 0 0\n", "1:6", "a vertex needs 3 coordinates, found 2" },
		{ "v 0 0 0\n", "1:1", "no faces" },
		{ "", "1:1", "no faces" },
		{ "v 1e40 0 0\n", "1:3", "not a finite single-precision number" },
		{ "v nan 0 0\n", "1:3", "not a finite single-precision number" },
		{ "v 0 0 0 \x01\n", "1:9", "binary data (byte 0x01)" },
		{ "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999\n", "4:7", "out of range" },
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		struct obj_mesh om;
		char err[512], prefix[64];
		int rc = obj_read_string(cases[i].text, strlen(cases[i].text), "t.obj", &om, err,
					 sizeof err);
		if (rc == 0)
			fail_msg("case %zu accepted", i);
		assert_null(om.vert);
		assert_null(om.face);
		snprintf(prefix, sizeof prefix, "t.obj:%s: ", cases[i].where);
		if (strncmp(err, prefix, strlen(prefix)) || !strstr(err, cases[i].frag))
			fail_msg("case %zu: expected '%s...%s', got '%s'", i, prefix, cases[i].frag,
				 err);
	}
}

static void
test_write_file(void **unused)
{
	(void)unused;
	char dir[] = "/tmp/posture_figXXXXXX", path[600], tmp[640], err[512];
	assert_non_null(mkdtemp(dir));
	snprintf(path, sizeof path, "%s/chair.fig", dir);
	snprintf(tmp, sizeof tmp, "%s.tmp", path);
	struct model *m = read_ok(ENV_DIR "/chair.fig");
	if (figure_write_file(m, path, err, sizeof err) < 0)
		fail_msg("%s", err);
	assert_int_not_equal(access(tmp, F_OK), 0);
	struct model *m2 = read_ok(path);
	assert_true(model_equal(m, m2));
	model_free(m2);
	model_free(m);
	unlink(path);

	/* a name the language cannot spell: refused, and no file is left */
	struct model_builder *b = model_builder_create("bad name");
	struct segment_def sd = segment_default_def();
	sd.name = "a";
	double o[3] = { 0, 0, 0 };
	int seg = model_builder_segment(b, &sd);
	int site = model_builder_site(b, seg, "s", o, QID);
	assert_int_equal(model_builder_root(b, site, o, QID), 0);
	m = model_builder_finish(b);
	assert_non_null(m);
	model_builder_free(b);
	FILE *f = fopen("/dev/null", "w");
	assert_non_null(f);
	errno = 0;
	assert_int_equal(figure_write(m, f), -1);
	assert_int_equal(errno, EINVAL);
	fclose(f);
	assert_int_equal(figure_write_file(m, path, err, sizeof err), -1);
	assert_non_null(strstr(err, "cannot express"));
	assert_int_not_equal(access(path, F_OK), 0);
	assert_int_not_equal(access(tmp, F_OK), 0);
	model_free(m);
	assert_int_equal(rmdir(dir), 0);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_figure_a1),
		cmocka_unit_test(test_units_and_transforms),
		cmocka_unit_test(test_crlf_and_exact_message),
		cmocka_unit_test(test_round_trip_files),
		cmocka_unit_test(test_round_trip_two_meshes_at_identity),
		cmocka_unit_test(test_environment_figures),
		cmocka_unit_test(test_round_trip_random),
		cmocka_unit_test(test_bad_files),
		cmocka_unit_test(test_bad_generated),
		cmocka_unit_test(test_obj_forms),
		cmocka_unit_test(test_obj_errors),
		cmocka_unit_test(test_write_file),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
