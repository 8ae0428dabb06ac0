/*
 * posture-input - recorded input through the daemon's own decoders.
 *
 *   posture-input describe FILE          a HID descriptor's reports, fields, usages, bits
 *   posture-input decode FILE [--map M]  a recording through the decoders, one event a line
 *   posture-input decode --evemu FILE    a HID recording as the evdev events the kernel
 *                                        would emit, in evemu's E: lines
 *   posture-input record evdev:PATH [-o FILE] [--count N] [--seconds S] [--decode]
 *                                        a real device into an evemu file (or, with
 *                                        --decode, through the backend's decoder)
 *   posture-input record can:IFACE[:MAP] [-o FILE] [--count N] [--seconds S] [--decode]
 *                                        a CAN interface into a candump -l log
 *
 * Recordings are read in the ecosystem's formats, told apart by their
 * content: evemu (evdev), hid-recorder (raw HID), candump -l (CAN; needs
 * the panel map). The bytes take the path a device's bytes take: evemu
 * events become struct input_event records, hid-recorder lines reports,
 * candump lines struct can_frame.
 */
#include <errno.h>
#include <libevdev/libevdev.h>
#include <linux/can.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "devices/can_dev.h"
#include "devices/can_input.h"
#include "devices/can_map.h"
#include "devices/evdev_dev.h"
#include "devices/evdev_input.h"
#include "devices/hid_desc.h"
#include "devices/hid_input.h"
#include "devices/hid_keymap.h"
#include "devices/hidraw_dev.h"
#include "devices/input_backends.h"
#include "devices/input_devs.h"
#include "devices/queue.h"
#include "devices/rec_candump.h"
#include "devices/rec_evemu.h"
#include "devices/rec_hid.h"
#include "devices/textfile.h"
#include "devices/usb_dev.h"

static const char usage[] =
	"usage: posture-input describe FILE\n"
	"       posture-input decode FILE [--map PANEL]\n"
	"       posture-input decode --evemu FILE.hid\n"
	"       posture-input record evdev:PATH [-o FILE] [--count N] [--seconds S] [--decode]\n"
	"       posture-input record --fd N [...]   (tests: records from an inherited fd)\n"
	"       posture-input record hidraw:VID:PID[:IFACE]|hidraw:PATH [-o FILE] [--count N]\n"
	"                            [--seconds S] [--decode]\n"
	"       posture-input record can:IFACE[:MAP] [-o FILE] [--count N] [--seconds S] [--decode]\n"
	"       posture-input record usb:VID:PID[:IFACE] [-o FILE] [--count N] [--seconds S] [--decode]\n"
	"       posture-input list [SPEC...]\n"
	"\n"
	"describe: a HID report descriptor's input reports, fields, usages and bit offsets;\n"
	"  FILE is a hid-recorder file (every device in it) or a raw descriptor (the bytes of\n"
	"  /sys/class/hidraw/hidrawN/device/report_descriptor, or the same as hex text).\n"
	"decode: a recording through the daemon's decoders, one normalised event a line\n"
	"  (seconds from the first event, device, kind, values). FILE is an evemu recording,\n"
	"  a hid-recorder file or a candump -l log; a log needs --map, the panel map, and gives\n"
	"  one line a decoded frame: (time) ID NAME=value ..., with the log's own times.\n"
	"decode --evemu: for a hid-recorder file, the evdev events the kernel's hid-input\n"
	"  would emit, as evemu E: lines, a SYN_REPORT after each report.\n"
	"record: a real evdev device (/dev/input/eventN) into an evemu 1.3 file as evemu-record\n"
	"  writes one: its description, then its events with times rebased to the first; stops\n"
	"  after N events, S seconds, SIGINT or the device going away. --decode prints what the\n"
	"  daemon's evdev backend makes of the events instead, as decode does for a file.\n"
	"  --fd N reads struct input_event records from the inherited fd N (a pipe, socket or\n"
	"  pty standing in for a device in tests) through the same backend, with no description.\n"
	"record hidraw:...: the hidraw nodes of that mouse or keyboard (or that node) through\n"
	"  the daemon's hidraw backend into a hid-recorder file: each device's descriptor, then\n"
	"  its reports (E: lines, times from the first report; D: lines when several); --count\n"
	"  counts reports. --decode prints the backend's events instead.\n"
	"record usb:...: the HID interfaces of that USB device through the daemon's libusb\n"
	"  backend (the kernel's driver detached meanwhile) into a hid-recorder file, as\n"
	"  record hidraw: writes one.\n"
	"record can: the frames of a CAN interface into a candump -l log, as candump -l writes\n"
	"  it (the kernel's receive times, wall clock); with MAP only the map's ids (the kernel\n"
	"  filters the rest), and --decode prints the panel's events instead.\n"
	"list: the devices the daemon would open for the --input SPECs (default auto) and\n"
	"  what it would skip and why, without a daemon: index, backend, path, class, name.\n";

enum format { FMT_EVEMU, FMT_HID, FMT_CANDUMP, FMT_UNKNOWN };

