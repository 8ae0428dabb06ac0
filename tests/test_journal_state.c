/*
 * test_journal_state.c - a snapshot's state (journal_state_read) is read
 * within the length it is given: the text is put at the very end of a
 * page before an inaccessible one, with no NUL after it, so a read past
 * its end faults. The undo history's lines used to be read with sscanf,
 * which runs to a NUL (found by the session fuzzer).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "daemon/journal.h"

/* text copied to end where an inaccessible page begins */
static char *
at_page_end(char **map, size_t *maplen, const char *text, size_t len)
{
	size_t page = (size_t)sysconf(_SC_PAGESIZE);
	*maplen = 2 * page;
	*map = mmap(NULL, *maplen, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
	assert_true(*map != MAP_FAILED && len <= page);
	assert_int_equal(mprotect(*map + page, page, PROT_NONE), 0);
	char *at = *map + page - len;
	memcpy(at, text, len);
	return at;
}

static void
test_the_undo_history_is_read_within_its_length(void **unused)
{
	(void)unused;
	static const char *const texts[] = {
		"session 1\nend\nundo",
		"session 1\nend\nundo 1",
		"session 1\nend\nundo 1\ncheckpoint",
		"session 1\nend\nundo 1\ncheckpoint 5",
		"session 1\nend\nundo 0\nredo 1\ncheckpoint 3\nab",
		"session 1\nend\nundo 0\nredo",
	};
	for (size_t i = 0; i < sizeof texts / sizeof texts[0]; i++) {
		static struct daemon d;
		char *map, err[300];
		size_t maplen, len = strlen(texts[i]);
		const char *text = at_page_end(&map, &maplen, texts[i], len);
		env_init(&d.env);
		assert_int_equal(journal_state_read(&d, text, len, err, sizeof err), -1);
		assert_string_equal(err, "bad undo history");
		daemon_checkpoints_clear(&d.undo);
		daemon_checkpoints_clear(&d.redo);
		env_clear(&d.env);
		munmap(map, maplen);
	}
	/* whole, it reads */
	static struct daemon d;
	const char *whole = "session 1\nend\nundo 1\ncheckpoint 3\nabcredo 0\n";
	char *map, err[300];
	size_t maplen;
	const char *text = at_page_end(&map, &maplen, whole, strlen(whole));
	env_init(&d.env);
	assert_int_equal(journal_state_read(&d, text, strlen(whole), err, sizeof err), 0);
	assert_int_equal(d.undo.n, 1);
	assert_int_equal(d.undo.len[0], 3);
	assert_memory_equal(d.undo.text[0], "abc", 3);
	assert_int_equal(d.redo.n, 0);
	daemon_checkpoints_clear(&d.undo);
	env_clear(&d.env);
	munmap(map, maplen);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_the_undo_history_is_read_within_its_length),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
