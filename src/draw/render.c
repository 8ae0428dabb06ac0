/*
 * render.c - OSMesa drawing of a draw list (see render.h). The only file
 * that includes GL or OSMesa headers.
 *
 * GL 2.1-style: fixed-function matrix stacks, vertex buffer objects and
 * GLSL 1.20 shaders, all on Mesa's llvmpipe. Everything that lives across
 * frames (buffers, shaders, meshes, the font texture, streaming vertex
 * buffers sized for a full draw list) is made in render_make and
 * render_add_model; render_frame only fills them.
 */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

#include <cglm/cglm.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "draw/font.h"
#include "draw/hemi.h"
#include "draw/pack.h"
#include "draw/render.h"
#include "draw/render_glsl.h"
#include "draw/tess.h"

#define SHADOW_TEX 128     /* the floor shadow map, texels a side (4.7 cm; render_glsl_blur_fs says 128) */
#define SHADOW_HALF 3.0f   /* it covers the floor 3 m around the view reference point */
#define XRAY_ALPHA 0.3f    /* icons behind geometry */
#define FLOOR_HALF 60.0f   /* the floor quad's half size, m */
#define TEXT_QUADS (VIEW_MAX_TEXT * VIEW_TEXT_LEN * 5) /* glyphs and their 4 outline copies */

/* a text vertex: pixel position, atlas uv, colour */
struct text_vertex {
	float x, y, u, v;
	uint8_t c[4];
};

struct render {
	OSMesaContext ctx;
	uint8_t *buf; /* max_w x max_h RGBA, rows top to bottom (OSMESA_Y_UP = 0) */
	int max_w, max_h, samples, shadows;
	int surf_w, surf_h; /* the OSMesa surface now: the last frame's size (rows max_w apart) */
	GLuint fbo, rb_color, rb_depth; /* the multisampled target, when samples > 0 */

	GLuint prog_lit, prog_color, prog_floor, prog_text;
	GLint lit_key, lit_fill, lit_up, lit_sbox, lit_smap;
	GLint floor_sbox, floor_smap;
	/* the shadow map: the casters squashed onto the floor along the light, seen from above */
	GLuint shadow_fbo, shadow_tex;
	GLuint blur_fbo, blur_tex, prog_blur; /* the map blurred: the soft edge */
	GLint blur_src;
	GLint color_tint;
	GLint floor_rgb, floor_far, floor_grid, floor_fade;
	GLint text_atlas;

	struct tess_mesh mesh[RENDER_MAX_MESH]; /* kept on the CPU for packing */
	int lod[RENDER_MAX_MESH];               /* the coarse version of each mesh */
	unsigned char dynamic[RENDER_MAX_MESH]; /* 1: made by render_set_mesh, replaceable */
	int nmesh;
	struct pack pack; /* the instances, packed every frame (pack.h) */
	GLuint pvbo, pibo;

	GLuint stream;  /* draw-list vertices + background + floor */
	GLuint tstream; /* text quads */
	struct text_vertex *tvert;
	struct font *font;
	GLuint font_tex;

	/* the visibility map's own small target, so the last picture in buf stays whole */
	GLuint hemi_fbo, hemi_color, hemi_depth;

	uint64_t seq;
	struct render_stats stats;
};

struct render_def
render_default_def(void)
{
	struct render_def d = { 1280, 720, 0, 1, FONT_DEFAULT_PATH };
	return d;
}

/* ---- shaders (sources in render_glsl.c) -------------------------------------- */
static GLuint
shader(GLenum kind, const char *src, char *err, size_t errlen)
{
	GLuint s = glCreateShader(kind);
	GLint ok = 0;
	glShaderSource(s, 1, &src, NULL);
	glCompileShader(s);
	glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
	if (!ok) {
		char log[512] = "";
		glGetShaderInfoLog(s, sizeof log, NULL, log);
		snprintf(err, errlen, "shader: %s", log);
		glDeleteShader(s);
		return 0;
	}
	return s;
}

static GLuint
program(const char *vs, const char *fs, char *err, size_t errlen)
{
	GLuint v = shader(GL_VERTEX_SHADER, vs, err, errlen), f = 0, p = 0;
	GLint ok = 0;
	if (!v || !(f = shader(GL_FRAGMENT_SHADER, fs, err, errlen)))
		goto out;
	p = glCreateProgram();
	glAttachShader(p, v);
	glAttachShader(p, f);
	glLinkProgram(p);
	glGetProgramiv(p, GL_LINK_STATUS, &ok);
	if (!ok) {
		char log[512] = "";
		glGetProgramInfoLog(p, sizeof log, NULL, log);
		snprintf(err, errlen, "program: %s", log);
		glDeleteProgram(p);
		p = 0;
	}
out:
	if (v)
		glDeleteShader(v);
	if (f)
		glDeleteShader(f);
	return p;
}

/* ---- making and freeing ---------------------------------------------------- */

/* takes over t's arrays; returns the mesh id or -1 when the table is full */
static int
keep(struct render *r, struct tess_mesh *t)
{
	if (r->nmesh >= RENDER_MAX_MESH)
		return -1;
	r->mesh[r->nmesh] = *t;
	r->lod[r->nmesh] = r->nmesh;
	memset(t, 0, sizeof *t);
	return r->nmesh++;
}

