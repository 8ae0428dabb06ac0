/* test_journal_scan.c - the journal's record lines: the checksum, and damage told apart */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/journal_scan.h"

/* CRC-32/ISO-HDLC's published check value: the CRC of "123456789" is cbf43926 */
static void
test_the_checksum_is_crc32(void **unused)
{
	(void)unused;
	assert_int_equal(journal_crc32(0, "123456789", 9), 0xcbf43926u);
	assert_int_equal(journal_crc32(0, "", 0), 0);
	/* continued: the same as at once */
	assert_int_equal(journal_crc32(journal_crc32(0, "1234", 4), "56789", 5), 0xcbf43926u);
}

static void
test_a_record_is_its_line_and_its_checksum(void **unused)
{
	(void)unused;
	size_t n;
	char *rec = journal_record_format(12, 'C', "load human as jack", 18, &n);
	char want[64];
	snprintf(want, sizeof want, "12 C load human as jack %08x\n",
		 journal_crc32(0, "12 C load human as jack", 23));
	assert_int_equal(n, strlen(want));
	assert_memory_equal(rec, want, n);
	struct journal_record r;
	const char *why;
	assert_int_equal(journal_record_parse(rec, n - 1, &r, &why), 0);
	assert_true(r.seq == 12 && r.kind == 'C' && r.len == 18);
	assert_memory_equal(r.body, "load human as jack", 18);
	/* any byte changed: its checksum does not match */
	for (size_t i = 0; i < n - 10; i++) {
		rec[i] ^= 0x04;
		assert_int_equal(journal_record_parse(rec, n - 1, &r, &why), -1);
		assert_string_equal(why, "its checksum does not match");
		rec[i] ^= 0x04;
	}
	free(rec);
	/* an empty body; the largest number */
	rec = journal_record_format(UINT64_MAX, 'E', "", 0, &n);
	assert_int_equal(journal_record_parse(rec, n - 1, &r, &why), 0);
	assert_true(r.seq == UINT64_MAX && r.kind == 'E' && r.len == 0);
	free(rec);
	/* the old form, with no checksum, and a checksum in capitals are not records */
	assert_int_equal(journal_record_parse("12 C load human as jack", 23, &r, &why), -1);
	assert_string_equal(why, "not a record");
	snprintf(want, sizeof want, "12 C x %08X", journal_crc32(0, "12 C x", 6));
	assert_int_equal(journal_record_parse(want, strlen(want), &r, &why), -1);
}

/* a journal of records 5, 6, 7 */
static char *
journal3(size_t *len, size_t ends[3])
{
	static const char *const bodies[] = { "load human as jack", "-", "set joint jack knee_l 30deg" };
	static const char kinds[] = { 'C', 'B', 'C' };
	char *text = NULL;
	FILE *f = open_memstream(&text, len);
	for (int i = 0; i < 3; i++) {
		size_t n;
		char *rec = journal_record_format(5 + (uint64_t)i, kinds[i], bodies[i], strlen(bodies[i]), &n);
		fwrite(rec, 1, n, f);
		fflush(f);
		ends[i] = *len;
		free(rec);
	}
	fclose(f);
	return text;
}

static void
test_whole_records_and_a_damaged_tail(void **unused)
{
	(void)unused;
	size_t len, end[3];
	char *text = journal3(&len, end);
	struct journal_scan s;
	journal_scan(text, len, &s);
	assert_int_equal(s.damage, JOURNAL_WHOLE);
	assert_true(s.good == len && s.records == 3 && s.last_seq == 7);
	journal_scan(text, 0, &s);
	assert_true(s.damage == JOURNAL_WHOLE && s.good == 0 && s.records == 0);

	/* torn anywhere in the last record */
	for (size_t cut = end[1] + 1; cut < len; cut++) {
		journal_scan(text, cut, &s);
		assert_int_equal(s.damage, JOURNAL_TAIL);
		assert_true(s.good == end[1] && s.records == 2 && s.last_seq == 6);
		assert_string_equal(s.why, "a record cut short, with no end of line");
	}
	/* a flipped bit anywhere in it, its newline included */
	for (size_t i = end[1]; i < len; i++) {
		text[i] ^= 0x20;
		journal_scan(text, len, &s);
		assert_int_equal(s.damage, JOURNAL_TAIL);
		assert_true(s.good == end[1] && s.last_seq == 6);
		text[i] ^= 0x20;
	}
	/* zero bytes over its end, and after a whole journal */
	char *z = calloc(1, len + 4096);
	memcpy(z, text, len - 7);
	journal_scan(z, len, &s);
	assert_true(s.damage == JOURNAL_TAIL && s.good == end[1]);
	assert_string_equal(s.why, "a record cut short, with no end of line");
	memcpy(z, text, len);
	journal_scan(z, len + 4096, &s);
	assert_true(s.damage == JOURNAL_TAIL && s.good == len && s.last_seq == 7);
	assert_string_equal(s.why, "zero bytes");
	free(z);
	free(text);
}

