/* gltf.c - binary glTF 2.0 export: meshes, a joint hierarchy, postures as an animation */
#include "export/gltf.h"

#include <jansson.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "export/export_file.h"
#include "export/seg_mesh.h"

/* glTF's numbers for what is written here */
#define GLB_MAGIC 0x46546C67u /* "glTF" */
#define GLB_JSON 0x4E4F534Au
#define GLB_BIN 0x004E4942u
#define GL_FLOAT 5126
#define GL_UNSIGNED_INT 5125
#define GL_ARRAY_BUFFER 34962
#define GL_ELEMENT_ARRAY_BUFFER 34963
#define GL_TRIANGLES 4

struct gltf {
	json_t *root, *nodes, *meshes, *materials, *accessors, *views, *scene_nodes;
	json_t *samplers, *channels;
	unsigned char *bin;
	size_t len, cap;
	int oom;
};

/* takes a new reference into an array or object; a NULL (jansson out of memory) is noted */
static void
push(struct gltf *g, json_t *array, json_t *v)
{
	if (!v || json_array_append_new(array, v) < 0)
		g->oom = 1;
}

static void
set(struct gltf *g, json_t *obj, const char *key, json_t *v)
{
	if (!v || json_object_set_new(obj, key, v) < 0)
		g->oom = 1;
}

static json_t *
numbers(const double *v, int n)
{
	json_t *a = json_array();
	for (int i = 0; a && i < n; i++)
		if (json_array_append_new(a, json_real(v[i])) < 0) {
			json_decref(a);
			return NULL;
		}
	return a;
}

/*
 * Appends n bytes (a multiple of 4, so every view starts 4-aligned as
 * accessors of 4-byte components need) as a buffer view; its index.
 */
static int
add_view(struct gltf *g, const void *data, size_t n, int target)
{
	if (g->len + n > g->cap) {
		size_t cap = g->cap ? g->cap : 1 << 16;
		while (cap < g->len + n)
			cap *= 2;
		unsigned char *b = realloc(g->bin, cap);
		if (!b) {
			g->oom = 1;
			return 0;
		}
		g->bin = b;
		g->cap = cap;
	}
	memcpy(g->bin + g->len, data, n);
	json_t *v = json_pack("{s:i, s:I, s:I}", "buffer", 0, "byteOffset", (json_int_t)g->len,
			      "byteLength", (json_int_t)n);
	if (v && target)
		set(g, v, "target", json_integer(target));
	g->len += n;
	push(g, g->views, v);
	return (int)json_array_size(g->views) - 1;
}

static const char *const type_name[] = { NULL, "SCALAR", NULL, "VEC3", "VEC4" };

/*
 * count elements of ncomp floats as a view and an accessor; with minmax the
 * per-component bounds of exactly the floats written (the spec asks them
 * of POSITION and of animation inputs). Its accessor index.
 */
static int
add_floats(struct gltf *g, const float *v, int count, int ncomp, int target, int minmax)
{
	int view = add_view(g, v, sizeof *v * (size_t)count * (size_t)ncomp, target);
	json_t *a = json_pack("{s:i, s:i, s:i, s:s}", "bufferView", view, "componentType", GL_FLOAT,
			      "count", count, "type", type_name[ncomp]);
	if (a && minmax) {
		double lo[4], hi[4];
		for (int c = 0; c < ncomp; c++) {
			lo[c] = hi[c] = v[c];
			for (int i = 1; i < count; i++) {
				lo[c] = fmin(lo[c], v[ncomp * i + c]);
				hi[c] = fmax(hi[c], v[ncomp * i + c]);
			}
		}
		set(g, a, "min", numbers(lo, ncomp));
		set(g, a, "max", numbers(hi, ncomp));
	}
	push(g, g->accessors, a);
	return (int)json_array_size(g->accessors) - 1;
}

