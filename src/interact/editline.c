#include "interact/editline.h"

#include <stdint.h>
#include <string.h>

struct editline_def
editline_default_def(void)
{
	return (struct editline_def){ .history = EDITLINE_HISTORY_MAX };
}

void
editline_init(struct editline *el, const struct editline_def *d)
{
	memset(el, 0, sizeof *el);
	el->def = *d;
	if (el->def.history < 1)
		el->def.history = 1;
	if (el->def.history > EDITLINE_HISTORY_MAX)
		el->def.history = EDITLINE_HISTORY_MAX;
	el->hist_pos = -1;
}

/* ---- UTF-8 ---------------------------------------------------------------- */

static int
is_continuation(unsigned char c)
{
	return (c & 0xc0) == 0x80;
}

/*
 * The length of the well-formed character at s (at most n bytes), or 0:
 * no overlong forms, no surrogates, nothing above U+10FFFF, and no control
 * characters (C0, DEL, C1), which have no place on one line of text.
 */
static size_t
utf8_char_len(const unsigned char *s, size_t n)
{
	unsigned char c = s[0];
	size_t len;
	uint32_t cp, min;
	if (c < 0x80)
		return c >= 0x20 && c != 0x7f;
	if (c >= 0xc2 && c <= 0xdf)
		len = 2, cp = c & 0x1f, min = 0x80;
	else if (c >= 0xe0 && c <= 0xef)
		len = 3, cp = c & 0x0f, min = 0x800;
	else if (c >= 0xf0 && c <= 0xf4)
		len = 4, cp = c & 0x07, min = 0x10000;
	else
		return 0;
	if (len > n)
		return 0;
	for (size_t i = 1; i < len; i++) {
		if (!is_continuation(s[i]))
			return 0;
		cp = cp << 6 | (s[i] & 0x3f);
	}
	if (cp < min || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff) || cp <= 0x9f)
		return 0;
	return len;
}

/* 1 when the n bytes at s are whole, printable characters */
static int
utf8_valid(const char *s, size_t n)
{
	const unsigned char *u = (const unsigned char *)s;
	for (size_t i = 0; i < n;) {
		size_t k = utf8_char_len(u + i, n - i);
		if (!k)
			return 0;
		i += k;
	}
	return 1;
}

/* the boundary after the character at i (i < len) */
static size_t
next_char(const char *s, size_t len, size_t i)
{
	for (i++; i < len && is_continuation((unsigned char)s[i]); i++)
		;
	return i;
}

/* the boundary before i (i > 0) */
static size_t
prev_char(const char *s, size_t i)
{
	for (i--; i > 0 && is_continuation((unsigned char)s[i]); i--)
		;
	return i;
}

/* characters in s[from, to) */
static size_t
count_chars(const char *s, size_t from, size_t to)
{
	size_t n = 0;
	for (size_t i = from; i < to; i++)
		n += !is_continuation((unsigned char)s[i]);
	return n;
}

/* the byte offset of character number k, or len when the line has fewer */
static size_t
char_offset(const char *s, size_t len, size_t k)
{
	size_t i = 0;
	for (; k > 0 && i < len; k--)
		i = next_char(s, len, i);
	return i;
}

/* ---- the line ------------------------------------------------------------- */

static void
set_line(struct editline *el, const char *text)
{
	el->len = strlen(text);
	memmove(el->line, text, el->len + 1);
	el->cursor = el->len;
	el->scroll = 0;
}

/* deletes [from, to): both on boundaries; the cursor goes to from */
static enum editline_result
delete_span(struct editline *el, size_t from, size_t to)
{
	if (from >= to)
		return EDITLINE_NONE;
	memmove(el->line + from, el->line + to, el->len - to + 1);
	el->len -= to - from;
	el->cursor = from;
	return EDITLINE_CHANGED;
}

static enum editline_result
move_to(struct editline *el, size_t pos)
{
	if (pos == el->cursor)
		return EDITLINE_NONE;
	el->cursor = pos;
	return EDITLINE_CHANGED;
}