/* the format by the first line that says: evemu's header or lines, R: (HID), '(' (candump) */
static enum format
sniff(const char *text, size_t n)
{
	const char *p = text, *end = text + n;
	while (p < end) {
		const char *nl = memchr(p, '\n', (size_t)(end - p));
		size_t len = nl ? (size_t)(nl - p) : (size_t)(end - p);
		if (len >= 7 && !strncmp(p, "# EVEMU", 7))
			return FMT_EVEMU;
		if (len >= 2 && p[1] == ':' && strchr("BAPLS", p[0]))
			return FMT_EVEMU;
		if (len >= 2 && !strncmp(p, "R:", 2))
			return FMT_HID;
		if (len >= 1 && p[0] == '(')
			return FMT_CANDUMP;
		p = nl ? nl + 1 : end;
	}
	return FMT_UNKNOWN;
}

static void
print_time(uint64_t t_us)
{
	printf("%llu.%06llu", (unsigned long long)(t_us / 1000000),
	       (unsigned long long)(t_us % 1000000));
}

/* the shortest decimal that reads back as v, as Python's repr finds it */
static const char *
num(double v)
{
	static char buf[32];
	if (v == (double)(long long)v && v > -1e15 && v < 1e15) { /* whole: no exponent */
		snprintf(buf, sizeof buf, "%lld", (long long)v);
		return buf;
	}
	for (int prec = 1; prec <= 17; prec++) {
		snprintf(buf, sizeof buf, "%.*g", prec, v);
		if (strtod(buf, NULL) == v)
			break;
	}
	return buf;
}

static void
print_num(double v)
{
	printf(" %s", num(v));
}

/* one normalised event, one line */
static void
print_event(const struct input_event_rec *e, const struct can_map *map)
{
	print_time(e->t_us);
	printf(" %u %s", e->device, input_kind_to_str((enum input_kind)e->kind));
	const char *name;
	switch ((enum input_kind)e->kind) {
	case INPUT_MOTION:
	case INPUT_POINTER:
		print_num(e->x);
		print_num(e->y);
		break;
	case INPUT_BUTTON:
	case INPUT_KEY:
		name = libevdev_event_code_get_name(EV_KEY, e->code);
		if (name)
			printf(" %s %d", name, e->value);
		else
			printf(" %u %d", e->code, e->value);
		break;
	case INPUT_WHEEL:
		printf(" %s %d", e->code == INPUT_WHEEL_H ? "horizontal" : "vertical", e->value);
		print_num(e->x);
		break;
	case INPUT_VALUATOR:
		if (map && e->code < map->n)
			printf(" %s", map->line[e->code].name);
		else
			printf(" %u", e->code);
		print_num(e->x);
		if (e->flags & INPUT_F_STALE)
			printf(" stale");
		break;
	case INPUT_ADDED:
	case INPUT_REMOVED:
	case INPUT_FRAME:
		break;
	}
	putchar('\n');
}

static void
drain(struct input_queue *q, const struct can_map *map)
{
	struct input_event_rec e;
	while (input_queue_pop(q, &e))
		print_event(&e, map);
}

static int
decode_evemu(const char *path, struct input_queue *q)
{
	char err[512];
	static struct rec_evemu r;
	if (rec_evemu_read(path, &r, err, sizeof err) < 0) {
		fprintf(stderr, "posture-input: %s\n", err);
		return 1;
	}
	size_t need = rec_evemu_to_records(&r, NULL, 0);
	uint8_t *rec = malloc(need ? need : 1);
	if (!rec) {
		rec_evemu_free(&r);
		fprintf(stderr, "posture-input: out of memory\n");
		return 1;
	}
	rec_evemu_to_records(&r, rec, need);
	static struct evdev_input e;
	evdev_input_init(&e, 0, path);
	rec_evemu_apply_abs(&r, &e);
	/* a few hundred records at a time, so the queue never fills */
	const size_t chunk = 256 * sizeof(struct input_event);
	int rc = 0;
	for (size_t off = 0; off < need; off += chunk) {
		size_t n = need - off < chunk ? need - off : chunk;
		rc |= evdev_input_feed(&e, rec + off, n, q) < 0;
		drain(q, NULL);
	}
	free(rec);
	rec_evemu_free(&r);
	return rc;
}

/* each device's descriptor, parsed; -1 with a message */
static int
parse_devices(const char *path, const struct rec_hid *r, struct hid_desc *desc)
{
	for (unsigned i = 0; i < r->ndevices; i++) {
		char err[256];
		if (hid_desc_parse(r->devices[i].desc, r->devices[i].desc_len, &desc[i], err,
				   sizeof err) < 0) {
			fprintf(stderr, "posture-input: %s: device %u: %s\n", path, i, err);
			return -1;
		}
	}
	return 0;
}

/* one evdev event as evemu-record writes it */
static void
put(unsigned type, unsigned code, int32_t value, uint64_t t_us, uint64_t *last_ms)
{
	struct rec_evemu_event ev = { .t_us = t_us, .sec = t_us / 1000000,
				      .usec = (uint32_t)(t_us % 1000000), .type = (uint16_t)type,
				      .code = (uint16_t)code, .value = value };
	rec_evemu_write_event(stdout, &ev, last_ms);
}

/*
 * The HID usage the kernel reports as MSC_SCAN before a key or button
 * changes (hid-input): a mouse's button n is BTN_MOUSE + n - 1, a key the
 * keyboard usage that maps to it. 0 when none does.
 */
static uint32_t
scancode(const struct input_event_rec *e)
{
	if (e->kind == INPUT_BUTTON && e->code >= BTN_MOUSE && e->code < BTN_MOUSE + 16)
		return 0x90000u | (uint32_t)(e->code - BTN_MOUSE + 1);
	for (uint32_t id = 0; id < 256 && e->kind == INPUT_KEY; id++)
		if (hid_keymap_key(id) == e->code)
			return 0x70000u | id;
	return 0;
}

