/* can_map.c - the CAN panel map: parser, writer and filters (see can_map.h) */
#include "devices/can_map.h"

#include <errno.h>
#include <linux/input-event-codes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "devices/textfile.h"

#define MAX_TOKENS 16

/* the button names a map may give; the first of two names for one code is written */
#define BTN(x) { #x, x }
static const struct {
	const char *name;
	uint16_t code;
} btn_names[] = {
	BTN(BTN_0), BTN(BTN_1), BTN(BTN_2), BTN(BTN_3), BTN(BTN_4), BTN(BTN_5), BTN(BTN_6),
	BTN(BTN_7), BTN(BTN_8), BTN(BTN_9), BTN(BTN_LEFT), BTN(BTN_RIGHT), BTN(BTN_MIDDLE),
	BTN(BTN_SIDE), BTN(BTN_EXTRA), BTN(BTN_FORWARD), BTN(BTN_BACK), BTN(BTN_TASK),
	BTN(BTN_TRIGGER), BTN(BTN_THUMB), BTN(BTN_THUMB2), BTN(BTN_TOP), BTN(BTN_TOP2),
	BTN(BTN_PINKIE), BTN(BTN_BASE), BTN(BTN_BASE2), BTN(BTN_BASE3), BTN(BTN_BASE4),
	BTN(BTN_BASE5), BTN(BTN_BASE6), BTN(BTN_DEAD), BTN(BTN_SOUTH), BTN(BTN_A), BTN(BTN_EAST),
	BTN(BTN_B), BTN(BTN_C), BTN(BTN_NORTH), BTN(BTN_X), BTN(BTN_WEST), BTN(BTN_Y), BTN(BTN_Z),
	BTN(BTN_TL), BTN(BTN_TR), BTN(BTN_TL2), BTN(BTN_TR2), BTN(BTN_SELECT), BTN(BTN_START),
	BTN(BTN_MODE), BTN(BTN_THUMBL), BTN(BTN_THUMBR), BTN(BTN_GEAR_DOWN), BTN(BTN_GEAR_UP),
	BTN(BTN_TRIGGER_HAPPY1), BTN(BTN_TRIGGER_HAPPY2), BTN(BTN_TRIGGER_HAPPY3),
	BTN(BTN_TRIGGER_HAPPY4), BTN(BTN_TRIGGER_HAPPY5), BTN(BTN_TRIGGER_HAPPY6),
	BTN(BTN_TRIGGER_HAPPY7), BTN(BTN_TRIGGER_HAPPY8), BTN(BTN_TRIGGER_HAPPY9),
	BTN(BTN_TRIGGER_HAPPY10), BTN(BTN_TRIGGER_HAPPY11), BTN(BTN_TRIGGER_HAPPY12),
	BTN(BTN_TRIGGER_HAPPY13), BTN(BTN_TRIGGER_HAPPY14), BTN(BTN_TRIGGER_HAPPY15),
	BTN(BTN_TRIGGER_HAPPY16), BTN(BTN_TRIGGER_HAPPY17), BTN(BTN_TRIGGER_HAPPY18),
	BTN(BTN_TRIGGER_HAPPY19), BTN(BTN_TRIGGER_HAPPY20), BTN(BTN_TRIGGER_HAPPY21),
	BTN(BTN_TRIGGER_HAPPY22), BTN(BTN_TRIGGER_HAPPY23), BTN(BTN_TRIGGER_HAPPY24),
	BTN(BTN_TRIGGER_HAPPY25), BTN(BTN_TRIGGER_HAPPY26), BTN(BTN_TRIGGER_HAPPY27),
	BTN(BTN_TRIGGER_HAPPY28), BTN(BTN_TRIGGER_HAPPY29), BTN(BTN_TRIGGER_HAPPY30),
	BTN(BTN_TRIGGER_HAPPY31), BTN(BTN_TRIGGER_HAPPY32), BTN(BTN_TRIGGER_HAPPY33),
	BTN(BTN_TRIGGER_HAPPY34), BTN(BTN_TRIGGER_HAPPY35), BTN(BTN_TRIGGER_HAPPY36),
	BTN(BTN_TRIGGER_HAPPY37), BTN(BTN_TRIGGER_HAPPY38), BTN(BTN_TRIGGER_HAPPY39),
	BTN(BTN_TRIGGER_HAPPY40),
};
#undef BTN