/* the unit primitives in enum view_mesh order, fine (fine = 1) or coarse */
static int
builtin_meshes(struct render *r, int fine)
{
	struct tess_mesh t;
	int base = r->nmesh;
	for (int k = 0; k < VIEW_MESH_BUILTIN; k++) {
		if (view_mesh_tess((enum view_mesh)k, fine, &t))
			return -1;
		if (keep(r, &t) != base + k) {
			tess_free(&t);
			return -1;
		}
	}
	return 0;
}

static int
font_texture(struct render *r, const char *path, char *err, size_t errlen)
{
	r->font = font_load(path, VIEW_FONT_PX, err, errlen);
	if (!r->font)
		return -1;
	glGenTextures(1, &r->font_tex);
	glBindTexture(GL_TEXTURE_2D, r->font_tex);
	glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
	glTexImage2D(GL_TEXTURE_2D, 0, GL_ALPHA, r->font->atlas_w, r->font->atlas_h, 0, GL_ALPHA,
		     GL_UNSIGNED_BYTE, r->font->atlas);
	/* glyphs are drawn at whole pixels, one texel a pixel */
	glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
	glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
	return 0;
}

/* a SHADOW_TEX square texture to draw into; 0 or -1 */
static int
target_texture(GLuint *tex, GLuint *fbo)
{
	glGenTextures(1, tex);
	glBindTexture(GL_TEXTURE_2D, *tex);
	glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, SHADOW_TEX, SHADOW_TEX, 0, GL_RGBA, GL_UNSIGNED_BYTE,
		     NULL);
	glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
	glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
	glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
	glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
	glGenFramebuffers(1, fbo);
	glBindFramebuffer(GL_FRAMEBUFFER, *fbo);
	glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, *tex, 0);
	return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE ? 0 : -1;
}

