/*
 * menu.h - the kiosk's pop-up menu of commands (§1.7: Jack's
 * commands were picked from pop-up menus). A mouse button pressed on the
 * background with no mode active opens it at the pointer; it lists the
 * commands ("manipulate joint", "save posture") under group titles, and
 * the pointer, the keys and typed text pick one.
 *
 * Pure, like the rest of this layer: positions, keys and buttons in, an
 * action out; the caller runs what was chosen and draws the layout
 * (menu_draw.h). Everything is in struct menu, which the caller places
 * where it likes; nothing here allocates.
 *
 * The model. menu_init reads the command table through the callbacks of
 * struct menu_def (the daemon's cmd_entry_verb/object/usage fit them as
 * they are) and sorts each command into a group by this module's table,
 * keyed by verb and object; commands the table does not know go to "Other",
 * so nothing is lost, and a few commands of no use at a kiosk (quit,
 * subscribe, unsubscribe, auth, input ..., pick) are left out.
 *
 * The state. Closed, or open at a pixel with a highlighted row, which is
 * always a command, never a group title (-1 when nothing matches):
 *
 *   Up, Down           the previous or next command; they wrap around
 *   PageUp, PageDown   a window of rows up or down, stopping at the ends
 *   Home, End          the first and the last command
 *   Tab, Shift+Tab     the first command of the next or previous group (wrapping)
 *   Enter              chooses the highlighted command
 *   Escape             closes
 *   text               printable ASCII typed is added to the filter: a command
 *                      stays when the filter is a case-insensitive substring of
 *                      "verb object" or of its group's title; groups left with
 *                      no command disappear; the highlight goes to the first
 *   BackSpace          takes the filter's last character back off
 *   wheel              the highlight moves a command per detent
 *
 * The pointer highlights the command under it. A button released on a
 * command chooses it, except the release of the press that opened the menu
 * when the pointer has not moved since (so a click on the background
 * leaves the menu open, and press, drag, release chooses in one stroke).
 * A press outside the panel closes it; so does letting go of the opening
 * press outside after dragging. A press on a "more" marker scrolls a page.
 *
 * The layout. A panel of fixed width and height for as long as the menu is
 * open (so rows do not jump while typing): the filter row, the list, and a
 * hint row with the highlighted command's usage. The panel's corner is at
 * the pointer; it flips left or up when it would overflow the screen and
 * is then kept inside. When the list is taller than the screen, a window
 * of rows scrolls between two "more" markers and always holds the
 * highlight.
 */
#ifndef POSTURE_INTERACT_MENU_H
#define POSTURE_INTERACT_MENU_H

#include "interact/kbd_text.h"

#define MENU_MAX_ITEMS 192  /* commands kept; more are counted in menu.dropped */
#define MENU_MAX_GROUPS 12  /* the table's groups and "Other" */
#define MENU_MAX_ROWS (MENU_MAX_ITEMS + MENU_MAX_GROUPS) /* titles and commands */
#define MENU_LABEL_MAX 48   /* bytes of "verb object" with its NUL */
#define MENU_FILTER_MAX 32  /* bytes of the filter with its NUL */
#define MENU_TEXT_MAX 160   /* bytes of a row's text in the layout, with its NUL */
#define MENU_LAYOUT_MAX_ROWS (MENU_MAX_ROWS + 4) /* the list, the filter, the hint, two markers */

/*
 * Where the commands come from: entry i's verb, object ("" for none) and
 * usage, NULL past the last. usage may be NULL (no hint). The strings must
 * outlive the menu. Row and character sizes are pixels.
 */
struct menu_def {
	const char *(*verb)(int i);
	const char *(*object)(int i);
	const char *(*usage)(int i);
	int row_px;  /* a row's height (VIEW_LINE_PX) */
	int char_px; /* a character's advance, monospaced (VIEW_CHAR_PX) */
	int pad_px;  /* the panel's margin around its rows */
	int max_rows; /* the panel's rows at most, filter and hint included (a scrolled
		       * panel has at least 5); 0: as many as the screen holds */
};

/*
 * No commands; rows and characters as view.h draws the status line, a 4 px
 * margin, at most 30 rows (a panel that tall is already a long read, and a
 * draw list holds VIEW_MAX_TEXT texts in all).
 */
struct menu_def menu_default_def(void);

struct menu_item {
	int cmd;                     /* the caller's command index */
	int group;                   /* index into menu.group */
	const char *usage;           /* may be NULL */
	char label[MENU_LABEL_MAX];  /* "verb object" */
};

struct menu_group {
	const char *title;
	int first, count;            /* its commands: item[first .. first + count - 1] */
};

enum menu_state { MENU_STATE_CLOSED, MENU_STATE_OPEN };

/* the panel's geometry while open, pixels; slots are rows of the panel, top to bottom */
struct menu_geom {
	int x0, y0, x1, y1;  /* the panel: [x0, x1) x [y0, y1) */
	int cols;            /* characters a row holds */
	int slots;           /* rows of the panel */
	int scrolling;       /* 1: the list is longer than the panel; markers are shown */
	int list_slot;       /* the slot of the window's first row */
	int window;          /* rows of the list the window shows */
};

