/* menu.c - the kiosk's pop-up menu of commands (see menu.h) */
#include "interact/menu.h"

#include <linux/input-event-codes.h>
#include <string.h>
#include <xkbcommon/xkbcommon-keysyms.h>

#include "draw/view.h"

/* ---- the groups ----------------------------------------------------------- */

enum {
	G_FIGURES,
	G_POSTURE,
	G_MANIPULATE,
	G_BEHAVIOURS,
	G_CONSTRAINTS,
	G_ERGONOMICS,
	G_VIEWS,
	G_FILES,
	G_INPUT,
	G_STATUS,
	G_OTHER,
	G_COUNT,
};

/*
 * Titles are short and never contain a word of a command's name, so that
 * typing a command's word ("joint") keeps exactly the commands that have it.
 */
static const char *const group_title[G_COUNT] = {
	"Figures", "Posture", "Manipulate", "Behaviours", "Constraints", "Ergonomics",
	"Views", "Files & history", "Input & kiosk", "Status & help", "Other",
};

/*
 * Which group a command goes to, and its place there (the table's order):
 * what a human-factors engineer does first comes first. object "" is a
 * verb alone; NULL is any object of the verb, so a new "manipulate X"
 * lands in its group without a change here.
 */
struct group_key {
	const char *verb, *object;
	int group;
};

static const struct group_key group_table[] = {
	{ "load", "human", G_FIGURES },
	{ "load", "family", G_FIGURES },
	{ "show", "family", G_FIGURES },
	{ "load", "population", G_FIGURES },
	{ "load", "figure", G_FIGURES },
	{ "unload", "figure", G_FIGURES },
	{ "list", "figures", G_FIGURES },
	{ "show", "figure", G_FIGURES },
	{ "set", "location", G_FIGURES },
	{ "set", "root", G_FIGURES },
	{ "set", "site", G_FIGURES },
	{ "get", "site", G_FIGURES },
	{ "get", "anthropometry", G_FIGURES },

	{ "set", "joint", G_POSTURE },
	{ "get", "joint", G_POSTURE },
	{ "get", "posture", G_POSTURE },
	{ "get", "balance", G_POSTURE },
	{ "apply", "posture", G_POSTURE },
	{ "mirror", "posture", G_POSTURE },
	{ "pose", "family", G_POSTURE },

	{ "manipulate", NULL, G_MANIPULATE },
	{ "drag", "", G_MANIPULATE },
	{ "snap", "", G_MANIPULATE },
	{ "set", "manip", G_MANIPULATE },
	{ "get", "manip", G_MANIPULATE },

	{ "behave", "", G_BEHAVIOURS },
	{ "set", "behavior", G_BEHAVIOURS },
	{ "get", "behavior", G_BEHAVIOURS },
	{ "move", "foot", G_BEHAVIOURS },
	{ "move", "hand", G_BEHAVIOURS },
	{ "move", "com", G_BEHAVIOURS },
	{ "bend", "torso", G_BEHAVIOURS },
	{ "rotate", "pelvis", G_BEHAVIOURS },
	{ "move", "head", G_BEHAVIOURS },
	{ "move", "eyes", G_BEHAVIOURS },
	{ "grab", "", G_BEHAVIOURS },
	{ "hold", NULL, G_BEHAVIOURS },
	{ "release", NULL, G_BEHAVIOURS },

	{ "add", "constraint", G_CONSTRAINTS },
	{ "set", "constraint", G_CONSTRAINTS },
	{ "set", "goal", G_CONSTRAINTS },
	{ "move", "goal", G_CONSTRAINTS },
	{ "enable", "constraint", G_CONSTRAINTS },
	{ "disable", "constraint", G_CONSTRAINTS },
	{ "delete", "constraint", G_CONSTRAINTS },
	{ "list", "constraints", G_CONSTRAINTS },
	{ "settle", "", G_CONSTRAINTS },

	{ "assess", NULL, G_ERGONOMICS },
	{ "can", "reach", G_ERGONOMICS },
	{ "reach", "", G_ERGONOMICS },
	{ "add", "load", G_ERGONOMICS },
	{ "list", "loads", G_ERGONOMICS },
	{ "delete", "load", G_ERGONOMICS },
	{ "analyze", NULL, G_ERGONOMICS },
	{ "list", "envelopes", G_ERGONOMICS },
	{ "set", "envelope", G_ERGONOMICS },
	{ "remove", "envelope", G_ERGONOMICS },
	{ "export", "envelope", G_ERGONOMICS },
	{ "get", "angles", G_ERGONOMICS },
	{ "set", "assess", G_ERGONOMICS },
	{ "get", "assess", G_ERGONOMICS },
	{ "export", "assessment", G_ERGONOMICS },

	{ "add", "view", G_VIEWS },
	{ "set", "camera", G_VIEWS },
	{ "set", "view", G_VIEWS },
	{ "render", "view", G_VIEWS },
	{ "delete", "view", G_VIEWS },
	{ "list", "views", G_VIEWS },
	{ "layout", "", G_VIEWS },
	{ "get", "layout", G_VIEWS },
	{ "render", "screen", G_VIEWS },

	{ "save", "posture", G_FILES },
	{ "load", "posture", G_FILES },
	{ "save", "session", G_FILES },
	{ "load", "session", G_FILES },
	{ "export", "urdf", G_FILES },
	{ "export", "gltf", G_FILES },
	{ "export", "bvh", G_FILES },
	{ "undo", "", G_FILES },
	{ "redo", "", G_FILES },
	{ "record", "start", G_FILES },
	{ "record", "stop", G_FILES },
	{ "get", "record", G_FILES },

	{ "set", "input", G_INPUT },
	{ "list", "devices", G_INPUT },
	{ "bind", "", G_INPUT },
	{ "unbind", "", G_INPUT },
	{ "list", "bindings", G_INPUT },
	{ "set", "kiosk", G_INPUT },
	{ "get", "kiosk", G_INPUT },

	{ "status", "", G_STATUS },
	{ "help", "", G_STATUS },
};