/* the insertion of n bytes at the cursor, checked first */
static enum editline_result
insert_bytes(struct editline *el, const char *text, size_t n)
{
	if (n == 0)
		return EDITLINE_NONE;
	if (!utf8_valid(text, n))
		return EDITLINE_INVALID;
	if (n > EDITLINE_MAX - el->len)
		return EDITLINE_REFUSED;
	memmove(el->line + el->cursor + n, el->line + el->cursor, el->len - el->cursor + 1);
	memcpy(el->line + el->cursor, text, n);
	el->len += n;
	el->cursor += n;
	return EDITLINE_CHANGED;
}

enum editline_result
editline_insert(struct editline *el, const char *text)
{
	return insert_bytes(el, text, strlen(text));
}

/* the start of the word before pos: back over spaces, then over the word */
static size_t
word_start_before(const struct editline *el, size_t pos)
{
	while (pos > 0 && el->line[pos - 1] == ' ')
		pos--;
	while (pos > 0 && el->line[pos - 1] != ' ')
		pos--;
	return pos;
}

/* the end of the word after pos: over spaces, then over the word */
static size_t
word_end_after(const struct editline *el, size_t pos)
{
	while (pos < el->len && el->line[pos] == ' ')
		pos++;
	while (pos < el->len && el->line[pos] != ' ')
		pos++;
	return pos;
}

/* ---- history -------------------------------------------------------------- */

/* the i-th newest entry */
static const char *
hist_entry(const struct editline *el, int i)
{
	int n = el->def.history;
	return el->hist[((el->hist_head - 1 - i) % n + n) % n];
}

static void
hist_store(struct editline *el, const char *text)
{
	if (!text[0] || (el->hist_count > 0 && !strcmp(hist_entry(el, 0), text)))
		return;
	strcpy(el->hist[el->hist_head], text);
	el->hist_head = (el->hist_head + 1) % el->def.history;
	if (el->hist_count < el->def.history)
		el->hist_count++;
}

static enum editline_result
hist_older(struct editline *el)
{
	if (el->hist_pos + 1 >= el->hist_count)
		return EDITLINE_NONE;
	/* walking into the history keeps what was being typed */
	if (el->hist_pos < 0)
		memcpy(el->draft, el->line, el->len + 1);
	el->hist_pos++;
	set_line(el, hist_entry(el, el->hist_pos));
	return EDITLINE_CHANGED;
}

static enum editline_result
hist_newer(struct editline *el)
{
	if (el->hist_pos < 0)
		return EDITLINE_NONE;
	el->hist_pos--;
	set_line(el, el->hist_pos < 0 ? el->draft : hist_entry(el, el->hist_pos));
	return EDITLINE_CHANGED;
}

static enum editline_result
enter(struct editline *el)
{
	memcpy(el->entered, el->line, el->len + 1);
	hist_store(el, el->entered);
	el->hist_pos = -1;
	set_line(el, "");
	return EDITLINE_ENTERED;
}

static enum editline_result
clear(struct editline *el)
{
	el->hist_pos = -1;
	set_line(el, "");
	return EDITLINE_CLEARED;
}

/* ---- completion ----------------------------------------------------------- */

/* splits the line before start into words for the completer; returns their count */
static int
split_words(struct editline *el, size_t start)
{
	memcpy(el->words_buf, el->line, start);
	el->words_buf[start] = '\0';
	int n = 0;
	for (size_t i = 0; i < start;) {
		while (i < start && el->words_buf[i] == ' ')
			el->words_buf[i++] = '\0';
		if (i == start)
			break;
		el->words[n++] = el->words_buf + i;
		while (i < start && el->words_buf[i] != ' ')
			i++;
	}
	return n;
}

/*
 * keeps the candidates that extend prefix (length plen) and could be typed,
 * so their common prefix never ends inside a character of the prefix
 */
