/* cmd_view.c - views, cameras, and pictures on request */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/daemon.h"
#include "daemon/scene.h"
#include "draw/sink.h"
#include "draw/tiles.h"
#include "daemon/statefile.h"
#include "pose/eyeview.h"

static int
read_point(struct cmd_ctx *c, const char *key, double dest[3])
{
	const char *v = cmd_key(c, key);
	if (v && words_list(v, UNIT_LENGTH, 3, dest) < 0)
		return cmd_fail(c, "bad-number", "%s=X,Y,Z: three lengths", key);
	return 0;
}

static int
read_size(struct cmd_ctx *c, const char *key, int *dest)
{
	const char *v = cmd_key(c, key);
	double d;
	int max = !strcmp(key, "width") ? VIEW_MAX_W : VIEW_MAX_H;
	if (v && (words_number(v, UNIT_NONE, &d) < 0 || d < 16 || d > max || d != (int)d))
		return cmd_fail(c, "bad-number", "%s: a whole number of pixels from 16 to %d", key, max);
	if (v)
		*dest = (int)d;
	return 0;
}

/* fovy=DEG: the vertical field of view in degrees (a bare number), 1 to 170 */
static int
read_fovy(struct cmd_ctx *c, double *dest)
{
	const char *v = cmd_key(c, "fovy");
	double d;
	if (v && (words_number(v, UNIT_NONE, &d) < 0 || d < ENV_VIEW_FOVY_MIN ||
		  d > ENV_VIEW_FOVY_MAX))
		return cmd_fail(c, "bad-number", "fovy: degrees from %g to %g", ENV_VIEW_FOVY_MIN,
				ENV_VIEW_FOVY_MAX);
	if (v)
		*dest = d;
	return 0;
}

static int
only_keys(struct cmd_ctx *c, int from, const char *const *keys, int n)
{
	for (int i = from; i < c->argc; i++) {
		int ok = 0;
		for (int k = 0; k < n; k++)
			ok |= words_is_key(c->argv[i], keys[k]);
		if (!ok)
			return cmd_fail(c, "bad-argument", "unexpected '%.60s'", c->argv[i]);
	}
	return 0;
}

static int
aim_ok(struct cmd_ctx *c, const double eye[3], const double target[3])
{
	double d[3] = { target[0] - eye[0], target[1] - eye[1], target[2] - eye[2] };
	if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < 1e-6)
		return cmd_fail(c, "bad-argument", "the eye and the target coincide");
	return 0;
}

/* hfov=DEG: an eye view's horizontal field of view in degrees (a bare number) */
static int
read_hfov(struct cmd_ctx *c, double *dest)
{
	const char *v = cmd_key(c, "hfov");
	double d;
	if (v && (words_number(v, UNIT_NONE, &d) < 0 || d < EYEVIEW_HFOV_MIN || d > EYEVIEW_HFOV_MAX))
		return cmd_fail(c, "bad-number", "hfov: degrees from %g to %g", EYEVIEW_HFOV_MIN,
				EYEVIEW_HFOV_MAX);
	if (v)
		*dest = d;
	return 0;
}

/*
 * eyes=FIG [which=left|right|both] [hfov=DEG]: the view's camera is the
 * figure's eyes (eyeview.h), placed now; no camera of its own beside
 */
static int
read_eyes(struct cmd_ctx *c, struct env_view *v)
{
	const char *eyes = cmd_key(c, "eyes"), *which = cmd_key(c, "which");
	if (!eyes) {
		if (which || cmd_key(c, "hfov"))
			return cmd_fail(c, "bad-argument", "which= and hfov= are an eye view's (eyes=FIG)");
		return 0;
	}
	if (cmd_key(c, "eye") || cmd_key(c, "target") || cmd_key(c, "fovy"))
		return cmd_fail(c, "bad-argument",
				"an eye view's camera is the figure's eyes: no eye=, target= or fovy=");
	const struct env *e = &c->d->env;
	int fig = cmd_figure(c, eyes), sites[2];
	if (fig < 0)
		return -1;
	v->eyes_which = which ? eyeview_which_find(which) : ENV_EYES_BOTH;
	if (v->eyes_which < 0)
		return cmd_fail(c, "bad-argument", "which=left|right|both, not '%.40s'", which);
	if (eyeview_sites(e->fig[fig].model, v->eyes_which, sites) < 0)
		return cmd_fail(c, "bad-argument", "%s has no eyes (eyeball_l.gaze, eyeball_r.gaze)",
				e->fig[fig].name);
	v->hfov_deg = eyeview_default_hfov(v->eyes_which);
	if (read_hfov(c, &v->hfov_deg) < 0)
		return -1;
	snprintf(v->eyes, sizeof v->eyes, "%s", e->fig[fig].name);
	v->icons = 0; /* what the manikin sees: the icons only when asked for */
	v->ncones = eyeview_default_cones(v->cones_deg);
	if (!eyeview_follow(e, v))
		return cmd_fail(c, "bad-argument", "%s's eyes have no line of sight", v->eyes);
	return 0;
}

