/*
 * assess_json.h - an assessment as JSON text (jbuf: nothing allocates, so
 * the assessment events of a frame are written as the others are): a
 * result with its whole derivation for the commands' replies, its summary
 * for the events, and the body angles by name.
 */
#ifndef POSTURE_ASSESS_JSON_H
#define POSTURE_ASSESS_JSON_H

#include "assess/assess.h"
#include "assess/body_angles.h"
#include "daemon/jbuf.h"

/* the method's name as the protocol writes it: "rula", "reba", "owas" */
const char *assess_json_method(enum assess_method m);

/*
 * The keys of a result, without the braces around them (the caller adds
 * its own keys, "figure", "inputs", before or after):
 *   "score","action_level","action","side":"left"|"right"|null,
 *   "parts":{NAME:{"angle","angle_name","band","base","adjust":[{"value","reason"}],
 *                  "score","max"}},
 *   "tables":{TABLE:value},  (each table's cell, the issue's {"A":3,"B":4,"C":5})
 *   "lookups":[{"table","idx":{NAME:i},"value"}],  (every look-up with its indices)
 *   "worst":NAME|null, and for OWAS "code":"2131".
 * first: no comma before the first key.
 */
void assess_json_result_keys(struct jbuf *j, const struct assess_result *r, int first);

/*
 * A result's summary, an object: {"score","action_level","side","worst",
 * "parts":{NAME:score}} (OWAS: and "code"), what an assessment event says.
 */
void assess_json_summary(struct jbuf *j, const struct assess_result *r);

/* the body angles as an object {NAME:value} in body_angle_names' order (NAN: null) */
void assess_json_angles(struct jbuf *j, const struct body_angles *a);

#endif
