/* rec_evemu.c - evemu recordings read and written (see rec_evemu.h) */
#include "devices/rec_evemu.h"

#include <inttypes.h>
#include <stdlib.h>
#include <string.h>

#include "devices/textfile.h"

/* the newest format this reader knows and the writer writes */
#define FORMAT_MAJOR 1
#define FORMAT_MINOR 3

/* as printf shows a NULL string, which evemu's comments carry for codes without a name */
static const char *
shown(const char *name)
{
	return name ? name : "(null)";
}

/* the highest code of a type, as the writer sizes its bitmask lines; -1 for none */
static int
type_max(unsigned type)
{
	switch (type) {
	case EV_SYN:
		return SYN_MAX;
	case EV_KEY:
		return KEY_MAX;
	case EV_REL:
		return REL_MAX;
	case EV_ABS:
		return ABS_MAX;
	case EV_MSC:
		return MSC_MAX;
	case EV_SW:
		return SW_MAX;
	case EV_LED:
		return LED_MAX;
	case EV_SND:
		return SND_MAX;
	case EV_REP:
		return REP_MAX;
	case EV_FF:
		return FF_MAX;
	default:
		return -1;
	}
}

static int
bit(const uint8_t *mask, unsigned i)
{
	return (mask[i / 8] >> (i % 8)) & 1;
}

/* ---- reading -------------------------------------------------------------- */

struct parser {
	const char *name;
	unsigned line;
	char *err;
	size_t errlen;
	int seen_version_line; /* a non-blank line has been read */
	int seen_n, seen_i, seen_desc, seen_e;
	unsigned pbytes;                /* P: bytes read */
	unsigned mbytes[EV_CNT];        /* B: bytes read, per type */
	uint64_t first_us, prev_us;
	size_t cap;                     /* of dest->ev */
};

/* the parser's refusal at its current line */
#define fail(p, ...) textfile_fail((p)->err, (p)->errlen, (p)->name, (p)->line, __VA_ARGS__)

/* a line's cursor: s moves towards end */
struct cursor {
	const char *s, *end;
};

static void
skip_blank(struct cursor *c)
{
	while (c->s < c->end && (*c->s == ' ' || *c->s == '\t'))
		c->s++;
}

/* 1 when the cursor stands at the end of a token */
static int
at_break(const struct cursor *c)
{
	return c->s == c->end || *c->s == ' ' || *c->s == '\t' || *c->s == '#';
}

/* a hex number of 1..maxdigits digits after blanks: 0, or -1 */
static int
take_hex(struct cursor *c, int maxdigits, unsigned *dest)
{
	skip_blank(c);
	unsigned v = 0;
	int n = 0;
	while (c->s < c->end && textfile_hex_digit(*c->s) >= 0) {
		if (++n > maxdigits)
			return -1;
		v = v * 16 + (unsigned)textfile_hex_digit(*c->s++);
	}
	if (!n || !at_break(c))
		return -1;
	*dest = v;
	return 0;
}

/* a decimal int32 with an optional sign after blanks: 0, or -1 */
static int
take_int(struct cursor *c, int32_t *dest)
{
	skip_blank(c);
	int neg = 0;
	if (c->s < c->end && (*c->s == '-' || *c->s == '+'))
		neg = *c->s++ == '-';
	int64_t v = 0;
	int n = 0;
	while (c->s < c->end && *c->s >= '0' && *c->s <= '9') {
		v = v * 10 + (*c->s++ - '0');
		if (v > (int64_t)INT32_MAX + 1)
			return -1;
		n++;
	}
	if (!n || !at_break(c))
		return -1;
	v = neg ? -v : v;
	if (v > INT32_MAX)
		return -1;
	*dest = (int32_t)v;
	return 0;
}

/* nothing but blanks, then the end or a comment: 0, or -1 */
static int
take_end(struct cursor *c)
{
	skip_blank(c);
	return c->s == c->end || *c->s == '#' ? 0 : -1;
}