/*
 * Commands of no use at a kiosk: they serve a connection (quit, the event
 * streams, auth), inject input the kiosk's own devices give (input ...), or
 * ask for pixel coordinates a click gives (pick).
 */
static const struct group_key excluded[] = {
	{ "quit", NULL, 0 },     { "subscribe", NULL, 0 }, { "unsubscribe", NULL, 0 },
	{ "auth", NULL, 0 },     { "input", NULL, 0 },     { "pick", NULL, 0 },
};

#define NKEYS(a) ((int)(sizeof(a) / sizeof((a)[0])))
/* the width of a filter the panel leaves room for, characters */
#define FILTER_COLS 16
#define FILTER_PREFIX "filter: "
/* the pointer moves this far (pixels) from where the menu opened before its release chooses */
#define MOVE_SLOP 3

/* the entry of keys matching verb and object: an exact object first, then any; -1 none */
static int
key_find(const struct group_key *keys, int n, const char *verb, const char *object)
{
	int any = -1;
	for (int i = 0; i < n; i++) {
		if (strcmp(keys[i].verb, verb))
			continue;
		if (!keys[i].object) {
			if (any < 0)
				any = i;
		} else if (!strcmp(keys[i].object, object)) {
			return i;
		}
	}
	return any;
}

/* ---- the model ------------------------------------------------------------- */

struct menu_def
menu_default_def(void)
{
	return (struct menu_def){ .row_px = VIEW_LINE_PX, .char_px = VIEW_CHAR_PX, .pad_px = 4,
				  .max_rows = 30 };
}

/* an item's sort key: its group, its place in the table, then the caller's order */
struct item_key {
	int group, rank;
};

