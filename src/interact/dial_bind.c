/* dial_bind.c - the dial panel's bindings: the file, the bind command, events to actions */
#include "interact/dial_bind.h"

#include <ctype.h>
#include <errno.h>
#include <linux/input-event-codes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "devices/can_map.h"
#include "devices/textfile.h"

#define MAX_WORDS 16 /* words in a statement: the longest has 9 */

/* ---- words and numbers, as the protocol has them (docs/protocol.md "Words") ---- */

/*
 * Splits line (NUL-terminated, no line end) into at most MAX_WORDS words
 * copied into buf (as long as line, plus one). '#' outside quotes ends the
 * line. Returns the number of words, or -1 with *msg.
 */
static int
split_words(const char *line, const char **w, char *buf, const char **msg)
{
	int n = 0;
	size_t i = 0, o = 0;
	for (;;) {
		while (line[i] == ' ' || line[i] == '\t')
			i++;
		if (!line[i] || line[i] == '#')
			return n;
		if (n == MAX_WORDS) {
			*msg = "too many words in the line";
			return -1;
		}
		w[n++] = &buf[o];
		int quoted = 0;
		while (line[i] && (quoted || !strchr(" \t#", line[i]))) {
			char c = line[i++];
			if (c == '"') {
				quoted = !quoted;
				continue;
			}
			if (quoted && c == '\\') {
				if (line[i] != '"' && line[i] != '\\') {
					*msg = "only \\\" and \\\\ may be escaped";
					return -1;
				}
				c = line[i++];
			}
			buf[o++] = c;
		}
		if (quoted) {
			*msg = "unbalanced quote";
			return -1;
		}
		buf[o++] = 0;
	}
}

/* the units of docs/protocol.md "Words"; scale takes a written value to metres or radians */
static const struct {
	const char *name;
	enum dial_unit unit;
	enum dial_quantity quantity;
	double scale;
} units[] = {
	{ "m", DIAL_UNIT_M, DIAL_QUANTITY_LENGTH, 1 },
	{ "cm", DIAL_UNIT_CM, DIAL_QUANTITY_LENGTH, 0.01 },
	{ "mm", DIAL_UNIT_MM, DIAL_QUANTITY_LENGTH, 0.001 },
	{ "deg", DIAL_UNIT_DEG, DIAL_QUANTITY_ANGLE, M_PI / 180 },
	{ "rad", DIAL_UNIT_RAD, DIAL_QUANTITY_ANGLE, 1 },
};

/* a finite decimal number, no unit; nan, inf and hex are refused as the protocol does */
static int
number_parse(const char *s, double *dest, const char **rest)
{
	const char *p = s + (*s == '+' || *s == '-');
	if (!isdigit((unsigned char)*p) && *p != '.')
		return -1;
	if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X'))
		return -1;
	char *end;
	errno = 0;
	double v = strtod(s, &end);
	if (end == s || errno == ERANGE || !isfinite(v))
		return -1;
	*dest = v;
	*rest = end;
	return 0;
}

/* a number with an optional unit of quantity q: as written, its unit, and in base units */
static int
quantity_parse(const char *s, enum dial_quantity q, double *written, uint8_t *unit, double *base)
{
	const char *end;
	double v;
	if (number_parse(s, &v, &end))
		return -1;
	if (!*end) {
		*written = *base = v;
		*unit = DIAL_UNIT_NONE;
		return 0;
	}
	for (size_t i = 0; i < sizeof units / sizeof units[0]; i++) {
		if (strcmp(end, units[i].name))
			continue;
		if (q != DIAL_QUANTITY_EITHER && q != units[i].quantity)
			return -1;
		double b = v * units[i].scale;
		if (!isfinite(b))
			return -1;
		*written = v;
		*unit = (uint8_t)units[i].unit;
		*base = b;
		return 0;
	}
	return -1;
}

static const char *
unit_to_str(enum dial_unit u)
{
	for (size_t i = 0; i < sizeof units / sizeof units[0]; i++)
		if (units[i].unit == u)
			return units[i].name;
	return "";
}


