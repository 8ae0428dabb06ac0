/* kms_pick.c - the KMS sink's choices on plain structs: connector, mode, CRTC, buffers */
#include "draw/kms_pick.h"

#include <stdarg.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

static int
say(char *why, size_t len, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(why, len, fmt, ap);
	va_end(ap);
	return -1;
}

int
kms_parse_mode(const char *s, struct kms_want *dest)
{
	int w = 0, h = 0, hz = 0, used = 0;
	if (!s || !s[0]) {
		dest->w = dest->h = dest->hz = 0;
		return 0;
	}
	if (sscanf(s, "%dx%d%n", &w, &h, &used) != 2 || w < 1 || h < 1 || w > 16384 || h > 16384)
		return -1;
	if (s[used] == '@') {
		int more = 0;
		if (sscanf(s + used + 1, "%d%n", &hz, &more) != 1 || hz < 1 || hz > 1000)
			return -1;
		used += 1 + more;
	}
	if (s[used])
		return -1;
	dest->w = w;
	dest->h = h;
	dest->hz = hz;
	return 0;
}

static const struct kms_encoder *
encoder(const struct kms_resources *r, uint32_t id)
{
	for (int i = 0; i < r->nencoders; i++)
		if (r->encoders[i].id == id)
			return &r->encoders[i];
	return NULL;
}

/* the mode of c to show: the wanted one, else the preferred, else the first; -1: none fits */
static int
pick_mode(const struct kms_connector *c, const struct kms_want *want)
{
	if (want->w) {
		for (int m = 0; m < c->nmodes; m++)
			if (c->modes[m].w == want->w && c->modes[m].h == want->h &&
			    (!want->hz || c->modes[m].refresh == (uint32_t)want->hz))
				return m;
		return -1;
	}
	for (int m = 0; m < c->nmodes; m++)
		if (c->modes[m].preferred)
			return m;
	return c->nmodes ? 0 : -1;
}

/* a CRTC for c: the one its encoder drives now, else the first one an encoder of it can drive */
static uint32_t
pick_crtc(const struct kms_resources *r, const struct kms_connector *c)
{
	const struct kms_encoder *e = c->encoder ? encoder(r, c->encoder) : NULL;
	if (e && e->crtc)
		return e->crtc;
	for (int k = 0; k < c->nencoders; k++) {
		const struct kms_encoder *pe = encoder(r, c->encoders[k]);
		for (int i = 0; pe && i < r->ncrtcs && i < 32; i++)
			if (pe->possible_crtcs & (1u << i))
				return r->crtcs[i];
	}
	return 0;
}

int
kms_choose(const struct kms_resources *r, const struct kms_want *want, struct kms_choice *dest,
	   char *why, size_t whylen)
{
	int found = -1;
	for (int i = 0; i < r->nconnectors && found < 0; i++) {
		const struct kms_connector *c = &r->connectors[i];
		if (want->connector[0] ? !strcmp(c->name, want->connector)
				       : c->connected && c->nmodes > 0)
			found = i;
	}
	if (found < 0)
		return want->connector[0] ? say(why, whylen, "no connector %s", want->connector)
					  : say(why, whylen, "no connector is connected");
	const struct kms_connector *c = &r->connectors[found];
	if (!c->connected)
		return say(why, whylen, "connector %s is not connected", c->name);
	int m = pick_mode(c, want);
	if (m < 0)
		return want->w ? say(why, whylen, "connector %s has no mode %dx%d%s", c->name, want->w,
				     want->h, want->hz ? " at that rate" : "")
			       : say(why, whylen, "connector %s has no modes", c->name);
	uint32_t crtc = pick_crtc(r, c);
	if (!crtc)
		return say(why, whylen, "no CRTC can drive connector %s", c->name);
	dest->connector = found;
	dest->mode = m;
	dest->crtc = crtc;
	return 0;
}

int
kms_flips_back(const struct kms_flips *f)
{
	return f->in_flight ? -1 : 1 - f->front;
}

void
kms_flips_asked(struct kms_flips *f)
{
	f->in_flight = 1;
}

void
kms_flips_done(struct kms_flips *f)
{
	if (!f->in_flight)
		return;
	f->in_flight = 0;
	f->front = 1 - f->front;
	f->flips++;
}

/* b - a in us, 0 when b is earlier, saturated */
static uint32_t
span(uint64_t a, uint64_t b)
{
	uint64_t d = b > a ? b - a : 0;
	return d > UINT32_MAX ? UINT32_MAX : (uint32_t)d;
}

void
kms_times_add(struct kms_times *t, uint64_t handed, uint64_t began, uint64_t waited,
	      uint64_t copied, uint64_t asked)
{
	if (!handed || handed > began)
		handed = began;
	/* each stamp no earlier than the one before: the parts add up to the total */
	waited = waited > began ? waited : began;
	copied = copied > waited ? copied : waited;
	asked = asked > copied ? asked : copied;
	t->ring[t->n++ % KMS_TIMES] = (struct kms_frame_time){
		span(handed, asked), span(handed, began), span(began, waited), span(waited, copied),
		span(copied, asked) };
}

/* a frame's time as its parts in the struct's order, and back */
enum { PARTS = 5 };

static void
parts_of(const struct kms_frame_time *f, uint32_t *p)
{
	p[0] = f->total, p[1] = f->queue, p[2] = f->wait, p[3] = f->copy, p[4] = f->ioctl;
}

static struct kms_frame_time
time_of(const uint32_t *p)
{
	return (struct kms_frame_time){ p[0], p[1], p[2], p[3], p[4] };
}

static int
by_value(const void *a, const void *b)
{
	uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
	return (x > y) - (x < y);
}

void
kms_times_sum(const struct kms_times *t, struct kms_times_summary *dest)
{
	memset(dest, 0, sizeof *dest);
	dest->n = t->n;
	dest->kept = (int)(t->n < KMS_TIMES ? t->n : KMS_TIMES);
	if (!dest->kept)
		return;
	uint32_t v[KMS_TIMES], p[PARTS], med[PARTS], p99[PARTS], max[PARTS];
	int n = dest->kept;
	for (int k = 0; k < PARTS; k++) {
		for (int i = 0; i < n; i++) {
			parts_of(&t->ring[i], p);
			v[i] = p[k];
		}
		qsort(v, (size_t)n, sizeof *v, by_value);
		med[k] = v[n / 2];
		p99[k] = v[(n * 99) / 100];
		max[k] = v[n - 1];
	}
	dest->median = time_of(med);
	dest->p99 = time_of(p99);
	dest->max = time_of(max);
}