static int
item_before(const struct item_key *a, int acmd, const struct item_key *b, int bcmd)
{
	if (a->group != b->group)
		return a->group < b->group;
	if (a->rank != b->rank)
		return a->rank < b->rank;
	return acmd < bcmd;
}

/* "verb object", or the verb alone, cut to fit */
static void
label_make(const char *verb, const char *object, char dest[MENU_LABEL_MAX])
{
	size_t n = strlen(verb);
	if (n > MENU_LABEL_MAX - 1)
		n = MENU_LABEL_MAX - 1;
	memcpy(dest, verb, n);
	if (object && object[0] && n + 1 < MENU_LABEL_MAX - 1) {
		dest[n++] = ' ';
		size_t k = strlen(object);
		if (k > MENU_LABEL_MAX - 1 - n)
			k = MENU_LABEL_MAX - 1 - n;
		memcpy(dest + n, object, k);
		n += k;
	}
	dest[n] = '\0';
}

/* inserts command cmd at its place among the items sorted so far; returns that place */
static int
item_insert(struct menu *m, struct item_key keys[], int cmd, const struct item_key *key)
{
	int at = m->nitems;
	while (at > 0 && item_before(key, cmd, &keys[at - 1], m->item[at - 1].cmd))
		at--;
	memmove(&m->item[at + 1], &m->item[at], (size_t)(m->nitems - at) * sizeof m->item[0]);
	memmove(&keys[at + 1], &keys[at], (size_t)(m->nitems - at) * sizeof keys[0]);
	keys[at] = *key;
	m->item[at].cmd = cmd;
	m->item[at].group = key->group; /* the table's group for now; renumbered after */
	m->nitems++;
	return at;
}

/* the groups that have commands, in the table's order; items point at them */
static void
groups_collect(struct menu *m)
{
	m->ngroups = 0;
	for (int i = 0; i < m->nitems; i++) {
		int g = m->item[i].group;
		if (!m->ngroups || m->group[m->ngroups - 1].title != group_title[g]) {
			struct menu_group *ng = &m->group[m->ngroups++];
			ng->title = group_title[g];
			ng->first = i;
			ng->count = 0;
		}
		m->group[m->ngroups - 1].count++;
		m->item[i].group = m->ngroups - 1;
	}
}

/* the widest row any state can show, characters */
static int
cols_needed(const struct menu *m)
{
	int cols = (int)strlen(FILTER_PREFIX) + FILTER_COLS;
	for (int g = 0; g < m->ngroups; g++) {
		int n = (int)strlen(m->group[g].title);
		cols = n > cols ? n : cols;
	}
	for (int i = 0; i < m->nitems; i++) {
		int n = 2 + (int)strlen(m->item[i].label);
		cols = n > cols ? n : cols;
	}
	return cols;
}

int
menu_init(struct menu *m, const struct menu_def *d)
{
	if (!d->verb || d->row_px <= 0 || d->char_px <= 0 || d->pad_px < 0 || d->max_rows < 0)
		return -1;
	memset(m, 0, sizeof *m);
	m->def = *d;
	m->state = MENU_STATE_CLOSED;
	m->hi = -1;
	struct item_key keys[MENU_MAX_ITEMS];
	for (int i = 0; d->verb(i); i++) {
		const char *verb = d->verb(i), *object = d->object ? d->object(i) : "";
		if (!object)
			object = "";
		if (key_find(excluded, NKEYS(excluded), verb, object) >= 0) {
			m->excluded++;
			continue;
		}
		if (m->nitems == MENU_MAX_ITEMS) {
			m->dropped++;
			continue;
		}
		int k = key_find(group_table, NKEYS(group_table), verb, object);
		struct item_key key = { k >= 0 ? group_table[k].group : G_OTHER,
					k >= 0 ? k : NKEYS(group_table) };
		struct menu_item *it = &m->item[item_insert(m, keys, i, &key)];
		it->usage = d->usage ? d->usage(i) : NULL;
		label_make(verb, object, it->label);
	}
	groups_collect(m);
	m->cols_wanted = cols_needed(m);
	return m->nitems;
}

