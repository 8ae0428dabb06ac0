/*
 * rtt_client.c - round-trip latency and throughput of one request line over a
 * Unix socket, with N clients at once (one thread each, one request in flight
 * per client, so every sample is a full round trip).
 *
 * Usage: rtt_client SOCKET CLIENTS REQUESTS LINE NAME
 * Each client connects, sends WARMUP untimed requests, then REQUESTS timed
 * ones, reading each reply line whole before sending the next. Prints
 *   BENCH NAME.rtt.<N>client median_us=... p99_us=... rps=...
 * where the percentiles are over every client's samples and rps is all timed
 * replies divided by the wall time from the first timed send to the last reply.
 * A reply that does not start with {"ok":true is counted as an error (and for
 * an echo server, the echoed line counts as a reply). Exit status 1 on errors.
 */
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#define WARMUP 200
#define MAX_CLIENTS 256

struct worker {
	pthread_t thread;
	const char *path, *line;
	int requests;
	int check_ok;            /* replies must start with {"ok":true */
	double *us;              /* requests samples */
	int errors;
	uint64_t t_first, t_last; /* first timed send, last reply (ns) */
};

static pthread_barrier_t start_line;

static uint64_t
now_ns(void)
{
	struct timespec ts;
	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

/* sends line, reads one reply line; 1 when it is ok, 0 when not, -1 on I/O error */
static int
round_trip(int fd, const char *line, size_t len, int check_ok)
{
	static _Thread_local char buf[1 << 16];
	size_t have = 0;
	if (write(fd, line, len) != (ssize_t)len)
		return -1;
	for (;;) {
		ssize_t n = read(fd, buf + have, sizeof buf - 1 - have);
		if (n <= 0)
			return -1;
		have += (size_t)n;
		if (buf[have - 1] == '\n')
			break;
		if (have == sizeof buf - 1)
			return -1;
	}
	return !check_ok || !strncmp(buf, "{\"ok\":true", 10);
}

static void *
work(void *arg)
{
	struct worker *w = arg;
	struct sockaddr_un addr = { .sun_family = AF_UNIX };
	snprintf(addr.sun_path, sizeof addr.sun_path, "%s", w->path);
	int fd = socket(AF_UNIX, SOCK_STREAM, 0);
	int connected = fd >= 0 && connect(fd, (struct sockaddr *)&addr, sizeof addr) == 0;
	size_t len = strlen(w->line);

	/* warm up, then start together */
	for (int i = 0; connected && i < WARMUP; i++)
		if (round_trip(fd, w->line, len, w->check_ok) < 0)
			connected = 0;
	pthread_barrier_wait(&start_line);
	if (!connected) {
		w->errors = w->requests;
		w->t_first = w->t_last = now_ns();
		if (fd >= 0)
			close(fd);
		return NULL;
	}
	w->t_first = now_ns();
	for (int i = 0; i < w->requests; i++) {
		uint64_t t0 = now_ns();
		int rc = round_trip(fd, w->line, len, w->check_ok);
		uint64_t t1 = now_ns();
		w->us[i] = (double)(t1 - t0) / 1000.0;
		if (rc < 0) {
			w->errors += w->requests - i;
			break;
		}
		w->errors += !rc;
		w->t_last = t1;
	}
	close(fd);
	return NULL;
}

static int
cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return (x > y) - (x < y);
}

int
main(int argc, char **argv)
{
	if (argc != 6) {
		fprintf(stderr, "usage: rtt_client SOCKET CLIENTS REQUESTS LINE NAME\n");
		return 2;
	}
	int clients = atoi(argv[2]), requests = atoi(argv[3]);
	if (clients < 1 || clients > MAX_CLIENTS || requests < 1) {
		fprintf(stderr, "rtt_client: 1..%d clients, at least 1 request\n", MAX_CLIENTS);
		return 2;
	}
	char *line = malloc(strlen(argv[4]) + 2);
	double *all = malloc(sizeof *all * (size_t)clients * (size_t)requests);
	static struct worker w[MAX_CLIENTS];
	if (!line || !all)
		return 1;
	sprintf(line, "%s\n", argv[4]);
	int check_ok = strcmp(argv[5], "echo") != 0;

	/* run */
	pthread_barrier_init(&start_line, NULL, (unsigned)clients);
	for (int i = 0; i < clients; i++) {
		w[i] = (struct worker){ .path = argv[1], .line = line, .requests = requests,
					.check_ok = check_ok, .us = all + (size_t)i * (size_t)requests };
		pthread_create(&w[i].thread, NULL, work, &w[i]);
	}
	int errors = 0;
	uint64_t first = UINT64_MAX, last = 0;
	for (int i = 0; i < clients; i++) {
		pthread_join(w[i].thread, NULL);
		errors += w[i].errors;
		first = w[i].t_first < first ? w[i].t_first : first;
		last = w[i].t_last > last ? w[i].t_last : last;
	}

	/* report */
	size_t n = (size_t)clients * (size_t)requests;
	qsort(all, n, sizeof *all, cmp_double);
	double secs = (double)(last - first) / 1e9;
	printf("BENCH %s.rtt.%dclient median_us=%.2f p99_us=%.2f rps=%.0f clients=%d requests=%zu "
	       "errors=%d\n", argv[5], clients, all[n / 2], all[(size_t)(0.99 * (double)(n - 1))],
	       secs > 0 ? (double)n / secs : 0.0, clients, n, errors);
	free(all);
	free(line);
	return errors ? 1 : 0;
}
