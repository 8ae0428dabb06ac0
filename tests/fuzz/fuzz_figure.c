/*
 * fuzz_figure.c - the figure language (figure/figure.h: what `load figure`
 * reads) through the lexer, parser and model builder, from memory. Mesh
 * paths are read relative to tests/figures (POSTURE_FUZZ_FIGURES names
 * another folder), where the seeds' meshes are. A refusal names the
 * origin; a figure it accepts is written, read back to an equal model, and
 * written again to the same text (figure.h: load -> save -> load).
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/figure.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char *
written(const struct model *m, size_t *n)
{
	char *text = NULL;
	FILE *f = open_memstream(&text, n);
	if (!f)
		abort();
	int rc = figure_write(m, f);
	fclose(f);
	if (rc < 0)
		abort(); /* whatever the reader accepts, the writer can express */
	return text;
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	const char *dir = getenv("POSTURE_FUZZ_FIGURES");
	char err[1024];
	if (!dir)
		dir = "tests/figures";
	struct model *m = figure_read_string((const char *)data, size, "fuzz.fig", dir, err, sizeof err);
	if (!m) {
		if (strncmp(err, "fuzz.fig", 8))
			abort();
		return 0;
	}
	size_t n, n2;
	char *text = written(m, &n);
	struct model *back = figure_read_string(text, n, "written.fig", dir, err, sizeof err);
	if (!back) {
		fprintf(stderr, "the written figure does not read back: %s\n%.*s\n", err, (int)n, text);
		abort();
	}
	if (!model_equal(m, back))
		abort();
	char *again = written(back, &n2);
	if (n != n2 || memcmp(text, again, n))
		abort();
	free(again);
	free(text);
	model_free(back);
	model_free(m);
	return 0;
}
