/*
 * cmd_input.c - input over the socket: the same events a mouse, a keyboard
 * and the dial panel give, put into the same queue, so that scripts and
 * remote front ends drive the daemon exactly as the devices do.
 */
#include <libevdev/libevdev.h>
#include <linux/input-event-codes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/family.h"

#define INPUT_MOTION_MAX 1e6 /* counts: more in one line is a mistake, not a mouse */
#define INPUT_WHEEL_MAX 1000 /* detents */

/* queues e as the socket's device; its reply says whether it was queued or merged */
static int
inject(struct cmd_ctx *c, struct input_event_rec *e)
{
	if (!c->d->input)
		return cmd_fail(c, "bad-argument", "this daemon takes no input");
	e->device = INPUT_DEVICE_SOCKET;
	e->t_us = c->d->now_us ? c->d->now_us(c->d) : 0;
	int rc = input_queue_push(c->d->input, e);
	if (rc < 0)
		return cmd_fail(c, "limit", "the input queue is full");
	/* an injected event is a frame of its own, as one report of a device is */
	struct input_event_rec end;
	memset(&end, 0, sizeof end);
	end.kind = INPUT_FRAME;
	end.device = e->device;
	end.t_us = e->t_us;
	input_queue_push(c->d->input, &end);
	json_object_set_new(c->result, "queued", json_boolean(rc == 0));
	return 0;
}

static struct input_event_rec
event(enum input_kind kind)
{
	struct input_event_rec e;
	memset(&e, 0, sizeof e);
	e.kind = (uint8_t)kind;
	return e;
}

/* "down" 1, "up" 0, or -1 with the error set */
static int
down_up(struct cmd_ctx *c, const char *w)
{
	if (!strcmp(w, "down"))
		return 1;
	if (!strcmp(w, "up"))
		return 0;
	return cmd_fail(c, "bad-argument", "down or up, not '%.20s'", w);
}

int
cmd_input_pointer(struct cmd_ctx *c)
{
	int v = env_find_view(&c->d->env, c->argv[0]);
	if (v < 0)
		return cmd_fail(c, "not-found", "no view '%.60s'", c->argv[0]);
	const struct env_view *vw = &c->d->env.view[v];
	double x, y;
	if (words_number(c->argv[1], UNIT_NONE, &x) < 0 || words_number(c->argv[2], UNIT_NONE, &y) < 0)
		return cmd_fail(c, "bad-number", "X and Y are pixels, e.g. 320 or 320.5");
	if (x < 0 || y < 0 || x > vw->width || y > vw->height)
		return cmd_fail(c, "bad-argument", "(%g, %g) is outside view %s (%d x %d)", x, y,
				vw->name, vw->width, vw->height);
	struct input_event_rec e = event(INPUT_POINTER);
	e.flags = INPUT_F_VIEW;
	e.code = (uint16_t)v;
	e.x = x;
	e.y = y;
	return inject(c, &e);
}

int
cmd_input_motion(struct cmd_ctx *c)
{
	double d[2];
	for (int i = 0; i < 2; i++)
		if (words_number(c->argv[i], UNIT_NONE, &d[i]) < 0 || fabs(d[i]) > INPUT_MOTION_MAX)
			return cmd_fail(c, "bad-number", "DX and DY are counts within +-%g",
					INPUT_MOTION_MAX);
	struct input_event_rec e = event(INPUT_MOTION);
	e.x = d[0];
	e.y = d[1];
	return inject(c, &e);
}

int
cmd_input_button(struct cmd_ctx *c)
{
	static const struct {
		const char *name;
		uint16_t code;
	} buttons[] = { { "left", BTN_LEFT }, { "middle", BTN_MIDDLE }, { "right", BTN_RIGHT },
			{ "side", BTN_SIDE } };
	int code = -1;
	for (size_t i = 0; i < sizeof buttons / sizeof *buttons; i++)
		if (!strcmp(c->argv[0], buttons[i].name))
			code = buttons[i].code;
	/* any other button by the kernel's name: a panel's (BTN_TRIGGER_HAPPY1), a joystick's */
	if (code < 0 && !strncmp(c->argv[0], "BTN_", 4))
		code = libevdev_event_code_from_name(EV_KEY, c->argv[0]);
	if (code < 0)
		return cmd_fail(c, "bad-argument",
				"buttons are left, middle, right, side, or a BTN_ name of the kernel's");
	int down = down_up(c, c->argv[1]);
	if (down < 0)
		return -1;
	struct input_event_rec e = event(INPUT_BUTTON);
	e.code = (uint16_t)code;
	e.value = down;
	return inject(c, &e);
}