const char *
can_map_code_to_str(uint16_t code)
{
	for (size_t i = 0; i < sizeof btn_names / sizeof btn_names[0]; i++)
		if (btn_names[i].code == code)
			return btn_names[i].name;
	return NULL;
}

int
can_map_find(const struct can_map *m, const char *name)
{
	for (int i = 0; i < m->n; i++)
		if (strcmp(m->line[i].name, name) == 0)
			return i;
	return -1;
}

/* the network (sequential) position of a DBC sawtooth bit number */
static int
network_bit(int sawtooth)
{
	return 8 * (sawtooth / 8) + 7 - sawtooth % 8;
}

/* a whole token of decimal digits into *dest, at most max; 0 or -1 */
static int
parse_uint(const char **s, unsigned max, unsigned *dest)
{
	const char *p = *s;
	unsigned v = 0;
	if (*p < '0' || *p > '9')
		return -1;
	while (*p >= '0' && *p <= '9') {
		v = v * 10 + (unsigned)(*p - '0');
		if (v > max)
			return -1;
		p++;
	}
	*s = p;
	*dest = v;
	return 0;
}

static int
parse_double(const char *s, double *dest)
{
	char *end;
	if (!*s)
		return -1;
	errno = 0;
	double v = strtod(s, &end);
	if (*end || errno == ERANGE || !isfinite(v))
		return -1;
	*dest = v;
	return 0;
}

static int
parse_int64(const char *s, int64_t *dest)
{
	char *end;
	if (!*s)
		return -1;
	errno = 0;
	long long v = strtoll(s, &end, 10);
	if (*end || errno == ERANGE)
		return -1;
	*dest = v;
	return 0;
}

static int
parse_hex_id(const char *s, uint32_t *dest)
{
	size_t n = strlen(s);
	uint32_t v = 0;
	if (n != 3 && n != 8)
		return -1;
	for (size_t i = 0; i < n; i++) {
		int d = textfile_hex_digit(s[i]);
		if (d < 0)
			return -1;
		v = v << 4 | (unsigned)d;
	}
	if (n == 3 && v > CAN_SFF_MASK)
		return -2;
	if (n == 8 && v > CAN_EFF_MASK)
		return -2;
	*dest = n == 8 ? v | CAN_EFF_FLAG : v;
	return 0;
}

static int
name_valid(const char *s)
{
	size_t n = strlen(s);
	if (n == 0 || n >= CAN_MAP_NAME_MAX)
		return 0;
	for (size_t i = 0; i < n; i++) {
		char c = s[i];
		if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
		      c == '_' || c == '.' || c == '-'))
			return 0;
	}
	return 1;
}