/* "# EVEMU <major>.<minor>" on the first line: 1 taken, 0 not such a line, -1 bad */
static int
parse_version(struct parser *p, struct cursor c, struct rec_evemu *r)
{
	static const char tag[] = "# EVEMU";
	size_t k = sizeof tag - 1;
	if ((size_t)(c.end - c.s) < k || memcmp(c.s, tag, k))
		return 0;
	c.s += k;
	skip_blank(&c);
	unsigned v[2] = { 0, 0 };
	for (int i = 0; i < 2; i++) {
		int n = 0;
		while (c.s < c.end && *c.s >= '0' && *c.s <= '9' && n < 5) {
			v[i] = v[i] * 10 + (unsigned)(*c.s++ - '0');
			n++;
		}
		if (!n || (i == 0 && (c.s == c.end || *c.s++ != '.')))
			return fail(p, "bad format line, expected \"# EVEMU <major>.<minor>\"");
	}
	if (take_end(&c))
		return fail(p, "bad format line, expected \"# EVEMU <major>.<minor>\"");
	if (v[0] != FORMAT_MAJOR)
		return fail(p, "format %u.%u is not one this reader knows (1.x)", v[0], v[1]);
	r->major = v[0];
	r->minor = v[1];
	return 1;
}

static int
parse_name(struct parser *p, struct cursor c, struct rec_evemu *r)
{
	if (p->seen_n)
		return fail(p, "a second N: line");
	if (p->seen_desc)
		return fail(p, "N: after the description's other lines");
	skip_blank(&c);
	const char *cr = memchr(c.s, '\r', (size_t)(c.end - c.s));
	size_t len = (size_t)((cr ? cr : c.end) - c.s);
	if (len >= sizeof r->name)
		return fail(p, "name longer than %zu bytes", sizeof r->name - 1);
	memcpy(r->name, c.s, len);
	r->name[len] = 0;
	p->seen_n = 1;
	return 0;
}

static int
parse_id(struct parser *p, struct cursor c, struct rec_evemu *r)
{
	if (!p->seen_n)
		return fail(p, "I: before the N: line");
	if (p->seen_i)
		return fail(p, "a second I: line");
	unsigned v[4];
	for (int i = 0; i < 4; i++)
		if (take_hex(&c, 4, &v[i]))
			return fail(p, "expected \"I: <bus> <vendor> <product> <version>\" in hex");
	if (take_end(&c))
		return fail(p, "unexpected text after the I: line's four numbers");
	r->bustype = (uint16_t)v[0];
	r->vendor = (uint16_t)v[1];
	r->product = (uint16_t)v[2];
	r->version = (uint16_t)v[3];
	p->seen_i = 1;
	return 0;
}

/*
 * 8 hex bytes onto a bitmask of cap bytes from byte *at: bytes past cap
 * must be zero (a longer bitmask than this kernel's, with nothing in it)
 */
static int
parse_bytes(struct parser *p, struct cursor *c, uint8_t *mask, size_t cap, unsigned *at,
	    const char *what)
{
	for (int i = 0; i < 8; i++) {
		unsigned b;
		if (take_hex(c, 2, &b))
			return fail(p, "expected 8 hex bytes in the %s line", what);
		if (*at + (unsigned)i < cap)
			mask[*at + (unsigned)i] = (uint8_t)b;
		else if (b)
			return fail(p, "bits past the %zu bytes of the %s bitmask", cap, what);
	}
	if (take_end(c))
		return fail(p, "unexpected text after the %s line's 8 bytes", what);
	if (*at < 4096)
		*at += 8;
	return 0;
}

static int
parse_prop(struct parser *p, struct cursor c, struct rec_evemu *r)
{
	return parse_bytes(p, &c, r->props, sizeof r->props, &p->pbytes, "P:");
}

