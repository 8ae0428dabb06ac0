/*
 * cmd_clearance.c - analyze clearance: how near a figure's segments come
 * to other figures' and to its own (fit/clearance.h, fit_live.h): every
 * pair nearer than a threshold with its two closest points, and the
 * smallest distance of all; for a family, each member's.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/fit_live.h"
#include "daemon/jbuf.h"
#include "daemon/words.h"

/* m: the threshold unless threshold= says. Not a standard's figure (none was found to
 * cite): the 2 cm the fit analysis was specified with, a working default to set per task */
#define CLEARANCE_DEFAULT 0.02
#define REPLY_BUF (4 * 1024 * 1024)

static struct clearance_result result; /* large: one a command, never two at once */

static void
seg_name(const struct env *e, int fig, int seg, char *dest, size_t len)
{
	snprintf(dest, len, "%s.%s", e->fig[fig].name, e->fig[fig].model->seg_name[seg]);
}

static void
pair_json(struct jbuf *j, const struct env *e, const struct clearance_pair *p)
{
	char a[2 * MODEL_NAME_MAX + 2], b[2 * MODEL_NAME_MAX + 2];
	seg_name(e, p->fig_a, p->seg_a, a, sizeof a);
	seg_name(e, p->fig_b, p->seg_b, b, sizeof b);
	jbuf_raw(j, "{");
	jbuf_key(j, "a", 1);
	jbuf_str(j, a);
	jbuf_key(j, "b", 0);
	jbuf_str(j, b);
	jbuf_key(j, "distance", 0);
	jbuf_num(j, p->distance);
	jbuf_key(j, "points", 0);
	jbuf_raw(j, "[");
	jbuf_vec(j, p->pa, 3);
	jbuf_raw(j, ",");
	jbuf_vec(j, p->pb, 3);
	jbuf_raw(j, "]}");
}

/* figure slot fig's clearance, its reply object, into j; 0 or -1 with the error set */
static int
clearance_of(struct cmd_ctx *c, int fig, const int *with, int n, int self, double threshold,
	     struct jbuf *j)
{
	struct daemon *d = c->d;
	char why[200];
	clearance_begin(&result, threshold);
	if (fit_live_clearance(d, fig, with, n, self, &result, why, sizeof why) < 0)
		return cmd_fail(c, "bad-argument", "%s", why);
	jbuf_raw(j, "{");
	jbuf_key(j, "figure", 1);
	jbuf_str(j, d->env.fig[fig].name);
	jbuf_key(j, "frame", 0);
	jbuf_int(j, (long long)d->stats.frame);
	jbuf_key(j, "threshold", 0);
	jbuf_num(j, threshold);
	jbuf_key(j, "with", 0);
	jbuf_raw(j, "[");
	for (int k = 0; k < n; k++) {
		if (k)
			jbuf_raw(j, ",");
		jbuf_str(j, d->env.fig[with[k]].name);
	}
	jbuf_raw(j, "]");
	jbuf_key(j, "self", 0);
	jbuf_bool(j, self);
	jbuf_key(j, "pairs", 0);
	jbuf_raw(j, "[");
	for (int k = 0; k < result.npairs; k++) {
		if (k)
			jbuf_raw(j, ",");
		pair_json(j, &d->env, &result.pair[k]);
	}
	jbuf_raw(j, "]");
	jbuf_key(j, "more", 0);
	jbuf_int(j, result.more);
	jbuf_key(j, "minimum", 0);
	if (result.has_minimum)
		jbuf_num(j, result.minimum.distance);
	else
		jbuf_raw(j, "null");
	jbuf_key(j, "minimum_pair", 0);
	if (result.has_minimum)
		pair_json(j, &d->env, &result.minimum);
	else
		jbuf_raw(j, "null");
	jbuf_key(j, "asked", 0);
	jbuf_int(j, result.asked);
	jbuf_key(j, "candidates", 0);
	jbuf_int(j, result.candidates);
	jbuf_raw(j, "}");
	return 0;
}

