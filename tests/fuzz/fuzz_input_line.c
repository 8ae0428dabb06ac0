/*
 * fuzz_input_line.c - `input ...` request lines through the real dispatch
 * (word splitting, the command table, the input handlers) into the queue.
 * The fuzzer's bytes follow "input " on one line.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/cmd.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static struct daemon d;
static struct input_queue q;

static void
setup(void)
{
	static int done;
	if (done)
		return;
	done = 1;
	env_init(&d.env);
	input_queue_init(&q);
	d.input = &q;
	struct cmd_outcome out;
	const char *view = "add view front width=320 height=240 eye=0,1.2,3 target=0,1,0";
	cmd_run(&d, -1, view, strlen(view), &out);
	free(out.json);
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static char line[70000];
	setup();
	if (size > sizeof line - 8)
		size = sizeof line - 8;
	memcpy(line, "input ", 6);
	memcpy(line + 6, data, size);
	struct cmd_outcome out;
	cmd_run(&d, 0, line, size + 6, &out);
	free(out.json);
	struct input_event_rec e;
	while (input_queue_pop(&q, &e))
		;
	return 0;
}
