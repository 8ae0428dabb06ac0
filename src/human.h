/*
 * human.h - the standard human figure (§5.5.5, Appendix D), built from
 * stature, body mass and sex with published anthropometry.
 */
#ifndef POSTURE_HUMAN_H
#define POSTURE_HUMAN_H

#include <stddef.h>

#include "model.h"

enum human_sex {
	HUMAN_MALE,
	HUMAN_FEMALE,
};

struct human_def {
	double stature; /* m */
	double mass;    /* kg */
	enum human_sex sex;
};

/* 1.75 m / 75 kg for a man; the female default for a woman */
struct human_def human_default_def(enum human_sex sex);

/*
 * Builds the figure standing on the floor (y = 0), facing +z, x to its left.
 * Returns NULL with a message in err for a stature or mass out of range.
 */
struct model *human_build(const struct human_def *d, char *err, size_t errlen);

#endif
