/*
 * html.h - the pieces of an HTML file an export writes: text escaped so
 * that nothing in it is markup, and bytes as base64 (a picture inlined in
 * a data: URL). The writers take a stream; export_file.h puts it on disk.
 */
#ifndef POSTURE_HTML_H
#define POSTURE_HTML_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/*
 * Writes s as HTML text: & < > " ' as character references, so it is
 * safe in an element and in a quoted attribute; control characters but
 * tab and newline (not allowed in HTML) as U+FFFD. Bytes from 0x80 up
 * pass as they are (the file is UTF-8).
 */
void html_text(FILE *f, const char *s);

/* printf's format, then html_text; a result over 1023 bytes is cut there */
void html_textf(FILE *f, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* bytes as base64 (RFC 4648, with padding), no line breaks */
void html_base64(FILE *f, const uint8_t *p, size_t n);

#endif
