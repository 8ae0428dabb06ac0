/*
 * fuzz_config.c - postured's config file (daemon/settings.h: what --config
 * and a recording's config read), from memory through fmemopen. Whatever
 * it reads: no crash, leak or undefined behaviour. The reader says what is
 * wrong on stderr, closed for the harness.
 *
 * fuzz-options: -close_fd_mask=2
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/settings.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static struct settings s;
	if (size == 0)
		return 0; /* fmemopen takes no empty buffer */
	memset(&s, 0, sizeof s);
	FILE *f = fmemopen((void *)data, size, "r");
	if (!f)
		abort();
	settings_read(&s, f, "fuzz.conf");
	fclose(f);
	return 0;
}