/* 1 when s is 1..max-1 letters, digits, '_', '.' or '-' */
static int
name_valid(const char *s, size_t max)
{
	size_t n = 0;
	for (; s[n]; n++)
		if (!(isalnum((unsigned char)s[n]) || s[n] == '_' || s[n] == '.' || s[n] == '-'))
			return 0;
	return n > 0 && n < max;
}

/* ---- buttons ---- */

static void
button_write(char *dest, size_t n, uint16_t code)
{
	const char *name = can_map_code_to_str(code);
	if (name)
		snprintf(dest, n, "%s", name);
	else
		snprintf(dest, n, "%u", code);
}

/* 1 when s is a command the caller can run: 1..DIAL_BIND_COMMAND_MAX-1 bytes, no control bytes */
static int
command_valid(const char *s)
{
	size_t n = 0;
	for (; s[n]; n++)
		if ((unsigned char)s[n] < 0x20 || s[n] == 0x7f)
			return 0;
	return n > 0 && n < DIAL_BIND_COMMAND_MAX;
}

/* ---- targets ---- */

static const char *const camera_names[] = { "sweep_h", "sweep_v", "zoom" };
static const char *const behavior_names[] = { "elevation", "torso_forward", "torso_lateral",
					      "torso_axial" };
static const char *const manip_names[] = { "x", "y", "z", "rx", "ry", "rz" };

/* the index of s among names[0..n-1], or -1 */
static int
word_index(const char *s, const char *const *names, int n)
{
	for (int i = 0; i < n; i++)
		if (!strcmp(s, names[i]))
			return i;
	return -1;
}

enum dial_quantity
dial_target_quantity(const struct dial_target *target)
{
	switch ((enum dial_target_kind)target->kind) {
	case DIAL_TARGET_DOF:
	case DIAL_TARGET_JOINT:
		return DIAL_QUANTITY_EITHER;
	case DIAL_TARGET_CAMERA:
		return target->axis == DIAL_CAMERA_ZOOM ? DIAL_QUANTITY_LENGTH
							: DIAL_QUANTITY_ANGLE;
	case DIAL_TARGET_BEHAVIOR:
		return target->axis == DIAL_BEHAVIOR_ELEVATION ? DIAL_QUANTITY_LENGTH
							       : DIAL_QUANTITY_ANGLE;
	case DIAL_TARGET_MANIP:
		return target->axis < DIAL_MANIP_RX ? DIAL_QUANTITY_LENGTH : DIAL_QUANTITY_ANGLE;
	}
	return DIAL_QUANTITY_EITHER;
}

const char *
dial_target_to_str(const struct dial_target *target, char *dest, size_t len)
{
	switch ((enum dial_target_kind)target->kind) {
	case DIAL_TARGET_DOF:
		snprintf(dest, len, "dof %u", target->dof);
		return dest;
	case DIAL_TARGET_JOINT:
		snprintf(dest, len, "joint %s %s %u", target->figure, target->joint, target->dof);
		return dest;
	case DIAL_TARGET_CAMERA:
		snprintf(dest, len, "camera %s", camera_names[target->axis]);
		return dest;
	case DIAL_TARGET_BEHAVIOR:
		snprintf(dest, len, "behavior %s", behavior_names[target->axis]);
		return dest;
	case DIAL_TARGET_MANIP:
		snprintf(dest, len, "manip %s", manip_names[target->axis]);
		return dest;
	}
	snprintf(dest, len, "?");
	return dest;
}

/* a DOF's index in its joint */
static int
dof_parse(const char *s, uint8_t *dest)
{
	if (!(s[0] >= '0' && s[0] < '0' + DIAL_BIND_DOF_MAX) || s[1])
		return -1;
	*dest = (uint8_t)(s[0] - '0');
	return 0;
}

/*
 * The target's words from w[0] into dest; *used says how many it took.
 * NULL, or a message (in buf when it needs words).
 */
