/*
 * test_kiosk.c - the kiosk's keyboard: keys to the edit line when no mode
 * takes them and Enter hands over the line; in a mode a digit starts a
 * value (Enter applies it, ESC drops it and not the mode) and the mode's
 * own keys pass; the change-view key, undo and redo, Page Down and Page
 * Up; keys that belong to
 * change view still move the modifiers; a keyboard unplugged mid-edit
 * loses the typed line and nothing else; the configured layout's names.
 * Expected characters are the US and German layouts' (xkb-data
 * symbols/us and symbols/de), as in test_kbd_text.c.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <linux/input-event-codes.h>
#include <string.h>

#include "interact/kiosk.h"

static struct kiosk_action
key(struct kiosk *k, unsigned code, int value, enum kiosk_keys keys)
{
	struct input_event_rec e = { .kind = INPUT_KEY, .code = (uint16_t)code, .value = value };
	return kiosk_input(k, &e, keys);
}

/* a press and its release; the press's action */
static struct kiosk_action
tap(struct kiosk *k, unsigned code, enum kiosk_keys keys)
{
	struct kiosk_action a = key(k, code, 1, keys);
	key(k, code, 0, keys);
	return a;
}

static struct kiosk_action
chord(struct kiosk *k, unsigned mod, unsigned code, enum kiosk_keys keys)
{
	key(k, mod, 1, keys);
	struct kiosk_action a = tap(k, code, keys);
	key(k, mod, 0, keys);
	return a;
}

static struct kiosk *
make(const char *layout)
{
	struct kiosk_def d = kiosk_default_def();
	char names[64], err[256];
	assert_int_equal(kiosk_keymap_names(layout, &d.keymap, names, sizeof names), 0);
	struct kiosk *k = kiosk_create(&d, err, sizeof err);
	assert_non_null(k);
	return k;
}

static void
test_the_edit_line_runs_what_is_typed(void **unused)
{
	(void)unused;
	struct kiosk *k = make("us");
	static const unsigned word[] = { KEY_L, KEY_I, KEY_S, KEY_T, KEY_SPACE, KEY_V, KEY_I,
					 KEY_E, KEY_W, KEY_S };
	for (size_t i = 0; i < sizeof word / sizeof *word; i++)
		assert_int_equal(tap(k, word[i], KIOSK_KEYS_LINE).kind, KIOSK_TAKEN);
	/* V at the edit line is a letter, not change view */
	assert_string_equal(editline_text(kiosk_line(k)), "list views");
	struct kiosk_action a = tap(k, KEY_ENTER, KIOSK_KEYS_LINE);
	assert_int_equal(a.kind, KIOSK_RUN);
	assert_string_equal(a.line, "list views");
	assert_string_equal(editline_text(kiosk_line(k)), "");
	/* Enter on nothing runs nothing; ESC on nothing is nobody's */
	assert_int_equal(tap(k, KEY_ENTER, KIOSK_KEYS_LINE).kind, KIOSK_TAKEN);
	assert_int_equal(tap(k, KEY_ESC, KIOSK_KEYS_LINE).kind, KIOSK_NONE);
	/* ESC on a line clears it */
	tap(k, KEY_X, KIOSK_KEYS_LINE);
	assert_int_equal(tap(k, KEY_ESC, KIOSK_KEYS_LINE).kind, KIOSK_TAKEN);
	assert_string_equal(editline_text(kiosk_line(k)), "");
	kiosk_free(k);
}

