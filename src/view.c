/*
 * view.c - cameras and the abstract draw list (see view.h). No GL here:
 * this file only fills arrays that render.c draws.
 */
#include <cglm/cglm.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view.h"

/* icon colours */
static const uint8_t C_AXIS[3][4] = { { 230, 60, 50, 255 }, { 40, 185, 70, 255 },
				      { 50, 110, 240, 255 } };
static const uint8_t C_AXIS_NEG[3][4] = { { 240, 150, 140, 255 }, { 140, 215, 150, 255 },
					  { 140, 170, 245, 255 } };
static const uint8_t C_WHEEL[4] = { 250, 200, 40, 255 };
static const uint8_t C_GREEN[4] = { 40, 200, 70, 255 };
static const uint8_t C_RED[4] = { 225, 45, 40, 255 };
static const uint8_t C_GOAL[4] = { 235, 120, 20, 255 };
static const uint8_t C_BAND[4] = { 255, 255, 255, 100 };
static const uint8_t C_WHITE[4] = { 255, 255, 255, 255 };
static const uint8_t C_BLACK[4] = { 0, 0, 0, 255 };

#define ICON_WIDTH 2.0f  /* line width of icons, pixels before icon_scale */
#define THICK_WIDTH 3.5f /* their emphasised lines */

static uint8_t *
with_alpha(const uint8_t c[4], uint8_t a, uint8_t dest[4])
{
	memcpy(dest, c, 3);
	dest[3] = a;
	return dest;
}

/* ---- small vector helpers ------------------------------------------------ */

static void
v_set(double d[3], double x, double y, double z)
{
	d[0] = x, d[1] = y, d[2] = z;
}

static double
v_dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void
v_cross(const double a[3], const double b[3], double d[3])
{
	double t[3] = { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
			a[0] * b[1] - a[1] * b[0] };
	memcpy(d, t, sizeof t);
}

static double
v_norm(const double a[3])
{
	return sqrt(v_dot(a, a));
}

/* d = a / |a|; returns |a| (d untouched when 0) */
static double
v_unit(const double a[3], double d[3])
{
	double l = v_norm(a);
	if (l > 0)
		v_set(d, a[0] / l, a[1] / l, a[2] / l);
	return l;
}

/* d = a + s * b */
static void
v_madd(const double a[3], double s, const double b[3], double d[3])
{
	v_set(d, a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]);
}

/* a unit vector perpendicular to unit a */
static void
v_perp(const double a[3], double d[3])
{
	double t[3] = { 1, 0, 0 };
	if (fabs(a[0]) > 0.8)
		v_set(t, 0, 1, 0);
	v_cross(a, t, d);
	v_unit(d, d);
}

/* column j of a row-major rotation */
static void
r_col(const double r[9], int j, double d[3])
{
	v_set(d, r[j], r[3 + j], r[6 + j]);
}

/* ---- cameras --------------------------------------------------------------- */

void
view_camera_default(struct camera *dest)
{
	memset(dest, 0, sizeof *dest);
	xform_identity(&dest->xf);
	v_set(dest->xf.p, 0, 1, 4);
	dest->vrd = 4;
	dest->fovy = 40 * M_PI / 180;
	dest->znear = 0.05;
	dest->zfar = 200;
}

int
view_camera_aim(struct camera *c, const double eye[3], const double target[3])
{
	double z[3] = { eye[0] - target[0], eye[1] - target[1], eye[2] - target[2] }, x[3], y[3];
	double d = v_norm(z);
	if (!(d > 0) || !isfinite(d))
		return -1;
	v_set(z, z[0] / d, z[1] / d, z[2] / d);
	/* x = world up x z: horizontal by construction */
	v_set(x, z[2], 0, -z[0]);
	if (v_unit(x, x) < 1e-9) {
		/* straight up or down: keep the old heading, made horizontal */
		v_set(x, c->xf.r[0], 0, c->xf.r[6]);
		if (v_unit(x, x) < 1e-9)
			v_set(x, 1, 0, 0);
	}
	v_cross(z, x, y);
	for (int i = 0; i < 3; i++) {
		c->xf.r[3 * i + 0] = x[i];
		c->xf.r[3 * i + 1] = y[i];
		c->xf.r[3 * i + 2] = z[i];
		c->xf.p[i] = eye[i];
	}
	c->vrd = d;
	return 0;
}

void
view_camera_vrp(const struct camera *c, double dest[3])
{
	double z[3];
	r_col(c->xf.r, 2, z);
	v_madd(c->xf.p, -c->vrd, z, dest);
}

void
view_camera_view_matrix(const struct camera *c, float dest[16])
{
	struct xform inv;
	xform_inv(&c->xf, &inv);
	memset(dest, 0, sizeof(float) * 16);
	for (int i = 0; i < 3; i++) {
		for (int j = 0; j < 3; j++)
			dest[4 * j + i] = (float)inv.r[3 * i + j];
		dest[12 + i] = (float)inv.p[i];
	}
	dest[15] = 1;
}

