/*
 * fuzz_can_map.c - the panel map parser on any bytes: no crash, and a map
 * it accepts is written and read back as the same map, and decodes a frame
 * taken from the input without trouble.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "devices/can_input.h"
#include "devices/can_map.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static struct can_map m, back;

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	char err[256];
	if (can_map_parse((const char *)data, size, "fuzz", &m, err, sizeof err))
		return 0;
	/* written and read back: the same */
	char *text = NULL;
	size_t n = 0;
	FILE *f = open_memstream(&text, &n);
	if (can_map_write(f, &m))
		abort();
	fclose(f);
	if (can_map_parse(text, n, "written", &back, err, sizeof err))
		abort();
	if (back.n != m.n || memcmp(back.line, m.line, (size_t)m.n * sizeof m.line[0]))
		abort();
	free(text);
	/* a frame of each id decodes */
	uint8_t frame[8] = { 0 };
	memcpy(frame, data, size < 8 ? size : 8);
	int lines[CAN_MAP_MAX_LINES];
	double vals[CAN_MAP_MAX_LINES];
	for (int j = 0; j < m.n_ids; j++)
		for (int len = 0; len <= 8; len += 3)
			if (can_input_decode(&m, m.ids[j], frame, len, lines, vals,
					     CAN_MAP_MAX_LINES) > m.n)
				abort();
	return 0;
}
