/*
 * test_kbd_text.c - evdev keys to text through xkb-data's layouts and
 * libx11-data's compose table. The expected characters are the published
 * definitions, cited by file and line (xkb-data 2.35.1, libx11-data 1.8.4
 * of Debian 12): the symbol files under /usr/share/X11/xkb/symbols, the
 * keycode names of /usr/share/X11/xkb/keycodes/evdev (an evdev code plus 8),
 * and /usr/share/X11/locale/en_US.UTF-8/Compose, which compose.dir gives
 * to C.UTF-8 as to every UTF-8 locale. Where a key's place was in doubt it
 * was checked with xkbcommon's own `xkbcli how-to-type --layout de`.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <linux/input-event-codes.h>
#include <stdlib.h>
#include <string.h>
#include <xkbcommon/xkbcommon-keysyms.h>

#include "interact/kbd_text.h"

#include "alloc_count.h"

static struct kbd_text *
make(const char *layout)
{
	struct kbd_text_def d = kbd_text_default_def();
	d.layout = layout;
	char err[256];
	struct kbd_text *kt = kbd_text_create(&d, err, sizeof err);
	if (!kt)
		fail_msg("%s", err);
	return kt;
}

static void
press(struct kbd_text *kt, unsigned code, struct kbd_text_key *dest)
{
	assert_int_equal(kbd_text_key(kt, code, 1, dest), 1);
}

static void
release(struct kbd_text *kt, unsigned code)
{
	struct kbd_text_key k;
	assert_int_equal(kbd_text_key(kt, code, 0, &k), 0);
	assert_string_equal(k.text, "");
}

/* a tap: press then release, the press's translation in dest */
static void
tap(struct kbd_text *kt, unsigned code, struct kbd_text_key *dest)
{
	press(kt, code, dest);
	release(kt, code);
}

/* the text a tap of code gives */
static const char *
typed(struct kbd_text *kt, unsigned code)
{
	static struct kbd_text_key k;
	tap(kt, code, &k);
	return k.text;
}

static void
test_us_letters(void **unused)
{
	(void)unused;
	struct kbd_text *kt = make("us");
	struct kbd_text_key k;
	/* KEY_A = 30 is <AC01> (keycodes/evdev: <AC01> = 38); symbols/us:33 [ a, A ] */
	tap(kt, KEY_A, &k);
	assert_string_equal(k.text, "a");
	assert_int_equal(k.keysym, XKB_KEY_a);
	assert_int_equal(k.ctl, KBD_CTL_NONE);
	assert_int_equal(k.mods, 0);
	assert_int_equal(k.compose, KBD_COMPOSE_NONE);

	/* Shift picks level 2, "A"; Shift is used up choosing it, so not reported */
	press(kt, KEY_LEFTSHIFT, &k);
	assert_string_equal(k.text, "");
	tap(kt, KEY_A, &k);
	assert_string_equal(k.text, "A");
	assert_int_equal(k.mods & KBD_MOD_SHIFT, 0);
	release(kt, KEY_LEFTSHIFT);
	assert_string_equal(typed(kt, KEY_A), "a");
	kbd_text_free(kt);
}

static void
test_us_repeat_and_range(void **unused)
{
	(void)unused;
	struct kbd_text *kt = make("us");
	struct kbd_text_key k;
	press(kt, KEY_A, &k);
	assert_int_equal(k.repeat, 0);
	assert_int_equal(kbd_text_key(kt, KEY_A, 2, &k), 1);
	assert_string_equal(k.text, "a");
	assert_int_equal(k.repeat, 1);
	release(kt, KEY_A);

	assert_int_equal(kbd_text_key(kt, KBD_TEXT_MAX_CODE + 1, 1, &k), -1);
	assert_int_equal(kbd_text_key(kt, KEY_A, 3, &k), -1);
	assert_int_equal(kbd_text_key(kt, KEY_A, -1, &k), -1);
	/* a release never pressed (held before we started) changes nothing */
	release(kt, KEY_LEFTSHIFT);
	assert_string_equal(typed(kt, KEY_A), "a");
	kbd_text_free(kt);
}

