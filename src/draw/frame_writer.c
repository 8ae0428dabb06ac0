/* frame_writer.c - sinks written on a thread of their own, newest frame first (see frame_writer.h) */
#include "draw/frame_writer.h"

#include <pthread.h>
#include <semaphore.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#define FRESH 4u /* in a slot's mid: the frame there has not been taken */

/*
 * How the thread waits. Waking a sleeping thread from the loop (a futex
 * wake, an IPI to the other CPU) now and then held the loop 2-5 ms on the
 * 2-vCPU machine we measure on (sem_post alone, timed in the daemon). So
 * while frames come the thread looks for them every POLL_US on its own,
 * and the loop wakes it only after it has found none for IDLE_US and gone
 * to sleep: one wake per burst of frames, and nothing at all while idle.
 */
#define FRAME_WRITER_POLL_US 2000
#define FRAME_WRITER_IDLE_US 250000

/*
 * One sink's mailbox: three buffers, as a triple buffer. The caller fills
 * `back`, then swaps it with `mid` in one atomic exchange (marking it
 * fresh); the thread swaps its `front` with a fresh `mid` and writes from
 * it. Neither side waits for the other and no frame is copied twice: a
 * fresh frame replaced in mid is a dropped one. The lock guards the rest
 * (the sink, busy), which the caller touches only to attach or flush.
 */
struct frame_writer_slot {
	uint8_t *buf[3];
	size_t cap[3];
	struct frame f[3];
	atomic_uint mid; /* the middle buffer's index, | FRESH */
	int back;	 /* the caller's buffer */
	int front;	 /* the thread's buffer */
	struct sink *sink;    /* where frames go; NULL: none (the caller's; read under the lock) */
	struct sink *retired; /* a replaced sink the thread still writes with: it closes it */
	int busy;	      /* the thread is writing front */
};

struct frame_writer {
	pthread_t thread;
	sem_t wake;	     /* posted to stop, and for a frame given while the thread sleeps */
	atomic_int sleeping; /* the thread waits on wake (else it looks every POLL_US) */
	pthread_mutex_t lock;
	pthread_cond_t done; /* broadcast when a write ends or nothing is left */
	atomic_int stop;
	int nice;	     /* the thread's niceness */
	struct frame_writer_slot slot[FRAME_WRITER_SLOTS];
	atomic_uint_fast64_t written, dropped, failed;
	uint64_t errors; /* under the lock: failures the caller has not taken */
	/* under the lock: input-to-pixels samples, a ring of the newest */
	uint64_t lat[FRAME_WRITER_LATENCIES];
	uint64_t nlat;
	char err[256];	 /* the newest one's message */
};

int
frame_writer_latencies(struct frame_writer *w, uint64_t *dest, int max)
{
	pthread_mutex_lock(&w->lock);
	uint64_t n = w->nlat < FRAME_WRITER_LATENCIES ? w->nlat : FRAME_WRITER_LATENCIES;
	if ((uint64_t)max < n)
		n = (uint64_t)max;
	for (uint64_t i = 0; i < n; i++)
		dest[i] = w->lat[(w->nlat - n + i) % FRAME_WRITER_LATENCIES];
	pthread_mutex_unlock(&w->lock);
	return (int)n;
}

/* takes slot i's fresh frame, if any: 1 with *sink to write it with, else 0. Locked */
static int
frame_writer_take(struct frame_writer_slot *s, struct sink **sink)
{
	if (!(atomic_load(&s->mid) & FRESH))
		return 0;
	unsigned got = atomic_exchange(&s->mid, (unsigned)s->front);
	s->front = (int)(got & 3u);
	s->busy = 1;
	*sink = s->sink;
	return 1;
}

/* 1 when a slot has a frame waiting */
static int
frame_writer_fresh(struct frame_writer *w)
{
	for (int i = 0; i < FRAME_WRITER_SLOTS; i++)
		if (atomic_load(&w->slot[i].mid) & FRESH)
			return 1;
	return 0;
}