int
cmd_add_view(struct cmd_ctx *c)
{
	static const char *const keys[] = { "width", "height", "eye",  "target", "icons",
					    "fovy",  "eyes",   "which", "hfov" };
	struct env *e = &c->d->env;
	const char *name = c->argv[0];
	if (!words_is_name(name))
		return cmd_fail(c, "bad-argument", "a view's name: letters, digits, '_'");
	if (env_find_view(e, name) >= 0)
		return cmd_fail(c, "exists", "a view named '%s' exists", name);
	struct env_view v = { .used = 1, .width = 640, .height = 480, .icons = 1,
			      .eye = { 2.2, 1.5, 3.2 }, .target = { 0, 0.95, 0 },
			      .fovy_deg = ENV_VIEW_FOVY_DEG };
	snprintf(v.name, sizeof v.name, "%s", name);
	const char *icons = cmd_key(c, "icons");
	if (only_keys(c, 1, keys, 9) < 0 || read_size(c, "width", &v.width) < 0 ||
	    read_size(c, "height", &v.height) < 0 || read_point(c, "eye", v.eye) < 0 ||
	    read_point(c, "target", v.target) < 0 || aim_ok(c, v.eye, v.target) < 0 ||
	    read_fovy(c, &v.fovy_deg) < 0 || read_eyes(c, &v) < 0)
		return -1;
	if (icons && strcmp(icons, "0") && strcmp(icons, "1"))
		return cmd_fail(c, "bad-argument", "icons=0|1");
	if (icons)
		v.icons = !strcmp(icons, "1");
	for (int i = 0; i < ENV_MAX_VIEWS; i++)
		if (!e->view[i].used) {
			e->view[i] = v;
			json_object_set_new(c->result, "view", json_string(name));
			return 0;
		}
	return cmd_fail(c, "limit", "%d views at most", ENV_MAX_VIEWS);
}

static int
view_of(struct cmd_ctx *c, const char *name)
{
	int v = env_find_view(&c->d->env, name);
	if (v < 0)
		cmd_fail(c, "not-found", "no view '%.60s'", name);
	return v;
}

int
cmd_set_camera(struct cmd_ctx *c)
{
	static const char *const keys[] = { "eye", "target", "fovy", "hfov" };
	int v = view_of(c, c->argv[0]);
	if (v < 0 || only_keys(c, 1, keys, 4) < 0)
		return -1;
	struct env_view *w = &c->d->env.view[v];
	if (w->eyes[0]) { /* the eyes place it: only its width is the view's own */
		double hfov = w->hfov_deg;
		if (!cmd_key(c, "hfov") || c->argc != 2)
			return cmd_fail(c, "bad-argument",
					"%s looks through %s's eyes: set camera %s hfov=DEG only", w->name,
					w->eyes, w->name);
		if (read_hfov(c, &hfov) < 0)
			return -1;
		w->hfov_deg = hfov;
		eyeview_follow(&c->d->env, w);
		return 0;
	}
	if (cmd_key(c, "hfov"))
		return cmd_fail(c, "bad-argument", "hfov= is an eye view's (add view NAME eyes=FIG)");
	double eye[3], target[3], fovy = w->fovy_deg;
	int aim = cmd_key(c, "eye") || cmd_key(c, "target");
	if ((aim && (!cmd_key(c, "eye") || !cmd_key(c, "target"))) || (!aim && !cmd_key(c, "fovy")))
		return cmd_fail(c, "arity", "set camera VIEW [eye=X,Y,Z target=X,Y,Z] [fovy=DEG]");
	if (aim && (read_point(c, "eye", eye) < 0 || read_point(c, "target", target) < 0 ||
		    aim_ok(c, eye, target) < 0))
		return -1;
	if (read_fovy(c, &fovy) < 0)
		return -1;
	if (aim) {
		memcpy(w->eye, eye, sizeof eye);
		memcpy(w->target, target, sizeof target);
	}
	w->fovy_deg = fovy;
	return 0;
}

/*
 * sight=FIG|all|off [sight_length=LEN]: the manikins' sight cones drawn in
 * the view (eyeview.h) into w, checked first; a length only with sight on.
 * Returns 0, or -1 (w untouched) with the reply's error.
 */
