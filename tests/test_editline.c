/*
 * test_editline.c - the edit line key by key: insertion and motion by
 * characters of one to four bytes, words, BackSpace and Delete, Ctrl+W and
 * Ctrl+U, the history ring and the draft it keeps, completion with one and
 * several candidates, the length limit, the scrolled window; keys typed on a
 * German keyboard through kbd_text; and 100 000 random keys after each of
 * which the line is well-formed UTF-8 with the cursor on a character
 * boundary, checked by a decoder of the test's own.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <linux/input-event-codes.h>
#include <stdio.h>
#include <string.h>

#include "interact/editline.h"
#include "interact/kbd_text.h"

#include "alloc_count.h"
#include "test_random.h"

#define EMOJI "\xf0\x9f\x98\x80" /* U+1F600, four bytes */

static struct editline el; /* 140 kB: not on the stack */

static void
fresh(void)
{
	struct editline_def d = editline_default_def();
	editline_init(&el, &d);
}

static enum editline_result
ctl(enum kbd_ctl c, unsigned mods)
{
	struct kbd_text_key k = { .ctl = c, .mods = mods };
	return editline_key(&el, &k);
}

static enum editline_result
ctrl(char letter)
{
	struct kbd_text_key k = { .keysym = (uint32_t)letter, .mods = KBD_MOD_CTRL };
	return editline_key(&el, &k);
}

/* one key that types s */
static enum editline_result
key_text(const char *s)
{
	struct kbd_text_key k = { .keysym = (unsigned char)s[0] };
	snprintf(k.text, sizeof k.text, "%s", s);
	return editline_key(&el, &k);
}

/* types s a character at a time */
static void
type(const char *s)
{
	while (*s) {
		char ch[5] = { *s++ };
		for (int i = 1; (*s & 0xc0) == 0x80; i++)
			ch[i] = *s++;
		assert_int_equal(key_text(ch), EDITLINE_CHANGED);
	}
}

static void
times(enum kbd_ctl c, unsigned mods, int n)
{
	while (n-- > 0)
		ctl(c, mods);
}

static void
test_insert_and_move(void **unused)
{
	(void)unused;
	fresh();
	assert_string_equal(editline_text(&el), "");
	type("hello");
	assert_int_equal(el.cursor, 5);
	assert_int_equal(ctl(KBD_CTL_RIGHT, 0), EDITLINE_NONE);
	times(KBD_CTL_LEFT, 0, 2);
	type("X");
	assert_string_equal(editline_text(&el), "helXlo");
	assert_int_equal(ctl(KBD_CTL_HOME, 0), EDITLINE_CHANGED);
	assert_int_equal(el.cursor, 0);
	assert_int_equal(ctl(KBD_CTL_LEFT, 0), EDITLINE_NONE);
	assert_int_equal(ctl(KBD_CTL_HOME, 0), EDITLINE_NONE);
	type(">");
	assert_int_equal(ctl(KBD_CTL_END, 0), EDITLINE_CHANGED);
	assert_int_equal(el.cursor, 7);
	assert_int_equal(ctrl('a'), EDITLINE_CHANGED);
	assert_int_equal(el.cursor, 0);
	assert_int_equal(ctrl('e'), EDITLINE_CHANGED);
	assert_int_equal(el.cursor, 7);
	assert_string_equal(editline_text(&el), ">helXlo");

	/* with Ctrl or Alt held a text key types nothing; F keys are the caller's */
	struct kbd_text_key k = { .keysym = '1', .text = "1", .mods = KBD_MOD_ALT };
	assert_int_equal(editline_key(&el, &k), EDITLINE_NONE);
	k.mods = KBD_MOD_CTRL;
	assert_int_equal(editline_key(&el, &k), EDITLINE_NONE);
	assert_int_equal(ctl(KBD_CTL_F1 + 2, 0), EDITLINE_NONE);
	/* a modifier's press, or a dead key's, types nothing */
	assert_int_equal(key_text(""), EDITLINE_NONE);
	assert_string_equal(editline_text(&el), ">helXlo");
}