static void
test_the_keys_beside_the_line(void **unused)
{
	(void)unused;
	struct kiosk *k = make("us");
	assert_int_equal(tap(k, KEY_F2, KIOSK_KEYS_LINE).kind, KIOSK_CHANGE_VIEW);
	kiosk_set_view_key(k, KEY_F3);
	assert_int_equal(tap(k, KEY_F2, KIOSK_KEYS_LINE).kind, KIOSK_TAKEN);
	assert_int_equal(tap(k, KEY_F3, KIOSK_KEYS_LINE).kind, KIOSK_CHANGE_VIEW);
	assert_int_equal(chord(k, KEY_LEFTCTRL, KEY_Z, KIOSK_KEYS_LINE).kind, KIOSK_UNDO);
	assert_int_equal(chord(k, KEY_RIGHTCTRL, KEY_Y, KIOSK_KEYS_LINE).kind, KIOSK_REDO);
	key(k, KEY_LEFTCTRL, 1, KIOSK_KEYS_LINE);
	assert_int_equal(chord(k, KEY_LEFTSHIFT, KEY_Z, KIOSK_KEYS_LINE).kind, KIOSK_REDO);
	key(k, KEY_LEFTCTRL, 0, KIOSK_KEYS_LINE);
	/* in a mode too */
	assert_int_equal(chord(k, KEY_LEFTCTRL, KEY_Z, KIOSK_KEYS_MODE).kind, KIOSK_UNDO);
	assert_string_equal(editline_text(kiosk_line(k)), "");
	/* Page Down and Page Up, the next and the one before, leave what is typed alone */
	tap(k, KEY_X, KIOSK_KEYS_LINE);
	assert_int_equal(tap(k, KEY_PAGEDOWN, KIOSK_KEYS_LINE).kind, KIOSK_NEXT);
	assert_int_equal(tap(k, KEY_PAGEUP, KIOSK_KEYS_LINE).kind, KIOSK_PREVIOUS);
	assert_string_equal(editline_text(kiosk_line(k)), "x");
	assert_int_equal(chord(k, KEY_LEFTCTRL, KEY_PAGEDOWN, KIOSK_KEYS_LINE).kind, KIOSK_TAKEN);
	assert_int_equal(tap(k, KEY_PAGEDOWN, KIOSK_KEYS_MODE).kind, KIOSK_NONE); /* the mode's */
	kiosk_free(k);
}

static void
test_a_value_typed_in_a_mode(void **unused)
{
	(void)unused;
	struct kiosk *k = make("us");
	/* the mode's keys pass: V, C, S, ESC, the modifiers, a letter */
	static const unsigned mode_keys[] = { KEY_V, KEY_C, KEY_S, KEY_ESC, KEY_LEFTSHIFT, KEY_Q };
	for (size_t i = 0; i < sizeof mode_keys / sizeof *mode_keys; i++)
		assert_int_equal(tap(k, mode_keys[i], KIOSK_KEYS_MODE).kind, KIOSK_NONE);
	/* a minus starts a value, letters then are its unit */
	static const unsigned value[] = { KEY_MINUS, KEY_3, KEY_0, KEY_D, KEY_E, KEY_G };
	for (size_t i = 0; i < sizeof value / sizeof *value; i++)
		assert_int_equal(tap(k, value[i], KIOSK_KEYS_MODE).kind, KIOSK_TAKEN);
	assert_true(kiosk_typing_value(k));
	assert_string_equal(editline_text(kiosk_line(k)), "-30deg");
	struct kiosk_action a = tap(k, KEY_ENTER, KIOSK_KEYS_MODE);
	assert_int_equal(a.kind, KIOSK_VALUE);
	assert_string_equal(a.line, "-30deg");
	assert_false(kiosk_typing_value(k));
	/* ESC drops a value, not the mode (it is taken); the next ESC is the mode's */
	tap(k, KEY_1, KIOSK_KEYS_MODE);
	assert_int_equal(tap(k, KEY_ESC, KIOSK_KEYS_MODE).kind, KIOSK_TAKEN);
	assert_false(kiosk_typing_value(k));
	assert_int_equal(tap(k, KEY_ESC, KIOSK_KEYS_MODE).kind, KIOSK_NONE);
	/* erased back to nothing, the keys are the mode's again */
	tap(k, KEY_DOT, KIOSK_KEYS_MODE);
	tap(k, KEY_BACKSPACE, KIOSK_KEYS_MODE);
	assert_false(kiosk_typing_value(k));
	assert_int_equal(tap(k, KEY_V, KIOSK_KEYS_MODE).kind, KIOSK_NONE);
	/* the mode ends under a half-typed value: it goes */
	tap(k, KEY_2, KIOSK_KEYS_MODE);
	kiosk_mode_ended(k);
	assert_false(kiosk_typing_value(k));
	assert_string_equal(editline_text(kiosk_line(k)), "");
	kiosk_free(k);
}

static void
test_keys_of_another_still_move_the_modifiers(void **unused)
{
	(void)unused;
	struct kiosk *k = make("us");
	/* Shift goes down while change view has the keys, then the line has them */
	assert_int_equal(key(k, KEY_LEFTSHIFT, 1, KIOSK_KEYS_OTHER).kind, KIOSK_NONE);
	assert_int_equal(tap(k, KEY_C, KIOSK_KEYS_OTHER).kind, KIOSK_NONE);
	assert_string_equal(editline_text(kiosk_line(k)), "");
	tap(k, KEY_A, KIOSK_KEYS_LINE);
	key(k, KEY_LEFTSHIFT, 0, KIOSK_KEYS_LINE);
	tap(k, KEY_A, KIOSK_KEYS_LINE);
	assert_string_equal(editline_text(kiosk_line(k)), "Aa");
	kiosk_free(k);
}

