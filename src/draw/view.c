/*
 * view.c - cameras and the abstract draw list (see view.h). No GL here:
 * this file only fills arrays that render.c draws.
 */
#include <cglm/cglm.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "draw/tess.h"
#include "draw/view.h"
#include "draw/view_internal.h"

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
view_camera_of_view(const struct env_view *v, struct camera *dest)
{
	view_camera_default(dest);
	view_camera_aim(dest, v->eye, v->target);
	if (v->fovy_deg > 0)
		dest->fovy = v->fovy_deg * M_PI / 180;
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
void
view_mat_from_xform(const struct xform *x, const double s[3], float dest[16])
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
	view_mat_from_xform(x, s, mat);
	view_add_instance(dl, mesh, mat, rgba, top_y(mat, ext) > 0.005);
}

int
view_geom_parts(const struct model *m, int g, struct view_part dest[VIEW_GEOM_PARTS_MAX])
{
	const double *sz = &m->geom_size[3 * g];
	struct view_part *p = &dest[0];
	mathx_quat_to_mat(&m->geom_quat[4 * g], p->xf.r);
	memcpy(p->xf.p, &m->geom_pos[3 * g], sizeof p->xf.p);
	p->model_mesh = -1;
	switch ((enum geom_kind)m->geom_kind[g]) {
	case GEOM_BOX:
		p->mesh = VIEW_MESH_BOX;
		v_set(p->scale, sz[0], sz[1], sz[2]);
		return 1;
	case GEOM_ELLIPSOID:
		p->mesh = VIEW_MESH_SPHERE;
		v_set(p->scale, sz[0], sz[1], sz[2]);
		return 1;
	case GEOM_CYLINDER:
		p->mesh = VIEW_MESH_CYLINDER;
		v_set(p->scale, sz[0], sz[1], sz[0]);
		return 1;
	case GEOM_CAPSULE:
		/* a tube and two hemispheres, the lower one turned over (about x) */
		p->mesh = VIEW_MESH_TUBE;
		v_set(p->scale, sz[0], sz[1], sz[0]);
		for (int k = 1; k < 3; k++) {
			struct view_part *c = &dest[k];
			double sign = k == 1 ? 1 : -1;
			*c = *p;
			c->mesh = VIEW_MESH_HEMISPHERE;
			v_set(c->scale, sz[0], sz[0], sz[0]);
			for (int i = 0; i < 3; i++) {
				c->xf.p[i] = p->xf.p[i] + sign * p->xf.r[3 * i + 1] * sz[1] / 2;
				c->xf.r[3 * i + 1] = sign * p->xf.r[3 * i + 1];
				c->xf.r[3 * i + 2] = sign * p->xf.r[3 * i + 2];
			}
		}
		return 3;
	case GEOM_MESH:
		p->mesh = VIEW_MESH_BUILTIN;
		p->model_mesh = m->geom_mesh[g];
		v_set(p->scale, sz[0], sz[1], sz[2]);
		return 1;
	}
	return 0;
}

int
view_mesh_tess(enum view_mesh k, int fine, struct tess_mesh *dest)
{
	int n = fine ? 20 : 10;
	switch (k) {
	case VIEW_MESH_SPHERE:
		return tess_sphere(n, n / 2 + 2, dest);
	case VIEW_MESH_HEMISPHERE:
		return tess_hemisphere(n, n / 4, dest);
	case VIEW_MESH_TUBE:
		return tess_cylinder(n, 0, dest);
	case VIEW_MESH_CYLINDER:
		return tess_cylinder(n, 1, dest);
	case VIEW_MESH_CONE:
		return tess_cone(n, dest);
	case VIEW_MESH_BOX:
		return tess_box(dest);
	case VIEW_MESH_BUILTIN:
		break;
	}
	return -1;
}

/*
 * the instances of m's geoms; fig < 0: coloured by segment (seg_rgba's
 * colours, or the model's when NULL), with shadows when alpha is 1
 * (translucent, alpha < 1: none), else flat id colours
 */