static void
test_utf8(void **unused)
{
	(void)unused;
	fresh();
	type("a\xc3\xbc\xc3\xa9" EMOJI "z"); /* a ü é 😀 z */
	assert_int_equal(el.len, 1 + 2 + 2 + 4 + 1);
	/* Left steps over whole characters: 10 -> 9 -> 5 -> 3 -> 1 -> 0 */
	static const size_t stops[] = { 9, 5, 3, 1, 0 };
	for (int i = 0; i < 5; i++) {
		assert_int_equal(ctl(KBD_CTL_LEFT, 0), EDITLINE_CHANGED);
		assert_int_equal(el.cursor, stops[i]);
	}
	for (int i = 3; i >= 0; i--) {
		assert_int_equal(ctl(KBD_CTL_RIGHT, 0), EDITLINE_CHANGED);
		assert_int_equal(el.cursor, stops[i]);
	}
	/* the cursor after the emoji: BackSpace takes its four bytes */
	assert_int_equal(ctl(KBD_CTL_BACKSPACE, 0), EDITLINE_CHANGED);
	assert_string_equal(editline_text(&el), "a\xc3\xbc\xc3\xa9z");
	assert_int_equal(el.cursor, 5);
	/* Delete after ü takes é's two */
	ctl(KBD_CTL_LEFT, 0);
	assert_int_equal(ctl(KBD_CTL_DELETE, 0), EDITLINE_CHANGED);
	assert_string_equal(editline_text(&el), "a\xc3\xbcz");
	assert_int_equal(el.cursor, 3);
	/* an emoji inserted between: still whole */
	type(EMOJI);
	assert_string_equal(editline_text(&el), "a\xc3\xbc" EMOJI "z");
	ctl(KBD_CTL_END, 0);
	assert_int_equal(ctl(KBD_CTL_DELETE, 0), EDITLINE_NONE);
	ctl(KBD_CTL_HOME, 0);
	assert_int_equal(ctl(KBD_CTL_BACKSPACE, 0), EDITLINE_NONE);
}

static void
test_invalid_text(void **unused)
{
	(void)unused;
	fresh();
	type("ok");
	static const char *const bad[] = {
		"\xff",             /* never in UTF-8 */
		"\xc3",             /* a lead byte alone */
		"\xa9",             /* a continuation alone */
		"\xc0\xaf",         /* overlong '/' */
		"\xe0\x80\xaf",     /* overlong, three bytes */
		"\xed\xa0\x80",     /* a surrogate, U+D800 */
		"\xf4\x90\x80\x80", /* above U+10FFFF */
		"a\tb",             /* a control character */
		"\x7f",             /* DEL */
		"\xc2\x85",         /* C1 control NEL */
	};
	for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
		assert_int_equal(editline_insert(&el, bad[i]), EDITLINE_INVALID);
	assert_string_equal(editline_text(&el), "ok");
	assert_int_equal(editline_insert(&el, ""), EDITLINE_NONE);
	assert_int_equal(editline_insert(&el, "\xef\xbf\xbd\xf4\x8f\xbf\xbf"), EDITLINE_CHANGED);
}

static void
test_words(void **unused)
{
	(void)unused;
	fresh();
	type("set  view main");
	/* Ctrl+Left: to the start of this word, then of each one before */
	assert_int_equal(ctl(KBD_CTL_LEFT, KBD_MOD_CTRL), EDITLINE_CHANGED);
	assert_int_equal(el.cursor, 10);
	ctl(KBD_CTL_LEFT, KBD_MOD_CTRL);
	assert_int_equal(el.cursor, 5);
	ctl(KBD_CTL_LEFT, KBD_MOD_CTRL);
	assert_int_equal(el.cursor, 0);
	assert_int_equal(ctl(KBD_CTL_LEFT, KBD_MOD_CTRL), EDITLINE_NONE);
	/* Ctrl+Right: to the end of this word, then of each one after */
	ctl(KBD_CTL_RIGHT, KBD_MOD_CTRL);
	assert_int_equal(el.cursor, 3);
	ctl(KBD_CTL_RIGHT, KBD_MOD_CTRL);
	assert_int_equal(el.cursor, 9);
	ctl(KBD_CTL_RIGHT, KBD_MOD_CTRL);
	assert_int_equal(el.cursor, 14);
	assert_int_equal(ctl(KBD_CTL_RIGHT, KBD_MOD_CTRL), EDITLINE_NONE);

	/* Ctrl+W: the word before the cursor, and the spaces after it */
	assert_int_equal(ctrl('w'), EDITLINE_CHANGED);
	assert_string_equal(editline_text(&el), "set  view ");
	assert_int_equal(ctrl('w'), EDITLINE_CHANGED);
	assert_string_equal(editline_text(&el), "set  ");
	/* from the middle of a word: its part before the cursor */
	type("vi\xc3\xbc" "ew");
	times(KBD_CTL_LEFT, 0, 2);
	ctrl('W');
	assert_string_equal(editline_text(&el), "set  ew");
	assert_int_equal(el.cursor, 5);
	/* Ctrl+U: everything before the cursor */
	assert_int_equal(ctrl('u'), EDITLINE_CHANGED);
	assert_string_equal(editline_text(&el), "ew");
	assert_int_equal(el.cursor, 0);
	assert_int_equal(ctrl('u'), EDITLINE_NONE);
	assert_int_equal(ctrl('w'), EDITLINE_NONE);
	assert_int_equal(ctrl('q'), EDITLINE_NONE);
}

