/*
 * scene.h - the views' pictures: each view of the environment drawn by the
 * renderer (made when first needed; without OSMesa the daemon runs on with
 * no pictures), written to a PNG file per view and the framebuffer, and
 * sent as frame events, at most SCENE_PERIOD_US apart.
 *
 * The loop only draws: files and the screen are written by two frame
 * writers (draw/frame_writer.h) on threads of their own, one for the PNG
 * files (encoding and fsync take tens of milliseconds) and one for the
 * framebuffer (a pixel conversion of 1-2 ms a 1280x720 frame, measured),
 * so a file being written never holds the screen back. Frame events'
 * PNGs are made on the files' thread too (a relay sink per view) and sent
 * by the loop when they are ready.
 */
#ifndef POSTURE_SCENE_H
#define POSTURE_SCENE_H

#include <stdint.h>

#include "interact/menu.h"
#include "daemon/daemon.h"
#include "daemon/envelopes.h"
#include "daemon/events.h"
#include "daemon/tint.h"
#include "draw/frame.h"
#include "draw/frame_writer.h"
#include "draw/render.h"
#include "draw/sink.h"
#include "draw/view.h"

#define SCENE_PERIOD_US 100000 /* frame files and frame events: at most 10 a second */
/*
 * the files' writer yields the CPUs to the loop and the renderer: PNG
 * encoding at the same priority preempted the loop on a 2-core machine,
 * and a file written late is only a file dropped
 */
#define SCENE_FILES_NICE 10

/* the band at the bottom of a layout's screen: its message and status (edit) lines */
#define SCENE_BAND (2 * VIEW_LINE_PX)

struct scene {
	struct render *r; /* made when first needed */
	int failed;       /* OSMesa could not start: no pictures */
	struct drawlist *dl;
	struct hemi_map *hemi; /* §3.7.1's visibility map, made with the renderer */
	struct hemi_map *idmap[2]; /* analyze visibility's two maps (scene_id_map), made with it */
	int mesh_base[ENV_MAX_FIGURES]; /* each figure's meshes in the renderer */
	uint32_t mesh_gen[ENV_MAX_FIGURES];
	const char *frames_dir; /* NULL: no frame files */
	struct frame_writer *files; /* the views' PNG files, slot v for view v; made when needed */
	char png_name[ENV_MAX_VIEWS][MODEL_NAME_MAX]; /* the file slot v writes; "": none yet */
	struct sink *fb;             /* the first view goes here too, when set; then the screen's */
	struct frame_writer *screen; /* writes fb; made when needed */
	int screen_held;             /* the VT is switched away: nothing drawn to the screen */
	/* the kiosk's screen with the layout's views tiled on it, composed for fb */
	uint8_t *screen_rgba;
	int screen_w, screen_h;
	struct frame screen_frame;
	int screen_file; /* FRAMES/screen.png has its slot in the files' writer */
	int writer_failed;           /* no thread for a writer: said once */
	/* frame events: view v's PNG made by relay[v] in the files' writer (slot ENV_MAX_VIEWS + v) */
	struct sink *relay[ENV_MAX_VIEWS];
	int relay_pending[ENV_MAX_VIEWS]; /* a picture handed over, its event not sent yet */
	struct frame frame;          /* the last view drawn */
	uint64_t last_png_us, last_event_us;
	int dirty; /* something changed since the pictures were last published */
	uint64_t input_us; /* the oldest input taken since the last pictures (0: none), for latency */
	struct menu_layout menu_layout; /* the pop-up menu's rows as last laid out */
	/* time spent rendering so far, by wall_us and by cpu_us (the loop's stall measure) */
	uint64_t drawn_us, drawn_cpu_us;
	uint64_t (*cpu_us)(void); /* the calling thread's CPU time; NULL: not measured */
	uint64_t (*wall_us)(void); /* the real clock (never a replay's); NULL: not measured */
	int replaying;             /* a replay's pictures: the status line shows no timings */
	struct tint tint;          /* a tinted view's colours (set view VIEW tint=...) */
	/*
	 * The kept reach envelopes' surfaces in the renderer (render_set_mesh):
	 * for store slot k its reach and comfort meshes' ids plus 1 (0: none
	 * made yet), and the envelope's serial they hold (0: nothing); uploaded
	 * when an envelope is new, not every frame. envelopes_seen: the store's
	 * serial last drawn (a change redraws).
	 */
	int envelope_mesh[ENVELOPES_MAX][2];
	uint64_t envelope_serial[ENVELOPES_MAX];
	uint64_t envelopes_seen;
};

