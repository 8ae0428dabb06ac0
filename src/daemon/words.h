/*
 * words.h - one request line split into words (docs/protocol.md "Words"), and
 * the number and list readers the command handlers share.
 */
#ifndef POSTURE_WORDS_H
#define POSTURE_WORDS_H

#include <stddef.h>

#define WORDS_MAX 64          /* words in a line */
#define WORDS_LINE_MAX 65536  /* bytes in a line */

struct words {
	int n;
	char *w[WORDS_MAX];
	char buf[WORDS_LINE_MAX + 1];
	char tag[48]; /* "#TAG" prefix, without the '#'; empty when none */
};

enum words_status {
	WORDS_OK,
	WORDS_EMPTY,    /* blank or a % comment: no reply */
	WORDS_PARSE,    /* unbalanced quote, bad escape, bad tag */
	WORDS_TOO_MANY, /* more than WORDS_MAX words */
};

/* splits line (len bytes, no newline) into dest; on error msg says why */
enum words_status words_split(const char *line, size_t len, struct words *dest, const char **msg);

/* the kind of unit a number may carry */
enum unit_kind {
	UNIT_LENGTH,
	UNIT_ANGLE,
	UNIT_NONE,
};

/* a finite number with an optional unit of the kind; 0 or -1 */
int words_number(const char *s, enum unit_kind kind, double *dest);

/* "a,b,c": exactly n numbers of the kind; 0 or -1 */
int words_list(const char *s, enum unit_kind kind, int n, double *dest);

/* for "key=value" returns value and sets *klen; NULL when the word has no '=' */
const char *words_value(const char *word, size_t *klen);

/* 1 when word is "key=..." for this key */
int words_is_key(const char *word, const char *key);

/* a name: [A-Za-z_][A-Za-z0-9_]* shorter than 48 bytes */
int words_is_name(const char *s);

#endif
