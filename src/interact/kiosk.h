/*
 * kiosk.h - the kiosk's keyboard (§1.7): keys become text
 * (kbd_text, the configured layout) and go to the edit line whenever no
 * mode takes them; Enter gives the daemon a command line to run. In a
 * mode, a digit, a sign or a point starts a value typed for the active
 * axis (`10cm`, `-30deg`: Blender's habit), which Enter applies and ESC
 * drops; every other key is the mode's (V, C, S, ESC, the modifiers).
 * Beside the line: the change-view key (F2 by default: at the edit line V
 * is a letter), undo (Ctrl+Z) and redo (Ctrl+Y, Ctrl+Shift+Z), and Page
 * Down and Page Up, the next and the one before of what the daemon shows
 * one of (the members of a family).
 *
 * Pure, like the rest of this layer: an event in, an action out; the
 * daemon runs the lines, draws the line and routes the rest. Nothing here
 * allocates after kiosk_create.
 */
#ifndef POSTURE_INTERACT_KIOSK_H
#define POSTURE_INTERACT_KIOSK_H

#include <stddef.h>

#include "devices/event.h"
#include "interact/editline.h"
#include "interact/kbd_text.h"

enum kiosk_action_kind {
	KIOSK_NONE,        /* the event is not the kiosk's: route it on */
	KIOSK_TAKEN,       /* taken; the line or its state changed (redraw) */
	KIOSK_RUN,         /* Enter at the edit line: run action.line as a command */
	KIOSK_VALUE,       /* Enter on a value typed in a mode: apply action.line (set manip) */
	KIOSK_UNDO,
	KIOSK_REDO,
	KIOSK_CHANGE_VIEW, /* the change-view key at the edit line */
	KIOSK_NEXT,        /* Page Down at the edit line: the next one (of the family shown) */
	KIOSK_PREVIOUS,    /* Page Up: the one before */
};

struct kiosk_action {
	enum kiosk_action_kind kind;
	const char *line; /* KIOSK_RUN, KIOSK_VALUE: valid until the next event */
};

struct kiosk_def {
	struct kbd_text_def keymap;
	unsigned view_key; /* evdev code of the change-view key at the edit line (KEY_F2) */
	int (*complete)(void *user, const char *const *words, int nwords, const char *prefix,
			const char **dest, int max); /* Tab (editline.h); may be NULL */
	void *complete_user;
};

struct kiosk_def kiosk_default_def(void);

/*
 * A keymap named as the configuration names it, LAYOUT[:VARIANT] ("de",
 * "de:nodeadkeys"), into d's layout and variant, their text kept in buf.
 * 0, or -1 when spec is empty, too long or has characters no xkb name has.
 */
int kiosk_keymap_names(const char *spec, struct kbd_text_def *d, char *buf, size_t len);

struct kiosk;

/* NULL with err when the keymap cannot be made (an unknown layout, say) */
struct kiosk *kiosk_create(const struct kiosk_def *d, char *err, size_t errlen);
void kiosk_free(struct kiosk *k);

/*
 * Replaces the keymap (the layout of `set kiosk keymap=`); the line is
 * kept. 0, or -1 with err and the old keymap kept.
 */
int kiosk_set_keymap(struct kiosk *k, const struct kbd_text_def *d, char *err, size_t errlen);
void kiosk_set_view_key(struct kiosk *k, unsigned code);
unsigned kiosk_view_key(const struct kiosk *k);

/* whose the keys are when the event comes */
enum kiosk_keys {
	KIOSK_KEYS_LINE,  /* no mode: the edit line's */
	KIOSK_KEYS_MODE,  /* a mode's, but for a value typed in it */
	KIOSK_KEYS_OTHER, /* another's (change view): only followed, for the modifiers */
};

/*
 * One input event. Every key event goes through here first, so the
 * modifiers' and compose state stays true even for the keys others take.
 * A keyboard removed (INPUT_REMOVED of a keyboard class) drops what was
 * held and typed: only the typed line is lost.
 */
struct kiosk_action kiosk_input(struct kiosk *k, const struct input_event_rec *e,
				enum kiosk_keys keys);

/*
 * A key event translated for someone else (the menu) but through the
 * kiosk's keyboard, so its modifiers stay true: 1 with dest for a press or
 * repeat, 0 otherwise.
 */
int kiosk_translate(struct kiosk *k, const struct input_event_rec *e, struct kbd_text_key *dest);

/* what is typed goes (a command cancelled under it) */
void kiosk_clear(struct kiosk *k);

/* the mode ended (ESC, or from elsewhere): a value half typed goes with it */
void kiosk_mode_ended(struct kiosk *k);

/* what the status line shows: the line, 1 while a value is being typed in a mode */
const struct editline *kiosk_line(const struct kiosk *k);
int kiosk_typing_value(const struct kiosk *k);

/* the edit line's window for a field width characters wide (editline_visible) */
void kiosk_visible(struct kiosk *k, int width, struct editline_window *dest);

#endif