int
cmd_input_key(struct cmd_ctx *c)
{
	/* the kernel's names, as libevdev knows them; buttons go through input button */
	const char *name = c->argv[0];
	int code = strncmp(name, "KEY_", 4) ? -1 : libevdev_event_code_from_name(EV_KEY, name);
	if (code < 0)
		return cmd_fail(c, "bad-argument", "no key '%.40s' (the kernel's names: KEY_A, KEY_ESC)",
				name);
	int down = down_up(c, c->argv[1]);
	if (down < 0)
		return -1;
	struct input_event_rec e = event(INPUT_KEY);
	e.code = (uint16_t)code;
	e.value = down;
	return inject(c, &e);
}

int
cmd_input_wheel(struct cmd_ctx *c)
{
	double n;
	if (words_number(c->argv[0], UNIT_NONE, &n) < 0 || n != floor(n) || fabs(n) > INPUT_WHEEL_MAX)
		return cmd_fail(c, "bad-number", "N is a whole number of detents within +-%d",
				INPUT_WHEEL_MAX);
	struct input_event_rec e = event(INPUT_WHEEL);
	e.code = INPUT_WHEEL_V;
	e.value = (int32_t)n;
	e.x = n * 120;
	return inject(c, &e);
}

int
cmd_input_valuator(struct cmd_ctx *c)
{
	const struct can_map *m = c->d->panel;
	int k = m ? can_map_find(m, c->argv[0]) : -1;
	if (k >= 0 && m->line[k].kind == CAN_MAP_BUTTON)
		return cmd_fail(c, "bad-argument", "'%.60s' is a button of the panel, not an axis",
				c->argv[0]);
	if (k < 0)
		return cmd_fail(c, "not-found", "no valuator '%.60s'%s", c->argv[0],
				m ? "" : " (no panel map is loaded)");
	double v;
	if (words_number(c->argv[1], UNIT_NONE, &v) < 0)
		return cmd_fail(c, "bad-number", "V is a number");
	struct input_event_rec e = event(INPUT_VALUATOR);
	e.code = (uint16_t)k;
	e.x = v;
	return inject(c, &e);
}

static const char *
class_name(enum input_class c)
{
	switch (c) {
	case INPUT_CLASS_MOUSE:
		return "mouse";
	case INPUT_CLASS_KEYBOARD:
		return "keyboard";
	case INPUT_CLASS_PANEL:
		return "panel";
	case INPUT_CLASS_OTHER:
		return "other";
	}
	return "other";
}

int
cmd_list_devices(struct cmd_ctx *c)
{
	json_t *open = json_array(), *skip = json_array();
	const struct input_devs *s = c->d->devices;
	for (int i = 0; s && i < INPUT_DEVS_MAX; i++) {
		const struct input_devs_place *p = &s->place[i];
		if (!p->be)
			continue;
		json_t *o = json_object();
		json_object_set_new(o, "device", json_integer(i));
		json_object_set_new(o, "backend", json_string(p->be->name));
		json_object_set_new(o, "path", json_string(p->info.path));
		json_object_set_new(o, "name", json_string(p->info.name));
		json_object_set_new(o, "class", json_string(class_name(p->info.cls)));
		char id[16];
		snprintf(id, sizeof id, "%04x:%04x", p->info.vendor, p->info.product);
		json_object_set_new(o, "id", json_string(id));
		if (p->info.iface >= 0)
			json_object_set_new(o, "interface", json_integer(p->info.iface));
		if (p->info.cls == INPUT_CLASS_MOUSE)
			json_object_set_new(o, "dpi", json_real(p->info.dpi));
		json_object_set_new(o, "grabbed", json_boolean(p->info.grabbed));
		if (p->be->stats) {
			struct input_dev_stats st;
			p->be->stats(p->dev, &st);
			json_object_set_new(o, "reads", json_integer((json_int_t)st.reads));
			json_object_set_new(o, "capped", json_integer((json_int_t)st.capped));
			json_object_set_new(o, "resyncs", json_integer((json_int_t)st.resyncs));
			json_object_set_new(o, "errors", json_integer((json_int_t)st.errors));
		}
		json_array_append_new(open, o);
	}
	for (int k = 0; s && k < s->nskip; k++) {
		json_t *o = json_object();
		json_object_set_new(o, "what", json_string(s->skip[k].what));
		json_object_set_new(o, "why", json_string(s->skip[k].why));
		json_array_append_new(skip, o);
	}
	json_object_set_new(c->result, "devices", open);
	json_object_set_new(c->result, "skipped", skip);
	return 0;
}