/* the evdev events the kernel emits for one normalised event */
static void
print_evdev(const struct input_event_rec *e, uint64_t t_us, uint64_t *last_ms)
{
	switch ((enum input_kind)e->kind) {
	case INPUT_MOTION:
		if (e->x)
			put(EV_REL, REL_X, (int32_t)e->x, t_us, last_ms);
		if (e->y)
			put(EV_REL, REL_Y, (int32_t)e->y, t_us, last_ms);
		break;
	case INPUT_WHEEL: {
		/* hid-input's scroll: whole detents, then the same in 1/120 */
		int h = e->code == INPUT_WHEEL_H;
		if (e->value)
			put(EV_REL, h ? REL_HWHEEL : REL_WHEEL, e->value, t_us, last_ms);
		if (e->x)
			put(EV_REL, h ? REL_HWHEEL_HI_RES : REL_WHEEL_HI_RES, (int32_t)e->x, t_us,
			    last_ms);
		break;
	}
	case INPUT_BUTTON:
	case INPUT_KEY: {
		uint32_t scan = scancode(e);
		if (scan)
			put(EV_MSC, MSC_SCAN, (int32_t)scan, t_us, last_ms);
		put(EV_KEY, e->code, e->value, t_us, last_ms);
		break;
	}
	case INPUT_POINTER:
	case INPUT_VALUATOR:
	case INPUT_ADDED:
	case INPUT_REMOVED:
	case INPUT_FRAME:
		break;
	}
}

static int
decode_hid(const char *path, int as_evemu, struct input_queue *q)
{
	char err[512];
	static struct rec_hid r;
	static struct hid_desc desc[REC_HID_MAX_DEVICES];
	static struct hid_input in[REC_HID_MAX_DEVICES];
	if (rec_hid_read(path, &r, err, sizeof err) < 0) {
		fprintf(stderr, "posture-input: %s\n", err);
		return 1;
	}
	if (parse_devices(path, &r, desc) < 0) {
		rec_hid_free(&r);
		return 1;
	}
	for (unsigned i = 0; i < r.ndevices; i++)
		hid_input_init(&in[i], &desc[i], (uint16_t)i, r.devices[i].name);
	if (as_evemu && r.ndevices)
		printf("# EVEMU 1.3\nN: %s\nI: %04x %04x %04x 0000\n", r.devices[0].name,
		       r.devices[0].bus, r.devices[0].vid, r.devices[0].pid);
	int dropped = 0;
	uint64_t last_ms = 0;
	for (size_t k = 0; k < r.nevents; k++) {
		const struct rec_hid_event *ev = &r.events[k];
		int bad = hid_input_feed(&in[ev->device], ev->bytes, ev->len, ev->t_us, q) < 0;
		dropped += bad;
		if (!as_evemu) {
			drain(q, NULL);
			continue;
		}
		/* one report, then a SYN_REPORT, as hid-input ends a report */
		struct input_event_rec e;
		int any = 0;
		while (input_queue_pop(q, &e)) {
			print_evdev(&e, ev->t_us, &last_ms);
			any |= e.kind != INPUT_FRAME;
		}
		if (any) /* the input core sends no empty frame */
			put(EV_SYN, SYN_REPORT, 0, ev->t_us, &last_ms);
	}
	if (dropped)
		fprintf(stderr, "posture-input: %s: reports dropped (see above)\n", path);
	rec_hid_free(&r);
	return 0;
}

static int
decode_candump(const char *path, const char *map_path)
{
	char err[512];
	static struct can_map map;
	static struct rec_candump r;
	if (!map_path) {
		fprintf(stderr, "posture-input: %s is a candump log: give the panel map (--map)\n",
			path);
		return 2;
	}
	if (can_map_read(map_path, &map, err, sizeof err) < 0) {
		fprintf(stderr, "posture-input: %s\n", err);
		return 1;
	}
	if (rec_candump_read(path, &r, err, sizeof err) < 0) {
		fprintf(stderr, "posture-input: %s\n", err);
		return 1;
	}
	int line[CAN_MAP_MAX_LINES];
	double value[CAN_MAP_MAX_LINES];
	for (size_t k = 0; k < r.n; k++) {
		const struct rec_candump_frame *f = &r.frames[k];
		if (f->can_id & (CAN_ERR_FLAG | CAN_RTR_FLAG))
			continue;
		int n = can_input_decode(&map, f->can_id, f->data, f->len, line, value,
					 CAN_MAP_MAX_LINES);
		if (n <= 0)
			continue;
		int ext = (f->can_id & CAN_EFF_FLAG) != 0;
		printf("(%llu.%06llu) %0*X", (unsigned long long)(f->t_abs_us / 1000000),
		       (unsigned long long)(f->t_abs_us % 1000000), ext ? 8 : 3,
		       f->can_id & (ext ? CAN_EFF_MASK : CAN_SFF_MASK));
		for (int i = 0; i < n; i++) {
			printf(" %s=%s", map.line[line[i]].name, num(value[i]));
		}
		putchar('\n');
	}
	rec_candump_free(&r);
	return 0;
}

