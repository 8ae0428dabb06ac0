/* kiosk_route.c - the kiosk's input before the modes (see kiosk_route.h) */
#include "daemon/kiosk_route.h"

#include <linux/input-event-codes.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "daemon/cmd.h"
#include "daemon/family.h"
#include "draw/tiles.h"
#include "interact/mouse_line.h"
#include "interact/pick.h"

/* the change-view key at the edit line: change view entered as V enters it from a mode */
static void
enter_change_view(struct modes *M, const struct input_event_rec *e)
{
	struct input_event_rec v = *e;
	v.code = KEY_V;
	v.value = 1;
	modes_view_input(M, &v, 0, 0);
}

/* the prompt asked its last question, or was cancelled: the pointer picks nothing now */
static void
prompt_over(struct modes *M)
{
	M->hover_fig = M->hover_seg = -1;
	M->d->hover_fig = M->d->hover_seg = -1;
	M->scene->dirty = 1;
}

/* what a prompt asking now would show on the message line */
static void
say_question(struct modes *M)
{
	const struct prompt_arg *a = prompt_asking(&M->prompt);
	if (a)
		snprintf(M->d->message, sizeof M->d->message, "%s%s", a->question,
			 a->kind <= PROMPT_VIEW ? " (pick it, or type it; ESC cancels)" : " (ESC cancels)");
}

/* an answer to the prompt: the next question, or the whole line run */
static void
answer(struct modes *M, const char *word)
{
	int r = prompt_answer(&M->prompt, word);
	if (r == 1) {
		prompt_over(M);
		M->run_typed(M->ctx, prompt_line(&M->prompt));
	} else {
		say_question(M);
	}
	M->scene->dirty = 1;
}

/*
 * Enter at the edit line: the answer to a prompt asking; else the line,
 * run when it is whole, or its missing arguments asked for first.
 */
static void
line_entered(struct modes *M, const char *line)
{
	if (M->prompt.active) {
		answer(M, line);
		return;
	}
	const char *usage = cmd_usage_of_line(line);
	if (usage && prompt_begin(&M->prompt, usage, line) == 1) {
		say_question(M);
		return;
	}
	M->run_typed(M->ctx, line);
}

/* what lies under the pointer of view v: figure and segment, with the hit; 0 on nothing */
static int
under_pointer(struct modes *M, struct pick_hit *h, int *fig)
{
	int v = M->pointer_view;
	if (v < 0 || !M->d->env.view[v].used)
		return 0;
	const struct env_view *vw = &M->d->env.view[v];
	struct camera cam;
	view_camera_of_view(vw, &cam);
	struct ray r;
	return mouse_line(&cam, vw->width, vw->height, M->pointer_x, M->pointer_y, &r) == 0 &&
	       daemon_pick(M->d, &r, cam.znear, -1, h, fig) > 0;
}

/* the word the pointer picks for the question asked: a figure's, a joint's, a site's, a view's */
static int
picked_word(struct modes *M, const struct prompt_arg *a, char *dest, size_t len)
{
	if (a->kind == PROMPT_VIEW) {
		if (M->pointer_view < 0 || !M->d->env.view[M->pointer_view].used)
			return 0;
		snprintf(dest, len, "%s", M->d->env.view[M->pointer_view].name);
		return 1;
	}
	struct pick_hit h;
	int fig;
	if (!under_pointer(M, &h, &fig))
		return 0;
	const struct env_figure *f = &M->d->env.fig[fig];
	if (a->kind == PROMPT_FIGURE) {
		snprintf(dest, len, "%s", f->name);
	} else if (a->kind == PROMPT_SITE && h.site >= 0) {
		model_site_fullname(f->model, h.site, dest, len);
	} else if (a->kind == PROMPT_JOINT) {
		/* the joint above the segment; the root segment's: the one it hangs the rest from */
		int j = f->state->seg_root_joint[h.segment];
		for (int k = 0; j < 0 && k < f->model->njnt; k++)
			if (f->model->site_seg[f->model->jnt_site_from[k]] == h.segment ||
			    f->model->site_seg[f->model->jnt_site_to[k]] == h.segment)
				j = k;
		if (j < 0)
			return 0;
		snprintf(dest, len, "%s", f->model->jnt_name[j]);
	} else {
		return 0;
	}
	return 1;
}

/*
 * While a prompt asks for something the pointer can pick: what is under
 * the pointer is highlighted as it moves, and a left click answers.
 * Returns 1 when the event was the prompt's.
 */
