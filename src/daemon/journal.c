/* journal.c - the write-ahead record of state changes, and snapshots */
#include "daemon/journal.h"

#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "daemon/cmd.h"
#include "daemon/journal_scan.h"
#include "daemon/posture_hash.h"
#include "daemon/session.h"
#include "daemon/statefile.h"
#include "devices/textfile.h"

/* the message into err; -1, for "return say(...)" */
#define say(err, errlen, ...) textfile_fail(err, errlen, NULL, 0, __VA_ARGS__)

/* the current posture hashes, so only later solver changes are recorded */
static void
note_postures(struct journal *j, const struct daemon *d)
{
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		const struct env_figure *f = &d->env.fig[i];
		j->posture_gen[i] = f->gen;
		j->posture_hash[i] = f->gen ? posture_figure_hash(f) : 0;
	}
}

/* ---- snapshots ------------------------------------------------------------ */

static void
write_checkpoints(FILE *f, const char *name, const struct checkpoints *c)
{
	fprintf(f, "%s %d\n", name, c->n);
	for (int i = 0; i < c->n; i++) {
		fprintf(f, "checkpoint %zu\n", c->len[i]);
		fwrite(c->text[i], 1, c->len[i], f);
	}
}

int
journal_state_write(const struct daemon *d, FILE *f)
{
	struct assess_config cfg = daemon_assess_config(d);
	session_write_with(&d->env, &cfg, f);
	write_checkpoints(f, "undo", &d->undo);
	write_checkpoints(f, "redo", &d->redo);
	if (populations_write(&d->pops, f) < 0)
		return -1;
	return ferror(f) ? -1 : 0;
}

int
journal_snapshot(struct journal *j, const struct daemon *d, int force)
{
	if (j->fd < 0 || (!force && j->since_snap < JOURNAL_SNAPSHOT_RECORDS) || d->step.open)
		return 0;
	char *buf = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&buf, &len);
	if (!f)
		return -1;
	fprintf(f, "snapshot 1 %" PRIu64 "\n", j->seq);
	int bad = journal_state_write(d, f);
	fclose(f);
	if (bad || statefile_write(j->snap_path, buf, len) < 0) {
		free(buf);
		return -1;
	}
	free(buf);
	/* the snapshot holds everything: the records can go */
	if (ftruncate(j->fd, 0) < 0 || fsync(j->fd) < 0)
		return -1;
	j->size = 0;
	j->torn = 0;
	j->since_snap = 0;
	return 0;
}

/*
 * The line at p, before end, into buf without its newline; the byte after
 * it, or NULL when there is no whole line shorter than size. The text is
 * read within its length: it need not end in a NUL.
 */
static const char *
line_at(const char *p, const char *end, char *buf, size_t size)
{
	const char *nl = memchr(p, '\n', (size_t)(end - p));
	if (!nl || (size_t)(nl - p) >= size)
		return NULL;
	memcpy(buf, p, (size_t)(nl - p));
	buf[nl - p] = 0;
	return nl + 1;
}

/* "WORD N", N decimal and at most max: N, or -1 */
static long long
counted(const char *line, const char *word, unsigned long long max)
{
	size_t n = strlen(word);
	if (strncmp(line, word, n) || line[n] != ' ' || line[n + 1] < '0' || line[n + 1] > '9')
		return -1;
	char *e;
	errno = 0;
	unsigned long long v = strtoull(line + n + 1, &e, 10);
	return *e || errno || v > max ? -1 : (long long)v;
}

/* "NAME N", then N entries "checkpoint LEN\n" + LEN bytes; returns the rest or NULL */
static const char *
read_checkpoints(const char *p, const char *end, const char *name, struct checkpoints *dest)
{
	char line[64];
	long long n = (p = line_at(p, end, line, sizeof line)) ? counted(line, name, DAEMON_UNDO_MAX) : -1;
	if (n < 0)
		return NULL;
	for (long long i = 0; i < n; i++) {
		long long len = (p = line_at(p, end, line, sizeof line))
					? counted(line, "checkpoint", (unsigned long long)(end - p))
					: -1;
		if (len < 0)
			return NULL;
		char *text = malloc((size_t)len + 1);
		if (!text)
			return NULL;
		memcpy(text, p, (size_t)len);
		text[len] = 0;
		daemon_checkpoints_push(dest, text, (size_t)len);
		p += len;
	}
	return p;
}