static int
read_sight(struct cmd_ctx *c, struct env_view *w)
{
	const char *sight = cmd_key(c, "sight"), *len = cmd_key(c, "sight_length");
	const struct env *e = &c->d->env;
	double l = w->sight[0] ? w->sight_len : EYEVIEW_SIGHT_LEN;
	int fig = -1, sites[2];
	if (!sight && !len)
		return 0;
	if (sight && strcmp(sight, "off") && strcmp(sight, EYEVIEW_SIGHT_ALL)) {
		if ((fig = cmd_figure(c, sight)) < 0)
			return -1;
		if (eyeview_sites(e->fig[fig].model, ENV_EYES_BOTH, sites) < 0)
			return cmd_fail(c, "bad-argument", "%s has no eyes (eyeball_l.gaze, eyeball_r.gaze)",
					e->fig[fig].name);
	}
	int on = sight ? strcmp(sight, "off") != 0 : w->sight[0] != 0;
	if (len && !on)
		return cmd_fail(c, "bad-argument", "sight_length= draws sight cones: sight=FIG|all too");
	if (len && (words_number(len, UNIT_LENGTH, &l) < 0 || l < EYEVIEW_SIGHT_LEN_MIN ||
		    l > EYEVIEW_SIGHT_LEN_MAX))
		return cmd_fail(c, "bad-number", "sight_length: a length from %g to %g m",
				EYEVIEW_SIGHT_LEN_MIN, EYEVIEW_SIGHT_LEN_MAX);
	if (sight)
		snprintf(w->sight, sizeof w->sight, "%s", !on ? "" : fig >= 0 ? e->fig[fig].name : sight);
	w->sight_len = on ? l : 0;
	return 0;
}

/* a view's sight cones in a reply: what draws them and how long (null: none) */
static void
sight_reply(json_t *o, const struct env_view *v)
{
	json_object_set_new(o, "sight", json_string(v->sight[0] ? v->sight : "off"));
	json_object_set_new(o, "sight_length", v->sight[0] ? json_real(v->sight_len) : json_null());
}

/*
 * set view VIEW [tint=rula|reba|owas|strength|off] [loads=on|off] [cones=off|DEG,...]
 * [sight=FIG|all|off] [sight_length=LEN]:
 * the humans in the view coloured by that assessment's part scores
 * (view_tint.h), or in their own colours; the loads on the figures drawn as
 * arrows, or not; an eye view's cones marked about the line of sight
 */
int
cmd_set_view(struct cmd_ctx *c)
{
	static const char *const keys[] = { "tint", "loads", "cones", "sight", "sight_length" };
	int v = view_of(c, c->argv[0]);
	if (v < 0 || only_keys(c, 1, keys, 5) < 0)
		return -1;
	const char *tint = cmd_key(c, "tint"), *loads = cmd_key(c, "loads");
	const char *cones = cmd_key(c, "cones");
	int t = tint ? env_tint_find(tint) : -1;
	struct env_view *w = &c->d->env.view[v];
	double deg[ENV_VIEW_CONES];
	int ncones = 0;
	struct env_view sighted = *w; /* the sight read first, taken only when all is well */
	if (!tint && !loads && !cones && !cmd_key(c, "sight") && !cmd_key(c, "sight_length"))
		return cmd_fail(c, "arity", "set view VIEW [tint=rula|reba|owas|strength|off] "
					    "[loads=on|off] [cones=off|DEG,...] [sight=FIG|all|off] "
					    "[sight_length=LEN]");
	if (read_sight(c, &sighted) < 0)
		return -1;
	if (tint && t < 0)
		return cmd_fail(c, "bad-argument", "tint=rula|reba|owas|strength|off, not '%.40s'", tint);
	if (loads && strcmp(loads, "on") && strcmp(loads, "off"))
		return cmd_fail(c, "bad-argument", "loads=on|off, not '%.40s'", loads);
	if (cones && !w->eyes[0])
		return cmd_fail(c, "bad-argument", "cones= are an eye view's (add view NAME eyes=FIG)");
	if (cones && (ncones = eyeview_parse_cones(cones, deg)) < 0)
		return cmd_fail(c, "bad-argument", "cones=off or 1 to %d full angles from %g to %g "
				"degrees, e.g. 3,20,40,60", ENV_VIEW_CONES, EYEVIEW_CONE_MIN,
				EYEVIEW_CONE_MAX);
	memcpy(w->sight, sighted.sight, sizeof w->sight);
	w->sight_len = sighted.sight_len;
	if (tint)
		w->tint = t;
	if (loads)
		w->loads_hidden = !strcmp(loads, "off");
	if (cones) {
		memset(w->cones_deg, 0, sizeof w->cones_deg);
		memcpy(w->cones_deg, deg, (size_t)ncones * sizeof *deg);
		w->ncones = ncones;
	}
	json_object_set_new(c->result, "view", json_string(w->name));
	json_object_set_new(c->result, "tint", json_string(env_tint_str(w->tint)));
	json_object_set_new(c->result, "loads", json_string(w->loads_hidden ? "off" : "on"));
	if (w->eyes[0])
		json_object_set_new(c->result, "cones", cmd_vec(w->cones_deg, w->ncones));
	if (w->sight[0] || cmd_key(c, "sight") || cmd_key(c, "sight_length"))
		sight_reply(c->result, w); /* as cones: only where it concerns the view */
	return 0;
}