static const char *
target_parse(const char *const *w, int n, struct dial_target *dest, int *used, char *buf,
	     size_t buflen)
{
	memset(dest, 0, sizeof *dest);
	if (n < 1)
		return "a dial needs a target: dof, joint, camera, behavior or manip";
	const char *kind = w[0];
	if (!strcmp(kind, "dof")) {
		dest->kind = DIAL_TARGET_DOF;
		if (n < 2 || dof_parse(w[1], &dest->dof))
			return "dof N needs a DOF of the joint, 0..5";
		*used = 2;
		return NULL;
	}
	if (!strcmp(kind, "joint")) {
		dest->kind = DIAL_TARGET_JOINT;
		if (n < 4)
			return "joint FIG JOINT N needs a figure, a joint and a DOF";
		if (!name_valid(w[1], DIAL_BIND_NAME_MAX) || !name_valid(w[2], DIAL_BIND_NAME_MAX))
			return "a figure's or joint's name is 1..47 letters, digits, '_', '.', '-'";
		if (dof_parse(w[3], &dest->dof))
			return "joint FIG JOINT N needs a DOF of the joint, 0..5";
		memcpy(dest->figure, w[1], strlen(w[1]) + 1);
		memcpy(dest->joint, w[2], strlen(w[2]) + 1);
		*used = 4;
		return NULL;
	}
	static const struct {
		const char *word;
		enum dial_target_kind kind;
		const char *const *names;
		int n;
		const char *choices;
	} axes[] = {
		{ "camera", DIAL_TARGET_CAMERA, camera_names, 3, "sweep_h, sweep_v or zoom" },
		{ "behavior", DIAL_TARGET_BEHAVIOR, behavior_names, 4,
		  "elevation, torso_forward, torso_lateral or torso_axial" },
		{ "manip", DIAL_TARGET_MANIP, manip_names, 6, "x, y, z, rx, ry or rz" },
	};
	for (size_t i = 0; i < sizeof axes / sizeof axes[0]; i++) {
		if (strcmp(kind, axes[i].word))
			continue;
		int a = n < 2 ? -1 : word_index(w[1], axes[i].names, axes[i].n);
		if (a < 0) {
			snprintf(buf, buflen, "%s needs %s", axes[i].word, axes[i].choices);
			return buf;
		}
		dest->kind = (uint8_t)axes[i].kind;
		dest->axis = (uint8_t)a;
		*used = 2;
		return NULL;
	}
	snprintf(buf, buflen, "unknown target '%.40s' (dof, joint, camera, behavior or manip)",
		 kind);
	return buf;
}

/* ---- statements ---- */

static const char *
gain_message(enum dial_quantity q)
{
	switch (q) {
	case DIAL_QUANTITY_LENGTH:
		return "gain= needs a finite number, bare or a length (m, cm, mm)";
	case DIAL_QUANTITY_ANGLE:
		return "gain= needs a finite number, bare or an angle (deg, rad)";
	case DIAL_QUANTITY_EITHER:
		return "gain= needs a finite number, bare, a length (m, cm, mm) or an angle "
		       "(deg, rad)";
	}
	return "gain= needs a finite number";
}

/* the options after a dial's target */
static const char *
dial_options_parse(const char *const *w, int n, struct dial_bind_dial *d, char *buf, size_t buflen)
{
	unsigned seen = 0;
	for (int i = 0; i < n; i++) {
		const char *opt = w[i], *val = strchr(opt, '=');
		size_t klen = val ? (size_t)(val - opt) : strlen(opt);
		int k;
		if (!val && !strcmp(opt, "invert"))
			k = 0;
		else if (val && klen == 4 && !strncmp(opt, "gain", 4))
			k = 1;
		else if (val && klen == 4 && !strncmp(opt, "dead", 4))
			k = 2;
		else {
			snprintf(buf, buflen, "unknown option '%.40s' (gain=, invert, dead=)", opt);
			return buf;
		}
		if (seen & 1u << k) {
			snprintf(buf, buflen, "option '%.*s' given twice", (int)klen, opt);
			return buf;
		}
		seen |= 1u << k;
		if (k == 0) {
			d->invert = 1;
		} else if (k == 1) {
			enum dial_quantity q = dial_target_quantity(&d->target);
			if (quantity_parse(val + 1, q, &d->gain_written, &d->gain_unit, &d->gain))
				return gain_message(q);
		} else {
			const char *end;
			if (number_parse(val + 1, &d->dead, &end) || *end || d->dead < 0)
				return "dead= needs a finite number >= 0, in the dial's units";
		}
	}
	return NULL;
}

