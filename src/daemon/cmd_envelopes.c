/*
 * cmd_envelopes.c - the envelopes kept (envelopes.h): listed, hidden or
 * shown in the views, removed, and written for other tools as STL or glTF.
 */
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/envelopes.h"
#include "export/mesh_export.h"

/* the envelope named argv[0]: its slot, or -1 with the error set */
static int
named(struct cmd_ctx *c)
{
	const struct envelopes *s = c->d->envelopes;
	int k = s ? envelopes_find(s, c->argv[0]) : -1;
	if (k < 0)
		return cmd_fail(c, "not-found", "no envelope '%.60s' (list envelopes)", c->argv[0]);
	return k;
}

int
cmd_list_envelopes(struct cmd_ctx *c)
{
	const struct envelopes *s = c->d->envelopes;
	json_t *list = json_array();
	static const char *const modes[] = { "arm", "torso", "body" };
	for (int k = 0; s && k < ENVELOPES_MAX; k++) {
		const struct envelope_entry *x = &s->slot[k];
		if (!x->used)
			continue;
		json_t *o = json_pack("{s:s, s:s, s:s, s:s, s:f, s:f, s:i, s:i, s:b, s:b}", "name",
				      x->name, "figure", x->fig_name, "hand",
				      x->e.req.side ? "right" : "left", "mode", modes[x->e.req.mode],
				      "resolution", x->e.req.resolution, "volume", x->e.reach.volume,
				      "vertices", x->e.reach.nvert, "triangles", x->e.reach.ntri,
				      "comfort", x->e.req.comfort, "hidden", x->hidden);
		json_array_append_new(list, o);
	}
	json_object_set_new(c->result, "envelopes", list);
	return 0;
}

int
cmd_set_envelope(struct cmd_ctx *c)
{
	int k = named(c);
	if (k < 0)
		return -1;
	const char *h = NULL;
	for (int i = 1; i < c->argc; i++) {
		if (!words_is_key(c->argv[i], "hidden"))
			return cmd_fail(c, "bad-argument", "unexpected '%.60s' (hidden=yes|no)",
					c->argv[i]);
		h = cmd_key(c, "hidden");
	}
	if (!h || (strcmp(h, "yes") && strcmp(h, "no")))
		return cmd_fail(c, "bad-argument", "hidden=yes|no");
	envelopes_set_hidden(c->d->envelopes, k, !strcmp(h, "yes"));
	json_object_set_new(c->result, "hidden", json_boolean(c->d->envelopes->slot[k].hidden));
	return 0;
}

int
cmd_remove_envelope(struct cmd_ctx *c)
{
	int k = named(c);
	if (k < 0)
		return -1;
	envelopes_remove(c->d->envelopes, k);
	return 0;
}

/* mesh m of envelope x as the writer takes it */
static struct mesh_export
as_export(const struct envelope_mesh *m, const char *name, const float rgba[4])
{
	struct mesh_export x = { .name = name, .nvert = m->nvert, .ntri = m->ntri, .vert = m->vert,
				 .normal = m->normal, .tri = m->tri };
	memcpy(x.rgba, rgba, sizeof x.rgba);
	return x;
}

int
cmd_export_envelope(struct cmd_ctx *c)
{
	int k = named(c);
	if (k < 0)
		return -1;
	const struct envelope_entry *x = &c->d->envelopes->slot[k];
	const char *part = cmd_key(c, "part");
	if (c->argc == 3 && !part)
		return cmd_fail(c, "bad-argument", "unexpected '%.60s' (part=reach|comfort)", c->argv[2]);
	if (part && strcmp(part, "reach") && strcmp(part, "comfort"))
		return cmd_fail(c, "bad-argument", "part=reach|comfort");
	if (part && !strcmp(part, "comfort") && !x->e.req.comfort)
		return cmd_fail(c, "bad-argument", "%s has no comfort zone (analyze reach ... comfort=on)",
				x->name);
	const char *rel = c->argv[1], *ext = strrchr(rel, '.');
	if (!ext || (strcmp(ext, ".stl") && strcmp(ext, ".glb") && strcmp(ext, ".gltf")))
		return cmd_fail(c, "bad-argument", "'%.60s' must end in .stl, .glb or .gltf", rel);
	char path[4096], err[512], comfort_name[ENVELOPE_NAME_MAX + 8];
	if (cmd_path(c, rel, 1, path, sizeof path) < 0)
		return -1;
	snprintf(comfort_name, sizeof comfort_name, "%s.comfort", x->name);
	struct mesh_export m[2];
	int n = 0;
	if (!part || !strcmp(part, "reach"))
		m[n++] = as_export(&x->e.reach, x->name, ENVELOPE_REACH_RGBA);
	if ((!part && x->e.req.comfort) || (part && !strcmp(part, "comfort")))
		m[n++] = as_export(&x->e.comfort, comfort_name, ENVELOPE_COMFORT_RGBA);
	if (!strcmp(ext, ".stl"))
		n = 1; /* STL holds one surface: the first asked for */
	if (m[0].ntri < 1)
		return cmd_fail(c, "nothing", "%s: the surface is empty (nothing reachable)",
				m[0].name);
	if (n == 2 && m[1].ntri < 1)
		n = 1; /* an empty comfort zone: nothing to draw in the file */
	if (mesh_export_write(m, n, path, err, sizeof err) < 0)
		return cmd_fail(c, "io", "%s", err);
	json_object_set_new(c->result, "path", json_string(rel));
	json_object_set_new(c->result, "meshes", json_integer(n));
	json_object_set_new(c->result, "triangles", json_integer(m[0].ntri + (n == 2 ? m[1].ntri : 0)));
	return 0;
}