/* ---- rows, the filter and the highlight ---------------------------------------- */

static int
lower(int c)
{
	return c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c;
}

/* 1 when needle is a substring of hay, ASCII letters of either case alike */
static int
contains_nocase(const char *hay, const char *needle)
{
	size_t n = strlen(needle);
	for (const char *h = hay;; h++) {
		size_t k = 0;
		while (k < n && h[k] && lower((unsigned char)h[k]) == lower((unsigned char)needle[k]))
			k++;
		if (k == n)
			return 1;
		if (!*h)
			return 0;
	}
}

static int
row_is_item(const struct menu *m, int r)
{
	return r >= 0 && r < m->nrows && m->row[r] >= 0;
}

/* the first command row from `from` on in steps of dir (+1, -1), -1 when none */
static int
item_from(const struct menu *m, int from, int dir)
{
	for (int r = from; r >= 0 && r < m->nrows; r += dir)
		if (m->row[r] >= 0)
			return r;
	return -1;
}

/* the window scrolls as little as it must to hold the highlight (and its title when it can) */
static void
window_follow(struct menu *m)
{
	int window = m->geom.window, hi = m->hi;
	if (hi >= 0) {
		if (hi < m->top)
			m->top = hi > 0 && m->row[hi - 1] < 0 && window >= 2 ? hi - 1 : hi;
		if (hi >= m->top + window)
			m->top = hi - window + 1;
	}
	int last_top = m->nrows - window > 0 ? m->nrows - window : 0;
	if (m->top > last_top)
		m->top = last_top;
	if (m->top < 0)
		m->top = 0;
}

/* the rows the filter lets through; the highlight goes to the first command */
static void
rows_filter(struct menu *m)
{
	m->nrows = 0;
	for (int g = 0; g < m->ngroups; g++) {
		const struct menu_group *grp = &m->group[g];
		int whole = contains_nocase(grp->title, m->filter), titled = 0;
		for (int i = grp->first; i < grp->first + grp->count; i++) {
			if (!whole && !contains_nocase(m->item[i].label, m->filter))
				continue;
			if (!titled) {
				m->row[m->nrows++] = (short)(-1 - g);
				titled = 1;
			}
			m->row[m->nrows++] = (short)i;
		}
	}
	m->hi = item_from(m, 0, 1);
	m->top = 0;
	window_follow(m);
}

static struct menu_action
act(enum menu_action_kind kind)
{
	return (struct menu_action){ kind, -1 };
}

/* moves the highlight to row r (a command row, or -1 for none) */
static struct menu_action
highlight(struct menu *m, int r)
{
	if (r < 0 || r == m->hi)
		return act(MENU_NONE);
	m->hi = r;
	window_follow(m);
	return act(MENU_CHANGED);
}

/* n commands on (n > 0) or back (n < 0); wrap or stop at the ends */
static struct menu_action
highlight_step(struct menu *m, int n, int wrap)
{
	if (m->hi < 0)
		return act(MENU_NONE);
	int dir = n > 0 ? 1 : -1, r = m->hi;
	for (int k = 0; k != n; k += dir) {
		int next = item_from(m, r + dir, dir);
		if (next < 0 && wrap)
			next = item_from(m, dir > 0 ? 0 : m->nrows - 1, dir);
		if (next < 0)
			break;
		r = next;
	}
	return highlight(m, r);
}

/* a window's worth of rows on or back, landing on a command, stopping at the ends */
static struct menu_action
highlight_page(struct menu *m, int dir)
{
	if (m->hi < 0)
		return act(MENU_NONE);
	int target = m->hi + dir * (m->geom.window > 1 ? m->geom.window - 1 : 1);
	if (target >= m->nrows)
		target = m->nrows - 1;
	if (target < 0)
		target = 0;
	int r = item_from(m, target, dir);
	if (r < 0)
		r = item_from(m, target, -dir);
	return highlight(m, r);
}

