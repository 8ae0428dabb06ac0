/*
 * test_menu.c - the kiosk's pop-up menu of commands against the real
 * command table (proto/commands.def) and a made-up one: every command
 * listed once in its group, unknown ones under "Other", the kiosk's
 * useless ones left out; the filter; the keys, which never rest on a group
 * title; the pointer, aimed from the layout; the panel inside the screen
 * from all four corners; a scrolled window that keeps the highlight; 100 000
 * random events after each of which the state holds its invariants, with
 * no allocation; and the menu drawn by the real renderer, its highlight
 * band where the layout says (the picture goes to test-output/menu.png).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <linux/input-event-codes.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "draw/render.h"
#include "draw/view.h"
#include "interact/menu.h"
#include "interact/menu_draw.h"

#include "alloc_count.h"
#include "test_random.h"

#define SW 1280
#define SH 720

/* ---- command tables ---------------------------------------------------------- */

struct entry {
	const char *verb, *object, *usage;
};

/* the daemon's table, as the daemon reads it */
static const struct entry real_table[] = {
#define CMD(verb, object, min, max, flags, handler, usage, reply, summary) { verb, object, usage },
#include "proto/commands.def"
#undef CMD
	{ NULL, NULL, NULL },
};

/* a table with commands the grouping does not know, and some it leaves out */
static const struct entry odd_table[] = {
	{ "frobnicate", "widget", "frobnicate widget N" },
	{ "load", "human", "load human" },
	{ "quit", "", "quit" },
	{ "manipulate", "spline", "manipulate spline FIG" }, /* any "manipulate" is Manipulate */
	{ "input", "gesture", "input gesture" },
	{ "zap", "", NULL },
	{ "undo", "", "undo" },
	{ NULL, NULL, NULL },
};

static const struct entry *table = real_table;

static const char *
t_verb(int i)
{
	return table[i].verb;
}

static const char *
t_object(int i)
{
	return table[i].object;
}

static const char *
t_usage(int i)
{
	return table[i].usage;
}

static int
table_size(void)
{
	int n = 0;
	while (table[n].verb)
		n++;
	return n;
}

/* 1 for the commands the menu leaves out (menu.c's list) */
static int
kiosk_useless(const struct entry *e)
{
	static const char *const verbs[] = { "quit", "subscribe", "unsubscribe", "auth", "input",
					     "pick" };
	for (size_t i = 0; i < sizeof verbs / sizeof verbs[0]; i++)
		if (!strcmp(e->verb, verbs[i]))
			return 1;
	return 0;
}

static struct menu menu;
static struct menu_layout layout;

static int
fresh(const struct entry *t)
{
	table = t;
	struct menu_def d = menu_default_def();
	d.verb = t_verb;
	d.object = t_object;
	d.usage = t_usage;
	return menu_init(&menu, &d);
}

/* the item of command cmd, -1 when the menu does not list it */
static int
item_of(int cmd)
{
	int found = -1;
	for (int i = 0; i < menu.nitems; i++)
		if (menu.item[i].cmd == cmd) {
			assert_int_equal(found, -1); /* listed once */
			found = i;
		}
	return found;
}

/* ---- events -------------------------------------------------------------------- */

static struct menu_action
ctl(enum kbd_ctl c)
{
	struct kbd_text_key k = { .ctl = c };
	return menu_key(&menu, 0, &k);
}

static struct menu_action
code(unsigned c)
{
	struct kbd_text_key k = { .ctl = KBD_CTL_NONE };
	return menu_key(&menu, c, &k);
}

static struct menu_action
type(const char *s)
{
	struct menu_action a = { MENU_NONE, -1 };
	for (; *s; s++) {
		struct kbd_text_key k = { .ctl = KBD_CTL_NONE, .keysym = (unsigned char)*s };
		k.text[0] = *s;
		a = menu_key(&menu, 0, &k);
	}
	return a;
}

/* the layout's row of command cmd, NULL when it is not visible */
static const struct menu_layout_row *
row_of(int cmd)
{
	menu_layout(&menu, &layout);
	for (int i = 0; i < layout.nrows; i++)
		if (layout.row[i].kind == MENU_ROW_ITEM && layout.row[i].cmd == cmd)
			return &layout.row[i];
	return NULL;
}

static const struct menu_layout_row *
highlighted_row(void)
{
	menu_layout(&menu, &layout);
	const struct menu_layout_row *found = NULL;
	for (int i = 0; i < layout.nrows; i++)
		if (layout.row[i].highlighted) {
			assert_null(found);
			assert_int_equal(layout.row[i].kind, MENU_ROW_ITEM);
			found = &layout.row[i];
		}
	return found;
}

