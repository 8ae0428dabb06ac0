/* cmd_anthro.c - a human figure measured as ANSUR II measured people (pose/anthropometry.h) */
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "pose/anthropometry.h"

int
cmd_get_anthropometry(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]);
	if (fig < 0)
		return -1;
	const struct env_figure *f = &c->d->env.fig[fig];
	double v[HUMAN_MEASURE_N];
	char err[256];
	/* on a state of its own: the figure's posture stays as it is */
	if (anthro_measure_figure(f->model, f->is_human ? &f->human : NULL, v, err, sizeof err) < 0)
		return cmd_fail(c, strstr(err, "memory") ? "internal" : "bad-argument", "%s", err);
	json_t *o = json_object();
	for (int k = 0; k < HUMAN_MEASURE_N; k++)
		json_object_set_new(o, anthro_name((enum human_measure)k), json_real(v[k]));
	json_object_set_new(c->result, "measures", o);
	return 0;
}
