/* cmd_attach.c - grab, hold and release through the protocol (Table D.4) */
#include <string.h>

#include "pose/attach.h"
#include "daemon/cmd_ctx.h"

int
cmd_grab(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]), side, obj;
	if (fig < 0 || (side = cmd_side(c, c->argv[1])) < 0 || (obj = cmd_figure(c, c->argv[2])) < 0)
		return -1;
	struct env *e = &c->d->env;
	char err[200];
	if (attach_grab(e, fig, side, obj, err, sizeof err) < 0)
		return cmd_fail(c, "bad-argument", "%s", err);
	return 0;
}

/* "OBJ" (its base segment) or "OBJ.SEGMENT" */
static int
object_segment(struct cmd_ctx *c, const char *w, int *seg)
{
	char name[2 * MODEL_NAME_MAX];
	snprintf(name, sizeof name, "%s", w);
	char *dot = strchr(name, '.');
	if (dot)
		*dot = 0;
	int obj = cmd_figure(c, name);
	if (obj < 0)
		return -1;
	const struct model *m = c->d->env.fig[obj].model;
	*seg = dot ? model_find_segment(m, dot + 1) : 0;
	if (*seg < 0)
		return cmd_fail(c, "not-found", "%s has no segment '%.48s'", c->d->env.fig[obj].name, dot + 1);
	return obj;
}

static int
hold(struct cmd_ctx *c, enum attach_limb limb)
{
	int fig = cmd_figure(c, c->argv[0]), side, obj, seg;
	if (fig < 0 || (side = cmd_side(c, c->argv[1])) < 0 ||
	    (obj = object_segment(c, c->argv[2], &seg)) < 0)
		return -1;
	struct env *e = &c->d->env;
	char err[200];
	env_sync_solver(e, fig);
	if (attach_local(e, fig, limb, side, obj, seg, err, sizeof err) < 0)
		return cmd_fail(c, "bad-argument", "%s", err);
	return 0;
}

int
cmd_hold_hand(struct cmd_ctx *c)
{
	return hold(c, ATTACH_HAND);
}

int
cmd_hold_foot(struct cmd_ctx *c)
{
	return hold(c, ATTACH_FOOT);
}

static int
release(struct cmd_ctx *c, enum attach_limb limb)
{
	int fig = cmd_figure(c, c->argv[0]), side;
	if (fig < 0 || (side = cmd_side(c, c->argv[1])) < 0)
		return -1;
	json_object_set_new(c->result, "released",
			    json_boolean(attach_release(&c->d->env, fig, limb, side)));
	return 0;
}

int
cmd_release_hand(struct cmd_ctx *c)
{
	return release(c, ATTACH_HAND);
}

int
cmd_release_foot(struct cmd_ctx *c)
{
	return release(c, ATTACH_FOOT);
}
