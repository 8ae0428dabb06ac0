#include "interact/kbd_text.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <xkbcommon/xkbcommon-compose.h>
#include <xkbcommon/xkbcommon.h>

/* evdev codes are xkb keycodes less 8 (the X server's offset, kept by xkb-data's keycodes) */
#define EVDEV_XKB_OFFSET 8

/* the compose table every UTF-8 locale of libx11-data shares */
#define FALLBACK_LOCALE "en_US.UTF-8"

#define HELD_WORDS ((KBD_TEXT_MAX_CODE + 1 + 63) / 64)

struct kbd_text {
	struct xkb_context *ctx;
	struct xkb_keymap *keymap;
	struct xkb_state *state;
	struct xkb_compose_table *compose_table;
	struct xkb_compose_state *compose;
	xkb_mod_index_t mod_shift, mod_ctrl, mod_alt;
	/* keys down, so a reset can release them through the keymap's own actions */
	uint64_t held[HELD_WORDS];
	char compose_locale[64];
	/* xkbcommon's last error while creating, for the message to the caller */
	char xkb_error[160];
};

struct kbd_text_def
kbd_text_default_def(void)
{
	return (struct kbd_text_def){
		.model = "pc105",
		.layout = "us",
		.variant = "",
		.options = "",
		.locale = "C.UTF-8",
	};
}

/* keeps xkbcommon's first error of a creation instead of printing it on stderr */
static void
keep_xkb_error(struct xkb_context *ctx, enum xkb_log_level level, const char *fmt, va_list args)
{
	struct kbd_text *kt = xkb_context_get_user_data(ctx);
	(void)level;
	if (kt->xkb_error[0])
		return;
	vsnprintf(kt->xkb_error, sizeof kt->xkb_error, fmt, args);
	/* its messages end in a newline; ours are one line */
	kt->xkb_error[strcspn(kt->xkb_error, "\n")] = '\0';
}

static const char *
or_empty(const char *s)
{
	return s ? s : "";
}

static int
compile_keymap(struct kbd_text *kt, const struct kbd_text_def *d, char *err, size_t errlen)
{
	const struct xkb_rule_names names = {
		.rules = NULL,
		.model = or_empty(d->model),
		.layout = or_empty(d->layout),
		.variant = or_empty(d->variant),
		.options = or_empty(d->options),
	};
	if (!names.layout[0]) {
		snprintf(err, errlen, "kbd_text: no keyboard layout given");
		return -1;
	}
	kt->keymap = xkb_keymap_new_from_names(kt->ctx, &names, XKB_KEYMAP_COMPILE_NO_FLAGS);
	if (!kt->keymap) {
		snprintf(err, errlen,
			 "kbd_text: no keymap for layout \"%s\" variant \"%s\" options \"%s\" "
			 "(see /usr/share/X11/xkb/rules/evdev.lst): %s",
			 names.layout, names.variant, names.options,
			 kt->xkb_error[0] ? kt->xkb_error : "xkbcommon gave no reason");
		return -1;
	}
	kt->state = xkb_state_new(kt->keymap);
	if (!kt->state) {
		snprintf(err, errlen, "kbd_text: out of memory");
		return -1;
	}
	kt->mod_shift = xkb_keymap_mod_get_index(kt->keymap, XKB_MOD_NAME_SHIFT);
	kt->mod_ctrl = xkb_keymap_mod_get_index(kt->keymap, XKB_MOD_NAME_CTRL);
	kt->mod_alt = xkb_keymap_mod_get_index(kt->keymap, XKB_MOD_NAME_ALT);
	return 0;
}

static struct xkb_compose_table *
compose_table_for(struct kbd_text *kt, const char *locale)
{
	struct xkb_compose_table *t =
		xkb_compose_table_new_from_locale(kt->ctx, locale, XKB_COMPOSE_COMPILE_NO_FLAGS);
	if (t)
		snprintf(kt->compose_locale, sizeof kt->compose_locale, "%s", locale);
	return t;
}

