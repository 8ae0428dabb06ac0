/*
 * session.h - the environment and postures as versioned text: session
 * files, posture files, journal snapshots and undo checkpoints all use it.
 * Numbers are written with 17 significant digits, so reading back gives
 * the same state bit for bit.
 */
#ifndef POSTURE_SESSION_H
#define POSTURE_SESSION_H

#include <stddef.h>
#include <stdio.h>

#include "assess/assess.h"
#include "pose/env.h"

/* 2: a human's measures and provenance (manikin.h); 3: the family shown; 4: the assessments'
 * settings (set assess), an optional line: older sessions read with the defaults; 5: the
 * loads on the figures (add load), "load" lines: older sessions have none */
#define SESSION_VERSION 5
#define POSTURE_VERSION 2 /* 2: a human's support height */

/* writes the whole environment; 0, or -1 on an I/O error */
int session_write(const struct env *e, FILE *f);
/* ... and the assessments' settings cfg (set assess; NULL: none written) */
int session_write_with(const struct env *e, const struct assess_config *cfg, FILE *f);

/*
 * Reads an environment from text into dest (which must be initialised and
 * empty). Figure files are read relative to base_dir, "lib:NAME" ones from
 * library_dir. On error returns -1 with "line N: ..." in err and leaves
 * dest empty.
 */
int session_read(const char *text, size_t len, const char *base_dir, const char *library_dir,
		 struct env *dest, char *err, size_t errlen);
/*
 * ... and the assessments' settings into cfg (NULL: checked, not kept): the
 * session's, else (an older session) the defaults. cfg is left alone on error.
 */
int session_read_with(const char *text, size_t len, const char *base_dir,
		      const char *library_dir, struct env *dest, struct assess_config *cfg,
		      char *err, size_t errlen);

/* a figure's posture: root and every joint value */
int session_write_posture(const struct env *e, int fig, FILE *f);

/*
 * Applies a posture file to figure fig: joints by name (all must exist),
 * the root by site name and frame. A human's posture file says how high
 * its feet were (support: the lowest site of its feet and toes); a human
 * of another size is then raised or lowered until its feet are as high,
 * so it stands where the file's figure stood, joint angles as they were.
 * Checks everything before changing anything.
 */
int session_read_posture(struct env *e, int fig, const char *text, size_t len, char *err,
			 size_t errlen);
/*
 * The same onto state s of model m (a human's when is_human), which need
 * not be a figure's of the environment: a copy, to measure a posture on
 * without changing what is shown. s is unchanged on error.
 */
int session_posture_onto(const struct model *m, int is_human, struct state *s, const char *text,
			 size_t len, char *err, size_t errlen);

/*
 * Applies one posture statement of a session ("root FIG SITE XFORM" or
 * "q FIG VALUES..."), as the journal records solver changes. 0 or -1.
 */
int session_apply_line(struct env *e, const char *line, size_t len, char *err, size_t errlen);

/* writes one figure's posture statements (root and q lines) */
void session_write_figure_posture(const struct env *e, int fig, FILE *f);

/* writes the whole environment into a malloc'd string; NULL when out of memory */
char *session_to_string(const struct env *e, size_t *len);
/* ... with the assessments' settings (NULL: none) */
char *session_to_string_with(const struct env *e, const struct assess_config *cfg, size_t *len);

#endif
