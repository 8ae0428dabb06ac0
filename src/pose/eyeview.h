/*
 * eyeview.h - a view whose camera is a manikin's eyes (add view NAME
 * eyes=FIG): the camera sits at the eye's centre (the eyeball's "gaze"
 * site) and looks along its line of sight (the site's +z), following the
 * head and the eyes every frame. which=both: the cyclopean eye, midway
 * between the two, looking along the mean of their lines of sight.
 *
 * The view's width is its horizontal field of view (hfov_deg); the
 * vertical one follows from the picture's aspect. Defaults (research file
 * §6.2): both eyes, DELMIA Human's binocular 90° (the field both eyes
 * share: what the picture shows, both eyes see); one eye, CATIA V5 Human
 * Builder's monocular 100°.
 */
#ifndef POSTURE_EYEVIEW_H
#define POSTURE_EYEVIEW_H

#include "pose/env.h"

#define EYEVIEW_HFOV_BOTH 90.0 /* deg: DELMIA Human's horizontal binocular field */
#define EYEVIEW_HFOV_ONE 100.0 /* deg: CATIA V5 Human Builder's horizontal monocular field */
#define EYEVIEW_HFOV_MIN 1.0   /* the horizontal fields a view may ask for, degrees */
#define EYEVIEW_HFOV_MAX 170.0 /* a perspective picture's: 180 would be a flat line */
#define EYEVIEW_AIM 1.0        /* m: the target kept this far along the line of sight */

/*
 * The cones an eye view's picture marks by default (full angles about the
 * line of sight, degrees; research file §6.2): CATIA V5 Human Builder's
 * central spot, 3; DELMIA Human's central field limits for reading, 20,
 * symbol recognition, 40, and colour discrimination, 60.
 */
#define EYEVIEW_CONE_CENTRAL 3.0
#define EYEVIEW_CONE_READING 20.0
#define EYEVIEW_CONE_SYMBOLS 40.0
#define EYEVIEW_CONE_COLOUR 60.0
#define EYEVIEW_CONE_MIN 0.5   /* a marked cone's full angle at least, degrees */
#define EYEVIEW_CONE_MAX 170.0 /* and at most */

/*
 * Sight cones drawn in other views (set view VIEW sight=FIG|all|off): from
 * the cyclopean eye along the mean line of sight, each cone's sides this
 * long, so its rim lies at that range from the eye. Process Simulate's
 * vision envelope is a cone to a maximum range set by the user (research
 * file §6.2, no default published); 1 m is the farther of Hill & Kroemer's
 * two viewing distances (0.5 and 1.0 m, §6.2), a workplace's arm's length
 * and more. At least the eye views' near plane (5 cm: shorter lies inside
 * the head), at most 20 m (a hall).
 */
#define EYEVIEW_SIGHT_LEN 1.0
#define EYEVIEW_SIGHT_LEN_MIN 0.05
#define EYEVIEW_SIGHT_LEN_MAX 20.0
#define EYEVIEW_SIGHT_ALL "all" /* sight=all: every figure with eyes */

/*
 * The cones figure fig's sight is drawn with: those of the first eye view
 * through its eyes (env_view.eyes), else the defaults. Returns how many.
 */
int eyeview_figure_cones(const struct env *e, int fig, double dest[ENV_VIEW_CONES]);
/* 1 when view v draws figure fig's sight cones (not in fig's own eye view: it marks them) */
int eyeview_draws_sight(const struct env *e, const struct env_view *v, int fig);

/* the default cones into dest (ENV_VIEW_CONES of them); returns how many */
int eyeview_default_cones(double dest[ENV_VIEW_CONES]);
/*
 * "off" (no cones: returns 0) or 1 to ENV_VIEW_CONES full angles "A,B,..."
 * (bare numbers, degrees, each EYEVIEW_CONE_MIN to EYEVIEW_CONE_MAX) into
 * dest; returns how many, or -1 (dest then undefined)
 */
int eyeview_parse_cones(const char *s, double dest[ENV_VIEW_CONES]);
/* 1 when v marks the default cones */
int eyeview_cones_default(const struct env_view *v);

/* which eye (env_view.eyes_which) and back; -1: none such */
const char *eyeview_which_str(int which);
int eyeview_which_find(const char *name);
/* the default horizontal field of view for which */
double eyeview_default_hfov(int which);

/*
 * The eye sites of model m for which: sites[0] and sites[1] (the same for
 * one eye). Returns 0, or -1 when m has no eyeball_l.gaze and
 * eyeball_r.gaze (not a human).
 */
int eyeview_sites(const struct model *m, int which, int sites[2]);

/*
 * The camera's place and line of sight (unit) from figure fig's eyes now
 * (its site frames current). Returns 0, or -1 when it has no eyes.
 */
int eyeview_camera(const struct env *e, int fig, int which, double eye[3], double dir[3]);

/* vertical field of view (deg) of a w x h picture hfov_deg wide, at most ENV_VIEW_FOVY_MAX */
double eyeview_fovy(double hfov_deg, int w, int h);

/*
 * Places an eye view's camera (v->eyes set) at its figure's eyes now, and
 * its vertical field of view from hfov_deg and its size. A view whose
 * figure is gone (or is no view of the eyes) is left as it is. Returns 1
 * when it was placed, else 0.
 */
int eyeview_follow(const struct env *e, struct env_view *v);
/* every eye view of e */
void eyeview_follow_all(struct env *e);

#endif