int
journal_state_read(struct daemon *d, const char *body, size_t len, char *err, size_t errlen)
{
	const char *end = body + len;
	/* the session runs to its "end" line; the checkpoints follow */
	const char *stop = NULL;
	for (const char *q = body; !stop && q + 5 <= end; q++)
		if (!memcmp(q, "\nend\n", 5))
			stop = q;
	if (!stop)
		return say(err, errlen, "the session has no end");
	stop += 5;
	char msg[300];
	struct assess_config cfg;
	if (session_read_with(body, (size_t)(stop - body), d->state_dir, d->library_dir, &d->env,
			      &cfg, msg, sizeof msg) < 0)
		return say(err, errlen, "%s", msg);
	daemon_set_assess_config(d, &cfg);
	const char *p = read_checkpoints(stop, end, "undo", &d->undo);
	if (!p || !(p = read_checkpoints(p, end, "redo", &d->redo)))
		return say(err, errlen, "bad undo history");
	/* the populations loaded, when the state has them (older ones do not: none) */
	size_t used = 0;
	if (p < end && !strncmp(p, "populations ", 12)) {
		if (populations_read(&d->pops, p, (size_t)(end - p), &used, msg, sizeof msg) < 0)
			return say(err, errlen, "%s", msg);
	} else {
		populations_clear(&d->pops);
	}
	return 0;
}

static int
load_snapshot(struct journal *j, struct daemon *d, uint64_t *snap_seq, char *err, size_t errlen)
{
	size_t len;
	char *text = statefile_read(j->snap_path, &len);
	*snap_seq = 0;
	if (!text)
		return errno == ENOENT ? 0 : say(err, errlen, "%s: %s", j->snap_path, strerror(errno));
	const char *body = memchr(text, '\n', len);
	char msg[400];
	int rc = 0;
	if (!body || sscanf(text, "snapshot 1 %" SCNu64, snap_seq) != 1)
		rc = say(err, errlen, "%s: not a snapshot", j->snap_path);
	else if (journal_state_read(d, body + 1, len - (size_t)(body + 1 - text), msg, sizeof msg) < 0)
		rc = say(err, errlen, "%s: %s", j->snap_path, msg);
	free(text);
	return rc;
}

/* ---- recovery ------------------------------------------------------------- */

static int record(struct journal *j, char kind, const char *body, size_t len);

/* a kiosk step's mark, as the live daemon acted on it */
static void
replay_step(struct daemon *d, char kind, uint64_t seq)
{
	char msg[300];
	if (kind == 'B' && daemon_step_begin(d, -1, "replay") < 0)
		fprintf(stderr, "postured: journal record %" PRIu64 ": out of memory\n", seq);
	else if (kind == 'E')
		daemon_step_end(d);
	else if (kind == 'A' && daemon_step_abandon(d, msg, sizeof msg) < 0)
		fprintf(stderr, "postured: journal record %" PRIu64 ": %s\n", seq, msg);
}

/*
 * A file's text as one record's body: bytes below 0x20, DEL and '\\' as
 * \xHH, so a newline cannot end the record. NULL when out of memory.
 */
static char *
escape_text(const char *text, size_t len, size_t *out)
{
	char *buf = malloc(4 * len + 1), *q = buf;
	if (!buf)
		return NULL;
	for (size_t i = 0; i < len; i++) {
		unsigned char ch = (unsigned char)text[i];
		if (ch < 0x20 || ch == 0x7f || ch == '\\')
			q += sprintf(q, "\\x%02x", ch);
		else
			*q++ = (char)ch;
	}
	*q = 0;
	*out = (size_t)(q - buf);
	return buf;
}

/* escape_text undone into dest (malloc'd, NUL-terminated); -1 on a bad escape or no memory */
static int
unescape_text(const char *body, size_t len, struct daemon_text *dest)
{
	char *buf = malloc(len + 1), *q = buf;
	if (!buf)
		return -1;
	for (size_t i = 0; i < len; i++) {
		if (body[i] != '\\') {
			*q++ = body[i];
			continue;
		}
		int hi = i + 3 < len && body[i + 1] == 'x' ? textfile_hex_digit(body[i + 2]) : -1;
		int lo = hi >= 0 ? textfile_hex_digit(body[i + 3]) : -1;
		if (lo < 0) {
			free(buf);
			return -1;
		}
		*q++ = (char)(hi << 4 | lo);
		i += 3;
	}
	*q = 0;
	daemon_text_clear(dest);
	dest->text = buf;
	dest->len = (size_t)(q - buf);
	return 0;
}