/* "dial DIAL TARGET [options]" from w[0] == "dial" */
static const char *
dial_parse(const char *const *w, int n, struct dial_bind_dial *d, char *buf, size_t buflen)
{
	memset(d, 0, sizeof *d);
	d->index = -1;
	d->gain = d->gain_written = 1;
	d->gain_unit = DIAL_UNIT_NONE;
	if (n < 2 || !name_valid(w[1], DIAL_BIND_DIAL_MAX))
		return "a dial's name is 1..63 letters, digits, '_', '.' or '-' (the panel map's)";
	memcpy(d->name, w[1], strlen(w[1]) + 1);
	int used = 0;
	const char *msg = target_parse(w + 2, n - 2, &d->target, &used, buf, buflen);
	if (msg)
		return msg;
	return dial_options_parse(w + 2 + used, n - 2 - used, d, buf, buflen);
}

/* on=press|release */
static int
edge_parse(const char *s, uint8_t *dest)
{
	if (strncmp(s, "on=", 3))
		return -1;
	if (!strcmp(s + 3, "press"))
		*dest = DIAL_EDGE_PRESS;
	else if (!strcmp(s + 3, "release"))
		*dest = DIAL_EDGE_RELEASE;
	else
		return -1;
	return 0;
}

/* "button BUTTON COMMAND [on=...]" from w[0] == "button" */
static const char *
button_binding_parse(const char *const *w, int n, struct dial_bind_button *b)
{
	memset(b, 0, sizeof *b);
	if (n < 3)
		return "button BUTTON COMMAND [on=press|release]";
	if (can_map_code_parse(w[1], &b->code))
		return "a button is a BTN_* name or an evdev code 1..0x2ff";
	if (!command_valid(w[2]))
		return "a command is 1..1023 bytes without control characters";
	memcpy(b->command, w[2], strlen(w[2]) + 1);
	if (n > 4)
		return "button BUTTON COMMAND [on=press|release]: too many words "
		       "(quote the command)";
	if (n == 4 && edge_parse(w[3], &b->edge))
		return "button BUTTON COMMAND [on=press|release]: quote a command with spaces";
	return NULL;
}

static int
dial_find(const struct dial_bind *t, const char *name)
{
	for (int i = 0; i < t->ndial; i++)
		if (!strcmp(t->dial[i].name, name))
			return i;
	return -1;
}

int
dial_bind_button_find(const struct dial_bind *t, uint16_t code, uint8_t edge)
{
	for (int i = 0; i < t->nbutton; i++)
		if (t->button[i].code == code && t->button[i].edge == edge)
			return i;
	return -1;
}

/* the dial's code through lookup (-1 without one); a message when the panel has no such dial */
static const char *
dial_resolve(struct dial_bind_dial *d, const struct dial_bind_lookup *lookup, char *buf,
	     size_t buflen)
{
	d->index = -1;
	if (!lookup || !lookup->find)
		return NULL;
	int k = lookup->find(lookup->user, d->name);
	if (k < 0 || k >= DIAL_BIND_MAX_AXES) {
		snprintf(buf, buflen, "the panel has no dial '%s'", d->name);
		return buf;
	}
	d->index = k;
	return NULL;
}

/* ---- lookups ---- */

int
dial_bind_find_in_names(const void *names, const char *name)
{
	const struct dial_bind_names *nm = names;
	for (int i = 0; i < nm->n; i++)
		if (nm->name[i] && !strcmp(nm->name[i], name))
			return i;
	return -1;
}

int
dial_bind_find_in_map(const void *can_map, const char *name)
{
	const struct can_map *m = can_map;
	int k = can_map_find(m, name);
	if (k < 0 || m->line[k].kind == CAN_MAP_BUTTON)
		return -1;
	return k;
}

/* ---- the table ---- */

void
dial_bind_init(struct dial_bind *dest)
{
	memset(dest, 0, sizeof *dest);
}

void
dial_bind_reset(struct dial_bind *t)
{
	memset(t->has_ref, 0, sizeof t->has_ref);
}

