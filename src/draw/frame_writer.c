/* frame_writer.c - sinks written on a thread of their own, newest frame first (see frame_writer.h) */
#include "draw/frame_writer.h"

#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/*
 * One sink's mailbox. Two buffers go round: the caller fills `wait` (under
 * the lock) and the thread writes from `work` (outside it), swapping them
 * when it takes a frame, so neither ever copies while the other reads.
 */
struct frame_writer_slot {
	struct sink *sink;    /* where this slot's frames go; NULL: none */
	struct sink *retired; /* a replaced sink the thread is still writing with: it closes it */
	uint8_t *wait, *work; /* the frame waiting, the frame being written */
	size_t wait_cap, work_cap;
	struct frame wait_f, work_f;
	int full; /* wait holds a frame not yet taken */
	int busy; /* the thread is writing work */
};

struct frame_writer {
	pthread_t thread;
	pthread_mutex_t lock;
	pthread_cond_t wake; /* to the thread: a frame came, or stop */
	pthread_cond_t done; /* from the thread: nothing waiting, nothing being written */
	int stop;
	int next; /* the slot looked at first: slots take turns */
	struct frame_writer_slot slot[FRAME_WRITER_SLOTS];
	struct frame_writer_stats stats;
	uint64_t errors;	 /* failures the caller has not taken yet */
	char err[256];		 /* the newest one's message */
};

/* a slot with a frame waiting, taking turns from w->next; -1 when none. Locked */
static int
frame_writer_pick(struct frame_writer *w)
{
	for (int k = 0; k < FRAME_WRITER_SLOTS; k++) {
		int i = (w->next + k) % FRAME_WRITER_SLOTS;
		if (w->slot[i].full) {
			w->next = (i + 1) % FRAME_WRITER_SLOTS;
			return i;
		}
	}
	return -1;
}

static void *
frame_writer_run(void *arg)
{
	struct frame_writer *w = arg;
	pthread_mutex_lock(&w->lock);
	for (;;) {
		int i = frame_writer_pick(w);
		if (i < 0) {
			pthread_cond_broadcast(&w->done);
			if (w->stop) /* stopping writes what waits first */
				break;
			pthread_cond_wait(&w->wake, &w->lock);
			continue;
		}

		/* take the waiting frame: the buffers change places */
		struct frame_writer_slot *s = &w->slot[i];
		uint8_t *b = s->work;
		size_t cap = s->work_cap;
		s->work = s->wait;
		s->work_cap = s->wait_cap;
		s->work_f = s->wait_f;
		s->wait = b;
		s->wait_cap = cap;
		s->full = 0;
		s->busy = 1;
		struct sink *sink = s->sink;
		struct frame f = s->work_f;
		pthread_mutex_unlock(&w->lock);

		char err[sizeof w->err];
		int r = sink_write(sink, &f, err, sizeof err);

		pthread_mutex_lock(&w->lock);
		s->busy = 0;
		if (r == 0) {
			w->stats.written++;
		} else {
			w->stats.failed++;
			w->errors++;
			memcpy(w->err, err, sizeof err);
		}
		struct sink *old = s->retired;
		s->retired = NULL;
		if (old) {
			pthread_mutex_unlock(&w->lock);
			sink_close(old);
			pthread_mutex_lock(&w->lock);
		}
	}
	pthread_mutex_unlock(&w->lock);
	return NULL;
}

struct frame_writer *
frame_writer_make(char *err, size_t errlen)
{
	struct frame_writer *w = calloc(1, sizeof *w);
	if (!w) {
		snprintf(err, errlen, "frame writer: out of memory");
		return NULL;
	}
	pthread_mutex_init(&w->lock, NULL);
	pthread_cond_init(&w->wake, NULL);
	pthread_cond_init(&w->done, NULL);

	/* the thread takes no signals: they stay with the loop (its signalfd) */
	sigset_t all, old;
	sigfillset(&all);
	pthread_sigmask(SIG_SETMASK, &all, &old);
	int rc = pthread_create(&w->thread, NULL, frame_writer_run, w);
	pthread_sigmask(SIG_SETMASK, &old, NULL);
	if (rc) {
		snprintf(err, errlen, "frame writer: no thread: %s", strerror(rc));
		pthread_cond_destroy(&w->done);
		pthread_cond_destroy(&w->wake);
		pthread_mutex_destroy(&w->lock);
		free(w);
		return NULL;
	}
	return w;
}

void
frame_writer_free(struct frame_writer *w)
{
	if (!w)
		return;
	pthread_mutex_lock(&w->lock);
	w->stop = 1;
	pthread_cond_signal(&w->wake);
	pthread_mutex_unlock(&w->lock);
	pthread_join(w->thread, NULL);
	for (int i = 0; i < FRAME_WRITER_SLOTS; i++) {
		struct frame_writer_slot *s = &w->slot[i];
		sink_close(s->sink);
		sink_close(s->retired);
		free(s->wait);
		free(s->work);
	}
	pthread_cond_destroy(&w->done);
	pthread_cond_destroy(&w->wake);
	pthread_mutex_destroy(&w->lock);
	free(w);
}