void
view_camera_proj_matrix(const struct camera *c, double aspect, float dest[16])
{
	mat4 p;
	glm_perspective((float)c->fovy, (float)aspect, (float)c->znear, (float)c->zfar, p);
	memcpy(dest, p, sizeof p);
}

int
view_project(const struct camera *c, int w, int h, const double p[3], double dest[2])
{
	/* camera coordinates: R^T (p - eye) */
	double d[3] = { p[0] - c->xf.p[0], p[1] - c->xf.p[1], p[2] - c->xf.p[2] }, pc[3];
	for (int j = 0; j < 3; j++)
		pc[j] = c->xf.r[j] * d[0] + c->xf.r[3 + j] * d[1] + c->xf.r[6 + j] * d[2];
	if (-pc[2] <= c->znear)
		return 0;
	double f = 1 / tan(c->fovy / 2), aspect = (double)w / h;
	double nx = f / aspect * pc[0] / -pc[2], ny = f * pc[1] / -pc[2];
	dest[0] = (nx + 1) / 2 * w;
	dest[1] = (1 - ny) / 2 * h;
	return 1;
}

void
view_mouse_line(const struct camera *c, int w, int h, double px, double py, double origin[3],
		double dir[3])
{
	double f = 1 / tan(c->fovy / 2), aspect = (double)w / h;
	double nx = 2 * px / w - 1, ny = 1 - 2 * py / h;
	double dc[3] = { nx * aspect / f, ny / f, -1 };
	xform_rotate(&c->xf, dc, dir);
	v_unit(dir, dir);
	memcpy(origin, c->xf.p, sizeof(double) * 3);
}

/* ---- the draw list ------------------------------------------------------- */

struct drawlist *
view_drawlist_make(void)
{
	struct drawlist *dl = calloc(1, sizeof *dl);
	if (dl) {
		struct camera c;
		view_camera_default(&c);
		view_begin(dl, &c, 640, 480);
	}
	return dl;
}

void
view_drawlist_free(struct drawlist *dl)
{
	free(dl);
}