int
cmd_set_input(struct cmd_ctx *c)
{
	for (int i = 0; i < c->argc; i++)
		if (strncmp(c->argv[i], "grab=", 5) && strncmp(c->argv[i], "gain=", 5) &&
		    strncmp(c->argv[i], "held=", 5))
			return cmd_fail(c, "bad-argument", "grab=yes|no, gain=G or held=SECONDS, not '%.40s'",
					c->argv[i]);
	const char *g = cmd_key(c, "grab"), *k = cmd_key(c, "gain"), *h = cmd_key(c, "held");
	double held = 0;
	if (h && (words_number(h, UNIT_NONE, &held) < 0 || !(held >= 1 && held <= 3600)))
		return cmd_fail(c, "bad-argument", "held is seconds, from 1 to 3600");
	if ((g || k) && !c->d->set_input)
		return cmd_fail(c, "bad-argument", "this daemon reads no devices");
	if (h)
		c->d->held_max_us = (uint64_t)(held * 1e6);
	json_object_set_new(c->result, "held", json_real((double)c->d->held_max_us / 1e6));
	if (!g && !k)
		return 0;
	int grab = -1;
	double gain = 0;
	if (g) {
		if (strcmp(g, "yes") && strcmp(g, "no"))
			return cmd_fail(c, "bad-argument", "grab=yes or grab=no, not '%.20s'", g);
		grab = !strcmp(g, "yes");
	}
	if (k && (words_number(k, UNIT_NONE, &gain) < 0 || !(gain > 0 && gain <= 100)))
		return cmd_fail(c, "bad-argument", "gain is a number above 0, at most 100");
	if (c->d->set_input(c->d, grab, gain) < 0)
		return cmd_fail(c, "busy", "a device refused the grab (another reader holds it)");
	json_object_set_new(c->result, "grab", json_boolean(c->d->devices && c->d->devices->grab));
	json_object_set_new(c->result, "gain", json_real(c->d->pointer_gain));
	return 0;
}

/* the kiosk's keyboard: set kiosk [keymap=LAYOUT[:VARIANT]] [viewkey=KEY] */
int
cmd_set_kiosk(struct cmd_ctx *c)
{
	struct kiosk *k = c->d->kiosk;
	if (!k)
		return cmd_fail(c, "bad-argument", "this daemon has no kiosk keyboard");
	for (int i = 0; i < c->argc; i++)
		if (!words_is_key(c->argv[i], "keymap") && !words_is_key(c->argv[i], "viewkey"))
			return cmd_fail(c, "bad-argument", "keymap=LAYOUT[:VARIANT] or viewkey=KEY, not '%.40s'",
					c->argv[i]);
	const char *map = cmd_key(c, "keymap"), *vk = cmd_key(c, "viewkey");
	int code = -1;
	if (vk) {
		char name[64];
		snprintf(name, sizeof name, "%s%.50s", strncmp(vk, "KEY_", 4) ? "KEY_" : "", vk);
		if ((code = libevdev_event_code_from_name(EV_KEY, name)) < 0)
			return cmd_fail(c, "bad-argument", "viewkey: '%.40s' is no key name (F2, KEY_F3)", vk);
	}
	if (map) {
		struct kbd_text_def kd = kbd_text_default_def();
		char names[128], err[300];
		if (kiosk_keymap_names(map, &kd, names, sizeof names) < 0)
			return cmd_fail(c, "bad-argument", "keymap is LAYOUT[:VARIANT], such as de or de:nodeadkeys");
		if (kiosk_set_keymap(k, &kd, err, sizeof err) < 0)
			return cmd_fail(c, "not-found", "%s", err);
		snprintf(c->d->keymap, sizeof c->d->keymap, "%s", map);
	}
	if (code >= 0)
		kiosk_set_view_key(k, (unsigned)code);
	return cmd_get_kiosk(c);
}