/* *buf grown to n bytes; 0, or -1 (out of memory, *buf kept) */
static int
frame_writer_grow(uint8_t **buf, size_t *cap, size_t n)
{
	if (*cap >= n)
		return 0;
	uint8_t *b = realloc(*buf, n);
	if (!b)
		return -1;
	*buf = b;
	*cap = n;
	return 0;
}

int
frame_writer_attach(struct frame_writer *w, int slot, struct sink *s, int max_w, int max_h,
		    char *err, size_t errlen)
{
	if (slot < 0 || slot >= FRAME_WRITER_SLOTS) {
		snprintf(err, errlen, "frame writer: no slot %d", slot);
		sink_close(s);
		return -1;
	}
	size_t n = 4 * (size_t)(max_w > 0 ? max_w : 1) * (size_t)(max_h > 0 ? max_h : 1);
	struct frame_writer_slot *sl = &w->slot[slot];
	struct sink *refused = NULL, *close_old = NULL;
	int rc = 0;
	pthread_mutex_lock(&w->lock);

	/* the buffers for the new sink's frames; the one being written grows when next needed */
	if (s && (frame_writer_grow(&sl->wait, &sl->wait_cap, n) < 0 ||
		  (!sl->busy && frame_writer_grow(&sl->work, &sl->work_cap, n) < 0))) {
		snprintf(err, errlen, "frame writer: out of memory for %dx%d frames", max_w, max_h);
		refused = s;
		s = NULL;
		rc = -1;
	}

	/*
	 * the old sink closed now, or by the thread when it is done with it:
	 * while busy, the thread writes with the retired sink if there is one,
	 * else with the slot's
	 */
	struct sink *old = sl->sink;
	sl->sink = s;
	if (old && sl->busy && !sl->retired)
		sl->retired = old;
	else
		close_old = old;
	if (!s && sl->full) { /* a frame with nowhere to go */
		sl->full = 0;
		w->stats.dropped++;
	}
	pthread_mutex_unlock(&w->lock);
	sink_close(refused);
	sink_close(close_old);
	return rc;
}

int
frame_writer_submit(struct frame_writer *w, int slot, const struct frame *f, char *err,
		    size_t errlen)
{
	if (slot < 0 || slot >= FRAME_WRITER_SLOTS) {
		snprintf(err, errlen, "frame writer: no slot %d", slot);
		return -1;
	}
	if (sink_frame_check(f, err, errlen) < 0)
		return -1;
	struct frame_writer_slot *s = &w->slot[slot];
	size_t row = 4 * (size_t)f->width;
	pthread_mutex_lock(&w->lock);
	if (!s->sink) {
		pthread_mutex_unlock(&w->lock);
		snprintf(err, errlen, "frame writer: slot %d has no sink", slot);
		return -1;
	}
	if (frame_writer_grow(&s->wait, &s->wait_cap, row * (size_t)f->height) < 0) {
		pthread_mutex_unlock(&w->lock);
		snprintf(err, errlen, "frame writer: out of memory for a %dx%d frame", f->width,
			 f->height);
		return -1;
	}

	/* the newest frame wins: one still waiting is replaced */
	if (s->full)
		w->stats.dropped++;
	for (int y = 0; y < f->height; y++)
		memcpy(s->wait + (size_t)y * row, f->rgba + (size_t)y * (size_t)f->stride, row);
	frame_init(&s->wait_f, f->width, f->height, s->wait);
	s->wait_f.seq = f->seq;
	s->wait_f.t_us = f->t_us;
	s->full = 1;
	pthread_cond_signal(&w->wake);
	pthread_mutex_unlock(&w->lock);
	return 0;
}

uint64_t
frame_writer_error(struct frame_writer *w, char *err, size_t errlen)
{
	pthread_mutex_lock(&w->lock);
	uint64_t n = w->errors;
	if (n)
		snprintf(err, errlen, "%s", w->err);
	w->errors = 0;
	pthread_mutex_unlock(&w->lock);
	return n;
}

void
frame_writer_stats(struct frame_writer *w, struct frame_writer_stats *dest)
{
	pthread_mutex_lock(&w->lock);
	*dest = w->stats;
	pthread_mutex_unlock(&w->lock);
}

void
frame_writer_flush(struct frame_writer *w)
{
	pthread_mutex_lock(&w->lock);
	for (;;) {
		int pending = 0;
		for (int i = 0; i < FRAME_WRITER_SLOTS; i++)
			pending |= w->slot[i].full | w->slot[i].busy;
		if (!pending)
			break;
		pthread_cond_wait(&w->done, &w->lock);
	}
	pthread_mutex_unlock(&w->lock);
}