/* hex text ("05 01 09 02 ...", # comments) into bytes; -1 when it is not hex text */
static long
hex_text(const char *text, size_t n, uint8_t *dest, size_t max)
{
	size_t k = 0;
	for (size_t i = 0; i < n;) {
		if (text[i] == '#') { /* a comment to the end of the line */
			while (i < n && text[i] != '\n')
				i++;
			continue;
		}
		if (strchr(" \t\r\n,", text[i])) {
			i++;
			continue;
		}
		if (i + 1 < n && text[i] == '0' && (text[i + 1] == 'x' || text[i + 1] == 'X'))
			i += 2;
		unsigned v;
		int used;
		if (i + 2 > n || sscanf(text + i, "%2x%n", &v, &used) != 1 || used != 2 || k == max)
			return -1;
		dest[k++] = (uint8_t)v;
		i += 2;
	}
	return (long)k;
}

static int
describe(const char *path)
{
	char err[512];
	size_t n;
	char *text = textfile_read(path, &n, err, sizeof err);
	if (!text) {
		fprintf(stderr, "posture-input: %s\n", err);
		return 1;
	}
	static struct hid_desc d;
	int rc = 0;
	if (sniff(text, n) == FMT_HID) {
		static struct rec_hid r;
		if (rec_hid_parse(text, n, path, &r, err, sizeof err) < 0) {
			fprintf(stderr, "posture-input: %s\n", err);
			free(text);
			return 1;
		}
		for (unsigned i = 0; i < r.ndevices && !rc; i++) {
			printf("device %u: %s (bus %04x, %04x:%04x), %u descriptor bytes\n", i,
			       r.devices[i].name, r.devices[i].bus, r.devices[i].vid, r.devices[i].pid,
			       r.devices[i].desc_len);
			if (hid_desc_parse(r.devices[i].desc, r.devices[i].desc_len, &d, err,
					   sizeof err) < 0) {
				fprintf(stderr, "posture-input: %s: device %u: %s\n", path, i, err);
				rc = 1;
			} else {
				hid_desc_describe(&d, stdout);
			}
		}
		rec_hid_free(&r);
		free(text);
		return rc;
	}
	static uint8_t bytes[HID_DESC_MAX_BYTES];
	long nb = hex_text(text, n, bytes, sizeof bytes);
	const uint8_t *raw = nb >= 0 ? bytes : (const uint8_t *)text;
	size_t rn = nb >= 0 ? (size_t)nb : n;
	if (hid_desc_parse(raw, rn, &d, err, sizeof err) < 0) {
		fprintf(stderr, "posture-input: %s: %s\n", path, err);
		rc = 1;
	} else {
		hid_desc_describe(&d, stdout);
	}
	free(text);
	return rc;
}

static int
decode(int argc, char **argv)
{
	const char *file = NULL, *map = NULL;
	int evemu = 0;
	for (int i = 0; i < argc; i++) {
		if (!strcmp(argv[i], "--evemu"))
			evemu = 1;
		else if (!strcmp(argv[i], "--map") && i + 1 < argc)
			map = argv[++i];
		else if (argv[i][0] != '-' && !file)
			file = argv[i];
		else {
			fputs(usage, stderr);
			return 2;
		}
	}
	if (!file) {
		fputs(usage, stderr);
		return 2;
	}
	char err[512];
	size_t n;
	char *text = textfile_read(file, &n, err, sizeof err);
	if (!text) {
		fprintf(stderr, "posture-input: %s\n", err);
		return 1;
	}
	enum format fmt = sniff(text, n);
	free(text);
	static struct input_queue q;
	input_queue_init(&q);
	if (evemu && fmt != FMT_HID) {
		fprintf(stderr, "posture-input: --evemu takes a hid-recorder file\n");
		return 2;
	}
	switch (fmt) {
	case FMT_EVEMU:
		return decode_evemu(file, &q);
	case FMT_HID:
		return decode_hid(file, evemu, &q);
	case FMT_CANDUMP:
		return decode_candump(file, map);
	case FMT_UNKNOWN:
		break;
	}
	fprintf(stderr, "posture-input: %s: not an evemu, hid-recorder or candump recording\n",
		file);
	return 1;
}

/* ---- record ------------------------------------------------------------------ */

static volatile sig_atomic_t record_stop;

static void
record_on_signal(int sig)
{
	(void)sig;
	record_stop = 1;
}

static uint64_t
record_now_us(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
}

struct record_opts {
	const char *spec;     /* the device spec as given: evdev:PATH, hidraw:..., can:... */
	const char *path, *out;
	int fd;               /* --fd: a test's stand-in for the device, or -1 */
	unsigned long count;  /* 0: no limit */
	double seconds;       /* 0: no limit */
	int decode;
};

