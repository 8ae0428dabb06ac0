/*
 * fuzz_frame_log.c - a recording's frame log (daemon/tape.h) through the
 * replay's reader: the input is the `frames` file of a recording whose
 * other files are whole (a manifest of a killed recording, so a torn tail
 * is allowed, a start with the human, two lines). Whatever it accepts or
 * refuses, it must not crash, leak or read out of bounds; a refusal names
 * the file and its line.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "daemon/journal.h"
#include "daemon/tape_read.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char dir[64];

static void
put(const char *name, const void *text, size_t n)
{
	char path[128];
	snprintf(path, sizeof path, "%s/%s", dir, name);
	FILE *f = fopen(path, "w");
	if (!f)
		abort();
	fwrite(text, 1, n, f);
	fclose(f);
}

/* the recording's other files, once */
static void
prepare(void)
{
	snprintf(dir, sizeof dir, "/tmp/fuzz-frame-log-%ld", (long)getpid());
	mkdir(dir, 0700);
	static const char manifest[] = "posture-recording 1\nstate recording\n";
	static const char lines[] = "100 0 load human as jack\n200 3 input key KEY_A down\n";
	static const char start[] = "posture 1\nend\nundo 0\nredo 0\nkiosk pointer -1 0 0\n"
				    "kiosk picked -1 0\n";
	put("manifest", manifest, sizeof manifest - 1);
	put("lines", lines, sizeof lines - 1);
	put("config", "fps = 60\n", 9);
	put("start", start, sizeof start - 1);
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static int ready;
	static struct tape t;
	static struct daemon d;
	char err[4800], *config = NULL;
	if (!ready) {
		prepare();
		ready = 1;
	}
	put("frames", data, size);
	memset(&d, 0, sizeof d);
	env_init(&d.env);
	snprintf(d.state_dir, sizeof d.state_dir, "%s", dir);
	if (tape_replay_open(&t, dir, &d, &config, err, sizeof err) == 0) {
		for (const struct tape_entry *e; (e = tape_peek(&t));)
			tape_take(&t);
		free(config);
		tape_free(&t);
	} else if (!strstr(err, dir)) {
		abort(); /* a refusal names its file */
	}
	daemon_checkpoints_clear(&d.undo);
	daemon_checkpoints_clear(&d.redo);
	env_clear(&d.env);
	return 0;
}
