/* tape_read.c - reading a recording for a replay: every file checked, errors as file:line */
#include "daemon/tape_read.h"

#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon/journal.h"
#include "daemon/posture_hash.h"
#include "daemon/statefile.h"
#include "devices/textfile.h"

/* the message into err; -1, for "return say(...)" */
#define say(err, errlen, ...) textfile_fail(err, errlen, NULL, 0, __VA_ARGS__)

/* the file dir/name, whole and NUL-terminated; NULL with err */
static char *
slurp(const struct tape *t, const char *name, size_t *len, char *err, size_t errlen)
{
	char path[TAPE_PATH_MAX + 64];
	snprintf(path, sizeof path, "%s/%s", t->dir, name);
	char *text = statefile_read(path, len);
	if (!text)
		say(err, errlen, "%s: %s", path, strerror(errno));
	return text;
}

/* the next line of text from *p (its end put at *end), or NULL at the end of the text */
static char *
next_line(char **p, const char *stop, int *torn)
{
	char *s = *p;
	if (s >= stop)
		return NULL;
	char *nl = memchr(s, '\n', (size_t)(stop - s));
	*torn = !nl;
	if (!nl)
		nl = (char *)stop;
	*nl = 0;
	*p = nl + 1;
	return s;
}

static int
read_manifest(struct tape *t, char *err, size_t errlen)
{
	size_t len;
	char *text = slurp(t, "manifest", &len, err, errlen);
	if (!text)
		return -1;
	char *p = text, *line;
	int torn, ver = 0, n = 0, rc = 0, state = 0;
	unsigned long long frames = 0, lines = 0;
	while (rc == 0 && (line = next_line(&p, text + len, &torn))) {
		n++;
		if (n == 1) {
			if (sscanf(line, "posture-recording %d", &ver) != 1 || ver != TAPE_VERSION)
				rc = say(err, errlen, "%s/manifest:1: not a posture recording of version %d",
					 t->dir, TAPE_VERSION);
		} else if (!strncmp(line, "state ", 6)) {
			state = 1;
			if (!strcmp(line, "state recording"))
				t->complete = 0;
			else if (sscanf(line, "state complete frames=%llu lines=%llu", &frames, &lines) == 2)
				t->complete = 1;
			else
				rc = say(err, errlen, "%s/manifest:%d: state recording, or state complete "
						      "frames=N lines=N", t->dir, n);
		}
	}
	if (rc == 0 && !state)
		rc = say(err, errlen, "%s/manifest:%d: no state line", t->dir, n);
	t->frames = frames; /* what a complete recording must hold; counted again as it is read */
	t->lines = lines;
	free(text);
	return rc;
}

static int
unescape(char *s, size_t *len)
{
	char *w = s;
	for (const char *r = s; *r; r++) {
		if (*r != '\\') {
			*w++ = *r;
			continue;
		}
		unsigned v;
		if (r[1] == '\\') {
			*w++ = '\\';
			r++;
		} else if (r[1] == 'x' && sscanf(r + 2, "%2x", &v) == 1 && r[2] && r[3]) {
			*w++ = (char)v;
			r += 3;
		} else {
			return -1;
		}
	}
	*len = (size_t)(w - s);
	*w = 0;
	return 0;
}

