/*
 * motion_scale.h - relative mouse motion to screen pixels: flat (no
 * acceleration, so a hand's movement maps to the same distance at any
 * speed, which precise posing wants), normalised by the mouse's resolution
 * so a 400 DPI and a 1600 DPI mouse move the pointer alike, times a gain.
 * Whole pixels come out; the fractions are kept for the next motion, so
 * slow motion is not lost to rounding and the sum of the pixels never
 * drifts from the scaled sum of the counts by a pixel or more.
 */
#ifndef POSTURE_DEVICES_MOTION_SCALE_H
#define POSTURE_DEVICES_MOTION_SCALE_H

struct motion_scale {
	double k;      /* pixels per count: gain * 1000 / dpi */
	double rx, ry; /* the fractions not yet given out */
};

/* gain pixels per 1/1000 inch; dpi <= 0 means INPUT_DEV_DPI_DEFAULT */
void motion_scale_init(struct motion_scale *m, double dpi, double gain);

/* counts (dx, dy) to whole pixels (*px, *py), the remainders kept */
void motion_scale_apply(struct motion_scale *m, double dx, double dy, long *px, long *py);

#endif