/* the field token into start, length, order and sign; NULL or a message */
static const char *
field_parse(const char *tok, struct can_map_line *l)
{
	const char *p = tok;
	unsigned a, b;
	if (strchr(tok, '|')) {
		/* S|L@O+ */
		if (parse_uint(&p, 63, &a) || *p++ != '|')
			return "a DBC field is START|LENGTH@ORDER+ or -, e.g. 3|13@1-";
		if (parse_uint(&p, 64, &b) || b == 0)
			return "the field's length must be 1..64 bits";
		if (*p++ != '@' || (*p != '0' && *p != '1'))
			return "a DBC field's order is @1 (Intel) or @0 (Motorola)";
		l->order = *p++ == '1' ? CAN_MAP_INTEL : CAN_MAP_MOTOROLA;
		if (*p != '+' && *p != '-')
			return "a DBC field ends with + (unsigned) or - (signed)";
		l->is_signed = *p++ == '-';
		if (*p)
			return "unexpected characters after the field";
		l->start = (uint8_t)a;
		l->length = (uint8_t)b;
	} else if (strchr(tok, '.')) {
		/* N.b */
		if (parse_uint(&p, 7, &a) || *p++ != '.' || parse_uint(&p, 7, &b) || *p)
			return "a bit field is BYTE.BIT, both 0..7";
		l->order = CAN_MAP_INTEL;
		l->is_signed = 0;
		l->start = (uint8_t)(8 * a + b);
		l->length = 1;
	} else {
		/* N or A-B, then le/be, then +/- */
		if (parse_uint(&p, 7, &a))
			return "a field is a byte (0..7), a byte range A-B, a bit N.b "
			       "or START|LENGTH@ORDER+";
		b = a;
		if (p[0] == '-' && p[1] >= '0' && p[1] <= '9') {
			p++;
			if (parse_uint(&p, 7, &b) || b < a)
				return "a byte range A-B needs A <= B <= 7";
		}
		int be = 0;
		if (strncmp(p, "le", 2) == 0) {
			p += 2;
		} else if (strncmp(p, "be", 2) == 0) {
			be = 1;
			p += 2;
		}
		l->is_signed = 0;
		if (*p == '+' || *p == '-')
			l->is_signed = *p++ == '-';
		if (*p)
			return "unexpected characters after the field";
		l->order = be ? CAN_MAP_MOTOROLA : CAN_MAP_INTEL;
		l->start = (uint8_t)(be ? 8 * a + 7 : 8 * a);
		l->length = (uint8_t)(8 * (b - a + 1));
	}
	/* place within the 64 bits of the frame */
	int first = l->order == CAN_MAP_INTEL ? l->start : network_bit(l->start);
	if (first + l->length > 64)
		return "the field runs past the 8 bytes of a CAN frame";
	l->nbytes = (uint8_t)((first + l->length - 1) / 8 + 1);
	l->shift = (uint8_t)(l->order == CAN_MAP_INTEL ? first : 64 - (first + l->length));
	l->mask = l->length == 64 ? ~(uint64_t)0 : ((uint64_t)1 << l->length) - 1;
	return NULL;
}

int
can_map_code_parse(const char *s, uint16_t *dest)
{
	for (size_t i = 0; i < sizeof btn_names / sizeof btn_names[0]; i++) {
		if (strcmp(btn_names[i].name, s) == 0) {
			*dest = btn_names[i].code;
			return 0;
		}
	}
	char *end;
	if (!(*s >= '0' && *s <= '9'))
		return -1;
	errno = 0;
	unsigned long v = strtoul(s, &end, 0);
	if (*end || errno || v == 0 || v > KEY_MAX)
		return -1;
	*dest = (uint16_t)v;
	return 0;
}