/* the options, or 2 with the usage */
static int
record_parse(int argc, char **argv, struct record_opts *dest)
{
	memset(dest, 0, sizeof *dest);
	dest->fd = -1;
	for (int i = 0; i < argc; i++) {
		char *end;
		if (!strcmp(argv[i], "-o") && i + 1 < argc) {
			dest->out = argv[++i];
		} else if (!strcmp(argv[i], "--count") && i + 1 < argc) {
			dest->count = strtoul(argv[++i], &end, 10);
			if (*end || !dest->count)
				goto usage;
		} else if (!strcmp(argv[i], "--seconds") && i + 1 < argc) {
			dest->seconds = strtod(argv[++i], &end);
			if (*end || !(dest->seconds > 0))
				goto usage;
		} else if (!strcmp(argv[i], "--fd") && i + 1 < argc && !dest->path) {
			long fd = strtol(argv[++i], &end, 10);
			if (*end || fd < 0 || fd > 1 << 20)
				goto usage;
			dest->fd = (int)fd;
			dest->path = "fd";
		} else if (!strcmp(argv[i], "--decode")) {
			dest->decode = 1;
		} else if (!strncmp(argv[i], "evdev:", 6) && argv[i][6] && !dest->path) {
			dest->spec = argv[i];
			dest->path = argv[i] + 6;
		} else if ((!strncmp(argv[i], "hidraw:", 7) || !strncmp(argv[i], "can:", 4) ||
			    !strncmp(argv[i], "usb:", 4)) &&
			   strchr(argv[i], ':')[1] && !dest->path) {
			dest->spec = dest->path = argv[i];
		} else {
			goto usage;
		}
	}
	if (dest->path)
		return 0;
usage:
	fputs(usage, stderr);
	return 2;
}

/* one record of the last read: an E: line rebased to the first event, or nothing */
static int
record_write(FILE *out, const uint8_t *bytes, uint64_t *t0, int *first, uint64_t *last_ms)
{
	struct input_event rec;
	memcpy(&rec, bytes, sizeof rec);
	uint64_t t = (uint64_t)rec.input_event_sec * 1000000u + (uint64_t)rec.input_event_usec;
	if (*first) {
		*t0 = t;
		*first = 0;
	}
	/* evemu-record puts the first event at 0.000001 */
	uint64_t rel = (t >= *t0 ? t - *t0 : 0) + 1;
	struct rec_evemu_event ev = {
		.t_us = rel,
		.sec = rel / 1000000u,
		.usec = (uint32_t)(rel % 1000000u),
		.type = rec.type,
		.code = rec.code,
		.value = rec.value,
	};
	return rec_evemu_write_event(out, &ev, last_ms);
}

/* the queue's events, times from the first record (decode's times for a file) */
static void
record_drain(struct input_queue *q, uint64_t t0, int print)
{
	struct input_event_rec e;
	while (input_queue_pop(q, &e)) {
		if (!print)
			continue;
		e.t_us = e.t_us >= t0 ? e.t_us - t0 : 0;
		print_event(&e, NULL);
	}
}

/* what every recorder shares: the output, the signals, the time limit, the status */
struct record_session {
	FILE *out;
	uint64_t start, limit;
	int rc;
};

/* opens the output (stdout when path is NULL) and arms SIGINT/SIGTERM; 0, or -1 said */
static int
record_begin(struct record_session *r, const char *path, double seconds)
{
	r->out = stdout;
	r->rc = 0;
	if (path && !(r->out = fopen(path, "w"))) {
		fprintf(stderr, "posture-input: %s: %s\n", path, strerror(errno));
		return -1;
	}
	struct sigaction sa;
	memset(&sa, 0, sizeof sa);
	sa.sa_handler = record_on_signal;
	sigaction(SIGINT, &sa, NULL);
	sigaction(SIGTERM, &sa, NULL);
	r->start = record_now_us();
	r->limit = seconds > 0 ? (uint64_t)(seconds * 1e6) : 0;
	return 0;
}

/*
 * Waits for the nfds fds (at most 200 ms, or the time left): 1 when one is
 * ready, 0 to look again, -1 to stop (a signal, the time is up, poll failed).
 */
static int
record_wait(struct record_session *r, struct pollfd *fds, int nfds)
{
	uint64_t now = record_now_us();
	if (record_stop || (r->limit && now - r->start >= r->limit))
		return -1;
	int wait_ms = 200;
	if (r->limit && (r->limit - (now - r->start)) / 1000 < (uint64_t)wait_ms)
		wait_ms = (int)((r->limit - (now - r->start)) / 1000) + 1;
	int n = poll(fds, (nfds_t)nfds, wait_ms);
	if (n < 0 && errno != EINTR) {
		fprintf(stderr, "posture-input: poll: %s\n", strerror(errno));
		r->rc = 1;
		return -1;
	}
	return n > 0;
}

/* closes the output; the session's status */
static int
record_end(struct record_session *r)
{
	if (ferror(r->out))
		r->rc = 1;
	if (r->out != stdout)
		fclose(r->out);
	else
		fflush(r->out);
	return r->rc;
}

static int record_hidraw(const struct record_opts *o);
static int record_can(const struct record_opts *o);
static int record_usb(const struct record_opts *o);

static int
record(int argc, char **argv)
{
	struct record_opts o;
	if (record_parse(argc, argv, &o))
		return 2;
	if (!strncmp(o.spec ? o.spec : "", "hidraw:", 7))
		return record_hidraw(&o);
	if (!strncmp(o.spec ? o.spec : "", "can:", 4))
		return record_can(&o);
	if (!strncmp(o.spec ? o.spec : "", "usb:", 4))
		return record_usb(&o);

	char err[512];
	static struct evdev_dev d;
	int opened = o.fd >= 0 ? evdev_dev_adopt(&d, o.fd, 0, "fd", err, sizeof err)
			       : evdev_dev_open(&d, o.path, 0, 0, err, sizeof err);
	if (opened < 0) {
		fprintf(stderr, "posture-input: %s\n", err);
		return 1;
	}
	struct record_session r;
	if (record_begin(&r, o.out, o.seconds) < 0) {
		evdev_dev_close(&d, 0, NULL);
		return 1;
	}

