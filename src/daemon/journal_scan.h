/*
 * journal_scan.h - the journal's records as bytes: each one a line
 * "SEQ KIND BODY CRC", CRC the CRC-32 (IEEE 802.3, zlib's crc32) of the
 * line before its last space, as 8 lowercase hex digits; and a journal's
 * text scanned for the whole records it starts with.
 *
 * A crash, a full disk or a flipped bit leaves damage at the end of the
 * file: a record cut short, zero bytes, a record whose checksum no longer
 * matches. What follows the last whole record is then the damaged tail,
 * dropped on recovery. Damage with whole records after it is in the
 * middle: a crash cannot cause it, and recovery refuses rather than drop
 * acknowledged records after it (journal.h).
 */
#ifndef POSTURE_JOURNAL_SCAN_H
#define POSTURE_JOURNAL_SCAN_H

#include <stddef.h>
#include <stdint.h>

/* the CRC-32 of n bytes, continuing from crc (0 to start) */
uint32_t journal_crc32(uint32_t crc, const void *p, size_t n);

/*
 * The record "SEQ KIND BODY CRC\n" in a malloc'd buffer of *n bytes (no
 * NUL); body holds no newline. NULL when out of memory.
 */
char *journal_record_format(uint64_t seq, char kind, const char *body, size_t len, size_t *n);

struct journal_record {
	uint64_t seq;
	char kind;
	const char *body; /* inside the scanned text, not NUL-terminated */
	size_t len;
};

/*
 * One line (without its newline) as a record: 0, or -1 with what is wrong
 * in *why (a constant string): not a record, or a checksum that does not
 * match.
 */
int journal_record_parse(const char *line, size_t len, struct journal_record *r, const char **why);

/*
 * A record as journals wrote them before records had checksums, "SEQ KIND
 * BODY" with nothing after the body: 0, or -1 with *why.
 */
int journal_record_parse_unchecked(const char *line, size_t len, struct journal_record *r,
				   const char **why);

enum journal_damage {
	JOURNAL_WHOLE,  /* nothing but whole records */
	JOURNAL_TAIL,   /* whole records, then bytes that are none: dropped */
	JOURNAL_MIDDLE, /* damage with a whole record after it: refused */
};

struct journal_scan {
	enum journal_damage damage;
	size_t good;       /* bytes of whole, numbered-in-order records from the start */
	uint64_t records;  /* how many */
	uint64_t last_seq; /* the last one's number (0: none) */
	const char *why;   /* what is wrong at byte good (damage only) */
	int unchecked;     /* written before checksums: records without them, read as such */
	size_t next;       /* JOURNAL_MIDDLE: the byte where the first whole record after it starts */
	uint64_t next_seq; /* ... and its number */
};

/*
 * Scans a journal's text. Records follow each other by number (each one's
 * SEQ the one before it plus 1); the first may have any number.
 */
void journal_scan(const char *text, size_t len, struct journal_scan *s);

/* one line as a record of the kind the scan found the journal written in */
int journal_scan_parse(const struct journal_scan *s, const char *line, size_t len,
		       struct journal_record *r, const char **why);

#endif
