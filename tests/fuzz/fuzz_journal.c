/*
 * fuzz_journal.c - the journal as recovery reads it (daemon/journal.h:
 * journal_replay_text), from memory: the record lines and their checksums
 * checked, a damaged tail told from damage in the middle, and the whole
 * records replayed into a daemon without a loop (commands through the real
 * dispatch, file texts unescaped, the solver's postures, step marks).
 *
 * The first byte chooses how the rest is taken: even, as it is, as a file
 * on disk would be; odd, every line of it first sealed with its right
 * checksum (a last line without its newline stays torn), so that the
 * fuzzer reaches what the records say. Commands that write files write
 * them in a folder of their own under /tmp, emptied after an input that
 * wrote there, so each input starts from the same nothing; figure files
 * come from src/figure/library (POSTURE_FUZZ_LIBRARY names another).
 *
 * Whatever it reads: no crash, leak or hang; a refusal (damage in the
 * middle) names the journal and changes nothing; otherwise the bytes kept
 * are whole records, and as many as were counted.
 *
 * Inputs are kept to 4 KiB, a few dozen records: longer ones only
 * repeat commands.
 *
 * fuzz-options: -max_len=4096
 * fuzz-link: -Wl,--wrap=human_build,--wrap=figure_read_file
 */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "daemon/journal.h"
#include "model_cache.h"
#include "daemon/journal_scan.h"
#include "devices/queue.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
const char *__asan_default_options(void);

/* freed memory held back 8 MiB, not 256: an input frees megabytes of figures, and
 * fresh pages for every allocation were half of its time */
const char *
__asan_default_options(void)
{
	return "quarantine_size_mb=8";
}

static struct daemon d;
static struct input_queue q;
static char dir[64];

static void
daemon_fresh(void)
{
	const char *lib = getenv("POSTURE_FUZZ_LIBRARY");
	memset(&d, 0, sizeof d);
	env_init(&d.env);
	snprintf(d.state_dir, sizeof d.state_dir, "%s", dir);
	snprintf(d.library_dir, sizeof d.library_dir, "%s", lib ? lib : "src/figure/library");
	d.picked.fig = -1;
	d.pointer_view = -1;
	d.screen_w = 1280;
	d.screen_h = 720;
	input_queue_init(&q);
	d.input = &q;
}

static void
daemon_done(void)
{
	char err[300];
	if (d.step.open) /* as journal_open does with a step never ended */
		daemon_step_abandon(&d, err, sizeof err);
	daemon_checkpoints_clear(&d.undo);
	daemon_checkpoints_clear(&d.redo);
	daemon_text_clear(&d.file_read);
	daemon_text_clear(&d.file_given);
	daemon_picks_free(&d);
	env_clear(&d.env);
	struct input_event_rec e;
	while (input_queue_pop(&q, &e))
		;
}

/* what the input's commands wrote (save, export) removed, when they wrote anything */
static void
empty_dir(void)
{
	static struct timespec seen;
	struct stat st;
	if (stat(dir, &st) < 0)
		abort();
	if (st.st_mtim.tv_sec == seen.tv_sec && st.st_mtim.tv_nsec == seen.tv_nsec)
		return;
	DIR *dp = opendir(dir);
	if (!dp)
		abort();
	for (struct dirent *e; (e = readdir(dp));) {
		char path[400];
		if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
			snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
			remove(path); /* the commands write files, beside each other */
		}
	}
	closedir(dp);
	if (stat(dir, &st) < 0)
		abort();
	seen = st.st_mtim;
}

static void
remove_dir(void)
{
	rmdir(dir); /* emptied after every input */
}

/* every line with its checksum after it, as the journal writes them */
static char *
sealed(const char *text, size_t len, size_t *out)
{
	size_t lines = 0;
	for (size_t i = 0; i < len; i++)
		lines += text[i] == '\n';
	char *buf = malloc(len + 9 * lines + 1), *o = buf;
	if (!buf)
		abort();
	for (const char *p = text, *end = text + len; p < end;) {
		const char *nl = memchr(p, '\n', (size_t)(end - p));
		size_t n = nl ? (size_t)(nl - p) : (size_t)(end - p);
		memcpy(o, p, n);
		o += n;
		if (nl)
			o += sprintf(o, " %08x\n", journal_crc32(0, p, n));
		p += n + (nl != NULL);
	}
	*out = (size_t)(o - buf);
	return buf;
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static int ready;
	if (!ready) {
		snprintf(dir, sizeof dir, "/tmp/fuzz-journal-%ld", (long)getpid());
		mkdir(dir, 0700);
		atexit(remove_dir);
		ready = 1;
	}
	if (size < 1)
		return 0;
	size_t len = size - 1;
	char *text = data[0] & 1 ? sealed((const char *)data + 1, len, &len) : malloc(len + 1);
	if (!text)
		abort();
	if (!(data[0] & 1))
		memcpy(text, data + 1, len);
	struct journal j = { .fd = -1 };
	snprintf(j.path, sizeof j.path, "%s/journal", dir);
	daemon_fresh();
	char err[600];
	size_t keep = 0;
	/* the snapshot's number: the first byte's other bits, so records may be skipped */
	uint64_t snap_seq = data[0] >> 1;
	if (journal_replay_text(&j, &d, text, len, snap_seq, &keep, err, sizeof err) < 0) {
		if (!strstr(err, j.path) || env_count(&d.env))
			abort(); /* a refusal names the journal and replays nothing */
	} else {
		struct journal_scan s;
		journal_scan(text, keep, &s);
		if (keep > len || s.damage != JOURNAL_WHOLE || s.good != keep ||
		    (s.records && s.last_seq != j.seq) || s.records != j.since_snap)
			abort();
	}
	daemon_done();
	empty_dir();
	free(text);
	return 0;
}