static void
enter_line(const char *s)
{
	ctrl('u');
	ctrl('e');
	ctrl('u');
	editline_insert(&el, s);
	assert_int_equal(ctl(KBD_CTL_RETURN, 0), EDITLINE_ENTERED);
	assert_string_equal(editline_entered(&el), s);
	assert_string_equal(editline_text(&el), "");
}

static void
test_return_and_escape(void **unused)
{
	(void)unused;
	fresh();
	assert_string_equal(editline_entered(&el), "");
	type("settle");
	ctl(KBD_CTL_HOME, 0);
	/* Return enters the whole line wherever the cursor is */
	assert_int_equal(ctl(KBD_CTL_RETURN, 0), EDITLINE_ENTERED);
	assert_string_equal(editline_entered(&el), "settle");
	assert_string_equal(editline_text(&el), "");
	assert_int_equal(el.cursor, 0);
	type("oops");
	assert_int_equal(ctl(KBD_CTL_ESCAPE, 0), EDITLINE_CLEARED);
	assert_string_equal(editline_text(&el), "");
	assert_int_equal(el.cursor, 0);
	assert_int_equal(ctl(KBD_CTL_ESCAPE, 0), EDITLINE_CLEARED);
	/* an empty line is entered but not kept */
	assert_int_equal(ctl(KBD_CTL_RETURN, 0), EDITLINE_ENTERED);
	assert_string_equal(editline_entered(&el), "");
	assert_int_equal(el.hist_count, 1);
}

static void
test_history(void **unused)
{
	(void)unused;
	fresh();
	assert_int_equal(ctl(KBD_CTL_UP, 0), EDITLINE_NONE);
	enter_line("one");
	enter_line("two");
	enter_line("two"); /* the same as the newest: not kept twice */
	enter_line("three");
	assert_int_equal(el.hist_count, 3);

	type("dra");
	ctl(KBD_CTL_LEFT, 0);
	assert_int_equal(ctl(KBD_CTL_DOWN, 0), EDITLINE_NONE);
	assert_int_equal(ctl(KBD_CTL_UP, 0), EDITLINE_CHANGED);
	assert_string_equal(editline_text(&el), "three");
	assert_int_equal(el.cursor, 5);
	ctl(KBD_CTL_UP, 0);
	assert_string_equal(editline_text(&el), "two");
	ctl(KBD_CTL_UP, 0);
	assert_string_equal(editline_text(&el), "one");
	assert_int_equal(ctl(KBD_CTL_UP, 0), EDITLINE_NONE);
	assert_string_equal(editline_text(&el), "one");
	ctl(KBD_CTL_DOWN, 0);
	assert_string_equal(editline_text(&el), "two");
	ctl(KBD_CTL_DOWN, 0);
	assert_string_equal(editline_text(&el), "three");
	/* out of the history: the draft comes back */
	assert_int_equal(ctl(KBD_CTL_DOWN, 0), EDITLINE_CHANGED);
	assert_string_equal(editline_text(&el), "dra");
	assert_int_equal(ctl(KBD_CTL_DOWN, 0), EDITLINE_NONE);

	/* a recalled line edited and entered becomes the newest; the draft is gone */
	ctl(KBD_CTL_UP, 0);
	ctl(KBD_CTL_UP, 0);
	type("s");
	assert_int_equal(ctl(KBD_CTL_RETURN, 0), EDITLINE_ENTERED);
	assert_string_equal(editline_entered(&el), "twos");
	ctl(KBD_CTL_UP, 0);
	assert_string_equal(editline_text(&el), "twos");
	ctl(KBD_CTL_DOWN, 0);
	assert_string_equal(editline_text(&el), "");
	/* Escape in the history goes back to an empty line below the newest */
	ctl(KBD_CTL_UP, 0);
	ctl(KBD_CTL_ESCAPE, 0);
	assert_int_equal(ctl(KBD_CTL_DOWN, 0), EDITLINE_NONE);
	ctl(KBD_CTL_UP, 0);
	assert_string_equal(editline_text(&el), "twos");
}

