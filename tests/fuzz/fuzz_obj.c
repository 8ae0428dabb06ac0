/*
 * fuzz_obj.c - Wavefront OBJ text (figure/obj.h, what a figure's mesh()
 * and psurf name) through the reader, from memory. A mesh it accepts has
 * a triangle (a degenerate one is fine), every corner a vertex it defined
 * and every coordinate a finite float; a refusal names the text and keeps
 * nothing.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "figure/obj.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct obj_mesh m;
	char err[512];
	if (obj_read_string((const char *)data, size, "fuzz.obj", &m, err, sizeof err) < 0) {
		if (strncmp(err, "fuzz.obj:", 9) || m.vert || m.face || m.nvert || m.nface)
			abort(); /* the message names the text; nothing is kept */
		return 0;
	}
	if (m.nface < 1 || m.nvert < 1)
		abort();
	for (int i = 0; i < 3 * m.nface; i++)
		if (m.face[i] < 0 || m.face[i] >= m.nvert)
			abort();
	for (int i = 0; i < 3 * m.nvert; i++)
		if (!isfinite(m.vert[i]))
			abort();
	obj_mesh_free(&m);
	return 0;
}
