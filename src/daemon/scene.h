/*
 * scene.h - the views' pictures: each view of the environment drawn by the
 * renderer (made when first needed; without OSMesa the daemon runs on with
 * no pictures), written to a PNG file per view and the framebuffer, and
 * sent as frame events, at most SCENE_PERIOD_US apart.
 */
#ifndef POSTURE_SCENE_H
#define POSTURE_SCENE_H

#include <stdint.h>

#include "interact/menu.h"
#include "daemon/daemon.h"
#include "daemon/events.h"
#include "draw/frame.h"
#include "draw/render.h"
#include "draw/sink.h"
#include "draw/view.h"

#define SCENE_PERIOD_US 100000 /* frame files and frame events: at most 10 a second */

struct scene {
	struct render *r; /* made when first needed */
	int failed;       /* OSMesa could not start: no pictures */
	struct drawlist *dl;
	struct hemi_map *hemi; /* §3.7.1's visibility map, made with the renderer */
	int mesh_base[ENV_MAX_FIGURES]; /* each figure's meshes in the renderer */
	uint32_t mesh_gen[ENV_MAX_FIGURES];
	const char *frames_dir; /* NULL: no frame files */
	struct sink *png[ENV_MAX_VIEWS];
	char png_name[ENV_MAX_VIEWS][MODEL_NAME_MAX];
	struct sink *fb;             /* the first view goes here too, when set */
	struct sink_png_encoder enc; /* frame events */
	struct frame frame;          /* the last view drawn */
	uint64_t last_png_us, last_event_us;
	int dirty; /* something changed since the pictures were last published */
	struct menu_layout menu_layout; /* the pop-up menu's rows as last laid out */
	uint64_t drawn_us; /* time spent rendering so far, by d->now_us (the loop's stall measure) */
};

void scene_init(struct scene *sc, const char *frames_dir);
void scene_free(struct scene *sc);

/*
 * Draws view v of d's environment; *dest stays valid until the next
 * drawing. Returns 0, or -1 with err when there is no renderer.
 */
int scene_draw(struct scene *sc, struct daemon *d, int v, const struct frame **dest, char *err,
	       size_t errlen);

/*
 * §3.7.1's visibility map from origin towards dir (the camera) over the
 * environment's figures, into the scene's own map (valid until the next
 * call). Of figure slot skip (-1: none), the segments whose skip_seg[seg]
 * is set are left out, or the whole figure when skip_seg is NULL. Returns
 * it, or NULL with err when there is no renderer or no direction.
 */
const struct hemi_map *scene_hemicube(struct scene *sc, struct daemon *d, const double origin[3],
				      const double dir[3], int skip, const unsigned char *skip_seg,
				      char *err, size_t errlen);

/*
 * After a frame that changed something: every view drawn, written and sent
 * where due at time now. Returns 1 when it drew, 0 when nothing was due.
 */
int scene_publish(struct scene *sc, struct daemon *d, struct events *E, uint64_t now);

#endif