static int
add_indices(struct gltf *g, const unsigned *idx, int count)
{
	int view = add_view(g, idx, sizeof *idx * (size_t)count, GL_ELEMENT_ARRAY_BUFFER);
	push(g, g->accessors,
	     json_pack("{s:i, s:i, s:i, s:s}", "bufferView", view, "componentType",
		       GL_UNSIGNED_INT, "count", count, "type", "SCALAR"));
	return (int)json_array_size(g->accessors) - 1;
}

/* the segment's colour as a material: opaque, or blended when the renderer blends it */
static int
add_material(struct gltf *g, const struct model *m, int seg)
{
	double c[4];
	for (int i = 0; i < 4; i++)
		c[i] = fmin(1, fmax(0, m->seg_rgba[4 * seg + i]));
	json_t *mat = json_pack("{s:s, s:{s:o, s:f, s:f}}", "name", m->seg_name[seg],
				"pbrMetallicRoughness", "baseColorFactor", numbers(c, 4),
				"metallicFactor", 0.0, "roughnessFactor", 0.8);
	if (mat && c[3] < 1)
		set(g, mat, "alphaMode", json_string("BLEND"));
	push(g, g->materials, mat);
	return (int)json_array_size(g->materials) - 1;
}

/* the segment's mesh and material; the mesh's index, -1 for a segment without geometry */
static int
add_mesh(struct gltf *g, const struct model *m, int seg, char *err, size_t errlen)
{
	struct seg_mesh sm;
	if (seg_mesh_build(m, seg, &sm) < 0) {
		snprintf(err, errlen, "out of memory");
		return -2;
	}
	int mesh = -1;
	if (sm.nvert > 0 && sm.ntri > 0) {
		int pos = add_floats(g, sm.pos, sm.nvert, 3, GL_ARRAY_BUFFER, 1);
		int nrm = add_floats(g, sm.nrm, sm.nvert, 3, GL_ARRAY_BUFFER, 0);
		int idx = add_indices(g, sm.idx, 3 * sm.ntri);
		int mat = add_material(g, m, seg);
		push(g, g->meshes,
		     json_pack("{s:s, s:[{s:{s:i, s:i}, s:i, s:i, s:i}]}", "name", m->seg_name[seg],
			       "primitives", "attributes", "POSITION", pos, "NORMAL", nrm, "indices",
			       idx, "material", mat, "mode", GL_TRIANGLES));
		mesh = (int)json_array_size(g->meshes) - 1;
	}
	seg_mesh_free(&sm);
	return mesh;
}

/* unit quaternion (x, y, z, w) of a rotation matrix */
static void
quat_of(const double r[9], double q[4])
{
	mathx_mat_to_quat(r, q);
	double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
	for (int i = 0; i < 4; i++)
		q[i] /= n;
}

/* a node of the given name and local transform; its index */
static int
add_node(struct gltf *g, const char *name, const struct xform *x)
{
	double q[4];
	quat_of(x->r, q);
	push(g, g->nodes,
	     json_pack("{s:s, s:o, s:o}", "name", name, "translation", numbers(x->p, 3),
		       "rotation", numbers(q, 4)));
	return (int)json_array_size(g->nodes) - 1;
}

static void
add_child(struct gltf *g, int parent, int child)
{
	json_t *node = json_array_get(g->nodes, (size_t)parent);
	if (!node) {
		g->oom = 1;
		return;
	}
	json_t *children = json_object_get(node, "children");
	if (!children) {
		children = json_array();
		set(g, node, "children", children);
		if (!children)
			return;
	}
	push(g, children, json_integer(child));
}

/*
 * The local transforms of a figure's top node and joint nodes in a
 * posture, read from its global frames so that whatever root the posture
 * was computed from, the tree is the one of the posture now (tree).
 * Joint j's node sits under its parent segment at the child-side site's
 * global frame: that is the parent-side site's frame moved by the joint,
 * inverted joints included, as kin computed it.
 */
static void
top_local(const struct state *tree, const struct state *pose, struct xform *dest)
{
	*dest = pose->site_xf[tree->root_site];
}