/* the kiosk's state: its mode, the edit line and the keyboard's settings */
int
cmd_get_kiosk(struct cmd_ctx *c)
{
	struct kiosk *k = c->d->kiosk;
	const struct interact *ia = c->d->interact;
	json_object_set_new(c->result, "mode",
			    json_string(ia && ia->mode != INTERACT_NONE ? interact_name(ia) : "none"));
	json_object_set_new(c->result, "step", json_boolean(c->d->step.open));
	json_object_set_new(c->result, "attract", json_boolean(c->d->attracting));
	/* the figure the status line names, in its words, and the line as last drawn */
	int fig = daemon_kiosk_figure(c->d);
	char who[160];
	if (fig >= 0)
		family_describe(&c->d->env, fig, who, sizeof who);
	json_object_set_new(c->result, "figure",
			    fig >= 0 ? json_pack("{ssss}", "name", c->d->env.fig[fig].name, "says", who)
				     : json_null());
	json_object_set_new(c->result, "status",
			    c->d->status_line[0] ? json_string(c->d->status_line) : json_null());
	json_object_set_new(c->result, "message", json_string(c->d->message));
	if (!k)
		return 0;
	const struct editline *el = kiosk_line(k);
	json_object_set_new(c->result, "line", json_string(editline_text(el)));
	json_object_set_new(c->result, "cursor", json_integer((json_int_t)el->cursor));
	json_object_set_new(c->result, "value", json_boolean(kiosk_typing_value(k)));
	json_object_set_new(c->result, "keymap", json_string(c->d->keymap));
	const char *key = libevdev_event_code_get_name(EV_KEY, kiosk_view_key(k));
	json_object_set_new(c->result, "viewkey", json_string(key ? key : "?"));
	const struct prompt_arg *a = c->d->prompt ? prompt_asking(c->d->prompt) : NULL;
	json_t *pr = json_null();
	if (a) {
		pr = json_object();
		json_object_set_new(pr, "line", json_string(prompt_line(c->d->prompt)));
		json_object_set_new(pr, "question", json_string(a->question));
	}
	json_object_set_new(c->result, "prompt", pr);
	json_t *hover = json_null();
	if (c->d->hover_fig >= 0 && c->d->hover_fig < ENV_MAX_FIGURES && c->d->env.fig[c->d->hover_fig].gen) {
		const struct env_figure *f = &c->d->env.fig[c->d->hover_fig];
		hover = json_object();
		json_object_set_new(hover, "figure", json_string(f->name));
		json_object_set_new(hover, "segment", json_string(f->model->seg_name[c->d->hover_seg]));
	}
	json_object_set_new(c->result, "picked", hover);
	const struct menu *m = c->d->menu;
	json_t *menu = json_null();
	if (m && menu_is_open(m)) {
		menu = json_object();
		json_object_set_new(menu, "filter", json_string(m->filter));
		int hi = menu_highlighted(m);
		json_t *label = json_null();
		for (int i = 0; hi >= 0 && i < m->nitems; i++)
			if (m->item[i].cmd == hi)
				label = json_string(m->item[i].label);
		json_object_set_new(menu, "highlighted", label);
	}
	json_object_set_new(c->result, "menu", menu);
	const struct daemon *d = c->d;
	json_object_set_new(c->result, "pointer",
			    d->pointer_view >= 0 && d->env.view[d->pointer_view].used
				    ? json_pack("{sssfsf}", "view", d->env.view[d->pointer_view].name,
						"x", d->pointer_x, "y", d->pointer_y)
				    : json_null());
	return 0;
}

/* bind dial|button ..., unbind dial|button ...: the panel's bindings changed at run time */
static int
rebind(struct cmd_ctx *c, const char *verb)
{
	struct dial_bind *t = c->d->bindings;
	if (!t)
		return cmd_fail(c, "bad-argument", "this daemon has no dial panel bindings");
	const char *w[16];
	int n = 0;
	w[n++] = verb;
	for (int i = 0; i < c->argc && n < 16; i++)
		w[n++] = c->argv[i];
	struct dial_bind_lookup lookup = { dial_bind_find_in_map, c->d->panel };
	char err[300];
	if (dial_bind_command(t, w, n, c->d->panel ? &lookup : NULL, err, sizeof err) < 0)
		return cmd_fail(c, "bad-argument", "%s", err);
	return 0;
}

int
cmd_bind(struct cmd_ctx *c)
{
	return rebind(c, "bind");
}

int
cmd_unbind(struct cmd_ctx *c)
{
	return rebind(c, "unbind");
}

/* the bindings as their file would hold them, and the dials' counters */
int
cmd_list_bindings(struct cmd_ctx *c)
{
	const struct dial_bind *t = c->d->bindings;
	if (!t)
		return cmd_fail(c, "bad-argument", "this daemon has no dial panel bindings");
	char *text = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&text, &len);
	if (!f)
		return cmd_fail(c, "internal", "out of memory");
	dial_bind_write(f, t);
	fclose(f);
	json_object_set_new(c->result, "text", json_stringn(text ? text : "", len));
	free(text);
	json_object_set_new(c->result, "dials", json_integer(t->ndial));
	json_object_set_new(c->result, "buttons", json_integer(t->nbutton));
	json_object_set_new(c->result, "nonfinite", json_integer((json_int_t)t->nonfinite));
	json_object_set_new(c->result, "dead", json_integer((json_int_t)t->dead));
	return 0;
}
