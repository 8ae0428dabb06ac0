/* hemi.c - the visibility map's camera and pixel directions (see hemi.h) */
#include "draw/hemi.h"

#include <math.h>

int
hemi_camera(struct camera *cam, const double origin[3], const double dir[3])
{
	double t[3] = { origin[0] + dir[0], origin[1] + dir[1], origin[2] + dir[2] };
	view_camera_default(cam);
	cam->fovy = HEMI_FOV;
	cam->znear = HEMI_ZNEAR;
	cam->zfar = HEMI_ZFAR;
	return view_camera_aim(cam, origin, t);
}

void
hemi_pixel_dir(const struct hemi_map *m, int px, int py, double dest[3])
{
	double o[3];
	view_mouse_line(&m->cam, HEMI_N, HEMI_N, px + 0.5, py + 0.5, o, dest);
}