static int
parse_mask(struct parser *p, struct cursor c, struct rec_evemu *r)
{
	unsigned type;
	if (take_hex(&c, 2, &type))
		return fail(p, "expected \"B: <type> <8 hex bytes>\"");
	if (type > EV_MAX)
		return fail(p, "no event type %#x (the largest is %#x)", type, EV_MAX);
	return parse_bytes(p, &c, r->bits[type], sizeof r->bits[type], &p->mbytes[type], "B:");
}

static int
parse_abs(struct parser *p, struct cursor c, struct rec_evemu *r)
{
	/* the resolution came with format 1.2 */
	int needed = r->major == 1 && r->minor < 2 ? 5 : 6;
	unsigned code;
	int32_t v[5] = { 0, 0, 0, 0, 0 };
	if (take_hex(&c, 4, &code))
		return fail(p, "expected \"A: <code> <min> <max> <fuzz> <flat>%s\"",
			    needed == 6 ? " <res>" : "");
	if (code > ABS_MAX)
		return fail(p, "no ABS code %#x (the largest is %#x)", code, ABS_MAX);
	for (int i = 0; i < needed - 1; i++)
		if (take_int(&c, &v[i]))
			return fail(p,
				    "expected %d numbers after the A: line's code (format %u.%u)",
				    needed - 1, r->major, r->minor);
	if (take_end(&c))
		return fail(p, "more than %d numbers after the A: line's code in format %u.%u",
			    needed - 1, r->major, r->minor);
	struct rec_evemu_abs *a = &r->abs[code];
	a->min = v[0];
	a->max = v[1];
	a->fuzz = v[2];
	a->flat = v[3];
	a->res = v[4];
	r->abs_given[code] = 1;
	return 0;
}

/* L: and S: lines: a code and its state */
static int
parse_state(struct parser *p, struct cursor c, int32_t *states, unsigned max, char tag)
{
	unsigned code;
	int32_t v;
	if (take_hex(&c, 4, &code) || take_int(&c, &v) || take_end(&c))
		return fail(p, "expected \"%c: <code> <state>\"", tag);
	if (code > max)
		return fail(p, "no %s code %#x (the largest is %#x)", tag == 'L' ? "LED" : "SW",
			    code, max);
	states[code] = v;
	return 0;
}

static int
parse_event(struct parser *p, struct cursor c, struct rec_evemu *r)
{
	struct rec_evemu_event ev;
	uint64_t sec = 0;
	int n = 0;
	skip_blank(&c);
	while (c.s < c.end && *c.s >= '0' && *c.s <= '9') {
		if (sec > (UINT64_MAX / 1000000u - 9) / 10)
			return fail(p, "the event's seconds are too large");
		sec = sec * 10 + (uint64_t)(*c.s++ - '0');
		n++;
	}
	if (!n || c.s == c.end || *c.s++ != '.')
		return fail(p, "expected \"E: <sec>.<usec> <type> <code> <value>\"");
	uint32_t usec = 0;
	for (n = 0; c.s < c.end && *c.s >= '0' && *c.s <= '9'; n++)
		usec = usec * 10 + (uint32_t)(*c.s++ - '0');
	if (n != 6 || !at_break(&c))
		return fail(p, "the event's fraction of a second must have 6 digits");
	unsigned type, code;
	if (take_hex(&c, 4, &type) || take_hex(&c, 4, &code) || take_int(&c, &ev.value))
		return fail(p, "expected \"E: <sec>.<usec> <type> <code> <value>\"");
	if (take_end(&c))
		return fail(p, "unexpected text after the event's value");
	if (type > EV_MAX)
		return fail(p, "no event type %#x (the largest is %#x)", type, EV_MAX);
	uint64_t t = sec * 1000000u + usec;
	if (!p->seen_e)
		p->first_us = t;
	if (t < p->first_us)
		return fail(p, "the event is earlier than the first event");
	ev.t_us = t - p->first_us;
	ev.sec = sec;
	ev.usec = usec;
	ev.type = (uint16_t)type;
	ev.code = (uint16_t)code;
	if (r->nev == p->cap) {
		size_t cap = p->cap ? p->cap * 2 : 256;
		struct rec_evemu_event *grown = realloc(r->ev, cap * sizeof *grown);
		if (!grown)
			return fail(p, "out of memory for %zu events", cap);
		r->ev = grown;
		p->cap = cap;
	}
	r->ev[r->nev++] = ev;
	p->seen_e = 1;
	return 0;
}