/* the title row of the group the highlight is in */
static int
title_of(const struct menu *m, int r)
{
	while (r > 0 && m->row[r] >= 0)
		r--;
	return r;
}

/* the first command of the next (dir 1) or previous (dir -1) group, wrapping */
static struct menu_action
highlight_group(struct menu *m, int dir)
{
	if (m->hi < 0)
		return act(MENU_NONE);
	int t = title_of(m, m->hi), r = -1;
	if (dir > 0) {
		for (r = m->hi + 1; r < m->nrows && m->row[r] >= 0; r++)
			;
		r = r < m->nrows ? item_from(m, r, 1) : item_from(m, 0, 1);
	} else {
		r = t > 0 ? title_of(m, t - 1) : title_of(m, m->nrows - 1);
		r = item_from(m, r, 1);
	}
	return highlight(m, r);
}

/* ---- open and closed -------------------------------------------------------- */

/* where a panel of size px starts so that it covers `at` onwards, or ends there, inside the screen */
static int
place(int at, int size, int screen)
{
	int lo = at;
	if (lo + size > screen)
		lo = at - size;
	if (lo + size > screen)
		lo = screen - size;
	return lo < 0 ? 0 : lo;
}

/* the panel's size and place for the whole list on this screen */
static void
geom_place(struct menu *m)
{
	const struct menu_def *d = &m->def;
	struct menu_geom *g = &m->geom;
	int total = m->ngroups + m->nitems;
	int maxcols = (m->screen_w - 2 * d->pad_px) / d->char_px;
	g->cols = m->cols_wanted < maxcols ? m->cols_wanted : maxcols;
	if (g->cols < 1)
		g->cols = 1;
	int fit = (m->screen_h - 2 * d->pad_px) / d->row_px;
	if (d->max_rows > 0 && fit > d->max_rows)
		fit = d->max_rows;
	g->scrolling = total + 2 > fit;
	if (!g->scrolling) {
		g->window = total;
		g->list_slot = 1;
		g->slots = total + 2;
	} else {
		/* the filter, the hint and the two markers around the window */
		g->window = fit - 4 > 1 ? fit - 4 : 1;
		g->list_slot = 2;
		g->slots = g->window + 4;
	}
	int w = 2 * d->pad_px + g->cols * d->char_px, h = 2 * d->pad_px + g->slots * d->row_px;
	g->x0 = place(m->open_x, w, m->screen_w);
	g->y0 = place(m->open_y, h, m->screen_h);
	g->x1 = g->x0 + w;
	g->y1 = g->y0 + h;
}

struct menu_action
menu_open(struct menu *m, int x, int y, int screen_w, int screen_h)
{
	if (screen_w <= 0 || screen_h <= 0)
		return act(MENU_NONE);
	m->state = MENU_STATE_OPEN;
	m->screen_w = screen_w;
	m->screen_h = screen_h;
	m->open_x = m->ptr_x = x;
	m->open_y = m->ptr_y = y;
	m->held = m->armed = 1;
	m->moved = 0;
	m->filter[0] = '\0';
	geom_place(m);
	rows_filter(m);
	return act(MENU_CHANGED);
}

struct menu_action
menu_close(struct menu *m)
{
	if (m->state == MENU_STATE_CLOSED)
		return act(MENU_NONE);
	m->state = MENU_STATE_CLOSED;
	m->held = m->armed = 0;
	return act(MENU_CLOSED);
}

int
menu_is_open(const struct menu *m)
{
	return m->state == MENU_STATE_OPEN;
}

int
menu_highlighted(const struct menu *m)
{
	if (m->state != MENU_STATE_OPEN || m->hi < 0)
		return -1;
	return m->item[m->row[m->hi]].cmd;
}