struct render *
render_make(const struct render_def *d, char *err, size_t errlen)
{
	struct render *r = calloc(1, sizeof *r);
	if (!r) {
		snprintf(err, errlen, "out of memory");
		return NULL;
	}
	if (d->max_w < 1 || d->max_h < 1 || d->max_w > 8192 || d->max_h > 8192 ||
	    (d->samples != 0 && d->samples != 4)) {
		snprintf(err, errlen, "bad size %dx%d or samples %d", d->max_w, d->max_h, d->samples);
		goto fail;
	}
	r->max_w = d->max_w;
	r->max_h = d->max_h;
	r->samples = d->samples;
	r->shadows = d->shadows;
	r->buf = calloc((size_t)d->max_w * (size_t)d->max_h, 4);
	r->tvert = malloc(sizeof *r->tvert * 6 * TEXT_QUADS);
	if (!r->buf || !r->tvert || pack_init(&r->pack) < 0) {
		snprintf(err, errlen, "out of memory");
		goto fail;
	}

	/* a compatibility context with depth and stencil over our buffer */
	const int attr[] = { OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
			     OSMESA_STENCIL_BITS, 8, OSMESA_PROFILE, OSMESA_COMPAT_PROFILE,
			     OSMESA_CONTEXT_MAJOR_VERSION, 2, OSMESA_CONTEXT_MINOR_VERSION, 1, 0 };
	r->ctx = OSMesaCreateContextAttribs(attr, NULL);
	r->surf_w = r->max_w;
	r->surf_h = r->max_h;
	if (!r->ctx || !OSMesaMakeCurrent(r->ctx, r->buf, GL_UNSIGNED_BYTE, r->max_w, r->max_h)) {
		snprintf(err, errlen, "OSMesa: no %dx%d context", r->max_w, r->max_h);
		goto fail;
	}
	OSMesaPixelStore(OSMESA_Y_UP, 0);

	if (r->samples) {
		glGenFramebuffers(1, &r->fbo);
		glGenRenderbuffers(1, &r->rb_color);
		glGenRenderbuffers(1, &r->rb_depth);
		glBindRenderbuffer(GL_RENDERBUFFER, r->rb_color);
		glRenderbufferStorageMultisample(GL_RENDERBUFFER, r->samples, GL_RGBA8, r->max_w,
						 r->max_h);
		glBindRenderbuffer(GL_RENDERBUFFER, r->rb_depth);
		glRenderbufferStorageMultisample(GL_RENDERBUFFER, r->samples, GL_DEPTH24_STENCIL8,
						 r->max_w, r->max_h);
		glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
		glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
					  r->rb_color);
		glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT,
					  GL_RENDERBUFFER, r->rb_depth);
		if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
			snprintf(err, errlen, "no %dx multisampled framebuffer", r->samples);
			goto fail;
		}
		glBindFramebuffer(GL_FRAMEBUFFER, 0);
	}

	/* the visibility map's target (render_hemicube): colour ids and depth, no samples */
	glGenFramebuffers(1, &r->hemi_fbo);
	glGenRenderbuffers(1, &r->hemi_color);
	glGenRenderbuffers(1, &r->hemi_depth);
	glBindRenderbuffer(GL_RENDERBUFFER, r->hemi_color);
	glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, HEMI_N, HEMI_N);
	glBindRenderbuffer(GL_RENDERBUFFER, r->hemi_depth);
	glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, HEMI_N, HEMI_N);
	glBindFramebuffer(GL_FRAMEBUFFER, r->hemi_fbo);
	glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
				  r->hemi_color);
	glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
				  r->hemi_depth);
	if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
		snprintf(err, errlen, "no framebuffer for the visibility map");
		goto fail;
	}
	glBindFramebuffer(GL_FRAMEBUFFER, 0);

	/* the shadow map and its blurred copy: each a texture behind a framebuffer */
	if (r->shadows && (target_texture(&r->shadow_tex, &r->shadow_fbo) < 0 ||
			   target_texture(&r->blur_tex, &r->blur_fbo) < 0)) {
		snprintf(err, errlen, "no shadow map framebuffer");
		goto fail;
	}
	glBindFramebuffer(GL_FRAMEBUFFER, 0);
	r->prog_lit = program(render_glsl_lit_vs, render_glsl_lit_fs, err, errlen);
	r->prog_color = r->prog_lit ? program(render_glsl_color_vs, render_glsl_color_fs, err, errlen) : 0;
	r->prog_floor = r->prog_color ? program(render_glsl_floor_vs, render_glsl_floor_fs, err, errlen) : 0;
	r->prog_text = r->prog_floor ? program(render_glsl_text_vs, render_glsl_text_fs, err, errlen) : 0;
	r->prog_blur = r->prog_text ? program(render_glsl_blur_vs, render_glsl_blur_fs, err, errlen) : 0;
	if (!r->prog_blur)
		goto fail;
	r->blur_src = glGetUniformLocation(r->prog_blur, "src");
	r->lit_key = glGetUniformLocation(r->prog_lit, "key");
	r->lit_fill = glGetUniformLocation(r->prog_lit, "fill");
	r->lit_up = glGetUniformLocation(r->prog_lit, "up");
	r->lit_sbox = glGetUniformLocation(r->prog_lit, "sbox");
	r->lit_smap = glGetUniformLocation(r->prog_lit, "smap");
	r->floor_sbox = glGetUniformLocation(r->prog_floor, "sbox");
	r->floor_smap = glGetUniformLocation(r->prog_floor, "smap");
	r->color_tint = glGetUniformLocation(r->prog_color, "tint");
	r->floor_rgb = glGetUniformLocation(r->prog_floor, "rgb");
	r->floor_far = glGetUniformLocation(r->prog_floor, "far_rgb");
	r->floor_grid = glGetUniformLocation(r->prog_floor, "grid");
	r->floor_fade = glGetUniformLocation(r->prog_floor, "fade");
	r->text_atlas = glGetUniformLocation(r->prog_text, "atlas");

	/* ids 0 .. VIEW_MESH_BUILTIN - 1 fine, then their coarse versions */
	if (builtin_meshes(r, 1) || builtin_meshes(r, 0)) {
		snprintf(err, errlen, "out of memory");
		goto fail;
	}
	for (int k = 0; k < VIEW_MESH_BUILTIN; k++)
		r->lod[k] = VIEW_MESH_BUILTIN + k;
	if (font_texture(r, d->font_path ? d->font_path : FONT_DEFAULT_PATH, err, errlen))
		goto fail;

	/* streaming buffers sized for a full draw list, filled every frame */
	glGenBuffers(1, &r->stream);
	glBindBuffer(GL_ARRAY_BUFFER, r->stream);
	glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(struct view_vertex) * (VIEW_MAX_VERT + 8)),
		     NULL, GL_STREAM_DRAW);
	glGenBuffers(1, &r->tstream);
	glBindBuffer(GL_ARRAY_BUFFER, r->tstream);
	glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(struct text_vertex) * 6 * TEXT_QUADS),
		     NULL, GL_STREAM_DRAW);
	glGenBuffers(1, &r->pvbo);
	glBindBuffer(GL_ARRAY_BUFFER, r->pvbo);
	glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof *r->pack.pv * PACK_MAX_VERT), NULL,
		     GL_STREAM_DRAW);
	glGenBuffers(1, &r->pibo);
	glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->pibo);
	glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(sizeof *r->pack.pi * PACK_MAX_IDX), NULL,
		     GL_STREAM_DRAW);
	glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
	glBindBuffer(GL_ARRAY_BUFFER, 0);
	if (glGetError() != GL_NO_ERROR) {
		snprintf(err, errlen, "GL error while setting up");
		goto fail;
	}
	return r;
fail:
	render_free(r);
	return NULL;
}

void
render_free(struct render *r)
{
	if (!r)
		return;
	if (r->ctx) {
		OSMesaMakeCurrent(r->ctx, r->buf, GL_UNSIGNED_BYTE, r->max_w, r->max_h);
		glDeleteBuffers(1, &r->pvbo);
		glDeleteBuffers(1, &r->pibo);
		glDeleteBuffers(1, &r->stream);
		glDeleteBuffers(1, &r->tstream);
		glDeleteTextures(1, &r->font_tex);
		glDeleteProgram(r->prog_lit);
		glDeleteProgram(r->prog_color);
		glDeleteProgram(r->prog_floor);
		glDeleteProgram(r->prog_text);
		if (r->shadow_fbo) {
			glDeleteFramebuffers(1, &r->shadow_fbo);
			glDeleteTextures(1, &r->shadow_tex);
		}
		if (r->blur_fbo) {
			glDeleteFramebuffers(1, &r->blur_fbo);
			glDeleteTextures(1, &r->blur_tex);
		}
		glDeleteProgram(r->prog_blur);
		if (r->hemi_fbo) {
			glDeleteFramebuffers(1, &r->hemi_fbo);
			glDeleteRenderbuffers(1, &r->hemi_color);
			glDeleteRenderbuffers(1, &r->hemi_depth);
		}
		if (r->fbo) {
			glDeleteFramebuffers(1, &r->fbo);
			glDeleteRenderbuffers(1, &r->rb_color);
			glDeleteRenderbuffers(1, &r->rb_depth);
		}
		OSMesaDestroyContext(r->ctx);
	}
	for (int i = 0; i < r->nmesh; i++)
		tess_free(&r->mesh[i]);
	font_free(r->font);
	pack_free(&r->pack);
	free(r->tvert);
	free(r->buf);
	free(r);
}

