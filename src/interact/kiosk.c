/* kiosk.c - the kiosk's keyboard: the edit line, values typed in a mode, its keys (see kiosk.h) */
#include "interact/kiosk.h"

#include <linux/input-event-codes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct kiosk {
	struct kbd_text *kt;
	unsigned view_key;
	struct editline line;  /* the command line, with its history */
	struct editline value; /* a value typed in a mode: a history of its own */
	int typing_value;
	char out[EDITLINE_MAX + 1]; /* the line an action hands over */
};

struct kiosk_def
kiosk_default_def(void)
{
	struct kiosk_def d = { .keymap = kbd_text_default_def(), .view_key = KEY_F2 };
	return d;
}

int
kiosk_keymap_names(const char *spec, struct kbd_text_def *d, char *buf, size_t len)
{
	size_t n = strlen(spec);
	if (!n || n >= len)
		return -1;
	for (size_t i = 0; i < n; i++) {
		char ch = spec[i];
		int ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
			 ch == '_' || ch == '-' || ch == ',' || ch == ':' || ch == '(' || ch == ')';
		if (!ok)
			return -1;
	}
	memcpy(buf, spec, n + 1);
	char *colon = strchr(buf, ':');
	if (colon)
		*colon = '\0';
	if (!buf[0] || (colon && (!colon[1] || strchr(colon + 1, ':'))))
		return -1;
	d->layout = buf;
	d->variant = colon ? colon + 1 : "";
	return 0;
}

struct kiosk *
kiosk_create(const struct kiosk_def *d, char *err, size_t errlen)
{
	struct kiosk *k = calloc(1, sizeof *k);
	if (!k) {
		snprintf(err, errlen, "out of memory");
		return NULL;
	}
	if (!(k->kt = kbd_text_create(&d->keymap, err, errlen))) {
		free(k);
		return NULL;
	}
	k->view_key = d->view_key;
	struct editline_def ed = editline_default_def();
	ed.complete = d->complete;
	ed.complete_user = d->complete_user;
	editline_init(&k->line, &ed);
	struct editline_def vd = editline_default_def();
	vd.history = 8;
	editline_init(&k->value, &vd);
	return k;
}

void
kiosk_free(struct kiosk *k)
{
	if (!k)
		return;
	kbd_text_free(k->kt);
	free(k);
}

int
kiosk_set_keymap(struct kiosk *k, const struct kbd_text_def *d, char *err, size_t errlen)
{
	struct kbd_text *kt = kbd_text_create(d, err, errlen);
	if (!kt)
		return -1;
	kbd_text_free(k->kt);
	k->kt = kt;
	return 0;
}

void
kiosk_set_view_key(struct kiosk *k, unsigned code)
{
	k->view_key = code;
}

unsigned
kiosk_view_key(const struct kiosk *k)
{
	return k->view_key;
}

const struct editline *
kiosk_line(const struct kiosk *k)
{
	return k->typing_value ? &k->value : &k->line;
}

int
kiosk_typing_value(const struct kiosk *k)
{
	return k->typing_value;
}

void
kiosk_visible(struct kiosk *k, int width, struct editline_window *dest)
{
	editline_visible(k->typing_value ? &k->value : &k->line, width, dest);
}

static void
drop_value(struct kiosk *k)
{
	struct kbd_text_key esc = { .ctl = KBD_CTL_ESCAPE };
	editline_key(&k->value, &esc);
	k->typing_value = 0;
}

int
kiosk_translate(struct kiosk *k, const struct input_event_rec *e, struct kbd_text_key *dest)
{
	return e->kind == INPUT_KEY && kbd_text_key(k->kt, e->code, e->value, dest) == 1;
}

void
kiosk_clear(struct kiosk *k)
{
	struct kbd_text_key esc = { .ctl = KBD_CTL_ESCAPE };
	editline_key(&k->line, &esc);
	drop_value(k);
}

void
kiosk_mode_ended(struct kiosk *k)
{
	drop_value(k);
}

static struct kiosk_action
act(enum kiosk_action_kind kind, const char *line)
{
	struct kiosk_action a = { kind, line };
	return a;
}

