/*
 * render.h - draws a draw list (view.h) offscreen with OSMesa, like
 * MuJoCo's mjr_. This is the only module that talks to GL.
 *
 * One struct render owns a GL context and an RGBA buffer of at most
 * max_w x max_h pixels; every view of any size up to that renders into its
 * top left corner, so changing sizes between views costs nothing. Meshes
 * (the unit primitives, every model's Wavefront meshes) and the font atlas
 * are uploaded once; render_frame allocates nothing of its own.
 *
 * Picture: figures with per-pixel lighting (a key and a fill light over a
 * sky/ground ambient term), a floor with an antialiased grid fading into
 * the distance, soft shadows on the floor and on floor-level faces (a
 * small shadow map of the casters squashed along the light, sampled
 * bilinearly), a background gradient, translucent instances, the icons
 * (lines and triangles; parts hidden by geometry drawn faintly), then
 * screen-space overlays and text with a dark outline. Instances are packed
 * into one world-space buffer and drawn nearest first, so a frame is a
 * handful of draw calls. With samples = 4 it renders through a 4x
 * multisampled framebuffer and resolves into the buffer.
 *
 * GL runs on the calling thread; a struct render must stay on one thread.
 */
#ifndef POSTURE_RENDER_H
#define POSTURE_RENDER_H

#include <stddef.h>
#include <stdint.h>

#include "draw/frame.h"
#include "draw/hemi.h"
#include "figure/model.h"
#include "draw/view.h"

#define RENDER_MAX_MESH 512 /* built-in and model meshes together */

struct render_def {
	int max_w, max_h;      /* largest image, pixels */
	int samples;           /* 0: no antialiasing; 4: 4x multisampling */
	int shadows;           /* 1: shadows on the floor */
	const char *font_path; /* a TrueType face for the text */
};

/*
 * 1280 x 720, shadows, DejaVu Sans Mono, no multisampling: on llvmpipe 4x
 * multisampling costs about three times the frame (see the render bench);
 * lines are smoothed either way.
 */
struct render_def render_default_def(void);

/*
 * Makes the context, buffers, shaders, unit meshes and font atlas.
 * Returns NULL with a message in err when OSMesa cannot make a context of
 * that size, a shader does not compile, the font does not load or memory
 * runs out.
 */
struct render *render_make(const struct render_def *d, char *err, size_t errlen);
void render_free(struct render *r);

/*
 * Takes in the meshes of m (normals computed once, kept for the frames).
 * Returns the mesh id of m's mesh 0, which view_add_figure takes as
 * mesh_base (ids below it belong to the built-in primitives and earlier
 * models), or -1 with a message in err when the mesh table is full or
 * memory runs out.
 */
int render_add_model(struct render *r, const struct model *m, char *err, size_t errlen);

/*
 * A mesh made at run time (an analysis's surface): nvert vertices (vert and
 * normal, 3 floats each, world or mesh units) and ntri triangles of vertex
 * indices (tri, 3 each, counter-clockwise seen from outside: the side
 * drawn). id -1 takes a new mesh id; an id this returned earlier is
 * replaced (ntri 0 empties it: it draws nothing until set again, and keeps
 * its id for reuse). The arrays are copied; call it when the mesh changes,
 * not every frame. Returns the id, or -1 with a message in err (a vertex
 * index out of range, the mesh table full, out of memory; an id it did not
 * make), the mesh then unchanged.
 */
int render_set_mesh(struct render *r, int id, const float *vert, const float *normal, int nvert,
		    const int *tri, int ntri, char *err, size_t errlen);

/*
 * Draws dl (dl->width x dl->height, at most max_w x max_h) and reads it
 * back. dest gets the picture: its rgba points into the renderer's buffer
 * (rows top to bottom, stride 4 * max_w) and stays valid until the next
 * render_frame or render_free; seq counts frames from 1; t_us is copied.
 * Returns 0, or -1 when the size is out of range (dest untouched).
 */
int render_frame(struct render *r, const struct drawlist *dl, uint64_t t_us, struct frame *dest);

/*
 * The visibility map of §3.7.1 (hemi.h): dl is HEMI_N x HEMI_N pixels
 * through a camera from hemi_camera, with the figures added by
 * view_add_figure_ids (any other instances are taken as they are; lines,
 * text, the floor and the background are not drawn). Renders into a small
 * target of its own, so the last render_frame's picture is untouched,
 * and fills dest (its camera too). Returns 0, or -1 for a list of another
 * size. Allocates nothing.
 */
int render_hemicube(struct render *r, const struct drawlist *dl, struct hemi_map *dest);

/* what the last render_frame drew */
struct render_stats {
	int instances; /* mesh instances */
	int triangles; /* of the instances, without shadows */
	int vertices;  /* icon and overlay vertices */
	int glyphs;
};
struct render_stats render_last_stats(const struct render *r);

#endif