void scene_init(struct scene *sc, const char *frames_dir);
/*
 * The newest input-to-pixels latencies of the framebuffer (frame_writer.h):
 * up to max into dest, oldest first; how many there are (0: no framebuffer).
 */
int scene_latencies(struct scene *sc, uint64_t *dest, int max);

/* the KMS screen's render-to-flip times (sink_kms_times): 0, or -1 when the screen is not KMS */
int scene_flip_times(struct scene *sc, struct kms_times_summary *dest);

void scene_free(struct scene *sc);
/*
 * The screen given up (held 1: the VT switched away; frames wait, a KMS
 * screen's DRM master dropped once the last frame is written) or taken back
 * (held 0: master taken again, the next frame drawn whole).
 */
void scene_hold_screen(struct scene *sc, int held);
/*
 * A KMS screen's connectors read again (a hot-plug): 1 when it now shows
 * another mode or connector (its size in w, h), 0 when as before or not a
 * KMS screen, -1 when none can show (said on stderr).
 */
int scene_reprobe_screen(struct scene *sc, int *w, int *h);

/*
 * Draws view v of d's environment; *dest stays valid until the next
 * drawing. Returns 0, or -1 with err when there is no renderer.
 */
int scene_draw(struct scene *sc, struct daemon *d, int v, const struct frame **dest, char *err,
	       size_t errlen);

/*
 * A picture through vw's camera at its size (vw need not be one of the
 * environment's views), for a file rather than the screen: the figures in
 * vw's tint, no icons, status lines, pointer or menu. only >= 0: of the
 * humans only figure slot only, with every figure that is not a human (the
 * objects it works with); -1: every figure. Ghosts are left out. *dest
 * stays valid until the next drawing. 0, or -1 with err.
 */
int scene_draw_picture(struct scene *sc, struct daemon *d, const struct env_view *vw, int only,
		       const struct frame **dest, char *err, size_t errlen);

/*
 * The kiosk's screen as the framebuffer shows it: with a layout, its views
 * drawn now and tiled; without, the first view. Valid until the next
 * drawing. 0, or -1 with err.
 */
int scene_draw_screen(struct scene *sc, struct daemon *d, const struct frame **dest, char *err,
		      size_t errlen);

/*
 * §3.7.1's visibility map from origin towards dir (the camera) over the
 * environment's figures, into the scene's own map (valid until the next
 * call). Of figure slot skip (-1: none), the segments whose skip_seg[seg]
 * is set are left out, or the whole figure when skip_seg is NULL. Returns
 * it, or NULL with err when there is no renderer or no direction.
 */
/*
 * An id map through cam (HEMI_N square, any field of view) into map slot
 * (0 or 1): every figure but the ghosts, or figure only alone (-1: all),
 * figure skip's segments whose skip_seg is set left out (NULL: none).
 * NULL with err when there is no renderer. Allocates nothing once ready.
 */
const struct hemi_map *scene_id_map(struct scene *sc, struct daemon *d, const struct camera *cam,
				    int slot, int only, int skip, const unsigned char *skip_seg,
				    char *err, size_t errlen);

const struct hemi_map *scene_hemicube(struct scene *sc, struct daemon *d, const double origin[3],
				      const double dir[3], int skip, const unsigned char *skip_seg,
				      char *err, size_t errlen);

/*
 * After a frame that changed something: every view drawn, handed to the
 * writers and sent where due at time now. Returns 1 when it drew, 0 when
 * nothing was due.
 */
int scene_publish(struct scene *sc, struct daemon *d, struct events *E, uint64_t now);

/* 1 when a changed picture waits to be published somewhere (files, screen, frame events) */
int scene_waiting(const struct scene *sc, const struct events *E);

/*
 * The writers' news, without waiting for them: the frame events whose
 * PNGs are ready sent to E, failures logged (the newest message and how
 * many), the counters into d's stats.
 */
void scene_sync(struct scene *sc, struct daemon *d, struct events *E);

#endif