int
tape_lines_read(const char *path, int torn_ok, struct tape_line **dest, size_t *count, char *err,
		size_t errlen)
{
	size_t len;
	char *text = statefile_read(path, &len);
	*dest = NULL;
	*count = 0;
	if (!text)
		return say(err, errlen, "%s: %s", path, strerror(errno));
	size_t cap = 0;
	for (size_t i = 0; i < len; i++)
		cap += text[i] == '\n';
	struct tape_line *out = calloc(cap + 1, sizeof *out);
	int rc = out ? 0 : say(err, errlen, "out of memory");
	char *p = text, *line;
	int torn, n = 0;
	size_t nline = 0;
	uint64_t last = 0;
	while (rc == 0 && (line = next_line(&p, text + len, &torn))) {
		n++;
		unsigned long long tu;
		int client, used = 0;
		struct tape_line *l = &out[nline];
		if (torn && torn_ok) /* a line being written when the daemon was killed: no frame ran it */
			break;
		if (sscanf(line, "%llu %d %n", &tu, &client, &used) != 2 || !used ||
		    line[used - 1] != ' ' || unescape(line + used, &l->len) < 0 || tu < last) {
			rc = say(err, errlen, "%s:%d: expected T_US CLIENT TEXT, in time order", path, n);
			break;
		}
		l->t_us = last = tu;
		l->client = client;
		if (!(l->text = malloc(l->len + 1))) {
			rc = say(err, errlen, "out of memory");
			break;
		}
		memcpy(l->text, line + used, l->len + 1);
		nline++;
	}
	free(text);
	if (rc < 0 && out) {
		for (size_t i = 0; i < nline; i++)
			free(out[i].text);
		free(out);
		return -1;
	}
	*dest = out;
	*count = nline;
	return rc;
}

static int
read_lines(struct tape *t, char *err, size_t errlen)
{
	char path[TAPE_PATH_MAX + 16];
	snprintf(path, sizeof path, "%s/lines", t->dir);
	return tape_lines_read(path, 1, &t->line, &t->nline, err, errlen);
}

static int
hex_bytes(const char *s, struct tape_entry *e)
{
	size_t n = strlen(s);
	if (n % 2 || !(e->text = malloc(n / 2 + 1)))
		return -1;
	for (size_t k = 0; k < n / 2; k++) {
		unsigned v;
		if (sscanf(s + 2 * k, "%2x", &v) != 1)
			return -1;
		e->text[k] = (char)v;
	}
	e->ntext = n / 2;
	return 0;
}

/* device, dev and event records (tape_dev.h) into e; 0, or -1 with why */
static int
parse_device_record(char *line, struct tape_entry *e, char *why, size_t whylen)
{
	unsigned long long t, count;
	int dev, used = 0, arg;
	char a[32], b[64], c[64], call[16], rest[300];
	double dpi;
	unsigned kind, code, flags;
	int value;
	if (sscanf(line, "device %d %31s %63s %63s dpi=%lf%n", &dev, a, b, c, &dpi, &used) == 5 &&
	    !line[used]) {
		e->kind = TAPE_DEVICE;
		e->fig = dev;
		e->x = dpi;
		if (!(e->text = malloc(200)))
			return say(why, whylen, "out of memory");
		snprintf(e->text, 200, "%s %s %s", a, b, c);
		return 0;
	}
	if (sscanf(line, "dev %d %15s %llu%n", &dev, call, &t, &used) == 3) {
		e->kind = TAPE_DEVCALL;
		e->fig = dev;
		e->t = t;
		char *p = line + used;
		if (!strcmp(call, "bytes") && sscanf(p, " %llu%n", &count, &used) == 1 && !p[used]) {
			e->sub = INPUT_TAP_BYTES;
			e->count = count;
		} else if (!strcmp(call, "resync") && sscanf(p, " %299s%n", rest, &used) == 1 &&
			   !p[used] && hex_bytes(rest, e) == 0) {
			e->sub = INPUT_TAP_RESYNC;
		} else if (!strcmp(call, "release") && sscanf(p, " %d%n", &arg, &used) == 1 &&
			   !p[used]) {
			e->sub = INPUT_TAP_RELEASE;
			e->arg = arg;
		} else if (!strcmp(call, "tick") && !*p) {
			e->sub = INPUT_TAP_TICK;
		} else {
			return say(why, whylen, "dev DEV bytes|resync|release|tick T ...");
		}
		return 0;
	}
	if (sscanf(line, "event %d %llu %u %u %d %u %lf %lf%n", &dev, &t, &kind, &code, &value,
		   &flags, &e->ev.x, &e->ev.y, &used) == 8 && !line[used] && dev >= 0 &&
	    dev < 0xffff && kind <= INPUT_FRAME && code <= 0xffff && flags <= 0xff) {
		e->kind = TAPE_EVENT;
		e->ev.device = (uint16_t)dev;
		e->ev.t_us = t;
		e->ev.kind = (uint8_t)kind;
		e->ev.code = (uint16_t)code;
		e->ev.value = value;
		e->ev.flags = (uint8_t)flags;
		return 0;
	}
	return say(why, whylen, "not a device record of the frame log");
}

