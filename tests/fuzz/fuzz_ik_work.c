/*
 * fuzz_ik_work.c - lines of a frame log through ik_work_read; whatever it
 * accepts must write back to a line that reads as the same record.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "pose/ik_work.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static char line[4096];
	char err[160], again[IK_WORK_LINE_MAX];
	struct ik_work w, back;
	if (size > sizeof line - 1)
		size = sizeof line - 1;
	memcpy(line, data, size);
	line[size] = '\0';
	if (ik_work_read(line, &w, err, sizeof err) < 0)
		return 0;
	if (ik_work_write(&w, again, sizeof again) < 0 ||
	    ik_work_read(again, &back, err, sizeof err) < 0 || !ik_work_equal(&w, &back))
		abort();
	return 0;
}
