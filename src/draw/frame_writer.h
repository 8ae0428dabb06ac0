/*
 * frame_writer.h - finished frames handed to sinks on a thread of their own.
 *
 * The frame loop must not wait for PNG encoding, fsync or a framebuffer's
 * pixel conversion. A writer owns one thread and a few slots (a view's file,
 * the screen), each holding one sink and a mailbox of two preallocated
 * pixel buffers: the frame waiting, and the frame being written. Submitting
 * copies the frame into the waiting buffer and returns; a frame still
 * waiting when the next one comes is replaced and counted as dropped, so
 * the sink always gets the newest frame next and a slow sink falls behind
 * by at most one frame. The loop never waits for the thread: a slot is a
 * triple buffer, handed over by one atomic exchange each way; a lock
 * guards only what changes when a sink is attached.
 *
 * Errors a sink returns on the thread are kept (the newest message, and a
 * count) until the loop takes them with frame_writer_error.
 */
#ifndef POSTURE_FRAME_WRITER_H
#define POSTURE_FRAME_WRITER_H

#include <stddef.h>
#include <stdint.h>

#include "draw/frame.h"
#include "draw/sink.h"

#define FRAME_WRITER_SLOTS 17 /* sinks per writer: the daemon's 8 views' files and events, the screen */

struct frame_writer;

struct frame_writer_stats {
	uint64_t written; /* frames a sink took */
	uint64_t dropped; /* frames replaced by a newer one before a sink took them */
	uint64_t failed;  /* sink writes that returned -1 */
};

/*
 * Starts a writer and its thread, which runs at niceness nice (0: the
 * caller's; higher: it yields the CPUs to the loop and the renderer).
 * Returns it, or NULL with err (out of memory, no thread).
 */
struct frame_writer *frame_writer_make(int nice, char *err, size_t errlen);

/*
 * Frames no longer taken; the newest frame waiting in each slot written,
 * the thread joined, every sink closed and w freed. NULL is allowed.
 */
void frame_writer_free(struct frame_writer *w);

/*
 * Gives slot (0..FRAME_WRITER_SLOTS-1) sink s (w owns it from now on; NULL
 * empties the slot), with buffers for frames up to max_w x max_h. The
 * slot's earlier sink is closed (by the thread, if it is writing with it);
 * a frame still waiting for it goes to s. Returns 0, or -1 with err when
 * the buffers cannot be had (s is closed, the slot left empty).
 */
int frame_writer_attach(struct frame_writer *w, int slot, struct sink *s, int max_w, int max_h,
			char *err, size_t errlen);

/*
 * Copies f into slot's waiting buffer for its sink, replacing (dropping) a
 * frame still waiting there, and returns at once. A frame larger than the
 * slot's buffers grows them (the view was made larger). Returns 0, or -1
 * with err for a slot without a sink, a frame sinks refuse, or no memory.
 * A frame with done_us 0 gets the time of the call (CLOCK_MONOTONIC, us).
 */
int frame_writer_submit(struct frame_writer *w, int slot, const struct frame *f, char *err,
			size_t errlen);

/*
 * Returns the sink failures since the last call (0: none) and, when there
 * were any, the newest one's message in err. Never waits for a write.
 */
uint64_t frame_writer_error(struct frame_writer *w, char *err, size_t errlen);

/* the counters so far, summed over the slots */
void frame_writer_stats(struct frame_writer *w, struct frame_writer_stats *dest);

#define FRAME_WRITER_LATENCIES 512 /* input-to-pixels samples kept, the newest */

/*
 * Input to pixels: for each frame written that carried input_us, the time
 * from that event to the end of the sink's write (CLOCK_MONOTONIC, us).
 * Copies up to max of the newest samples into dest, oldest first; returns
 * how many. Waits only for the writer's lock (held a few instructions).
 */
int frame_writer_latencies(struct frame_writer *w, uint64_t *dest, int max);

/* the sink of slot (NULL: none); the writer owns it: for the caller's questions, not writes */
struct sink *frame_writer_sink(struct frame_writer *w, int slot);

/* waits until every frame submitted so far is written or has failed (tests, shutdown) */
void frame_writer_flush(struct frame_writer *w);

#endif