/* Ctrl+Z undo, Ctrl+Y or Ctrl+Shift+Z redo; KIOSK_NONE for any other key */
static enum kiosk_action_kind
history_key(const struct kbd_text_key *key)
{
	if (!(key->mods & KBD_MOD_CTRL) || (key->mods & KBD_MOD_ALT))
		return KIOSK_NONE;
	if (key->keysym == 'z')
		return key->mods & KBD_MOD_SHIFT ? KIOSK_REDO : KIOSK_UNDO;
	if (key->keysym == 'Z' || key->keysym == 'y' || key->keysym == 'Y')
		return KIOSK_REDO;
	return KIOSK_NONE;
}

/* the first character of a value typed in a mode: a digit, a sign or a point */
static int
starts_value(const struct kbd_text_key *key)
{
	const char *t = key->text;
	return !(key->mods & (KBD_MOD_CTRL | KBD_MOD_ALT)) && t[0] && !t[1] &&
	       ((t[0] >= '0' && t[0] <= '9') || t[0] == '-' || t[0] == '+' || t[0] == '.');
}

/* a key while a value is being typed in a mode: the value's, all of it */
static struct kiosk_action
value_key(struct kiosk *k, const struct kbd_text_key *key)
{
	if (key->ctl == KBD_CTL_ESCAPE) { /* drops the value, not the mode */
		drop_value(k);
		return act(KIOSK_TAKEN, NULL);
	}
	enum editline_result r = editline_key(&k->value, key);
	if (r == EDITLINE_ENTERED) {
		k->typing_value = 0;
		snprintf(k->out, sizeof k->out, "%s", editline_entered(&k->value));
		return act(k->out[0] ? KIOSK_VALUE : KIOSK_TAKEN, k->out);
	}
	if (!editline_text(&k->value)[0]) /* erased back to nothing: the mode's keys again */
		k->typing_value = 0;
	return act(KIOSK_TAKEN, NULL);
}

/* a key at the edit line (no mode) */
static struct kiosk_action
line_key(struct kiosk *k, unsigned code, const struct kbd_text_key *key)
{
	if (code == k->view_key)
		return act(KIOSK_CHANGE_VIEW, NULL);
	enum kiosk_action_kind h = history_key(key);
	if (h != KIOSK_NONE)
		return act(h, NULL);
	if ((code == KEY_PAGEDOWN || code == KEY_PAGEUP) && !(key->mods & (KBD_MOD_CTRL | KBD_MOD_ALT)))
		return act(code == KEY_PAGEDOWN ? KIOSK_NEXT : KIOSK_PREVIOUS, NULL);
	/* ESC on an empty line is nobody's: the change of view, say, may want it */
	if (key->ctl == KBD_CTL_ESCAPE && !editline_text(&k->line)[0])
		return act(KIOSK_NONE, NULL);
	enum editline_result r = editline_key(&k->line, key);
	if (r == EDITLINE_ENTERED) {
		snprintf(k->out, sizeof k->out, "%s", editline_entered(&k->line));
		return act(k->out[0] ? KIOSK_RUN : KIOSK_TAKEN, k->out);
	}
	return act(KIOSK_TAKEN, NULL);
}

struct kiosk_action
kiosk_input(struct kiosk *k, const struct input_event_rec *e, enum kiosk_keys keys)
{
	if (e->kind == INPUT_REMOVED && e->code == INPUT_CLASS_KEYBOARD) {
		/* its releases will never come; the typed line goes with it */
		kbd_text_reset(k->kt);
		struct kbd_text_key esc = { .ctl = KBD_CTL_ESCAPE };
		editline_key(&k->line, &esc);
		drop_value(k);
		return act(KIOSK_NONE, NULL);
	}
	if (e->kind != INPUT_KEY)
		return act(KIOSK_NONE, NULL);
	struct kbd_text_key key;
	if (kbd_text_key(k->kt, e->code, e->value, &key) != 1 || keys == KIOSK_KEYS_OTHER)
		return act(KIOSK_NONE, NULL); /* a release (the mode may want it), or not ours */
	if (keys == KIOSK_KEYS_LINE) {
		drop_value(k);
		return line_key(k, e->code, &key);
	}
	if (k->typing_value)
		return value_key(k, &key);
	enum kiosk_action_kind h = history_key(&key);
	if (h != KIOSK_NONE)
		return act(h, NULL);
	if (starts_value(&key)) {
		k->typing_value = 1;
		editline_insert(&k->value, key.text);
		return act(KIOSK_TAKEN, NULL);
	}
	return act(KIOSK_NONE, NULL);
}