	/* the description first, as evemu-record writes it */
	static struct rec_evemu desc;
	if (!o.decode) {
		evdev_dev_describe(&d, &desc);
		rec_evemu_write(r.out, &desc);
		fflush(r.out);
	}

	static struct input_queue q;
	input_queue_init(&q);
	uint64_t t0 = 0, last_ms = 0;
	unsigned long written = 0;
	int first = 1;
	while (!o.count || written < o.count) {
		struct pollfd p = { .fd = evdev_dev_fd(&d), .events = POLLIN };
		if (record_wait(&r, &p, 1) < 0)
			break;
		int n = evdev_dev_read(&d, record_now_us(), &q);
		for (int i = 0; i < n && (!o.count || written < o.count); i++, written++) {
			const uint8_t *bytes = d.buf + (size_t)i * sizeof(struct input_event);
			if (o.decode) {
				if (first) {
					struct input_event rec;
					memcpy(&rec, bytes, sizeof rec);
					t0 = (uint64_t)rec.input_event_sec * 1000000u +
					     (uint64_t)rec.input_event_usec;
					first = 0;
				}
			} else if (record_write(r.out, bytes, &t0, &first, &last_ms) < 0) {
				r.rc = 1;
			}
		}
		record_drain(&q, t0, o.decode);
		fflush(r.out);
		if (n < 0) {
			fprintf(stderr, "posture-input: %s: the device went away\n", o.path);
			r.rc = 1;
			break;
		}
	}

	fprintf(stderr, "posture-input: %lu records in %llu reads (%llu stopped at the %d-record cap)\n",
		written, (unsigned long long)d.reads, (unsigned long long)d.capped,
		EVDEV_DEV_READ_MAX);

	/* what is still held is released, as the daemon does */
	evdev_dev_close(&d, record_now_us(), &q);
	record_drain(&q, t0, o.decode);
	return record_end(&r);
}

/* ---- record hidraw -------------------------------------------------------------- */

/* what the tap of each recorded device writes into */
struct record_hid_sink {
	FILE *out;
	int decode;           /* print events, not E: lines */
	int several;          /* D: lines */
	int last;             /* the device of the last E: line */
	unsigned long count;  /* 0: no limit */
	unsigned long written;
	int first;
	uint64_t t0;          /* the first report's time: hid-recorder's zero */
};

struct record_hid_tap {
	struct record_hid_sink *sink;
	int index;
};

static void
record_hid_on_report(void *ctx, uint64_t t_us, const uint8_t *report, size_t n)
{
	struct record_hid_tap *tap = ctx;
	struct record_hid_sink *k = tap->sink;
	if (k->first) {
		k->t0 = t_us;
		k->first = 0;
	}
	if (k->count && k->written >= k->count)
		return;
	k->written++;
	if (k->decode)
		return;
	if (k->several && tap->index != k->last) {
		fprintf(k->out, "D: %d\n", tap->index);
		k->last = tap->index;
	}
	rec_hid_write_event(k->out, t_us >= k->t0 ? t_us - k->t0 : 0, report, (unsigned)n);
}

/* the devices a hidraw spec names, opened into d[]: their count, or -1 with a message */
static int
record_hidraw_open(const char *spec, struct hidraw_dev *d, int max)
{
	char err[512];
	uint16_t vid, pid;
	int iface;
	const char *path;
	if (hidraw_dev_parse_spec(spec + 7, &vid, &pid, &iface, &path, err, sizeof err) < 0) {
		fprintf(stderr, "posture-input: %s\n", err);
		return -1;
	}
	static struct hidraw_dev_found found[HIDRAW_DEV_FOUND_MAX];
	int n = 1;
	if (path) {
		snprintf(found[0].path, sizeof found[0].path, "%s", path);
		found[0].iface = -1;
	} else {
		n = hidraw_dev_enumerate(vid, pid, iface, found, HIDRAW_DEV_FOUND_MAX, err,
					 sizeof err);
		if (n <= 0) {
			fprintf(stderr, "posture-input: %s: %s\n", spec, err);
			return -1;
		}
	}
	int opened = 0;
	for (int k = 0; k < n && opened < max; k++) {
		if (hidraw_dev_open(&d[opened], found[k].path, found[k].iface, (uint16_t)opened, err,
				    sizeof err) < 0) {
			fprintf(stderr, "posture-input: %s\n", err);
			continue;
		}
		opened++;
	}
	return opened ? opened : -1;
}