static void
test_history_ring(void **unused)
{
	(void)unused;
	struct editline_def d = editline_default_def();
	d.history = 3;
	editline_init(&el, &d);
	const char *lines[] = { "l1", "l2", "l3", "l4", "l5" };
	for (int i = 0; i < 5; i++)
		enter_line(lines[i]);
	assert_int_equal(el.hist_count, 3);
	for (int i = 4; i >= 2; i--) {
		assert_int_equal(ctl(KBD_CTL_UP, 0), EDITLINE_CHANGED);
		assert_string_equal(editline_text(&el), lines[i]);
	}
	assert_int_equal(ctl(KBD_CTL_UP, 0), EDITLINE_NONE);

	/* the history size is kept to what the struct holds */
	d.history = 1000;
	editline_init(&el, &d);
	assert_int_equal(el.def.history, EDITLINE_HISTORY_MAX);
	d.history = 0;
	editline_init(&el, &d);
	assert_int_equal(el.def.history, 1);
	enter_line("a");
	enter_line("b");
	ctl(KBD_CTL_UP, 0);
	assert_string_equal(editline_text(&el), "b");
	assert_int_equal(ctl(KBD_CTL_UP, 0), EDITLINE_NONE);
}

/* ---- completion: a small command language ---------------------------------- */

static struct {
	int calls;
	int nwords;
	char words[8][32];
	char prefix[64];
} seen;

static int
list_from(const char *const *pool, int n, const char **dest, int max)
{
	int k = 0;
	for (int i = 0; i < n && k < max; i++)
		dest[k++] = pool[i];
	return k;
}

/* deliberately lists words that do not match: editline filters by the prefix */
static int
complete_commands(void *user, const char *const *words, int nwords, const char *prefix,
		  const char **dest, int max)
{
	(void)user;
	seen.calls++;
	seen.nwords = nwords;
	for (int i = 0; i < nwords && i < 8; i++)
		snprintf(seen.words[i], sizeof seen.words[i], "%s", words[i]);
	snprintf(seen.prefix, sizeof seen.prefix, "%s", prefix);
	static const char *const commands[] = { "add", "attach", "render", "set", "settle",
						"\xc3\xbc" "ber", "\xc3\xbc" "bel",
						"\xc3\xa9t\xc3\xa9", "\xc3\xa8re", "\xc3" };
	static const char *const render_args[] = { "view", "frame" };
	static const char *const add_args[] = { "constraint", "effector=", "goal=" };
	static const char *const say_args[] = { "\xc3\xa9t\xc3\xa9", "\xc3\xa8re" };
	if (nwords == 0)
		return list_from(commands, 10, dest, max);
	if (!strcmp(words[0], "render"))
		return list_from(render_args, 2, dest, max);
	if (!strcmp(words[0], "add"))
		return list_from(add_args, 3, dest, max);
	if (!strcmp(words[0], "say"))
		return list_from(say_args, 2, dest, max);
	return 0;
}

static void
fresh_completing(void)
{
	struct editline_def d = editline_default_def();
	d.complete = complete_commands;
	editline_init(&el, &d);
	memset(&seen, 0, sizeof seen);
}