static int
member(const int *slot, int n, int fig)
{
	for (int k = 0; k < n; k++)
		if (slot[k] == fig)
			return 1;
	return 0;
}

/*
 * The figures fig is checked against: with=FIG, with=* (every other figure
 * but the family's own members), with=none. Returns how many, or -1.
 */
static int
others(struct cmd_ctx *c, int fig, const int *family, int nfamily, int dest[ENV_MAX_FIGURES])
{
	const struct env *e = &c->d->env;
	const char *w = cmd_key(c, "with");
	int n = 0;
	if (w && !strcmp(w, "none"))
		return 0;
	if (w && strcmp(w, "*")) {
		int other = cmd_figure(c, w);
		if (other < 0)
			return -1;
		if (other == fig)
			return cmd_fail(c, "bad-argument", "with=%s is the figure itself (self=yes checks it "
					"against itself)", w);
		dest[0] = other;
		return 1;
	}
	for (int k = 0; k < ENV_MAX_FIGURES; k++)
		if (e->fig[k].gen && k != fig && !member(family, nfamily, k))
			dest[n++] = k;
	return n;
}

int
cmd_analyze_clearance(struct cmd_ctx *c)
{
	struct daemon *d = c->d;
	for (int i = 1; i < c->argc; i++)
		if (!words_is_key(c->argv[i], "with") && !words_is_key(c->argv[i], "self") &&
		    !words_is_key(c->argv[i], "threshold"))
			return cmd_fail(c, "bad-argument", "unexpected '%.60s' (with=FIG|*|none, "
					"self=yes|no, threshold=LEN)", c->argv[i]);
	double threshold = CLEARANCE_DEFAULT;
	const char *t = cmd_key(c, "threshold");
	if (t && (words_number(t, UNIT_LENGTH, &threshold) < 0 || threshold < 0))
		return cmd_fail(c, "bad-number", "threshold=%.40s: a length of 0 or more", t);
	const char *s = cmd_key(c, "self");
	if (s && strcmp(s, "yes") && strcmp(s, "no"))
		return cmd_fail(c, "bad-argument", "self=yes|no");
	int self = !s || !strcmp(s, "yes");
	int slot[ENV_MAX_FIGURES];
	const char *family;
	int n = cmd_figures(c, c->argv[0], slot, &family);
	if (n < 0)
		return -1;
	int with[ENV_MAX_FIGURES][ENV_MAX_FIGURES], nwith[ENV_MAX_FIGURES];
	for (int i = 0; i < n; i++)
		if ((nwith[i] = others(c, slot[i], family ? slot : NULL, family ? n : 0, with[i])) < 0)
			return -1;
	struct jbuf j;
	if (jbuf_init(&j, REPLY_BUF) < 0)
		return cmd_fail(c, "internal", "out of memory");
	int rc = 0;
	if (family) {
		jbuf_raw(&j, "{");
		jbuf_key(&j, "family", 1);
		jbuf_str(&j, family);
		jbuf_key(&j, "figures", 0);
		jbuf_raw(&j, "[");
		char near[ENV_MAX_FIGURES];
		for (int i = 0; i < n && !rc; i++) {
			if (i)
				jbuf_raw(&j, ",");
			rc = clearance_of(c, slot[i], with[i], nwith[i], self, threshold, &j);
			near[i] = result.npairs > 0 || result.more > 0;
		}
		jbuf_raw(&j, "]");
		jbuf_key(&j, "within", 0); /* the members with a pair nearer than the threshold */
		jbuf_raw(&j, "[");
		for (int i = 0, first = 1; i < n && !rc; i++)
			if (near[i]) {
				if (!first)
					jbuf_raw(&j, ",");
				jbuf_str(&j, d->env.fig[slot[i]].name);
				first = 0;
			}
		jbuf_raw(&j, "]}");
	} else {
		rc = clearance_of(c, slot[0], with[0], nwith[0], self, threshold, &j);
	}
	if (!rc)
		rc = cmd_merge_json(c, c->result, &j);
	jbuf_free(&j);
	return rc;
}