int
dial_bind_resolve(struct dial_bind *t, const struct dial_bind_lookup *lookup)
{
	char buf[128];
	int unresolved = 0;
	for (int i = 0; i < t->ndial; i++)
		if (dial_resolve(&t->dial[i], lookup, buf, sizeof buf) || t->dial[i].index < 0)
			unresolved++;
	dial_bind_reset(t);
	return unresolved;
}

/* one line of the file, without its end, into t; NULL or a message */
static const char *
statement_parse(const char *const *w, int n, struct dial_bind *t, int lineno, int *dial_line,
		int *button_line, const struct dial_bind_lookup *lookup, char *buf, size_t buflen)
{
	const char *msg;
	if (!strcmp(w[0], "dial")) {
		struct dial_bind_dial d;
		if ((msg = dial_parse(w, n, &d, buf, buflen)))
			return msg;
		int k = dial_find(t, d.name);
		if (k >= 0) {
			snprintf(buf, buflen, "the dial '%s' is already bound on line %d", d.name,
				 dial_line[k]);
			return buf;
		}
		if (t->ndial == DIAL_BIND_MAX_DIALS)
			return "too many dials (at most 64)";
		if ((msg = dial_resolve(&d, lookup, buf, buflen)))
			return msg;
		dial_line[t->ndial] = lineno;
		t->dial[t->ndial++] = d;
		return NULL;
	}
	if (!strcmp(w[0], "button")) {
		struct dial_bind_button b;
		if ((msg = button_binding_parse(w, n, &b)))
			return msg;
		int k = dial_bind_button_find(t, b.code, b.edge);
		if (k >= 0) {
			snprintf(buf, buflen, "the button's %s is already bound on line %d",
				 b.edge == DIAL_EDGE_PRESS ? "press" : "release", button_line[k]);
			return buf;
		}
		if (t->nbutton == DIAL_BIND_MAX_BUTTONS)
			return "too many button commands (at most 64)";
		button_line[t->nbutton] = lineno;
		t->button[t->nbutton++] = b;
		return NULL;
	}
	if (!strcmp(w[0], "bindings"))
		return "the version is given once, on the first line";
	snprintf(buf, buflen, "unknown statement '%.40s' (dial or button)", w[0]);
	return buf;
}

/* "bindings N" with N this reader's version or older */
static const char *
version_parse(const char *const *w, int n, char *buf, size_t buflen)
{
	if (n != 2 || strcmp(w[0], "bindings")) {
		snprintf(buf, buflen, "not a bindings file (expected 'bindings %d')",
			 DIAL_BIND_VERSION);
		return buf;
	}
	size_t digits = strspn(w[1], "0123456789");
	unsigned long v = strtoul(w[1], NULL, 10);
	if (!digits || w[1][digits] || digits > 6 || v < 1) {
		snprintf(buf, buflen, "the version is a whole number (expected 'bindings %d')",
			 DIAL_BIND_VERSION);
		return buf;
	}
	if (v > DIAL_BIND_VERSION) {
		snprintf(buf, buflen, "bindings version %lu is newer than this reader's %d", v,
			 DIAL_BIND_VERSION);
		return buf;
	}
	return NULL;
}

/* the parser's working memory: too large for a stack */
struct parse_scratch {
	struct dial_bind t;
	char line[DIAL_BIND_LINE_MAX + 1];
	char words[DIAL_BIND_LINE_MAX + 1];
	int dial_line[DIAL_BIND_MAX_DIALS];
	int button_line[DIAL_BIND_MAX_BUTTONS];
};

#define fail(err, errlen, name, lineno, msg) \
	textfile_fail((err), (errlen), (name), (unsigned)(lineno), "%s", (msg))