/* the options of one line; NULL or a message (in buf when it needs words) */
static const char *
options_parse(char **tok, int ntok, struct can_map *m, struct can_map_line *l, int *has_code,
	      char *buf, size_t buflen)
{
	unsigned seen = 0;
	static const char *const keys[] = { "factor", "offset", "clamp", "stale",
					    "mux",    "code",   "dlc" };
	for (int t = 0; t < ntok; t++) {
		char *eq = strchr(tok[t], '=');
		if (!eq) {
			snprintf(buf, buflen, "'%.40s' is not an option (KEY=VALUE)", tok[t]);
			return buf;
		}
		*eq = 0;
		const char *key = tok[t], *val = eq + 1;
		int k = -1;
		for (int i = 0; i < (int)(sizeof keys / sizeof keys[0]); i++)
			if (strcmp(keys[i], key) == 0)
				k = i;
		if (k < 0) {
			snprintf(buf, buflen,
				 "unknown option '%.40s' "
				 "(factor, offset, clamp, stale, mux, code, dlc)",
				 key);
			return buf;
		}
		if (seen & 1u << k) {
			snprintf(buf, buflen, "option '%s' given twice", key);
			return buf;
		}
		seen |= 1u << k;
		switch (k) {
		case 0:
			if (parse_double(val, &l->factor))
				return "factor= needs a finite number";
			break;
		case 1:
			if (parse_double(val, &l->offset))
				return "offset= needs a finite number";
			break;
		case 2: {
			if (l->kind != CAN_MAP_AXIS)
				return "clamp= is for axis lines";
			char *comma = strchr(val, ',');
			if (!comma)
				return "clamp= needs MIN,MAX";
			*comma = 0;
			if (parse_double(val, &l->clamp_min) ||
			    parse_double(comma + 1, &l->clamp_max))
				return "clamp= needs two finite numbers MIN,MAX";
			if (l->clamp_min > l->clamp_max)
				return "clamp=MIN,MAX needs MIN <= MAX";
			l->has_clamp = 1;
			break;
		}
		case 3: {
			const char *p = val;
			unsigned ms;
			if (parse_uint(&p, 3600000, &ms) || *p)
				return "stale= needs milliseconds, 0..3600000";
			l->stale_ms = ms;
			break;
		}
		case 4: {
			char *colon = strrchr(val, ':');
			if (!colon)
				return "mux= needs NAME:VALUE[,VALUE...]";
			*colon = 0;
			int sel = can_map_find(m, val);
			if (sel < 0) {
				snprintf(buf, buflen, "mux=%.63s: no earlier line has that name",
					 val);
				return buf;
			}
			if (m->line[sel].kind != CAN_MAP_MUX) {
				snprintf(buf, buflen, "mux=%.63s: that line is not a mux line",
					 val);
				return buf;
			}
			if (m->line[sel].can_id != l->can_id) {
				snprintf(buf, buflen, "mux=%.63s: that mux line has another id",
					 val);
				return buf;
			}
			l->mux_line = (int16_t)sel;
			char *v = colon + 1;
			for (;;) {
				char *comma = strchr(v, ',');
				if (comma)
					*comma = 0;
				if (l->n_mux == CAN_MAP_MUX_VALUES)
					return "mux= takes at most 8 values";
				if (parse_int64(v, &l->mux_values[l->n_mux]))
					return "mux= values are integers";
				l->n_mux++;
				if (!comma)
					break;
				v = comma + 1;
			}
			break;
		}
		case 5:
			if (l->kind != CAN_MAP_BUTTON)
				return "code= is for button lines";
			if (can_map_code_parse(val, &l->code))
				return "code= needs a BTN_* name or a code 1..0x2ff";
			*has_code = 1;
			break;
		case 6: {
			const char *p = val;
			unsigned d;
			if (parse_uint(&p, 8, &d) || *p || d == 0)
				return "dlc= needs a length 1..8";
			l->dlc = (uint8_t)d;
			break;
		}
		}
	}
	return NULL;
}

/* one line's tokens into m->line[m->n]; NULL or a message */
static const char *
line_parse(char **tok, int ntok, struct can_map *m, int *has_code, char *buf, size_t buflen)
{
	struct can_map_line *l = &m->line[m->n];
	memset(l, 0, sizeof *l);
	l->factor = 1;
	l->mux_line = -1;
	l->stale_ms = CAN_MAP_STALE_DEFAULT_MS;
	*has_code = 0;
	if (strcmp(tok[0], "axis") == 0)
		l->kind = CAN_MAP_AXIS;
	else if (strcmp(tok[0], "button") == 0)
		l->kind = CAN_MAP_BUTTON;
	else if (strcmp(tok[0], "mux") == 0)
		l->kind = CAN_MAP_MUX;
	else {
		snprintf(buf, buflen, "unknown line kind '%.40s' (axis, button or mux)", tok[0]);
		return buf;
	}
	if (ntok < 4)
		return "a line is KIND ID FIELD NAME [OPTION=VALUE ...]";
	int r = parse_hex_id(tok[1], &l->can_id);
	if (r == -1)
		return "the id is 3 hex digits (standard) or 8 (extended), as candump writes it";
	if (r == -2)
		return "the id is out of range (standard 000..7FF, extended 00000000..1FFFFFFF)";
	const char *msg = field_parse(tok[2], l);
	if (msg)
		return msg;
	if (!name_valid(tok[3]))
		return "a name is 1..63 letters, digits, '_', '.' or '-'";
	if (can_map_find(m, tok[3]) >= 0) {
		snprintf(buf, buflen, "the name '%s' is already used", tok[3]);
		return buf;
	}
	memcpy(l->name, tok[3], strlen(tok[3]) + 1);
	return options_parse(tok + 4, ntok - 4, m, l, has_code, buf, buflen);
}