static int
keep_matches(struct editline *el, int n, const char *prefix, size_t plen)
{
	int kept = 0;
	for (int i = 0; i < n; i++) {
		const char *c = el->cand[i];
		if (c && !strncmp(c, prefix, plen) && utf8_valid(c, strlen(c)))
			el->cand[kept++] = c;
	}
	return kept;
}

/* the candidates' longest common prefix, cut back to a character boundary */
static size_t
common_prefix(struct editline *el)
{
	size_t n = strlen(el->cand[0]);
	for (int i = 1; i < el->ncand; i++) {
		size_t k = 0;
		while (k < n && el->cand[i][k] == el->cand[0][k])
			k++;
		n = k;
	}
	while (n > 0 && is_continuation((unsigned char)el->cand[0][n]))
		n--;
	return n;
}

/*
 * asks the completer about the word before the cursor and keeps the
 * candidates that fit; returns the length of the word's part before the cursor
 */
static size_t
ask_completer(struct editline *el)
{
	size_t start = el->cursor;
	while (start > 0 && el->line[start - 1] != ' ')
		start--;
	int nwords = split_words(el, start);
	/* the prefix goes after the words, NUL-terminated, so the line stays as it is */
	size_t plen = el->cursor - start;
	char *prefix = el->words_buf + start + 1;
	memcpy(prefix, el->line + start, plen);
	prefix[plen] = '\0';
	int n = el->def.complete(el->def.complete_user, el->words, nwords, prefix, el->cand,
				 EDITLINE_MAX_CANDIDATES);
	n = n < 0 ? 0 : n > EDITLINE_MAX_CANDIDATES ? EDITLINE_MAX_CANDIDATES : n;
	el->ncand = keep_matches(el, n, prefix, plen);
	return plen;
}

/* the one candidate: the rest of it, then a space unless it asks for a value */
static enum editline_result
complete_unique(struct editline *el, size_t plen)
{
	const char *word = el->cand[0];
	size_t len = strlen(word);
	enum editline_result r = insert_bytes(el, word + plen, len - plen);
	if (r == EDITLINE_REFUSED || r == EDITLINE_INVALID)
		return r;
	/* a space that does not fit leaves the word complete all the same */
	if (len > 0 && word[len - 1] != '=' && el->line[el->cursor] != ' ' &&
	    insert_bytes(el, " ", 1) == EDITLINE_CHANGED)
		r = EDITLINE_CHANGED;
	return r;
}

static enum editline_result
complete(struct editline *el)
{
	int again = el->tab_again;
	el->tab_again = 1;
	el->ncand = 0;
	if (!el->def.complete)
		return EDITLINE_NO_MATCH;
	size_t plen = ask_completer(el);
	if (el->ncand == 0)
		return EDITLINE_NO_MATCH;
	if (el->ncand == 1)
		return complete_unique(el, plen);
	size_t common = common_prefix(el);
	if (common > plen)
		return insert_bytes(el, el->cand[0] + plen, common - plen);
	/* nothing to add: the second Tab in a row shows the choice */
	return again ? EDITLINE_CANDIDATES : EDITLINE_NONE;
}

/* ---- keys ----------------------------------------------------------------- */

static enum editline_result
control_letter(struct editline *el, uint32_t keysym)
{
	/* keysyms of Latin letters are their ASCII codes */
	switch (keysym | 0x20) {
	case 'a':
		return move_to(el, 0);
	case 'e':
		return move_to(el, el->len);
	case 'w':
		return delete_span(el, word_start_before(el, el->cursor), el->cursor);
	case 'u':
		return delete_span(el, 0, el->cursor);
	default:
		return EDITLINE_NONE;
	}
}

