/*
 * assess_report.h - a posture's assessment as the one-page report a
 * human-factors engineer files (export assessment FIG PATH): a
 * self-contained HTML file, printable on one A4 page, holding the picture
 * of the figure, RULA's, REBA's and OWAS's derivations (each part's angle,
 * band, adjustments with their reasons and score; each table look-up with
 * its indices; the grand score, action level and the method's words), the
 * inputs and thresholds they were scored with (each threshold's source),
 * the figure's size, the date, the methods' sources and what is not
 * modelled. Every text is escaped; the file is written whole or not at
 * all (export_file.h).
 */
#ifndef POSTURE_ASSESS_REPORT_H
#define POSTURE_ASSESS_REPORT_H

#include <jansson.h>
#include <stddef.h>
#include <stdint.h>

#include "assess/assess.h"
#include "assess/body_angles.h"

#define ASSESS_REPORT_MAX_INPUTS 24

/* one input the scores were made with that the posture does not show: "load", "12.5 kg", why */
struct assess_report_input {
	char key[32];
	char value[64];
	char note[160];
};

struct assess_report {
	const char *figure;   /* its name */
	const json_t *about;  /* its size as list figures says it (manikin_json), or NULL */
	const struct body_angles *angles;
	const struct assess_result *res[ASSESS_NMETHODS]; /* enum assess_method */
	struct assess_config cfg;                        /* the thresholds scored with */
	int ninputs;
	struct assess_report_input input[ASSESS_REPORT_MAX_INPUTS];
	const uint8_t *png; /* the picture, its PNG bytes */
	size_t png_len;
	int png_w, png_h;
	char date[64];        /* when it was made, as written ("2025-11-27 17:05 UTC") */
};

/*
 * Writes the report to path (resolved by the caller; never through a
 * link). 0, or -1 with why in err (nothing written then).
 */
int assess_report_write(const struct assess_report *r, const char *path, char *err, size_t errlen);

#endif