static void
joint_local(const struct state *tree, const struct state *pose, int j, struct xform *dest)
{
	int child = tree->jnt_child_seg[j];
	struct xform inv;
	xform_inv(&pose->seg_xf[tree->seg_parent[child]], &inv);
	xform_mul(&inv, &pose->site_xf[tree->seg_root_site[child]], dest);
}

/* the figure's nodes and meshes; the index of its top node, or -1 with why in err */
static int
add_figure(struct gltf *g, const struct motion *mo, int *jnt_node, char *err, size_t errlen)
{
	const struct model *m = mo->m;
	const struct state *s = mo->now;
	struct xform x;
	top_local(s, s, &x);
	int top = add_node(g, mo->name, &x);
	int *seg_node = malloc(sizeof *seg_node * (size_t)m->nseg);
	if (!seg_node) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	/* top-down, so a joint's parent segment node exists before the joint */
	for (int i = 0; i < m->nseg; i++) {
		int seg = s->seg_order[i], j = s->seg_root_joint[seg], up = top;
		if (j >= 0) {
			joint_local(s, s, j, &x);
			jnt_node[j] = up = add_node(g, m->jnt_name[j], &x);
			add_child(g, seg_node[s->seg_parent[seg]], up);
		}
		/* under the site at the segment's top: the joint's child side, or the root site */
		seg_node[seg] = add_node(g, m->seg_name[seg], &m->site_loc_inv[s->seg_root_site[seg]]);
		add_child(g, up, seg_node[seg]);
		int mesh = add_mesh(g, m, seg, err, errlen);
		if (mesh < -1) {
			free(seg_node);
			return -1;
		}
		if (mesh >= 0)
			set(g, json_array_get(g->nodes, (size_t)seg_node[seg]), "mesh",
			    json_integer(mesh));
	}
	free(seg_node);
	return top;
}

/*
 * One channel of a node over the frames: its translations, or its
 * rotations each on the hemisphere of the one before, so LINEAR
 * interpolation turns the short way.
 */
static void
add_channel(struct gltf *g, int node, const struct xform *local, int nkey, int rotation,
	    int input, float *scratch)
{
	int n = rotation ? 4 : 3;
	double prev[4] = { 0, 0, 0, 1 };
	for (int k = 0; k < nkey; k++) {
		double v[4];
		if (rotation) {
			quat_of(local[k].r, v);
			if (v[0] * prev[0] + v[1] * prev[1] + v[2] * prev[2] + v[3] * prev[3] < 0)
				for (int i = 0; i < 4; i++)
					v[i] = -v[i];
			memcpy(prev, v, sizeof prev);
		} else {
			memcpy(v, local[k].p, sizeof local[k].p);
		}
		for (int i = 0; i < n; i++)
			scratch[n * k + i] = (float)v[i];
	}
	int output = add_floats(g, scratch, nkey, n, 0, 0);
	push(g, g->samplers,
	     json_pack("{s:i, s:i, s:s}", "input", input, "output", output, "interpolation",
		       "LINEAR"));
	int sampler = (int)json_array_size(g->samplers) - 1;
	push(g, g->channels,
	     json_pack("{s:i, s:{s:i, s:s}}", "sampler", sampler, "target", "node", node, "path",
		       rotation ? "rotation" : "translation"));
}

/* the figure's channels over nkey keyframes; -1 when out of memory */
static int
add_figure_motion(struct gltf *g, const struct motion *mo, int top, const int *jnt_node,
		  int nkey, int input)
{
	const struct model *m = mo->m;
	struct xform *local = malloc(sizeof *local * (size_t)nkey);
	float *scratch = malloc(sizeof *scratch * 4 * (size_t)nkey);
	if (!local || !scratch) {
		free(local);
		free(scratch);
		return -1;
	}
	for (int k = 0; k < nkey; k++)
		top_local(mo->now, motion_frame(mo, k), &local[k]);
	add_channel(g, top, local, nkey, 0, input, scratch);
	add_channel(g, top, local, nkey, 1, input, scratch);
	for (int j = 0; j < m->njnt; j++) {
		int moves = model_joint_has(m, j, DOF_TRANSLATION), turns = model_joint_has(m, j, DOF_ROTATION);
		if (!moves && !turns)
			continue;
		for (int k = 0; k < nkey; k++)
			joint_local(mo->now, motion_frame(mo, k), j, &local[k]);
		if (moves)
			add_channel(g, jnt_node[j], local, nkey, 0, input, scratch);
		if (turns)
			add_channel(g, jnt_node[j], local, nkey, 1, input, scratch);
	}
	free(local);
	free(scratch);
	return 0;
}

