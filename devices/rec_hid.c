/* rec_hid.c - hid-recorder files (see rec_hid.h) */
#include "devices/rec_hid.h"

#include <inttypes.h>
#include <stdlib.h>
#include <string.h>

#include "devices/textfile.h"

struct reader {
	const char *name;
	unsigned line;
	char *err;
	size_t errlen;
	struct rec_hid *r;
	unsigned cur;                            /* the device D: chose */
	int has_desc[REC_HID_MAX_DEVICES];
	unsigned first_line[REC_HID_MAX_DEVICES]; /* where a device was first named */
	size_t cap_events, cap_pool, npool;
	uint64_t first_t, last_t;
};

/* the reader's refusal at its current line */
#define fail(rd, ...) textfile_fail((rd)->err, (rd)->errlen, (rd)->name, (rd)->line, __VA_ARGS__)

/* a cursor over one line */
struct cur {
	const char *p, *end;
};

/* blanks: a stray CR counts as one */
static int
blank(char ch)
{
	return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\v' || ch == '\f';
}

static void
skip_space(struct cur *c)
{
	while (c->p < c->end && blank(*c->p))
		c->p++;
}

/* an unsigned number in base 10 or 16 of at most maxdigits digits */
static int
number(struct cur *c, int base, unsigned maxdigits, uint64_t *dest)
{
	uint64_t v = 0;
	unsigned k = 0;
	while (c->p < c->end) {
		int d = textfile_hex_digit(*c->p);
		if (base == 10 && d > 9)
			d = -1;
		if (d < 0)
			break;
		if (++k > maxdigits)
			return -1;
		v = v * (uint64_t)base + (uint64_t)d;
		c->p++;
	}
	if (k == 0)
		return -1;
	*dest = v;
	return 0;
}

/* the end of a token: space or the end of the line */
static int
at_token_end(const struct cur *c)
{
	return c->p == c->end || blank(*c->p);
}

/* "<len> <hex> <hex> ...": exactly len bytes of one or two hex digits */
static int
hex_bytes(struct reader *rd, struct cur *c, const char *what, unsigned max, uint8_t *dest,
	  unsigned *len)
{
	uint64_t n;
	skip_space(c);
	if (number(c, 10, 6, &n) < 0 || !at_token_end(c))
		return fail(rd, "%s: expected a decimal length", what);
	if (n == 0 || n > max)
		return fail(rd, "%s: length %" PRIu64 " outside 1-%u", what, n, max);
	for (unsigned i = 0; i < n; i++) {
		uint64_t b;
		skip_space(c);
		if (c->p == c->end)
			return fail(rd, "%s: length %" PRIu64 " but %u bytes follow", what, n, i);
		if (number(c, 16, 2, &b) < 0 || !at_token_end(c))
			return fail(rd, "%s: byte %u is not one or two hex digits", what, i + 1);
		dest[i] = (uint8_t)b;
	}
	skip_space(c);
	if (c->p != c->end) {
		unsigned extra = 0;
		while (c->p < c->end) {
			extra++;
			while (c->p < c->end && !at_token_end(c))
				c->p++;
			skip_space(c);
		}
		return fail(rd, "%s: length %" PRIu64 " but %" PRIu64 " bytes follow", what, n,
			    n + extra);
	}
	*len = (unsigned)n;
	return 0;
}

/* the rest of the line as text, trailing blanks dropped */
static int
text(struct reader *rd, struct cur *c, const char *what, char *dest)
{
	skip_space(c);
	const char *e = c->end;
	while (e > c->p && blank(e[-1]))
		e--;
	size_t n = (size_t)(e - c->p);
	if (n >= REC_HID_MAX_NAME)
		return fail(rd, "%s: longer than %d bytes", what, REC_HID_MAX_NAME - 1);
	if (memchr(c->p, '\0', n))
		return fail(rd, "%s: holds a NUL byte", what);
	memcpy(dest, c->p, n);
	dest[n] = '\0';
	return 0;
}

static int
line_device(struct reader *rd, struct cur *c)
{
	uint64_t idx;
	skip_space(c);
	if (number(c, 10, 6, &idx) < 0)
		return fail(rd, "D: expected a device index");
	skip_space(c);
	if (c->p != c->end)
		return fail(rd, "D: junk after the device index");
	if (idx >= REC_HID_MAX_DEVICES)
		return fail(rd, "D: device %" PRIu64 " outside 0-%d", idx, REC_HID_MAX_DEVICES - 1);
	rd->cur = (unsigned)idx;
	if (!rd->first_line[idx])
		rd->first_line[idx] = rd->line;
	return 0;
}