static void
test_complete_one(void **unused)
{
	(void)unused;
	fresh_completing();
	type("ren");
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_CHANGED);
	assert_string_equal(editline_text(&el), "render ");
	assert_int_equal(seen.nwords, 0);
	assert_string_equal(seen.prefix, "ren");
	/* the next word: the completer hears the words before it */
	type("v");
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_CHANGED);
	assert_string_equal(editline_text(&el), "render view ");
	assert_int_equal(seen.nwords, 1);
	assert_string_equal(seen.words[0], "render");
	assert_string_equal(seen.prefix, "v");

	/* a key=value word gets no space: its value follows */
	ctrl('u');
	type("add  eff");
	ctl(KBD_CTL_TAB, 0);
	assert_string_equal(editline_text(&el), "add  effector=");
	assert_int_equal(seen.nwords, 1);
	assert_string_equal(seen.words[0], "add");

	/* completing in the middle of a line: the cursor's word up to the cursor */
	ctrl('u');
	type("at x");
	times(KBD_CTL_LEFT, 0, 2);
	ctl(KBD_CTL_TAB, 0);
	assert_string_equal(seen.prefix, "at");
	assert_string_equal(editline_text(&el), "attach x");
	assert_int_equal(el.cursor, 6); /* a space follows already: none added */

	/* nothing matches */
	ctrl('u');
	ctrl('e');
	ctrl('u');
	type("zz");
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_NO_MATCH);
	assert_string_equal(editline_text(&el), "zz");
	type(" q");
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_NO_MATCH);

	/* no completer */
	fresh();
	type("x");
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_NO_MATCH);
}

static void
test_complete_several(void **unused)
{
	(void)unused;
	fresh_completing();
	type("se");
	/* set and settle: the common prefix, then the list */
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_CHANGED);
	assert_string_equal(editline_text(&el), "set");
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_CANDIDATES);
	const char *const *cand;
	assert_int_equal(editline_candidates(&el, &cand), 2);
	assert_string_equal(cand[0], "set");
	assert_string_equal(cand[1], "settle");
	assert_string_equal(editline_text(&el), "set");

	/* a Tab after another key grows the word or does nothing: no list yet */
	ctrl('u');
	ctrl('e');
	ctrl('u');
	type("a");
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_NONE); /* add, attach: nothing to add */
	type("d");
	ctl(KBD_CTL_BACKSPACE, 0);
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_NONE);
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_CANDIDATES);
	/* a modifier's press between the two Tabs does not count as a key */
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_CANDIDATES);
	key_text("");
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_CANDIDATES);

	/* über, übel: the common prefix in characters, "übe" */
	ctrl('u');
	type("\xc3\xbc");
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_CHANGED);
	assert_string_equal(editline_text(&el), "\xc3\xbc" "be");
	/* été, ère share a lead byte but no character: nothing is added */
	ctrl('u');
	type("say ");
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_NONE);
	assert_string_equal(editline_text(&el), "say ");
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_CANDIDATES);
	assert_int_equal(editline_candidates(&el, &cand), 2);
	/* the first word: all but the one that is no UTF-8 */
	ctrl('u');
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_NONE);
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_CANDIDATES);
	assert_int_equal(editline_candidates(&el, &cand), 9);
	type("\xc3\xa9");
	ctl(KBD_CTL_TAB, 0);
	assert_string_equal(editline_text(&el), "\xc3\xa9t\xc3\xa9 ");
}

static void
test_length_limit(void **unused)
{
	(void)unused;
	fresh();
	char full[EDITLINE_MAX + 1];
	memset(full, 'a', EDITLINE_MAX);
	full[EDITLINE_MAX] = '\0';
	assert_int_equal(editline_insert(&el, full), EDITLINE_CHANGED);
	assert_int_equal(el.len, EDITLINE_MAX);
	assert_int_equal(key_text("b"), EDITLINE_REFUSED);
	assert_int_equal(el.len, EDITLINE_MAX);

	/* one byte free: a two-byte ü is refused whole, an ASCII letter fits */
	ctl(KBD_CTL_BACKSPACE, 0);
	ctl(KBD_CTL_HOME, 0);
	assert_int_equal(key_text("\xc3\xbc"), EDITLINE_REFUSED);
	assert_int_equal(el.len, EDITLINE_MAX - 1);
	assert_int_equal(el.cursor, 0);
	assert_int_equal(key_text("b"), EDITLINE_CHANGED);
	assert_int_equal(el.line[0], 'b');

	/* four bytes free: the emoji fits exactly, then nothing more */
	times(KBD_CTL_DELETE, 0, 4);
	assert_int_equal(key_text(EMOJI), EDITLINE_CHANGED);
	assert_int_equal(el.len, EDITLINE_MAX);
	assert_int_equal(strlen(editline_text(&el)), EDITLINE_MAX);
	/* a completion that would not fit is refused too */
	struct editline_def d = editline_default_def();
	d.complete = complete_commands;
	editline_init(&el, &d);
	memset(full, 'x', EDITLINE_MAX);
	memcpy(full, "add ", 4);
	memcpy(full + EDITLINE_MAX - 2, " e", 2);
	editline_insert(&el, full);
	assert_int_equal(el.len, EDITLINE_MAX);
	assert_int_equal(ctl(KBD_CTL_TAB, 0), EDITLINE_REFUSED); /* effector= */
	assert_string_equal(editline_text(&el), full);
	/* entered and recalled whole */
	char copy[EDITLINE_MAX + 1];
	strcpy(copy, editline_text(&el));
	ctl(KBD_CTL_RETURN, 0);
	assert_string_equal(editline_entered(&el), copy);
	ctl(KBD_CTL_UP, 0);
	assert_string_equal(editline_text(&el), copy);
}

