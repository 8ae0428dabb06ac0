/*
 * cmd_report.c - export assessment FIG PATH [view=VIEW]: a figure's RULA,
 * REBA and OWAS as the one-page HTML report of assess_report.h, with its
 * picture, written whole into the state directory.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "assess/reba.h"
#include "assess/rula.h"
#include "daemon/assess_live.h"
#include "daemon/assess_report.h"
#include "daemon/cmd_ctx.h"
#include "daemon/manikin.h"
#include "draw/sink.h"

/* the report's picture when no view is named: portrait, the figure whole */
#define REPORT_PICTURE_W 480
#define REPORT_PICTURE_H 600
#define REPORT_FOVY_DEG 30.0

/*
 * A camera for figure slot fig alone: its segments' bounding box (with a
 * margin for their flesh) seen from its front and 35 deg to its left, 12
 * deg from above, near enough to fill the picture. The figure's front is
 * its pelvis's +z (a human faces +z standing at rest).
 */
static void
figure_camera(const struct env_figure *f, struct env_view *dest)
{
	const struct model *m = f->model;
	const struct state *s = f->state;
	double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
	for (int g = 0; g < m->nseg; g++)
		for (int k = 0; k < 3; k++) {
			lo[k] = fmin(lo[k], s->seg_xf[g].p[k]);
			hi[k] = fmax(hi[k], s->seg_xf[g].p[k]);
		}
	const double margin = 0.15; /* a segment's origin is at its joint: the body reaches past it */
	double c[3], half[3];
	for (int k = 0; k < 3; k++) {
		lo[k] -= margin;
		hi[k] += margin;
		c[k] = (lo[k] + hi[k]) / 2;
		half[k] = (hi[k] - lo[k]) / 2;
	}
	int pelvis = model_find_segment(m, "pelvis");
	const double *r = s->seg_xf[pelvis >= 0 ? pelvis : 0].r;
	double fwd[3] = { r[2], 0, r[8] }, n = hypot(fwd[0], fwd[2]);
	if (n < 1e-6) { /* lying face up or down: look along world +z */
		fwd[0] = 0;
		fwd[2] = 1;
	} else {
		fwd[0] /= n;
		fwd[2] /= n;
	}
	/* the figure's left, y up: fwd x ... turned 35 deg about y towards it */
	double a = 35 * M_PI / 180, el = 12 * M_PI / 180;
	double dir[3] = { fwd[0] * cos(a) + fwd[2] * sin(a), 0, fwd[2] * cos(a) - fwd[0] * sin(a) };
	double t = tan(REPORT_FOVY_DEG * M_PI / 180 / 2), aspect = (double)REPORT_PICTURE_W / REPORT_PICTURE_H;
	double radius = sqrt(half[0] * half[0] + half[2] * half[2]);
	double dist = fmax(half[1] / t, radius / (t * aspect)) + radius;
	memset(dest, 0, sizeof *dest);
	dest->used = 1;
	snprintf(dest->name, sizeof dest->name, "report");
	dest->width = REPORT_PICTURE_W;
	dest->height = REPORT_PICTURE_H;
	dest->fovy_deg = REPORT_FOVY_DEG;
	for (int k = 0; k < 3; k++)
		dest->target[k] = c[k];
	dest->eye[0] = c[0] + dist * cos(el) * dir[0];
	dest->eye[1] = c[1] + dist * sin(el);
	dest->eye[2] = c[2] + dist * cos(el) * dir[2];
}

static void
input(struct assess_report *r, const char *key, const char *note, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));

static void
input(struct assess_report *r, const char *key, const char *note, const char *fmt, ...)
{
	if (r->ninputs >= ASSESS_REPORT_MAX_INPUTS)
		return;
	struct assess_report_input *in = &r->input[r->ninputs++];
	snprintf(in->key, sizeof in->key, "%s", key);
	snprintf(in->note, sizeof in->note, "%s", note);
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(in->value, sizeof in->value, fmt, ap);
	va_end(ap);
}

static const char *
yes_no(int v)
{
	return v ? "yes" : "no";
}

