/* prompt.c - a command's missing arguments asked for one by one (see prompt.h) */
#include "interact/prompt.h"

#include <ctype.h>
#include <stdio.h>
#include <string.h>

#define TOKENS_MAX 48

static int
all_lower(const char *w)
{
	for (; *w; w++)
		if (isupper((unsigned char)*w))
			return 0;
	return 1;
}

/* the first form of usage split into its top-level tokens; bracketed parts dropped */
static int
usage_tokens(const char *usage, char tok[][48], int max)
{
	int n = 0, depth = 0;
	const char *p = usage;
	while (*p && n < max) {
		while (*p == ' ')
			p++;
		if (!*p)
			break;
		const char *start = p;
		while (*p && (*p != ' ' || depth > 0)) {
			depth += *p == '[';
			depth -= *p == ']' && depth > 0;
			p++;
		}
		size_t len = (size_t)(p - start);
		if (len == 1 && *start == '|')
			break; /* another form of the command begins: the first one is asked for */
		if (*start == '[' || len >= 48)
			continue;
		memcpy(tok[n], start, len);
		tok[n][len] = '\0';
		n++;
	}
	return n;
}

/* the line's words after its first skip words that are not key=value: the arguments given */
static int
given_args(const char *line, int skip)
{
	int n = 0, word = 0;
	const char *p = line;
	while (*p) {
		while (*p == ' ' || *p == '\t')
			p++;
		if (!*p)
			break;
		int keyed = 0;
		if (*p == '"') { /* a quoted word, as the protocol's words are */
			for (p++; *p && *p != '"'; p++)
				p += *p == '\\' && p[1];
			p += *p == '"';
		} else {
			for (; *p && *p != ' ' && *p != '\t'; p++)
				keyed |= *p == '=';
		}
		if (word++ >= skip && !keyed)
			n++;
	}
	return n;
}

static void
describe(struct prompt_arg *a, const char *w)
{
	snprintf(a->word, sizeof a->word, "%s", w);
	size_t len = strlen(a->word);
	if (len > 3 && !strcmp(a->word + len - 3, "..."))
		a->word[len - 3] = '\0';
	const char *x = a->word;
	if (strchr(x, '|') && all_lower(x)) {
		a->kind = PROMPT_CHOICE;
		/* "a|b|c" asks "a, b or c?" */
		const char *last = strrchr(x, '|');
		size_t n = 0;
		for (const char *c = x; c < last && n + 3 < sizeof a->question; c++) {
			if (*c == '|') {
				a->question[n++] = ',';
				a->question[n++] = ' ';
			} else {
				a->question[n++] = *c;
			}
		}
		snprintf(a->question + n, sizeof a->question - n, " or %s?", last + 1);
		return;
	}
	static const struct {
		const char *word;
		enum prompt_kind kind;
		const char *question;
	} known[] = {
		{ "FIG", PROMPT_FIGURE, "select a figure" },
		{ "OBJ", PROMPT_FIGURE, "select an object" },
		{ "OBJ[.SEGMENT]", PROMPT_FIGURE, "select an object" },
		{ "JOINT", PROMPT_JOINT, "select a joint" },
		{ "SEG.SITE", PROMPT_SITE, "select a site" },
		{ "VIEW", PROMPT_VIEW, "select a view" },
		{ "CON", PROMPT_CONSTRAINT, "which constraint?" },
	};
	for (size_t i = 0; i < sizeof known / sizeof *known; i++)
		if (!strcmp(x, known[i].word)) {
			a->kind = known[i].kind;
			snprintf(a->question, sizeof a->question, "%s", known[i].question);
			return;
		}
	a->kind = PROMPT_VALUE;
	char q[48];
	size_t i = 0;
	for (; x[i] && i + 1 < sizeof q; i++)
		q[i] = x[i] == '|' ? '/' : (char)tolower((unsigned char)x[i]);
	q[i] = '\0';
	snprintf(a->question, sizeof a->question, "%s?", q);
}

int
prompt_begin(struct prompt *p, const char *usage, const char *line)
{
	p->active = 0;
	p->narg = p->next = 0;
	if (strlen(line) > PROMPT_LINE_MAX)
		return -1;
	char tok[TOKENS_MAX][48];
	int ntok = usage_tokens(usage, tok, TOKENS_MAX), literal = 0;
	/* the command's own words: lowercase, no alternatives, no key */
	while (literal < ntok && all_lower(tok[literal]) && !strchr(tok[literal], '|') &&
	       !strchr(tok[literal], '='))
		literal++;
	int given = given_args(line, literal), k = 0;
	for (int i = literal; i < ntok; i++) {
		if (strchr(tok[i], '=') || (all_lower(tok[i]) && !strchr(tok[i], '|')))
			continue; /* key=VALUE, or a literal word inside the arguments */
		if (k++ < given)
			continue;
		if (p->narg == PROMPT_ARGS_MAX)
			break;
		describe(&p->arg[p->narg++], tok[i]);
	}
	if (!p->narg)
		return 0;
	snprintf(p->line, sizeof p->line, "%s", line);
	size_t len = strlen(p->line);
	while (len && (p->line[len - 1] == ' ' || p->line[len - 1] == '\t'))
		p->line[--len] = '\0';
	p->active = 1;
	return 1;
}

const struct prompt_arg *
prompt_asking(const struct prompt *p)
{
	return p->active && p->next < p->narg ? &p->arg[p->next] : NULL;
}

int
prompt_answer(struct prompt *p, const char *word)
{
	if (!prompt_asking(p) || !word[0])
		return -1;
	int quote = strpbrk(word, " \t\"#") != NULL;
	if (quote && strchr(word, '"'))
		return -1; /* a word with a quote of its own: not worth escaping here */
	size_t len = strlen(p->line), add = strlen(word) + (quote ? 3 : 1);
	if (len + add > PROMPT_LINE_MAX)
		return -1;
	snprintf(p->line + len, sizeof p->line - len, quote ? " \"%s\"" : " %s", word);
	if (++p->next < p->narg)
		return 0;
	p->active = 0;
	return 1;
}

const char *
prompt_line(const struct prompt *p)
{
	return p->line;
}

void
prompt_cancel(struct prompt *p)
{
	p->active = 0;
	p->narg = p->next = 0;
}