static int
drive_prompt(struct modes *M, const struct input_event_rec *e)
{
	const struct prompt_arg *a = prompt_asking(&M->prompt);
	if (!a || M->interact.mode != INTERACT_NONE || modes_viewing(M))
		return 0;
	if (e->kind == INPUT_KEY && e->code == KEY_ESC && e->value == 1) {
		prompt_cancel(&M->prompt);
		prompt_over(M);
		if (M->kiosk)
			kiosk_clear(M->kiosk);
		snprintf(M->d->message, sizeof M->d->message, "cancelled: nothing changed");
		return 1;
	}
	if (a->kind > PROMPT_VIEW)
		return 0;
	if (e->kind == INPUT_MOTION || e->kind == INPUT_POINTER) {
		struct pick_hit h;
		int fig = -1;
		int hit = a->kind != PROMPT_VIEW && under_pointer(M, &h, &fig);
		M->hover_fig = M->d->hover_fig = hit ? fig : -1;
		M->hover_seg = M->d->hover_seg = hit ? h.segment : -1;
		M->scene->dirty = 1;
		return 0; /* the pointer goes on moving for everyone */
	}
	if (e->kind == INPUT_BUTTON && e->code == BTN_LEFT && e->value == 1) {
		char word[128];
		if (picked_word(M, a, word, sizeof word))
			answer(M, word);
		else
			snprintf(M->d->message, sizeof M->d->message, "nothing there: %s", a->question);
		return 1;
	}
	return e->kind == INPUT_BUTTON && e->code == BTN_LEFT; /* its release too */
}

/* the menu chose a command: its words go to the edit line's path (the prompts ask the rest) */
static void
menu_chosen(struct modes *M, int cmd)
{
	char line[96];
	const char *obj = cmd_entry_object(cmd);
	snprintf(line, sizeof line, "%s%s%s", cmd_entry_verb(cmd), obj && obj[0] ? " " : "",
		 obj ? obj : "");
	line_entered(M, line);
}

/*
 * The pop-up menu: a mouse button pressed on the background
 * (nothing under the pointer) with no mode, prompt or change view opens it
 * at the pointer; while open, the pointer, the buttons, the wheel and the
 * keys are its own. Returns 1 when the event was the menu's.
 */
static int
drive_menu(struct modes *M, const struct input_event_rec *e)
{
	struct menu *m = &M->menu;
	int open = menu_is_open(m);
	if (!open) {
		if (e->kind != INPUT_BUTTON || e->value != 1 || !input_is_mouse_button(e) ||
		    M->interact.mode != INTERACT_NONE || prompt_asking(&M->prompt) || modes_viewing(M) ||
		    M->pointer_view < 0 || !M->d->env.view[M->pointer_view].used)
			return 0;
		struct pick_hit h;
		int fig;
		if (under_pointer(M, &h, &fig))
			return 0; /* on a figure: not the background */
		const struct env_view *vw = &M->d->env.view[M->pointer_view];
		/* above the message and status lines, which stay readable under it */
		if (menu_open(m, (int)M->pointer_x, (int)M->pointer_y, vw->width,
			      vw->height - 2 * VIEW_LINE_PX).kind == MENU_NONE)
			return 0;
		M->menu_view = M->d->menu_view = M->pointer_view;
		M->scene->dirty = 1;
		return 1;
	}
	struct menu_action a = { MENU_NONE, -1 };
	struct kbd_text_key key;
	int x = (int)M->pointer_x, y = (int)M->pointer_y;
	if (e->kind == INPUT_KEY) {
		if (M->kiosk && kiosk_translate(M->kiosk, e, &key))
			a = menu_key(m, e->code, &key);
	} else if (e->kind == INPUT_MOTION || e->kind == INPUT_POINTER) {
		a = menu_pointer(m, x, y);
	} else if (e->kind == INPUT_BUTTON && input_is_mouse_button(e)) {
		a = menu_button(m, e->value != 0, x, y);
	} else if (e->kind == INPUT_WHEEL) {
		a = menu_wheel(m, e->value);
	} else {
		return 0;
	}
	if (a.kind != MENU_NONE)
		M->scene->dirty = 1;
	if (a.kind == MENU_CHOSEN || a.kind == MENU_CLOSED)
		M->menu_view = M->d->menu_view = -1;
	if (a.kind == MENU_CHOSEN)
		menu_chosen(M, a.cmd);
	return 1;
}

/* member fig of the family shown made the selected one: the line run as if typed */
static void
select_member(struct modes *M, int fig)
{
	const struct env_show *sh = &M->d->env.show;
	char line[256];
	int row = sh->arrange == ENV_SHOW_ROW;
	int k = snprintf(line, sizeof line, "show family %s %s select=%s", sh->family,
			 row ? "row" : "overlay", M->d->env.fig[fig].name);
	if (row) /* the row's spacing kept, not its default taken again */
		snprintf(line + k, sizeof line - (size_t)k, " spacing=%.17g", sh->spacing);
	M->run_typed(M->ctx, line);
}

/* Page Down (dir 1), Page Up (-1): the next or previous member of the family shown, around */
static void
step_member(struct modes *M, int dir)
{
	const struct env *e = &M->d->env;
	int sel = family_selected(e);
	if (sel < 0) {
		snprintf(M->d->message, sizeof M->d->message,
			 "Page Down, Page Up: no family shown (show family PREFIX row|overlay)");
		return;
	}
	int slot[ENV_MAX_FIGURES], n = family_members(e, e->show.family, slot), i = 0;
	while (slot[i] != sel)
		i++;
	select_member(M, slot[(i + dir + n) % n]);
}

