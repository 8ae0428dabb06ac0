/*
 * figure.h - the peabody figure language (Figure A.1 style): reading a
 * figure file into a model, and writing a model back out.
 *
 * Reading is all-or-nothing: on any error nothing is returned, and the
 * message names "file:line:column: what was expected". Writing emits numbers
 * in base units (m, rad, kg) with 17 significant digits and orientations as
 * quaternions, so load -> save -> load gives an identical model.
 * The grammar is documented at the top of figure_read.c.
 */
#ifndef POSTURE_FIGURE_H
#define POSTURE_FIGURE_H

#include <stddef.h>
#include <stdio.h>

#include "figure/model.h"

/*
 * Parses text. `origin` names the text in messages (a file name);
 * `base_dir` resolves relative mesh paths (NULL: the current directory).
 * Returns the model, or NULL with the message in err.
 */
struct model *figure_read_string(const char *text, size_t len, const char *origin,
				 const char *base_dir, char *err, size_t errlen);

/* reads and parses a file; mesh paths are relative to the file's directory */
struct model *figure_read_file(const char *path, char *err, size_t errlen);

/*
 * writes m in the figure language; returns 0, or -1 with errno set: EIO on
 * an I/O error, EINVAL when m holds something the language cannot express
 * (a name that is not [A-Za-z_][A-Za-z0-9_]*, a mesh path with '"' or a
 * control byte, a non-finite number). Mesh geometry is written as its path;
 * size[2] of cylinders and capsules is not written (it is unused).
 */
int figure_write(const struct model *m, FILE *f);

/* writes to PATH.tmp, then renames it to PATH; returns 0, or -1 with err set */
int figure_write_file(const struct model *m, const char *path, char *err, size_t errlen);

#endif