int
render_add_model(struct render *r, const struct model *m, char *err, size_t errlen)
{
	int base = r->nmesh;
	if (r->nmesh + m->nmesh > RENDER_MAX_MESH) {
		snprintf(err, errlen, "%s: mesh table full (%d meshes)", m->name, RENDER_MAX_MESH);
		return -1;
	}
	for (int i = 0; i < m->nmesh; i++) {
		struct tess_mesh t;
		/* smooth normals, creases above 40 deg kept sharp */
		if (tess_mesh_from_triangles(m->mesh_vert + 3 * m->mesh_vert0[i], m->mesh_nvert[i],
					     m->mesh_face + 3 * m->mesh_face0[i], m->mesh_nface[i],
					     40, &t)) {
			snprintf(err, errlen, "out of memory");
			return -1;
		}
		keep(r, &t);
	}
	return base;
}

int
render_set_mesh(struct render *r, int id, const float *vert, const float *normal, int nvert,
		const int *tri, int ntri, char *err, size_t errlen)
{
	if (id >= 0 && (id >= r->nmesh || !r->dynamic[id])) {
		snprintf(err, errlen, "mesh %d is not a run-time mesh", id);
		return -1;
	}
	if (id < 0 && r->nmesh >= RENDER_MAX_MESH) {
		snprintf(err, errlen, "mesh table full (%d meshes)", RENDER_MAX_MESH);
		return -1;
	}
	if (nvert < 0 || ntri < 0 || (long long)ntri * 3 > 0x7fffffff) {
		snprintf(err, errlen, "bad mesh size");
		return -1;
	}
	for (long long i = 0; i < 3LL * ntri; i++)
		if (tri[i] < 0 || tri[i] >= nvert) {
			snprintf(err, errlen, "triangle %lld names vertex %d of %d", i / 3, tri[i], nvert);
			return -1;
		}
	struct tess_mesh t = { 0 };
	if (ntri) {
		t.vn = malloc(sizeof *t.vn * 6 * (size_t)nvert);
		t.idx = malloc(sizeof *t.idx * 3 * (size_t)ntri);
		if (!t.vn || !t.idx) {
			tess_free(&t);
			snprintf(err, errlen, "out of memory");
			return -1;
		}
		t.nvert = nvert;
		t.nidx = 3 * ntri;
		for (int i = 0; i < nvert; i++)
			for (int k = 0; k < 3; k++) {
				t.vn[6 * i + k] = vert[3 * i + k];
				t.vn[6 * i + 3 + k] = normal[3 * i + k];
				float v = vert[3 * i + k];
				t.lo[k] = i == 0 || v < t.lo[k] ? v : t.lo[k];
				t.hi[k] = i == 0 || v > t.hi[k] ? v : t.hi[k];
			}
		for (int i = 0; i < 3 * ntri; i++)
			t.idx[i] = (unsigned)tri[i];
	}
	if (id < 0) {
		id = keep(r, &t);
		r->dynamic[id] = 1;
		return id;
	}
	tess_free(&r->mesh[id]);
	r->mesh[id] = t;
	return id;
}

/* ---- drawing ------------------------------------------------------------------- */

/* a direction from world into eye space (rotation part of view) */
static void
to_eye(const float view[16], const float w[3], float dest[3])
{
	for (int i = 0; i < 3; i++)
		dest[i] = view[i] * w[0] + view[4 + i] * w[1] + view[8 + i] * w[2];
}

/* the OSMesa surface made w x h (rows max_w apart): it copies only the frame's pixels out */
static void
surface_size(struct render *r, int w, int h)
{
	if (r->surf_w == w && r->surf_h == h)
		return;
	OSMesaMakeCurrent(r->ctx, r->buf, GL_UNSIGNED_BYTE, w, h);
	OSMesaPixelStore(OSMESA_ROW_LENGTH, r->max_w);
	r->surf_w = w;
	r->surf_h = h;
}

/* the packed arrays into their buffers */
static void
upload_packed(const struct render *r)
{
	const struct pack *p = &r->pack;
	/* a new store each frame: in place, llvmpipe copied all the last frame still held */
	glBindBuffer(GL_ARRAY_BUFFER, r->pvbo);
	glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof *p->pv * (size_t)p->nv), p->pv,
		     GL_STREAM_DRAW);
	glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->pibo);
	glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(sizeof *p->pi * (size_t)p->ni), p->pi,
		     GL_STREAM_DRAW);
}

/* draws classes c0..c1 of the packed instances (buffers bound) */
static void
draw_packed(const struct render *r, int c0, int c1)
{
	const int(*range)[2] = r->pack.range;
	int first = range[c0][0], count = range[c1][0] + range[c1][1] - first;
	if (count > 0)
		glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT,
			       (void *)(sizeof(unsigned) * (size_t)first));
}

