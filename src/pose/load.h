/*
 * load.h - an external load on a figure: a force and a torque applied at a
 * point fixed in one of its segments, or a weight (a mass hanging there).
 * What joint moments, the low back, strength and balance read of the
 * outside world's pull on a body.
 */
#ifndef POSTURE_LOAD_H
#define POSTURE_LOAD_H

/* standard gravity, m/s^2 (3rd CGPM, 1901; ISO 80000-3): a weight's force is mass x this, down (-y) */
#define LOAD_GRAVITY 9.80665

struct ext_load {
	int seg;          /* the segment of the figure it acts on */
	double local[3];  /* where it acts, in the segment's frame (m) */
	double force[3];  /* world frame (y up), N; a weight's: (0, -mass g, 0) */
	double torque[3]; /* world frame, N m */
	double mass;      /* kg: a weight (its force follows gravity; balance counts it); 0: a force */
};

#endif