/* the lines of text into s->t; NULL, or a message with *lineno where it is */
static const char *
lines_parse(const char *text, size_t n, struct parse_scratch *s,
	    const struct dial_bind_lookup *lookup, int *lineno, char *buf, size_t buflen)
{
	int versioned = 0;
	size_t pos = 0;
	*lineno = 0;
	while (pos < n) {
		/* one line, without its end */
		++*lineno;
		size_t end = pos;
		while (end < n && text[end] != '\n')
			end++;
		size_t len = end - pos;
		if (len > 0 && text[end - 1] == '\r')
			len--;
		if (len > DIAL_BIND_LINE_MAX)
			return "line too long (at most 4096 bytes)";
		memcpy(s->line, text + pos, len);
		s->line[len] = 0;
		pos = end + 1;
		if (strlen(s->line) != len)
			return "a NUL byte in the line";
		const char *w[MAX_WORDS];
		const char *msg;
		int nw = split_words(s->line, w, s->words, &msg);
		if (nw < 0)
			return msg;
		if (nw == 0)
			continue;
		if (!versioned) {
			if ((msg = version_parse(w, nw, buf, buflen)))
				return msg;
			versioned = 1;
			continue;
		}
		msg = statement_parse(w, nw, &s->t, *lineno, s->dial_line, s->button_line, lookup,
				      buf, buflen);
		if (msg)
			return msg;
	}
	if (!versioned) {
		if (*lineno == 0)
			*lineno = 1;
		snprintf(buf, buflen, "not a bindings file (expected 'bindings %d')",
			 DIAL_BIND_VERSION);
		return buf;
	}
	return NULL;
}

int
dial_bind_parse(const char *text, size_t n, const char *name,
		const struct dial_bind_lookup *lookup, struct dial_bind *dest, char *err,
		size_t errlen)
{
	struct parse_scratch *s = malloc(sizeof *s);
	if (!s)
		return fail(err, errlen, name, 0, "out of memory");
	dial_bind_init(&s->t);
	char buf[200];
	int lineno;
	const char *msg = lines_parse(text, n, s, lookup, &lineno, buf, sizeof buf);
	if (msg) {
		free(s);
		return fail(err, errlen, name, lineno, msg);
	}
	/* the counters go on across reloads */
	s->t.nonfinite = dest->nonfinite;
	s->t.overflow = dest->overflow;
	s->t.dead = dest->dead;
	s->t.lost = dest->lost;
	memcpy(dest, &s->t, sizeof *dest);
	free(s);
	return 0;
}

int
dial_bind_read(const char *path, const struct dial_bind_lookup *lookup, struct dial_bind *dest,
	       char *err, size_t errlen)
{
	size_t n;
	char *text = textfile_read(path, &n, err, errlen);
	if (!text)
		return -1;
	int rc = dial_bind_parse(text, n, path, lookup, dest, err, errlen);
	free(text);
	return rc;
}

/* ---- the run-time command ---- */

/* bind dial ...: the dial's binding replaced or added */
static const char *
bind_dial(struct dial_bind *t, const char *const *w, int n, const struct dial_bind_lookup *lookup,
	  char *buf, size_t buflen)
{
	struct dial_bind_dial d;
	const char *msg = dial_parse(w, n, &d, buf, buflen);
	if (msg || (msg = dial_resolve(&d, lookup, buf, buflen)))
		return msg;
	int k = dial_find(t, d.name);
	if (k < 0 && t->ndial == DIAL_BIND_MAX_DIALS)
		return "too many dials (at most 64)";
	t->dial[k < 0 ? t->ndial++ : k] = d;
	return NULL;
}

/* bind button ...: the edge's command replaced or added */
static const char *
bind_button(struct dial_bind *t, const char *const *w, int n)
{
	struct dial_bind_button b;
	const char *msg = button_binding_parse(w, n, &b);
	if (msg)
		return msg;
	int k = dial_bind_button_find(t, b.code, b.edge);
	if (k < 0 && t->nbutton == DIAL_BIND_MAX_BUTTONS)
		return "too many button commands (at most 64)";
	t->button[k < 0 ? t->nbutton++ : k] = b;
	return NULL;
}

static void
dial_remove(struct dial_bind *t, int k)
{
	memmove(&t->dial[k], &t->dial[k + 1], (size_t)(t->ndial - k - 1) * sizeof t->dial[0]);
	t->ndial--;
}

static void
button_remove(struct dial_bind *t, int k)
{
	memmove(&t->button[k], &t->button[k + 1],
		(size_t)(t->nbutton - k - 1) * sizeof t->button[0]);
	t->nbutton--;
}