/* the command shown as the n-th command row of the layout (from 0), -1 when fewer */
static int
nth_visible_cmd(int n)
{
	menu_layout(&menu, &layout);
	for (int i = 0; i < layout.nrows; i++)
		if (layout.row[i].kind == MENU_ROW_ITEM && n-- == 0)
			return layout.row[i].cmd;
	return -1;
}

static int
cx(const struct menu_layout_row *r)
{
	return (r->x0 + r->x1) / 2;
}

static int
cy(const struct menu_layout_row *r)
{
	return (r->y0 + r->y1) / 2;
}

/* ---- invariants ---------------------------------------------------------------------- */

/*
 * What every state keeps: the highlight on a command row inside the window
 * (or none, only when no command passes the filter), the window inside the
 * rows, and the panel inside the screen when the screen can hold it.
 */
static void
check_state(void)
{
	if (!menu_is_open(&menu)) {
		assert_int_equal(menu_highlighted(&menu), -1);
		return;
	}
	const struct menu_geom *g = &menu.geom;
	assert_true(menu.nrows >= 0 && menu.nrows <= MENU_MAX_ROWS);
	assert_true(menu.hi >= -1 && menu.hi < menu.nrows);
	int items = 0;
	for (int r = 0; r < menu.nrows; r++)
		items += menu.row[r] >= 0;
	if (menu.hi < 0) {
		assert_int_equal(items, 0);
	} else {
		assert_true(menu.row[menu.hi] >= 0 && menu.row[menu.hi] < menu.nitems);
		assert_true(menu.hi >= menu.top && menu.hi < menu.top + g->window);
	}
	assert_true(menu.top >= 0);
	assert_true(menu.top == 0 || menu.top + g->window <= menu.nrows);
	int w = g->x1 - g->x0, h = g->y1 - g->y0;
	if (w <= menu.screen_w)
		assert_true(g->x0 >= 0 && g->x1 <= menu.screen_w);
	if (h <= menu.screen_h)
		assert_true(g->y0 >= 0 && g->y1 <= menu.screen_h);
}

/* ---- grouping -------------------------------------------------------------------------- */

static void
test_every_command_once(void **unused)
{
	(void)unused;
	int n = fresh(real_table), useless = 0;
	assert_true(n > 50);
	for (int i = 0; i < table_size(); i++) {
		int it = item_of(i);
		if (kiosk_useless(&table[i])) {
			useless++;
			assert_int_equal(it, -1);
			continue;
		}
		assert_true(it >= 0);
		/* its label is "verb object" */
		char want[MENU_LABEL_MAX];
		snprintf(want, sizeof want, "%s%s%s", table[i].verb, table[i].object[0] ? " " : "",
			 table[i].object);
		assert_string_equal(menu.item[it].label, want);
		assert_ptr_equal(menu.item[it].usage, table[i].usage);
	}
	assert_int_equal(menu.excluded, useless);
	assert_int_equal(n + useless, table_size());
	assert_int_equal(menu.dropped, 0);
	/* the groups cover the items in order, each non-empty; none of them is "Other":
	 * a new command belongs in a group of menu.c's table */
	int next = 0;
	for (int g = 0; g < menu.ngroups; g++) {
		assert_int_equal(menu.group[g].first, next);
		assert_true(menu.group[g].count > 0);
		assert_string_not_equal(menu.group[g].title, "Other");
		for (int i = 0; i < menu.group[g].count; i++)
			assert_int_equal(menu.item[next + i].group, g);
		next += menu.group[g].count;
	}
	assert_int_equal(next, n);
	/* a few by name */
	const char *figures = menu.group[menu.item[item_of(2)].group].title; /* load human */
	assert_string_equal(figures, "Figures");
	for (int i = 0; i < table_size(); i++)
		if (!strcmp(table[i].verb, "manipulate"))
			assert_string_equal(menu.group[menu.item[item_of(i)].group].title, "Manipulate");
}

