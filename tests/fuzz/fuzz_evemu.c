/*
 * fuzz_evemu.c - the evemu reader on any text. What it accepts must
 * write and read back the same, and replay through the evdev decoder.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "devices/rec_evemu.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static struct input_queue q;
static struct evdev_input e;

static void
same_or_abort(const struct rec_evemu *a, const struct rec_evemu *b)
{
	if (a->described != b->described || strcmp(a->name, b->name) ||
	    a->bustype != b->bustype || a->vendor != b->vendor || a->product != b->product ||
	    a->version != b->version || memcmp(a->props, b->props, sizeof a->props) ||
	    memcmp(a->bits, b->bits, sizeof a->bits) || memcmp(a->abs, b->abs, sizeof a->abs) ||
	    memcmp(a->abs_given, b->abs_given, sizeof a->abs_given) ||
	    memcmp(a->led, b->led, sizeof a->led) || memcmp(a->sw, b->sw, sizeof a->sw) ||
	    a->nev != b->nev)
		abort();
	for (size_t i = 0; i < a->nev; i++)
		if (a->ev[i].t_us != b->ev[i].t_us || a->ev[i].sec != b->ev[i].sec ||
		    a->ev[i].usec != b->ev[i].usec || a->ev[i].type != b->ev[i].type ||
		    a->ev[i].code != b->ev[i].code || a->ev[i].value != b->ev[i].value)
			abort();
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct rec_evemu r, back;
	char err[256];
	if (rec_evemu_parse((const char *)data, size, "fuzz", &r, err, sizeof err)) {
		if (strncmp(err, "fuzz:", 5) || r.ev || r.nev)
			abort();
		return 0;
	}
	/* written and read back: the same recording */
	char *text = NULL;
	size_t len = 0;
	FILE *m = open_memstream(&text, &len);
	if (!m || rec_evemu_write(m, &r))
		abort();
	fclose(m);
	if (rec_evemu_parse(text, len, "written", &back, err, sizeof err))
		abort();
	same_or_abort(&r, &back);
	free(text);
	rec_evemu_free(&back);
	/* and through the device's path */
	size_t need = rec_evemu_to_records(&r, NULL, 0);
	uint8_t *bytes = malloc(need ? need : 1);
	if (rec_evemu_to_records(&r, bytes, need) != need)
		abort();
	input_queue_init(&q);
	evdev_input_init(&e, 1, "fuzz");
	e.log.out = fopen("/dev/null", "w");
	rec_evemu_apply_abs(&r, &e);
	if (evdev_input_feed(&e, bytes, need, &q))
		abort();
	fclose(e.log.out);
	free(bytes);
	rec_evemu_free(&r);
	return 0;
}