static void
assert_window(int width, const char *text, int cursor_col, int left, int right)
{
	struct editline_window w;
	editline_visible(&el, width, &w);
	assert_int_equal(w.len, strlen(text));
	assert_memory_equal(w.text, text, w.len);
	assert_int_equal(w.cursor_col, cursor_col);
	assert_int_equal(w.more_left, left);
	assert_int_equal(w.more_right, right);
}

static void
test_visible(void **unused)
{
	(void)unused;
	fresh();
	assert_window(10, "", 0, 0, 0);
	type("0123456789abcdef");
	/* the cursor after f needs a cell: f in column 8, the cursor in 9 */
	assert_window(10, "789abcdef", 9, 1, 0);
	/* moving left inside the window does not scroll */
	times(KBD_CTL_LEFT, 0, 9);
	assert_window(10, "789abcdef", 0, 1, 0);
	/* past its left edge it scrolls by as much */
	ctl(KBD_CTL_LEFT, 0);
	assert_window(10, "6789abcdef", 0, 1, 0);
	ctl(KBD_CTL_HOME, 0);
	assert_window(10, "0123456789", 0, 0, 1);
	times(KBD_CTL_RIGHT, 0, 9);
	assert_window(10, "0123456789", 9, 0, 1);
	ctl(KBD_CTL_RIGHT, 0);
	assert_window(10, "123456789a", 9, 1, 1);
	/* the line shortened: the window comes back rather than show empty cells */
	ctrl('e');
	assert_window(10, "789abcdef", 9, 1, 0);
	times(KBD_CTL_BACKSPACE, 0, 4);
	assert_window(10, "3456789ab", 9, 1, 0);
	ctrl('u');
	assert_window(10, "", 0, 0, 0);

	/* columns are characters: ü is two bytes, the emoji four */
	type("\xc3\xbc\xc3\xbc\xc3\xbc" EMOJI EMOJI "xy");
	assert_window(4, EMOJI "xy", 3, 1, 0);
	ctl(KBD_CTL_HOME, 0);
	assert_window(4, "\xc3\xbc\xc3\xbc\xc3\xbc" EMOJI, 0, 0, 1);
	/* one column: only the cursor's cell */
	assert_window(1, "\xc3\xbc", 0, 0, 1);
	ctrl('e');
	assert_window(1, "", 0, 1, 0);
	/* no field at all */
	assert_window(0, "", 0, 0, 0);
	assert_window(-3, "", 0, 0, 0);
}