static void
packed_pointers(const struct render *r)
{
	glBindBuffer(GL_ARRAY_BUFFER, r->pvbo);
	glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->pibo);
	glVertexPointer(3, GL_FLOAT, sizeof(struct pack_vertex), (void *)0);
	glNormalPointer(GL_FLOAT, sizeof(struct pack_vertex),
			(void *)offsetof(struct pack_vertex, n));
	glColorPointer(4, GL_UNSIGNED_BYTE, sizeof(struct pack_vertex),
		       (void *)offsetof(struct pack_vertex, c));
}

/*
 * The shadow map: the casters' coarse meshes squashed onto y = 0 along the
 * light (p' = p - (p.y / l.y) l) and seen from above over a square of the
 * floor around (cx, cz): 1 where the floor is lit, 0 in shadow. Drawn at
 * SHADOW_TEX^2 it costs little however much the casters overlap; the
 * floor and floor-level faces sample it with a small blur.
 */
static void
draw_shadow_map(struct render *r, const struct drawlist *dl, float cx, float cz)
{
	const float *l = dl->light, k = 1 / SHADOW_HALF;
	const float s[16] = { 1, 0, 0, 0, -l[0] / l[1], 0, -l[2] / l[1], 0, 0, 0, 1, 0, 0, 0, 0, 1 };
	/* x -> clip x, z -> clip y, around (cx, cz) */
	const float p[16] = { k, 0, 0, 0, 0, 0, 0, 0, 0, k, 0, 0, -cx * k, -cz * k, 0, 1 };
	glBindFramebuffer(GL_FRAMEBUFFER, r->shadow_fbo);
	glViewport(0, 0, SHADOW_TEX, SHADOW_TEX);
	glDisable(GL_SCISSOR_TEST);
	glClearColor(1, 1, 1, 1);
	glClear(GL_COLOR_BUFFER_BIT);
	glMatrixMode(GL_PROJECTION);
	glLoadMatrixf(p);
	glMatrixMode(GL_MODELVIEW);
	glLoadMatrixf(s);
	glUseProgram(r->prog_color);
	glUniform4f(r->color_tint, 0, 0, 0, 1);
	/* either face of a closed mesh covers its shadow: one is enough */
	glEnable(GL_CULL_FACE);
	glCullFace(GL_BACK);
	draw_packed(r, PACK_SHADOW, PACK_SHADOW);
	glDisable(GL_CULL_FACE);

	/* the soft edge: the blurred copy, from the background quad's corners (clip space) */
	glBindFramebuffer(GL_FRAMEBUFFER, r->blur_fbo);
	glUseProgram(r->prog_blur);
	glUniform1i(r->blur_src, 0);
	glBindTexture(GL_TEXTURE_2D, r->shadow_tex);
	glBindBuffer(GL_ARRAY_BUFFER, r->stream);
	glVertexPointer(3, GL_FLOAT, sizeof(struct view_vertex), (void *)0);
	glDrawArrays(GL_TRIANGLE_STRIP, VIEW_MAX_VERT, 4);
	packed_pointers(r);
}

static void
stream_pointers(void)
{
	glVertexPointer(3, GL_FLOAT, sizeof(struct view_vertex), (void *)0);
	glColorPointer(4, GL_UNSIGNED_BYTE, sizeof(struct view_vertex),
		       (void *)offsetof(struct view_vertex, c));
}

/* the batches of one space; xray: 1 the hidden parts' pass, 0 the normal pass */
static void
draw_batches(const struct drawlist *dl, enum view_space space, int xray)
{
	for (int i = 0; i < dl->nbatch; i++) {
		const struct view_batch *b = &dl->batch[i];
		if (b->space != space || b->count == 0 || (xray && !b->xray))
			continue;
		if (b->prim == VIEW_LINES) {
			glLineWidth(b->width * dl->icon_scale);
			glDrawArrays(GL_LINES, b->first, b->count - b->count % 2);
		} else {
			glDrawArrays(GL_TRIANGLES, b->first, b->count - b->count % 3);
		}
	}
}

/* one glyph quad into v; returns the quads written (0 or 1) */
static int
glyph_quad(const struct font *f, const struct font_glyph *g, float x, float y, const uint8_t c[4],
	   struct text_vertex *v)
{
	if (g->w == 0 || g->h == 0)
		return 0;
	float x0 = x + (float)g->left, y0 = y - (float)g->top, x1 = x0 + (float)g->w,
	      y1 = y0 + (float)g->h;
	float u0 = (float)g->x / (float)f->atlas_w, v0 = (float)g->y / (float)f->atlas_h;
	float u1 = (float)(g->x + g->w) / (float)f->atlas_w,
	      v1 = (float)(g->y + g->h) / (float)f->atlas_h;
	const struct text_vertex q[6] = {
		{ x0, y0, u0, v0, { c[0], c[1], c[2], c[3] } },
		{ x1, y0, u1, v0, { c[0], c[1], c[2], c[3] } },
		{ x1, y1, u1, v1, { c[0], c[1], c[2], c[3] } },
		{ x0, y0, u0, v0, { c[0], c[1], c[2], c[3] } },
		{ x1, y1, u1, v1, { c[0], c[1], c[2], c[3] } },
		{ x0, y1, u0, v1, { c[0], c[1], c[2], c[3] } },
	};
	memcpy(v, q, sizeof q);
	return 1;
}

