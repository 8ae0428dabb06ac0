/*
 * fuzz_dial_bind.c - the dial bindings' parser on any bytes: no crash; a
 * table it accepts is written, read back and written again to the same
 * text; and events made from the input give only finite deltas.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "interact/dial_feed.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static struct dial_bind t, back;

static char *
written(const struct dial_bind *b, size_t *n)
{
	char *text = NULL;
	FILE *f = open_memstream(&text, n);
	if (dial_bind_write(f, b))
		abort();
	fclose(f);
	return text;
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static const char *const names[] = { "Panel.Dial1", "Panel.Dial2", "Panel.Dial3" };
	static const struct dial_bind_names list = { names, 3 };
	const struct dial_bind_lookup lookup = { dial_bind_find_in_names, &list };
	char err[256];
	dial_bind_init(&t);
	if (dial_bind_parse((const char *)data, size, "fuzz", NULL, &t, err, sizeof err))
		return 0;
	/* written and read back: the same text */
	size_t n, n2;
	char *text = written(&t, &n);
	if (dial_bind_parse(text, n, "written", NULL, &back, err, sizeof err))
		abort();
	char *again = written(&back, &n2);
	if (n != n2 || memcmp(text, again, n))
		abort();
	free(again);
	free(text);
	/* events from the input's bytes */
	dial_bind_resolve(&t, &lookup);
	for (size_t i = 0; i + 10 <= size; i += 10) {
		struct input_event_rec e = { .kind = data[i] % 3 ? INPUT_VALUATOR : INPUT_BUTTON,
					     .flags = data[i + 1] & 1 ? INPUT_F_STALE : 0,
					     .code = (uint16_t)(data[i + 1] >> 1),
					     .value = data[i + 1] & 1 };
		memcpy(&e.x, data + i + 2, sizeof e.x);
		struct dial_action a;
		if (dial_bind_feed(&t, &e, &a, 1) == 1 && a.kind == DIAL_ACTION_MOVE &&
		    !isfinite(a.delta))
			abort();
	}
	return 0;
}
