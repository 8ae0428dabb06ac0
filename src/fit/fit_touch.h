/*
 * fit_touch.h - the human's segments whose meshes touch or overlap in a
 * normal posture, left out of self-clearance (fit_model.h): the table and
 * the measurement it was made from are in fit_touch.c.
 */
#ifndef POSTURE_FIT_TOUCH_H
#define POSTURE_FIT_TOUCH_H

#include "figure/model.h"

/* 1 when segments a and b of m are a pair of the table (m a human), else 0 */
int fit_touch(const struct model *m, int a, int b);

#endif
