/*
 * cmd_reach.c - can reach: "can she reach it?" (pose/reach.h), solved on a
 * copy of the figure's state, so nothing the person sees changes; and
 * reach, the same solve with the posture taken.
 */
#include <stdlib.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/words.h"
#include "figure/kin.h"
#include "pose/reach.h"


#define REACH_RESTARTS_MAX 64 /* reach_solve's own bound */

/* the request's words (nearest= only when may_take); 0, or -1 with the error set */
static int
read_request(struct cmd_ctx *c, const char *usage, int may_take, struct reach_request *q)
{
	*q = (struct reach_request){ .mode = REACH_BODY, .balance = 1 };
	int have_target = 0;
	for (int i = 1; i < c->argc; i++) {
		const char *w = c->argv[i];
		if (words_is_key(w, "hand") || words_is_key(w, "rot") || words_is_key(w, "yaw") ||
		    words_is_key(w, "mode") || words_is_key(w, "balance") || words_is_key(w, "restarts") ||
		    (may_take && words_is_key(w, "nearest")))
			continue;
		if (have_target || words_list(w, UNIT_LENGTH, 3, q->target) < 0)
			return cmd_fail(c, "bad-argument", "unexpected '%.60s' (X,Y,Z: three lengths)", w);
		have_target = 1;
	}
	if (!have_target)
		return cmd_fail(c, "arity", "%s", usage);
	int side, mode = (int)q->mode, balance;
	if (cmd_reach_words(c, &side, &mode, &balance) < 0)
		return -1;
	q->side = side;
	q->mode = (enum reach_mode)mode;
	q->balance = balance;
	const char *rs = cmd_key(c, "restarts");
	if (rs) { /* as the envelopes solve (assess/envelope.h): stuck short, from other postures */
		char *end;
		long n = strtol(rs, &end, 10);
		if (!rs[0] || *end || n < 0 || n > REACH_RESTARTS_MAX)
			return cmd_fail(c, "bad-argument", "restarts=N from 0 to %d", REACH_RESTARTS_MAX);
		q->restarts = (int)n;
	}
	return cmd_rotation(c, q->rot, &q->oriented);
}

/* the solve on a copy; its reach object (the caller frees it) or NULL with the error set */
static struct reach *
solve(struct cmd_ctx *c, int fig, const struct reach_request *q, struct reach_result *res)
{
	const struct env_figure *f = &c->d->env.fig[fig];
	if (!f->is_human) {
		cmd_fail(c, "bad-argument", "%s is not a human figure", f->name);
		return NULL;
	}
	struct reach *r = reach_make(f->model);
	if (!r) {
		cmd_fail(c, "bad-argument", "%s has no hands and feet to reach with", f->name);
		return NULL;
	}
	const struct behave *b = f->behave;
	if (reach_solve(r, f->model, f->state, b ? &b->p : NULL, b ? b->mass : NULL,
			b ? b->nmass : 0, q, res) < 0) {
		reach_free(r);
		cmd_fail(c, "bad-number", "the target and rotation must be finite");
		return NULL;
	}
	return r;
}

static void
reply(struct cmd_ctx *c, const struct model *m, const struct reach *r,
      const struct reach_request *q, const struct reach_result *res)
{
	const struct state *s = reach_posture(r);
	json_t *p = json_object(), *lim = json_array();
	for (int j = 0; j < m->njnt; j++)
		if (m->jnt_ndof[j])
			json_object_set_new(p, m->jnt_name[j], cmd_vec(&s->q[m->jnt_dof0[j]], m->jnt_ndof[j]));
	for (int i = 0; i < res->nlimiting; i++)
		json_array_append_new(lim, json_string(m->jnt_name[res->limiting[i]]));
	json_object_set_new(c->result, "reached", json_boolean(res->reached));
	json_object_set_new(c->result, "distance", json_real(res->distance));
	if (q->oriented)
		json_object_set_new(c->result, "angle", json_real(res->angle));
	json_object_set_new(c->result, "posture", p);
	json_object_set_new(c->result, "limiting", lim);
	json_object_set_new(c->result, "margin", json_real(res->margin));
	json_object_set_new(c->result, "mode", json_string(cmd_reach_mode_name(q->mode)));
}

int
cmd_can_reach(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]);
	if (fig < 0)
		return -1;
	struct reach_request q;
	if (read_request(c, "can reach FIG hand=left|right X,Y,Z", 0, &q) < 0)
		return -1;
	struct reach_result res;
	struct reach *r = solve(c, fig, &q, &res);
	if (!r)
		return -1;
	reply(c, c->d->env.fig[fig].model, r, &q, &res);
	reach_free(r);
	return 0;
}

/*
 * The solved posture onto the figure: its joints, and its root site placed
 * where the copy has it. A behaving figure's behaviours then hold the new
 * posture (the reaching hand held where it is), or the next frame would
 * pull the body back to the old goals.
 */
static int
take(struct cmd_ctx *c, int fig, const struct reach *r, const struct reach_request *q)
{
	struct env_figure *f = &c->d->env.fig[fig];
	const struct model *m = f->model;
	int root = f->state->root_site;
	state_copy(m, reach_posture(r), f->state);
	kin_update(m, f->state);
	if (f->state->root_site != root && kin_set_root(m, f->state, root) < 0)
		return cmd_fail(c, "internal", "%s: its root site is gone", f->name);
	f->ik_stale = 1;
	if (!f->behave)
		return 0;
	struct behave *b = f->behave;
	b->p.hand[q->side] = HAND_HOLD_GLOBAL;
	/* a bent spine held as bent, as bend torso holds it; a body that squatted kept at the
	 * height it squatted to, or the knee springs would stand it up out of the reach */
	if (q->mode != REACH_ARM && b->p.torso == TORSO_KEEP_VERTICAL)
		b->p.torso = TORSO_HOLD_GLOBAL;
	if (q->mode == REACH_BODY)
		b->p.hold_elevation = 1;
	f->behave = NULL; /* the solver refilled with the client's constraints alone */
	env_sync_solver(&c->d->env, fig);
	int rc = behave_hold_posture(b, m, f->state, f->ik);
	f->behave = b;
	f->ik_stale = 1;
	if (rc < 0)
		return cmd_fail(c, "internal", "%s: the behaviours cannot hold the posture", f->name);
	return 0;
}

int
cmd_reach(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]);
	if (fig < 0)
		return -1;
	struct reach_request q;
	if (read_request(c, "reach FIG hand=left|right X,Y,Z", 1, &q) < 0)
		return -1;
	const char *nearest = cmd_key(c, "nearest");
	if (nearest && strcmp(nearest, "yes") && strcmp(nearest, "no"))
		return cmd_fail(c, "bad-argument", "nearest=yes|no");
	struct reach_result res;
	struct reach *r = solve(c, fig, &q, &res);
	if (!r)
		return -1;
	int apply = res.reached || (nearest && !strcmp(nearest, "yes"));
	reply(c, c->d->env.fig[fig].model, r, &q, &res);
	if (apply && take(c, fig, r, &q) < 0) {
		reach_free(r);
		return -1;
	}
	reach_free(r);
	json_object_set_new(c->result, "applied", json_boolean(apply));
	c->unchanged = !apply;
	return 0;
}