/* the highlighted command chosen: the menu closes */
static struct menu_action
choose(struct menu *m)
{
	if (m->hi < 0)
		return act(MENU_NONE);
	int cmd = m->item[m->row[m->hi]].cmd;
	menu_close(m);
	return (struct menu_action){ MENU_CHOSEN, cmd };
}

/* ---- keys ------------------------------------------------------------------- */

/* printable ASCII appended to the filter, refused whole when it would not fit */
static struct menu_action
filter_type(struct menu *m, const char *text)
{
	size_t n = strlen(text), len = strlen(m->filter);
	for (size_t i = 0; i < n; i++)
		if ((unsigned char)text[i] < 0x20 || (unsigned char)text[i] > 0x7e)
			return act(MENU_NONE); /* the font draws ASCII only, and names are ASCII */
	if (len + n > MENU_FILTER_MAX - 1)
		return act(MENU_NONE);
	memcpy(m->filter + len, text, n + 1);
	rows_filter(m);
	return act(MENU_CHANGED);
}

static struct menu_action
filter_backspace(struct menu *m)
{
	size_t len = strlen(m->filter);
	if (!len)
		return act(MENU_NONE);
	m->filter[len - 1] = '\0';
	rows_filter(m);
	return act(MENU_CHANGED);
}

/* Shift+Tab: most layouts use Shift up choosing ISO_Left_Tab, so the keysym tells */
static int
shift_tab(const struct kbd_text_key *k)
{
	return k->keysym == XKB_KEY_ISO_Left_Tab || (k->mods & KBD_MOD_SHIFT);
}

/* the keys that have no control key of their own in kbd_text */
static struct menu_action
key_by_code(struct menu *m, unsigned code)
{
	switch (code) {
	case KEY_PAGEUP:
		return highlight_page(m, -1);
	case KEY_PAGEDOWN:
		return highlight_page(m, 1);
	}
	return act(MENU_NONE);
}

struct menu_action
menu_key(struct menu *m, unsigned code, const struct kbd_text_key *k)
{
	if (m->state != MENU_STATE_OPEN)
		return act(MENU_NONE);
	switch (k->ctl) {
	case KBD_CTL_UP:
		return highlight_step(m, -1, 1);
	case KBD_CTL_DOWN:
		return highlight_step(m, 1, 1);
	case KBD_CTL_HOME:
		return highlight(m, item_from(m, 0, 1));
	case KBD_CTL_END:
		return highlight(m, item_from(m, m->nrows - 1, -1));
	case KBD_CTL_TAB:
		return highlight_group(m, shift_tab(k) ? -1 : 1);
	case KBD_CTL_RETURN:
		return choose(m);
	case KBD_CTL_ESCAPE:
		return menu_close(m);
	case KBD_CTL_BACKSPACE:
		return filter_backspace(m);
	case KBD_CTL_NONE:
		if (k->text[0] && !(k->mods & (KBD_MOD_CTRL | KBD_MOD_ALT)))
			return filter_type(m, k->text);
		return key_by_code(m, code);
	case KBD_CTL_DELETE:
	case KBD_CTL_LEFT:
	case KBD_CTL_RIGHT:
	case KBD_CTL_F1:
	case KBD_CTL_F12:
		break;
	}
	return act(MENU_NONE); /* Delete, Left, Right, the function keys: nothing here */
}

/* ---- the pointer -------------------------------------------------------------- */

/* what is under a pixel */
enum hit {
	HIT_OUTSIDE, /* off the panel */
	HIT_PANEL,   /* the panel, on no row that does anything */
	HIT_ROW,     /* a row of the list (title or command): hit.row */
	HIT_MORE_UP,
	HIT_MORE_DOWN,
};