void
view_begin(struct drawlist *dl, const struct camera *cam, int w, int h)
{
	dl->cam = *cam;
	dl->width = w;
	dl->height = h;
	static const float top[3] = { 0.46f, 0.56f, 0.70f }, bottom[3] = { 0.83f, 0.85f, 0.88f };
	static const float floor_rgb[3] = { 0.66f, 0.67f, 0.68f };
	memcpy(dl->bg_top, top, sizeof top);
	memcpy(dl->bg_bottom, bottom, sizeof bottom);
	memcpy(dl->floor_rgb, floor_rgb, sizeof floor_rgb);
	dl->floor = 1;
	dl->grid = 0.5f;
	/* key light: above, in front and to the left of a figure facing +z */
	float l[3] = { 0.35f, 1.0f, 0.45f }, n = sqrtf(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
	for (int i = 0; i < 3; i++)
		dl->light[i] = l[i] / n;
	dl->icon_scale = h > 480 ? (float)h / 480 : 1;
	dl->ninst = dl->nvert = dl->nbatch = dl->ntext = 0;
	dl->dropped = 0;
}

int
view_add_instance(struct drawlist *dl, int mesh, const float mat[16], const float rgba[4],
		  int shadow)
{
	if (dl->ninst >= VIEW_MAX_INST) {
		dl->dropped++;
		return -1;
	}
	struct view_instance *in = &dl->inst[dl->ninst];
	in->mesh = mesh;
	memcpy(in->mat, mat, sizeof in->mat);
	memcpy(in->rgba, rgba, sizeof in->rgba);
	in->shadow = (unsigned char)(shadow != 0);
	return dl->ninst++;
}

/* column-major matrix of x with its local axes scaled by s */
static void
mat_from_xform(const struct xform *x, const double s[3], float dest[16])
{
	for (int j = 0; j < 3; j++) {
		for (int i = 0; i < 3; i++)
			dest[4 * j + i] = (float)(x->r[3 * i + j] * s[j]);
		dest[4 * j + 3] = 0;
		dest[12 + j] = (float)x->p[j];
	}
	dest[15] = 1;
}

/* highest world y of a unit mesh of half-extent ext placed by mat */
static double
top_y(const float mat[16], double ext)
{
	return mat[13] + ext * (fabs(mat[1]) + fabs(mat[5]) + fabs(mat[9]));
}

/* an instance of a unit mesh at frame x scaled by s; shadows only above the floor */
static void
add_unit(struct drawlist *dl, int mesh, const struct xform *x, const double s[3],
	 const float rgba[4], double ext)
{
	float mat[16];
	mat_from_xform(x, s, mat);
	view_add_instance(dl, mesh, mat, rgba, top_y(mat, ext) > 0.005);
}

int
view_add_figure(struct drawlist *dl, const struct model *m, const struct state *s, int mesh_base)
{
	int before = dl->ninst;
	for (int g = 0; g < m->ngeom; g++) {
		int seg = m->geom_seg[g];
		const double *sz = &m->geom_size[3 * g];
		const float *rgba = &m->seg_rgba[4 * seg];
		struct xform loc, x;
		mathx_quat_to_mat(&m->geom_quat[4 * g], loc.r);
		memcpy(loc.p, &m->geom_pos[3 * g], sizeof loc.p);
		xform_mul(&s->seg_xf[seg], &loc, &x);
		switch ((enum geom_kind)m->geom_kind[g]) {
		case GEOM_BOX:
			add_unit(dl, VIEW_MESH_BOX, &x, sz, rgba, 0.5);
			break;
		case GEOM_ELLIPSOID:
			add_unit(dl, VIEW_MESH_SPHERE, &x, sz, rgba, 1);
			break;
		case GEOM_CYLINDER: {
			double c[3] = { sz[0], sz[1], sz[0] };
			add_unit(dl, VIEW_MESH_CYLINDER, &x, c, rgba, 1);
			break;
		}
		case GEOM_CAPSULE: {
			/* a tube and two hemispheres, the lower one turned over */
			double c[3] = { sz[0], sz[1], sz[0] }, r[3] = { sz[0], sz[0], sz[0] };
			struct xform cap = x;
			add_unit(dl, VIEW_MESH_TUBE, &x, c, rgba, 1);
			for (int i = 0; i < 3; i++)
				cap.p[i] = x.p[i] + x.r[3 * i + 1] * sz[1] / 2;
			add_unit(dl, VIEW_MESH_HEMISPHERE, &cap, r, rgba, 1);
			for (int i = 0; i < 3; i++) {
				cap.p[i] = x.p[i] - x.r[3 * i + 1] * sz[1] / 2;
				cap.r[3 * i + 1] = -x.r[3 * i + 1];
				cap.r[3 * i + 2] = -x.r[3 * i + 2];
			}
			add_unit(dl, VIEW_MESH_HEMISPHERE, &cap, r, rgba, 1);
			break;
		}
		case GEOM_MESH: {
			float mat[16];
			mat_from_xform(&x, sz, mat);
			view_add_instance(dl, mesh_base + m->geom_mesh[g], mat, rgba, 1);
			break;
		}
		}
	}
	return dl->ninst - before;
}

/* ---- lines, triangles and text --------------------------------------------- */

void
view_batch_begin(struct drawlist *dl, enum view_prim prim, enum view_space space, float width,
		 int xray)
{
	struct view_batch *b = dl->nbatch ? &dl->batch[dl->nbatch - 1] : NULL;
	if (b && b->prim == prim && b->space == space && b->width == width && b->xray == xray)
		return;
	if (b && b->count == 0) {
		/* reuse an empty batch */
	} else if (dl->nbatch >= VIEW_MAX_BATCH) {
		dl->dropped++;
		return;
	} else {
		b = &dl->batch[dl->nbatch++];
	}
	b->prim = (uint8_t)prim;
	b->space = (uint8_t)space;
	b->xray = (uint8_t)(xray != 0);
	b->width = width;
	b->first = dl->nvert;
	b->count = 0;
}

void
view_vertex(struct drawlist *dl, const double p[3], const uint8_t c[4])
{
	if (!dl->nbatch || dl->nvert >= VIEW_MAX_VERT) {
		dl->dropped++;
		return;
	}
	struct view_vertex *v = &dl->vert[dl->nvert++];
	for (int i = 0; i < 3; i++)
		v->p[i] = (float)p[i];
	memcpy(v->c, c, 4);
	dl->batch[dl->nbatch - 1].count++;
}

void
view_line(struct drawlist *dl, const double a[3], const double b[3], const uint8_t c[4])
{
	if (dl->nvert + 2 > VIEW_MAX_VERT) {
		dl->dropped++;
		return;
	}
	view_vertex(dl, a, c);
	view_vertex(dl, b, c);
}

void
view_triangle(struct drawlist *dl, const double a[3], const double b[3], const double c[3],
	      const uint8_t rgba[4])
{
	if (dl->nvert + 3 > VIEW_MAX_VERT) {
		dl->dropped++;
		return;
	}
	view_vertex(dl, a, rgba);
	view_vertex(dl, b, rgba);
	view_vertex(dl, c, rgba);
}

int
view_add_text(struct drawlist *dl, double x, double y, const char *text, const uint8_t c[4],
	      enum view_align align)
{
	if (dl->ntext >= VIEW_MAX_TEXT) {
		dl->dropped++;
		return -1;
	}
	struct view_text *t = &dl->text[dl->ntext++];
	t->x = (float)x;
	t->y = (float)y;
	memcpy(t->c, c, 4);
	t->align = (uint8_t)align;
	snprintf(t->s, sizeof t->s, "%s", text);
	return 0;
}

/* text centred on the projection of a world point, when it is in view */
static void
world_label(struct drawlist *dl, const double p[3], const char *text, const uint8_t c[4])
{
	double px[2];
	if (view_project(&dl->cam, dl->width, dl->height, p, px))
		view_add_text(dl, px[0], px[1] + VIEW_FONT_PX * 0.35, text, c, VIEW_ALIGN_CENTER);
}

/* a circle of radius r about unit axis a through c, n segments, from unit u */
static void
circle(struct drawlist *dl, const double c[3], const double a[3], const double u[3], double r,
       int n, const uint8_t col[4])
{
	double v[3], p0[3], p1[3];
	v_cross(a, u, v);
	for (int i = 0; i < n; i++) {
		double t0 = 2 * M_PI * i / n, t1 = 2 * M_PI * (i + 1) / n;
		for (int k = 0; k < 3; k++) {
			p0[k] = c[k] + r * (cos(t0) * u[k] + sin(t0) * v[k]);
			p1[k] = c[k] + r * (cos(t1) * u[k] + sin(t1) * v[k]);
		}
		view_line(dl, p0, p1, col);
	}
}

/* ---- icons ------------------------------------------------------------------- */

void
view_add_frame_icon(struct drawlist *dl, const struct xform *xf, double size, int labels)
{
	static const char *const pos[3] = { "x", "y", "z" }, *const neg[3] = { "-x", "-y", "-z" };
	double a[3], e[3];
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, THICK_WIDTH, 1);
	for (int k = 0; k < 3; k++) {
		r_col(xf->r, k, a);
		v_madd(xf->p, size, a, e);
		view_line(dl, xf->p, e, C_AXIS[k]);
	}
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
	for (int k = 0; k < 3; k++) {
		r_col(xf->r, k, a);
		v_madd(xf->p, -size, a, e);
		view_line(dl, xf->p, e, C_AXIS_NEG[k]);
	}
	if (!labels)
		return;
	for (int k = 0; k < 3; k++) {
		r_col(xf->r, k, a);
		v_madd(xf->p, 1.18 * size, a, e);
		world_label(dl, e, pos[k], C_AXIS[k]);
		v_madd(xf->p, -1.18 * size, a, e);
		world_label(dl, e, neg[k], C_AXIS_NEG[k]);
	}
}

