/* cmd_pick.c - the mouse line through a pixel of a view, and what it hits first */
#include <math.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/daemon.h"
#include "interact/mouse_line.h"
#include "interact/pick.h"

/* the hit as the reply's object: ids and names, world metres */
static json_t *
hit_json(const struct env *e, const struct pick_hit *h, int slot)
{
	const struct model *m = e->fig[slot].model;
	char id[32], site[2 * MODEL_NAME_MAX];
	env_figure_id(e, slot, id);
	json_t *o = json_object();
	json_object_set_new(o, "figure", json_string(id));
	json_object_set_new(o, "name", json_string(e->fig[slot].name));
	json_object_set_new(o, "segment", json_string(m->seg_name[h->segment]));
	json_object_set_new(o, "site", h->site < 0 ? json_null()
					   : json_string(model_site_fullname(m, h->site, site,
									     sizeof site)));
	json_object_set_new(o, "point", cmd_vec(h->point, 3));
	json_object_set_new(o, "normal", cmd_vec(h->normal, 3));
	json_object_set_new(o, "distance", json_real(h->distance));
	json_object_set_new(o, "geom", json_integer(h->geom));
	json_object_set_new(o, "part", json_integer(h->part));
	json_object_set_new(o, "face", json_integer(h->face));
	json_t *edge = json_array();
	json_array_append_new(edge, json_integer(h->edge[0]));
	json_array_append_new(edge, json_integer(h->edge[1]));
	json_object_set_new(o, "edge", edge);
	json_object_set_new(o, "vertex", json_integer(h->vertex));
	return o;
}

int
cmd_pick(struct cmd_ctx *c)
{
	struct env *e = &c->d->env;
	int v = env_find_view(e, c->argv[0]);
	if (v < 0)
		return cmd_fail(c, "not-found", "no view '%.60s'", c->argv[0]);
	const struct env_view *vw = &e->view[v];
	double x, y;
	if (words_number(c->argv[1], UNIT_NONE, &x) < 0 || words_number(c->argv[2], UNIT_NONE, &y) < 0)
		return cmd_fail(c, "bad-number", "X and Y are pixels, e.g. 320 or 320.5");
	if (x < 0 || y < 0 || x > vw->width || y > vw->height)
		return cmd_fail(c, "bad-argument", "(%g, %g) is outside view %s (%d x %d)", x, y,
				vw->name, vw->width, vw->height);

	struct camera cam;
	struct ray r;
	view_camera_of_view(vw, &cam);
	if (mouse_line(&cam, vw->width, vw->height, x, y, &r) < 0)
		return cmd_fail(c, "internal", "no mouse line through (%g, %g)", x, y);

	/* what lies nearer than the near plane is clipped from the picture: not hit either */
	double ahead = -(r.d[0] * cam.xf.r[2] + r.d[1] * cam.xf.r[5] + r.d[2] * cam.xf.r[8]);
	double tmin = ahead > 0 ? cam.znear / ahead : 0;
	struct pick_hit h;
	int fig, hit = daemon_pick(c->d, &r, tmin, -1, &h, &fig);
	if (hit < 0)
		return cmd_fail(c, "internal", "out of memory");

	json_object_set_new(c->result, "origin", cmd_vec(r.o, 3));
	json_object_set_new(c->result, "direction", cmd_vec(r.d, 3));
	json_object_set_new(c->result, "hit", hit ? hit_json(e, &h, fig) : json_null());
	return 0;
}