static void
test_damage_with_a_whole_record_after_it_is_in_the_middle(void **unused)
{
	(void)unused;
	size_t len, end[3];
	char *text = journal3(&len, end);
	struct journal_scan s;
	text[end[0] + 1] ^= 0x01; /* record 6's kind: B -> C */
	journal_scan(text, len, &s);
	assert_int_equal(s.damage, JOURNAL_MIDDLE);
	assert_true(s.good == end[0] && s.records == 1 && s.last_seq == 5);
	assert_true(s.next == end[1] && s.next_seq == 7);
	assert_string_equal(s.why, "its checksum does not match");
	text[end[0] + 1] ^= 0x01;

	/* whole records out of order: 5, 7 */
	size_t n;
	char *r5 = journal_record_format(5, 'C', "a", 1, &n), *r7 = journal_record_format(7, 'C', "b", 1, &n);
	char two[64];
	snprintf(two, sizeof two, "%.*s%.*s", (int)n, r5, (int)n, r7);
	journal_scan(two, 2 * n, &s);
	assert_true(s.damage == JOURNAL_MIDDLE && s.good == n && s.next == n && s.next_seq == 7);
	assert_string_equal(s.why, "a record out of order");
	free(r5);
	free(r7);
	free(text);
}

/* a journal written before checksums is read as it was written; one with a record of
 * today's after such lines is not, and its first line is damage in the middle */
static void
test_a_journal_of_before_checksums_is_read_without_them(void **unused)
{
	(void)unused;
	const char *old = "1 C load human as jack\n2 C behave jack on\n3 P q jack 0.5,0.25\n";
	struct journal_scan s;
	journal_scan(old, strlen(old), &s);
	assert_true(s.unchecked);
	assert_int_equal(s.damage, JOURNAL_WHOLE);
	assert_int_equal(s.records, 3);
	assert_int_equal(s.good, strlen(old));
	/* torn as a crash tears it: the piece without its end of line is the tail */
	const char *torn = "1 C load human as jack\n2 C behave jack on\n3 P q jack 0.";
	journal_scan(torn, strlen(torn), &s);
	assert_true(s.unchecked);
	assert_int_equal(s.damage, JOURNAL_TAIL);
	assert_int_equal(s.records, 2);
	/* a line of before, then a record with its checksum: not a journal of before */
	size_t n;
	char *rec = journal_record_format(2, 'C', "behave jack on", 14, &n);
	char mixed[200];
	snprintf(mixed, sizeof mixed, "1 C load human as jack\n%.*s", (int)n, rec);
	free(rec);
	journal_scan(mixed, strlen(mixed), &s);
	assert_false(s.unchecked);
	assert_int_equal(s.damage, JOURNAL_MIDDLE);
	assert_int_equal(s.records, 0);
	/* today's journals are never read without their checksums */
	rec = journal_record_format(1, 'C', "load human as jack", 18, &n);
	journal_scan(rec, n, &s);
	free(rec);
	assert_false(s.unchecked);
	assert_int_equal(s.records, 1);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_the_checksum_is_crc32),
		cmocka_unit_test(test_a_record_is_its_line_and_its_checksum),
		cmocka_unit_test(test_whole_records_and_a_damaged_tail),
		cmocka_unit_test(test_damage_with_a_whole_record_after_it_is_in_the_middle),
		cmocka_unit_test(test_a_journal_of_before_checksums_is_read_without_them),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
