/* journal_scan.c - the journal's record lines: written with a checksum, checked on reading */
#include "daemon/journal_scan.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* the reflected CRC-32 polynomial 0xedb88320 a nibble at a time: 16 entries, no setup */
static const uint32_t crc_nibble[16] = {
	0x00000000, 0x1db71064, 0x3b6e20c8, 0x26d930ac, 0x76dc4190, 0x6b6b51f4,
	0x4db26158, 0x5005713c, 0xedb88320, 0xf00f9344, 0xd6d6a3e8, 0xcb61b38c,
	0x9b64c2b0, 0x86d3d2d4, 0xa00ae278, 0xbdbdf21c,
};

uint32_t
journal_crc32(uint32_t crc, const void *p, size_t n)
{
	const unsigned char *b = p;
	crc = ~crc;
	for (size_t i = 0; i < n; i++) {
		crc ^= b[i];
		crc = (crc >> 4) ^ crc_nibble[crc & 15];
		crc = (crc >> 4) ^ crc_nibble[crc & 15];
	}
	return ~crc;
}

char *
journal_record_format(uint64_t seq, char kind, const char *body, size_t len, size_t *n)
{
	char head[32];
	int h = snprintf(head, sizeof head, "%" PRIu64 " %c ", seq, kind);
	/* the head, the body, " CRC", the newline */
	char *buf = malloc((size_t)h + len + 11);
	if (!buf)
		return NULL;
	memcpy(buf, head, (size_t)h);
	memcpy(buf + h, body, len);
	size_t at = (size_t)h + len;
	uint32_t crc = journal_crc32(0, buf, at);
	snprintf(buf + at, 11, " %08" PRIx32, crc);
	buf[at + 9] = '\n';
	*n = at + 10;
	return buf;
}

static int
lower_hex(char c)
{
	return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
}

/* "SEQ KIND BODY" in the first n bytes of line: 0, or -1 */
static int
parse_head(const char *line, size_t n, struct journal_record *r)
{
	size_t i = 0;
	uint64_t seq = 0;
	for (; i < n && line[i] >= '0' && line[i] <= '9'; i++) {
		unsigned d = (unsigned)(line[i] - '0');
		if (seq > (UINT64_MAX - d) / 10)
			return -1;
		seq = seq * 10 + d;
	}
	/* a number without leading zeros, one printable kind between single spaces */
	if (i == 0 || line[0] == '0' || i + 3 > n || line[i] != ' ' || line[i + 1] <= ' ' ||
	    line[i + 1] > '~' || line[i + 2] != ' ')
		return -1;
	r->seq = seq;
	r->kind = line[i + 1];
	r->body = line + i + 3;
	r->len = n - (i + 3);
	return 0;
}

int
journal_record_parse(const char *line, size_t len, struct journal_record *r, const char **why)
{
	*why = "not a record";
	/* "1 C  xxxxxxxx" is the shortest: a number, a kind, an empty body, the checksum */
	if (len < 13 || line[len - 9] != ' ')
		return -1;
	uint32_t crc = 0;
	for (size_t i = len - 8; i < len; i++) {
		int v = lower_hex(line[i]);
		if (v < 0)
			return -1;
		crc = crc << 4 | (uint32_t)v;
	}
	size_t n = len - 9; /* the bytes the checksum covers */
	if (journal_crc32(0, line, n) != crc) {
		*why = "its checksum does not match";
		return -1;
	}
	return parse_head(line, n, r);
}

int
journal_record_parse_unchecked(const char *line, size_t len, struct journal_record *r,
			       const char **why)
{
	*why = "not a record";
	return parse_head(line, len, r);
}

/*
 * A journal written before records had checksums: its first line is a
 * record without one, and no line of it is a record with one.
 */
static int
written_before_checksums(const char *text, const char *end)
{
	struct journal_record r;
	const char *why;
	const char *nl = memchr(text, '\n', (size_t)(end - text));
	if (!nl || journal_record_parse(text, (size_t)(nl - text), &r, &why) == 0 ||
	    journal_record_parse_unchecked(text, (size_t)(nl - text), &r, &why) < 0)
		return 0;
	for (const char *p = text; p < end;) {
		nl = memchr(p, '\n', (size_t)(end - p));
		if (!nl)
			break;
		if (journal_record_parse(p, (size_t)(nl - p), &r, &why) == 0)
			return 0;
		p = nl + 1;
	}
	return 1;
}

static int
all_zero(const char *p, const char *end)
{
	for (; p < end; p++)
		if (*p)
			return 0;
	return 1;
}

/* damage at p: in the middle when a whole record follows it (from q on), else the tail */
static void
damaged(const char *text, const char *p, const char *q, const char *end, const char *why,
	struct journal_scan *s)
{
	s->why = all_zero(p, end) ? "zero bytes" : why;
	s->damage = JOURNAL_TAIL;
	while (q && q < end) {
		const char *nl = memchr(q, '\n', (size_t)(end - q));
		struct journal_record r;
		const char *ignored;
		if (!nl)
			break;
		if (journal_scan_parse(s, q, (size_t)(nl - q), &r, &ignored) == 0) {
			s->damage = JOURNAL_MIDDLE;
			s->next = (size_t)(q - text);
			s->next_seq = r.seq;
			return;
		}
		q = nl + 1;
	}
}

int
journal_scan_parse(const struct journal_scan *s, const char *line, size_t len,
		   struct journal_record *r, const char **why)
{
	return s->unchecked ? journal_record_parse_unchecked(line, len, r, why)
			    : journal_record_parse(line, len, r, why);
}

void
journal_scan(const char *text, size_t len, struct journal_scan *s)
{
	memset(s, 0, sizeof *s);
	const char *p = text, *end = text + len;
	s->unchecked = written_before_checksums(text, end);
	while (p < end) {
		const char *nl = memchr(p, '\n', (size_t)(end - p)), *why;
		struct journal_record r;
		if (!nl) {
			damaged(text, p, NULL, end, "a record cut short, with no end of line", s);
			return;
		}
		if (journal_scan_parse(s, p, (size_t)(nl - p), &r, &why) < 0) {
			damaged(text, p, nl + 1, end, why, s);
			return;
		}
		if (s->records && r.seq != s->last_seq + 1) {
			/* whole, but not the record due: itself the whole record after the damage */
			damaged(text, p, p, end, "a record out of order", s);
			return;
		}
		s->records++;
		s->last_seq = r.seq;
		p = nl + 1;
		s->good = (size_t)(p - text);
	}
	s->damage = JOURNAL_WHOLE;
}
