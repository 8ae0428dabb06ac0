/*
 * fuzz_rec_hid.c - the hid-recorder reader on any bytes: no crash, nothing
 * undefined, a refusal names the file and line, and a recording it accepts
 * is written and read back as the same recording.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "devices/rec_hid.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static struct rec_hid r, back;

static int
same(const struct rec_hid *a, const struct rec_hid *b)
{
	if (a->ndevices != b->ndevices || a->nevents != b->nevents)
		return 0;
	for (unsigned i = 0; i < a->ndevices; i++) {
		const struct rec_hid_device *x = &a->devices[i], *y = &b->devices[i];
		if (strcmp(x->name, y->name) || strcmp(x->phys, y->phys) || x->bus != y->bus ||
		    x->vid != y->vid || x->pid != y->pid || x->desc_len != y->desc_len ||
		    memcmp(x->desc, y->desc, x->desc_len))
			return 0;
	}
	for (size_t i = 0; i < a->nevents; i++) {
		const struct rec_hid_event *x = &a->events[i], *y = &b->events[i];
		if (x->t_us != y->t_us || x->device != y->device || x->len != y->len ||
		    memcmp(x->bytes, y->bytes, x->len))
			return 0;
	}
	return 1;
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	char err[256];
	if (rec_hid_parse((const char *)data, size, "fuzz", &r, err, sizeof err) != 0) {
		if (strncmp(err, "fuzz:", 5) != 0 || r.events || r.ndevices)
			abort();
		return 0;
	}
	char *buf = NULL;
	size_t n = 0;
	FILE *out = open_memstream(&buf, &n);
	if (!out || rec_hid_write(out, &r) != 0)
		abort();
	fclose(out);
	if (rec_hid_parse(buf, n, "again", &back, err, sizeof err) != 0 || !same(&r, &back))
		abort();
	free(buf);
	rec_hid_free(&r);
	rec_hid_free(&back);
	return 0;
}