/* a frame whose y axis is dir (unit), origin at p */
static void
frame_along(const double p[3], const double dir[3], struct xform *dest)
{
	double x[3], z[3];
	v_perp(dir, x);
	v_cross(x, dir, z);
	for (int i = 0; i < 3; i++) {
		dest->r[3 * i + 0] = x[i];
		dest->r[3 * i + 1] = dir[i];
		dest->r[3 * i + 2] = z[i];
		dest->p[i] = p[i];
	}
}

void
view_add_translation_arrow(struct drawlist *dl, const double origin[3], const double dir[3],
			   double length)
{
	static const float rgba[4] = { 1.0f, 0.82f, 0.2f, 0.45f };
	double d[3], head = 0.18 * length, r = 0.025 * length;
	if (v_unit(dir, d) <= 0)
		return;
	struct xform x;
	/* the shaft between the heads, then a cone at each end pointing outwards */
	frame_along(origin, d, &x);
	double shaft[3] = { r, length - 2 * head, r };
	float mat[16];
	mat_from_xform(&x, shaft, mat);
	view_add_instance(dl, VIEW_MESH_CYLINDER, mat, rgba, 0);
	for (int s = -1; s <= 1; s += 2) {
		double nd[3] = { s * d[0], s * d[1], s * d[2] }, base[3];
		v_madd(origin, length / 2 - head, nd, base);
		frame_along(base, nd, &x);
		double cone[3] = { 2.6 * r, head, 2.6 * r };
		mat_from_xform(&x, cone, mat);
		view_add_instance(dl, VIEW_MESH_CONE, mat, rgba, 0);
	}
}

/* direction at angle t from unit u about unit a (right hand): u cos t + (a x u) sin t */
static void
turn(const double a[3], const double u[3], double t, double dest[3])
{
	double v[3];
	v_cross(a, u, v);
	for (int k = 0; k < 3; k++)
		dest[k] = cos(t) * u[k] + sin(t) * v[k];
}

/* a filled sector of the wheel from angle t0 to t1 */
static void
sector(struct drawlist *dl, const double c[3], const double a[3], const double u[3], double r,
       double t0, double t1, const uint8_t col[4])
{
	int n = (int)ceil(fabs(t1 - t0) / (2 * M_PI) * 48);
	n = n < 1 ? 1 : n;
	double d0[3], d1[3], p0[3], p1[3];
	for (int i = 0; i < n; i++) {
		turn(a, u, t0 + (t1 - t0) * i / n, d0);
		turn(a, u, t0 + (t1 - t0) * (i + 1) / n, d1);
		v_madd(c, r, d0, p0);
		v_madd(c, r, d1, p1);
		view_triangle(dl, c, p0, p1, col);
	}
}

/* the rim from t0 to t1 as lines */
static void
arc(struct drawlist *dl, const double c[3], const double a[3], const double u[3], double r,
    double t0, double t1, const uint8_t col[4])
{
	int n = (int)ceil(fabs(t1 - t0) / (2 * M_PI) * 64);
	n = n < 1 ? 1 : n;
	double d0[3], d1[3], p0[3], p1[3];
	for (int i = 0; i < n; i++) {
		turn(a, u, t0 + (t1 - t0) * i / n, d0);
		turn(a, u, t0 + (t1 - t0) * (i + 1) / n, d1);
		v_madd(c, r, d0, p0);
		v_madd(c, r, d1, p1);
		view_line(dl, p0, p1, col);
	}
}