static int
add_figure(struct drawlist *dl, const struct model *m, const struct state *s, int mesh_base,
	   int fig, const unsigned char *skip_seg, float alpha, const float *seg_rgba)
{
	int before = dl->ninst;
	int shadows = fig < 0 && alpha >= 1;
	for (int g = 0; g < m->ngeom; g++) {
		int seg = m->geom_seg[g];
		if (skip_seg && skip_seg[seg])
			continue;
		float rgba[4];
		memcpy(rgba, &(seg_rgba ? seg_rgba : m->seg_rgba)[4 * seg], sizeof rgba);
		if (fig >= 0)
			view_id_rgba(view_id(fig, seg), rgba);
		else if (alpha < 1)
			rgba[3] *= alpha;
		struct view_part part[VIEW_GEOM_PARTS_MAX];
		int n = view_geom_parts(m, g, part);
		for (int k = 0; k < n; k++) {
			struct xform x;
			xform_mul(&s->seg_xf[seg], &part[k].xf, &x);
			float mat[16];
			view_mat_from_xform(&x, part[k].scale, mat);
			if (part[k].model_mesh >= 0)
				view_add_instance(dl, mesh_base + part[k].model_mesh, mat, rgba,
						  shadows);
			else if (!shadows) /* an id map or a ghost casts no shadow */
				view_add_instance(dl, part[k].mesh, mat, rgba, 0);
			else
				add_unit(dl, part[k].mesh, &x, part[k].scale, rgba,
					 part[k].mesh == VIEW_MESH_BOX ? 0.5 : 1);
		}
	}
	return dl->ninst - before;
}

int
view_add_figure(struct drawlist *dl, const struct model *m, const struct state *s, int mesh_base)
{
	return add_figure(dl, m, s, mesh_base, -1, NULL, 1, NULL);
}

int
view_add_figure_rgba(struct drawlist *dl, const struct model *m, const struct state *s,
		     int mesh_base, const float *seg_rgba)
{
	return add_figure(dl, m, s, mesh_base, -1, NULL, 1, seg_rgba);
}

int
view_add_figure_ghost(struct drawlist *dl, const struct model *m, const struct state *s,
		      int mesh_base, float alpha)
{
	return add_figure(dl, m, s, mesh_base, -1, NULL, alpha, NULL);
}

uint32_t
view_id(int fig, int seg)
{
	return (uint32_t)(fig + 1) << 16 | (uint32_t)(seg + 1);
}

void
view_id_rgba(uint32_t id, float dest[4])
{
	/* k / 255 comes back from an 8 bit channel as k (pack.c rounds) */
	dest[0] = (float)(id >> 16 & 0xff) / 255;
	dest[1] = (float)(id >> 8 & 0xff) / 255;
	dest[2] = (float)(id & 0xff) / 255;
	dest[3] = 1;
}

int
view_add_figure_ids(struct drawlist *dl, const struct model *m, const struct state *s,
		    int mesh_base, int fig)
{
	return add_figure(dl, m, s, mesh_base, fig < 0 ? 0 : fig, NULL, 1, NULL);
}

int
view_add_figure_ids_except(struct drawlist *dl, const struct model *m, const struct state *s,
			   int mesh_base, int fig, const unsigned char *skip_seg)
{
	return add_figure(dl, m, s, mesh_base, fig < 0 ? 0 : fig, skip_seg, 1, NULL);
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
void
view_world_label(struct drawlist *dl, const double p[3], const char *text, const uint8_t c[4])
{
	double px[2];
	if (view_project(&dl->cam, dl->width, dl->height, p, px))
		view_add_text(dl, px[0], px[1] + VIEW_FONT_PX * 0.35, text, c, VIEW_ALIGN_CENTER);
}

/* a circle of radius r about unit axis a through c, n segments, from unit u */
void
view_circle(struct drawlist *dl, const double c[3], const double a[3], const double u[3], double r,
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
view_add_rect(struct drawlist *dl, double x0, double y0, double x1, double y1, const uint8_t rgba[4])
{
	view_batch_begin(dl, VIEW_TRIANGLES, VIEW_SCREEN, 1, 0);
	rect(dl, x0, y0, x1, y1, rgba);
}

void
view_add_status(struct drawlist *dl, const char *status, const char *message, int caret)
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
	if (status)
		view_add_text(dl, 6, h - VIEW_LINE_PX + base, status, c_status, VIEW_ALIGN_LEFT);
	if (status && caret >= 0 && caret < VIEW_TEXT_LEN - 1) {
		/* as many spaces as characters before it: monospaced, the caret lands under its cell */
		char under[VIEW_TEXT_LEN];
		memset(under, ' ', (size_t)caret);
		under[caret] = '_';
		under[caret + 1] = '\0';
		view_add_text(dl, 6, h - VIEW_LINE_PX + base, under, c_status, VIEW_ALIGN_LEFT);
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