/* the text items: a dark outline under each glyph, then the glyph */
static void
draw_text(struct render *r, const struct drawlist *dl)
{
	static const int off[4][2] = { { 1, 1 }, { -1, 1 }, { 1, -1 }, { -1, -1 } };
	int nq = 0;
	for (int pass = 0; pass < 2; pass++)
		for (int i = 0; i < dl->ntext; i++) {
			const struct view_text *t = &dl->text[i];
			float x = floorf(t->x + 0.5f), y = floorf(t->y + 0.5f);
			if (t->align == VIEW_ALIGN_CENTER)
				x -= (float)(font_text_width(r->font, t->s) / 2);
			uint8_t shade[4] = { 0, 0, 0, (uint8_t)(t->c[3] * 0.55f) };
			for (const unsigned char *p = (const unsigned char *)t->s; *p; p++) {
				const struct font_glyph *g = font_glyph(r->font, *p);
				/* pass 0: the outline, four offsets at the centre-aligned glyph */
				for (int k = 0; k < (pass ? 1 : 4) && nq < TEXT_QUADS; k++)
					nq += glyph_quad(r->font, g, x + (pass ? 0 : (float)off[k][0]),
							 y + (pass ? 0 : (float)off[k][1]),
							 pass ? t->c : shade, r->tvert + 6 * nq);
				x += (float)g->advance;
			}
		}
	if (!nq)
		return;
	r->stats.glyphs = nq;
	glBindBuffer(GL_ARRAY_BUFFER, r->tstream);
	glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(sizeof(struct text_vertex) * 6 * (size_t)nq),
			r->tvert);
	glUseProgram(r->prog_text);
	glUniform1i(r->text_atlas, 0);
	glBindTexture(GL_TEXTURE_2D, r->font_tex);
	glEnableClientState(GL_TEXTURE_COORD_ARRAY);
	glVertexPointer(2, GL_FLOAT, sizeof(struct text_vertex), (void *)0);
	glTexCoordPointer(2, GL_FLOAT, sizeof(struct text_vertex), (void *)(2 * sizeof(float)));
	glColorPointer(4, GL_UNSIGNED_BYTE, sizeof(struct text_vertex),
		       (void *)offsetof(struct text_vertex, c));
	glDrawArrays(GL_TRIANGLES, 0, 6 * nq);
	glDisableClientState(GL_TEXTURE_COORD_ARRAY);
}

/* background gradient and the floor quad, after the draw list's vertices in the stream */
static void
fill_fixed(const struct drawlist *dl, struct view_vertex *v)
{
	double vrp[3];
	view_camera_vrp(&dl->cam, vrp);
	const float *t = dl->bg_top, *b = dl->bg_bottom;
	const float ndc[4][2] = { { -1, -1 }, { 1, -1 }, { -1, 1 }, { 1, 1 } };
	for (int k = 0; k < 4; k++) {
		const float *c = ndc[k][1] > 0 ? t : b;
		struct view_vertex q = { { ndc[k][0], ndc[k][1], 1 },
					 { (uint8_t)(c[0] * 255), (uint8_t)(c[1] * 255),
					   (uint8_t)(c[2] * 255), 255 } };
		v[k] = q;
		/* the floor around the view reference point */
		struct view_vertex f = { { (float)vrp[0] + ndc[k][0] * FLOOR_HALF, -0.0005f,
					   (float)vrp[2] - ndc[k][1] * FLOOR_HALF },
					 { 255, 255, 255, 255 } };
		v[4 + k] = f;
	}
}