/* one pass over the slots, each fresh frame written; returns how many were */
static int
frame_writer_pass(struct frame_writer *w)
{
	int n = 0;
	for (int i = 0; i < FRAME_WRITER_SLOTS; i++) {
		struct frame_writer_slot *s = &w->slot[i];
		struct sink *sink = NULL;
		pthread_mutex_lock(&w->lock);
		int took = frame_writer_take(s, &sink);
		pthread_mutex_unlock(&w->lock);
		if (!took)
			continue;

		char err[sizeof w->err];
		int r = sink ? sink_write(sink, &s->f[s->front], err, sizeof err) : 0;
		uint64_t input_us = s->f[s->front].input_us, now = input_us ? frame_now_us() : 0;
		if (r == 0 && sink)
			atomic_fetch_add(&w->written, 1);
		else if (!sink)
			atomic_fetch_add(&w->dropped, 1); /* its sink went before it came out */

		pthread_mutex_lock(&w->lock);
		if (r < 0) {
			atomic_fetch_add(&w->failed, 1);
			w->errors++;
			memcpy(w->err, err, sizeof err);
		} else if (sink && input_us && now >= input_us) {
			w->lat[w->nlat++ % FRAME_WRITER_LATENCIES] = now - input_us;
		}
		/* a sink replaced meanwhile goes now (closing frees, unmaps: no waiting on a disk) */
		sink_close(s->retired);
		s->retired = NULL;
		s->busy = 0;
		pthread_cond_broadcast(&w->done);
		pthread_mutex_unlock(&w->lock);
		n++;
	}
	return n;
}

static void *
frame_writer_run(void *arg)
{
	struct frame_writer *w = arg;
	/* behind the loop and the renderer when the CPUs are short: a late file is a dropped one */
	if (w->nice)
		setpriority(PRIO_PROCESS, (id_t)syscall(SYS_gettid), w->nice);
	int quiet = 0; /* passes in a row that found nothing */
	for (;;) {
		if (quiet * FRAME_WRITER_POLL_US < FRAME_WRITER_IDLE_US) {
			struct timespec t = { 0, FRAME_WRITER_POLL_US * 1000L };
			nanosleep(&t, NULL);
		} else {
			/* asleep: then a last look, so a frame given meanwhile is not left (Dekker) */
			atomic_store(&w->sleeping, 1);
			if (!frame_writer_fresh(w))
				while (sem_wait(&w->wake) < 0)
					; /* EINTR */
			atomic_store(&w->sleeping, 0);
			quiet = 0;
		}
		int n = 0;
		for (int k; (k = frame_writer_pass(w)) > 0;)
			n += k;
		quiet = n ? 0 : quiet + 1;
		if (atomic_load(&w->stop)) {
			/* a frame given before stop was set is seen now: written before the end */
			while (frame_writer_pass(w) > 0)
				;
			break;
		}
		pthread_mutex_lock(&w->lock);
		pthread_cond_broadcast(&w->done);
		pthread_mutex_unlock(&w->lock);
	}
	return NULL;
}

struct frame_writer *
frame_writer_make(int nice, char *err, size_t errlen)
{
	struct frame_writer *w = calloc(1, sizeof *w);
	if (!w) {
		snprintf(err, errlen, "frame writer: out of memory");
		return NULL;
	}
	w->nice = nice;
	for (int i = 0; i < FRAME_WRITER_SLOTS; i++) {
		struct frame_writer_slot *s = &w->slot[i];
		atomic_init(&s->mid, 1u);
		s->back = 0;
		s->front = 2;
	}
	atomic_init(&w->stop, 0);
	atomic_init(&w->sleeping, 0);
	atomic_init(&w->written, 0);
	atomic_init(&w->dropped, 0);
	atomic_init(&w->failed, 0);
	sem_init(&w->wake, 0, 0);
	pthread_mutex_init(&w->lock, NULL);
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
		pthread_mutex_destroy(&w->lock);
		sem_destroy(&w->wake);
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
	atomic_store(&w->stop, 1);
	sem_post(&w->wake);
	pthread_join(w->thread, NULL);
	for (int i = 0; i < FRAME_WRITER_SLOTS; i++) {
		struct frame_writer_slot *s = &w->slot[i];
		sink_close(s->sink);
		sink_close(s->retired);
		for (int k = 0; k < 3; k++)
			free(s->buf[k]);
	}
	pthread_cond_destroy(&w->done);
	pthread_mutex_destroy(&w->lock);
	sem_destroy(&w->wake);
	free(w);
}