static int
line_info(struct reader *rd, struct cur *c, struct rec_hid_device *dev)
{
	uint64_t v[3];
	static const char *what[3] = { "bus", "vendor", "product" };
	for (int i = 0; i < 3; i++) {
		skip_space(c);
		if (number(c, 16, 8, &v[i]) < 0 || !at_token_end(c))
			return fail(rd, "I: expected bus, vendor and product in hex");
		if (v[i] > 0xffff)
			return fail(rd, "I: %s 0x%" PRIx64 " over 0xffff", what[i], v[i]);
	}
	skip_space(c);
	if (c->p != c->end)
		return fail(rd, "I: junk after the product");
	dev->bus = (uint16_t)v[0];
	dev->vid = (uint16_t)v[1];
	dev->pid = (uint16_t)v[2];
	return 0;
}

static int
line_desc(struct reader *rd, struct cur *c, struct rec_hid_device *dev)
{
	unsigned len;
	if (rd->has_desc[rd->cur])
		return fail(rd, "R: a second descriptor for device %u", rd->cur);
	if (hex_bytes(rd, c, "R", HID_DESC_MAX_BYTES, dev->desc, &len) < 0)
		return -1;
	dev->desc_len = (uint16_t)len;
	rd->has_desc[rd->cur] = 1;
	return 0;
}

static int
grow(void **p, size_t *cap, size_t need, size_t size)
{
	if (need <= *cap)
		return 0;
	size_t n = *cap ? *cap : 64;
	while (n < need)
		n *= 2;
	void *q = realloc(*p, n * size);
	if (!q)
		return -1;
	*p = q;
	*cap = n;
	return 0;
}

static int
line_event(struct reader *rd, struct cur *c)
{
	struct rec_hid *r = rd->r;
	uint64_t sec, usec;
	uint8_t buf[REC_HID_MAX_REPORT];
	unsigned len;

	/* sec.usec: any number of second digits, exactly six after the point */
	skip_space(c);
	if (number(c, 10, 12, &sec) < 0 || c->p == c->end || *c->p != '.')
		return fail(rd, "E: expected a time as seconds.microseconds");
	c->p++;
	const char *frac = c->p;
	if (number(c, 10, 6, &usec) < 0 || c->p - frac != 6 || !at_token_end(c))
		return fail(rd, "E: the time needs exactly six digits after the point");
	if (hex_bytes(rd, c, "E", REC_HID_MAX_REPORT, buf, &len) < 0)
		return -1;
	if (!rd->has_desc[rd->cur])
		return fail(rd, "E: a report of device %u before its R: line", rd->cur);

	/* times from the first event, never going back */
	uint64_t t = sec * 1000000 + usec;
	if (r->nevents == 0)
		rd->first_t = rd->last_t = t;
	if (t < rd->last_t)
		return fail(rd, "E: time %" PRIu64 ".%06" PRIu64 " before the previous event's",
			    sec, usec);
	rd->last_t = t;

	if (grow((void **)&r->events, &rd->cap_events, r->nevents + 1, sizeof r->events[0]) < 0 ||
	    grow((void **)&r->pool, &rd->cap_pool, rd->npool + len, 1) < 0)
		return fail(rd, "out of memory");
	struct rec_hid_event *e = &r->events[r->nevents++];
	e->t_us = t - rd->first_t;
	e->device = (uint16_t)rd->cur;
	e->len = (uint16_t)len;
	e->offset = (uint32_t)rd->npool;
	e->bytes = NULL; /* set once the pool stops moving */
	memcpy(r->pool + rd->npool, buf, len);
	rd->npool += len;
	return 0;
}

/* one line: a comment, blank, unknown, or X: with X one of D R N P I E */
static int
line(struct reader *rd, const char *p, const char *end)
{
	struct cur c = { p, end };
	skip_space(&c);
	if (c.p == c.end || *c.p == '#')
		return 0;
	if (c.end - c.p < 2 || c.p[1] != ':')
		return 0;
	char kind = c.p[0];
	c.p += 2;
	if (kind == 'D')
		return line_device(rd, &c);
	if (!strchr("RNPIE", kind) || kind == '\0')
		return 0;
	/* a device is the one D: chose last, 0 before any D: */
	if (!rd->first_line[rd->cur])
		rd->first_line[rd->cur] = rd->line;
	if (rd->cur + 1 > rd->r->ndevices)
		rd->r->ndevices = rd->cur + 1;
	struct rec_hid_device *dev = &rd->r->devices[rd->cur];
	switch (kind) {
	case 'R':
		return line_desc(rd, &c, dev);
	case 'N':
		return text(rd, &c, "N:", dev->name);
	case 'P':
		return text(rd, &c, "P:", dev->phys);
	case 'I':
		return line_info(rd, &c, dev);
	case 'E':
		return line_event(rd, &c);
	}
	return 0;
}