void
view_add_rotation_wheel(struct drawlist *dl, const struct view_wheel *w)
{
	double a[3], u[3], e[3];
	uint8_t tc[4];
	if (v_unit(w->axis, a) <= 0)
		return;
	/* the initial spoke in the wheel's plane */
	v_madd(w->spoke, -v_dot(w->spoke, a), a, u);
	if (v_unit(u, u) < 1e-9)
		v_perp(a, u);
	double r = w->radius;
	double lo = w->lo - w->current, hi = w->hi - w->current;
	int sectors = w->limited && hi - lo < 2 * M_PI;

	/* translucent sectors: green where the spoke may go, red beyond the limits */
	if (sectors) {
		view_batch_begin(dl, VIEW_TRIANGLES, VIEW_WORLD, 1, 1);
		sector(dl, w->center, a, u, r, lo, hi, with_alpha(C_GREEN, 80, tc));
		sector(dl, w->center, a, u, r, hi, lo + 2 * M_PI, with_alpha(C_RED, 80, tc));
	}
	/* the rim, coloured by sector, and eight spokes */
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, THICK_WIDTH, 1);
	if (sectors) {
		arc(dl, w->center, a, u, r, lo, hi, C_GREEN);
		arc(dl, w->center, a, u, r, hi, lo + 2 * M_PI, C_RED);
	} else {
		arc(dl, w->center, a, u, r, 0, 2 * M_PI, C_WHEEL);
	}
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
	for (int i = 1; i < 8; i++) {
		double d[3];
		turn(a, u, i * M_PI / 4, d);
		v_madd(w->center, r, d, e);
		view_line(dl, w->center, e, with_alpha(C_WHEEL, 200, tc));
	}
	/* the spoke, extended past the rim (§3.5) */
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, THICK_WIDTH + 1, 1);
	v_madd(w->center, 1.3 * r, u, e);
	view_line(dl, w->center, e, C_WHEEL);
	/* the limits as short ticks outside the rim */
	if (sectors) {
		view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, THICK_WIDTH, 1);
		for (int k = 0; k < 2; k++) {
			double d[3], p0[3];
			turn(a, u, k ? hi : lo, d);
			v_madd(w->center, 0.85 * r, d, p0);
			v_madd(w->center, 1.15 * r, d, e);
			view_line(dl, p0, e, C_WHITE);
		}
	}
}

int
view_add_joint_wheel(struct drawlist *dl, const struct model *m, const struct state *s, int dof,
		     double radius)
{
	if (dof < 0 || dof >= m->ndof || m->dof_kind[dof] != DOF_ROTATION)
		return -1;
	int j = m->dof_jnt[dof], child = s->jnt_child_seg[j];
	struct view_wheel w;
	double com[3];
	/* the child turns by jnt_dir * q about the dof's world axis */
	for (int k = 0; k < 3; k++) {
		w.axis[k] = s->jnt_dir[j] * s->dof_axis_w[3 * dof + k];
		w.center[k] = s->dof_pivot_w[3 * dof + k];
	}
	xform_apply(&s->seg_xf[child], &m->seg_com[3 * child], com);
	for (int k = 0; k < 3; k++)
		w.spoke[k] = com[k] - w.center[k];
	w.radius = radius;
	w.limited = 1;
	w.lo = m->dof_lo[dof];
	w.hi = m->dof_hi[dof];
	w.current = s->q[dof];
	if (s->jnt_dir[j] < 0) {
		/* seen from the other side, the limits swap */
		w.lo = -m->dof_hi[dof];
		w.hi = -m->dof_lo[dof];
		w.current = -s->q[dof];
	}
	view_add_rotation_wheel(dl, &w);
	return 0;
}

void
view_add_fan(struct drawlist *dl, const double origin[3], const double from[3], const double to[3],
	     double radius, const uint8_t rgba[4])
{
	double u[3], v[3], a[3], e[3];
	uint8_t fill[4];
	if (v_unit(from, u) <= 0 || v_unit(to, v) <= 0)
		return;
	v_cross(u, v, a);
	double sn = v_unit(a, a), t = atan2(sn, v_dot(u, v));
	if (sn < 1e-9)
		return;
	view_batch_begin(dl, VIEW_TRIANGLES, VIEW_WORLD, 1, 1);
	sector(dl, origin, a, u, radius, 0, t, with_alpha(rgba, 90, fill));
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
	arc(dl, origin, a, u, radius, 0, t, rgba);
	v_madd(origin, radius, u, e);
	view_line(dl, origin, e, rgba);
	v_madd(origin, radius, v, e);
	view_line(dl, origin, e, rgba);
}

