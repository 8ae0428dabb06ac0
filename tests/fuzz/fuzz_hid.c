/*
 * fuzz_hid.c - any bytes as a report descriptor and reports: the first two
 * bytes (little-endian) give the descriptor's length, the descriptor
 * follows, then reports, each after a byte giving its length. The parser
 * and decoder must not crash or do anything undefined, a descriptor they
 * accept must describe itself, and every report ends in exactly one frame
 * or is dropped.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "devices/hid_desc.h"
#include "devices/hid_input.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static struct hid_desc d;
static struct hid_input h;
static struct input_queue q;
static FILE *null_out;

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	char err[256];
	if (!null_out)
		null_out = fopen("/dev/null", "w");
	if (size < 2)
		return 0;
	size_t n = (size_t)(data[0] | data[1] << 8);
	data += 2;
	size -= 2;
	if (n > size)
		n = size;
	if (hid_desc_parse(data, n, &d, err, sizeof err) != 0) {
		/* refused: an empty descriptor and a message naming a byte */
		if (d.nreports != 0 || strncmp(err, "byte ", 5) != 0)
			abort();
		return 0;
	}
	hid_desc_describe(&d, null_out);
	hid_input_init(&h, &d, 1, "fuzz");
	h.log.out = null_out;
	input_queue_init(&q);
	data += n;
	size -= n;

	/* reports: a length byte, then that many bytes */
	uint64_t t = 0;
	while (size > 0) {
		size_t len = data[0];
		data++;
		size--;
		if (len > size)
			len = size;
		unsigned before = q.len;
		int ret = hid_input_feed(&h, data, len, t++, &q);
		struct input_event_rec e;
		unsigned frames = 0, got = 0;
		while (input_queue_pop(&q, &e)) {
			got++;
			frames += e.kind == INPUT_FRAME;
			if (e.kind == INPUT_POINTER && (e.x < 0 || e.x > 1 || e.y < 0 || e.y > 1))
				abort();
		}
		if (before != 0 || (ret == 0 && frames != 1) || (ret != 0 && got != 0))
			abort();
		data += len;
		size -= len;
	}
	hid_input_release_all(&h, t, &q);
	return 0;
}
