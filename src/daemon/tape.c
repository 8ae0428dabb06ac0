/* tape.c - making a recording: its folder, its one-off files, and the writer thread */
#include "daemon/tape.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "daemon/journal.h"
#include "daemon/posture_hash.h"
#include "daemon/statefile.h"

const char *
tape_kind_name(enum tape_kind kind)
{
	static const char *const name[] = {
		[TAPE_CLOCK] = "a clock read",     [TAPE_LINE] = "a line",
		[TAPE_FRAME] = "a frame",          [TAPE_IK] = "a solve's work",
		[TAPE_FIG] = "a figure's hash",    [TAPE_JOINTS] = "joints' hashes",
		[TAPE_POSTURE] = "a frame's end",  [TAPE_STOP] = "the stop",
		[TAPE_DEVICE] = "a device's file", [TAPE_DEVCALL] = "a device's decoder call",
		[TAPE_EVENT] = "a device event",   [TAPE_FILE] = "a state file read",
	};
	return (unsigned)kind < sizeof name / sizeof *name && name[kind] ? name[kind] : "a record";
}

uint64_t
tape_real_now(void)
{
	struct timespec t;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return (uint64_t)t.tv_sec * 1000000u + (uint64_t)t.tv_nsec / 1000u;
}

static int
pending(const struct tape *t)
{
	for (int i = 0; i < t->nout; i++)
		if (t->out[i].len)
			return 1;
	return 0;
}

/* the writer thread: takes each file's buffer whole and writes it */
static void *
writer_main(void *arg)
{
	struct tape *t = arg;
	pthread_mutex_lock(&t->mu);
	for (;;) {
		while (!t->quit && !pending(t))
			pthread_cond_wait(&t->work, &t->mu);
		if (!pending(t))
			break;
		for (int i = 0; i < t->nout; i++) {
			struct tape_out *o = &t->out[i];
			char *b = o->wbuf;
			o->wbuf = o->buf;
			o->wlen = o->len;
			o->buf = b;
			o->len = 0;
		}
		pthread_cond_broadcast(&t->room);
		pthread_mutex_unlock(&t->mu);
		int bad = 0;
		for (int i = 0; i < t->nout; i++) {
			struct tape_out *o = &t->out[i];
			if (o->wlen && o->fd >= 0 && statefile_write_all(o->fd, o->wbuf, o->wlen) < 0)
				bad = errno ? errno : EIO;
			o->wlen = 0;
		}
		pthread_mutex_lock(&t->mu);
		if (bad && !t->write_error) {
			t->write_error = bad;
			fprintf(stderr, "postured: recording %s: %s\n", t->dir, strerror(bad));
		}
	}
	pthread_mutex_unlock(&t->mu);
	return NULL;
}

void
tape_out_bytes(struct tape *t, int id, const void *bytes, size_t n)
{
	if (t->mode != TAPE_RECORD || id >= t->nout || n > TAPE_OUT_BYTES)
		return;
	struct tape_out *o = &t->out[id];
	pthread_mutex_lock(&t->mu);
	while (o->len + n > TAPE_OUT_BYTES) { /* the writer is behind: the loop waits, counted */
		t->waits++;
		pthread_cond_signal(&t->work);
		pthread_cond_wait(&t->room, &t->mu);
	}
	memcpy(o->buf + o->len, bytes, n);
	o->len += n;
	pthread_mutex_unlock(&t->mu);
}

void
tape_out_printf(struct tape *t, int id, const char *fmt, ...)
{
	char buf[1024];
	va_list ap;
	va_start(ap, fmt);
	int n = vsnprintf(buf, sizeof buf, fmt, ap);
	va_end(ap);
	if (n > 0)
		tape_out_bytes(t, id, buf, (size_t)n < sizeof buf ? (size_t)n : sizeof buf - 1);
}

void
tape_out_escaped(struct tape *t, int id, const char *text, size_t n)
{
	char buf[1024];
	size_t k = 0;
	for (size_t i = 0; i < n; i++) {
		unsigned char c = (unsigned char)text[i];
		if (k + 5 > sizeof buf) {
			tape_out_bytes(t, id, buf, k);
			k = 0;
		}
		if (c == '\\') {
			buf[k++] = '\\';
			buf[k++] = '\\';
		} else if (c < 0x20 || c == 0x7f) {
			k += (size_t)snprintf(buf + k, 5, "\\x%02x", c);
		} else {
			buf[k++] = (char)c;
		}
	}
	buf[k++] = '\n';
	tape_out_bytes(t, id, buf, k);
}

