/*
 * sink_relay.c - frames encoded as PNG where they are written (a frame
 * writer's thread) and handed back to another thread to send (see sink.h).
 */
#include "draw/sink.h"

#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>

#define FRESH 4u /* in mid: a PNG not taken yet */

/*
 * Three encoders as a triple buffer: the writer encodes into `back` and
 * swaps it into `mid` (fresh); the taker swaps its `front` with a fresh
 * mid. So neither waits for the other, the taker gets the newest PNG, and
 * a PNG it never took is simply overwritten.
 */
struct sink_relay {
	struct sink base;
	struct sink_png_encoder enc[3];
	struct frame info[3]; /* size, seq, time of each PNG (no pixels) */
	atomic_uint mid;
	int back;  /* the writer's */
	int front; /* the taker's */
};

static int
sink_relay_write(struct sink *s, const struct frame *f, char *err, size_t errlen)
{
	struct sink_relay *r = (struct sink_relay *)s;
	int rc = sink_png_encode(&r->enc[r->back], f, err, errlen);
	if (rc < 0) /* handed over empty: the taker knows this frame will not come */
		r->enc[r->back].len = 0;
	r->info[r->back] = *f;
	r->info[r->back].rgba = NULL;
	r->back = (int)(atomic_exchange(&r->mid, (unsigned)r->back | FRESH) & 3u);
	return rc;
}

static void
sink_relay_close(struct sink *s)
{
	struct sink_relay *r = (struct sink_relay *)s;
	for (int k = 0; k < 3; k++)
		sink_png_encoder_free(&r->enc[k]);
	free(r);
}

static const struct sink_ops sink_relay_ops = {
	.name = "relay",
	.write = sink_relay_write,
	.close = sink_relay_close,
};

struct sink *
sink_relay_open(char *err, size_t errlen)
{
	struct sink_relay *r = calloc(1, sizeof *r);
	if (!r) {
		snprintf(err, errlen, "relay: out of memory");
		return NULL;
	}
	r->base.ops = &sink_relay_ops;
	for (int k = 0; k < 3; k++)
		sink_png_encoder_init(&r->enc[k]);
	atomic_init(&r->mid, 1u);
	r->back = 0;
	r->front = 2;
	return &r->base;
}

int
sink_relay_take(struct sink *s, const uint8_t **data, size_t *len, struct frame *info)
{
	struct sink_relay *r = (struct sink_relay *)s;
	if (!(atomic_load(&r->mid) & FRESH))
		return 0;
	r->front = (int)(atomic_exchange(&r->mid, (unsigned)r->front) & 3u);
	*data = r->enc[r->front].data;
	*len = r->enc[r->front].len;
	*info = r->info[r->front];
	return 1;
}
