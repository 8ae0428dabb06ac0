/*
 * envelope_comfort.h - the comfort zone's joint ranges (envelope.h): the
 * defaults and their sources, a request's text form, and the narrowed
 * limits a comfort solve runs with.
 */
#ifndef POSTURE_ENVELOPE_COMFORT_H
#define POSTURE_ENVELOPE_COMFORT_H

#include <stddef.h>

#include "figure/model.h"

/* a joint dof held within [lo, hi] degrees for the comfort zone */
#define ENVELOPE_COMFORT_MAX 24
struct envelope_comfort_range {
	char joint[24]; /* the human's limb joint name without its side ("shoulder", "elbow"...),
			   "spine" for the trunk, or any joint's full name */
	int dof;        /* the joint's dof index (0-based) */
	double lo, hi;  /* degrees */
};
struct envelope_comfort {
	int n;
	struct envelope_comfort_range r[ENVELOPE_COMFORT_MAX];
};

/* the default comfort ranges (each cited in envelope_comfort.c) */
void envelope_comfort_default(struct envelope_comfort *dest);
/* the source of default range i, or NULL */
const char *envelope_comfort_source(int i);

/*
 * Sets ranges from text "JOINT.DOF=LO,HI;JOINT.DOF=LO,HI..." (degrees, the
 * dof's 0-based index; spaces allowed around the numbers): a range already
 * in *dest for that JOINT.DOF is replaced, another is added. JOINT is a limb
 * joint without its side ("shoulder"), "spine" (the trunk), or any joint's
 * name. Returns 0, or -1 with a message in err and *dest unchanged.
 */
int envelope_comfort_parse(const char *text, struct envelope_comfort *dest, char *err,
			   size_t errlen);

/*
 * Narrows the limits of model m (a human, or a copy of one) to the ranges
 * for hand `side`: each range meets the dof's own limits. Returns 0, or -1
 * with a message (no such joint or dof, a range outside the limits).
 */
int envelope_comfort_apply(const struct envelope_comfort *c, struct model *m, int side, char *err,
			   size_t errlen);

#endif
