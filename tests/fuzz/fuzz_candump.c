/*
 * fuzz_candump.c - the candump log reader on any bytes: no crash, and a log
 * it accepts is written and read back as the same frames.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "devices/rec_candump.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct rec_candump r, back;
	char err[256];
	if (rec_candump_parse((const char *)data, size, "fuzz", &r, err, sizeof err))
		return 0;
	char *text = NULL;
	size_t n = 0;
	FILE *f = open_memstream(&text, &n);
	if (rec_candump_write(f, &r))
		abort();
	fclose(f);
	if (rec_candump_parse(text, n, "written", &back, err, sizeof err))
		abort();
	if (back.n != r.n || back.nanoseconds != r.nanoseconds)
		abort();
	for (size_t i = 0; i < r.n; i++) {
		const struct rec_candump_frame *a = &r.frames[i], *b = &back.frames[i];
		if (a->t_abs_us != b->t_abs_us || a->t_ns != b->t_ns || a->t_us != b->t_us ||
		    strcmp(a->iface, b->iface) || a->can_id != b->can_id || a->len != b->len ||
		    a->len8_dlc != b->len8_dlc || memcmp(a->data, b->data, 8) || a->dir != b->dir)
			abort();
	}
	free(text);
	rec_candump_free(&r);
	rec_candump_free(&back);
	return 0;
}
