/* motion_scale.c - counts to pixels with the remainders kept (see motion_scale.h) */
#include "devices/motion_scale.h"

#include <math.h>

#include "devices/input_backend.h"

void
motion_scale_init(struct motion_scale *m, double dpi, double gain)
{
	m->k = gain * 1000.0 / (dpi > 0 ? dpi : INPUT_DEV_DPI_DEFAULT);
	m->rx = m->ry = 0;
}

/* the whole part of v toward zero; the rest stays in v */
static long
motion_scale_take(double *v)
{
	double whole = trunc(*v);
	*v -= whole;
	return (long)whole;
}

void
motion_scale_apply(struct motion_scale *m, double dx, double dy, long *px, long *py)
{
	m->rx += dx * m->k;
	m->ry += dy * m->k;
	*px = motion_scale_take(&m->rx);
	*py = motion_scale_take(&m->ry);
}