/*
 * A left click on a member of the family shown (not a ghost: those are
 * not picked), with no mode, prompt or menu, makes it the selected one.
 * Returns 1 when the event was that.
 */
static int
drive_select(struct modes *M, const struct input_event_rec *e)
{
	struct pick_hit h;
	int fig;
	if (e->kind != INPUT_BUTTON || e->code != BTN_LEFT || e->value != 1 ||
	    M->interact.mode != INTERACT_NONE || prompt_asking(&M->prompt) || modes_viewing(M) ||
	    family_selected(&M->d->env) < 0 || !under_pointer(M, &h, &fig) ||
	    !family_is_member(&M->d->env, M->d->env.show.family, fig) ||
	    fig == family_selected(&M->d->env))
		return 0;
	select_member(M, fig);
	return 1;
}

/*
 * The keyboard's events go to the kiosk first (the edit line, a value
 * typed in a mode, undo and redo); 1 when it took the event.
 */
static int
drive_kiosk(struct modes *M, const struct input_event_rec *e)
{
	if (!M->kiosk)
		return 0;
	enum kiosk_keys keys = modes_viewing(M) ? KIOSK_KEYS_OTHER
				: M->interact.mode != INTERACT_NONE ? KIOSK_KEYS_MODE
								     : KIOSK_KEYS_LINE;
	struct kiosk_action a = kiosk_input(M->kiosk, e, keys);
	char line[EDITLINE_MAX + 32];
	switch (a.kind) {
	case KIOSK_NONE:
		return 0;
	case KIOSK_TAKEN:
		break;
	case KIOSK_RUN:
		line_entered(M, a.line);
		break;
	case KIOSK_VALUE:
		snprintf(line, sizeof line, "set manip %s", a.line);
		M->run_typed(M->ctx, line);
		break;
	case KIOSK_UNDO:
	case KIOSK_REDO:
		M->run_typed(M->ctx, a.kind == KIOSK_UNDO ? "undo" : "redo");
		break;
	case KIOSK_CHANGE_VIEW:
		enter_change_view(M, e);
		break;
	case KIOSK_NEXT:
	case KIOSK_PREVIOUS:
		step_member(M, a.kind == KIOSK_NEXT ? 1 : -1);
		break;
	}
	M->scene->dirty = 1;
	return 1;
}

/*
 * With views tiled on the screen (layout), the pointer is the screen's:
 * motion moves it across the tiles and an absolute position (0..1) is a
 * point of the whole screen. Either becomes a position in pixels of the
 * view under it, which is what the modes and change view take.
 */
static void
screen_pointer(struct modes *M, struct input_event_rec *e, long px, long py)
{
	const struct env *env = &M->d->env;
	struct tiles T;
	if (!env->nlayout || (e->kind != INPUT_MOTION && e->kind != INPUT_POINTER) ||
	    tiles_make(&T, M->d->screen_w, M->d->screen_h, SCENE_BAND, env->nlayout) < 0)
		return;
	if (e->kind == INPUT_POINTER && (e->flags & INPUT_F_VIEW)) {
		for (int i = 0; i < env->nlayout; i++) /* a view's pixel: where it is on the screen */
			if (env->layout[i] == e->code)
				tiles_to_screen(&T, i, e->x, e->y, &M->screen_x, &M->screen_y);
		return;
	}
	if (e->kind == INPUT_POINTER) {
		M->screen_x = e->x * T.screen_w;
		M->screen_y = e->y * T.screen_h;
	} else if (M->interact.mode == INTERACT_NONE && !modes_viewing(M)) {
		/* (in a mode, or changing the view, motion is the mode's, in its view) */
		M->screen_x = fmin(fmax(M->screen_x + (double)px, 0), T.screen_w - 1);
		M->screen_y = fmin(fmax(M->screen_y + (double)py, 0), T.screen_h - 1);
	} else {
		return;
	}
	double vx, vy;
	int i = tiles_at(&T, M->screen_x, M->screen_y, &vx, &vy);
	if (i < 0)
		return; /* a gap or the band: the pointer stays where it was for the views */
	e->kind = INPUT_POINTER;
	e->flags |= INPUT_F_VIEW;
	e->code = (uint16_t)env->layout[i];
	e->x = vx;
	e->y = vy;
}

void
kiosk_route_input(struct modes *M, const struct input_event_rec *in, long px, long py)
{
	struct input_event_rec ev = *in;
	const struct input_event_rec *e = &ev;
	screen_pointer(M, &ev, px, py);
	modes_track_pointer(M, e, px, py);
	enum interact_mode was = M->interact.mode;
	if (!drive_menu(M, e) && !drive_prompt(M, e) && !drive_select(M, e) && !drive_kiosk(M, e) &&
	    !modes_view_input(M, e, px, py))
		modes_mode_input(M, e, px, py);
	if (was != INTERACT_NONE && M->interact.mode == INTERACT_NONE && M->kiosk)
		kiosk_mode_ended(M->kiosk);
}