/* one whole record after the snapshot, acted on as the live daemon did */
static void
replay_record(struct daemon *d, const struct journal_record *r)
{
	if (r->kind == 'C') {
		struct cmd_outcome out;
		cmd_run(d, -1, r->body, r->len, &out);
		if (!out.ok)
			fprintf(stderr, "postured: journal record %" PRIu64 " failed on replay: %s\n",
				r->seq, out.json ? out.json : "");
		free(out.json);
		daemon_text_clear(&d->file_given); /* for this command only */
	} else if (r->kind == 'F') {
		if (unescape_text(r->body, r->len, &d->file_given) < 0)
			fprintf(stderr, "postured: journal record %" PRIu64 ": a bad file record\n", r->seq);
	} else if (r->kind == 'P') {
		char msg[300];
		if (session_apply_line(&d->env, r->body, r->len, msg, sizeof msg) < 0)
			fprintf(stderr, "postured: journal record %" PRIu64 ": %s\n", r->seq, msg);
	} else if (r->kind == 'B' || r->kind == 'E' || r->kind == 'A') {
		replay_step(d, r->kind, r->seq);
	}
}

int
journal_replay_text(struct journal *j, struct daemon *d, const char *text, size_t len,
		    uint64_t snap_seq, size_t *keep, char *err, size_t errlen)
{
	struct journal_scan s;
	journal_scan(text, len, &s);
	if (s.damage == JOURNAL_MIDDLE)
		return say(err, errlen,
			   "%s: byte %zu: %s, and whole records follow it (record %" PRIu64
			   " at byte %zu): damage in the middle, not a crash's; the journal is left "
			   "as it is. To start from the records before it, cut it there (truncate "
			   "-s %zu); to start from the snapshot alone, move it aside",
			   j->path, s.good, s.why, s.next_seq, s.next, s.good);
	for (const char *p = text, *end = text + s.good; p < end;) {
		const char *nl = memchr(p, '\n', (size_t)(end - p)), *why;
		struct journal_record r;
		journal_scan_parse(&s, p, (size_t)(nl - p), &r, &why); /* whole: the scan said so */
		if (r.seq > snap_seq)
			replay_record(d, &r);
		j->seq = r.seq;
		j->since_snap++;
		p = nl + 1;
	}
	if (s.damage == JOURNAL_TAIL) {
		char after[48] = "before any whole record";
		if (s.records)
			snprintf(after, sizeof after, "after record %" PRIu64, s.last_seq);
		fprintf(stderr, "postured: journal %s: the last %zu bytes (from byte %zu, %s) are "
			"not a whole record (%s): dropped\n", j->path, len - s.good, s.good, after, s.why);
	}
	if (s.unchecked && s.records) {
		/* records of before are read as they were; a snapshot at once (journal_open)
		 * empties the file, so no record with a checksum is ever added after them */
		fprintf(stderr, "postured: journal %s: written before records had checksums; its %" PRIu64
			" records are read without them\n", j->path, s.records);
		j->unchecked = 1;
	}
	*keep = s.good;
	return 0;
}

static int
replay(struct journal *j, struct daemon *d, uint64_t snap_seq, char *err, size_t errlen)
{
	size_t len, keep;
	char *text = statefile_read(j->path, &len);
	if (!text)
		return errno == ENOENT ? 0 : say(err, errlen, "%s: %s", j->path, strerror(errno));
	int rc = journal_replay_text(j, d, text, len, snap_seq, &keep, err, errlen);
	free(text);
	if (rc == 0 && keep < len && ftruncate(j->fd, (off_t)keep) < 0)
		return say(err, errlen, "%s: cannot drop a damaged tail: %s", j->path, strerror(errno));
	j->size = keep;
	return rc;
}