int
tape_out_open(struct tape *t, int id, const char *name)
{
	char path[TAPE_PATH_MAX + 64];
	snprintf(path, sizeof path, "%s/%s", t->dir, name);
	struct tape_out *o = &t->out[id];
	o->buf = malloc(TAPE_OUT_BYTES);
	o->wbuf = malloc(TAPE_OUT_BYTES);
	o->fd = o->buf && o->wbuf ? open(path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0640) : -1;
	if (o->fd < 0) {
		int e = o->buf && o->wbuf ? errno : ENOMEM;
		free(o->buf);
		free(o->wbuf);
		o->buf = o->wbuf = NULL;
		errno = e;
		return -1;
	}
	pthread_mutex_lock(&t->mu);
	if (id >= t->nout)
		t->nout = id + 1;
	pthread_mutex_unlock(&t->mu);
	return 0;
}

/* a folder to record into: made, or there and empty */
static int
make_empty_dir(const char *dir, char *err, size_t errlen)
{
	if (mkdir(dir, 0750) == 0)
		return 0;
	if (errno != EEXIST) {
		snprintf(err, errlen, "%s: %s", dir, strerror(errno));
		return -1;
	}
	DIR *d = opendir(dir);
	if (!d) {
		snprintf(err, errlen, "%s: %s", dir, strerror(errno));
		return -1;
	}
	int full = 0;
	for (struct dirent *e; !full && (e = readdir(d));)
		full = strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
	closedir(d);
	if (full)
		snprintf(err, errlen, "%s: not empty (a recording goes into a new folder)", dir);
	return full ? -1 : 0;
}

int
tape_write_file(const struct tape *t, const char *name, const char *text, size_t len)
{
	char path[TAPE_PATH_MAX + 64];
	snprintf(path, sizeof path, "%s/%s", t->dir, name);
	return statefile_write(path, text, len);
}

/* the manifest: what each file is, and whether the recording was ended cleanly */
static int
write_manifest(const struct tape *t, int complete)
{
	char text[8192];
	int n = snprintf(text, sizeof text, "posture-recording %d\n", TAPE_VERSION);
	if (complete)
		n += snprintf(text + n, sizeof text - (size_t)n,
			      "state complete frames=%" PRIu64 " lines=%" PRIu64 "\n", t->frames,
			      t->lines);
	else
		n += snprintf(text + n, sizeof text - (size_t)n, "state recording\n");
	n += snprintf(text + n, sizeof text - (size_t)n,
		      "file config config the settings, key = value\n"
		      "file start state the session and undo history when recording began\n"
		      "file lines lines the clients' lines: T_US CLIENT TEXT\n"
		      "file frames frames the frame log\n"
		      "files read.N read the state files commands read, as read (file N in the log)\n");
	for (int k = 0; k < t->dev_files && (size_t)n < sizeof text - 200; k++)
		n += snprintf(text + n, sizeof text - (size_t)n, "file %s\n", t->dev_file[k]);
	return tape_write_file(t, "manifest", text, (size_t)n);
}

/* the start: the state as a snapshot holds it, then what lives outside the session */
static int
write_start(const struct tape *t, const struct daemon *d)
{
	char *buf = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&buf, &len);
	if (!f)
		return -1;
	int bad = journal_state_write(d, f);
	fprintf(f, "kiosk pointer %d %.17g %.17g\n", d->pointer_view, d->pointer_x, d->pointer_y);
	fprintf(f, "kiosk picked %d %d\n", d->picked.fig, d->picked.joint);
	bad |= ferror(f);
	fclose(f);
	int rc = bad ? -1 : tape_write_file(t, "start", buf, len);
	free(buf);
	return rc;
}

