/*
 * mouse_line.h - the mouse line of §3.3.3: the ray in the world cast from
 * the camera (the centre of projection) through the point of the image
 * under the pointer, found by inverting the viewing transform. It is the
 * probe the manipulation operator and picking work with.
 *
 * Pixels have their origin at the top left corner of the image, x right,
 * y down, fractions allowed: the top-left pixel's centre is (0.5, 0.5).
 */
#ifndef POSTURE_MOUSE_LINE_H
#define POSTURE_MOUSE_LINE_H

#include "draw/view.h"
#include "interact/ray.h"
#include "pose/env.h"

/*
 * The mouse line through pixel (px, py) of a w x h image seen through cam
 * (perspective): origin the camera's, direction unit length. Returns 0, or
 * -1 (dest untouched) when the size is not positive or the pixel is not
 * finite. Pixels outside the image are allowed: the line exists there too.
 */
int mouse_line(const struct camera *cam, int w, int h, double px, double py, struct ray *dest);

/* the same through a named view's camera and size */
int mouse_line_of_view(const struct env_view *v, double px, double py, struct ray *dest);

#endif