static int
load_compose(struct kbd_text *kt, const struct kbd_text_def *d, char *err, size_t errlen)
{
	const char *locale = d->locale && d->locale[0] ? d->locale : "C.UTF-8";
	kt->compose_table = compose_table_for(kt, locale);
	/* older libx11-data has no C.UTF-8 entry; every UTF-8 locale shares en_US's table */
	if (!kt->compose_table)
		kt->compose_table = compose_table_for(kt, FALLBACK_LOCALE);
	if (!kt->compose_table) {
		snprintf(err, errlen,
			 "kbd_text: no compose table for locale \"%s\" nor \"%s\" "
			 "(is libx11-data installed? /usr/share/X11/locale)",
			 locale, FALLBACK_LOCALE);
		return -1;
	}
	kt->compose = xkb_compose_state_new(kt->compose_table, XKB_COMPOSE_STATE_NO_FLAGS);
	if (!kt->compose) {
		snprintf(err, errlen, "kbd_text: out of memory");
		return -1;
	}
	return 0;
}

static int
is_held(const struct kbd_text *kt, unsigned code)
{
	return (kt->held[code / 64] >> (code % 64)) & 1;
}

static void
set_held(struct kbd_text *kt, unsigned code, int down)
{
	uint64_t bit = (uint64_t)1 << (code % 64);
	if (down)
		kt->held[code / 64] |= bit;
	else
		kt->held[code / 64] &= ~bit;
}

static enum kbd_ctl
ctl_of_keysym(xkb_keysym_t sym)
{
	if (sym >= XKB_KEY_F1 && sym <= XKB_KEY_F12)
		return KBD_CTL_F1 + (int)(sym - XKB_KEY_F1);
	switch (sym) {
	case XKB_KEY_Return:
	case XKB_KEY_KP_Enter:
		return KBD_CTL_RETURN;
	case XKB_KEY_BackSpace:
		return KBD_CTL_BACKSPACE;
	case XKB_KEY_Delete:
	case XKB_KEY_KP_Delete:
		return KBD_CTL_DELETE;
	case XKB_KEY_Left:
	case XKB_KEY_KP_Left:
		return KBD_CTL_LEFT;
	case XKB_KEY_Right:
	case XKB_KEY_KP_Right:
		return KBD_CTL_RIGHT;
	case XKB_KEY_Up:
	case XKB_KEY_KP_Up:
		return KBD_CTL_UP;
	case XKB_KEY_Down:
	case XKB_KEY_KP_Down:
		return KBD_CTL_DOWN;
	case XKB_KEY_Home:
	case XKB_KEY_KP_Home:
		return KBD_CTL_HOME;
	case XKB_KEY_End:
	case XKB_KEY_KP_End:
		return KBD_CTL_END;
	case XKB_KEY_Tab:
	case XKB_KEY_ISO_Left_Tab:
	case XKB_KEY_KP_Tab:
		return KBD_CTL_TAB;
	case XKB_KEY_Escape:
		return KBD_CTL_ESCAPE;
	default:
		return KBD_CTL_NONE;
	}
}

/* a modifier counts when it is on and the key did not use it to pick its symbol (Shift+a) */
static int
mod_counts(const struct kbd_text *kt, xkb_keycode_t kc, xkb_mod_index_t m)
{
	if (m == XKB_MOD_INVALID)
		return 0;
	return xkb_state_mod_index_is_active(kt->state, m, XKB_STATE_MODS_EFFECTIVE) > 0 &&
	       xkb_state_mod_index_is_consumed(kt->state, kc, m) == 0;
}

static unsigned
mods_of_key(const struct kbd_text *kt, xkb_keycode_t kc)
{
	return (mod_counts(kt, kc, kt->mod_shift) ? KBD_MOD_SHIFT : 0) |
	       (mod_counts(kt, kc, kt->mod_ctrl) ? KBD_MOD_CTRL : 0) |
	       (mod_counts(kt, kc, kt->mod_alt) ? KBD_MOD_ALT : 0);
}

