/*
 * cmd_loads.c - what the loads do to a body (analyze loads): the static
 * equilibrium of a figure or of each member of a family under gravity, its
 * loads and what its hands carry, the joints' forces and moments, the
 * supports, the low back and strength (loads_live.h). The loads themselves
 * are cmd_load.c's.
 */
#include <stdio.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/loads_json.h"
#include "daemon/loads_live.h"

#define REPLY_BUF (4 * 1024 * 1024) /* a family's replies: up to 40 figures of up to ~80 KB */

/* figure slot fig's analysis, its whole reply object, into j */
static void
analysis_of(struct cmd_ctx *c, int fig, const struct loads_live_fig *a, struct jbuf *j)
{
	struct daemon *d = c->d;
	jbuf_raw(j, "{");
	jbuf_key(j, "figure", 1);
	jbuf_str(j, d->env.fig[fig].name);
	jbuf_key(j, "frame", 0);
	jbuf_int(j, (long long)d->stats.frame);
	loads_json_keys(j, &d->env, fig, a, 0);
	jbuf_raw(j, "}");
}

int
cmd_analyze_loads(struct cmd_ctx *c)
{
	struct daemon *d = c->d;
	int slot[ENV_MAX_FIGURES];
	const char *family;
	int n = cmd_figures(c, c->argv[0], slot, &family);
	if (n < 0)
		return -1;
	const struct loads_live_fig *a[ENV_MAX_FIGURES];
	for (int i = 0; i < n; i++)
		if (!(a[i] = loads_live_of(d, slot[i])))
			return cmd_fail(c, "bad-argument", "%s", loads_live_why(d, slot[i]));
	struct jbuf j;
	if (jbuf_init(&j, REPLY_BUF) < 0)
		return cmd_fail(c, "internal", "out of memory");
	if (family) {
		jbuf_raw(&j, "{");
		jbuf_key(&j, "family", 1);
		jbuf_str(&j, family);
		jbuf_key(&j, "figures", 0);
		jbuf_raw(&j, "[");
		for (int i = 0; i < n; i++) {
			if (i)
				jbuf_raw(&j, ",");
			analysis_of(c, slot[i], a[i], &j); /* one cache entry a figure: each still there */
		}
		jbuf_raw(&j, "]}");
	} else {
		analysis_of(c, slot[0], a[0], &j);
	}
	int rc = cmd_merge_json(c, c->result, &j);
	jbuf_free(&j);
	return rc;
}
