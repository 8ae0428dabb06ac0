/*
 * fuzz_can_frame.c - any bytes as reads of struct can_frame (16 bytes each,
 * the rest a short read) through a map with every kind of field, mux
 * branches and buttons, with ticks between: no crash, nothing undefined.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "devices/can_input.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static const char map_text[] =
	"mux 181 0|3@1+ sel\n"
	"axis 181 3|13@1- a mux=sel:0,1 factor=0.1 clamp=-5,5 stale=1\n"
	"axis 181 7|64@0- b mux=sel:2\n"
	"axis 181 0|64@1+ c\n"
	"button 181 7.7 btn stale=2\n"
	"axis 18FF0A42 0-7be- d offset=-1e300 factor=1e300\n"
	"axis 000 63|1@0+ e dlc=8\n";

static struct can_map m;
static struct can_input in;
static struct input_queue q;
static FILE *null_out;

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	char err[256];
	if (!m.n && can_map_parse(map_text, sizeof map_text - 1, "fuzz", &m, err, sizeof err))
		abort();
	can_input_init(&in, &m, 1, "fuzz");
	if (!null_out)
		null_out = fopen("/dev/null", "w");
	in.log.out = null_out;
	input_queue_init(&q);
	uint64_t t = 0;
	struct input_event_rec ev;
	while (size > 0) {
		size_t n = size < 16 ? size : 16;
		uint8_t frame[16];
		memcpy(frame, data, n);
		/* steer some frames to the map's ids */
		if (n == 16 && frame[15] & 1) {
			uint32_t ids[] = { 0x181, 0x18FF0A42 | 0x80000000u, 0 };
			memcpy(frame, &ids[frame[14] % 3], 4);
		}
		can_input_feed(&in, frame, n, t, &q);
		t += (uint64_t)frame[0] * 100;
		can_input_tick(&in, t, &q);
		while (input_queue_pop(&q, &ev))
			;
		data += n;
		size -= n;
	}
	return 0;
}