/* record hidraw:SPEC: a hid-recorder file (or, with --decode, the events) of its nodes */
static int
record_hidraw(const struct record_opts *o)
{
	struct record_hid_sink sink = { .first = 1, .last = -1, .count = o->count,
					.decode = o->decode };
	enum { MAXDEV = 8 };
	static struct hidraw_dev d[MAXDEV];
	static struct record_hid_tap taps[MAXDEV];
	int n = record_hidraw_open(o->spec, d, MAXDEV);
	if (n < 0)
		return 1;
	struct record_session r;
	if (record_begin(&r, o->out, o->seconds) < 0) {
		for (int k = 0; k < n; k++)
			hidraw_dev_close(&d[k], 0, NULL);
		return 1;
	}
	sink.out = r.out;
	sink.several = n > 1;
	for (int k = 0; k < n; k++) {
		taps[k] = (struct record_hid_tap){ .sink = &sink, .index = k };
		d[k].tap = record_hid_on_report;
		d[k].tap_ctx = &taps[k];
		if (!sink.decode) {
			static struct rec_hid_device rd;
			hidraw_dev_describe(&d[k], &rd);
			rec_hid_write_device(sink.out, &rd, sink.several ? k : -1);
		}
	}
	fflush(sink.out);

	static struct input_queue q;
	input_queue_init(&q);
	int open_now = n;
	while (open_now && (!sink.count || sink.written < sink.count)) {
		struct pollfd p[MAXDEV];
		int map[MAXDEV], np = 0;
		for (int k = 0; k < n; k++)
			if (hidraw_dev_fd(&d[k]) >= 0) {
				p[np] = (struct pollfd){ .fd = hidraw_dev_fd(&d[k]), .events = POLLIN };
				map[np++] = k;
			}
		if (record_wait(&r, p, np) < 0)
			break;
		for (int j = 0; j < np; j++) {
			if (!p[j].revents)
				continue;
			int k = map[j];
			int got = hidraw_dev_read(&d[k], record_now_us(), &q);
			record_drain(&q, sink.t0, sink.decode);
			if (got < 0) {
				fprintf(stderr, "posture-input: %s: the device went away\n", d[k].path);
				hidraw_dev_close(&d[k], record_now_us(), NULL);
				open_now--;
				r.rc = 1;
			}
		}
		fflush(sink.out);
	}

	uint64_t reads = 0, capped = 0;
	for (int k = 0; k < n; k++) {
		reads += d[k].reads;
		capped += d[k].capped;
	}
	fprintf(stderr,
		"posture-input: %lu reports in %llu reads (%llu stopped at the %d-report cap)\n",
		sink.written, (unsigned long long)reads, (unsigned long long)capped,
		HIDRAW_DEV_READ_MAX);
	/* what is still held is released, as the daemon does */
	for (int k = 0; k < n; k++)
		hidraw_dev_close(&d[k], record_now_us(), &q);
	record_drain(&q, sink.t0, sink.decode);
	return record_end(&r);
}

/* ---- record usb: HID interfaces through libusb into a hid-recorder file ---------- */

static int
record_usb(const struct record_opts *o)
{
	if (o->fd >= 0) {
		fputs(usage, stderr);
		return 2;
	}
	/* the daemon's own path: the device set over the usb backend alone */
	static const struct input_backend *const only_usb[] = { &input_backend_usb };
	static struct input_devs s;
	static struct input_queue q;
	input_queue_init(&q);
	input_devs_init(&s, only_usb, 1, 0, &q);
	char err[512];
	int n = input_devs_open(&s, o->spec, record_now_us(), err, sizeof err);
	if (n < 0) {
		fprintf(stderr, "posture-input: %s\n", err);
		return 2;
	}
	for (int k = 0; k < s.nskip; k++)
		fprintf(stderr, "posture-input: %s skipped: %s\n", s.skip[k].what, s.skip[k].why);
	if (n == 0) {
		fprintf(stderr, "posture-input: %s: nothing to record\n", o->spec);
		return 1;
	}
	struct record_session r;
	if (record_begin(&r, o->out, o->seconds) < 0) {
		input_devs_close_all(&s, 0, NULL);
		return 1;
	}
	struct record_hid_sink sink = { .out = r.out, .first = 1, .last = -1, .count = o->count,
					.decode = o->decode, .several = n > 1 };
	static struct record_hid_tap taps[INPUT_DEVS_MAX];
	for (int i = 0, k = 0; i < INPUT_DEVS_MAX; i++) {
		if (!s.place[i].be)
			continue;
		taps[i] = (struct record_hid_tap){ .sink = &sink, .index = k };
		usb_dev_set_tap(s.place[i].dev, record_hid_on_report, &taps[i]);
		if (!sink.decode) {
			static struct rec_hid_device rd;
			usb_dev_describe(s.place[i].dev, &rd);
			rec_hid_write_device(sink.out, &rd, sink.several ? k : -1);
		}
		k++;
	}
	fflush(sink.out);
	while (input_devs_count(&s) && (!sink.count || sink.written < sink.count)) {
		struct pollfd p[INPUT_DEVS_POLL_MAX];
		int tags[INPUT_DEVS_POLL_MAX];
		int np = input_devs_pollfds(&s, p, tags, INPUT_DEVS_POLL_MAX);
		if (record_wait(&r, p, np) < 0)
			break;
		for (int j = 0; j < np; j++)
			if (p[j].revents && input_devs_ready(&s, tags[j], record_now_us(), &q) < 0) {
				fprintf(stderr, "posture-input: a device went away\n");
				r.rc = 1;
			}
		record_drain(&q, sink.t0, sink.decode);
		fflush(sink.out);
	}
	fprintf(stderr, "posture-input: %lu reports\n", sink.written);
	/* what is still held is released, as the daemon does */
	input_devs_close_all(&s, record_now_us(), &q);
	record_drain(&q, sink.t0, sink.decode);
	return record_end(&r);
}

/* ---- record can: a CAN interface into a candump -l log ---------------------------- */