/* text with a C0 control or DEL in it is a control key's, not something to type */
static int
is_printable(const char *s)
{
	for (; *s; s++)
		if ((unsigned char)*s < 0x20 || (unsigned char)*s == 0x7f)
			return 0;
	return 1;
}

/* keeps text in dest only when it fit whole (a cut one could end mid-character) */
static void
keep_text(int need, struct kbd_text_key *dest)
{
	if (need <= 0 || need >= KBD_TEXT_MAX || !is_printable(dest->text))
		dest->text[0] = '\0';
}

/* the key through the compose table; a key outside any sequence keeps its own text */
static void
compose_key(struct kbd_text *kt, xkb_keycode_t kc, struct kbd_text_key *dest)
{
	xkb_compose_state_feed(kt->compose, dest->keysym);
	switch (xkb_compose_state_get_status(kt->compose)) {
	case XKB_COMPOSE_NOTHING:
		dest->compose = KBD_COMPOSE_NONE;
		keep_text(xkb_state_key_get_utf8(kt->state, kc, dest->text, KBD_TEXT_MAX), dest);
		return;
	case XKB_COMPOSE_COMPOSING:
		dest->compose = KBD_COMPOSE_PENDING;
		return;
	case XKB_COMPOSE_COMPOSED:
		dest->compose = KBD_COMPOSE_DONE;
		keep_text(xkb_compose_state_get_utf8(kt->compose, dest->text, KBD_TEXT_MAX), dest);
		dest->keysym = xkb_compose_state_get_one_sym(kt->compose);
		xkb_compose_state_reset(kt->compose);
		return;
	case XKB_COMPOSE_CANCELLED:
		dest->compose = KBD_COMPOSE_CANCELLED;
		xkb_compose_state_reset(kt->compose);
		return;
	}
}

/* a press or repeat, with the modifiers as they were before it */
static void
translate(struct kbd_text *kt, xkb_keycode_t kc, struct kbd_text_key *dest)
{
	dest->keysym = xkb_state_key_get_one_sym(kt->state, kc);
	dest->ctl = ctl_of_keysym(dest->keysym);
	dest->mods = mods_of_key(kt, kc);
	if (dest->keysym == XKB_KEY_NoSymbol)
		return;
	/* the edit line's commands act at once and end a pending sequence */
	if (dest->ctl != KBD_CTL_NONE || (dest->mods & (KBD_MOD_CTRL | KBD_MOD_ALT))) {
		xkb_compose_state_reset(kt->compose);
		return;
	}
	compose_key(kt, kc, dest);
}

int
kbd_text_key(struct kbd_text *kt, unsigned code, int value, struct kbd_text_key *dest)
{
	memset(dest, 0, sizeof *dest);
	if (code > KBD_TEXT_MAX_CODE || value < 0 || value > 2)
		return -1;
	xkb_keycode_t kc = code + EVDEV_XKB_OFFSET;
	if (value == 0) {
		/* a release of a key not known to be down (held before a reset) changes nothing */
		if (is_held(kt, code))
			xkb_state_update_key(kt->state, kc, XKB_KEY_UP);
		set_held(kt, code, 0);
		return 0;
	}
	translate(kt, kc, dest);
	dest->repeat = value == 2;
	/* repeats are not new presses: the state saw this key go down once */
	if (value == 1 && !is_held(kt, code)) {
		xkb_state_update_key(kt->state, kc, XKB_KEY_DOWN);
		set_held(kt, code, 1);
	}
	return 1;
}

void
kbd_text_reset(struct kbd_text *kt)
{
	/* releases through the keymap, so each modifier's action ends as it would by hand */
	for (unsigned code = 0; code <= KBD_TEXT_MAX_CODE; code++)
		if (is_held(kt, code))
			xkb_state_update_key(kt->state, code + EVDEV_XKB_OFFSET, XKB_KEY_UP);
	memset(kt->held, 0, sizeof kt->held);
	/* then locks and latches, which outlive their keys: a new keyboard starts with none */
	xkb_state_update_mask(kt->state, 0, 0, 0, 0, 0, 0);
	xkb_compose_state_reset(kt->compose);
}