static enum editline_result
edit_key(struct editline *el, enum kbd_ctl ctl, int word)
{
	switch (ctl) {
	case KBD_CTL_RETURN:
		return enter(el);
	case KBD_CTL_BACKSPACE:
		return el->cursor ? delete_span(el, prev_char(el->line, el->cursor), el->cursor)
				  : EDITLINE_NONE;
	case KBD_CTL_DELETE:
		if (el->cursor == el->len)
			return EDITLINE_NONE;
		return delete_span(el, el->cursor, next_char(el->line, el->len, el->cursor));
	case KBD_CTL_LEFT:
		if (word)
			return move_to(el, word_start_before(el, el->cursor));
		return el->cursor ? move_to(el, prev_char(el->line, el->cursor)) : EDITLINE_NONE;
	case KBD_CTL_RIGHT:
		if (word)
			return move_to(el, word_end_after(el, el->cursor));
		return el->cursor < el->len ? move_to(el, next_char(el->line, el->len, el->cursor))
					    : EDITLINE_NONE;
	case KBD_CTL_UP:
		return hist_older(el);
	case KBD_CTL_DOWN:
		return hist_newer(el);
	case KBD_CTL_HOME:
		return move_to(el, 0);
	case KBD_CTL_END:
		return move_to(el, el->len);
	case KBD_CTL_TAB:
		return complete(el);
	case KBD_CTL_ESCAPE:
		return clear(el);
	default:
		/* F1..F12 are the caller's */
		return EDITLINE_NONE;
	}
}

enum editline_result
editline_key(struct editline *el, const struct kbd_text_key *k)
{
	int ctrl = (k->mods & KBD_MOD_CTRL) != 0;
	int alt = (k->mods & KBD_MOD_ALT) != 0;
	/* a modifier or a pending compose sequence types nothing and breaks no Tab pair */
	if (k->ctl == KBD_CTL_NONE && !k->text[0] && !ctrl)
		return EDITLINE_NONE;
	int tab_again = el->tab_again;
	el->tab_again = 0;
	if (k->ctl != KBD_CTL_NONE) {
		if (k->ctl == KBD_CTL_TAB)
			el->tab_again = tab_again;
		return edit_key(el, k->ctl, ctrl);
	}
	if (ctrl && !alt)
		return control_letter(el, k->keysym);
	if (ctrl || alt)
		return EDITLINE_NONE;
	return editline_insert(el, k->text);
}

/* ---- what is shown -------------------------------------------------------- */

void
editline_visible(struct editline *el, int width, struct editline_window *dest)
{
	memset(dest, 0, sizeof *dest);
	dest->text = el->line;
	if (width < 1)
		return;
	size_t w = (size_t)width;
	size_t cursor_char = count_chars(el->line, 0, el->cursor);
	size_t total = count_chars(el->line, 0, el->len);
	/* scroll only as far as the cursor needs: left to it, or right until it fits */
	if (el->scroll > cursor_char)
		el->scroll = cursor_char;
	if (cursor_char - el->scroll >= w)
		el->scroll = cursor_char - w + 1;
	/* and back when the line got shorter, so no empty field shows beside hidden text */
	if (total + 1 < el->scroll + w)
		el->scroll = total + 1 > w ? total + 1 - w : 0;

	size_t from = char_offset(el->line, el->len, el->scroll);
	size_t to = char_offset(el->line + from, el->len - from, w) + from;
	dest->text = el->line + from;
	dest->len = to - from;
	dest->cursor_col = (int)(cursor_char - el->scroll);
	dest->more_left = from > 0;
	dest->more_right = to < el->len;
}

/* ---- the rest ------------------------------------------------------------- */

const char *
editline_text(const struct editline *el)
{
	return el->line;
}

const char *
editline_entered(const struct editline *el)
{
	return el->entered;
}

int
editline_candidates(const struct editline *el, const char *const **dest)
{
	*dest = el->cand;
	return el->ncand;
}

const char *
editline_result_to_str(enum editline_result r)
{
	switch (r) {
	case EDITLINE_NONE:
		return "none";
	case EDITLINE_CHANGED:
		return "changed";
	case EDITLINE_ENTERED:
		return "entered";
	case EDITLINE_CLEARED:
		return "cleared";
	case EDITLINE_REFUSED:
		return "refused";
	case EDITLINE_INVALID:
		return "invalid";
	case EDITLINE_NO_MATCH:
		return "no match";
	case EDITLINE_CANDIDATES:
		return "candidates";
	}
	return "?";
}