/* the index by id (see struct can_map) */
static void
index_build(struct can_map *m)
{
	m->n_ids = 0;
	for (int i = 0; i < m->n; i++) {
		uint32_t id = m->line[i].can_id;
		int j = 0;
		while (j < m->n_ids && m->ids[j] < id)
			j++;
		if (j < m->n_ids && m->ids[j] == id)
			continue;
		memmove(&m->ids[j + 1], &m->ids[j], (size_t)(m->n_ids - j) * sizeof m->ids[0]);
		m->ids[j] = id;
		m->n_ids++;
	}
	int k = 0;
	for (int j = 0; j < m->n_ids; j++) {
		m->id_first[j] = (uint16_t)k;
		int len = 0;
		for (int i = 0; i < m->n; i++) {
			const struct can_map_line *l = &m->line[i];
			if (l->can_id != m->ids[j])
				continue;
			m->by_id[k++] = (uint16_t)i;
			if (l->nbytes > len)
				len = l->nbytes;
			if (l->dlc > len)
				len = l->dlc;
		}
		m->id_count[j] = (uint16_t)(k - m->id_first[j]);
		m->id_len[j] = (uint8_t)len;
	}
}

/* a refusal: "name:line: msg" */
#define fail(err, errlen, name, lineno, msg) \
	textfile_fail((err), (errlen), (name), (unsigned)(lineno), "%s", (msg))

int
can_map_parse(const char *text, size_t n, const char *name, struct can_map *dest, char *err,
	      size_t errlen)
{
	struct can_map *m = malloc(sizeof *m);
	if (!m)
		return fail(err, errlen, name, 0, "out of memory");
	m->n = 0;
	char line[CAN_MAP_MAX_LINE_CHARS + 1];
	char buf[160];
	int has_code[CAN_MAP_MAX_LINES];
	int line_no[CAN_MAP_MAX_LINES]; /* each map line's line in the text */
	size_t pos = 0;
	int lineno = 0;
	while (pos < n) {
		/* one line, without its end and comment */
		lineno++;
		size_t end = pos;
		while (end < n && text[end] != '\n')
			end++;
		size_t len = end - pos;
		if (len > CAN_MAP_MAX_LINE_CHARS) {
			free(m);
			return fail(err, errlen, name, lineno,
				    "line too long (at most 1024 characters)");
		}
		memcpy(line, text + pos, len);
		line[len] = 0;
		pos = end + 1;
		if (strlen(line) != len) {
			free(m);
			return fail(err, errlen, name, lineno, "a NUL byte in the line");
		}
		char *hash = strchr(line, '#');
		if (hash)
			*hash = 0;
		/* tokens */
		char *tok[MAX_TOKENS];
		int ntok = 0;
		char *save = NULL;
		for (char *t = strtok_r(line, " \t\r\f\v", &save); t;
		     t = strtok_r(NULL, " \t\r\f\v", &save)) {
			if (ntok == MAX_TOKENS) {
				free(m);
				return fail(err, errlen, name, lineno,
					    "too many words in the line");
			}
			tok[ntok++] = t;
		}
		if (ntok == 0)
			continue;
		if (m->n == CAN_MAP_MAX_LINES) {
			free(m);
			return fail(err, errlen, name, lineno, "too many lines (at most 256)");
		}
		const char *msg = line_parse(tok, ntok, m, &has_code[m->n], buf, sizeof buf);
		if (msg) {
			free(m);
			return fail(err, errlen, name, lineno, msg);
		}
		line_no[m->n++] = lineno;
	}
	if (m->n == 0) {
		free(m);
		return fail(err, errlen, name, lineno > 0 ? lineno : 1,
			    "no axis, button or mux line in the map");
	}
	/* default button codes, in order */
	int nbutton = 0;
	for (int i = 0; i < m->n; i++) {
		if (m->line[i].kind != CAN_MAP_BUTTON)
			continue;
		if (!has_code[i]) {
			if (BTN_TRIGGER_HAPPY1 + nbutton > BTN_TRIGGER_HAPPY40) {
				int at = line_no[i];
				free(m);
				return fail(err, errlen, name, at,
					    "more than 40 buttons without code= (the default codes are "
					    "BTN_TRIGGER_HAPPY1..40): give this one a code=");
			}
			m->line[i].code = (uint16_t)(BTN_TRIGGER_HAPPY1 + nbutton);
		}
		nbutton++;
	}
	index_build(m);
	memcpy(dest, m, sizeof *m);
	free(m);
	return 0;
}