/* German keys through kbd_text into the line */
static void
test_from_kbd_text(void **unused)
{
	(void)unused;
	struct kbd_text_def d = kbd_text_default_def();
	d.layout = "de";
	char err[256];
	struct kbd_text *kt = kbd_text_create(&d, err, sizeof err);
	if (!kt)
		fail_msg("%s", err);
	fresh();
	/* z (KEY_Y on de), dead_acute e, ü, AltGr+Q, then Ctrl+A and Return */
	static const struct {
		unsigned code;
		int value;
	} keys[] = {
		{ KEY_Y, 1 },        { KEY_Y, 0 },         { KEY_EQUAL, 1 }, { KEY_EQUAL, 0 },
		{ KEY_E, 1 },        { KEY_E, 0 },         { KEY_LEFTBRACE, 1 },
		{ KEY_LEFTBRACE, 0 }, { KEY_RIGHTALT, 1 },  { KEY_Q, 1 },     { KEY_Q, 0 },
		{ KEY_RIGHTALT, 0 }, { KEY_LEFTCTRL, 1 },  { KEY_A, 1 },     { KEY_A, 0 },
		{ KEY_LEFTCTRL, 0 },
	};
	struct kbd_text_key k;
	for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
		if (kbd_text_key(kt, keys[i].code, keys[i].value, &k) == 1)
			editline_key(&el, &k);
	assert_string_equal(editline_text(&el), "z\xc3\xa9\xc3\xbc@");
	assert_int_equal(el.cursor, 0);
	kbd_text_key(kt, KEY_ENTER, 1, &k);
	assert_int_equal(editline_key(&el, &k), EDITLINE_ENTERED);
	assert_string_equal(editline_entered(&el), "z\xc3\xa9\xc3\xbc@");
	kbd_text_free(kt);
}

/* ---- random keys ----------------------------------------------------------- */

/* the test's own decoder: 1 when s[0, n) is well-formed, printable UTF-8 */
static int
reference_utf8(const unsigned char *s, size_t n, size_t *chars)
{
	*chars = 0;
	for (size_t i = 0; i < n; (*chars)++) {
		uint32_t cp;
		size_t len;
		if (s[i] < 0x80)
			cp = s[i], len = 1;
		else if ((s[i] & 0xe0) == 0xc0)
			cp = s[i] & 0x1f, len = 2;
		else if ((s[i] & 0xf0) == 0xe0)
			cp = s[i] & 0x0f, len = 3;
		else if ((s[i] & 0xf8) == 0xf0)
			cp = s[i] & 0x07, len = 4;
		else
			return 0;
		if (i + len > n)
			return 0;
		for (size_t k = 1; k < len; k++) {
			if ((s[i + k] & 0xc0) != 0x80)
				return 0;
			cp = (cp << 6) | (s[i + k] & 0x3f);
		}
		static const uint32_t least[] = { 0, 0, 0x80, 0x800, 0x10000 };
		if (cp < least[len] || cp > 0x10ffff || (cp >= 0xd800 && cp < 0xe000))
			return 0;
		if (cp < 0x20 || (cp >= 0x7f && cp < 0xa0))
			return 0;
		i += len;
	}
	return 1;
}

static int
on_boundary(const char *s, size_t i)
{
	return ((unsigned char)s[i] & 0xc0) != 0x80;
}

static void
check_invariants(long step)
{
	size_t chars, before;
	if (el.len > EDITLINE_MAX || el.line[el.len] != '\0' || strlen(el.line) != el.len)
		fail_msg("step %ld: length %zu, strlen %zu", step, el.len, strlen(el.line));
	if (!reference_utf8((const unsigned char *)el.line, el.len, &chars))
		fail_msg("step %ld: the line is no UTF-8", step);
	if (el.cursor > el.len || !on_boundary(el.line, el.cursor))
		fail_msg("step %ld: cursor %zu in a line of %zu", step, el.cursor, el.len);
	for (int i = 0; i < el.hist_count; i++) {
		const char *h = el.hist[i];
		if (strlen(h) > EDITLINE_MAX || !reference_utf8((const unsigned char *)h, strlen(h),
								&before))
			fail_msg("step %ld: history entry %d is no UTF-8", step, i);
	}
	/* the window: whole characters, the cursor inside it where it is in the line */
	int width = 1 + (int)(urand() * 40);
	struct editline_window w;
	editline_visible(&el, width, &w);
	size_t from = (size_t)(w.text - el.line);
	size_t shown;
	if (from + w.len > el.len || !on_boundary(el.line, from) ||
	    !on_boundary(el.line, from + w.len) ||
	    !reference_utf8((const unsigned char *)w.text, w.len, &shown) || shown > (size_t)width)
		fail_msg("step %ld: window [%zu, +%zu) of width %d", step, from, w.len, width);
	reference_utf8((const unsigned char *)el.line, from, &before);
	size_t cursor_chars;
	reference_utf8((const unsigned char *)el.line, el.cursor, &cursor_chars);
	if (w.cursor_col < 0 || w.cursor_col >= width || before + w.cursor_col != cursor_chars)
		fail_msg("step %ld: cursor column %d of %d, window at char %zu, cursor at %zu",
			 step, w.cursor_col, width, before, cursor_chars);
}

