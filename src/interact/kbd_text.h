/*
 * kbd_text.h - keys become text for the kiosk's edit line: Linux evdev key
 * codes through an xkb keymap (libxkbcommon, layouts from xkb-data) and
 * the locale's compose table (libx11-data), so a German keyboard types
 * "z" on the key marked Z and dead_acute then e gives "é".
 *
 * One struct kbd_text per keyboard layout: the keymap, the modifier state
 * (which keys are held, Shift, AltGr, Caps Lock) and a pending compose
 * sequence. Everything is allocated by kbd_text_create; feeding keys
 * allocates nothing. Nothing here reads a file descriptor or a clock
 * after creation, which reads the layout and compose files.
 *
 * Rules, as text input on Linux does it:
 * - a key is translated with the modifiers as they were before it (its own
 *   press changes the state afterwards), presses and repeats give text,
 *   releases give nothing but change the state;
 * - control keys (Return, BackSpace, arrows, Tab, Escape, F1..F12 ...) and
 *   keys pressed with Ctrl or Alt give no text: they are for the edit
 *   line's commands, and they cancel a pending compose sequence instead of
 *   being swallowed by it;
 * - a compose sequence (dead keys, Multi_key) gives nothing until it ends:
 *   then its result, or nothing at all when the table has no such sequence
 *   (cancelled);
 * - the layout, variant and options are exactly those given: the XKB_DEFAULT_*
 *   environment variables are not read, so the kiosk types the same whoever
 *   starts it.
 */
#ifndef POSTURE_INTERACT_KBD_TEXT_H
#define POSTURE_INTERACT_KBD_TEXT_H

#include <stddef.h>
#include <stdint.h>

/* the largest evdev key code taken (KEY_MAX of linux/input-event-codes.h) */
#define KBD_TEXT_MAX_CODE 0x2ff
/* bytes of one key's text with its NUL: a key or compose sequence gives a few characters */
#define KBD_TEXT_MAX 64

/* keys the edit line acts on; text keys are KBD_CTL_NONE */
enum kbd_ctl {
	KBD_CTL_NONE,
	KBD_CTL_RETURN,    /* Return, KP_Enter */
	KBD_CTL_BACKSPACE,
	KBD_CTL_DELETE,    /* Delete, KP_Delete */
	KBD_CTL_LEFT,      /* and the keypad's, Num Lock off */
	KBD_CTL_RIGHT,
	KBD_CTL_UP,
	KBD_CTL_DOWN,
	KBD_CTL_HOME,
	KBD_CTL_END,
	KBD_CTL_TAB,       /* Tab, and ISO_Left_Tab (Shift+Tab on most layouts) */
	KBD_CTL_ESCAPE,
	KBD_CTL_F1,        /* F1..F12 follow in order: KBD_CTL_F1 + n - 1 */
	KBD_CTL_F12 = KBD_CTL_F1 + 11,
};

/* modifiers as the edit line sees them */
#define KBD_MOD_SHIFT 0x1u
#define KBD_MOD_CTRL 0x2u
#define KBD_MOD_ALT 0x4u

/* where a compose sequence stands after a key */
enum kbd_compose {
	KBD_COMPOSE_NONE,      /* no sequence: the key gave its own text */
	KBD_COMPOSE_PENDING,   /* a sequence goes on (a dead key, Multi_key ...): no text yet */
	KBD_COMPOSE_DONE,      /* the sequence ended: text is its result */
	KBD_COMPOSE_CANCELLED, /* no sequence starts so: nothing is typed */
};

/* one press or repeat, translated */
struct kbd_text_key {
	uint32_t keysym;           /* the xkb keysym (for Latin-1 it equals the character) */
	enum kbd_ctl ctl;          /* the edit line's key, or KBD_CTL_NONE */
	unsigned mods;             /* KBD_MOD_*: held and not used up to choose the symbol */
	enum kbd_compose compose;
	int repeat;                /* 1 for an autorepeat (value 2) */
	char text[KBD_TEXT_MAX];   /* UTF-8, NUL-terminated; "" when the key types nothing */
};

/* the RMLVO names of a keymap and the compose locale; fill from kbd_text_default_def() */
struct kbd_text_def {
	const char *model;    /* "pc105" */
	const char *layout;   /* "us"; "de", "fr", or several: "us,de" */
	const char *variant;  /* "" or e.g. "nodeadkeys" */
	const char *options;  /* "" or e.g. "compose:ralt" */
	const char *locale;   /* the compose table's: "C.UTF-8" (en_US.UTF-8 if it has none) */
};

/* pc105, us, no variant, no options, C.UTF-8 */
struct kbd_text_def kbd_text_default_def(void);

struct kbd_text;

/*
 * Compiles the keymap and loads the compose table. Returns the translator,
 * or NULL with a message in err naming what failed: a layout, variant or
 * option xkb-data does not know (it names the layout and variant), no
 * compose table for the locale nor for en_US.UTF-8 (libx11-data missing),
 * or out of memory.
 */
struct kbd_text *kbd_text_create(const struct kbd_text_def *d, char *err, size_t errlen);
void kbd_text_free(struct kbd_text *kt);

/*
 * Feeds one evdev key event: code a KEY_* code, value 0 release, 1 press,
 * 2 autorepeat. Returns 1 with dest filled for a press or repeat (text
 * may still be empty: a modifier, a pending compose sequence, a control
 * key), 0 for a release (dest zeroed), or -1 with nothing changed when
 * code is above KBD_TEXT_MAX_CODE or value is none of 0, 1, 2.
 * Allocates nothing.
 */
int kbd_text_key(struct kbd_text *kt, unsigned code, int value, struct kbd_text_key *dest);

/*
 * Forgets the keyboard as if it had just been plugged in: keys held are
 * released (Shift, AltGr ...), locks (Caps Lock) and latches cleared, a
 * pending compose sequence dropped. For a device unplugged mid-edit, whose
 * releases will never come. Allocates nothing.
 */
void kbd_text_reset(struct kbd_text *kt);

/* 1 while a compose sequence is pending (the status line may show it) */
int kbd_text_composing(const struct kbd_text *kt);

/* the locale whose compose table is in use */
const char *kbd_text_compose_locale(const struct kbd_text *kt);

/* "return", "backspace", ... "f12"; "none" for KBD_CTL_NONE */
const char *kbd_ctl_to_str(enum kbd_ctl c);

#endif