static void
close_outs(struct tape *t)
{
	for (int i = 0; i < TAPE_OUTS; i++) {
		struct tape_out *o = &t->out[i];
		if (o->buf || o->wbuf) {
			if (o->fd >= 0)
				close(o->fd);
			free(o->buf);
			free(o->wbuf);
		}
		memset(o, 0, sizeof *o);
		o->fd = -1;
	}
	t->nout = 0;
}

int
tape_record_start(struct tape *t, const char *dir, const struct daemon *d, const char *config,
		  char *err, size_t errlen)
{
	if (t->mode != TAPE_OFF) {
		snprintf(err, errlen, "already %s %s", t->mode == TAPE_RECORD ? "recording into" : "replaying",
			 t->dir);
		return -1;
	}
	if (strlen(dir) >= sizeof t->dir - 64) {
		snprintf(err, errlen, "the folder's path is too long");
		return -1;
	}
	if (make_empty_dir(dir, err, errlen) < 0)
		return -1;
	memset(t, 0, sizeof *t);
	snprintf(t->dir, sizeof t->dir, "%s", dir);
	for (int i = 0; i < TAPE_OUTS; i++)
		t->out[i].fd = -1;
	pthread_mutex_init(&t->mu, NULL);
	pthread_cond_init(&t->work, NULL);
	pthread_cond_init(&t->room, NULL);
	t->mode = TAPE_RECORD;
	if ((config && tape_write_file(t, "config", config, strlen(config)) < 0) || write_start(t, d) < 0 ||
	    write_manifest(t, 0) < 0 || tape_out_open(t, TAPE_OUT_FRAMES, "frames") < 0 ||
	    tape_out_open(t, TAPE_OUT_LINES, "lines") < 0) {
		snprintf(err, errlen, "%s: %s", dir, strerror(errno));
		goto fail;
	}
	/* the writer takes no signals: they are the loop's (its signalfd) */
	sigset_t all, old;
	sigfillset(&all);
	pthread_sigmask(SIG_SETMASK, &all, &old);
	int made = pthread_create(&t->writer, NULL, writer_main, t);
	pthread_sigmask(SIG_SETMASK, &old, NULL);
	if (made != 0) {
		snprintf(err, errlen, "no writer thread");
		goto fail;
	}
	t->writer_on = 1;
	tape_out_printf(t, TAPE_OUT_FRAMES, "# posture frame log %d\n", TAPE_VERSION);
	for (int i = 0; i < ENV_MAX_FIGURES; i++)
		t->fig_hash[i] = d->env.fig[i].gen ? posture_figure_hash(&d->env.fig[i]) : 0;
	return 0;
fail:
	close_outs(t);
	t->mode = TAPE_OFF;
	return -1;
}

void
tape_flush(struct tape *t)
{
	if (t->mode != TAPE_RECORD)
		return;
	/* the writer woken at most every TAPE_FLUSH_US: each wake costs the loop's CPUs a switch */
	uint64_t now = tape_real_now();
	if (now - t->flushed_us < TAPE_FLUSH_US)
		return;
	t->flushed_us = now;
	pthread_mutex_lock(&t->mu);
	pthread_cond_signal(&t->work);
	pthread_mutex_unlock(&t->mu);
}

int
tape_record_stop(struct tape *t)
{
	if (t->mode != TAPE_RECORD)
		return 0;
	tape_out_printf(t, TAPE_OUT_FRAMES, "stop\n");
	if (t->writer_on) {
		pthread_mutex_lock(&t->mu);
		t->quit = 1;
		pthread_cond_signal(&t->work);
		pthread_mutex_unlock(&t->mu);
		pthread_join(t->writer, NULL);
	}
	int bad = t->write_error || !t->writer_on;
	for (int i = 0; i < t->nout; i++)
		if (t->out[i].fd >= 0 && fsync(t->out[i].fd) < 0)
			bad = 1;
	close_outs(t);
	if (!bad && write_manifest(t, 1) < 0)
		bad = 1;
	pthread_mutex_destroy(&t->mu);
	pthread_cond_destroy(&t->work);
	pthread_cond_destroy(&t->room);
	fprintf(stderr, "postured: recording %s ended: %" PRIu64 " frames, %" PRIu64 " lines%s\n",
		t->dir, t->frames, t->lines, bad ? " (not all of it was written)" : "");
	t->mode = TAPE_OFF;
	return bad ? -1 : 0;
}
