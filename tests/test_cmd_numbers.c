/*
 * test_cmd_numbers.c - whole numbers in requests (a view's size, a
 * constraint's group, settle's frames) far out of int's range: refused
 * with their error, nothing changed. They were cast to int before their
 * range was checked, which is undefined (the sanitizer build stopped on
 * width=3.2e85, found by the journal fuzzer replaying an add view).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>
#include <string.h>

#include "daemon/cmd.h"

static struct daemon d;

/* the reply's error code, or "" when it succeeded */
static const char *
run(const char *line)
{
	static char code[64];
	struct cmd_outcome out;
	cmd_run(&d, 0, line, strlen(line), &out);
	assert_non_null(out.json);
	const char *at = strstr(out.json, "\"code\":\"");
	code[0] = 0;
	if (!out.ok && at) {
		at += 8;
		size_t n = strcspn(at, "\"");
		memcpy(code, at, n < sizeof code ? n : sizeof code - 1);
		code[n < sizeof code ? n : sizeof code - 1] = 0;
	}
	free(out.json);
	return code;
}

static void
test_whole_numbers_out_of_int_range_are_refused(void **unused)
{
	(void)unused;
	env_init(&d.env);
	assert_string_equal(run("load human as h"), "");
	static const struct {
		const char *line, *code;
	} cases[] = {
		{ "add view v width=3.2e85", "bad-number" },
		{ "add view v height=-4e40", "bad-number" },
		{ "add view v width=2147483648", "bad-number" },
		{ "add constraint h effector=hand_r.palm group=1e40", "bad-argument" },
		{ "add constraint h effector=hand_r.palm group=-3e9", "bad-argument" },
		{ "settle frames=1e300", "bad-argument" },
		{ "settle frames=-9e18", "bad-argument" },
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
		if (strcmp(run(cases[i].line), cases[i].code))
			fail_msg("'%s' gave '%s', not %s", cases[i].line, run(cases[i].line), cases[i].code);
	/* nothing was added */
	assert_false(d.env.view[0].used);
	for (int i = 0; i < ENV_MAX_CONSTRAINTS; i++)
		assert_int_equal(d.env.con[i].gen, 0);
	/* in range, they are taken */
	assert_string_equal(run("add view v width=320 height=240"), "");
	daemon_checkpoints_clear(&d.undo);
	daemon_checkpoints_clear(&d.redo);
	env_clear(&d.env);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_whole_numbers_out_of_int_range_are_refused),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