void
view_add_orientation_fans(struct drawlist *dl, const struct xform *effector,
			  const struct xform *goal, double radius)
{
	for (int k = 0; k < 3; k++) {
		double a[3], b[3];
		r_col(effector->r, k, a);
		r_col(goal->r, k, b);
		view_add_fan(dl, effector->p, a, b, radius, C_AXIS[k]);
	}
}

/* a small three-axis cross at x, no labels */
static void
small_frame(struct drawlist *dl, const struct xform *x, double size)
{
	double a[3], e[3];
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
	for (int k = 0; k < 3; k++) {
		r_col(x->r, k, a);
		v_madd(x->p, size, a, e);
		view_line(dl, x->p, e, C_AXIS[k]);
	}
}

/* an octahedron outline of radius r at p */
static void
diamond(struct drawlist *dl, const double p[3], double r, const uint8_t c[4])
{
	double v[6][3];
	for (int k = 0; k < 6; k++) {
		memcpy(v[k], p, sizeof v[k]);
		v[k][k / 2] += (k % 2 ? -r : r);
	}
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
	for (int i = 0; i < 6; i++)
		for (int j = i + 1; j < 6; j++)
			if (i / 2 != j / 2)
				view_line(dl, v[i], v[j], c);
}

void
view_add_goals(struct drawlist *dl, const struct ik *ik, const struct model *m,
	       const struct state *s)
{
	uint8_t tc[4];
	for (int c = 0; c < ik_count(ik); c++) {
		const struct ik_constraint_def *d = ik_get(ik, c);
		if (!d || !d->enabled || d->effector_site >= m->nsite || d->goal_site >= m->nsite)
			continue;
		/* goal and effector frames in the world */
		struct xform g, e;
		if (d->goal_site >= 0)
			xform_mul(&s->site_xf[d->goal_site], &d->goal_xf, &g);
		else
			g = d->goal_xf;
		if (d->com_effector) {
			xform_identity(&e);
			memcpy(e.p, s->com, sizeof e.p);
		} else {
			xform_mul(&s->site_xf[d->effector_site], &d->effector_offset, &e);
		}
		double ga[3], ea[3], p0[3], p1[3], u[3], v[3];
		xform_rotate(&g, d->goal_axis, ga);
		xform_rotate(&e, d->effector_axis, ea);
		switch (d->pos) {
		case IK_POS_NONE:
			break;
		case IK_POINT:
			diamond(dl, g.p, 0.03, C_GOAL);
			break;
		case IK_LINE:
			v_unit(ga, ga);
			v_madd(g.p, -0.5, ga, p0);
			v_madd(g.p, 0.5, ga, p1);
			view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
			view_line(dl, p0, p1, C_GOAL);
			break;
		case IK_PLANE: {
			double q[4][3];
			v_unit(ga, ga);
			v_perp(ga, u);
			v_cross(ga, u, v);
			for (int k = 0; k < 4; k++) {
				double su = (k == 0 || k == 3) ? -0.2 : 0.2, sv = k < 2 ? -0.2 : 0.2;
				for (int i = 0; i < 3; i++)
					q[k][i] = g.p[i] + su * u[i] + sv * v[i];
			}
			view_batch_begin(dl, VIEW_TRIANGLES, VIEW_WORLD, 1, 1);
			view_triangle(dl, q[0], q[1], q[2], with_alpha(C_GOAL, 60, tc));
			view_triangle(dl, q[0], q[2], q[3], with_alpha(C_GOAL, 60, tc));
			view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
			for (int k = 0; k < 4; k++)
				view_line(dl, q[k], q[(k + 1) % 4], C_GOAL);
			break;
		}
		}
		switch (d->ori) {
		case IK_ORI_NONE:
			break;
		case IK_FRAME:
			small_frame(dl, &g, 0.08);
			view_add_orientation_fans(dl, &e, &g, 0.07);
			break;
		case IK_DIRECTION:
			view_add_fan(dl, e.p, ea, ga, 0.08, C_GOAL);
			break;
		case IK_AIM:
			view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, 1.5f, 1);
			view_line(dl, e.p, g.p, with_alpha(C_GOAL, 160, tc));
			break;
		}
		/* the rubber band from the effector to a positional goal it has not reached */
		double gap[3] = { g.p[0] - e.p[0], g.p[1] - e.p[1], g.p[2] - e.p[2] };
		if (d->pos == IK_POINT && v_norm(gap) > 0.005) {
			view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, 1.5f, 1);
			view_line(dl, e.p, g.p, with_alpha(C_GOAL, 200, tc));
		}
	}
}

/* ---- balance ------------------------------------------------------------- */

#define HULL_MAX 256

