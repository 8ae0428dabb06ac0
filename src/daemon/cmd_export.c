/* cmd_export.c - figures written for other tools: URDF, glTF, BVH */
#include <stdlib.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/history.h"
#include "export/bvh.h"
#include "export/gltf.h"
#include "export/urdf.h"

/* the file of an export (argv[1]): 0, or -1 with the error set */
static int
export_path(struct cmd_ctx *c, const char *ext, char *path, size_t len)
{
	const char *rel = c->argv[1], *name = strrchr(rel, '/');
	name = name ? name + 1 : rel;
	size_t n = strlen(name), e = strlen(ext);
	if (n <= e || strcmp(name + n - e, ext))
		return cmd_fail(c, "bad-argument", "'%.60s' must be a file name ending in %s", rel, ext);
	return cmd_path(c, rel, 1, path, len);
}

/* the figure (argv[0]) and the file of an export: the slot, or -1 with the error set */
static int
export_target(struct cmd_ctx *c, const char *ext, char *path, size_t len)
{
	int fig = cmd_figure(c, c->argv[0]);
	if (fig < 0)
		return -1;
	return export_path(c, ext, path, len) < 0 ? -1 : fig;
}

/* how many of a motion's frames before now hold the figure */
static int
past_frames(const struct motion *mo)
{
	int n = 0;
	for (int k = 0; k + 1 < mo->nframes; k++)
		n += mo->frames[k] != NULL;
	return n;
}

int
cmd_export_urdf(struct cmd_ctx *c)
{
	char path[4096], err[512];
	int fig = export_target(c, ".urdf", path, sizeof path);
	if (fig < 0)
		return -1;
	const struct env_figure *f = &c->d->env.fig[fig];
	int files = urdf_export(f->model, f->state, path, err, sizeof err);
	if (files < 0)
		return cmd_fail(c, "io", "%s", err);
	json_object_set_new(c->result, "path", json_string(c->argv[1]));
	json_object_set_new(c->result, "files", json_integer(files));
	return 0;
}

int
cmd_export_bvh(struct cmd_ctx *c)
{
	char path[4096], err[512];
	int fig = export_target(c, ".bvh", path, sizeof path);
	if (fig < 0)
		return -1;
	struct history h;
	if (history_read(c->d, &h, err, sizeof err) < 0)
		return cmd_fail(c, "internal", "%s", err);
	const struct state **frames = malloc(sizeof *frames * (size_t)(h.n + 1));
	if (!frames) {
		history_free(&h);
		return cmd_fail(c, "internal", "out of memory");
	}
	struct motion mo;
	history_motion(c->d, &h, fig, frames, &mo);
	int rc = 0;
	if (!past_frames(&mo))
		rc = cmd_fail(c, "nothing", "%s has no history to animate (no undo step holds it)",
			      mo.name);
	else if (bvh_export(&mo, MOTION_FRAME_SECONDS, path, err, sizeof err) < 0)
		rc = cmd_fail(c, "io", "%s", err);
	else {
		json_object_set_new(c->result, "path", json_string(c->argv[1]));
		json_object_set_new(c->result, "frames", json_integer(mo.nframes));
	}
	free(frames);
	history_free(&h);
	return rc;
}

/* the figures of `export gltf`: argv[0] names one, or "*" every one; their count */
static int
gltf_figures(struct cmd_ctx *c, int *slots)
{
	if (strcmp(c->argv[0], "*")) {
		int fig = cmd_figure(c, c->argv[0]);
		slots[0] = fig;
		return fig < 0 ? -1 : 1;
	}
	int n = 0;
	for (int f = 0; f < ENV_MAX_FIGURES; f++)
		if (c->d->env.fig[f].gen)
			slots[n++] = f;
	return n ? n : cmd_fail(c, "not-found", "the environment holds no figure");
}

int
cmd_export_gltf(struct cmd_ctx *c)
{
	const char *what = c->argc > 2 ? c->argv[2] : "posture";
	int session = !strcmp(what, "session");
	if (!session && strcmp(what, "posture"))
		return cmd_fail(c, "bad-argument", "'%.40s': posture or session", what);
	int slots[ENV_MAX_FIGURES];
	int nfig = gltf_figures(c, slots);
	char path[4096], err[512];
	if (nfig < 0 || export_path(c, ".glb", path, sizeof path) < 0)
		return -1;
	struct history h = { 0 };
	if (session && history_read(c->d, &h, err, sizeof err) < 0)
		return cmd_fail(c, "internal", "%s", err);
	struct motion mo[ENV_MAX_FIGURES];
	const struct state **frames = malloc(sizeof *frames * (size_t)nfig * (size_t)(h.n + 1));
	int rc = 0, past = 0;
	if (!frames) {
		rc = cmd_fail(c, "internal", "out of memory");
		goto out;
	}
	for (int i = 0; i < nfig; i++) {
		history_motion(c->d, session ? &h : NULL, slots[i], frames + (size_t)i * (size_t)(h.n + 1),
			       &mo[i]);
		past += past_frames(&mo[i]);
	}
	if (session && !past)
		rc = cmd_fail(c, "nothing", "no undo step holds %s: no history to animate",
			      nfig == 1 ? mo[0].name : "any figure");
	else if (gltf_export(mo, nfig, MOTION_FRAME_SECONDS, path, err, sizeof err) < 0)
		rc = cmd_fail(c, "io", "%s", err);
	else {
		json_object_set_new(c->result, "path", json_string(c->argv[1]));
		json_object_set_new(c->result, "figures", json_integer(nfig));
		json_object_set_new(c->result, "frames", json_integer(session ? h.n + 1 : 0));
	}
out:
	free(frames);
	history_free(&h);
	return rc;
}