static void
test_unknown_and_excluded(void **unused)
{
	(void)unused;
	assert_int_equal(fresh(odd_table), 5);
	assert_int_equal(menu.excluded, 2);
	assert_int_equal(item_of(2), -1); /* quit */
	assert_int_equal(item_of(4), -1); /* input gesture */
	/* groups in the table's order, Other last with the unknown in the caller's order */
	assert_int_equal(menu.ngroups, 4);
	assert_string_equal(menu.group[0].title, "Figures");
	assert_string_equal(menu.group[1].title, "Manipulate");
	assert_string_equal(menu.group[2].title, "Files & history");
	assert_string_equal(menu.group[3].title, "Other");
	assert_int_equal(menu.group[3].count, 2);
	assert_string_equal(menu.item[menu.group[3].first].label, "frobnicate widget");
	assert_string_equal(menu.item[menu.group[3].first + 1].label, "zap");
	assert_string_equal(menu.item[menu.group[1].first].label, "manipulate spline");
	assert_null(menu.item[item_of(5)].usage);
	/* no verb callback: refused */
	struct menu_def d = menu_default_def();
	assert_int_equal(menu_init(&menu, &d), -1);
}

/* ---- the filter ----------------------------------------------------------------------- */

/* the commands that pass: 1 per item in dest, the count returned */
static int
passing(unsigned char dest[MENU_MAX_ITEMS])
{
	memset(dest, 0, MENU_MAX_ITEMS);
	int n = 0;
	for (int r = 0; r < menu.nrows; r++)
		if (menu.row[r] >= 0) {
			assert_int_equal(dest[menu.row[r]], 0);
			dest[menu.row[r]] = 1;
			n++;
		}
	return n;
}

static void
test_filter(void **unused)
{
	(void)unused;
	fresh(real_table);
	assert_int_equal(menu_open(&menu, 100, 100, SW, SH).kind, MENU_CHANGED);
	int all_rows = menu.nrows, first = menu_highlighted(&menu);
	assert_int_equal(all_rows, menu.nitems + menu.ngroups);
	assert_int_equal(first, menu.item[0].cmd);

	assert_int_equal(type("joint").kind, MENU_CHANGED);
	assert_string_equal(menu.filter, "joint");
	unsigned char pass[MENU_MAX_ITEMS];
	int n = passing(pass), want = 0;
	for (int i = 0; i < menu.nitems; i++) {
		int has = strstr(menu.item[i].label, "joint") != NULL;
		assert_null(strstr(menu.group[menu.item[i].group].title, "joint"));
		assert_int_equal(pass[i], has);
		want += has;
	}
	assert_int_equal(n, want);
	assert_true(n >= 3); /* get joint, set joint, manipulate joint */
	/* a title per group that kept a command, and no other */
	for (int r = 0; r < menu.nrows; r++)
		if (menu.row[r] < 0) {
			assert_true(r + 1 < menu.nrows && menu.row[r + 1] >= 0);
			assert_int_equal(menu.item[menu.row[r + 1]].group, -1 - menu.row[r]);
		}
	/* the highlight went to the first match, shown in the layout */
	assert_int_equal(menu.hi, 1);
	assert_non_null(highlighted_row());
	assert_non_null(strstr(highlighted_row()->text, "joint"));

	/* case does not matter */
	for (int i = 0; i < 5; i++)
		assert_int_equal(ctl(KBD_CTL_BACKSPACE).kind, MENU_CHANGED);
	assert_int_equal(menu.nrows, all_rows);
	assert_int_equal(menu_highlighted(&menu), first);
	assert_int_equal(ctl(KBD_CTL_BACKSPACE).kind, MENU_NONE);
	type("JoInT");
	unsigned char pass2[MENU_MAX_ITEMS];
	assert_int_equal(passing(pass2), n);
	assert_memory_equal(pass, pass2, MENU_MAX_ITEMS);

	/* a group's title keeps the whole group */
	for (int i = 0; i < 5; i++)
		ctl(KBD_CTL_BACKSPACE);
	type("history");
	int files = -1;
	for (int g = 0; g < menu.ngroups; g++)
		if (!strcmp(menu.group[g].title, "Files & history"))
			files = g;
	assert_true(files >= 0);
	assert_int_equal(menu.nrows, 1 + menu.group[files].count);

	/* nothing matches: no highlight, Enter chooses nothing, the hint says so */
	type("zzz");
	assert_int_equal(menu.nrows, 0);
	assert_int_equal(menu_highlighted(&menu), -1);
	assert_int_equal(ctl(KBD_CTL_RETURN).kind, MENU_NONE);
	assert_int_equal(ctl(KBD_CTL_DOWN).kind, MENU_NONE);
	menu_layout(&menu, &layout);
	assert_string_equal(layout.row[layout.nrows - 1].text, "no command matches");
	/* the filter has a length limit: text past it is refused whole */
	fresh(real_table);
	menu_open(&menu, 0, 0, SW, SH);
	for (int i = 0; i < MENU_FILTER_MAX - 1; i++)
		type("x");
	assert_int_equal(strlen(menu.filter), MENU_FILTER_MAX - 1);
	assert_int_equal(type("x").kind, MENU_NONE);
	/* Ctrl+letter is no text; nor is a character the font cannot draw */
	struct kbd_text_key k = { .ctl = KBD_CTL_NONE, .mods = KBD_MOD_CTRL, .text = "a" };
	ctl(KBD_CTL_ESCAPE);
	menu_open(&menu, 0, 0, SW, SH);
	assert_int_equal(menu_key(&menu, KEY_A, &k).kind, MENU_NONE);
	struct kbd_text_key e = { .ctl = KBD_CTL_NONE, .text = "\xc3\xa9" };
	assert_int_equal(menu_key(&menu, KEY_E, &e).kind, MENU_NONE);
	assert_string_equal(menu.filter, "");
}

