/*
 * textfile.h - a whole text file read into memory, for the readers of
 * maps and recordings (which all parse from a buffer, so that the fuzzers
 * reach them the same way).
 */
#ifndef POSTURE_DEVICES_TEXTFILE_H
#define POSTURE_DEVICES_TEXTFILE_H

#include <stddef.h>

#define TEXTFILE_MAX ((size_t)256 << 20) /* larger files are refused */

/*
 * The file at path, NUL-terminated, its length in *n: malloc'd, for the
 * caller to free. NULL with "path: why" in err when it cannot be opened or
 * read, is larger than TEXTFILE_MAX or memory runs out.
 */
char *textfile_read(const char *path, size_t *n, char *err, size_t errlen);

/*
 * Writes "name:line: " and the message into err (nothing when errlen is
 * 0), the form every reader's refusals take; name NULL: the message alone.
 * Returns -1, for "return textfile_fail(...)".
 */
int textfile_fail(char *err, size_t errlen, const char *name, unsigned line, const char *fmt, ...)
	__attribute__((format(printf, 5, 6)));

/* the value of a hexadecimal digit (either case), or -1: every reader of hex text uses it */
int textfile_hex_digit(char c);

/* the shortest %g form of v (15 to 17 digits) that reads back as v: a file written and read is v */
void textfile_number_write(char *dest, size_t n, double v);

#endif
