/*
 * fuzz_session.c - a session file (daemon/session.h: what `load session`
 * reads), or a journal's snapshot when an "undo" line follows its "end"
 * line (journal_state_read: the session, then the undo and redo
 * checkpoints), read from memory. Figure files are read from
 * tests/figures and lib: ones from src/figure/library (POSTURE_FUZZ_FIGURES
 * and POSTURE_FUZZ_LIBRARY name others). A refused session names its line
 * and leaves the environment empty; a session it accepts is written, read
 * back and written again to the same text.
 *
 * Inputs are kept to 8 KiB, two or three humans with their postures:
 * longer ones only repeat statements, at a figure each.
 *
 * fuzz-options: -max_len=8192
 * fuzz-link: -Wl,--wrap=human_build,--wrap=figure_read_file
 */
#define _GNU_SOURCE /* memmem */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/journal.h"
#include "model_cache.h"
#include "daemon/session.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
const char *__asan_default_options(void);

/* freed memory held back 8 MiB, not 256: an input frees megabytes of figures, and
 * fresh pages for every allocation were half of its time */
const char *
__asan_default_options(void)
{
	return "quarantine_size_mb=8";
}

static struct daemon d;
static struct env back;

static char *
written(const struct env *e, size_t *n)
{
	char *text = session_to_string(e, n);
	if (!text)
		abort();
	return text;
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static int ready;
	if (!ready) {
		const char *dir = getenv("POSTURE_FUZZ_FIGURES"), *lib = getenv("POSTURE_FUZZ_LIBRARY");
		snprintf(d.state_dir, sizeof d.state_dir, "%s", dir ? dir : "tests/figures");
		snprintf(d.library_dir, sizeof d.library_dir, "%s", lib ? lib : "src/figure/library");
		env_init(&d.env);
		env_init(&back);
		ready = 1;
	}
	const char *text = (const char *)data;
	char err[512];
	int snapshot = memmem(text, size, "\nend\nundo ", 10) != NULL, rc;
	if (snapshot) /* a refused snapshot stops the daemon: what it left does not matter */
		rc = journal_state_read(&d, text, size, err, sizeof err);
	else
		rc = session_read(text, size, d.state_dir, d.library_dir, &d.env, err, sizeof err);
	if (rc == 0) {
		size_t n, n2;
		char *once = written(&d.env, &n);
		if (session_read(once, n, d.state_dir, d.library_dir, &back, err, sizeof err) < 0) {
			fprintf(stderr, "the written session does not read back: %s\n%s", err, once);
			abort();
		}
		char *twice = written(&back, &n2);
		if (n != n2 || memcmp(once, twice, n)) {
			fprintf(stderr, "written, read and written again:\n%s----\n%s", once, twice);
			abort();
		}
		free(once);
		free(twice);
	} else if (!snapshot && (env_count(&d.env) || strncmp(err, "line ", 5))) {
		abort(); /* a refused session left figures behind */
	}
	daemon_checkpoints_clear(&d.undo);
	daemon_checkpoints_clear(&d.redo);
	env_clear(&d.env);
	env_init(&d.env);
	env_clear(&back);
	env_init(&back);
	return 0;
}
