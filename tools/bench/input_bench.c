/*
 * input_bench - decode cost per event through each decoder's feed():
 * evdev records of a mouse, HID reports of a boot mouse and an NKRO
 * keyboard through their parsed descriptors, CAN frames through a panel
 * map; beside the floor, copying the same bytes (targets: evdev <= 50 ns,
 * HID <= 150 ns, CAN <= 100 ns a record, report or frame).
 *
 *   input_bench [ROOT]   ROOT: the checkout (for the descriptor and the map)
 *
 * Prints BENCH input.evdev, input.hid and input.can lines: ns, the cost
 * per event taken from the queue (input.hid: the worse of the two
 * devices), and the cost per record, report or frame; the queue is
 * drained between batches, as the loop drains it every frame.
 */
#include <linux/can.h>
#include <linux/input.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "devices/can_input.h"
#include "devices/can_map.h"
#include "devices/evdev_input.h"
#include "devices/hid_desc.h"
#include "devices/hid_input.h"
#include "devices/queue.h"

#define UNITS 200000 /* records, reports or frames a measurement */
#define BATCH 256    /* between drains of the queue */
#define ROUNDS 5     /* the best of */

static struct input_queue q;
static volatile uint64_t sink;
static uint64_t drained; /* events taken from the queue */

static void
drain(void)
{
	struct input_event_rec e;
	while (input_queue_pop(&q, &e)) {
		sink += e.kind;
		drained++;
	}
}

static uint32_t rng = 12345;

static uint32_t
next(void)
{
	rng ^= rng << 13;
	rng ^= rng >> 17;
	rng ^= rng << 5;
	return rng;
}

/* the floor: the same bytes copied, unit by unit, and touched */
static double
floor_ns(const uint8_t *bytes, size_t unit, size_t n)
{
	static uint8_t copy[4096];
	double best = 1e30;
	for (int r = 0; r < ROUNDS; r++) {
		uint64_t t0 = bench_clock_us(NULL);
		for (size_t i = 0; i < n; i++) {
			memcpy(copy, bytes + i * unit, unit);
			sink += copy[0];
		}
		double ns = (double)(bench_clock_us(NULL) - t0) * 1000.0 / (double)n;
		best = ns < best ? ns : best;
	}
	return best;
}

static void
bench_evdev(void)
{
	/* a mouse: X, Y, SYN; every eighth frame a button change too */
	size_t n = 0, cap = UNITS;
	struct input_event *rec = calloc(cap, sizeof *rec);
	for (unsigned f = 0; n + 4 <= cap; f++) {
		uint16_t type[4] = { EV_REL, EV_REL, EV_KEY, EV_SYN }, code[4] = { REL_X, REL_Y, BTN_LEFT, 0 };
		int32_t value[4] = { (int32_t)(next() % 21) - 10, (int32_t)(next() % 21) - 10, (f / 8) % 2, 0 };
		for (int k = 0; k < 4; k++) {
			if (k == 2 && f % 8)
				continue;
			rec[n].input_event_sec = f / 1000;
			rec[n].input_event_usec = (f % 1000) * 1000;
			rec[n].type = type[k];
			rec[n].code = code[k];
			rec[n].value = value[k];
			n++;
		}
	}
	static struct evdev_input e;
	double best = 1e30;
	for (int r = 0; r < ROUNDS; r++) {
		drained = 0;
		evdev_input_init(&e, 0, "bench");
		uint64_t t0 = bench_clock_us(NULL);
		for (size_t i = 0; i < n; i += BATCH) {
			size_t k = n - i < BATCH ? n - i : BATCH;
			evdev_input_feed(&e, (const uint8_t *)&rec[i], k * sizeof *rec, &q);
			drain();
		}
		double ns = (double)(bench_clock_us(NULL) - t0) * 1000.0 / (double)n;
		best = ns < best ? ns : best;
	}
	printf("BENCH input.evdev ns=%.1f record_ns=%.1f floor_ns=%.1f records=%zu events=%llu "
	       "target_ns=50\n",
	       best * (double)n / (double)drained, best,
	       floor_ns((const uint8_t *)rec, sizeof *rec, n), n, (unsigned long long)drained);
	free(rec);
}

/* n reports of len bytes through descriptor d; ns per report, *per_event ns per event */
static double
hid_run(const struct hid_desc *d, const uint8_t *reports, size_t len, size_t n, double *per_event)
{
	static struct hid_input h;
	double best = 1e30;
	for (int r = 0; r < ROUNDS; r++) {
		drained = 0;
		hid_input_init(&h, d, 0, "bench");
		uint64_t t0 = bench_clock_us(NULL);
		for (size_t i = 0; i < n; i++) {
			hid_input_feed(&h, reports + i * len, len, i, &q);
			if (i % BATCH == BATCH - 1)
				drain();
		}
		drain();
		double ns = (double)(bench_clock_us(NULL) - t0) * 1000.0 / (double)n;
		best = ns < best ? ns : best;
	}
	*per_event = best * (double)n / (double)drained;
	return best;
}

