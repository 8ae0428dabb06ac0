/*
 * fuzz_posture.c - a posture file (daemon/session.h: what `load posture`
 * reads) applied to the standard human, from memory. A refusal leaves the
 * figure as it was (the reader checks everything before changing
 * anything); a posture it accepts is written and read back onto a second
 * human to the same joint values and root, bit for bit.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/session.h"
#include "figure/human.h"
#include "figure/kin.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
const char *__asan_default_options(void);

/* freed memory held back 8 MiB, not 256: fresh pages for every allocation were a good
 * part of an input's time */
const char *
__asan_default_options(void)
{
	return "quarantine_size_mb=8";
}

static struct env e;

static void
add_human(const char *name)
{
	struct human_def hd = human_default_def(HUMAN_MALE);
	char err[256];
	struct model *m = human_build(&hd, err, sizeof err);
	if (!m || env_add_figure(&e, m, name, 1, &hd, NULL) < 0)
		abort();
}

/* the figure in slot fig back in its initial posture */
static uint64_t
reset(int fig)
{
	struct env_figure *f = &e.fig[fig];
	state_reset(f->model, f->state);
	kin_update(f->model, f->state);
	return state_hash(f->model, f->state);
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static int ready;
	if (!ready) {
		env_init(&e);
		add_human("jack");
		add_human("copy");
		ready = 1;
	}
	char err[512];
	uint64_t before = reset(0);
	const struct env_figure *f = &e.fig[0], *g = &e.fig[1];
	if (session_read_posture(&e, 0, (const char *)data, size, err, sizeof err) < 0) {
		if (state_hash(f->model, f->state) != before)
			abort(); /* a refused posture changed the figure */
		return 0;
	}
	char *text = NULL;
	size_t n = 0;
	FILE *out = open_memstream(&text, &n);
	if (!out || session_write_posture(&e, 0, out) < 0)
		abort();
	fclose(out);
	reset(1);
	if (session_read_posture(&e, 1, text, n, err, sizeof err) < 0) {
		fprintf(stderr, "the written posture does not read back: %s\n%s", err, text);
		abort();
	}
	if (state_hash(g->model, g->state) != state_hash(f->model, f->state))
		abort();
	free(text);
	return 0;
}
