/* sink_mem.c - the latest frame in memory, and its PNG on demand (see sink.h) */
#include "draw/sink.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/*
 * The copy has tightly packed rows in buf, which only grows: after the
 * largest frame so far, writing costs a copy and nothing else. The PNG is
 * encoded at the first sink_mem_png after a write and kept until the next
 * write, so any number of clients asking for one frame cost one encoding.
 */
struct sink_mem {
	struct sink base;
	struct frame frame; /* the copy; frame.rgba = buf */
	int have;	    /* 1 once a frame was written */
	uint8_t *buf;
	size_t cap;	    /* bytes at buf */
	struct sink_png_encoder enc;
	int png_ok;	    /* 1 when enc holds the PNG of frame */
};

static int
sink_mem_write(struct sink *s, const struct frame *f, char *err, size_t errlen)
{
	struct sink_mem *m = (struct sink_mem *)s;
	size_t row = 4 * (size_t)f->width;
	size_t need = row * (size_t)f->height;

	/* a larger buffer only when needed; the old frame stays if there is no memory */
	if (need > m->cap) {
		uint8_t *b = malloc(need);
		if (!b) {
			snprintf(err, errlen, "mem: out of memory for a %dx%d frame", f->width,
				 f->height);
			return -1;
		}
		free(m->buf);
		m->buf = b;
		m->cap = need;
	}

	/* copy the rows, packed */
	for (int y = 0; y < f->height; y++)
		memcpy(m->buf + (size_t)y * row, f->rgba + (size_t)y * (size_t)f->stride, row);
	m->frame = *f;
	m->frame.stride = (int)row;
	m->frame.rgba = m->buf;
	m->have = 1;
	m->png_ok = 0;
	return 0;
}

static void
sink_mem_close(struct sink *s)
{
	struct sink_mem *m = (struct sink_mem *)s;
	sink_png_encoder_free(&m->enc);
	free(m->buf);
	free(m);
}

static const struct sink_ops sink_mem_ops = {
	.name = "mem",
	.write = sink_mem_write,
	.close = sink_mem_close,
};

struct sink *
sink_mem_open(char *err, size_t errlen)
{
	struct sink_mem *m = calloc(1, sizeof *m);
	if (!m) {
		snprintf(err, errlen, "mem: out of memory");
		return NULL;
	}
	m->base.ops = &sink_mem_ops;
	sink_png_encoder_init(&m->enc);
	return &m->base;
}

const struct frame *
sink_mem_frame(const struct sink *s)
{
	const struct sink_mem *m = (const struct sink_mem *)s;
	if (s->ops != &sink_mem_ops || !m->have)
		return NULL;
	return &m->frame;
}

int
sink_mem_png(struct sink *s, const uint8_t **data, size_t *len, char *err, size_t errlen)
{
	struct sink_mem *m = (struct sink_mem *)s;
	if (s->ops != &sink_mem_ops) {
		snprintf(err, errlen, "mem: sink_mem_png on a %s sink", s->ops->name);
		return -1;
	}
	if (!m->have) {
		snprintf(err, errlen, "mem: no frame written yet");
		return -1;
	}
	if (!m->png_ok) {
		if (sink_png_encode(&m->enc, &m->frame, err, errlen) < 0)
			return -1;
		m->png_ok = 1;
	}
	*data = m->enc.data;
	*len = m->enc.len;
	return 0;
}