int
can_map_read(const char *path, struct can_map *dest, char *err, size_t errlen)
{
	size_t n;
	char *text = textfile_read(path, &n, err, errlen);
	if (!text)
		return -1;
	int rc = can_map_parse(text, n, path, dest, err, errlen);
	free(text);
	return rc;
}


static const char *
kind_to_str(enum can_map_kind k)
{
	switch (k) {
	case CAN_MAP_AXIS:
		return "axis";
	case CAN_MAP_BUTTON:
		return "button";
	case CAN_MAP_MUX:
		return "mux";
	}
	return "?";
}

int
can_map_write(FILE *out, const struct can_map *m)
{
	char a[32], b[32];
	fprintf(out, "# kind  id  field  name  options (see devices/can_map.h)\n");
	for (int i = 0; i < m->n; i++) {
		const struct can_map_line *l = &m->line[i];
		if (l->can_id & CAN_EFF_FLAG)
			snprintf(a, sizeof a, "%08X", l->can_id & CAN_EFF_MASK);
		else
			snprintf(a, sizeof a, "%03X", l->can_id & CAN_SFF_MASK);
		fprintf(out, "%s %s %u|%u@%c%c %s", kind_to_str((enum can_map_kind)l->kind), a,
			l->start, l->length, l->order == CAN_MAP_INTEL ? '1' : '0',
			l->is_signed ? '-' : '+', l->name);
		if (l->factor != 1) {
			textfile_number_write(a, sizeof a, l->factor);
			fprintf(out, " factor=%s", a);
		}
		if (l->offset != 0 || signbit(l->offset)) {
			textfile_number_write(a, sizeof a, l->offset);
			fprintf(out, " offset=%s", a);
		}
		if (l->has_clamp) {
			textfile_number_write(a, sizeof a, l->clamp_min);
			textfile_number_write(b, sizeof b, l->clamp_max);
			fprintf(out, " clamp=%s,%s", a, b);
		}
		if (l->stale_ms != CAN_MAP_STALE_DEFAULT_MS)
			fprintf(out, " stale=%u", l->stale_ms);
		if (l->mux_line >= 0) {
			fprintf(out, " mux=%s:", m->line[l->mux_line].name);
			for (int v = 0; v < l->n_mux; v++)
				fprintf(out, "%s%lld", v ? "," : "", (long long)l->mux_values[v]);
		}
		if (l->kind == CAN_MAP_BUTTON) {
			const char *c = can_map_code_to_str(l->code);
			if (c)
				fprintf(out, " code=%s", c);
			else
				fprintf(out, " code=0x%x", l->code);
		}
		if (l->dlc)
			fprintf(out, " dlc=%u", l->dlc);
		fputc('\n', out);
	}
	return ferror(out) ? -1 : 0;
}

int
can_map_filters(const struct can_map *m, struct can_filter *dest, int max)
{
	for (int j = 0; j < m->n_ids && j < max; j++) {
		uint32_t id = m->ids[j];
		dest[j].can_id = id;
		uint32_t mask = (id & CAN_EFF_FLAG) ? CAN_EFF_MASK : CAN_SFF_MASK;
		dest[j].can_mask = mask | CAN_EFF_FLAG;
	}
	return m->n_ids;
}