/* ---- keys ----------------------------------------------------------------------------- */

static void
test_keys(void **unused)
{
	(void)unused;
	fresh(real_table);
	menu_open(&menu, 10, 10, SW, SH);
	/* row 0 is the first group's title, row 1 its first command */
	assert_int_equal(menu.row[0], -1);
	assert_int_equal(menu.hi, 1);
	int first = menu_highlighted(&menu), second = menu.item[1].cmd;
	assert_int_equal(ctl(KBD_CTL_DOWN).kind, MENU_CHANGED);
	assert_int_equal(menu_highlighted(&menu), second);
	assert_int_equal(ctl(KBD_CTL_UP).kind, MENU_CHANGED);
	assert_int_equal(menu_highlighted(&menu), first);
	/* Up from the first wraps to the last; Down from the last back to the first */
	int last = menu.item[menu.nitems - 1].cmd;
	ctl(KBD_CTL_UP);
	assert_int_equal(menu_highlighted(&menu), last);
	ctl(KBD_CTL_DOWN);
	assert_int_equal(menu_highlighted(&menu), first);
	/* Down walks every command in order, stepping over the titles */
	for (int i = 1; i < menu.nitems; i++) {
		ctl(KBD_CTL_DOWN);
		assert_int_equal(menu_highlighted(&menu), menu.item[i].cmd);
		assert_non_null(highlighted_row());
	}
	assert_int_equal(ctl(KBD_CTL_HOME).kind, MENU_CHANGED);
	assert_int_equal(menu_highlighted(&menu), first);
	assert_int_equal(ctl(KBD_CTL_HOME).kind, MENU_NONE);
	ctl(KBD_CTL_END);
	assert_int_equal(menu_highlighted(&menu), last);
	/* pages stop at the ends, not wrapping */
	assert_int_equal(code(KEY_PAGEDOWN).kind, MENU_NONE);
	ctl(KBD_CTL_HOME);
	assert_int_equal(code(KEY_PAGEUP).kind, MENU_NONE);
	assert_int_equal(code(KEY_PAGEDOWN).kind, MENU_CHANGED);
	int after_page = menu.hi;
	assert_true(after_page > 1 + menu.geom.window / 2);
	code(KEY_PAGEUP);
	assert_int_equal(menu_highlighted(&menu), first);
	/* Tab: the next group's first command; Shift+Tab (ISO_Left_Tab) back */
	assert_int_equal(ctl(KBD_CTL_TAB).kind, MENU_CHANGED);
	assert_int_equal(menu_highlighted(&menu), menu.item[menu.group[1].first].cmd);
	struct kbd_text_key back = { .ctl = KBD_CTL_TAB, .keysym = 0xfe20 };
	menu_key(&menu, KEY_TAB, &back);
	assert_int_equal(menu_highlighted(&menu), first);
	menu_key(&menu, KEY_TAB, &back); /* wraps to the last group */
	assert_int_equal(menu_highlighted(&menu),
			 menu.item[menu.group[menu.ngroups - 1].first].cmd);
	/* keys of no use here */
	assert_int_equal(ctl(KBD_CTL_LEFT).kind, MENU_NONE);
	assert_int_equal(ctl(KBD_CTL_F1).kind, MENU_NONE);
	/* Enter chooses and closes */
	ctl(KBD_CTL_HOME);
	ctl(KBD_CTL_DOWN);
	struct menu_action a = ctl(KBD_CTL_RETURN);
	assert_int_equal(a.kind, MENU_CHOSEN);
	assert_int_equal(a.cmd, second);
	assert_false(menu_is_open(&menu));
	assert_int_equal(ctl(KBD_CTL_DOWN).kind, MENU_NONE);
	/* Escape closes without a choice */
	menu_open(&menu, 10, 10, SW, SH);
	a = ctl(KBD_CTL_ESCAPE);
	assert_int_equal(a.kind, MENU_CLOSED);
	assert_int_equal(a.cmd, -1);
	assert_false(menu_is_open(&menu));
	assert_int_equal(menu_close(&menu).kind, MENU_NONE);
}