/* one frame of the last read as a candump -l line */
static int
record_can_write(FILE *out, const struct can_dev *d, int k)
{
	struct can_frame f;
	memcpy(&f, d->frame[k], sizeof f);
	struct rec_candump_frame line;
	memset(&line, 0, sizeof line);
	line.t_abs_us = d->stamp_us[k];
	if (!line.t_abs_us) { /* no kernel time: the wall clock now, as candump falls back */
		struct timespec ts;
		clock_gettime(CLOCK_REALTIME, &ts);
		line.t_abs_us = (uint64_t)ts.tv_sec * 1000000u + (uint64_t)ts.tv_nsec / 1000u;
	}
	snprintf(line.iface, sizeof line.iface, "%s", d->iface);
	line.can_id = f.can_id;
	line.len = f.len;
	line.len8_dlc = f.len8_dlc;
	memcpy(line.data, f.data, sizeof line.data);
	struct rec_candump one = { .frames = &line, .n = 1 };
	return rec_candump_write(out, &one);
}

/* the panel's events, times from the start, named by the map (NULL: not printed) */
static void
record_can_drain(struct input_queue *q, uint64_t t0, const struct can_map *map)
{
	struct input_event_rec e;
	while (input_queue_pop(q, &e)) {
		if (!map)
			continue;
		e.t_us = e.t_us >= t0 ? e.t_us - t0 : 0;
		print_event(&e, map);
	}
}

static int
record_can(const struct record_opts *o)
{
	/* can:IFACE[:MAP] */
	const char *spec = o->spec + 4;
	char iface[IF_NAMESIZE];
	const char *colon = strchr(spec, ':');
	size_t len = colon ? (size_t)(colon - spec) : strlen(spec);
	if (!len || len >= sizeof iface || (colon && !colon[1]) || o->fd >= 0) {
		fputs(usage, stderr);
		return 2;
	}
	memcpy(iface, spec, len);
	iface[len] = 0;

	char err[512];
	static struct can_map map;
	if (colon && can_map_read(colon + 1, &map, err, sizeof err) < 0) {
		fprintf(stderr, "posture-input: %s\n", err);
		return 2;
	}
	static struct can_dev d;
	if (can_dev_open(&d, iface, colon ? &map : NULL, 0, err, sizeof err) < 0) {
		fprintf(stderr, "posture-input: %s: %s\n", iface, err);
		return 1;
	}
	struct record_session r;
	if (record_begin(&r, o->out, o->seconds) < 0) {
		can_dev_close(&d, 0, NULL);
		return 1;
	}

	static struct input_queue q;
	input_queue_init(&q);
	unsigned long written = 0;
	const struct can_map *names = o->decode && colon ? &map : NULL;
	while (!o->count || written < o->count) {
		struct pollfd p = { .fd = can_dev_fd(&d), .events = POLLIN };
		if (record_wait(&r, &p, 1) < 0)
			break;
		int n = can_dev_read(&d, record_now_us(), &q);
		for (int k = 0; k < n && (!o->count || written < o->count); k++, written++)
			if (!o->decode && record_can_write(r.out, &d, k) < 0)
				r.rc = 1;
		record_can_drain(&q, r.start, names);
		fflush(r.out);
		if (n < 0) {
			fprintf(stderr, "posture-input: %s: the interface went away\n", iface);
			r.rc = 1;
			break;
		}
	}
	fprintf(stderr, "posture-input: %lu frames in %llu reads (%llu error frames, %llu refused, "
		"%llu dropped by the kernel)\n",
		written, (unsigned long long)d.reads, (unsigned long long)d.error_frames,
		(unsigned long long)d.bad_size, (unsigned long long)d.kernel_dropped);
	can_dev_close(&d, record_now_us(), &q);
	record_can_drain(&q, r.start, names);
	return record_end(&r);
}

/* ---- list -------------------------------------------------------------------- */

static int
list(int argc, char **argv)
{
	static struct input_devs s;
	char err[512];
	input_devs_init(&s, input_backends, input_backends_count, 0, NULL);
	for (int k = 0; k < (argc ? argc : 1); k++)
		if (input_devs_open(&s, argc ? argv[k] : "auto", 0, err, sizeof err) < 0) {
			fprintf(stderr, "posture-input: %s\n", err);
			return 2;
		}
	static const char *const cls[] = { "mouse", "keyboard", "panel", "other" };
	for (int i = 0; i < INPUT_DEVS_MAX; i++) {
		const struct input_devs_place *p = &s.place[i];
		if (p->be)
			printf("%d %s %s %s %s\n", i, p->be->name, p->info.path,
			       cls[p->info.cls <= INPUT_CLASS_OTHER ? p->info.cls : INPUT_CLASS_OTHER],
			       p->info.name);
	}
	for (int k = 0; k < s.nskip; k++)
		printf("skipped %s: %s\n", s.skip[k].what, s.skip[k].why);
	input_devs_close_all(&s, 0, NULL);
	return 0;
}

int
main(int argc, char **argv)
{
	if (argc >= 3 && !strcmp(argv[1], "describe") && argc == 3)
		return describe(argv[2]);
	if (argc >= 3 && !strcmp(argv[1], "decode"))
		return decode(argc - 2, argv + 2);
	if (argc >= 3 && !strcmp(argv[1], "record"))
		return record(argc - 2, argv + 2);
	if (argc >= 2 && !strcmp(argv[1], "list"))
		return list(argc - 2, argv + 2);
	if (argc == 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
		fputs(usage, stdout);
		return 0;
	}
	fputs(usage, stderr);
	return 2;
}