static double
cross2(const double o[2], const double a[2], const double b[2])
{
	return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/* sorts points (x, z) by x then z; insertion sort: n is small */
static void
sort2(double (*p)[2], int n)
{
	for (int i = 1; i < n; i++)
		for (int j = i; j > 0 && (p[j][0] < p[j - 1][0] ||
					  (p[j][0] == p[j - 1][0] && p[j][1] < p[j - 1][1]));
		     j--) {
			double t[2] = { p[j][0], p[j][1] };
			memcpy(p[j], p[j - 1], sizeof t);
			memcpy(p[j - 1], t, sizeof t);
		}
}

/* Andrew's monotone chain: hull of p[0..n) into h, counter-clockwise in (x, z); returns its size */
static int
hull2(double (*p)[2], int n, double (*h)[2])
{
	int k = 0;
	sort2(p, n);
	for (int i = 0; i < n; i++) {
		while (k >= 2 && cross2(h[k - 2], h[k - 1], p[i]) <= 0)
			k--;
		memcpy(h[k++], p[i], sizeof p[i]);
	}
	for (int i = n - 2, t = k + 1; i >= 0; i--) {
		while (k >= t && cross2(h[k - 2], h[k - 1], p[i]) <= 0)
			k--;
		memcpy(h[k++], p[i], sizeof p[i]);
	}
	return n > 1 ? k - 1 : n;
}

/* sample points of a geom's surface (its bounding box corners and axis ends) in the world */
static int
geom_points(const struct model *m, const struct state *s, int g, double (*dest)[3])
{
	const double *sz = &m->geom_size[3 * g];
	double half[3];
	switch ((enum geom_kind)m->geom_kind[g]) {
	case GEOM_BOX:
	case GEOM_MESH:
		v_set(half, sz[0] / 2, sz[1] / 2, sz[2] / 2);
		break;
	case GEOM_ELLIPSOID:
		v_set(half, sz[0], sz[1], sz[2]);
		break;
	case GEOM_CYLINDER:
	case GEOM_CAPSULE:
		v_set(half, sz[0], sz[1] / 2 + (m->geom_kind[g] == GEOM_CAPSULE ? sz[0] : 0), sz[0]);
		break;
	default:
		return 0;
	}
	struct xform loc, x;
	mathx_quat_to_mat(&m->geom_quat[4 * g], loc.r);
	memcpy(loc.p, &m->geom_pos[3 * g], sizeof loc.p);
	xform_mul(&s->seg_xf[m->geom_seg[g]], &loc, &x);
	for (int c = 0; c < 8; c++) {
		double l[3] = { c & 1 ? half[0] : -half[0], c & 2 ? half[1] : -half[1],
				c & 4 ? half[2] : -half[2] };
		xform_apply(&x, l, dest[c]);
	}
	return 8;
}

/* 1 when (x, z) lies inside the counter-clockwise hull h */
static int
inside2(double (*h)[2], int n, const double p[2])
{
	if (n < 3)
		return 0;
	for (int i = 0; i < n; i++)
		if (cross2(h[i], h[(i + 1) % n], p) < 0)
			return 0;
	return 1;
}

int
view_add_balance(struct drawlist *dl, const struct model *m, const struct state *s)
{
	static const char *const feet[4] = { "foot_l", "foot_r", "toes_l", "toes_r" };
	static const uint8_t c_poly[4] = { 60, 120, 200, 255 }, c_line[4] = { 30, 60, 160, 255 };
	double pts[HULL_MAX][2], hull[HULL_MAX + 1][2], gp[8][3];
	uint8_t tc[4];
	int n = 0;
	int bl = model_find_site(m, "foot_l.balance"), br = model_find_site(m, "foot_r.balance");
	if (bl < 0 || br < 0)
		return -1;

	/* the feet's geometry near the floor, projected to it */
	for (int f = 0; f < 4; f++) {
		int seg = model_find_segment(m, feet[f]);
		if (seg < 0)
			continue;
		for (int g = m->seg_geom0[seg]; g < m->seg_geom0[seg] + m->seg_ngeom[seg]; g++) {
			int k = geom_points(m, s, g, gp);
			for (int i = 0; i < k && n < HULL_MAX; i++)
				if (gp[i][1] < 0.02) {
					pts[n][0] = gp[i][0];
					pts[n][1] = gp[i][2];
					n++;
				}
		}
	}
	int nh = hull2(pts, n, hull);
	const double y = 0.002; /* just above the floor */

	/* the support polygon: a translucent fill and its outline */
	if (nh >= 3) {
		view_batch_begin(dl, VIEW_TRIANGLES, VIEW_WORLD, 1, 1);
		for (int i = 1; i + 1 < nh; i++) {
			double a[3] = { hull[0][0], y, hull[0][1] }, b[3] = { hull[i][0], y, hull[i][1] },
			       c[3] = { hull[i + 1][0], y, hull[i + 1][1] };
			view_triangle(dl, a, b, c, with_alpha(c_poly, 70, tc));
		}
		view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, ICON_WIDTH, 1);
		for (int i = 0; i < nh; i++) {
			int j = (i + 1) % nh;
			double a[3] = { hull[i][0], y, hull[i][1] }, b[3] = { hull[j][0], y, hull[j][1] };
			view_line(dl, a, b, c_poly);
		}
	}

	/* the balance line between the feet's reference points */
	double pl[3] = { s->site_xf[bl].p[0], y, s->site_xf[bl].p[2] };
	double pr[3] = { s->site_xf[br].p[0], y, s->site_xf[br].p[2] };
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, THICK_WIDTH, 1);
	view_line(dl, pl, pr, c_line);

	/* the centre of mass: a plumb line, a ring at its height and the balance point */
	double b2[2] = { s->com[0], s->com[2] };
	const uint8_t *cb = inside2(hull, nh, b2) ? C_GREEN : C_RED;
	double bp[3] = { s->com[0], y, s->com[2] }, up[3] = { 0, 1, 0 }, ux[3] = { 1, 0, 0 };
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, 1.5f, 1);
	int dashes = 24;
	for (int i = 0; i < dashes; i += 2) {
		double a[3] = { bp[0], y + s->com[1] * i / dashes, bp[2] };
		double b[3] = { bp[0], y + s->com[1] * (i + 1) / dashes, bp[2] };
		view_line(dl, a, b, with_alpha(C_BLACK, 150, tc));
	}
	view_batch_begin(dl, VIEW_LINES, VIEW_WORLD, THICK_WIDTH, 1);
	circle(dl, s->com, up, ux, 0.045, 32, C_BLACK);
	double e0[3], e1[3];
	for (int k = 0; k < 3; k += 2) {
		double d[3] = { k == 0, 0, k == 2 };
		v_madd(s->com, -0.06, d, e0);
		v_madd(s->com, 0.06, d, e1);
		view_line(dl, e0, e1, C_BLACK);
	}
	circle(dl, bp, up, ux, 0.035, 32, cb);
	for (int k = 0; k < 3; k += 2) {
		double d[3] = { k == 0, 0, k == 2 };
		v_madd(bp, -0.05, d, e0);
		v_madd(bp, 0.05, d, e1);
		view_line(dl, e0, e1, cb);
	}
	return 0;
}