/* every number an export takes from a figure is finite; -1 with which not in err */
static int
check_motion(const struct motion *mo, char *err, size_t errlen)
{
	if (!mo->m || !mo->now || !mo->name || (mo->nframes > 0 && !mo->frames)) {
		snprintf(err, errlen, "figure %s: nothing to export", mo->name ? mo->name : "?");
		return -1;
	}
	for (int k = -1; k < mo->nframes; k++) {
		const struct state *s = k < 0 ? mo->now : mo->frames[k];
		for (int seg = 0; s && seg < mo->m->nseg; seg++)
			if (!xform_finite(&s->seg_xf[seg])) {
				snprintf(err, errlen, "figure %s: segment %s is not at a finite place",
					 mo->name, mo->m->seg_name[seg]);
				return -1;
			}
	}
	return 0;
}

static int
write_u32(FILE *f, uint32_t v)
{
	unsigned char b[4] = { v & 0xff, (v >> 8) & 0xff, (v >> 16) & 0xff, v >> 24 };
	return fwrite(b, 1, 4, f) == 4 ? 0 : -1;
}

/* the container: header, the JSON chunk padded with spaces, the BIN chunk (already 4-aligned) */
static void
write_glb(FILE *f, const char *json, const unsigned char *bin, size_t binlen)
{
	size_t jlen = strlen(json), jpad = (4 - jlen % 4) % 4;
	size_t total = 12 + 8 + jlen + jpad + (binlen ? 8 + binlen : 0);
	write_u32(f, GLB_MAGIC);
	write_u32(f, 2);
	write_u32(f, (uint32_t)total);
	write_u32(f, (uint32_t)(jlen + jpad));
	write_u32(f, GLB_JSON);
	fwrite(json, 1, jlen, f);
	fwrite("   ", 1, jpad, f);
	if (binlen) {
		write_u32(f, (uint32_t)binlen);
		write_u32(f, GLB_BIN);
		fwrite(bin, 1, binlen, f);
	}
}

/* the keyframe times, one a frame; the accessor's index */
static int
add_times(struct gltf *g, int nkey, double frame_seconds)
{
	float *t = malloc(sizeof *t * (size_t)nkey);
	if (!t) {
		g->oom = 1;
		return 0;
	}
	for (int k = 0; k < nkey; k++)
		t[k] = (float)(k * frame_seconds);
	int input = add_floats(g, t, nkey, 1, 0, 1);
	free(t);
	return input;
}

/* builds the document and its binary; 0, or -1 with why in err */
static int
build(struct gltf *g, const struct motion *figs, int nfig, double frame_seconds, char *err,
      size_t errlen)
{
	int nkey = 0, maxjnt = 0, input = -1;
	for (int i = 0; i < nfig; i++) {
		nkey = figs[i].nframes > nkey ? figs[i].nframes : nkey;
		maxjnt = figs[i].m->njnt > maxjnt ? figs[i].m->njnt : maxjnt;
	}
	int *jnt_node = malloc(sizeof *jnt_node * (size_t)(maxjnt + 1));
	int *top = malloc(sizeof *top * (size_t)nfig);
	int rc = jnt_node && top ? 0 : -1;
	for (int i = 0; !rc && i < nfig; i++) {
		top[i] = add_figure(g, &figs[i], jnt_node, err, errlen);
		if (top[i] < 0) {
			rc = -1;
			break;
		}
		push(g, g->scene_nodes, json_integer(top[i]));
		if (figs[i].nframes > 0) {
			/* every figure's keyframes share one time accessor */
			if (input < 0)
				input = add_times(g, nkey, frame_seconds);
			/* jnt_node holds this figure's joint nodes: its channels now */
			if (add_figure_motion(g, &figs[i], top[i], jnt_node, nkey, input) < 0)
				g->oom = 1;
		}
	}
	free(jnt_node);
	free(top);
	if (!rc && g->oom)
		snprintf(err, errlen, "out of memory");
	return rc || g->oom ? -1 : 0;
}