static int
complete_random(void *user, const char *const *words, int nwords, const char *prefix,
		const char **dest, int max)
{
	(void)user, (void)words, (void)nwords, (void)prefix;
	static const char *const pool[] = { "set", "settle", "\xc3\xa9t\xc3\xa9", "\xc3\xa8re",
					    "\xc3\xbc" "ber", "effector=", EMOJI "x", EMOJI "y",
					    "\xc3", "a\tb", "" };
	int n = (int)(urand() * 6);
	for (int i = 0; i < n && i < max; i++)
		dest[i] = pool[(int)(urand() * 11)];
	return n;
}

static enum editline_result
random_key(void)
{
	static const char *const texts[] = {
		"a", "b", " ", "\xc3\xbc", "\xc3\xa9", EMOJI, "x y", "\xc3", "\t", "\xed\xa0\x80",
		"0123456789012345678901234567890123456789012345678901234567890123456789"
		"\xc3\xbc\xc3\xbc\xc3\xbc" EMOJI EMOJI "0123456789012345678901234567890123456789",
	};
	static const char letters[] = "aewuqAEWU";
	double r = urand();
	unsigned mods = urand() < 0.15 ? KBD_MOD_CTRL : 0;
	if (urand() < 0.03)
		mods |= KBD_MOD_ALT;
	if (r < 0.45) {
		struct kbd_text_key k = { .mods = mods & KBD_MOD_ALT };
		snprintf(k.text, sizeof k.text, "%s", texts[(int)(urand() * 11)]);
		return editline_key(&el, &k);
	} else if (r < 0.47) {
		struct kbd_text_key k = { .mods = KBD_MOD_CTRL,
					  .keysym = (uint32_t)letters[(int)(urand() * 9)] };
		return editline_key(&el, &k);
	} else if (r < 0.999) {
		/* Return and Escape are rarer, so the line grows to its limit */
		static const enum kbd_ctl keys[] = {
			KBD_CTL_BACKSPACE, KBD_CTL_DELETE, KBD_CTL_LEFT, KBD_CTL_RIGHT, KBD_CTL_UP,
			KBD_CTL_DOWN,      KBD_CTL_HOME,   KBD_CTL_END,  KBD_CTL_TAB,   KBD_CTL_F1,
		};
		return ctl(keys[(int)(urand() * 10)], mods);
	}
	return ctl(urand() < 0.5 ? KBD_CTL_RETURN : KBD_CTL_ESCAPE, 0);
}

static void
test_random_keys(void **unused)
{
	(void)unused;
	rng_state = 0x6564697431;
	struct editline_def d = editline_default_def();
	d.history = 5;
	d.complete = complete_random;
	editline_init(&el, &d);
#if COUNT_ALLOCS
	long before = allocs;
#endif
	size_t longest = 0;
	long results[EDITLINE_CANDIDATES + 1] = { 0 };
	for (long step = 0; step < 100000; step++) {
		results[random_key()]++;
		check_invariants(step);
		if (el.len > longest)
			longest = el.len;
	}
#if COUNT_ALLOCS
	assert_int_equal(allocs, before);
#endif
	/* the walk reached the limit, where the refusals are, and every outcome */
	assert_true(longest > EDITLINE_MAX - 8);
	for (int r = EDITLINE_NONE; r <= EDITLINE_CANDIDATES; r++)
		if (results[r] < 10)
			fail_msg("%s only %ld times", editline_result_to_str(r), results[r]);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_insert_and_move),
		cmocka_unit_test(test_utf8),
		cmocka_unit_test(test_invalid_text),
		cmocka_unit_test(test_words),
		cmocka_unit_test(test_return_and_escape),
		cmocka_unit_test(test_history),
		cmocka_unit_test(test_history_ring),
		cmocka_unit_test(test_complete_one),
		cmocka_unit_test(test_complete_several),
		cmocka_unit_test(test_length_limit),
		cmocka_unit_test(test_visible),
		cmocka_unit_test(test_from_kbd_text),
		cmocka_unit_test(test_random_keys),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