static void
test_an_unplugged_keyboard_loses_the_typed_line_only(void **unused)
{
	(void)unused;
	struct kiosk *k = make("us");
	tap(k, KEY_L, KIOSK_KEYS_LINE);
	tap(k, KEY_S, KIOSK_KEYS_LINE);
	tap(k, KEY_ENTER, KIOSK_KEYS_LINE); /* "ls" in the history */
	key(k, KEY_LEFTSHIFT, 1, KIOSK_KEYS_LINE); /* held when it goes */
	tap(k, KEY_X, KIOSK_KEYS_LINE);
	struct input_event_rec gone = { .kind = INPUT_REMOVED, .code = INPUT_CLASS_KEYBOARD };
	assert_int_equal(kiosk_input(k, &gone, KIOSK_KEYS_LINE).kind, KIOSK_NONE);
	assert_string_equal(editline_text(kiosk_line(k)), "");
	/* another keyboard: no Shift stuck, the history kept */
	tap(k, KEY_A, KIOSK_KEYS_LINE);
	assert_string_equal(editline_text(kiosk_line(k)), "a");
	tap(k, KEY_ESC, KIOSK_KEYS_LINE);
	tap(k, KEY_UP, KIOSK_KEYS_LINE);
	assert_string_equal(editline_text(kiosk_line(k)), "ls");
	/* a mouse going is nothing to the line */
	struct input_event_rec mouse = { .kind = INPUT_REMOVED, .code = INPUT_CLASS_MOUSE };
	kiosk_input(k, &mouse, KIOSK_KEYS_LINE);
	assert_string_equal(editline_text(kiosk_line(k)), "ls");
	kiosk_free(k);
}

static void
test_the_layout_is_the_configured_one(void **unused)
{
	(void)unused;
	struct kiosk *k = make("de");
	/* symbols/de: Z and Y swapped, AD11 is udiaeresis */
	tap(k, KEY_Y, KIOSK_KEYS_LINE);
	tap(k, KEY_LEFTBRACE, KIOSK_KEYS_LINE);
	assert_string_equal(editline_text(kiosk_line(k)), "z\xc3\xbc");
	struct kbd_text_def d = kbd_text_default_def();
	char names[64], err[256];
	assert_int_equal(kiosk_keymap_names("us", &d, names, sizeof names), 0);
	assert_int_equal(kiosk_set_keymap(k, &d, err, sizeof err), 0);
	tap(k, KEY_Y, KIOSK_KEYS_LINE);
	assert_string_equal(editline_text(kiosk_line(k)), "z\xc3\xbcy");
	/* an unknown layout: refused, the old one kept */
	assert_int_equal(kiosk_keymap_names("klingon", &d, names, sizeof names), 0);
	assert_int_equal(kiosk_set_keymap(k, &d, err, sizeof err), -1);
	tap(k, KEY_Z, KIOSK_KEYS_LINE);
	assert_string_equal(editline_text(kiosk_line(k)), "z\xc3\xbcyz");
	kiosk_free(k);
}

static void
test_keymap_names(void **unused)
{
	(void)unused;
	struct kbd_text_def d = kbd_text_default_def();
	char buf[32];
	assert_int_equal(kiosk_keymap_names("de:nodeadkeys", &d, buf, sizeof buf), 0);
	assert_string_equal(d.layout, "de");
	assert_string_equal(d.variant, "nodeadkeys");
	assert_int_equal(kiosk_keymap_names("us,de", &d, buf, sizeof buf), 0);
	assert_string_equal(d.layout, "us,de");
	assert_string_equal(d.variant, "");
	static const char *const bad[] = { "", ":x", "de:", "de:a:b", "de;rm", "de x",
					   "a-very-long-layout-name-that-does-not-fit" };
	for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
		assert_int_equal(kiosk_keymap_names(bad[i], &d, buf, sizeof buf), -1);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_the_edit_line_runs_what_is_typed),
		cmocka_unit_test(test_the_keys_beside_the_line),
		cmocka_unit_test(test_a_value_typed_in_a_mode),
		cmocka_unit_test(test_keys_of_another_still_move_the_modifiers),
		cmocka_unit_test(test_an_unplugged_keyboard_loses_the_typed_line_only),
		cmocka_unit_test(test_the_layout_is_the_configured_one),
		cmocka_unit_test(test_keymap_names),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
