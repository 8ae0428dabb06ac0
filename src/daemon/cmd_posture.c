/* cmd_posture.c - one posture onto several figures, and a posture mirrored */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/session.h"
#include "figure/human_mirror.h"
#include "figure/kin.h"

int
cmd_apply_posture(struct cmd_ctx *c)
{
	struct env *e = &c->d->env;
	int n = c->argc - 1, slot[ENV_MAX_FIGURES];
	if (n > ENV_MAX_FIGURES)
		return cmd_fail(c, "arity", "at most %d figures", ENV_MAX_FIGURES);
	for (int i = 0; i < n; i++) {
		if ((slot[i] = cmd_figure(c, c->argv[1 + i])) < 0)
			return -1;
		for (int j = 0; j < i; j++)
			if (slot[j] == slot[i])
				return cmd_fail(c, "bad-argument", "%.60s is named twice", c->argv[1 + i]);
	}
	size_t len;
	char *text = cmd_read_file(c, c->argv[0], &len);
	if (!text)
		return -1;
	/* each figure's posture kept, so a file one of them refuses changes none */
	struct state *kept[ENV_MAX_FIGURES] = { 0 };
	char err[300];
	int rc = 0, done = 0;
	for (int i = 0; i < n && !rc; i++) {
		const struct env_figure *f = &e->fig[slot[i]];
		if (!(kept[i] = state_make(f->model)))
			rc = cmd_fail(c, "internal", "out of memory");
		else
			state_copy(f->model, f->state, kept[i]);
	}
	for (; done < n && !rc; done++)
		if (session_read_posture(e, slot[done], text, len, err, sizeof err) < 0)
			rc = cmd_fail(c, "bad-file", "%.60s onto %s: %s", c->argv[0], e->fig[slot[done]].name,
				      err);
	json_t *names = json_array();
	for (int i = 0; i < n; i++) {
		struct env_figure *f = &e->fig[slot[i]];
		if (rc && i < done && kept[i]) { /* taken back */
			state_copy(f->model, kept[i], f->state);
			kin_update(f->model, f->state);
		}
		f->ik_stale = 1; /* the root may have changed */
		json_array_append_new(names, json_string(f->name));
		state_free(kept[i]);
	}
	free(text);
	if (rc) {
		json_decref(names);
		return -1;
	}
	json_object_set_new(c->result, "figures", names);
	return 0;
}

int
cmd_mirror_posture(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]);
	if (fig < 0)
		return -1;
	struct env_figure *f = &c->d->env.fig[fig];
	if (!f->is_human)
		return cmd_fail(c, "bad-argument", "%s is not a human figure: mirror knows a human's joints",
				f->name);
	char err[256];
	if (human_mirror_posture(f->model, f->state, err, sizeof err) < 0)
		return cmd_fail(c, "bad-argument", "%s", err);
	f->ik_stale = 1;
	return 0;
}
