/* mouse_line.c - the ray through a pixel (see mouse_line.h) */
#include "interact/mouse_line.h"

#include <math.h>

int
mouse_line(const struct camera *cam, int w, int h, double px, double py, struct ray *dest)
{
	if (w <= 0 || h <= 0 || !isfinite(px) || !isfinite(py))
		return -1;
	/* the inverse of view_project: pixel -> normalised device -> camera -> world */
	view_mouse_line(cam, w, h, px, py, dest->o, dest->d);
	return 0;
}

int
mouse_line_of_view(const struct env_view *v, double px, double py, struct ray *dest)
{
	struct camera cam;
	view_camera_of_view(v, &cam);
	return mouse_line(&cam, v->width, v->height, px, py, dest);
}