/* ---- the pointer --------------------------------------------------------------------- */

static void
test_pointer(void **unused)
{
	(void)unused;
	fresh(real_table);
	menu_open(&menu, 200, 150, SW, SH);
	/* the opening press let go where it was: nothing chosen, still open */
	assert_int_equal(menu_button(&menu, 0, 200, 150).kind, MENU_NONE);
	assert_true(menu_is_open(&menu));
	/* hovering the third command highlights it */
	int cmd = nth_visible_cmd(2);
	const struct menu_layout_row *r = row_of(cmd);
	assert_non_null(r);
	int x = cx(r), y = cy(r);
	assert_int_equal(menu_pointer(&menu, x, y).kind, MENU_CHANGED);
	assert_int_equal(menu_highlighted(&menu), cmd);
	assert_int_equal(highlighted_row()->cmd, cmd);
	assert_int_equal(menu_pointer(&menu, x + 1, y).kind, MENU_NONE);
	/* a title row is no target: the highlight stays */
	menu_layout(&menu, &layout);
	const struct menu_layout_row *title = NULL;
	for (int i = 0; i < layout.nrows && !title; i++)
		if (layout.row[i].kind == MENU_ROW_TITLE)
			title = &layout.row[i];
	assert_non_null(title);
	int tx = cx(title), ty = cy(title);
	assert_int_equal(menu_pointer(&menu, tx, ty).kind, MENU_NONE);
	assert_int_equal(menu_highlighted(&menu), cmd);
	assert_int_equal(menu_button(&menu, 1, tx, ty).kind, MENU_NONE);
	assert_int_equal(menu_button(&menu, 0, tx, ty).kind, MENU_NONE);
	assert_true(menu_is_open(&menu));
	/* a click on a command chooses it: the row under the pointer, from the layout */
	int other = nth_visible_cmd(5);
	r = row_of(other);
	x = r->x0 + 1;
	y = r->y1 - 1; /* the row's far corner still counts */
	menu_button(&menu, 1, x, y);
	assert_int_equal(menu_highlighted(&menu), other);
	struct menu_action a = menu_button(&menu, 0, x, y);
	assert_int_equal(a.kind, MENU_CHOSEN);
	assert_int_equal(a.cmd, other);
	assert_false(menu_is_open(&menu));

	/* press, drag, release: the opening press chooses where it is let go */
	menu_open(&menu, 200, 150, SW, SH);
	cmd = nth_visible_cmd(4);
	r = row_of(cmd);
	x = cx(r);
	y = cy(r);
	menu_pointer(&menu, x, y);
	a = menu_button(&menu, 0, x, y);
	assert_int_equal(a.kind, MENU_CHOSEN);
	assert_int_equal(a.cmd, cmd);

	/* dragged off the panel and let go: closed */
	menu_open(&menu, 200, 150, SW, SH);
	menu_pointer(&menu, 5, 5);
	assert_int_equal(menu_button(&menu, 0, 5, 5).kind, MENU_CLOSED);

	/* a click outside closes; the release that follows is nobody's */
	menu_open(&menu, 200, 150, SW, SH);
	menu_button(&menu, 0, 200, 150);
	assert_int_equal(menu_button(&menu, 1, SW - 2, SH - 2).kind, MENU_CLOSED);
	assert_false(menu_is_open(&menu));
	assert_int_equal(menu_button(&menu, 0, SW - 2, SH - 2).kind, MENU_NONE);

	/* the wheel: up the list away from the user, stopping at the ends */
	menu_open(&menu, 200, 150, SW, SH);
	assert_int_equal(menu_wheel(&menu, 1).kind, MENU_NONE);
	assert_int_equal(menu_wheel(&menu, -2).kind, MENU_CHANGED);
	assert_int_equal(menu_highlighted(&menu), menu.item[2].cmd);
	assert_int_equal(menu_wheel(&menu, 1).kind, MENU_CHANGED);
	assert_int_equal(menu_highlighted(&menu), menu.item[1].cmd);
}

/* ---- placement and scrolling ----------------------------------------------------------- */