int
gltf_export(const struct motion *figs, int nfig, double frame_seconds, const char *path,
	    char *err, size_t errlen)
{
	char dir[4096], stem[4096];
	if (export_split_path(path, ".glb", dir, sizeof dir, stem, sizeof stem, err, errlen) < 0)
		return -1;
	if (nfig < 1 || !figs) {
		snprintf(err, errlen, "no figure to export");
		return -1;
	}
	int animated = 0;
	for (int i = 0; i < nfig; i++) {
		if (check_motion(&figs[i], err, errlen) < 0)
			return -1;
		animated |= figs[i].nframes > 0;
	}
	if (animated && !(isfinite(frame_seconds) && frame_seconds > 0)) {
		snprintf(err, errlen, "the time between frames must be positive, not %g",
			 frame_seconds);
		return -1;
	}
	struct gltf g = { 0 };
	g.root = json_pack("{s:{s:s, s:s}, s:i, s:[{s:[]}], s:[], s:[], s:[], s:[], s:[]}",
			   "asset", "version", "2.0", "generator", "posture", "scene", 0, "scenes",
			   "nodes", "nodes", "meshes", "materials", "accessors", "bufferViews");
	if (!g.root) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	g.nodes = json_object_get(g.root, "nodes");
	g.meshes = json_object_get(g.root, "meshes");
	g.materials = json_object_get(g.root, "materials");
	g.accessors = json_object_get(g.root, "accessors");
	g.views = json_object_get(g.root, "bufferViews");
	g.scene_nodes = json_object_get(json_array_get(json_object_get(g.root, "scenes"), 0), "nodes");
	json_t *anim = json_pack("{s:s, s:[], s:[]}", "name", "postures", "samplers", "channels");
	g.samplers = json_object_get(anim, "samplers");
	g.channels = json_object_get(anim, "channels");
	int rc = anim ? build(&g, figs, nfig, frame_seconds, err, errlen) : -1;
	if (!anim)
		snprintf(err, errlen, "out of memory");
	/* glTF forbids empty arrays: what a figure without geometry or frames lacks goes */
	if (!rc && json_array_size(g.channels))
		set(&g, g.root, "animations", json_pack("[O]", anim));
	static const char *const maybe_empty[] = { "meshes", "materials", "accessors", "bufferViews" };
	for (size_t i = 0; i < sizeof maybe_empty / sizeof *maybe_empty; i++)
		if (!json_array_size(json_object_get(g.root, maybe_empty[i])))
			json_object_del(g.root, maybe_empty[i]);
	if (!rc && g.len)
		set(&g, g.root, "buffers", json_pack("[{s:I}]", "byteLength", (json_int_t)g.len));
	char *json = !rc && !g.oom ? json_dumps(g.root, JSON_COMPACT | JSON_REAL_PRECISION(17)) : NULL;
	if (!rc && !json) {
		snprintf(err, errlen, "out of memory");
		rc = -1;
	}
	if (!rc) {
		struct export_file out;
		FILE *f = export_file_open(&out, path, err, errlen);
		if (f)
			write_glb(f, json, g.bin, g.len);
		rc = f ? export_file_commit(&out, err, errlen) : -1;
	}
	free(json);
	json_decref(anim);
	json_decref(g.root);
	free(g.bin);
	return rc;
}
