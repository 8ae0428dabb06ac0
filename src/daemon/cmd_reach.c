/*
 * cmd_reach.c - can reach: "can she reach it?" (pose/reach.h), solved on a
 * copy of the figure's state, so nothing the person sees changes.
 */
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/words.h"
#include "pose/reach.h"

static const char *const mode_names[] = { "arm", "torso", "body" };

int
cmd_can_reach(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]);
	if (fig < 0)
		return -1;
	const struct env_figure *f = &c->d->env.fig[fig];
	struct reach_request q = { .mode = REACH_BODY, .balance = 1 };
	int have_target = 0;
	for (int i = 1; i < c->argc; i++) {
		const char *w = c->argv[i];
		if (words_is_key(w, "hand") || words_is_key(w, "rot") || words_is_key(w, "yaw") ||
		    words_is_key(w, "mode") || words_is_key(w, "balance"))
			continue;
		if (have_target || words_list(w, UNIT_LENGTH, 3, q.target) < 0)
			return cmd_fail(c, "bad-argument", "unexpected '%.60s' (X,Y,Z: three lengths)", w);
		have_target = 1;
	}
	if (!have_target)
		return cmd_fail(c, "arity", "can reach FIG hand=left|right X,Y,Z");
	const char *hand = cmd_key(c, "hand");
	if (!hand)
		return cmd_fail(c, "arity", "hand=left|right");
	if ((q.side = cmd_side(c, hand)) < 0)
		return -1;
	const char *mode = cmd_key(c, "mode");
	if (mode) {
		int k = 0;
		while (k < 3 && strcmp(mode, mode_names[k]))
			k++;
		if (k == 3)
			return cmd_fail(c, "bad-argument", "mode=arm|torso|body");
		q.mode = (enum reach_mode)k;
	}
	const char *bal = cmd_key(c, "balance");
	if (bal && strcmp(bal, "on") && strcmp(bal, "off"))
		return cmd_fail(c, "bad-argument", "balance=on|off");
	if (bal && q.mode != REACH_BODY)
		return cmd_fail(c, "bad-argument", "balance= is for mode=body (the arm and torso "
				"move nothing the feet carry)");
	q.balance = !bal || !strcmp(bal, "on");
	if (cmd_rotation(c, q.rot, &q.oriented) < 0)
		return -1;
	if (!f->is_human)
		return cmd_fail(c, "bad-argument", "%s is not a human figure", f->name);
	struct reach *r = reach_make(f->model);
	if (!r)
		return cmd_fail(c, "bad-argument", "%s has no hands and feet to reach with", f->name);
	const struct behave *b = f->behave;
	struct reach_result res;
	int rc = reach_solve(r, f->model, f->state, b ? &b->p : NULL, b ? b->mass : NULL,
			     b ? b->nmass : 0, &q, &res);
	if (rc < 0) {
		reach_free(r);
		return cmd_fail(c, "bad-number", "the target and rotation must be finite");
	}
	const struct model *m = f->model;
	const struct state *s = reach_posture(r);
	json_t *p = json_object(), *lim = json_array();
	for (int j = 0; j < m->njnt; j++)
		if (m->jnt_ndof[j])
			json_object_set_new(p, m->jnt_name[j], cmd_vec(&s->q[m->jnt_dof0[j]], m->jnt_ndof[j]));
	for (int i = 0; i < res.nlimiting; i++)
		json_array_append_new(lim, json_string(m->jnt_name[res.limiting[i]]));
	json_object_set_new(c->result, "reached", json_boolean(res.reached));
	json_object_set_new(c->result, "distance", json_real(res.distance));
	if (q.oriented)
		json_object_set_new(c->result, "angle", json_real(res.angle));
	json_object_set_new(c->result, "posture", p);
	json_object_set_new(c->result, "limiting", lim);
	json_object_set_new(c->result, "margin", json_real(res.margin));
	json_object_set_new(c->result, "mode", json_string(mode_names[q.mode]));
	reach_free(r);
	return 0;
}
