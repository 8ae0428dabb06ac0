/*
 * demo_scene.h - the standard scenes the renderer's tests, tools and
 * benchmarks show: the human standing at rest, and the human seated as a
 * driver in the vehicle seat (pelvis on the H-point tilted back, heels on
 * the heel points with the soles level, palms on the wheel's grips, all
 * solved with the IK of Chapter 4).
 */
#ifndef POSTURE_DEMO_SCENE_H
#define POSTURE_DEMO_SCENE_H

#include <stddef.h>

#include "pose/ik.h"
#include "figure/model.h"
#include "figure/state.h"

#define DEMO_SCENE_SEAT "src/figures/vehicle_seat.fig"

struct demo_scene {
	struct model *human, *seat; /* seat: NULL when standing */
	struct state *hs, *ss;
	struct ik *ik; /* the seated posture's constraints (for goal icons); NULL standing */
	int seated;
};

/*
 * Makes scene "standing" or "seated" (the seat read from seat_path).
 * Returns 0, or -1 with a message; demo_scene_free cleans up either way.
 */
int demo_scene_make(struct demo_scene *sc, const char *name, const char *seat_path, char *err,
		    size_t errlen);
void demo_scene_free(struct demo_scene *sc);

struct drawlist;
/*
 * Every icon of the dissertation on the scene: the manipulation frame on
 * the right hand (unless frame is 0), the translation arrow, the elbow's
 * rotation wheel with its limits, rotation fans to a turned goal, the IK
 * goals, balance, the status and message lines and the pointer.
 */
void demo_scene_icons(struct drawlist *dl, const struct demo_scene *sc, int frame);

struct camera;
/* the scene's camera: a front three-quarter view, or the driver from the front left */
void demo_scene_camera(const struct demo_scene *sc, struct camera *cam);

/*
 * The scene's draw list for cam at w x h (base: the figures' mesh bases):
 * icons 0 none, 1 every icon, 2 every icon but the manipulation frame.
 */
void demo_scene_draw(struct drawlist *dl, const struct demo_scene *sc, const struct camera *cam,
		     int w, int h, const int base[2], int icons);

#endif
