/* tape_dev.c - the devices' side of a recording: their decoders' calls written down and replayed */
#include "daemon/tape_dev.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "devices/replay_dev.h"

/* ---- recording ---- */

static const char *const call_name[] = { "bytes", "resync", "release", "tick" };

static const char *
extension(const char *format)
{
	return !strcmp(format, "evemu") ? "evemu" : !strcmp(format, "hid-recorder") ? "hid" : "log";
}

/*
 * Device i's file begins (its head: the backend's description), and the
 * frame log says so. A device index used again after its device left gets
 * a new file.
 */
static void
open_device(struct tape *t, int i)
{
	const struct input_devs_place *p = &t->devs->place[i];
	t->dev_open[i] = 1;
	t->dev_out[i] = 0;
	if (!p->be || !p->be->describe)
		return;
	if (t->dev_files == TAPE_DEV_FILES) {
		fprintf(stderr, "postured: recording: more than %d devices: %s not recorded\n",
			TAPE_DEV_FILES, p->info.path);
		return;
	}
	const char *fmt = p->be->rec_format;
	int id = TAPE_OUT_DEV0 + t->dev_files;
	char file[64], map[64] = "-", *head = NULL;
	size_t len = 0;
	snprintf(file, sizeof file, "dev%d.%s", t->dev_files, extension(fmt));
	if (!strcmp(fmt, "candump"))
		snprintf(map, sizeof map, "dev%d.map", t->dev_files);
	t->dev_files++;
	FILE *f = open_memstream(&head, &len);
	if (!f)
		return;
	int bad = p->be->describe(p->dev, f) < 0;
	if (fclose(f) != 0 || bad) {
		free(head);
		fprintf(stderr, "postured: recording: %s cannot be described: not recorded\n",
			p->info.path);
		return;
	}
	int rc = strcmp(map, "-") ? tape_write_file(t, map, head, len) : 0;
	if (rc == 0)
		rc = tape_out_open(t, id, file);
	if (rc == 0 && strcmp(map, "-") == 0)
		tape_out_bytes(t, id, head, len);
	free(head);
	if (rc < 0) {
		fprintf(stderr, "postured: recording: %s: cannot write its file\n", p->info.path);
		return;
	}
	t->dev_out[i] = id;
	snprintf(t->dev_file[id - TAPE_OUT_DEV0], sizeof t->dev_file[0], "%s %s device %d: %.100s", file,
		 fmt, i, p->info.path);
	snprintf(t->dev_iface[i], sizeof t->dev_iface[i], "%s", p->info.path);
	tape_out_printf(t, TAPE_OUT_FRAMES, "device %d %s %s %s dpi=%.17g\n", i, fmt, file, map,
			p->info.dpi);
}

/* the read's bytes in the device's format: evemu records, a HID report, a CAN frame */
static size_t
write_bytes(struct tape *t, int i, const uint8_t *b, size_t n, uint64_t t_us)
{
	const char *fmt = t->devs->place[i].be->rec_format;
	char line[160 + 3 * 4096];
	int id = t->dev_out[i];
	if (!strcmp(fmt, "evemu")) {
		size_t count = n / sizeof(struct input_event);
		for (size_t k = 0; k < count; k++) {
			struct input_event e;
			memcpy(&e, b + k * sizeof e, sizeof e);
			int m = snprintf(line, sizeof line, "E: %lu.%06u %04x %04x %04d\n",
					 (unsigned long)e.input_event_sec, (unsigned)e.input_event_usec,
					 e.type, e.code, e.value);
			tape_out_bytes(t, id, line, (size_t)m);
		}
		return count;
	}
	if (!strcmp(fmt, "hid-recorder")) {
		size_t m = (size_t)snprintf(line, sizeof line, "E: %06" PRIu64 ".%06u %zu", t_us / 1000000,
					    (unsigned)(t_us % 1000000), n);
		for (size_t k = 0; k < n && k < 4096; k++)
			m += (size_t)snprintf(line + m, 4, " %02x", b[k]);
		line[m++] = '\n';
		tape_out_bytes(t, id, line, m);
		return 1;
	}
	/* candump -l: (seconds.micro) iface id#data */
	struct rec_candump_frame fr;
	uint8_t frame[16] = { 0 };
	memcpy(frame, b, n < sizeof frame ? n : sizeof frame);
	rec_candump_from_can_frame(frame, t_us, t->dev_iface[i], &fr);
	size_t m = rec_candump_format(line, sizeof line, &fr, 0, 0);
	tape_out_bytes(t, id, line, m);
	return 1;
}