int
render_frame(struct render *r, const struct drawlist *dl, uint64_t t_us, struct frame *dest)
{
	int w = dl->width, h = dl->height;
	if (w < 1 || h < 1 || w > r->max_w || h > r->max_h)
		return -1;
	float view[16], proj[16], ortho[16];
	struct view_vertex fixed[8];
	memset(&r->stats, 0, sizeof r->stats);
	view_camera_view_matrix(&dl->cam, view);
	view_camera_proj_matrix(&dl->cam, (double)w / h, proj);
	glm_ortho(0, (float)w, (float)h, 0, -1, 1, *(mat4 *)ortho);

	/* vertices of this frame */
	fill_fixed(dl, fixed);
	glBindBuffer(GL_ARRAY_BUFFER, r->stream);
	glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(sizeof(struct view_vertex) * (size_t)dl->nvert),
			dl->vert);
	glBufferSubData(GL_ARRAY_BUFFER, (GLintptr)(sizeof(struct view_vertex) * VIEW_MAX_VERT),
			sizeof fixed, fixed);
	r->stats.vertices = dl->nvert;
	stream_pointers();

	/* the instances, packed in the world; the shadow map from them */
	double vrp[3];
	view_camera_vrp(&dl->cam, vrp);
	int shadows = r->shadows && dl->floor;
	glEnableClientState(GL_VERTEX_ARRAY);
	glEnableClientState(GL_COLOR_ARRAY);
	pack_drawlist(&r->pack, dl, view, r->mesh, r->lod, r->nmesh);
	r->stats.instances = r->pack.instances;
	r->stats.triangles = r->pack.triangles;
	upload_packed(r);
	packed_pointers(r);
	glDisable(GL_DEPTH_TEST);
	glDisable(GL_BLEND);
	if (shadows)
		draw_shadow_map(r, dl, (float)vrp[0], (float)vrp[2]);
	float sbox[3] = { (float)vrp[0], (float)vrp[2], shadows ? 0.5f / SHADOW_HALF : 0 };

	/* the target: the top left w x h of the buffer, or of the multisampled one */
	glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
	surface_size(r, w, h);
	int y0 = 0;
	glViewport(0, y0, w, h);
	glScissor(0, y0, w, h);
	glEnable(GL_SCISSOR_TEST);
	glDepthMask(GL_TRUE);
	glStencilMask(0xff);
	glClearStencil(0);
	glClear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
	if (r->samples)
		glEnable(GL_MULTISAMPLE);

	/* opaque figures, lit, from the packed instances, nearest first */
	glMatrixMode(GL_PROJECTION);
	glLoadMatrixf(proj);
	glMatrixMode(GL_MODELVIEW);
	glLoadMatrixf(view);
	packed_pointers(r);
	glEnableClientState(GL_NORMAL_ARRAY);
	float key[3], fill[3], up[3];
	const float wfill[3] = { -0.5f, 0.25f, -0.6f }, wup[3] = { 0, 1, 0 };
	to_eye(view, dl->light, key);
	to_eye(view, wfill, fill);
	glm_vec3_normalize(fill);
	to_eye(view, wup, up);
	glUseProgram(r->prog_lit);
	glUniform3fv(r->lit_key, 1, key);
	glUniform3fv(r->lit_fill, 1, fill);
	glUniform3fv(r->lit_up, 1, up);
	glUniform3fv(r->lit_sbox, 1, sbox);
	glUniform1i(r->lit_smap, 0);
	glBindTexture(GL_TEXTURE_2D, r->blur_tex);
	glEnable(GL_DEPTH_TEST);
	glDepthFunc(GL_LEQUAL);
	glDepthMask(GL_TRUE);
	glEnable(GL_CULL_FACE);
	glCullFace(GL_BACK);
	draw_packed(r, PACK_CAST, PACK_OPAQUE);
	glDisableClientState(GL_NORMAL_ARRAY);
	glDisable(GL_CULL_FACE);

	/*
	 * The floor a hair below y = 0 (floor-level faces win) and then the
	 * background at the far plane, both depth-tested after the figures, so
	 * neither is shaded where a figure covers it.
	 */
	glBindBuffer(GL_ARRAY_BUFFER, r->stream);
	stream_pointers();
	if (dl->floor) {
		glUseProgram(r->prog_floor);
		glUniform3fv(r->floor_rgb, 1, dl->floor_rgb);
		glUniform3fv(r->floor_far, 1, dl->bg_bottom);
		glUniform1f(r->floor_grid, dl->grid);
		glUniform2f(r->floor_fade, (float)(2.0 * dl->cam.vrd), (float)(6.0 * dl->cam.vrd + 10));
		glUniform3fv(r->floor_sbox, 1, sbox);
		glUniform1i(r->floor_smap, 0);
		glBindTexture(GL_TEXTURE_2D, r->blur_tex);
		glDrawArrays(GL_TRIANGLE_STRIP, VIEW_MAX_VERT + 4, 4);
	}
	glUseProgram(r->prog_color);
	glUniform4f(r->color_tint, 1, 1, 1, 1);
	glMatrixMode(GL_PROJECTION);
	glLoadIdentity();
	glMatrixMode(GL_MODELVIEW);
	glLoadIdentity();
	glDrawArrays(GL_TRIANGLE_STRIP, VIEW_MAX_VERT, 4);
	glMatrixMode(GL_PROJECTION);
	glLoadMatrixf(proj);
	glMatrixMode(GL_MODELVIEW);
	glLoadMatrixf(view);
	packed_pointers(r);
	glEnableClientState(GL_NORMAL_ARRAY);
	glUseProgram(r->prog_lit);

	/* translucent instances */
	glDepthMask(GL_FALSE);
	glEnable(GL_BLEND);
	glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
	glEnable(GL_CULL_FACE);
	draw_packed(r, PACK_CLEAR, PACK_CLEAR);
	glDisableClientState(GL_NORMAL_ARRAY);
	glDisable(GL_CULL_FACE);

	/* icons in the world: faint where hidden, then in full */
	glBindBuffer(GL_ARRAY_BUFFER, r->stream);
	glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
	stream_pointers();
	glUseProgram(r->prog_color);
	glLoadMatrixf(view);
	glEnable(GL_LINE_SMOOTH);
	glDepthFunc(GL_GREATER);
	glUniform4f(r->color_tint, 1, 1, 1, XRAY_ALPHA);
	draw_batches(dl, VIEW_WORLD, 1);
	glDepthFunc(GL_LEQUAL);
	glUniform4f(r->color_tint, 1, 1, 1, 1);
	draw_batches(dl, VIEW_WORLD, 0);

	/* overlays in pixels, then text */
	glDisable(GL_DEPTH_TEST);
	glMatrixMode(GL_PROJECTION);
	glLoadMatrixf(ortho);
	glMatrixMode(GL_MODELVIEW);
	glLoadIdentity();
	draw_batches(dl, VIEW_SCREEN, 0);
	glDisable(GL_LINE_SMOOTH);
	draw_text(r, dl);
	glDisableClientState(GL_COLOR_ARRAY);
	glDisableClientState(GL_VERTEX_ARRAY);
	glBindBuffer(GL_ARRAY_BUFFER, 0);
	glUseProgram(0);
	glDisable(GL_BLEND);

	/* resolve the samples into the buffer's top left corner, and read back */
	if (r->fbo) {
		glBindFramebuffer(GL_READ_FRAMEBUFFER, r->fbo);
		glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
		glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
		glBindFramebuffer(GL_FRAMEBUFFER, 0);
	}
	glDisable(GL_SCISSOR_TEST);
	glFinish();

	dest->width = w;
	dest->height = h;
	dest->stride = 4 * r->max_w;
	dest->rgba = r->buf;
	dest->seq = ++r->seq;
	dest->t_us = t_us;
	dest->input_us = 0; /* the caller's to set: which input the picture is the first to show */
	dest->done_us = 0;  /* stamped when it is handed to a frame writer */
	return 0;
}

