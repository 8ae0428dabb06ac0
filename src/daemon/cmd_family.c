/*
 * cmd_family.c - a family of manikins shown at the kiosk: side by side in
 * a row, or overlaid with the others as ghosts about the selected one; and
 * posed alike, each as the selected one is, where it stands.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/family.h"
#include "draw/view.h"

/* the row's direction: view v's horizontal (its camera's x axis, level); world x without views */
static void
row_direction(const struct env *e, int v, double h[3])
{
	h[0] = 1, h[1] = 0, h[2] = 0;
	if (v < 0)
		return;
	struct camera cam;
	view_camera_of_view(&e->view[v], &cam);
	double x = cam.xf.r[0], z = cam.xf.r[6], n = hypot(x, z);
	if (n > 1e-9) { /* no twist keeps it level; a camera straight down keeps a heading */
		h[0] = x / n;
		h[2] = z / n;
	}
}

/* the reply: what is shown, and where each member stands and whether it is a ghost */
static void
reply(struct cmd_ctx *c, const int *slot, int n)
{
	const struct env *e = &c->d->env;
	const struct env_show *sh = &e->show;
	static const char *const names[] = { "off", "row", "overlay" };
	json_object_set_new(c->result, "family", json_string(sh->family));
	json_object_set_new(c->result, "arrangement", json_string(names[sh->arrange]));
	int sel = family_selected(e);
	json_object_set_new(c->result, "selected", sel >= 0 ? json_string(e->fig[sel].name) : json_null());
	json_object_set_new(c->result, "spacing", json_real(sh->spacing));
	json_t *list = json_array();
	for (int i = 0; i < n; i++) {
		const struct env_figure *f = &e->fig[slot[i]];
		double at[3];
		json_t *o = json_object();
		json_object_set_new(o, "name", json_string(f->name));
		if (family_place(f->model, f->state, at) == 0)
			json_object_set_new(o, "place", cmd_vec(at, 3));
		json_object_set_new(o, "ghost", json_boolean(daemon_is_ghost(c->d, slot[i])));
		json_array_append_new(list, o);
	}
	json_object_set_new(c->result, "figures", list);
}

