/* eyeview.c - the camera of a view through a manikin's eyes */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pose/eyeview.h"

static const char *const which_names[] = { "both", "left", "right" };

const char *
eyeview_which_str(int which)
{
	return which >= 0 && which < 3 ? which_names[which] : "?";
}

int
eyeview_which_find(const char *name)
{
	for (int i = 0; i < 3; i++)
		if (!strcmp(which_names[i], name))
			return i;
	return -1;
}

double
eyeview_default_hfov(int which)
{
	return which == ENV_EYES_BOTH ? EYEVIEW_HFOV_BOTH : EYEVIEW_HFOV_ONE;
}

int
eyeview_default_cones(double dest[ENV_VIEW_CONES])
{
	static const double d[] = { EYEVIEW_CONE_CENTRAL, EYEVIEW_CONE_READING,
				    EYEVIEW_CONE_SYMBOLS, EYEVIEW_CONE_COLOUR };
	_Static_assert(sizeof d / sizeof d[0] == ENV_VIEW_CONES, "a default for every cone");
	memcpy(dest, d, sizeof d);
	return ENV_VIEW_CONES;
}

int
eyeview_parse_cones(const char *s, double dest[ENV_VIEW_CONES])
{
	if (!strcmp(s, "off"))
		return 0;
	int n = 0;
	for (;;) {
		char *end;
		errno = 0;
		double d = strtod(s, &end);
		if (end == s || errno || n == ENV_VIEW_CONES || !(d >= EYEVIEW_CONE_MIN) ||
		    d > EYEVIEW_CONE_MAX)
			return -1;
		dest[n++] = d;
		if (!*end)
			return n;
		if (*end != ',')
			return -1;
		s = end + 1;
	}
}

int
eyeview_cones_default(const struct env_view *v)
{
	double d[ENV_VIEW_CONES];
	int n = eyeview_default_cones(d);
	return v->ncones == n && !memcmp(v->cones_deg, d, sizeof d);
}

int
eyeview_sites(const struct model *m, int which, int sites[2])
{
	int l = model_find_site(m, "eyeball_l.gaze"), r = model_find_site(m, "eyeball_r.gaze");
	if (l < 0 || r < 0)
		return -1;
	sites[0] = which == ENV_EYES_RIGHT ? r : l;
	sites[1] = which == ENV_EYES_LEFT ? l : r;
	return 0;
}

int
eyeview_camera(const struct env *e, int fig, int which, double eye[3], double dir[3])
{
	const struct env_figure *f = &e->fig[fig];
	int s[2];
	if (!f->gen || eyeview_sites(f->model, which, s) < 0)
		return -1;
	const struct xform *a = &f->state->site_xf[s[0]], *b = &f->state->site_xf[s[1]];
	/* the line of sight is the site's +z: the rotation's third column (row-major) */
	for (int i = 0; i < 3; i++) {
		eye[i] = s[0] == s[1] ? a->p[i] : 0.5 * (a->p[i] + b->p[i]);
		dir[i] = a->r[3 * i + 2] + b->r[3 * i + 2];
	}
	double n = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
	if (!(n > 1e-12)) /* both eyes turned apart by 180 degrees: no mean line of sight */
		return -1;
	for (int i = 0; i < 3; i++)
		dir[i] /= n;
	return 0;
}

double
eyeview_fovy(double hfov_deg, int w, int h)
{
	double t = tan(hfov_deg * M_PI / 360) * (double)h / (double)w;
	double fovy = 360 / M_PI * atan(t);
	return fovy > ENV_VIEW_FOVY_MAX ? ENV_VIEW_FOVY_MAX : fovy;
}

int
eyeview_follow(const struct env *e, struct env_view *v)
{
	if (!v->used || !v->eyes[0])
		return 0;
	int fig = env_find_figure(e, v->eyes);
	double eye[3], dir[3];
	if (fig < 0 || eyeview_camera(e, fig, v->eyes_which, eye, dir) < 0)
		return 0;
	for (int i = 0; i < 3; i++) {
		v->eye[i] = eye[i];
		v->target[i] = eye[i] + EYEVIEW_AIM * dir[i];
	}
	if (v->width > 0 && v->height > 0)
		v->fovy_deg = eyeview_fovy(v->hfov_deg, v->width, v->height);
	return 1;
}

void
eyeview_follow_all(struct env *e)
{
	for (int i = 0; i < ENV_MAX_VIEWS; i++)
		eyeview_follow(e, &e->view[i]);
}

int
eyeview_figure_cones(const struct env *e, int fig, double dest[ENV_VIEW_CONES])
{
	for (int i = 0; i < ENV_MAX_VIEWS; i++) {
		const struct env_view *v = &e->view[i];
		if (v->used && v->eyes[0] && !strcmp(v->eyes, e->fig[fig].name)) {
			memcpy(dest, v->cones_deg, sizeof v->cones_deg);
			return v->ncones;
		}
	}
	return eyeview_default_cones(dest);
}

int
eyeview_draws_sight(const struct env *e, const struct env_view *v, int fig)
{
	const struct env_figure *f = &e->fig[fig];
	if (!v->used || !v->sight[0] || !f->gen || (v->eyes[0] && !strcmp(v->eyes, f->name)))
		return 0;
	return !strcmp(v->sight, EYEVIEW_SIGHT_ALL) || !strcmp(v->sight, f->name);
}