static void
test_placement(void **unused)
{
	(void)unused;
	fresh(real_table);
	static const int screens[][2] = { { 1280, 720 }, { 640, 480 }, { 320, 240 }, { 1920, 1080 } };
	for (size_t s = 0; s < sizeof screens / sizeof screens[0]; s++) {
		int w = screens[s][0], h = screens[s][1];
		const int at[][2] = { { 0, 0 }, { w - 1, 0 }, { 0, h - 1 }, { w - 1, h - 1 },
				      { w / 2, h / 2 } };
		for (size_t k = 0; k < sizeof at / sizeof at[0]; k++) {
			menu_open(&menu, at[k][0], at[k][1], w, h);
			check_state();
			menu_layout(&menu, &layout);
			assert_true(layout.open);
			assert_true(layout.x0 >= 0 && layout.x1 <= w && layout.y0 >= 0 && layout.y1 <= h);
			for (int i = 0; i < layout.nrows; i++) {
				const struct menu_layout_row *r = &layout.row[i];
				assert_true(r->x0 >= layout.x0 && r->x1 <= layout.x1);
				assert_true(r->y0 >= layout.y0 && r->y1 <= layout.y1);
				/* the text fits the row, a monospaced character a column */
				assert_true((int)strlen(r->text) * layout.char_px <=
					    r->x1 - r->x0 - 2 * layout.pad_px);
			}
			/* the corner at the pointer when it fits: right of it or flipped left of it */
			int pw = layout.x1 - layout.x0, ph = layout.y1 - layout.y0;
			if (pw <= at[k][0] || pw <= w - at[k][0])
				assert_true(layout.x0 == at[k][0] || layout.x1 == at[k][0]);
			if (ph <= at[k][1] || ph <= h - at[k][1])
				assert_true(layout.y0 == at[k][1] || layout.y1 == at[k][1]);
		}
	}
	/* top left opens right and down, bottom right flips both */
	menu_open(&menu, 0, 0, SW, SH);
	assert_int_equal(menu.geom.x0, 0);
	assert_int_equal(menu.geom.y0, 0);
	menu_open(&menu, SW - 1, SH - 1, SW, SH);
	assert_int_equal(menu.geom.x1, SW - 1);
	assert_int_equal(menu.geom.y1, SH - 1);
	/* a screen too small for the panel: it keeps to the top left, still working */
	menu_open(&menu, 30, 30, 60, 40);
	check_state();
	assert_int_equal(menu.geom.x0, 0);
	assert_int_equal(menu.geom.y0, 0);
	assert_int_equal(menu.geom.window, 1);
	assert_int_equal(menu_open(&menu, 0, 0, 0, 10).kind, MENU_NONE);
}

static void
test_scrolling(void **unused)
{
	(void)unused;
	fresh(real_table);
	menu_open(&menu, 50, 50, 640, 300);
	assert_true(menu.geom.scrolling);
	int window = menu.geom.window;
	assert_true(window >= 5 && window < menu.nrows);
	menu_layout(&menu, &layout);
	/* at the top: more below only */
	int up = 0, down = 0;
	for (int i = 0; i < layout.nrows; i++) {
		up += layout.row[i].kind == MENU_ROW_MORE_UP;
		down += layout.row[i].kind == MENU_ROW_MORE_DOWN;
	}
	assert_int_equal(up, 0);
	assert_int_equal(down, 1);
	/* every command in turn is highlighted and visible */
	for (int i = 0; i < menu.nitems; i++) {
		if (i)
			ctl(KBD_CTL_DOWN);
		check_state();
		const struct menu_layout_row *r = highlighted_row();
		assert_non_null(r);
		assert_int_equal(r->cmd, menu.item[i].cmd);
	}
	/* at the bottom: more above only */
	up = down = 0;
	for (int i = 0; i < layout.nrows; i++) {
		up += layout.row[i].kind == MENU_ROW_MORE_UP;
		down += layout.row[i].kind == MENU_ROW_MORE_DOWN;
	}
	assert_int_equal(up, 1);
	assert_int_equal(down, 0);
	/* Home jumps back; a press on "more" pages down, keeping the highlight in view */
	ctl(KBD_CTL_HOME);
	assert_int_equal(menu.top, 0);
	menu_layout(&menu, &layout);
	const struct menu_layout_row *more = &layout.row[layout.nrows - 2];
	assert_int_equal(more->kind, MENU_ROW_MORE_DOWN);
	assert_int_equal(menu_button(&menu, 1, cx(more), cy(more)).kind, MENU_CHANGED);
	assert_true(menu.top > 0);
	assert_non_null(highlighted_row());
	/* the panel stays one size while the filter shortens the list */
	int h = menu.geom.y1 - menu.geom.y0;
	type("view");
	assert_int_equal(menu.geom.y1 - menu.geom.y0, h);
	assert_int_equal(menu.top, 0);
	check_state();
}

