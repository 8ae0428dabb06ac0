/*
 * ray.h - a half line in the world: the mouse line of §3.3.3 (from the
 * camera through a pixel), or any ray the manipulation operator and
 * picking work with. World metres, y up; d has unit length.
 */
#ifndef POSTURE_INTERACT_RAY_H
#define POSTURE_INTERACT_RAY_H

struct ray {
	double o[3]; /* origin */
	double d[3]; /* direction, unit length */
};

#endif
