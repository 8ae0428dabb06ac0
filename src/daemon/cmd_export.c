/* cmd_export.c - figures written for other tools: URDF, glTF, BVH */
#include <stdlib.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/history.h"
#include "export/bvh.h"
#include "export/urdf.h"

/* the figure and the file of an export: the slot, or -1 with the error set */
static int
export_target(struct cmd_ctx *c, const char *ext, char *path, size_t len)
{
	int fig = cmd_figure(c, c->argv[0]);
	if (fig < 0)
		return -1;
	const char *rel = c->argv[1], *name = strrchr(rel, '/');
	name = name ? name + 1 : rel;
	size_t n = strlen(name), e = strlen(ext);
	if (n <= e || strcmp(name + n - e, ext))
		return cmd_fail(c, "bad-argument", "'%.60s' must be a file name ending in %s", rel, ext);
	return cmd_path(c, rel, 1, path, len) < 0 ? -1 : fig;
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
	int past = 0;
	for (int k = 0; k < h.n; k++)
		past += frames[k] != NULL;
	int rc = 0;
	if (!past)
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