static enum hit
hit_test(const struct menu *m, int x, int y, int *row)
{
	const struct menu_geom *g = &m->geom;
	if (x < g->x0 || x >= g->x1 || y < g->y0 || y >= g->y1)
		return HIT_OUTSIDE;
	int dy = y - g->y0 - m->def.pad_px;
	if (dy < 0)
		return HIT_PANEL;
	int slot = dy / m->def.row_px;
	if (g->scrolling && slot == g->list_slot - 1)
		return HIT_MORE_UP;
	if (g->scrolling && slot == g->list_slot + g->window)
		return HIT_MORE_DOWN;
	if (slot < g->list_slot || slot >= g->list_slot + g->window)
		return HIT_PANEL;
	int r = m->top + slot - g->list_slot;
	if (r >= m->nrows)
		return HIT_PANEL;
	*row = r;
	return HIT_ROW;
}

struct menu_action
menu_pointer(struct menu *m, int x, int y)
{
	if (m->state != MENU_STATE_OPEN)
		return act(MENU_NONE);
	m->ptr_x = x;
	m->ptr_y = y;
	if (x - m->open_x > MOVE_SLOP || m->open_x - x > MOVE_SLOP || y - m->open_y > MOVE_SLOP ||
	    m->open_y - y > MOVE_SLOP)
		m->moved = 1;
	int r = -1;
	if (hit_test(m, x, y, &r) == HIT_ROW && row_is_item(m, r))
		return highlight(m, r);
	return act(MENU_NONE);
}

static struct menu_action
button_press(struct menu *m, int x, int y)
{
	int r = -1;
	switch (hit_test(m, x, y, &r)) {
	case HIT_OUTSIDE:
		return menu_close(m);
	case HIT_PANEL:
		m->armed = 1;
		return act(MENU_NONE);
	case HIT_ROW:
		m->armed = 1;
		return row_is_item(m, r) ? highlight(m, r) : act(MENU_NONE);
	case HIT_MORE_UP:
		m->armed = 1;
		return m->top > 0 ? highlight_page(m, -1) : act(MENU_NONE);
	case HIT_MORE_DOWN:
		m->armed = 1;
		return m->top + m->geom.window < m->nrows ? highlight_page(m, 1) : act(MENU_NONE);
	}
	return act(MENU_NONE);
}

static struct menu_action
button_release(struct menu *m, int x, int y)
{
	int opening = m->held, armed = m->armed, r = -1;
	m->held = m->armed = 0;
	if (!armed)
		return act(MENU_NONE);
	switch (hit_test(m, x, y, &r)) {
	case HIT_OUTSIDE:
		/* dragged off the panel and let go: no choice */
		return opening && m->moved ? menu_close(m) : act(MENU_NONE);
	case HIT_ROW:
		if (!row_is_item(m, r) || (opening && !m->moved))
			return act(MENU_NONE);
		m->hi = r;
		return choose(m);
	case HIT_PANEL:
	case HIT_MORE_UP:
	case HIT_MORE_DOWN:
		return act(MENU_NONE);
	}
	return act(MENU_NONE);
}

struct menu_action
menu_button(struct menu *m, int pressed, int x, int y)
{
	if (m->state != MENU_STATE_OPEN)
		return act(MENU_NONE);
	m->ptr_x = x;
	m->ptr_y = y;
	return pressed ? button_press(m, x, y) : button_release(m, x, y);
}

struct menu_action
menu_wheel(struct menu *m, int detents)
{
	if (m->state != MENU_STATE_OPEN || !detents)
		return act(MENU_NONE);
	/* away from the user is up the list; the wheel stops at the ends */
	return highlight_step(m, -detents, 0);
}

/* ---- the layout ----------------------------------------------------------------- */

