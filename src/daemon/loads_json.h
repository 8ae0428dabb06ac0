/*
 * loads_json.h - a figure's loads analysis (loads_live.h) as JSON text
 * (jbuf: nothing allocates, so the loads events of a frame are written as
 * the others are): the whole analysis for analyze loads, its summary for
 * the loads event and for the status line.
 */
#ifndef POSTURE_LOADS_JSON_H
#define POSTURE_LOADS_JSON_H

#include <stddef.h>

#include "daemon/jbuf.h"
#include "daemon/loads_live.h"

/*
 * The keys of figure slot fig's analysis a, without the braces around
 * them (the caller adds "figure", "frame" before):
 *   "seated", "weight" (N), "loads":[{"segment","point","force","torque","mass",
 *     "load","carried","hand","share"}],
 *   "joints":{JOINT:{"point","force","moment","torque":[per dof],
 *     "anatomical":{AXIS:N m}}}  (anatomical only for the joints statics gives it),
 *   "supports":[{"site","kind","point","force","moment","share"}],
 *   "balance":{"cop","margin","contacts","lifts","tips"},
 *   "low_back":{"level","compression","shear_ap","shear_lat","limit":{"action","max",
 *     "zone"},"model","muscle_force","moment_arm","moment_sagittal","moment_lateral",
 *     "moment_axial","unmodelled":[...]} | null, with "low_back_why" when null,
 *   "strength":{"capable","weakest":{"joint","axis"}|null,"modelled",
 *     "joints":{JOINT:{AXIS:{"percent","mean","sd","moment","angle"}}}} | null
 *     (a percent null where no published curve covers it), with "strength_why" when null.
 * first: no comma before the first key.
 */
void loads_json_keys(struct jbuf *j, const struct env *e, int fig, const struct loads_live_fig *a,
		     int first);

/*
 * The summary a loads event tells, keys without braces, each after a comma:
 *   "low_back":{"level","compression","shear_ap","shear_lat","limit":{"action","max",
 *     "zone"}}|null,
 *   "weakest":{"joint","axis","percent_capable"}|null,
 *   "supports":[{"site","force"}],"tips","loads" (how many act)
 */
void loads_json_summary_keys(struct jbuf *j, const struct env *e, int fig,
			     const struct loads_live_fig *a);

/* the weakest joint's model name and axis name of a, NULL when strength gives none */
const char *loads_json_weakest(const struct env *e, int fig, const struct loads_live_fig *a,
			       const char **axis);

/* "   L5/S1 2.1 kN, 82 % capable" for the status line ("" for no low back), into dest */
void loads_json_status(const struct loads_live_fig *a, char *dest, size_t len);

#endif