/* ---- random events ---------------------------------------------------------------------- */

static void
random_event(void)
{
	static const enum kbd_ctl ctls[] = { KBD_CTL_UP,     KBD_CTL_DOWN,   KBD_CTL_HOME,
					     KBD_CTL_END,    KBD_CTL_TAB,    KBD_CTL_RETURN,
					     KBD_CTL_ESCAPE, KBD_CTL_BACKSPACE, KBD_CTL_LEFT,
					     KBD_CTL_DELETE };
	static const char letters[] = "aeiostnrlmvjpgw ";
	const int sw = menu.screen_w > 0 ? menu.screen_w : SW, sh = menu.screen_h > 0 ? menu.screen_h : SH;
	double u = urand();
	if (!menu_is_open(&menu) || u < 0.01) {
		/* (re)open on a screen of some size, now and then a tiny one */
		int w = urand() < 0.1 ? (int)span(1, 120) : (int)span(200, 2000);
		int h = urand() < 0.1 ? (int)span(1, 120) : (int)span(150, 1200);
		menu_open(&menu, (int)span(-10, w + 10), (int)span(-10, h + 10), w, h);
	} else if (u < 0.25) {
		ctl(ctls[(int)span(0, sizeof ctls / sizeof ctls[0])]);
	} else if (u < 0.32) {
		code(urand() < 0.5 ? KEY_PAGEUP : KEY_PAGEDOWN);
	} else if (u < 0.4) {
		/* as often as letters, so the filter does not only grow */
		ctl(KBD_CTL_BACKSPACE);
	} else if (u < 0.5) {
		char s[2] = { letters[(int)span(0, sizeof letters - 1)], 0 };
		type(s);
	} else if (u < 0.55) {
		struct kbd_text_key back = { .ctl = KBD_CTL_TAB, .mods = KBD_MOD_SHIFT };
		menu_key(&menu, KEY_TAB, &back);
	} else if (u < 0.8) {
		/* mostly over the panel */
		const struct menu_geom *g = &menu.geom;
		int x = urand() < 0.8 ? (int)span(g->x0, g->x1) : (int)span(-20, sw + 20);
		int y = urand() < 0.8 ? (int)span(g->y0, g->y1) : (int)span(-20, sh + 20);
		menu_pointer(&menu, x, y);
	} else if (u < 0.95) {
		/* rarely outside, or the menu would hardly stay open */
		const struct menu_geom *g = &menu.geom;
		int x = urand() < 0.95 ? (int)span(g->x0, g->x1) : (int)span(0, sw);
		int y = urand() < 0.95 ? (int)span(g->y0, g->y1) : (int)span(0, sh);
		if (urand() < 0.97)
			x = menu.ptr_x, y = menu.ptr_y;
		menu_button(&menu, urand() < 0.5, x, y);
	} else {
		menu_wheel(&menu, (int)span(-3, 4));
	}
}

static void
test_random_events(void **unused)
{
	(void)unused;
	fresh(real_table);
	rng_state = 14;
	long opened = 0, closed = 0, filtered_empty = 0;
#if COUNT_ALLOCS
	long before = allocs;
#endif
	for (long step = 0; step < 100000; step++) {
		int was_open = menu_is_open(&menu);
		random_event();
		opened += !was_open && menu_is_open(&menu);
		filtered_empty += menu_is_open(&menu) && menu.nrows == 0;
		closed += was_open && !menu_is_open(&menu);
		check_state();
		menu_layout(&menu, &layout);
		if (layout.open) {
			assert_true(layout.nrows >= 2);
			assert_int_equal(layout.row[0].kind, MENU_ROW_FILTER);
			assert_int_equal(layout.row[layout.nrows - 1].kind, MENU_ROW_HINT);
			assert_int_equal(highlighted_row() != NULL, menu.hi >= 0);
		}
	}
#if COUNT_ALLOCS
	assert_int_equal(allocs, before);
#endif
	/* the walk saw the menu open and close many times, and the empty filter result */
	printf("# %ld openings, %ld closings, %ld steps with nothing matching\n", opened,
	       closed, filtered_empty);
	assert_true(opened > 100);
	assert_true(filtered_empty > 100);
}

/* ---- the picture ------------------------------------------------------------------------- */

#define RW 640
#define RH 480