/* one line (without its '\n'): 0, or -1 with the error written */
static int
parse_line(struct parser *p, struct cursor c, struct rec_evemu *r)
{
	if (memchr(c.s, 0, (size_t)(c.end - c.s)))
		return fail(p, "a NUL byte in the line");
	if (c.end > c.s && c.end[-1] == '\r')
		c.end--;
	skip_blank(&c);
	if (c.s == c.end)
		return 0;
	int first = !p->seen_version_line;
	p->seen_version_line = 1;
	if (*c.s == '#') {
		if (!first)
			return 0;
		return parse_version(p, c, r) < 0 ? -1 : 0;
	}
	if (c.end - c.s < 2 || c.s[1] != ':')
		return 0;
	char tag = c.s[0];
	struct cursor rest = { c.s + 2, c.end };
	if (tag == 'E')
		return parse_event(p, rest, r);
	if (tag == 0 || !strchr("NIPBALS", tag))
		return 0;
	if (p->seen_e)
		return fail(p, "a %c: line after the events", tag);
	if (tag == 'N')
		return parse_name(p, rest, r);
	if (tag == 'I')
		return parse_id(p, rest, r);
	if (!p->seen_i)
		return fail(p, "a %c: line before the N: and I: lines", tag);
	p->seen_desc = 1;
	switch (tag) {
	case 'P':
		return parse_prop(p, rest, r);
	case 'B':
		return parse_mask(p, rest, r);
	case 'A':
		return parse_abs(p, rest, r);
	case 'L':
		return parse_state(p, rest, r->led, LED_MAX, 'L');
	default:
		return parse_state(p, rest, r->sw, SW_MAX, 'S');
	}
}

int
rec_evemu_parse(const char *text, size_t n, const char *name, struct rec_evemu *dest, char *err,
		size_t errlen)
{
	struct parser p = { .name = name, .err = err, .errlen = errlen };
	struct rec_evemu *r = calloc(1, sizeof *r);
	memset(dest, 0, sizeof *dest);
	if (errlen)
		err[0] = 0;
	if (!r)
		return fail(&p, "out of memory");
	/* without a "# EVEMU" line, the file is format 1.0 */
	r->major = 1;
	r->minor = 0;
	const char *s = text, *end = text + n;
	while (s < end) {
		const char *nl = memchr(s, '\n', (size_t)(end - s));
		const char *e = nl ? nl : end;
		p.line++;
		struct cursor c = { s, e };
		if (parse_line(&p, c, r)) {
			rec_evemu_free(r);
			free(r);
			return -1;
		}
		s = nl ? nl + 1 : end;
	}
	if (!p.seen_n && !r->nev) {
		rec_evemu_free(r);
		free(r);
		return fail(&p, "neither a device description nor events");
	}
	if (p.seen_n && !p.seen_i) {
		rec_evemu_free(r);
		free(r);
		return fail(&p, "an N: line without an I: line");
	}
	r->described = p.seen_n;
	/* every code with its EV_ABS bit has an absinfo, all zero without an A: line */
	for (unsigned c = 0; c <= ABS_MAX; c++)
		if (bit(r->bits[EV_ABS], c))
			r->abs_given[c] = 1;
	*dest = *r;
	free(r);
	return 0;
}

