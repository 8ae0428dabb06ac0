/*
 * frame.h - one finished frame, as the renderer hands it to the sinks.
 *
 * Pixels are 8-bit R, G, B, A in that byte order (straight, not premultiplied
 * alpha), rows top to bottom, each row starting stride bytes after the
 * previous one (stride >= 4 * width; the bytes past 4 * width are ignored).
 * The frame does not own its pixels.
 */
#ifndef POSTURE_FRAME_H
#define POSTURE_FRAME_H

#include <stdint.h>
#include <time.h>

struct frame {
	int width, height; /* pixels */
	int stride;	   /* bytes per row */
	uint8_t *rgba;	   /* 8-bit R,G,B,A per pixel, rows top to bottom */
	uint64_t seq;	   /* frame number */
	uint64_t t_us;	   /* frame time, microseconds */
	/* CLOCK_MONOTONIC of the oldest input event this frame is the first to show, 0: none
	 * (for the input-to-pixels latency, measured when a sink has written it) */
	uint64_t input_us;
	/* CLOCK_MONOTONIC when the render was finished and handed over (0: not yet; the frame
	 * writer stamps it on submit), for the render-to-flip time the KMS sink measures */
	uint64_t done_us;
};

/* CLOCK_MONOTONIC now, us: the clock of input_us and done_us */
static inline uint64_t
frame_now_us(void)
{
	struct timespec t;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return (uint64_t)t.tv_sec * 1000000u + (uint64_t)t.tv_nsec / 1000u;
}

/* a w x h frame over buf with tightly packed rows (stride 4 * w), seq and times 0 */
static inline void
frame_init(struct frame *f, int w, int h, uint8_t *buf)
{
	f->width = w;
	f->height = h;
	f->stride = 4 * w;
	f->rgba = buf;
	f->seq = 0;
	f->t_us = 0;
	f->input_us = 0;
	f->done_us = 0;
}

#endif