struct menu {
	/* the model: menu_init */
	struct menu_def def;
	int nitems, ngroups;
	int excluded;        /* commands left out as of no use at a kiosk */
	int dropped;         /* commands beyond MENU_MAX_ITEMS */
	int cols_wanted;     /* the widest row, characters */
	struct menu_item item[MENU_MAX_ITEMS];
	struct menu_group group[MENU_MAX_GROUPS];

	/* the state */
	enum menu_state state;
	int screen_w, screen_h;
	int open_x, open_y;  /* where it opened */
	int ptr_x, ptr_y;    /* the pointer as last seen */
	int held;            /* the press that opened it is still down */
	int moved;           /* the pointer left the opening point since */
	int armed;           /* a button went down on the panel (or opened it) */
	char filter[MENU_FILTER_MAX];
	int nrows;           /* rows that pass the filter: group titles and commands */
	short row[MENU_MAX_ROWS]; /* >= 0: an item; < 0: the title of group -1 - row */
	int hi;              /* the highlighted row (always a command), -1: none */
	int top;             /* the window's first row */
	struct menu_geom geom;
};

/*
 * Reads the commands through d and groups them. Returns how many commands
 * the menu lists, or -1 when d has no verb callback or a size is not
 * positive. The menu is closed. Allocates nothing.
 */
int menu_init(struct menu *m, const struct menu_def *d);

enum menu_action_kind {
	MENU_NONE,    /* nothing changed (or the menu is closed) */
	MENU_CHANGED, /* the highlight, the filter or the window changed: redraw */
	MENU_CHOSEN,  /* action.cmd was chosen; the menu is closed */
	MENU_CLOSED,  /* closed without a choice */
};

struct menu_action {
	enum menu_action_kind kind;
	int cmd;      /* MENU_CHOSEN: the caller's command index; else -1 */
};

/*
 * Opens the menu at pixel (x, y) of a screen_w x screen_h screen with the
 * opening button held, the filter empty and the first command highlighted;
 * an open menu reopens there. MENU_CHANGED, or MENU_NONE when the sizes
 * are not positive (it stays closed).
 */
struct menu_action menu_open(struct menu *m, int x, int y, int screen_w, int screen_h);

/* closes it; MENU_CLOSED, or MENU_NONE when it was closed */
struct menu_action menu_close(struct menu *m);

int menu_is_open(const struct menu *m);

/*
 * A key press or repeat: code the evdev code (PageUp and PageDown are
 * known by it), k what kbd_text made of it (the control key, the text,
 * the modifiers). Text typed with Ctrl or Alt is no filter text.
 */
struct menu_action menu_key(struct menu *m, unsigned code, const struct kbd_text_key *k);

/* the pointer moved to pixel (x, y) */
struct menu_action menu_pointer(struct menu *m, int x, int y);

/* a mouse button pressed (1) or released (0) with the pointer at (x, y) */
struct menu_action menu_button(struct menu *m, int pressed, int x, int y);

/* the wheel turned: detents > 0 away from the user (up) */
struct menu_action menu_wheel(struct menu *m, int detents);

/* the highlighted command's index in the caller's table, -1 when none (or closed) */
int menu_highlighted(const struct menu *m);

/* ---- the layout ---------------------------------------------------------- */

enum menu_row_kind {
	MENU_ROW_FILTER,    /* "filter: ..." */
	MENU_ROW_TITLE,     /* a group's title: not selectable */
	MENU_ROW_ITEM,      /* a command */
	MENU_ROW_MORE_UP,   /* rows above the window */
	MENU_ROW_MORE_DOWN, /* rows below it */
	MENU_ROW_HINT,      /* the highlighted command's usage */
};

struct menu_layout_row {
	enum menu_row_kind kind;
	int x0, y0, x1, y1;     /* the row: [x0, x1) x [y0, y1), pixels */
	int highlighted;        /* the highlighted command's row */
	int cmd;                /* MENU_ROW_ITEM: the caller's command index; else -1 */
	char text[MENU_TEXT_MAX]; /* cut to the panel's width ("..." at the end) */
};

struct menu_layout {
	int open;
	int x0, y0, x1, y1;     /* the panel */
	int char_px, row_px, pad_px;
	int nrows;
	struct menu_layout_row row[MENU_LAYOUT_MAX_ROWS];
};

/*
 * The panel and its visible rows, top to bottom (empty slots of a filtered
 * list are left out), for the drawer; dest->open is 0 and it has no rows
 * when the menu is closed.
 */
void menu_layout(const struct menu *m, struct menu_layout *dest);

/* "closed", "open" */
const char *menu_state_to_str(enum menu_state s);
/* "none", "changed", "chosen", "closed" */
const char *menu_action_to_str(enum menu_action_kind k);

#endif