static void
tapped_call(void *user, uint16_t device, enum input_tap_kind kind, int arg, const uint8_t *bytes,
	    size_t n, uint64_t t_us)
{
	struct tape *t = user;
	int i = device;
	if (i >= TAPE_DEVS || t->mode != TAPE_RECORD)
		return;
	if (!t->dev_open[i])
		open_device(t, i);
	if (!t->dev_out[i])
		return;
	char head[96];
	int m = snprintf(head, sizeof head, "dev %d %s %" PRIu64, i, call_name[kind], t_us);
	if (kind == INPUT_TAP_BYTES) {
		size_t count = write_bytes(t, i, bytes, n, t_us);
		tape_out_printf(t, TAPE_OUT_FRAMES, "%s %zu\n", head, count);
	} else if (kind == INPUT_TAP_RESYNC) {
		char hex[2 * 128 + 2];
		size_t k = 0;
		for (; k < n && k < 128; k++)
			snprintf(hex + 2 * k, 3, "%02x", bytes[k]);
		hex[2 * k] = 0;
		tape_out_printf(t, TAPE_OUT_FRAMES, "%s %s\n", head, hex);
	} else if (kind == INPUT_TAP_RELEASE) {
		tape_out_printf(t, TAPE_OUT_FRAMES, "%s %d\n", head, arg);
	} else {
		tape_out_bytes(t, TAPE_OUT_FRAMES, head, (size_t)m);
		tape_out_bytes(t, TAPE_OUT_FRAMES, "\n", 1);
	}
}

static void
tapped_event(void *user, const struct input_event_rec *e)
{
	struct tape *t = user;
	if (t->mode != TAPE_RECORD || e->device >= TAPE_DEVS)
		return;
	if (e->kind == INPUT_ADDED) /* a new device at this index: a new file */
		open_device(t, e->device);
	tape_out_printf(t, TAPE_OUT_FRAMES, "event %u %" PRIu64 " %u %u %d %u %a %a\n", e->device,
			e->t_us, e->kind, e->code, e->value, e->flags, e->x, e->y);
}

void
tape_dev_attach(struct tape *t, struct input_queue *q, const struct input_devs *devs)
{
	t->devs = devs;
	t->tap = (struct input_queue_tap){ tapped_call, tapped_event, t };
	q->tap = &t->tap;
}

void
tape_dev_detach(struct tape *t, struct input_queue *q)
{
	if (q->tap == &t->tap)
		q->tap = NULL;
}

/* ---- replay ---- */

double
tape_dev_dpi(const struct tape *t, int device)
{
	return device >= 0 && device < TAPE_DEVS && t->dpi[device] > 0 ? t->dpi[device] : 1000.0;
}

static int
replay_device(struct tape *t, const struct tape_entry *e)
{
	char format[32], file[64], map[64], path[TAPE_PATH_MAX + 80], mpath[TAPE_PATH_MAX + 80];
	char err[TAPE_PATH_MAX + 300];
	int f = -1;
	if (sscanf(e->text, "%31s %63s %63s", format, file, map) != 3 ||
	    (f = replay_dev_format_of(format)) < 0) {
		snprintf(t->broken, sizeof t->broken, "%s/frames:%d: no such device format", t->dir,
			 e->lineno);
		return -1;
	}
	snprintf(path, sizeof path, "%s/%s", t->dir, file);
	snprintf(mpath, sizeof mpath, "%s/%s", t->dir, map);
	struct replay_dev *r = malloc(sizeof *r);
	if (!r || replay_dev_open(r, (enum replay_dev_format)f, path, mpath, (uint16_t)e->fig, err,
				  sizeof err) < 0) {
		snprintf(t->broken, sizeof t->broken, "%s", r ? err : "out of memory");
		free(r);
		return -1;
	}
	if (t->rdev[e->fig]) {
		replay_dev_free(t->rdev[e->fig]);
		free(t->rdev[e->fig]);
	}
	t->rdev[e->fig] = r;
	t->dpi[e->fig] = e->x;
	return 0;
}

int
tape_dev_replay(struct tape *t, const struct tape_entry *e, struct input_queue *q)
{
	if (e->kind == TAPE_EVENT)
		return input_queue_push(q, &e->ev), 0;
	if (e->kind == TAPE_DEVICE)
		return replay_device(t, e);
	struct replay_dev *r = t->rdev[e->fig];
	char err[TAPE_PATH_MAX + 300];
	if (!r) {
		snprintf(t->broken, sizeof t->broken, "%s/frames:%d: device %d has no file yet",
			 t->dir, e->lineno, e->fig);
		return -1;
	}
	if (replay_dev_call(r, (enum input_tap_kind)e->sub, e->arg, e->count,
			    (const uint8_t *)e->text, e->ntext, e->t, q, err, sizeof err) < 0) {
		snprintf(t->broken, sizeof t->broken, "%s/frames:%d: %.500s", t->dir, e->lineno, err);
		return -1;
	}
	return 0;
}

void
tape_dev_free(struct tape *t)
{
	for (int i = 0; i < TAPE_DEVS; i++)
		if (t->rdev[i]) {
			replay_dev_free(t->rdev[i]);
			free(t->rdev[i]);
			t->rdev[i] = NULL;
		}
}