int
cmd_show_family(struct cmd_ctx *c)
{
	struct daemon *d = c->d;
	struct env *e = &d->env;
	const char *prefix = c->argv[0], *how = c->argv[1];
	int row = !strcmp(how, "row"), overlay = !strcmp(how, "overlay"), off = !strcmp(how, "off");
	if (!row && !overlay && !off)
		return cmd_fail(c, "bad-argument", "show family PREFIX row|overlay|off: not '%.40s'", how);
	for (int i = 2; i < c->argc; i++)
		if (!words_is_key(c->argv[i], "spacing") && !words_is_key(c->argv[i], "select") &&
		    !words_is_key(c->argv[i], "view"))
			return cmd_fail(c, "bad-argument", "unexpected '%.60s'", c->argv[i]);
	int slot[ENV_MAX_FIGURES], n = family_members(e, prefix, slot);
	if (!n)
		return cmd_fail(c, "not-found", "no family '%.60s' (load family PREFIX sex=... makes one)",
				prefix);
	const char *sp = cmd_key(c, "spacing"), *sel_word = cmd_key(c, "select");
	const char *view_word = cmd_key(c, "view");
	if ((sp || view_word) && !row)
		return cmd_fail(c, "bad-argument", "spacing= and view= are a row's");
	if (off && sel_word)
		return cmd_fail(c, "bad-argument", "select= is for a row or an overlay");
	if (off) {
		if (e->show.arrange != ENV_SHOW_OFF && !strcmp(e->show.family, prefix))
			e->show = (struct env_show){ 0 };
		reply(c, slot, n);
		return 0;
	}
	double spacing = 0;
	if (sp && (words_number(sp, UNIT_LENGTH, &spacing) < 0 || !(spacing > 0 && spacing <= 100)))
		return cmd_fail(c, "bad-number", "spacing: a length above 0 and within 100 m, e.g. 0.8 "
				"or 80cm");
	int v = view_word ? env_find_view(e, view_word) : daemon_kiosk_view(d);
	if (view_word && v < 0)
		return cmd_fail(c, "not-found", "no view '%.60s'", view_word);
	/* the selected one: as asked, else the one selected now, else the first */
	int sel = 0;
	if (sel_word) {
		int fig = cmd_figure(c, sel_word);
		if (fig < 0)
			return -1;
		for (sel = 0; sel < n && slot[sel] != fig; sel++)
			;
		if (sel == n)
			return cmd_fail(c, "bad-argument", "%s is not of family %s", e->fig[fig].name, prefix);
	} else if (!strcmp(e->show.family, prefix)) {
		int now = family_selected(e);
		for (sel = 0; sel < n && slot[sel] != now; sel++)
			;
		sel = sel == n ? 0 : sel;
	}
	/* a member the kiosk is moving waits for the step's end, as the busy rule says */
	const struct daemon_step *st = &d->step;
	for (int i = 0; c->client >= 0 && st->open && i < n; i++)
		if (slot[i] == st->fig && e->fig[slot[i]].gen == st->gen)
			return cmd_fail(c, "busy", "the kiosk is moving %s (%s mode, a button held or the "
					"dials turning): showing its family waits until the step ends",
					e->fig[slot[i]].name, st->mode);
	const struct pick_model *pm[ENV_MAX_FIGURES];
	for (int i = 0; i < n; i++)
		if (!(pm[i] = daemon_pick_model(d, slot[i])))
			return cmd_fail(c, "internal", "out of memory");
	double h[3], used;
	char err[256];
	row_direction(e, v, h);
	if (family_arrange(e, slot, pm, n, sel, row, h, spacing, &used, err, sizeof err) < 0)
		return cmd_fail(c, "bad-argument", "%s", err);
	struct env_show *sh = &e->show;
	sh->arrange = row ? ENV_SHOW_ROW : ENV_SHOW_OVERLAY;
	snprintf(sh->family, sizeof sh->family, "%s", prefix);
	snprintf(sh->selected, sizeof sh->selected, "%s", e->fig[slot[sel]].name);
	sh->spacing = used;
	/* recovery has no pointer: the journal gets the view and spacing this row took */
	int k = snprintf(d->journal_as, sizeof d->journal_as, "show family %s %s select=%s", prefix,
			 how, sh->selected);
	if (row)
		snprintf(d->journal_as + k, sizeof d->journal_as - (size_t)k, " spacing=%.17g%s%s", used,
			 v >= 0 ? " view=" : "", v >= 0 ? e->view[v].name : "");
	reply(c, slot, n);
	if (row) {
		json_object_set_new(c->result, "view", v >= 0 ? json_string(e->view[v].name) : json_null());
		json_object_set_new(c->result, "direction", cmd_vec(h, 3));
	}
	return 0;
}

int
cmd_pose_family(struct cmd_ctx *c)
{
	struct env *e = &c->d->env;
	const char *prefix = c->argv[0];
	for (int i = 1; i < c->argc; i++)
		if (!words_is_key(c->argv[i], "like"))
			return cmd_fail(c, "bad-argument", "unexpected '%.60s'", c->argv[i]);
	int slot[ENV_MAX_FIGURES], n = family_members(e, prefix, slot);
	if (!n)
		return cmd_fail(c, "not-found", "no family '%.60s' (load family PREFIX sex=... makes one)",
				prefix);
	/* like the figure named, else the family's selected one when it is shown, else its first */
	const char *like = cmd_key(c, "like");
	int from = like ? cmd_figure(c, like) : -1;
	if (like && from < 0)
		return -1;
	if (!like)
		from = !strcmp(e->show.family, prefix) && family_selected(e) >= 0 ? family_selected(e)
										   : slot[0];
	if (!e->fig[from].is_human)
		return cmd_fail(c, "bad-argument", "%s is not a human figure", e->fig[from].name);
	const struct daemon_step *st = &c->d->step;
	for (int i = 0; c->client >= 0 && st->open && i < n; i++)
		if (slot[i] == st->fig && e->fig[slot[i]].gen == st->gen)
			return cmd_fail(c, "busy", "the kiosk is moving %s (%s mode, a button held or the "
					"dials turning): posing its family waits until the step ends",
					e->fig[slot[i]].name, st->mode);
	char err[256];
	if (family_pose_alike(e, slot, n, from, err, sizeof err) < 0)
		return cmd_fail(c, "bad-argument", "%s", err);
	json_t *names = json_array();
	for (int i = 0; i < n; i++)
		if (slot[i] != from)
			json_array_append_new(names, json_string(e->fig[slot[i]].name));
	json_object_set_new(c->result, "family", json_string(prefix));
	json_object_set_new(c->result, "like", json_string(e->fig[from].name));
	json_object_set_new(c->result, "figures", names);
	return 0;
}