static void
test_us_control_keys(void **unused)
{
	(void)unused;
	struct kbd_text *kt = make("us");
	struct kbd_text_key k;
	static const struct {
		unsigned code;
		enum kbd_ctl ctl;
	} keys[] = {
		{ KEY_ENTER, KBD_CTL_RETURN },     { KEY_KPENTER, KBD_CTL_RETURN },
		{ KEY_BACKSPACE, KBD_CTL_BACKSPACE }, { KEY_DELETE, KBD_CTL_DELETE },
		{ KEY_LEFT, KBD_CTL_LEFT },        { KEY_RIGHT, KBD_CTL_RIGHT },
		{ KEY_UP, KBD_CTL_UP },            { KEY_DOWN, KBD_CTL_DOWN },
		{ KEY_HOME, KBD_CTL_HOME },        { KEY_END, KBD_CTL_END },
		{ KEY_TAB, KBD_CTL_TAB },          { KEY_ESC, KBD_CTL_ESCAPE },
		{ KEY_F1, KBD_CTL_F1 },            { KEY_F5, KBD_CTL_F1 + 4 },
		{ KEY_F12, KBD_CTL_F12 },
	};
	for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++) {
		tap(kt, keys[i].code, &k);
		assert_int_equal(k.ctl, keys[i].ctl);
		/* Return's "\r", Tab's "\t", Escape's ESC are not typed */
		assert_string_equal(k.text, "");
	}
	assert_string_equal(kbd_ctl_to_str(KBD_CTL_F12), "f12");
	assert_string_equal(kbd_ctl_to_str(KBD_CTL_BACKSPACE), "backspace");

	/* Shift+Tab is ISO_Left_Tab, still Tab, with Shift used up choosing it */
	press(kt, KEY_LEFTSHIFT, &k);
	tap(kt, KEY_TAB, &k);
	assert_int_equal(k.ctl, KBD_CTL_TAB);
	release(kt, KEY_LEFTSHIFT);

	/* Ctrl+A: the letter and Ctrl for the edit line, no control character typed */
	press(kt, KEY_LEFTCTRL, &k);
	tap(kt, KEY_A, &k);
	assert_int_equal(k.keysym, XKB_KEY_a);
	assert_int_equal(k.mods, KBD_MOD_CTRL);
	assert_string_equal(k.text, "");
	tap(kt, KEY_LEFT, &k);
	assert_int_equal(k.ctl, KBD_CTL_LEFT);
	assert_int_equal(k.mods, KBD_MOD_CTRL);
	release(kt, KEY_LEFTCTRL);

	press(kt, KEY_LEFTALT, &k);
	tap(kt, KEY_B, &k);
	assert_int_equal(k.mods, KBD_MOD_ALT);
	assert_int_equal(k.keysym, XKB_KEY_b);
	release(kt, KEY_LEFTALT);
	assert_string_equal(typed(kt, KEY_B), "b");
	kbd_text_free(kt);
}

static void
test_de_letters(void **unused)
{
	(void)unused;
	struct kbd_text *kt = make("de");
	/* KEY_Y = 21 is <AD06> (= 29); symbols/de:17 [ z, Z, leftarrow, yen ] */
	assert_string_equal(typed(kt, KEY_Y), "z");
	/* KEY_Z = 44 is <AB01> (= 52); symbols/de:28 [ y, Y, guillemotright, U203A ] */
	assert_string_equal(typed(kt, KEY_Z), "y");
	/* KEY_LEFTBRACE = 26 is <AD11> (= 34); symbols/de:18 [ udiaeresis, Udiaeresis, ... ] */
	assert_string_equal(typed(kt, KEY_LEFTBRACE), "ü");
	kbd_text_free(kt);
}

static void
test_de_altgr(void **unused)
{
	(void)unused;
	struct kbd_text *kt = make("de");
	struct kbd_text_key k;
	/*
	 * KEY_RIGHTALT = 100 is <RALT> (= 108), ISO_Level3_Shift by symbols/de:37
	 * include "level3(ralt_switch)" (symbols/level3:10); KEY_Q = 16 is
	 * <AD01> (= 24), whose third level is "at": de includes latin(type4),
	 * which includes latin, symbols/latin:19 [ q, Q, at, Greek_OMEGA ]
	 */
	press(kt, KEY_RIGHTALT, &k);
	assert_string_equal(k.text, "");
	tap(kt, KEY_Q, &k);
	assert_string_equal(k.text, "@");
	/* AltGr is no Alt: the edit line must type the @ */
	assert_int_equal(k.mods & (KBD_MOD_ALT | KBD_MOD_CTRL), 0);
	release(kt, KEY_RIGHTALT);
	assert_string_equal(typed(kt, KEY_Q), "q");
	kbd_text_free(kt);
}