/* what the live scores were made with that the posture does not show (assess_live.h) */
static void
live_inputs(struct assess_report *r, struct daemon *d, int fig, const struct assess_live_fig *live)
{
	struct rula_options ro = rula_options_default();
	struct reba_options bo = reba_options_default();
	static const char *const sides[] = { "left", "right", "worse" };
	static const char *const couplings[] = { "good", "fair", "poor", "unacceptable" };
	input(r, "side", "the default: both arms scored, the worse kept (RULA, REBA)", "%s",
	      ro.side >= 0 && ro.side <= 2 ? sides[ro.side] : "?");
	input(r, "load", "the mass of the objects the hands hold (grab)", "%.2f kg", live->load_kg);
	input(r, "seated", "the figure's behaviour (set behavior seated=...)", "%s",
	      yes_no(assess_live_seated(&d->env, fig)));
	input(r, "static", "RULA muscle use and force/load: the default", "%s",
	      yes_no(ro.static_posture));
	input(r, "repeated", "RULA muscle use and force/load: the default", "%s", yes_no(ro.repeated));
	input(r, "arm_supported", "RULA, REBA upper arm -1: the default", "%s",
	      yes_no(ro.arm_supported || bo.arm_supported));
	input(r, "legs_supported", "RULA legs when seated: the default", "%s",
	      yes_no(ro.legs_supported));
	input(r, "shock", "RULA force 3, REBA load +1: the default", "%s", yes_no(ro.shock || bo.shock));
	input(r, "coupling", "REBA: the default", "%s",
	      bo.coupling >= 0 && bo.coupling <= 3 ? couplings[bo.coupling] : "?");
	input(r, "activity", "REBA activity items that hold: the default", "%d", bo.activity);
}

/* the calendar time as the report writes it; "unknown" without a calendar */
static void
report_date(struct daemon *d, char *dest, size_t len)
{
	struct tm tm;
	time_t t = d->calendar_s ? (time_t)d->calendar_s(d) : 0;
	if (!d->calendar_s || !gmtime_r(&t, &tm) || !strftime(dest, len, "%Y-%m-%d %H:%M UTC", &tm))
		snprintf(dest, len, "unknown");
}

int
cmd_export_assessment(struct cmd_ctx *c)
{
	struct daemon *d = c->d;
	int fig = cmd_figure(c, c->argv[0]);
	if (fig < 0)
		return -1;
	const char *rel = c->argv[1], *name = strrchr(rel, '/');
	name = name ? name + 1 : rel;
	size_t n = strlen(name);
	if (n <= 5 || strcmp(name + n - 5, ".html"))
		return cmd_fail(c, "bad-argument", "'%.60s' must be a file name ending in .html", rel);
	const char *view = NULL;
	for (int i = 2; i < c->argc; i++) {
		if (!words_is_key(c->argv[i], "view"))
			return cmd_fail(c, "bad-argument", "unexpected '%.60s'", c->argv[i]);
		view = c->argv[i] + 5;
	}
	int v = view ? env_find_view(&d->env, view) : -1;
	if (view && v < 0)
		return cmd_fail(c, "not-found", "no view '%.60s'", view);
	char path[4096], err[512];
	if (cmd_path(c, rel, 1, path, sizeof path) < 0)
		return -1;
	const struct assess_live_fig *live = assess_live_of(d, fig);
	if (!live || !live->valid)
		return cmd_fail(c, "bad-argument", "%s", assess_live_why(d, fig));
	if (!d->render_picture)
		return cmd_fail(c, "internal", "this daemon cannot render");

	/* the picture: the named view's camera and tint, else the figure's own camera */
	struct env_view pv;
	if (v >= 0)
		pv = d->env.view[v];
	else
		figure_camera(&d->env.fig[fig], &pv);
	const struct frame *f;
	if (d->render_picture(d, &pv, v >= 0 ? -1 : fig, &f, err, sizeof err) < 0)
		return cmd_fail(c, "internal", "rendering failed: %s", err);
	static struct sink_png_encoder enc; /* reused: the loop is single-threaded */
	static int ready;
	if (!ready) {
		sink_png_encoder_init(&enc);
		ready = 1;
	}
	if (sink_png_encode(&enc, f, err, sizeof err) < 0)
		return cmd_fail(c, "internal", "PNG: %s", err);

	static struct assess_report rep; /* large (its inputs); the loop is single-threaded */
	memset(&rep, 0, sizeof rep);
	const struct env_figure *ef = &d->env.fig[fig];
	json_t *about = json_object();
	manikin_json(ef, about);
	rep.figure = ef->name;
	rep.about = about;
	rep.angles = &live->angles;
	for (int m = 0; m < ASSESS_NMETHODS; m++)
		rep.res[m] = &live->res[m];
	rep.cfg = daemon_assess_config(d);
	live_inputs(&rep, d, fig, live);
	rep.png = enc.data;
	rep.png_len = enc.len;
	rep.png_w = f->width;
	rep.png_h = f->height;
	report_date(d, rep.date, sizeof rep.date);
	int rc = assess_report_write(&rep, path, err, sizeof err);
	json_decref(about);
	if (rc < 0)
		return cmd_fail(c, "io", "%s", err);
	json_object_set_new(c->result, "path", json_string(rel));
	json_object_set_new(c->result, "width", json_integer(f->width));
	json_object_set_new(c->result, "height", json_integer(f->height));
	for (int m = 0; m < ASSESS_NMETHODS; m++)
		json_object_set_new(c->result, m == ASSESS_RULA ? "rula" : m == ASSESS_REBA ? "reba" : "owas",
				    json_integer(live->res[m].score));
	return 0;
}