/* one record of the frame log into e; 0, or -1 with why */
static int
parse_record(struct tape *t, char *line, struct tape_entry *e, char *why, size_t whylen)
{
	unsigned long long a, b;
	int fig, used = 0;
	if (sscanf(line, "clock %llu%n", &a, &used) == 1 && !line[used]) {
		e->kind = TAPE_CLOCK;
		e->t = a;
	} else if (sscanf(line, "line %llu%n", &a, &used) == 1 && !line[used]) {
		if (a < 1 || a > t->nline)
			return say(why, whylen, "line %llu: `lines` has %zu", a, t->nline);
		e->kind = TAPE_LINE;
		e->t = a;
	} else if (sscanf(line, "frame %llu t=%llu%n", &a, &b, &used) == 2 && !line[used]) {
		e->kind = TAPE_FRAME;
		e->t = b;
	} else if (sscanf(line, "ik %d %n", &fig, &used) == 1 && used) {
		char msg[200];
		if (ik_work_read(line + used, &e->work, msg, sizeof msg) < 0)
			return say(why, whylen, "%s", msg);
		e->kind = TAPE_IK;
		e->fig = fig;
	} else if (sscanf(line, "fig %d %llx%n", &fig, &a, &used) == 2 && !line[used]) {
		e->kind = TAPE_FIG;
		e->fig = fig;
		e->hash = a;
	} else if (sscanf(line, "joints %d%n", &fig, &used) == 1) {
		uint32_t h[TAPE_JOINTS_MAX];
		int n = 0;
		for (char *s = line + used; *s;) {
			unsigned v;
			int k = 0;
			if (n >= TAPE_JOINTS_MAX || sscanf(s, " %8x%n", &v, &k) != 1 || (s[k] != ' ' && s[k]))
				return say(why, whylen, "joints FIG, then at most %d hex hashes",
					   TAPE_JOINTS_MAX);
			h[n++] = v;
			s += k;
		}
		if (!(e->joints = malloc(sizeof *h * (size_t)(n ? n : 1))))
			return say(why, whylen, "out of memory");
		memcpy(e->joints, h, sizeof *h * (size_t)n);
		e->kind = TAPE_JOINTS;
		e->fig = fig;
		e->njoints = n;
	} else if (sscanf(line, "posture %llu %llx%n", &a, &b, &used) == 2 && !line[used]) {
		e->kind = TAPE_POSTURE;
		e->t = a;
		e->hash = b;
	} else if (!strcmp(line, "stop")) {
		e->kind = TAPE_STOP;
	} else if (sscanf(line, "file %llu%n", &a, &used) == 1 && !line[used]) {
		if (a < 1)
			return say(why, whylen, "file N counts from 1");
		e->kind = TAPE_FILE;
		e->t = a;
		e->fig = 0;
	} else if (sscanf(line, "nofile %d%n", &fig, &used) == 1 && !line[used]) {
		if (fig <= 0)
			return say(why, whylen, "nofile ERRNO, a positive number");
		e->kind = TAPE_FILE;
		e->t = 0;
		e->fig = fig;
	} else if (!strncmp(line, "device ", 7) || !strncmp(line, "dev ", 4) ||
		   !strncmp(line, "event ", 6)) {
		if (parse_device_record(line, e, why, whylen) < 0)
			return -1;
	} else {
		return say(why, whylen, "not a record of the frame log");
	}
	if ((e->kind == TAPE_IK || e->kind == TAPE_FIG || e->kind == TAPE_JOINTS) &&
	    (e->fig < 0 || e->fig >= ENV_MAX_FIGURES))
		return say(why, whylen, "no figure slot %d", e->fig);
	if ((e->kind == TAPE_DEVICE || e->kind == TAPE_DEVCALL) && (e->fig < 0 || e->fig >= TAPE_DEVS))
		return say(why, whylen, "no device %d", e->fig);
	return 0;
}

