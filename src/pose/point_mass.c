/* point_mass.c - the centre of mass of a figure with the weights it carries */
#include "pose/point_mass.h"

#include <math.h>
#include <string.h>

int
point_mass_check(const struct model *m, const struct point_mass *pm, int n)
{
	if (n < 0 || n > POINT_MASS_MAX || (n > 0 && !pm))
		return -1;
	for (int i = 0; i < n; i++) {
		if (pm[i].seg < 0 || pm[i].seg >= m->nseg || !isfinite(pm[i].mass) || !(pm[i].mass > 0))
			return -1;
		for (int r = 0; r < 3; r++)
			if (!isfinite(pm[i].local[r]))
				return -1;
	}
	return 0;
}

int
point_mass_of_loads(const struct ext_load *loads, int n, struct point_mass *dest, int max)
{
	int k = 0;
	for (int i = 0; i < n; i++) {
		if (!(loads[i].mass > 0))
			continue;
		int j = 0;
		while (j < k && dest[j].seg != loads[i].seg)
			j++;
		if (j < k) { /* another on the same segment: one mass at their centre */
			double sum = dest[j].mass + loads[i].mass;
			for (int r = 0; r < 3; r++)
				dest[j].local[r] = (dest[j].mass * dest[j].local[r] +
						    loads[i].mass * loads[i].local[r]) / sum;
			dest[j].mass = sum;
			continue;
		}
		if (k >= max)
			return -1;
		dest[k].seg = loads[i].seg;
		memcpy(dest[k].local, loads[i].local, sizeof dest[k].local);
		dest[k].mass = loads[i].mass;
		k++;
	}
	return k;
}

void
point_mass_com(const struct state *s, const struct point_mass *pm, int n, double dest[3])
{
	if (n <= 0) { /* no weights: the figure's own, untouched */
		memcpy(dest, s->com, sizeof s->com);
		return;
	}
	double body = s->subtree_mass[s->seg_order[0]], total = body, sum[3];
	for (int r = 0; r < 3; r++)
		sum[r] = body * s->com[r];
	for (int i = 0; i < n; i++) {
		double p[3];
		xform_apply(&s->seg_xf[pm[i].seg], pm[i].local, p);
		for (int r = 0; r < 3; r++)
			sum[r] += pm[i].mass * p[r];
		total += pm[i].mass;
	}
	for (int r = 0; r < 3; r++)
		dest[r] = sum[r] / total;
}