int
cmd_delete_view(struct cmd_ctx *c)
{
	int v = view_of(c, c->argv[0]);
	if (v < 0)
		return -1;
	memset(&c->d->env.view[v], 0, sizeof c->d->env.view[v]);
	/* a view gone from the screen: the others close up */
	struct env *e = &c->d->env;
	int k = 0;
	for (int i = 0; i < e->nlayout; i++)
		if (e->layout[i] != v)
			e->layout[k++] = e->layout[i];
	e->nlayout = k;
	return 0;
}

/* the layout's reply: the screen, and each view's tile on it */
static int
layout_reply(struct cmd_ctx *c)
{
	const struct env *e = &c->d->env;
	json_object_set_new(c->result, "screen",
			    json_pack("[ii]", c->d->screen_w, c->d->screen_h));
	json_t *tiles = json_array();
	struct tiles T;
	if (e->nlayout && tiles_make(&T, c->d->screen_w, c->d->screen_h, SCENE_BAND,
				     e->nlayout) == 0)
		for (int i = 0; i < e->nlayout; i++)
			json_array_append_new(tiles, json_pack("{sssisisisi}", "view",
							       e->view[e->layout[i]].name, "x", T.t[i].x,
							       "y", T.t[i].y, "width", T.t[i].w,
							       "height", T.t[i].h));
	json_object_set_new(c->result, "tiles", tiles);
	return 0;
}

/*
 * layout VIEW... | layout off: the views tiled on the kiosk's screen (the
 * framebuffer's, or --screen), each resized to its tile; off: the first
 * view alone, at the size it has.
 */
int
cmd_layout(struct cmd_ctx *c)
{
	struct env *e = &c->d->env;
	if (c->argc == 1 && !strcmp(c->argv[0], "off")) {
		e->nlayout = 0;
		return layout_reply(c);
	}
	if (c->argc > ENV_MAX_VIEWS)
		return cmd_fail(c, "bad-argument", "at most %d views", ENV_MAX_VIEWS);
	int slots[ENV_MAX_VIEWS];
	for (int i = 0; i < c->argc; i++) {
		if ((slots[i] = view_of(c, c->argv[i])) < 0)
			return -1;
		for (int k = 0; k < i; k++)
			if (slots[k] == slots[i])
				return cmd_fail(c, "bad-argument", "view %s named twice", c->argv[i]);
	}
	struct tiles T;
	if (tiles_make(&T, c->d->screen_w, c->d->screen_h, SCENE_BAND, c->argc) < 0)
		return cmd_fail(c, "bad-argument", "%d views do not fit a %dx%d screen", c->argc,
				c->d->screen_w, c->d->screen_h);
	for (int i = 0; i < c->argc; i++) {
		e->layout[i] = slots[i];
		e->view[slots[i]].width = T.t[i].w;
		e->view[slots[i]].height = T.t[i].h;
	}
	e->nlayout = c->argc;
	eyeview_follow_all(e); /* an eye view's height changed: its vertical field follows */
	return layout_reply(c);
}

int
cmd_get_layout(struct cmd_ctx *c)
{
	const struct env *e = &c->d->env;
	json_t *views = json_array();
	for (int i = 0; i < e->nlayout; i++)
		json_array_append_new(views, json_string(e->view[e->layout[i]].name));
	json_object_set_new(c->result, "views", views);
	return layout_reply(c);
}