void
rec_hid_free(struct rec_hid *r)
{
	free(r->events);
	free(r->pool);
	memset(r, 0, sizeof *r);
}

int
rec_hid_parse(const char *txt, size_t n, const char *name, struct rec_hid *dest, char *err,
	      size_t errlen)
{
	struct reader rd;
	memset(&rd, 0, sizeof rd);
	memset(dest, 0, sizeof *dest);
	rd.name = name;
	rd.err = err;
	rd.errlen = errlen;
	rd.r = dest;
	if (errlen)
		err[0] = '\0';

	/* line by line; a CR before the LF is dropped */
	const char *p = txt, *end = txt + n;
	while (p < end) {
		const char *nl = memchr(p, '\n', (size_t)(end - p));
		const char *e = nl ? nl : end;
		rd.line++;
		if (e > p && e[-1] == '\r')
			e--;
		if (line(&rd, p, e) < 0)
			goto bad;
		p = nl ? nl + 1 : end;
	}

	/* every device named has a descriptor */
	if (dest->ndevices == 0) {
		rd.line = rd.line ? rd.line : 1;
		fail(&rd, "no R: line: not a hid-recorder file");
		goto bad;
	}
	for (unsigned i = 0; i < dest->ndevices; i++) {
		if (!rd.has_desc[i]) {
			rd.line = rd.first_line[i] ? rd.first_line[i] : 1;
			fail(&rd, "device %u has no R: line", i);
			goto bad;
		}
	}

	/* the pool stops moving: offsets become pointers */
	for (size_t i = 0; i < dest->nevents; i++)
		dest->events[i].bytes = dest->pool + dest->events[i].offset;
	return 0;

bad:
	rec_hid_free(dest);
	return -1;
}

int
rec_hid_read(const char *path, struct rec_hid *dest, char *err, size_t errlen)
{
	memset(dest, 0, sizeof *dest);
	size_t n;
	char *text = textfile_read(path, &n, err, errlen);
	if (!text)
		return -1;
	int rc = rec_hid_parse(text, n, path, dest, err, errlen);
	free(text);
	return rc;
}

static void
write_hex(FILE *out, const uint8_t *b, unsigned n)
{
	for (unsigned i = 0; i < n; i++)
		fprintf(out, " %02x", b[i]);
	fputc('\n', out);
}

void
rec_hid_write_device(FILE *out, const struct rec_hid_device *dev, int index)
{
	/* as hidraw.py's dump() writes it */
	if (index >= 0)
		fprintf(out, "D: %d\n", index);
	fprintf(out, "# %s\n", dev->name);
	fprintf(out, "R: %u", dev->desc_len);
	write_hex(out, dev->desc, dev->desc_len);
	fprintf(out, "N: %s\n", dev->name);
	if (dev->phys[0])
		fprintf(out, "P: %s\n", dev->phys);
	fprintf(out, "I: %x %04x %04x\n", dev->bus, dev->vid, dev->pid);
}

void
rec_hid_write_event(FILE *out, uint64_t t_us, const uint8_t *bytes, unsigned len)
{
	fprintf(out, "E: %06" PRIu64 ".%06u %u", t_us / 1000000, (unsigned)(t_us % 1000000), len);
	write_hex(out, bytes, len);
}

int
rec_hid_write(FILE *out, const struct rec_hid *r)
{
	int several = r->ndevices > 1;

	/* each device's header */
	for (unsigned i = 0; i < r->ndevices; i++)
		rec_hid_write_device(out, &r->devices[i], several ? (int)i : -1);

	/* the events, with D: when the device changes */
	unsigned last = several ? REC_HID_MAX_DEVICES : 0;
	for (size_t i = 0; i < r->nevents; i++) {
		const struct rec_hid_event *e = &r->events[i];
		if (e->device != last) {
			fprintf(out, "D: %u\n", e->device);
			last = e->device;
		}
		rec_hid_write_event(out, e->t_us, e->bytes, e->len);
	}
	return ferror(out) || fflush(out) ? -1 : 0;
}
