/* rec_candump.c - candump -l logs, read and written (see rec_candump.h) */
#include "devices/rec_candump.h"

#include <linux/can.h>
#include <stdlib.h>
#include <string.h>

#include "devices/textfile.h"

#define MAX_LINE 4096

/* "(SEC.FRAC)" into microseconds and nanoseconds; NULL or a message */
static const char *
time_parse(const char *s, size_t n, uint64_t *us_dest, uint16_t *ns_dest, int *digits_dest)
{
	size_t i = 1;
	uint64_t sec = 0;
	int nsec_digits = 0;
	if (n < 2 || s[0] != '(' || s[n - 1] != ')')
		return "the time must be (SECONDS.FRACTION)";
	while (i < n && s[i] >= '0' && s[i] <= '9') {
		if (i > 12)
			return "the time's seconds have more than 12 digits";
		sec = sec * 10 + (uint64_t)(s[i] - '0');
		i++;
	}
	if (i == 1 || i >= n || s[i] != '.')
		return "the time must be (SECONDS.FRACTION)";
	i++;
	uint64_t frac = 0;
	while (i < n && s[i] >= '0' && s[i] <= '9') {
		frac = frac * 10 + (uint64_t)(s[i] - '0');
		nsec_digits++;
		i++;
		if (nsec_digits > 9)
			break;
	}
	if (i != n - 1)
		return "the time must be (SECONDS.FRACTION)";
	if (nsec_digits != 6 && nsec_digits != 9)
		return "the time's fraction must have 6 digits (or 9)";
	if (nsec_digits == 6) {
		*us_dest = sec * 1000000 + frac;
		*ns_dest = 0;
	} else {
		*us_dest = sec * 1000000 + frac / 1000;
		*ns_dest = (uint16_t)(frac % 1000);
	}
	*digits_dest = nsec_digits;
	return NULL;
}

/* can-utils' compact frame syntax into f; NULL or a message */
static const char *
frame_parse(const char *s, size_t n, struct rec_candump_frame *f)
{
	size_t idlen = 0;
	while (idlen < n && s[idlen] != '#')
		idlen++;
	if (idlen == n)
		return "the frame has no '#' (ID#DATA)";
	if (idlen != 3 && idlen != 8)
		return "the frame's id must be 3 hex digits (standard) or 8 (extended)";
	uint32_t id = 0;
	for (size_t i = 0; i < idlen; i++) {
		int d = textfile_hex_digit(s[i]);
		if (d < 0)
			return "the frame's id is not hex";
		id = id << 4 | (uint32_t)d;
	}
	if (idlen == 3 && id > CAN_SFF_MASK)
		return "a standard id is at most 7FF";
	if (idlen == 8) {
		if (id & (CAN_EFF_FLAG | CAN_RTR_FLAG))
			return "an 8-digit id is at most 1FFFFFFF, or 2xxxxxxx for an error frame";
		if (!(id & CAN_ERR_FLAG))
			id |= CAN_EFF_FLAG;
	}
	size_t i = idlen + 1;
	if (i < n && s[i] == '#')
		return "a CAN FD frame (ID##...): only classic CAN frames are read";
	f->len = 0;
	f->len8_dlc = 0;
	memset(f->data, 0, sizeof f->data);
	if (i < n && (s[i] == 'R' || s[i] == 'r')) {
		/* remote frame, with an optional length and raw DLC */
		if (id & CAN_ERR_FLAG)
			return "an error frame cannot be a remote frame";
		id |= CAN_RTR_FLAG;
		i++;
		if (i < n) {
			if (s[i] < '0' || s[i] > '8')
				return "a remote frame's length is one digit 0..8 (ID#R5)";
			f->len = (uint8_t)(s[i] - '0');
			i++;
		}
	} else {
		/* data bytes, optionally '.'-separated */
		while (i < n && s[i] != '_') {
			if (s[i] == '.')
				i++;
			if (i >= n || s[i] == '_')
				break;
			if (f->len == 8)
				return "more than 8 data bytes";
			if (i + 1 >= n || textfile_hex_digit(s[i]) < 0 || textfile_hex_digit(s[i + 1]) < 0)
				return "the data must be pairs of hex digits";
			f->data[f->len++] = (uint8_t)(textfile_hex_digit(s[i]) << 4 | textfile_hex_digit(s[i + 1]));
			i += 2;
		}
	}
	if (i < n && s[i] == '_') {
		/* raw DLC of an 8-byte frame */
		int d = i + 2 == n ? textfile_hex_digit(s[i + 1]) : -1;
		if (f->len != 8 || d < 9)
			return "a raw DLC (_9.._F) follows 8 bytes only";
		f->len8_dlc = (uint8_t)d;
		i += 2;
	}
	if (i != n)
		return "unexpected characters after the frame";
	f->can_id = id;
	return NULL;
}

