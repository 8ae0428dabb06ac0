/*
 * prompt.h - a command asks for its missing arguments one by one (§1.7):
 * "select a figure", "select a site", "angle?". From the
 * command's usage (proto/commands.def's) and the words typed so far, the
 * placeholders still missing are asked for in order; each answer is a
 * word, picked with the pointer (a figure, a joint, a site, a view) or
 * typed; when the last one comes the line is whole.
 *
 * Usage strings read as the command table writes them: lowercase literal
 * words; UPPERCASE placeholders (FIG, JOINT, SEG.SITE, VIEW, CON, X ...);
 * lowercase alternatives a|b|c; [optional parts] and key=VALUE words,
 * never asked for; VALUE... (one asked for, the rest optional); and
 * alternative forms split by " | ", of which the first is asked for.
 *
 * Pure: strings in, strings out; nothing allocated.
 */
#ifndef POSTURE_INTERACT_PROMPT_H
#define POSTURE_INTERACT_PROMPT_H

#include <stddef.h>

#define PROMPT_LINE_MAX 1024
#define PROMPT_ARGS_MAX 16

enum prompt_kind {
	PROMPT_FIGURE,     /* picked: the figure under the pointer */
	PROMPT_JOINT,      /* picked: the joint above the segment under the pointer */
	PROMPT_SITE,       /* picked: the site nearest the point under the pointer */
	PROMPT_VIEW,       /* picked: the view the pointer is in */
	PROMPT_CONSTRAINT, /* typed */
	PROMPT_CHOICE,     /* typed: one of the alternatives */
	PROMPT_VALUE,      /* typed: a number, a name, a path */
};

struct prompt_arg {
	enum prompt_kind kind;
	char word[48];      /* the placeholder as the usage writes it */
	char question[96];  /* "select a figure", "left or right?" */
};

struct prompt {
	int active;
	char line[PROMPT_LINE_MAX + 1]; /* the line so far: the typed words, then the answers */
	struct prompt_arg arg[PROMPT_ARGS_MAX];
	int narg, next;                 /* the placeholders missing, and the one asked now */
};

/*
 * Begins asking when the line lacks required arguments of usage (the line's
 * command's). Returns 1 with the first question ready, 0 when nothing is
 * missing (or the usage has nothing to ask), -1 for a line too long.
 */
int prompt_begin(struct prompt *p, const char *usage, const char *line);

/* the argument asked for now; NULL when not asking */
const struct prompt_arg *prompt_asking(const struct prompt *p);

/*
 * The answer to the question asked now: a word (quoted in the line when it
 * has spaces). Returns 1 when the line is now whole (prompt_line has it, and
 * the prompt is no longer active), 0 when the next question is ready, -1
 * for an empty or unusable answer (nothing changed: ask again).
 */
int prompt_answer(struct prompt *p, const char *word);

/* the line as it stands */
const char *prompt_line(const struct prompt *p);

void prompt_cancel(struct prompt *p);

#endif