/*
 * buffer k of s grown to n bytes and touched, so that no page fault waits
 * in a later copy; 0, or -1 (out of memory, the buffer kept)
 */
static int
frame_writer_grow(struct frame_writer_slot *s, int k, size_t n)
{
	if (s->cap[k] >= n)
		return 0;
	uint8_t *b = realloc(s->buf[k], n);
	if (!b)
		return -1;
	memset(b, 0, n);
	s->buf[k] = b;
	s->cap[k] = n;
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

	/*
	 * the buffers for the new sink's frames; the thread takes mid only
	 * under the lock and touches front only while busy, so both may grow
	 * here (front, if busy, grows when the caller next fills it)
	 */
	int mid = (int)(atomic_load(&sl->mid) & 3u);
	if (s && (frame_writer_grow(sl, sl->back, n) < 0 || frame_writer_grow(sl, mid, n) < 0 ||
		  (!sl->busy && frame_writer_grow(sl, sl->front, n) < 0))) {
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
	if (!s && (atomic_load(&sl->mid) & FRESH)) { /* a frame with nowhere to go */
		atomic_fetch_and(&sl->mid, ~FRESH);
		atomic_fetch_add(&w->dropped, 1);
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
	/* the render counts as finished now, as it is handed over (before the copy below) */
	uint64_t done_us = f->done_us ? f->done_us : frame_now_us();
	struct frame_writer_slot *s = &w->slot[slot];
	/* the sink is the caller's to set, so it reads it without the lock */
	if (!s->sink) {
		snprintf(err, errlen, "frame writer: slot %d has no sink", slot);
		return -1;
	}

	/* into the caller's own buffer, packed; grown only for a frame larger than any before */
	size_t row = 4 * (size_t)f->width;
	if (frame_writer_grow(s, s->back, row * (size_t)f->height) < 0) {
		snprintf(err, errlen, "frame writer: out of memory for a %dx%d frame", f->width,
			 f->height);
		return -1;
	}
	uint8_t *b = s->buf[s->back];
	for (int y = 0; y < f->height; y++)
		memcpy(b + (size_t)y * row, f->rgba + (size_t)y * (size_t)f->stride, row);
	struct frame *d = &s->f[s->back];
	frame_init(d, f->width, f->height, b);
	d->seq = f->seq;
	d->t_us = f->t_us;
	d->input_us = f->input_us;
	d->done_us = done_us;

	/* the newest frame wins: one still fresh in mid is replaced */
	unsigned old = atomic_exchange(&s->mid, (unsigned)s->back | FRESH);
	s->back = (int)(old & 3u);
	if (old & FRESH)
		atomic_fetch_add(&w->dropped, 1);
	if (atomic_load(&w->sleeping)) /* else the thread finds it within POLL_US */
		sem_post(&w->wake);
	return 0;
}

uint64_t
frame_writer_error(struct frame_writer *w, char *err, size_t errlen)
{
	/* the thread holds the lock only for a few stores; if it does now, ask again later */
	if (pthread_mutex_trylock(&w->lock))
		return 0;
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
	dest->written = atomic_load(&w->written);
	dest->dropped = atomic_load(&w->dropped);
	dest->failed = atomic_load(&w->failed);
}

struct sink *
frame_writer_sink(struct frame_writer *w, int slot)
{
	if (slot < 0 || slot >= FRAME_WRITER_SLOTS)
		return NULL;
	pthread_mutex_lock(&w->lock);
	struct sink *s = w->slot[slot].sink;
	pthread_mutex_unlock(&w->lock);
	return s;
}

void
frame_writer_flush(struct frame_writer *w)
{
	pthread_mutex_lock(&w->lock);
	for (;;) {
		int pending = 0;
		for (int i = 0; i < FRAME_WRITER_SLOTS; i++)
			pending |= (atomic_load(&w->slot[i].mid) & FRESH) || w->slot[i].busy;
		if (!pending)
			break;
		pthread_cond_wait(&w->done, &w->lock);
	}
	pthread_mutex_unlock(&w->lock);
}
