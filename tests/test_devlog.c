/* test_devlog.c - rate-limited device log lines: the burst, the count, a device's last line */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "devices/devlog.h"

static int
count(const char *text, const char *what)
{
	int n = 0;
	for (const char *p = text; (p = strstr(p, what)); p++)
		n++;
	return n;
}

/* a burst per window, then silence and a count; a device's last line whatever the window */
static void
test_the_last_line_of_a_device_is_never_suppressed(void **unused)
{
	(void)unused;
	char *text = NULL;
	size_t len = 0;
	struct devlog l;
	devlog_init(&l, "panel (vcan0)");
	l.out = open_memstream(&text, &len);
	assert_non_null(l.out);
	for (int i = 0; i < DEVLOG_BURST + 3; i++)
		assert_int_equal(devlog(&l, 1000 + (uint64_t)i, DEVLOG_DEVICE, "frame %d", i),
				 i < DEVLOG_BURST);
	assert_int_equal(devlog_last(&l, 2000, DEVLOG_DEVICE, "interface vcan0 gone"), 1);
	/* the next window says how many were left out */
	assert_int_equal(devlog(&l, 2000 + DEVLOG_WINDOW_US, DEVLOG_KERNEL, "again"), 1);
	fclose(l.out);
	assert_int_equal(count(text, "posture: panel (vcan0): device fault: frame "), DEVLOG_BURST);
	assert_int_equal(count(text, "posture: panel (vcan0): device fault: interface vcan0 gone\n"), 1);
	assert_int_equal(count(text, "posture: panel (vcan0): 3 more lines suppressed\n"), 1);
	assert_int_equal(count(text, "posture: panel (vcan0): kernel: again\n"), 1);
	free(text);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_the_last_line_of_a_device_is_never_suppressed),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
