/*
 * editline.h - the kiosk's edit line: a one-line editor for typed
 * commands, fed the keys kbd_text translates. It keeps the line, the
 * cursor, a history ring and the horizontal scroll of the status line that
 * shows it; it never allocates (everything is in struct editline, which
 * the caller places where it likes) and knows nothing of what a command
 * means: completion asks the caller.
 *
 * The line is UTF-8, at most EDITLINE_MAX bytes. The cursor is a byte
 * offset that always stands on a character boundary: it moves, and
 * BackSpace and Delete delete, by code points. A word is a run of
 * characters other than the space. The keys:
 *
 *   text             inserted at the cursor (not with Ctrl or Alt held)
 *   Left, Right      a character;  Ctrl+Left, Ctrl+Right  a word
 *   Home, Ctrl+A     start;        End, Ctrl+E            end
 *   BackSpace        the character before the cursor; Delete the one after
 *   Ctrl+W           the word before the cursor;  Ctrl+U  all before the cursor
 *   Up, Down         older and newer lines of the history; the line being
 *                    typed is kept and comes back below the newest
 *   Return           the line is entered (editline_entered) and stored in the
 *                    history, unless empty or the same as the newest entry
 *   Escape           clears the line
 *   Tab              completes the word before the cursor (see struct editline_def)
 *
 * Text that would make the line longer than EDITLINE_MAX is refused whole
 * (EDITLINE_REFUSED), never cut; text that is not well-formed UTF-8 or
 * holds a control character is refused too (EDITLINE_INVALID).
 */
#ifndef POSTURE_INTERACT_EDITLINE_H
#define POSTURE_INTERACT_EDITLINE_H

#include <stddef.h>

#include "interact/kbd_text.h"

#define EDITLINE_MAX 1024                    /* bytes of a line, without its NUL */
#define EDITLINE_HISTORY_MAX 64              /* lines the history ring can keep */
#define EDITLINE_MAX_WORDS (EDITLINE_MAX / 2 + 1) /* words a full line can hold */
#define EDITLINE_MAX_CANDIDATES 256          /* completions taken from one Tab */

enum editline_result {
	EDITLINE_NONE,       /* nothing changed: a key of no use here, the cursor at the end ... */
	EDITLINE_CHANGED,    /* the line or the cursor changed: redraw */
	EDITLINE_ENTERED,    /* Return: editline_entered() has the line; the edit line is empty */
	EDITLINE_CLEARED,    /* Escape: the line is empty (it may have been before) */
	EDITLINE_REFUSED,    /* the text would pass EDITLINE_MAX bytes: nothing inserted */
	EDITLINE_INVALID,    /* not UTF-8, or a control character in it: nothing inserted */
	EDITLINE_NO_MATCH,   /* Tab: nothing completes the word */
	EDITLINE_CANDIDATES, /* Tab again: editline_candidates() lists what the word may become */
};

/*
 * Completion. Tab calls complete with the words before the cursor's word
 * (words[0] is the command) and prefix, that word's part before the
 * cursor ("" after a space). It writes up to max candidate words into dest
 * and returns how many; each is NUL-terminated, owned by the caller and
 * must stay valid until the next key is fed. Candidates that do not start
 * with prefix are ignored. Then:
 * - one candidate: the word is completed and a space follows it, unless
 *   the word ends in '=' (a key=value argument, whose value comes next);
 * - several: the word grows to their longest common prefix; a second Tab
 *   in a row answers EDITLINE_CANDIDATES for the status line to list them;
 * - none: EDITLINE_NO_MATCH.
 */
struct editline_def {
	int history; /* lines the history keeps, 1..EDITLINE_HISTORY_MAX */
	int (*complete)(void *user, const char *const *words, int nwords, const char *prefix,
			const char **dest, int max);
	void *complete_user;
};

/* a history of EDITLINE_HISTORY_MAX lines, no completion */
struct editline_def editline_default_def(void);

/* what the status line shows of the line: editline_visible() */
struct editline_window {
	const char *text; /* the visible characters: len bytes of the line, not NUL-terminated */
	size_t len;
	int cursor_col;   /* the cursor's column, 0..width-1 */
	int more_left;    /* characters hidden before text */
	int more_right;   /* characters hidden after it */
};

struct editline {
	struct editline_def def;
	char line[EDITLINE_MAX + 1];
	size_t len;         /* bytes */
	size_t cursor;      /* a byte offset on a character boundary, 0..len */
	size_t scroll;      /* the first visible character, counted in characters */
	char entered[EDITLINE_MAX + 1];

	/* the ring: hist[(hist_head - 1 - i) mod history] is the i-th newest of hist_count */
	char hist[EDITLINE_HISTORY_MAX][EDITLINE_MAX + 1];
	int hist_count, hist_head;
	int hist_pos;       /* -1: the line being typed; i: the i-th newest entry shown */
	char draft[EDITLINE_MAX + 1]; /* the line being typed, while the history is shown */

	int tab_again;      /* the last key was Tab: another lists the candidates */
	const char *cand[EDITLINE_MAX_CANDIDATES];
	int ncand;
	/* the words before the cursor, split for completion, then the prefix */
	char words_buf[EDITLINE_MAX + 2];
	const char *words[EDITLINE_MAX_WORDS];
};

/* an empty line with d's history size (clamped to 1..EDITLINE_HISTORY_MAX) and completion */
void editline_init(struct editline *el, const struct editline_def *d);

/*
 * Feeds one translated key (a press or repeat from kbd_text_key). Returns
 * what happened (enum editline_result). Allocates nothing.
 */
enum editline_result editline_key(struct editline *el, const struct kbd_text_key *k);

/*
 * Inserts UTF-8 text at the cursor, which moves past it. Returns
 * EDITLINE_CHANGED, EDITLINE_NONE for "", or EDITLINE_REFUSED or
 * EDITLINE_INVALID with the line unchanged.
 */
enum editline_result editline_insert(struct editline *el, const char *text);

/* the line being edited, NUL-terminated */
const char *editline_text(const struct editline *el);

/* the line the last Return entered ("" before any) */
const char *editline_entered(const struct editline *el);

/* the candidates the last EDITLINE_CANDIDATES listed: their count, the words in *dest */
int editline_candidates(const struct editline *el, const char *const **dest);

/*
 * The part of the line a field width characters wide shows, with the
 * cursor's column (a character is a column: the status line's font is
 * monospaced and draws one glyph per code point). The window scrolls only
 * as far as it must to keep the cursor in it, and back when the line
 * shortens, so it does not jump while the cursor moves inside it. The
 * cursor may stand after the last character, so that cell counts too.
 * width < 1 gives an empty window.
 */
void editline_visible(struct editline *el, int width, struct editline_window *dest);

const char *editline_result_to_str(enum editline_result r);

#endif