int
rec_evemu_read(const char *path, struct rec_evemu *dest, char *err, size_t errlen)
{
	memset(dest, 0, sizeof *dest);
	size_t n;
	char *text = textfile_read(path, &n, err, errlen);
	if (!text)
		return -1;
	int rc = rec_evemu_parse(text, n, path, dest, err, errlen);
	free(text);
	return rc;
}

void
rec_evemu_free(struct rec_evemu *r)
{
	free(r->ev);
	r->ev = NULL;
	r->nev = 0;
}

/* ---- writing -------------------------------------------------------------- */

static void
write_desc(FILE *out, const struct rec_evemu *r)
{
	fprintf(out, "# Input device name: \"%s\"\n", r->name);
	fprintf(out, "# Input device ID: bus %#04x vendor %#04x product %#04x version %#04x\n",
		r->bustype, r->vendor, r->product, r->version);
	if (bit(r->bits[EV_ABS], ABS_X) && bit(r->bits[EV_ABS], ABS_Y)) {
		const struct rec_evemu_abs *x = &r->abs[ABS_X], *y = &r->abs[ABS_Y];
		int64_t w = x->res ? ((int64_t)x->max - x->min) / x->res : 0;
		int64_t h = y->res ? ((int64_t)y->max - y->min) / y->res : 0;
		if (w && h)
			fprintf(out, "# Size in mm: %" PRId64 "x%" PRId64 "\n", w, h);
	}
	fprintf(out, "# Supported events:\n");
	for (unsigned t = 0; t <= EV_MAX; t++) {
		int any = 0;
		for (unsigned i = 0; i < REC_EVEMU_MASK_BYTES; i++)
			any |= r->bits[t][i];
		if (!any)
			continue;
		fprintf(out, "#   Event type %u (%s)\n", t, shown(rec_evemu_type_name(t)));
		for (unsigned c = 0; c < 8 * REC_EVEMU_MASK_BYTES; c++) {
			/* evemu lists every EV_SYN code once the type is there */
			if (t == EV_SYN ? c > SYN_MAX : !bit(r->bits[t], c))
				continue;
			fprintf(out, "#     Event code %u (%s)\n", c,
				shown(rec_evemu_code_name(t, c)));
			if (t == EV_ABS && c <= ABS_MAX) {
				const struct rec_evemu_abs *a = &r->abs[c];
				fprintf(out, "#       Value   %6d\n", 0);
				fprintf(out, "#       Min     %6d\n", a->min);
				fprintf(out, "#       Max     %6d\n", a->max);
				fprintf(out, "#       Fuzz    %6d\n", a->fuzz);
				fprintf(out, "#       Flat    %6d\n", a->flat);
				fprintf(out, "#       Resolution %3d\n", a->res);
			} else if (t == EV_LED && c <= LED_MAX) {
				fprintf(out, "#        State %d\n", r->led[c]);
			} else if (t == EV_SW && c <= SW_MAX) {
				fprintf(out, "#        State %d\n", r->sw[c]);
			}
		}
	}
	fprintf(out, "# Properties:\n");
	for (unsigned i = 0; i <= INPUT_PROP_MAX; i++)
		if (bit(r->props, i))
			fprintf(out, "#   Property  type %u (%s)\n", i, shown(rec_evemu_prop_name(i)));
}

/* 8 bytes of a bitmask as one line's hex */
static void
write_bytes(FILE *out, const uint8_t *b)
{
	for (int i = 0; i < 8; i++)
		fprintf(out, " %02x", b[i]);
	fputc('\n', out);
}

static void
write_masks(FILE *out, const struct rec_evemu *r)
{
	fputs("P:", out);
	write_bytes(out, r->props);
	for (unsigned t = 0; t <= EV_MAX; t++) {
		/* evemu writes every type with a largest code in full, and EV_SYN as one line */
		size_t bytes = t == EV_SYN ? 8 : (size_t)(type_max(t) + 1 + 7) / 8;
		for (size_t i = REC_EVEMU_MASK_BYTES; i-- > bytes;)
			if (r->bits[t][i]) {
				bytes = i + 1;
				break;
			}
		for (size_t i = 0; i < bytes; i += 8) {
			fprintf(out, "B: %02x", t);
			write_bytes(out, &r->bits[t][i]);
		}
	}
}