/* unbind dial DIAL | unbind button BUTTON [on=...] */
static const char *
unbind(struct dial_bind *t, const char *const *w, int n, char *buf, size_t buflen)
{
	if (n >= 2 && !strcmp(w[0], "dial")) {
		if (n != 2)
			return "unbind dial DIAL";
		int k = dial_find(t, w[1]);
		if (k < 0) {
			snprintf(buf, buflen, "the dial '%.63s' is not bound", w[1]);
			return buf;
		}
		dial_remove(t, k);
		return NULL;
	}
	if (n >= 2 && !strcmp(w[0], "button")) {
		uint16_t code;
		uint8_t edge = 0;
		if (n > 3 || can_map_code_parse(w[1], &code) || (n == 3 && edge_parse(w[2], &edge)))
			return "unbind button BUTTON [on=press|release]";
		int want_press = n == 2 || edge == DIAL_EDGE_PRESS;
		int want_release = n == 2 || edge == DIAL_EDGE_RELEASE;
		int kp = want_press ? dial_bind_button_find(t, code, DIAL_EDGE_PRESS) : -1;
		int kr = want_release ? dial_bind_button_find(t, code, DIAL_EDGE_RELEASE) : -1;
		if (kp < 0 && kr < 0) {
			snprintf(buf, buflen, "the button '%.40s' has no command%s", w[1],
				 n == 3 ? " on that edge" : "");
			return buf;
		}
		/* the later first, so the earlier index still holds */
		if (kp > kr) {
			button_remove(t, kp);
			kp = -1;
		}
		if (kr >= 0)
			button_remove(t, kr);
		if (kp >= 0)
			button_remove(t, kp);
		return NULL;
	}
	return "unbind dial DIAL, or unbind button BUTTON [on=press|release]";
}

int
dial_bind_command(struct dial_bind *t, const char *const *w, int n,
		  const struct dial_bind_lookup *lookup, char *err, size_t errlen)
{
	char buf[200];
	const char *msg;
	if (n >= 2 && !strcmp(w[0], "bind") && !strcmp(w[1], "dial"))
		msg = bind_dial(t, w + 1, n - 1, lookup, buf, sizeof buf);
	else if (n >= 2 && !strcmp(w[0], "bind") && !strcmp(w[1], "button"))
		msg = bind_button(t, w + 1, n - 1);
	else if (n >= 1 && !strcmp(w[0], "unbind"))
		msg = unbind(t, w + 1, n - 1, buf, sizeof buf);
	else
		msg = "bind dial ..., bind button ..., unbind dial ... or unbind button ...";
	if (msg && err && errlen)
		snprintf(err, errlen, "%s", msg);
	return msg ? -1 : 0;
}

/* ---- the writer ---- */

/* the command in double quotes, '"' and '\' escaped */
static void
quoted_write(FILE *out, const char *s)
{
	fputc('"', out);
	for (; *s; s++) {
		if (*s == '"' || *s == '\\')
			fputc('\\', out);
		fputc(*s, out);
	}
	fputc('"', out);
}

int
dial_bind_write(FILE *out, const struct dial_bind *t)
{
	char target[160], num[40], button[24];
	fprintf(out, "bindings %d\n", DIAL_BIND_VERSION);
	for (int i = 0; i < t->ndial; i++) {
		const struct dial_bind_dial *d = &t->dial[i];
		textfile_number_write(num, sizeof num, d->gain_written);
		fprintf(out, "dial %s %s gain=%s%s", d->name,
			dial_target_to_str(&d->target, target, sizeof target), num,
			unit_to_str(d->gain_unit));
		if (d->invert)
			fprintf(out, " invert");
		if (d->dead != 0) {
			textfile_number_write(num, sizeof num, d->dead);
			fprintf(out, " dead=%s", num);
		}
		fputc('\n', out);
	}
	for (int i = 0; i < t->nbutton; i++) {
		const struct dial_bind_button *b = &t->button[i];
		button_write(button, sizeof button, b->code);
		fprintf(out, "button %s ", button);
		quoted_write(out, b->command);
		fprintf(out, "%s\n", b->edge == DIAL_EDGE_RELEASE ? " on=release" : "");
	}
	return ferror(out) ? -1 : 0;
}