static int
read_frames(struct tape *t, char *err, size_t errlen)
{
	size_t len;
	char *text = slurp(t, "frames", &len, err, errlen);
	if (!text)
		return -1;
	size_t cap = 1;
	for (size_t i = 0; i < len; i++)
		cap += text[i] == '\n';
	t->ent = calloc(cap, sizeof *t->ent);
	int rc = t->ent ? 0 : say(err, errlen, "out of memory");
	char *p = text, *line;
	int torn, n = 0, stopped = 0;
	size_t whole = 0;          /* records up to the last complete frame */
	uint64_t frames = 0, lines = 0, whole_frames = 0, whole_lines = 0;
	while (rc == 0 && !stopped && (line = next_line(&p, text + len, &torn))) {
		n++;
		if (line[0] == '#' || !line[0])
			continue;
		if (torn && !t->complete) /* killed mid-record */
			break;
		struct tape_entry *e = &t->ent[t->nent];
		char why[300];
		if (parse_record(t, line, e, why, sizeof why) < 0) {
			free(e->joints);
			free(e->text);
			rc = say(err, errlen, "%s/frames:%d: %s", t->dir, n, why);
			break;
		}
		e->lineno = n;
		t->nent++;
		frames += e->kind == TAPE_FRAME;
		if (e->kind == TAPE_LINE && e->t != ++lines)
			rc = say(err, errlen, "%s/frames:%d: line %" PRIu64 " out of order (expected %" PRIu64
					      ")", t->dir, n, e->t, lines);
		if (e->kind == TAPE_POSTURE) {
			if (e->t != frames)
				rc = say(err, errlen, "%s/frames:%d: the end of frame %" PRIu64 " after frame %"
						      PRIu64, t->dir, n, e->t, frames);
			whole = t->nent;
			whole_frames = frames;
			whole_lines = lines;
		}
		stopped = e->kind == TAPE_STOP;
	}
	free(text);
	if (rc)
		return -1;
	if (t->complete) {
		if (!stopped)
			return say(err, errlen, "%s/frames:%d: truncated: the manifest says the recording "
						"was stopped, and this log has no stop", t->dir, n);
		if (frames != t->frames || lines != t->lines || t->nline != t->lines)
			return say(err, errlen, "%s/frames:%d: %" PRIu64 " frames and %" PRIu64 " lines (the "
						"lines file %zu), the manifest says %" PRIu64 " and %" PRIu64,
				   t->dir, n, frames, lines, t->nline, t->frames, t->lines);
		return 0;
	}
	/* killed: what followed the last complete frame is dropped */
	fprintf(stderr, "postured: %s was not stopped (the daemon was killed?): replaying its %" PRIu64
			" complete frames\n", t->dir, whole_frames);
	for (size_t i = whole; i < t->nent; i++) {
		free(t->ent[i].joints);
		free(t->ent[i].text);
	}
	t->nent = whole;
	t->frames = whole_frames;
	t->lines = whole_lines;
	return 0;
}