int
rec_evemu_write_event(FILE *out, const struct rec_evemu_event *ev, uint64_t *last_ms)
{
	fprintf(out, "E: %" PRIu64 ".%06u %04x %04x %04d\t", ev->sec, (unsigned)ev->usec, ev->type,
		ev->code, (int)ev->value);
	const char *code = shown(rec_evemu_code_name(ev->type, ev->code));
	if (ev->type == EV_SYN && ev->code == SYN_MT_REPORT) {
		fprintf(out, "# ++++++++++++ %s (%d) ++++++++++\n", code, (int)ev->value);
	} else if (ev->type == EV_SYN) {
		uint64_t ms = ev->sec * 1000 + ev->usec / 1000;
		fprintf(out, "# ------------ %s (%d) ---------- %+" PRId64 "ms\n", code,
			(int)ev->value, (int64_t)(ms - *last_ms));
		*last_ms = ms;
	} else {
		fprintf(out, "# %s / %-20s %d\n", shown(rec_evemu_type_name(ev->type)), code,
			(int)ev->value);
	}
	return ferror(out) ? -1 : 0;
}

int
rec_evemu_write(FILE *out, const struct rec_evemu *r)
{
	fprintf(out, "# EVEMU %d.%d\n", FORMAT_MAJOR, FORMAT_MINOR);
	if (r->described) {
		write_desc(out, r);
		fprintf(out, "N: %s\n", r->name);
		fprintf(out, "I: %04x %04x %04x %04x\n", r->bustype, r->vendor, r->product,
			r->version);
		write_masks(out, r);
		for (unsigned c = 0; c <= ABS_MAX; c++) {
			const struct rec_evemu_abs *a = &r->abs[c];
			if (r->abs_given[c])
				fprintf(out, "A: %02x %d %d %d %d %d\n", c, a->min, a->max, a->fuzz,
					a->flat, a->res);
		}
		for (unsigned c = 0; c <= LED_MAX; c++)
			if (r->led[c])
				fprintf(out, "L: %02x %d\n", c, r->led[c]);
		for (unsigned c = 0; c <= SW_MAX; c++)
			if (r->sw[c])
				fprintf(out, "S: %02x %d\n", c, r->sw[c]);
	}
	uint64_t last_ms = 0;
	for (size_t i = 0; i < r->nev; i++)
		rec_evemu_write_event(out, &r->ev[i], &last_ms);
	return ferror(out) ? -1 : 0;
}

/* ---- replay ---------------------------------------------------------------- */

size_t
rec_evemu_to_records(const struct rec_evemu *r, uint8_t *dest, size_t max)
{
	const size_t size = sizeof(struct input_event);
	for (size_t i = 0; i < r->nev && (i + 1) * size <= max; i++) {
		const struct rec_evemu_event *ev = &r->ev[i];
		struct input_event rec;
		memset(&rec, 0, sizeof rec);
		rec.input_event_sec = (time_t)(ev->t_us / 1000000u);
		rec.input_event_usec = (suseconds_t)(ev->t_us % 1000000u);
		rec.type = ev->type;
		rec.code = ev->code;
		rec.value = ev->value;
		memcpy(dest + i * size, &rec, size);
	}
	return r->nev * size;
}

int
rec_evemu_apply_abs(const struct rec_evemu *r, struct evdev_input *dest)
{
	int n = 0;
	for (uint16_t c = ABS_X; c <= ABS_Y; c++)
		if (r->abs_given[c] &&
		    evdev_input_set_abs(dest, c, r->abs[c].min, r->abs[c].max) == 0)
			n++;
	return n;
}
