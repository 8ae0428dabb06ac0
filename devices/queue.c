/* queue.c - the bounded device-to-loop queue (see queue.h) */
#include "devices/queue.h"

#include <string.h>

void
input_queue_init(struct input_queue *q)
{
	memset(q, 0, sizeof *q);
}

void
input_queue_decoder_enter(struct input_queue *q, uint16_t device, enum input_tap_kind kind,
			  int arg, const uint8_t *bytes, size_t n, uint64_t t_us)
{
	if (!q)
		return;
	if (q->tap && !q->in_decoder)
		q->tap->call(q->tap->user, device, kind, arg, bytes, n, t_us);
	q->in_decoder++;
}

void
input_queue_decoder_leave(struct input_queue *q)
{
	if (q)
		q->in_decoder--;
}

static struct input_event_rec *
at(struct input_queue *q, unsigned i)
{
	return &q->ev[(q->head + i) % INPUT_QUEUE_CAP];
}

/* kinds whose newer event can absorb an older one of the same device and code */
static int
mergeable(enum input_kind k)
{
	switch (k) {
	case INPUT_MOTION:
	case INPUT_POINTER:
	case INPUT_WHEEL:
	case INPUT_VALUATOR:
		return 1;
	case INPUT_BUTTON:
	case INPUT_KEY:
	case INPUT_ADDED:
	case INPUT_REMOVED:
	case INPUT_FRAME:
		return 0;
	}
	return 0;
}

/* the newest queued event of e's device, past its frame ends; NULL when none */
static struct input_event_rec *
newest_of_device(struct input_queue *q, const struct input_event_rec *e, int skip_frames)
{
	for (unsigned i = q->len; i-- > 0;) {
		struct input_event_rec *o = at(q, i);
		if (o->device != e->device)
			continue;
		if (skip_frames && o->kind == INPUT_FRAME)
			continue;
		return o;
	}
	return NULL;
}

/* folds e into o (same device, kind and code) */
static void
merge(struct input_event_rec *o, const struct input_event_rec *e)
{
	switch ((enum input_kind)o->kind) {
	case INPUT_MOTION:
		o->x += e->x;
		o->y += e->y;
		break;
	case INPUT_WHEEL:
		o->value += e->value;
		o->x += e->x;
		break;
	case INPUT_POINTER:
	case INPUT_VALUATOR:
		o->x = e->x;
		o->y = e->y;
		o->value = e->value;
		o->flags = e->flags;
		break;
	case INPUT_BUTTON:
	case INPUT_KEY:
	case INPUT_ADDED:
	case INPUT_REMOVED:
	case INPUT_FRAME:
		break;
	}
	o->t_us = e->t_us;
}

int
input_queue_push(struct input_queue *q, const struct input_event_rec *e)
{
	if (q->tap && !q->in_decoder && e->device != INPUT_DEVICE_SOCKET)
		q->tap->pushed(q->tap->user, e);
	if (q->len >= INPUT_QUEUE_SOFT) {
		if (mergeable((enum input_kind)e->kind)) {
			struct input_event_rec *o = newest_of_device(q, e, 1);
			if (o && o->kind == e->kind && o->code == e->code) {
				merge(o, e);
				q->coalesced++;
				return 1;
			}
		} else if (e->kind == INPUT_FRAME) {
			const struct input_event_rec *o = newest_of_device(q, e, 0);
			if (o && o->kind == INPUT_FRAME) {
				q->coalesced++;
				return 1;
			}
		}
		/* the last INPUT_QUEUE_RESERVE places are kept for transitions */
		int transition = e->kind == INPUT_BUTTON || e->kind == INPUT_KEY ||
				 e->kind == INPUT_ADDED || e->kind == INPUT_REMOVED;
		if (!transition && q->len >= INPUT_QUEUE_CAP - INPUT_QUEUE_RESERVE) {
			q->dropped++;
			return -1;
		}
	}
	if (q->len == INPUT_QUEUE_CAP) {
		q->dropped++;
		return -1;
	}
	*at(q, q->len++) = *e;
	return 0;
}

int
input_queue_pop(struct input_queue *q, struct input_event_rec *dest)
{
	if (!q->len)
		return 0;
	*dest = q->ev[q->head];
	q->head = (q->head + 1) % INPUT_QUEUE_CAP;
	q->len--;
	return 1;
}

int
input_queue_removed(struct input_queue *q, uint64_t t_us, uint16_t device, enum input_class cls)
{
	struct input_event_rec e = {
		.t_us = t_us, .device = device, .kind = INPUT_REMOVED, .code = (uint16_t)cls,
	};
	return input_queue_push(q, &e);
}