/* s cut to cols characters, "..." marking a cut */
static void
text_fit(char dest[MENU_TEXT_MAX], const char *prefix, const char *s, int cols)
{
	size_t np = strlen(prefix), ns = strlen(s), max = (size_t)cols;
	if (max > MENU_TEXT_MAX - 1)
		max = MENU_TEXT_MAX - 1;
	char *p = dest;
	size_t n = 0;
	for (size_t i = 0; i < np && n < max; i++)
		p[n++] = prefix[i];
	for (size_t i = 0; i < ns && n < max; i++)
		p[n++] = s[i];
	p[n] = '\0';
	if (np + ns > max && max >= 3)
		memcpy(p + max - 3, "...", 4);
}

static struct menu_layout_row *
layout_row(const struct menu *m, struct menu_layout *L, enum menu_row_kind kind, int slot)
{
	const struct menu_geom *g = &m->geom;
	struct menu_layout_row *row = &L->row[L->nrows++];
	row->kind = kind;
	row->x0 = g->x0;
	row->x1 = g->x1;
	row->y0 = g->y0 + m->def.pad_px + slot * m->def.row_px;
	row->y1 = row->y0 + m->def.row_px;
	row->highlighted = 0;
	row->cmd = -1;
	row->text[0] = '\0';
	return row;
}

void
menu_layout(const struct menu *m, struct menu_layout *dest)
{
	const struct menu_geom *g = &m->geom;
	dest->open = m->state == MENU_STATE_OPEN;
	dest->nrows = 0;
	dest->char_px = m->def.char_px;
	dest->row_px = m->def.row_px;
	dest->pad_px = m->def.pad_px;
	if (!dest->open) {
		dest->x0 = dest->y0 = dest->x1 = dest->y1 = 0;
		return;
	}
	dest->x0 = g->x0;
	dest->y0 = g->y0;
	dest->x1 = g->x1;
	dest->y1 = g->y1;

	/* the filter, with a caret where typing goes */
	char typed[MENU_FILTER_MAX + 1];
	memcpy(typed, m->filter, sizeof m->filter);
	strcat(typed, "_");
	text_fit(layout_row(m, dest, MENU_ROW_FILTER, 0)->text, FILTER_PREFIX, typed, g->cols);

	if (g->scrolling && m->top > 0)
		text_fit(layout_row(m, dest, MENU_ROW_MORE_UP, g->list_slot - 1)->text, "", "  ^ more",
			 g->cols);
	for (int s = 0; s < g->window && m->top + s < m->nrows; s++) {
		int r = m->top + s, code = m->row[r];
		if (code < 0) {
			struct menu_layout_row *row = layout_row(m, dest, MENU_ROW_TITLE, g->list_slot + s);
			text_fit(row->text, "", m->group[-1 - code].title, g->cols);
			continue;
		}
		struct menu_layout_row *row = layout_row(m, dest, MENU_ROW_ITEM, g->list_slot + s);
		row->cmd = m->item[code].cmd;
		row->highlighted = r == m->hi;
		text_fit(row->text, "  ", m->item[code].label, g->cols);
	}
	if (g->scrolling && m->top + g->window < m->nrows)
		text_fit(layout_row(m, dest, MENU_ROW_MORE_DOWN, g->list_slot + g->window)->text, "",
			 "  v more", g->cols);

	/* what the highlighted command takes */
	const char *hint = "no command matches";
	if (m->hi >= 0)
		hint = m->item[m->row[m->hi]].usage ? m->item[m->row[m->hi]].usage : "";
	text_fit(layout_row(m, dest, MENU_ROW_HINT, g->slots - 1)->text, "", hint, g->cols);
}

const char *
menu_state_to_str(enum menu_state s)
{
	switch (s) {
	case MENU_STATE_CLOSED:
		return "closed";
	case MENU_STATE_OPEN:
		return "open";
	}
	return "?";
}

const char *
menu_action_to_str(enum menu_action_kind k)
{
	switch (k) {
	case MENU_NONE:
		return "none";
	case MENU_CHANGED:
		return "changed";
	case MENU_CHOSEN:
		return "chosen";
	case MENU_CLOSED:
		return "closed";
	}
	return "?";
}