/* ---- overlay ------------------------------------------------------------- */

/* a screen rectangle from (x0, y0) to (x1, y1), pixels */
static void
rect(struct drawlist *dl, double x0, double y0, double x1, double y1, const uint8_t c[4])
{
	double a[3] = { x0, y0, 0 }, b[3] = { x1, y0, 0 }, cc[3] = { x1, y1, 0 }, d[3] = { x0, y1, 0 };
	view_triangle(dl, a, b, cc, c);
	view_triangle(dl, a, cc, d, c);
}

void
view_add_status(struct drawlist *dl, const char *status, const char *message, int edit)
{
	static const uint8_t c_status[4] = { 255, 255, 255, 255 }, c_msg[4] = { 255, 236, 170, 255 };
	static const uint8_t c_sband[4] = { 20, 24, 32, 200 }, c_mband[4] = { 20, 24, 32, 150 };
	double h = dl->height, w = dl->width, base = VIEW_LINE_PX - 5;
	view_batch_begin(dl, VIEW_TRIANGLES, VIEW_SCREEN, 1, 0);
	if (status)
		rect(dl, 0, h - VIEW_LINE_PX, w, h, c_sband);
	if (message)
		rect(dl, 0, h - 2 * VIEW_LINE_PX, w, h - VIEW_LINE_PX, c_mband);
	view_batch_begin(dl, VIEW_LINES, VIEW_SCREEN, 1, 0);
	if (status || message) {
		double top = h - (message ? 2 : 1) * VIEW_LINE_PX;
		double a[3] = { 0, top + 0.5, 0 }, b[3] = { w, top + 0.5, 0 };
		view_line(dl, a, b, C_BAND);
	}
	if (status) {
		char line[VIEW_TEXT_LEN];
		snprintf(line, sizeof line, "%s%s", status, edit ? "_" : "");
		view_add_text(dl, 6, h - VIEW_LINE_PX + base, line, c_status, VIEW_ALIGN_LEFT);
	}
	if (message)
		view_add_text(dl, 6, h - 2 * VIEW_LINE_PX + base, message, c_msg, VIEW_ALIGN_LEFT);
}

void
view_add_pointer(struct drawlist *dl, double x, double y)
{
	/* the classic arrow, 20 px tall at 480 lines, tip at (0, 0) */
	static const double shape[7][2] = { { 0, 0 }, { 0, 17 }, { 4, 13 }, { 7, 20 },
					    { 9.5, 19 }, { 6.5, 12 }, { 12, 12 } };
	static const int tris[5][3] = { { 0, 1, 2 }, { 0, 2, 5 }, { 0, 5, 6 }, { 2, 3, 4 },
					{ 2, 4, 5 } };
	double s = dl->icon_scale, p[7][3];
	for (int i = 0; i < 7; i++)
		v_set(p[i], x + s * shape[i][0], y + s * shape[i][1], 0);
	view_batch_begin(dl, VIEW_TRIANGLES, VIEW_SCREEN, 1, 0);
	for (int t = 0; t < 5; t++)
		view_triangle(dl, p[tris[t][0]], p[tris[t][1]], p[tris[t][2]], C_WHITE);
	view_batch_begin(dl, VIEW_LINES, VIEW_SCREEN, 1.5f, 0);
	for (int i = 0; i < 7; i++)
		view_line(dl, p[i], p[(i + 1) % 7], C_BLACK);
}