/*
 * The visibility map: the instances in their flat colours (the shader
 * without lighting, no blending, no dithering, no samples, so a colour
 * comes back as it went in), depth-tested, back faces culled (a ray from
 * inside a closed mesh does not see it, as pick.h's rays do not), read back
 * into the map's own arrays: colours as bytes into id, decoded in place;
 * window depths into dist, turned into distances along each pixel's ray.
 */
int
render_hemicube(struct render *r, const struct drawlist *dl, struct hemi_map *dest)
{
	if (dl->width != HEMI_N || dl->height != HEMI_N)
		return -1;
	const int n = HEMI_N;
	float view[16], proj[16];
	view_camera_view_matrix(&dl->cam, view);
	view_camera_proj_matrix(&dl->cam, 1, proj);
	pack_drawlist(&r->pack, dl, view, r->mesh, r->lod, r->nmesh);
	upload_packed(r);

	glBindFramebuffer(GL_FRAMEBUFFER, r->hemi_fbo);
	glViewport(0, 0, n, n);
	glDisable(GL_SCISSOR_TEST);
	glDisable(GL_BLEND);
	glDisable(GL_DITHER);
	glDisable(GL_MULTISAMPLE);
	glDisable(GL_LINE_SMOOTH);
	glClearColor(0, 0, 0, 0);
	glClearDepth(1);
	glDepthMask(GL_TRUE);
	glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
	glMatrixMode(GL_PROJECTION);
	glLoadMatrixf(proj);
	glMatrixMode(GL_MODELVIEW);
	glLoadMatrixf(view);
	glEnableClientState(GL_VERTEX_ARRAY);
	glEnableClientState(GL_COLOR_ARRAY);
	packed_pointers(r);
	glUseProgram(r->prog_color);
	glUniform4f(r->color_tint, 1, 1, 1, 1);
	glEnable(GL_DEPTH_TEST);
	glDepthFunc(GL_LESS);
	glEnable(GL_CULL_FACE);
	glCullFace(GL_BACK);
	draw_packed(r, PACK_CAST, PACK_CLEAR);
	glDisable(GL_CULL_FACE);
	glDisableClientState(GL_COLOR_ARRAY);
	glDisableClientState(GL_VERTEX_ARRAY);
	glBindBuffer(GL_ARRAY_BUFFER, 0);
	glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
	glUseProgram(0);
	glPixelStorei(GL_PACK_ALIGNMENT, 4);
	glReadPixels(0, 0, n, n, GL_RGBA, GL_UNSIGNED_BYTE, dest->id);
	glReadPixels(0, 0, n, n, GL_DEPTH_COMPONENT, GL_FLOAT, dest->dist);
	glBindFramebuffer(GL_FRAMEBUFFER, 0);
	glEnable(GL_DITHER);

	/* GL's rows run bottom to top: swap them while decoding (row y with row n-1-y) */
	const double zn = dl->cam.znear, zf = dl->cam.zfar, t = tan(dl->cam.fovy / 2);
	for (int y = 0; y < (n + 1) / 2; y++) {
		int y2 = n - 1 - y;
		for (int x = 0; x < n; x++) {
			int a = y * n + x, b = y2 * n + x;
			uint32_t ia = dest->id[a], ib = dest->id[b];
			float da = dest->dist[a], db = dest->dist[b];
			dest->id[a] = ib;
			dest->id[b] = ia;
			dest->dist[a] = db;
			dest->dist[b] = da;
		}
	}
	for (int y = 0; y < n; y++)
		for (int x = 0; x < n; x++) {
			int i = y * n + x;
			const uint8_t *c = (const uint8_t *)&dest->id[i];
			uint32_t id = (uint32_t)c[0] << 16 | (uint32_t)c[1] << 8 | c[2];
			double d = dest->dist[i];
			dest->id[i] = id;
			if (!id || d >= 1) {
				dest->id[i] = 0;
				dest->dist[i] = INFINITY;
				continue;
			}
			/* window depth to the eye's z, then along the pixel's ray */
			double zndc = 2 * d - 1, ze = 2 * zn * zf / (zf + zn - zndc * (zf - zn));
			double xn = (2 * (x + 0.5) / n - 1) * t, yn = (1 - 2 * (y + 0.5) / n) * t;
			dest->dist[i] = (float)(ze * sqrt(1 + xn * xn + yn * yn));
		}
	dest->cam = dl->cam;
	return 0;
}

struct render_stats
render_last_stats(const struct render *r)
{
	return r->stats;
}