int
journal_open(struct journal *j, struct daemon *d, char *err, size_t errlen)
{
	memset(j, 0, sizeof *j);
	snprintf(j->path, sizeof j->path, "%s/journal", d->state_dir);
	snprintf(j->snap_path, sizeof j->snap_path, "%s/snapshot", d->state_dir);
	j->fd = open(j->path, O_RDWR | O_CREAT | O_APPEND | O_CLOEXEC | O_NOFOLLOW, 0640);
	if (j->fd < 0)
		return say(err, errlen, "%s: %s", j->path, strerror(errno));
	uint64_t snap_seq;
	if (load_snapshot(j, d, &snap_seq, err, errlen) < 0 || replay(j, d, snap_seq, err, errlen) < 0)
		return -1;
	if (j->seq < snap_seq)
		j->seq = snap_seq;
	daemon_text_clear(&d->file_given); /* a file record torn from its command */
	/* a step begun and never ended: the daemon died mid-drag; back to before it */
	if (d->step.open) {
		if (daemon_step_abandon(d, err, errlen) < 0 || journal_step(j, 'A') < 0)
			return -1;
		fprintf(stderr, "postured: a step was under way when the daemon stopped: taken back\n");
	}
	if (j->unchecked) {
		if (journal_snapshot(j, d, 1) < 0)
			return say(err, errlen, "%s: cannot replace the journal written before checksums "
				   "with a snapshot: %s", j->path, strerror(errno));
		j->unchecked = 0;
	}
	note_postures(j, d);
	return 0;
}


static int
record(struct journal *j, char kind, const char *body, size_t len)
{
	if (j->fd < 0)
		return 0;
	/*
	 * A write that failed part way (a full disk) is cut back before the next
	 * record: records appended after a piece of one would be damage in the
	 * middle, which recovery refuses.
	 */
	if (j->torn && ftruncate(j->fd, (off_t)j->size) < 0)
		return -1;
	j->torn = 0;
	/* one write for the whole record, so a crash tears at most the last one */
	size_t n;
	char *buf = journal_record_format(j->seq + 1, kind, body, len, &n);
	if (!buf)
		return -1;
	int rc = statefile_write_all(j->fd, buf, n);
	free(buf);
	if (rc == 0) {
		j->size += n;
		j->seq++;
		j->since_snap++;
	} else {
		int e = errno;
		j->torn = ftruncate(j->fd, (off_t)j->size) < 0;
		errno = e;
	}
	return rc;
}


int
journal_postures(struct journal *j, const struct daemon *d)
{
	if (j->fd < 0)
		return 0;
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		const struct env_figure *f = &d->env.fig[i];
		if (!f->gen)
			continue;
		uint64_t h = posture_figure_hash(f);
		if (j->posture_gen[i] == f->gen && j->posture_hash[i] == h)
			continue;
		char *buf = NULL;
		size_t len = 0;
		FILE *m = open_memstream(&buf, &len);
		if (!m)
			return -1;
		session_write_figure_posture(&d->env, i, m);
		fclose(m);
		/* one record a statement: root, q, and a behaving figure's state */
		int rc = 0;
		for (char *line = buf, *nl; rc == 0 && line < buf + len; line = nl + 1) {
			nl = memchr(line, '\n', (size_t)(buf + len - line));
			if (!nl)
				break;
			rc = record(j, 'P', line, (size_t)(nl - line));
		}
		free(buf);
		if (rc)
			return -1;
		j->posture_gen[i] = f->gen;
		j->posture_hash[i] = h;
	}
	return 0;
}

int
journal_command(struct journal *j, const struct daemon *d, const char *line, size_t len)
{
	/* the state file the command read, as read: its 'F' record comes first */
	if (d->file_read.text && j->fd >= 0) {
		size_t n;
		char *body = escape_text(d->file_read.text, d->file_read.len, &n);
		int rc = body ? record(j, 'F', body, n) : -1;
		free(body);
		if (rc < 0)
			return -1;
	}
	/* the command as it is to be done again, its defaults written out (daemon.h) */
	if (d->journal_as[0]) {
		line = d->journal_as;
		len = strlen(line);
	}
	if (record(j, 'C', line, len) < 0)
		return -1;
	/* replaying the command reproduces its postures: no P records for them */
	note_postures(j, d);
	/* a big file read (a population) goes into a snapshot at once: the journal stays small */
	if (d->file_read.text && d->file_read.len > JOURNAL_FOLD_BYTES)
		return journal_snapshot(j, d, 1);
	return 0;
}

int
journal_sync(struct journal *j)
{
	if (j->fd < 0)
		return 0;
	return fdatasync(j->fd);
}

void
journal_close(struct journal *j)
{
	if (j->fd >= 0)
		close(j->fd);
	j->fd = -1;
}

int
journal_step(struct journal *j, char kind)
{
	return record(j, kind, "-", 1); /* a body, so the record reads like the others */
}