int
cmd_list_views(struct cmd_ctx *c)
{
	eyeview_follow_all(&c->d->env); /* the eye views where the eyes are now */
	json_t *list = json_array();
	for (int i = 0; i < ENV_MAX_VIEWS; i++) {
		const struct env_view *v = &c->d->env.view[i];
		if (!v->used)
			continue;
		json_t *o = json_object();
		json_object_set_new(o, "name", json_string(v->name));
		json_object_set_new(o, "width", json_integer(v->width));
		json_object_set_new(o, "height", json_integer(v->height));
		json_object_set_new(o, "eye", cmd_vec(v->eye, 3));
		json_object_set_new(o, "target", cmd_vec(v->target, 3));
		json_object_set_new(o, "fovy", json_real(v->fovy_deg));
		json_object_set_new(o, "icons", json_boolean(v->icons));
		json_object_set_new(o, "tint", json_string(env_tint_str(v->tint)));
		json_object_set_new(o, "loads", json_string(v->loads_hidden ? "off" : "on"));
		if (v->sight[0]) /* only when drawn: a view's list reads as before without */
			sight_reply(o, v);
		if (v->eyes[0]) {
			json_object_set_new(o, "eyes", json_string(v->eyes));
			json_object_set_new(o, "which", json_string(eyeview_which_str(v->eyes_which)));
			json_object_set_new(o, "hfov", json_real(v->hfov_deg));
			json_object_set_new(o, "cones", cmd_vec(v->cones_deg, v->ncones));
		}
		json_array_append_new(list, o);
	}
	json_object_set_new(c->result, "views", list);
	return 0;
}

static char *
base64(const uint8_t *p, size_t n)
{
	static const char a[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
	char *out = malloc(4 * ((n + 2) / 3) + 1), *o = out;
	if (!out)
		return NULL;
	for (size_t i = 0; i < n; i += 3) {
		uint32_t v = (uint32_t)p[i] << 16 | (i + 1 < n ? (uint32_t)p[i + 1] << 8 : 0) |
			     (i + 2 < n ? p[i + 2] : 0);
		*o++ = a[v >> 18 & 63];
		*o++ = a[v >> 12 & 63];
		*o++ = i + 1 < n ? a[v >> 6 & 63] : '=';
		*o++ = i + 2 < n ? a[v & 63] : '=';
	}
	*o = 0;
	return out;
}

static int reply_png(struct cmd_ctx *c, const struct frame *f, const char *to, const char *path);

int
cmd_render_view(struct cmd_ctx *c)
{
	static const char *const keys[] = { "to" };
	int v = view_of(c, c->argv[0]);
	if (v < 0 || only_keys(c, 1, keys, 1) < 0)
		return -1;
	const char *to = cmd_key(c, "to");
	char path[4096], err[256];
	if (to && cmd_path(c, to, 1, path, sizeof path) < 0)
		return -1;
	if (!c->d->render_view)
		return cmd_fail(c, "internal", "this daemon cannot render");
	const struct frame *f;
	if (c->d->render_view(c->d, v, &f, err, sizeof err) < 0)
		return cmd_fail(c, "internal", "rendering failed: %s", err);
	return reply_png(c, f, to, path);
}

/* render screen [to=PATH]: the kiosk's screen as the framebuffer shows it */
int
cmd_render_screen(struct cmd_ctx *c)
{
	static const char *const keys[] = { "to" };
	if (only_keys(c, 0, keys, 1) < 0)
		return -1;
	const char *to = cmd_key(c, "to");
	char path[4096], err[256];
	if (to && cmd_path(c, to, 1, path, sizeof path) < 0)
		return -1;
	if (!c->d->render_screen)
		return cmd_fail(c, "internal", "this daemon cannot render");
	const struct frame *f;
	if (c->d->render_screen(c->d, &f, err, sizeof err) < 0)
		return cmd_fail(c, "not-found", "%s", err);
	return reply_png(c, f, to, path);
}

/* a picture as the reply: a PNG in base64, or written to path (to, as the client named it) */
static int
reply_png(struct cmd_ctx *c, const struct frame *f, const char *to, const char *path)
{
	char err[256];
	static struct sink_png_encoder enc; /* reused: the loop is single-threaded */
	static int ready;
	if (!ready) {
		sink_png_encoder_init(&enc);
		ready = 1;
	}
	if (sink_png_encode(&enc, f, err, sizeof err) < 0)
		return cmd_fail(c, "internal", "PNG: %s", err);
	if (to) {
		if (statefile_write(path, enc.data, enc.len) < 0)
			return cmd_fail(c, "io", "%.60s: %s", to, strerror(errno));
		json_object_set_new(c->result, "path", json_string(to));
	} else {
		char *b64 = base64(enc.data, enc.len);
		if (!b64)
			return cmd_fail(c, "internal", "out of memory");
		json_object_set_new(c->result, "png", json_string(b64));
		free(b64);
	}
	json_object_set_new(c->result, "width", json_integer(f->width));
	json_object_set_new(c->result, "height", json_integer(f->height));
	return 0;
}