static void
test_de_dead_keys(void **unused)
{
	(void)unused;
	struct kbd_text *kt = make("de");
	struct kbd_text_key k;
	/*
	 * KEY_EQUAL = 13 is <AE12> (= 21); symbols/de:14 [ dead_acute, dead_grave,
	 * ... ] (`xkbcli how-to-type --layout de --keysym dead_acute`: keycode 21,
	 * level 1). Compose:448 <dead_acute> <e> : "é"
	 */
	tap(kt, KEY_EQUAL, &k);
	assert_int_equal(k.keysym, XKB_KEY_dead_acute);
	assert_int_equal(k.compose, KBD_COMPOSE_PENDING);
	assert_string_equal(k.text, "");
	assert_true(kbd_text_composing(kt));
	tap(kt, KEY_E, &k);
	assert_int_equal(k.compose, KBD_COMPOSE_DONE);
	assert_string_equal(k.text, "é");
	assert_int_equal(k.keysym, XKB_KEY_eacute);
	assert_false(kbd_text_composing(kt));
	assert_string_equal(typed(kt, KEY_E), "e");

	/* Shift inside a sequence only chooses the next symbol: Compose has <dead_acute> <E> */
	tap(kt, KEY_EQUAL, &k);
	press(kt, KEY_LEFTSHIFT, &k);
	assert_int_equal(k.compose, KBD_COMPOSE_PENDING);
	tap(kt, KEY_E, &k);
	release(kt, KEY_LEFTSHIFT);
	assert_string_equal(k.text, "É");

	/*
	 * a dead key then space gives the accent as a character: KEY_GRAVE = 41
	 * is <TLDE> (= 49), symbols/de:25 [ dead_circumflex, degree, ... ], and
	 * Compose:13 <dead_circumflex> <space> : "^". For dead_acute the table
	 * gives the apostrophe, Compose:8 <dead_acute> <space> : "'"
	 */
	tap(kt, KEY_GRAVE, &k);
	assert_int_equal(k.keysym, XKB_KEY_dead_circumflex);
	tap(kt, KEY_SPACE, &k);
	assert_string_equal(k.text, "^");
	tap(kt, KEY_EQUAL, &k);
	tap(kt, KEY_SPACE, &k);
	assert_string_equal(k.text, "'");

	/* Compose has no <dead_acute> <q>: the sequence is cancelled and nothing is typed */
	tap(kt, KEY_EQUAL, &k);
	tap(kt, KEY_Q, &k);
	assert_int_equal(k.compose, KBD_COMPOSE_CANCELLED);
	assert_string_equal(k.text, "");
	assert_string_equal(typed(kt, KEY_Q), "q");

	/* a control key ends a pending sequence and still acts */
	tap(kt, KEY_EQUAL, &k);
	tap(kt, KEY_BACKSPACE, &k);
	assert_int_equal(k.ctl, KBD_CTL_BACKSPACE);
	assert_false(kbd_text_composing(kt));
	assert_string_equal(typed(kt, KEY_E), "e");
	kbd_text_free(kt);
}

static void
test_fr_letters(void **unused)
{
	(void)unused;
	struct kbd_text *kt = make("fr");
	/* KEY_Q = 16 is <AD01>, symbols/fr:21 [ a, A, ae, AE ]; KEY_A <AC01>, fr:27 [ q, Q ... ] */
	assert_string_equal(typed(kt, KEY_Q), "a");
	assert_string_equal(typed(kt, KEY_A), "q");
	kbd_text_free(kt);
}

static void
test_unknown_layout(void **unused)
{
	(void)unused;
	struct kbd_text_def d = kbd_text_default_def();
	d.layout = "xx-no-such-layout";
	char err[512] = "";
	assert_null(kbd_text_create(&d, err, sizeof err));
	assert_non_null(strstr(err, "\"xx-no-such-layout\""));

	d = kbd_text_default_def();
	d.layout = "";
	err[0] = '\0';
	assert_null(kbd_text_create(&d, err, sizeof err));
	assert_non_null(strstr(err, "no keyboard layout"));
}