/* one "(time) iface frame [dir]" line into f; NULL or a message */
static const char *
line_parse(const char *s, size_t n, struct rec_candump_frame *f, int *digits_dest)
{
	const char *tok[4];
	size_t tlen[4];
	int ntok = 0;
	size_t i = 0;
	while (i < n && ntok < 4) {
		while (i < n && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r'))
			i++;
		if (i >= n)
			break;
		tok[ntok] = s + i;
		while (i < n && s[i] != ' ' && s[i] != '\t' && s[i] != '\r')
			i++;
		tlen[ntok] = (size_t)(s + i - tok[ntok]);
		ntok++;
	}
	if (ntok < 3)
		return "a frame line is (SECONDS.FRACTION) IFACE FRAME";
	const char *msg = time_parse(tok[0], tlen[0], &f->t_abs_us, &f->t_ns, digits_dest);
	if (msg)
		return msg;
	if (tlen[1] >= REC_CANDUMP_IFACE_MAX)
		return "the interface name is longer than 31 characters";
	memcpy(f->iface, tok[1], tlen[1]);
	f->iface[tlen[1]] = 0;
	msg = frame_parse(tok[2], tlen[2], f);
	if (msg)
		return msg;
	f->dir = 0;
	if (ntok == 4 && tlen[3] == 1 && (tok[3][0] == 'R' || tok[3][0] == 'T'))
		f->dir = tok[3][0];
	return NULL;
}

/* a refusal: "name:line: msg" */
#define fail(err, errlen, name, lineno, msg) \
	textfile_fail((err), (errlen), (name), (unsigned)(lineno), "%s", (msg))

int
rec_candump_parse(const char *text, size_t n, const char *name, struct rec_candump *dest,
		  char *err, size_t errlen)
{
	struct rec_candump r = { 0 };
	size_t cap = 0, pos = 0, lineno = 0;
	memset(dest, 0, sizeof *dest);
	while (pos < n) {
		/* one line */
		lineno++;
		size_t end = pos;
		while (end < n && text[end] != '\n')
			end++;
		const char *s = text + pos;
		size_t len = end - pos;
		pos = end + 1;
		size_t k = 0;
		while (k < len && (s[k] == ' ' || s[k] == '\t' || s[k] == '\r'))
			k++;
		if (k == len || s[k] != '(') {
			r.skipped++;
			continue;
		}
		if (len > MAX_LINE || memchr(s, 0, len)) {
			free(r.frames);
			return fail(err, errlen, name, lineno,
				    len > MAX_LINE ? "line too long" : "a NUL byte in the line");
		}
		if (r.n == cap) {
			size_t ncap = cap ? 2 * cap : 256;
			struct rec_candump_frame *t = realloc(r.frames, ncap * sizeof *t);
			if (!t) {
				free(r.frames);
				return fail(err, errlen, name, lineno, "out of memory");
			}
			r.frames = t;
			cap = ncap;
		}
		struct rec_candump_frame *f = &r.frames[r.n];
		memset(f, 0, sizeof *f);
		int digits;
		const char *msg = line_parse(s + k, len - k, f, &digits);
		if (!msg && r.n > 0) {
			const struct rec_candump_frame *p = &r.frames[r.n - 1];
			if (f->t_abs_us < p->t_abs_us ||
			    (f->t_abs_us == p->t_abs_us && f->t_ns < p->t_ns))
				msg = "the time is earlier than the line before";
		}
		if (msg) {
			free(r.frames);
			return fail(err, errlen, name, lineno, msg);
		}
		if (digits == 9)
			r.nanoseconds = 1;
		f->t_us = f->t_abs_us - r.frames[0].t_abs_us;
		r.n++;
	}
	*dest = r;
	return 0;
}

int
rec_candump_read(const char *path, struct rec_candump *dest, char *err, size_t errlen)
{
	memset(dest, 0, sizeof *dest);
	size_t n;
	char *text = textfile_read(path, &n, err, errlen);
	if (!text)
		return -1;
	int rc = rec_candump_parse(text, n, path, dest, err, errlen);
	free(text);
	return rc;
}

size_t
rec_candump_format(char *dest, size_t cap, const struct rec_candump_frame *f, int width,
		   int nanoseconds)
{
	size_t n = 0;
#define PUT(...) (n += (size_t)snprintf(dest + n, n < cap ? cap - n : 0, __VA_ARGS__))
	unsigned long long sec = f->t_abs_us / 1000000, us = f->t_abs_us % 1000000;
	if (nanoseconds)
		PUT("(%010llu.%09llu) ", sec, us * 1000 + f->t_ns);
	else
		PUT("(%010llu.%06llu) ", sec, us);
	PUT("%*s ", width, f->iface);
	/* the id */
	if (f->can_id & CAN_ERR_FLAG)
		PUT("%08X#", f->can_id & (CAN_ERR_MASK | CAN_ERR_FLAG));
	else if (f->can_id & CAN_EFF_FLAG)
		PUT("%08X#", f->can_id & CAN_EFF_MASK);
	else
		PUT("%03X#", f->can_id & CAN_SFF_MASK);
	/* remote request or data */
	int len = f->len > 8 ? 8 : f->len;
	if (f->can_id & CAN_RTR_FLAG) {
		PUT("R");
		if (len)
			PUT("%d", len);
	} else {
		for (int k = 0; k < len; k++)
			PUT("%02X", f->data[k]);
	}
	if (len == 8 && f->len8_dlc > 8 && f->len8_dlc <= 15)
		PUT("_%X", f->len8_dlc);
	if (f->dir)
		PUT(" %c", f->dir);
	PUT("\n");
#undef PUT
	return n;
}

int
rec_candump_write(FILE *out, const struct rec_candump *r)
{
	int width = 0;
	for (size_t i = 0; i < r->n; i++) {
		int w = (int)strlen(r->frames[i].iface);
		if (w > width)
			width = w;
	}
	for (size_t i = 0; i < r->n; i++) {
		char line[REC_CANDUMP_LINE_MAX];
		size_t n = rec_candump_format(line, sizeof line, &r->frames[i], width, r->nanoseconds);
		fwrite(line, 1, n < sizeof line ? n : sizeof line - 1, out);
	}
	return ferror(out) ? -1 : 0;
}

void
rec_candump_free(struct rec_candump *r)
{
	free(r->frames);
	memset(r, 0, sizeof *r);
}

void
rec_candump_from_can_frame(const uint8_t frame[16], uint64_t t_us, const char *iface,
			   struct rec_candump_frame *dest)
{
	memset(dest, 0, sizeof *dest);
	memcpy(&dest->can_id, frame, sizeof dest->can_id);
	dest->len = frame[4] > 8 ? 8 : frame[4];
	dest->len8_dlc = frame[7];
	if (!(dest->can_id & CAN_RTR_FLAG))
		memcpy(dest->data, frame + 8, 8);
	dest->t_abs_us = t_us;
	snprintf(dest->iface, sizeof dest->iface, "%s", iface);
}

void
rec_candump_to_can_frame(const struct rec_candump_frame *f, uint8_t dest[16])
{
	memset(dest, 0, 16);
	memcpy(dest, &f->can_id, sizeof f->can_id);
	dest[4] = f->len > 8 ? 8 : f->len;
	dest[7] = f->len8_dlc;
	if (!(f->can_id & CAN_RTR_FLAG))
		memcpy(dest + 8, f->data, 8);
}