static void
picture_save(const struct frame *f)
{
	char dir[512], path[600];
	const char *build = getenv("POSTURE_BUILD");
	snprintf(dir, sizeof dir, "%s/test-output", build && build[0] ? build : "build/rel");
	if (mkdir(dir, 0755) && errno != EEXIST) {
		printf("# no %s: the picture is not kept\n", dir);
		return;
	}
	snprintf(path, sizeof path, "%s/menu.png", dir);
	png_image img;
	memset(&img, 0, sizeof img);
	img.version = PNG_IMAGE_VERSION;
	img.width = (png_uint_32)f->width;
	img.height = (png_uint_32)f->height;
	img.format = PNG_FORMAT_RGBA;
	assert_true(png_image_write_to_file(&img, path, 0, f->rgba, f->stride, NULL));
	printf("# the menu: %s\n", path);
}

static const uint8_t *
pixel(const struct frame *f, int x, int y)
{
	return f->rgba + (size_t)f->stride * y + 4 * (size_t)x;
}

static int
near_rgb(const uint8_t *p, const uint8_t want[4], int tol)
{
	for (int i = 0; i < 3; i++)
		if (abs((int)p[i] - (int)want[i]) > tol)
			return 0;
	return 1;
}

static void
test_render(void **unused)
{
	(void)unused;
	char err[256];
	struct render_def d = render_default_def();
	d.max_w = RW;
	d.max_h = RH;
	d.samples = 0;
	d.shadows = 0;
	struct render *r = render_make(&d, err, sizeof err);
	if (!r)
		fail_msg("render_make: %s", err);
	struct drawlist *dl = view_drawlist_make();
	assert_non_null(dl);
	struct camera cam;
	view_camera_default(&cam);

	fresh(real_table);
	menu_open(&menu, 420, 300, RW, RH); /* flips left; as tall as the screen holds */
	type("o");
	ctl(KBD_CTL_DOWN);
	ctl(KBD_CTL_DOWN);
	menu_layout(&menu, &layout);
	assert_int_equal(layout.x1, 420);
	assert_true(layout.y0 >= 0 && layout.y1 <= RH);
	const struct menu_layout_row *hi = highlighted_row();
	assert_non_null(hi);

	view_begin(dl, &cam, RW, RH);
	menu_draw(dl, &layout);
	view_add_pointer(dl, 420, 300);
	assert_int_equal(dl->dropped, 0);
	struct frame f;
	assert_int_equal(render_frame(r, dl, 0, &f), 0);
	picture_save(&f);

	/* the band's colour across the highlighted row, right of its text */
	static const uint8_t band[4] = MENU_DRAW_HIGHLIGHT_RGBA;
	int text_end = hi->x0 + layout.pad_px + (int)strlen(hi->text) * VIEW_CHAR_PX;
	int found = 0, tried = 0;
	for (int x = text_end + 4; x < hi->x1 - 4; x += 3)
		for (int y = hi->y0 + 2; y < hi->y1 - 2; y += 3) {
			tried++;
			found += near_rgb(pixel(&f, x, y), band, 6);
		}
	assert_true(tried > 10);
	assert_int_equal(found, tried);
	/* and not on the other rows, nor outside the panel */
	for (int i = 0; i < layout.nrows; i++) {
		const struct menu_layout_row *row = &layout.row[i];
		if (row == hi)
			continue;
		assert_false(near_rgb(pixel(&f, row->x1 - 5, cy(row)), band, 24));
	}
	assert_false(near_rgb(pixel(&f, layout.x1 + 10, cy(hi)), band, 24));
	assert_false(near_rgb(pixel(&f, layout.x0 - 10, cy(hi)), band, 24));
	/* the panel darkens what is behind it */
	const uint8_t *in = pixel(&f, layout.x1 - 3, layout.y0 + 2), *out = pixel(&f, layout.x1 + 3, layout.y0 + 2);
	assert_true(in[0] + in[1] + in[2] < (out[0] + out[1] + out[2]) / 2);
	/* there is text on the highlighted row: bright pixels where its letters are */
	int bright = 0;
	for (int x = hi->x0 + layout.pad_px; x < text_end; x++)
		for (int y = hi->y0; y < hi->y1; y++) {
			const uint8_t *p = pixel(&f, x, y);
			bright += p[0] > 200 && p[1] > 200 && p[2] > 200;
		}
	assert_true(bright > 20);

	view_drawlist_free(dl);
	render_free(r);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_every_command_once),
		cmocka_unit_test(test_unknown_and_excluded),
		cmocka_unit_test(test_filter),
		cmocka_unit_test(test_keys),
		cmocka_unit_test(test_pointer),
		cmocka_unit_test(test_placement),
		cmocka_unit_test(test_scrolling),
		cmocka_unit_test(test_random_events),
		cmocka_unit_test(test_render),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