/*
 * xkbcommon keeps the action of each held modifier key in an array it
 * grows when more are held than ever before. Holding every key of the
 * keymap once, here, grows it to the most any keys held together can
 * need, so feeding keys never allocates afterwards.
 */
static void
hold_every_key_once(struct kbd_text *kt)
{
	xkb_keycode_t lo = xkb_keymap_min_keycode(kt->keymap);
	xkb_keycode_t hi = xkb_keymap_max_keycode(kt->keymap);
	for (xkb_keycode_t kc = lo; kc <= hi; kc++)
		if (kc >= EVDEV_XKB_OFFSET && kc - EVDEV_XKB_OFFSET <= KBD_TEXT_MAX_CODE) {
			xkb_state_update_key(kt->state, kc, XKB_KEY_DOWN);
			set_held(kt, kc - EVDEV_XKB_OFFSET, 1);
		}
	kbd_text_reset(kt);
}

struct kbd_text *
kbd_text_create(const struct kbd_text_def *d, char *err, size_t errlen)
{
	struct kbd_text *kt = calloc(1, sizeof *kt);
	if (!kt) {
		snprintf(err, errlen, "kbd_text: out of memory");
		return NULL;
	}
	/* exactly the names given: no XKB_DEFAULT_* from whoever started the daemon */
	kt->ctx = xkb_context_new(XKB_CONTEXT_NO_ENVIRONMENT_NAMES);
	if (!kt->ctx) {
		snprintf(err, errlen, "kbd_text: cannot make an xkb context (out of memory?)");
		free(kt);
		return NULL;
	}
	xkb_context_set_user_data(kt->ctx, kt);
	xkb_context_set_log_fn(kt->ctx, keep_xkb_error);
	if (compile_keymap(kt, d, err, errlen) || load_compose(kt, d, err, errlen)) {
		kbd_text_free(kt);
		return NULL;
	}
	hold_every_key_once(kt);
	return kt;
}

void
kbd_text_free(struct kbd_text *kt)
{
	if (!kt)
		return;
	xkb_compose_state_unref(kt->compose);
	xkb_compose_table_unref(kt->compose_table);
	xkb_state_unref(kt->state);
	xkb_keymap_unref(kt->keymap);
	xkb_context_unref(kt->ctx);
	free(kt);
}

int
kbd_text_composing(const struct kbd_text *kt)
{
	return xkb_compose_state_get_status(kt->compose) == XKB_COMPOSE_COMPOSING;
}

const char *
kbd_text_compose_locale(const struct kbd_text *kt)
{
	return kt->compose_locale;
}

const char *
kbd_ctl_to_str(enum kbd_ctl c)
{
	static const char *const fkeys[] = { "f1", "f2", "f3", "f4",  "f5",  "f6",
					     "f7", "f8", "f9", "f10", "f11", "f12" };
	if (c >= KBD_CTL_F1 && c <= KBD_CTL_F12)
		return fkeys[c - KBD_CTL_F1];
	switch (c) {
	case KBD_CTL_NONE:
		return "none";
	case KBD_CTL_RETURN:
		return "return";
	case KBD_CTL_BACKSPACE:
		return "backspace";
	case KBD_CTL_DELETE:
		return "delete";
	case KBD_CTL_LEFT:
		return "left";
	case KBD_CTL_RIGHT:
		return "right";
	case KBD_CTL_UP:
		return "up";
	case KBD_CTL_DOWN:
		return "down";
	case KBD_CTL_HOME:
		return "home";
	case KBD_CTL_END:
		return "end";
	case KBD_CTL_TAB:
		return "tab";
	case KBD_CTL_ESCAPE:
		return "escape";
	default:
		return "?";
	}
}