static void
test_compose_locale(void **unused)
{
	(void)unused;
	struct kbd_text_def d = kbd_text_default_def();
	char err[256];
	struct kbd_text *kt = kbd_text_create(&d, err, sizeof err);
	assert_non_null(kt);
	/* compose.dir gives C.UTF-8 en_US.UTF-8's table */
	assert_string_equal(kbd_text_compose_locale(kt), "C.UTF-8");
	kbd_text_free(kt);

	/* a locale libx11-data does not know falls back to en_US.UTF-8 */
	d.locale = "xx_XX.UTF-8";
	kt = kbd_text_create(&d, err, sizeof err);
	assert_non_null(kt);
	assert_string_equal(kbd_text_compose_locale(kt), "en_US.UTF-8");
	kbd_text_free(kt);
}

static void
test_reset(void **unused)
{
	(void)unused;
	struct kbd_text *kt = make("de");
	struct kbd_text_key k;
	/* unplugged mid-sequence: the pending dead_acute is gone */
	tap(kt, KEY_EQUAL, &k);
	assert_true(kbd_text_composing(kt));
	kbd_text_reset(kt);
	assert_false(kbd_text_composing(kt));
	assert_string_equal(typed(kt, KEY_E), "e");

	/* unplugged with Shift and AltGr down: their releases never come */
	press(kt, KEY_LEFTSHIFT, &k);
	press(kt, KEY_RIGHTALT, &k);
	kbd_text_reset(kt);
	assert_string_equal(typed(kt, KEY_Q), "q");
	tap(kt, KEY_Q, &k);
	assert_int_equal(k.mods, 0);

	/* Caps Lock goes too, as on a keyboard just plugged in */
	tap(kt, KEY_CAPSLOCK, &k);
	assert_string_equal(typed(kt, KEY_A), "A");
	kbd_text_reset(kt);
	assert_string_equal(typed(kt, KEY_A), "a");

	/* and Shift pressed again afterwards works as before */
	press(kt, KEY_LEFTSHIFT, &k);
	assert_string_equal(typed(kt, KEY_A), "A");
	release(kt, KEY_LEFTSHIFT);
	assert_string_equal(typed(kt, KEY_A), "a");
	kbd_text_free(kt);
}

static void
test_feeding_allocates_nothing(void **unused)
{
	(void)unused;
#if COUNT_ALLOCS
	struct kbd_text *kt = make("de");
	struct kbd_text_key k;
	static const unsigned codes[] = { KEY_A, KEY_LEFTSHIFT, KEY_EQUAL, KEY_E, KEY_RIGHTALT,
					  KEY_Q, KEY_GRAVE, KEY_SPACE, KEY_ENTER, KEY_LEFTCTRL };
	long before = allocs;
	for (int round = 0; round < 50; round++)
		for (size_t i = 0; i < sizeof codes / sizeof codes[0]; i++) {
			kbd_text_key(kt, codes[(i + round) % 10], 1, &k);
			kbd_text_key(kt, codes[(i + round) % 10], 2, &k);
			if (i % 3)
				kbd_text_key(kt, codes[(i + round) % 10], 0, &k);
		}
	/* every modifier held at once: more held keys than any test above */
	static const unsigned mods[] = { KEY_LEFTSHIFT, KEY_RIGHTSHIFT, KEY_LEFTCTRL, KEY_RIGHTCTRL,
					 KEY_LEFTALT,   KEY_RIGHTALT,   KEY_LEFTMETA, KEY_RIGHTMETA,
					 KEY_CAPSLOCK,  KEY_NUMLOCK,    KEY_COMPOSE };
	for (size_t i = 0; i < sizeof mods / sizeof mods[0]; i++)
		kbd_text_key(kt, mods[i], 1, &k);
	kbd_text_key(kt, KEY_A, 1, &k);
	kbd_text_reset(kt);
	assert_int_equal(allocs - before, 0);
	kbd_text_free(kt);
#else
	skip(); /* ASan owns malloc */
#endif
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_us_letters),
		cmocka_unit_test(test_us_repeat_and_range),
		cmocka_unit_test(test_us_control_keys),
		cmocka_unit_test(test_de_letters),
		cmocka_unit_test(test_de_altgr),
		cmocka_unit_test(test_de_dead_keys),
		cmocka_unit_test(test_fr_letters),
		cmocka_unit_test(test_unknown_layout),
		cmocka_unit_test(test_compose_locale),
		cmocka_unit_test(test_reset),
		cmocka_unit_test(test_feeding_allocates_nothing),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