/* the "kiosk" lines after the state: what lives outside the session */
static int
read_kiosk(struct daemon *d, const char *p, const char *end, const char *dir, int line, char *err,
	   size_t errlen)
{
	while (p < end) {
		const char *nl = memchr(p, '\n', (size_t)(end - p));
		if (!nl)
			nl = end;
		char buf[256];
		snprintf(buf, sizeof buf, "%.*s", (int)(nl - p < 255 ? nl - p : 255), p);
		int used = 0;
		if (sscanf(buf, "kiosk pointer %d %lf %lf%n", &d->pointer_view, &d->pointer_x,
			   &d->pointer_y, &used) == 3 && !buf[used])
			;
		else if (sscanf(buf, "kiosk picked %d %d%n", &d->picked.fig, &d->picked.joint, &used) == 2 &&
			 !buf[used])
			d->picked.gen = d->picked.fig >= 0 && d->picked.fig < ENV_MAX_FIGURES
						? d->env.fig[d->picked.fig].gen : 0;
		else if (buf[0])
			return say(err, errlen, "%s/start:%d: expected a kiosk line", dir, line);
		p = nl + 1;
		line++;
	}
	return 0;
}

static int
read_start(struct tape *t, struct daemon *d, char *err, size_t errlen)
{
	size_t len;
	char *text = slurp(t, "start", &len, err, errlen);
	if (!text)
		return -1;
	/* the kiosk lines follow the redo checkpoints: found from the end */
	char *k = NULL;
	int line = 1;
	for (char *q = text; q && q < text + len; q = memchr(q, '\n', (size_t)(text + len - q)), q = q ? q + 1 : q) {
		if (!strncmp(q, "kiosk ", 6) && !k)
			k = q;
		line += !k;
	}
	char msg[400];
	int rc = 0;
	if (!k)
		rc = say(err, errlen, "%s/start: no kiosk lines (truncated?)", t->dir);
	else if (journal_state_read(d, text, (size_t)(k - text), msg, sizeof msg) < 0)
		rc = say(err, errlen, "%s/start: %s", t->dir, msg);
	else
		rc = read_kiosk(d, k, text + len, t->dir, line, err, errlen);
	free(text);
	return rc;
}

int
tape_replay_open(struct tape *t, const char *dir, struct daemon *d, char **config, char *err,
		 size_t errlen)
{
	memset(t, 0, sizeof *t);
	snprintf(t->dir, sizeof t->dir, "%s", dir);
	for (int i = 0; i < TAPE_OUTS; i++)
		t->out[i].fd = -1;
	size_t len;
	*config = NULL;
	if (read_manifest(t, err, errlen) < 0 || read_lines(t, err, errlen) < 0 ||
	    read_frames(t, err, errlen) < 0 || read_start(t, d, err, errlen) < 0 ||
	    !(*config = slurp(t, "config", &len, err, errlen))) {
		tape_free(t);
		return -1;
	}
	/* the recording's hashes begin as the start's: frames record changes */
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		const struct env_figure *f = &d->env.fig[i];
		t->live_fig[i] = f->gen ? posture_figure_hash(f) : 0;
	}
	t->mode = TAPE_REPLAY;
	t->frames = 0;
	t->lines = 0;
	return 0;
}

const struct tape_entry *
tape_peek(const struct tape *t)
{
	return t->pos < t->nent ? &t->ent[t->pos] : NULL;
}

const struct tape_line *
tape_line_at(const struct tape *t, uint64_t n)
{
	return n >= 1 && n <= t->nline ? &t->line[n - 1] : NULL;
}

void
tape_take(struct tape *t)
{
	if (t->pos < t->nent)
		t->pos++;
}

void
tape_free(struct tape *t)
{
	for (size_t i = 0; i < t->nent; i++) {
		free(t->ent[i].joints);
		free(t->ent[i].text);
	}
	free(t->ent);
	for (size_t i = 0; i < t->nline; i++)
		free(t->line[i].text);
	free(t->line);
	t->ent = NULL;
	t->line = NULL;
	t->nent = t->nline = 0;
	if (t->mode == TAPE_REPLAY)
		t->mode = TAPE_OFF;
}