/* hex text with # comments into bytes; -1 when unreadable */
static long
read_hex(const char *path, uint8_t *dest, size_t max)
{
	FILE *f = fopen(path, "r");
	if (!f)
		return -1;
	size_t n = 0;
	int c;
	while ((c = fgetc(f)) != EOF) {
		if (c == '#') {
			while ((c = fgetc(f)) != EOF && c != '\n')
				;
			continue;
		}
		unsigned v;
		if (c <= ' ' || ungetc(c, f) == EOF)
			continue;
		if (fscanf(f, "%2x", &v) != 1 || n == max) {
			fclose(f);
			return -1;
		}
		dest[n++] = (uint8_t)v;
	}
	fclose(f);
	return (long)n;
}

static void
bench_hid(const char *root)
{
	static struct hid_desc mouse, nkro;
	char err[256], path[4096];
	hid_desc_boot(HID_BOOT_MOUSE, &mouse);
	snprintf(path, sizeof path, "%s/tests/input/hid/nkro_keyboard.rdesc", root);
	static uint8_t bytes[HID_DESC_MAX_BYTES];
	long nb = read_hex(path, bytes, sizeof bytes);
	if (nb < 0 || hid_desc_parse(bytes, (size_t)nb, &nkro, err, sizeof err) < 0) {
		fprintf(stderr, "input_bench: %s: %s\n", path, nb < 0 ? "unreadable" : err);
		exit(1);
	}
	/* boot mouse: buttons, X, Y; a button change every eighth report */
	size_t n = UNITS;
	uint8_t *m = malloc(n * 3);
	for (size_t i = 0; i < n; i++) {
		m[3 * i] = (uint8_t)((i / 8) % 2);
		m[3 * i + 1] = (uint8_t)(next() % 21 - 10);
		m[3 * i + 2] = (uint8_t)(next() % 21 - 10);
	}
	/* NKRO: the input report's length from the descriptor; a key or two changing a report */
	const struct hid_desc_report *rep = hid_desc_report_by_id(&nkro, 0);
	size_t klen = rep ? rep->bytes : 25;
	uint8_t *k = calloc(n, klen);
	for (size_t i = 1; i < n; i++) {
		memcpy(k + i * klen, k + (i - 1) * klen, klen);
		size_t byte = 1 + next() % (klen - 1);
		k[i * klen + byte] ^= (uint8_t)(1u << (next() % 8));
	}
	double ev_m, ev_k;
	double ns_m = hid_run(&mouse, m, 3, n, &ev_m), ns_k = hid_run(&nkro, k, klen, n, &ev_k);
	printf("BENCH input.hid ns=%.1f mouse_ns=%.1f nkro_ns=%.1f mouse_report_ns=%.1f "
	       "nkro_report_ns=%.1f floor_ns=%.1f reports=%zu target_ns=150\n",
	       ev_m > ev_k ? ev_m : ev_k, ev_m, ev_k, ns_m, ns_k, floor_ns(k, klen, n), n);
	free(m);
	free(k);
}

static void
bench_can(const char *root)
{
	static struct can_map map;
	static struct can_input c;
	char err[512], path[4096];
	snprintf(path, sizeof path, "%s/tests/input/can/panel.map", root);
	if (can_map_read(path, &map, err, sizeof err) < 0) {
		fprintf(stderr, "input_bench: %s\n", err);
		exit(1);
	}
	size_t n = UNITS;
	struct can_frame *f = calloc(n, sizeof *f);
	for (size_t i = 0; i < n; i++) {
		f[i].can_id = map.line[next() % (unsigned)map.n].can_id;
		f[i].len = map.id_len[0] ? map.id_len[0] : 8;
		for (int b = 0; b < 8; b++)
			f[i].data[b] = (uint8_t)next();
	}
	for (size_t i = 0; i < n; i++) /* each frame at its own message's length */
		for (int m = 0; m < map.n_ids; m++)
			if (map.ids[m] == f[i].can_id)
				f[i].len = map.id_len[m];
	double best = 1e30;
	for (int r = 0; r < ROUNDS; r++) {
		drained = 0;
		can_input_init(&c, &map, 0, "bench");
		uint64_t t0 = bench_clock_us(NULL);
		for (size_t i = 0; i < n; i++) {
			can_input_feed(&c, (const uint8_t *)&f[i], sizeof *f, i, &q);
			if (i % BATCH == BATCH - 1)
				drain();
		}
		drain();
		double ns = (double)(bench_clock_us(NULL) - t0) * 1000.0 / (double)n;
		best = ns < best ? ns : best;
	}
	printf("BENCH input.can ns=%.1f frame_ns=%.1f floor_ns=%.1f frames=%zu events=%llu lines=%d "
	       "target_ns=100\n",
	       best * (double)n / (double)drained, best, floor_ns((const uint8_t *)f, sizeof *f, n), n,
	       (unsigned long long)drained, map.n);
	free(f);
}

int
main(int argc, char **argv)
{
	const char *root = argc > 1 ? argv[1] : ".";
	input_queue_init(&q);
	bench_evdev();
	bench_hid(root);
	bench_can(root);
	return 0;
}
