/*
 * guest_daemon.h - the real daemon inside the test guest, and a client of
 * its line protocol: what guest_kiosk.c and guest_screen.c share. Static
 * functions in a header, as guest_check.h's: each guest program is one file.
 */
#ifndef POSTURE_GUEST_DAEMON_H
#define POSTURE_GUEST_DAEMON_H

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <jansson.h>

#include "tests/guest/guest_check.h"

#ifndef SOCK
#define SOCK "/tmp/kiosk/sock"
#endif

/* ---- the daemon ---- */

static pid_t daemon_pid = -1;

/* forks and runs argv (stdout and stderr stay on the console): 0, or -1 */
static inline int
daemon_start(char *const argv[])
{
	fflush(stdout);
	pid_t pid = fork();
	if (pid < 0)
		return -1;
	if (pid == 0) {
		execv(argv[0], argv);
		fprintf(stderr, "exec %s: %s\n", argv[0], strerror(errno));
		_exit(127);
	}
	daemon_pid = pid;
	return 0;
}

/* 1 while the daemon runs; its end said once */
static inline int
daemon_alive(void)
{
	if (daemon_pid < 0)
		return 0;
	int st;
	pid_t r = waitpid(daemon_pid, &st, WNOHANG);
	if (r == 0)
		return 1;
	if (r == daemon_pid) {
		if (WIFSIGNALED(st))
			printf("postured died of signal %d\n", WTERMSIG(st));
		else
			printf("postured exited with status %d\n", WEXITSTATUS(st));
	}
	daemon_pid = -1;
	return 0;
}

/* SIGTERM, then its exit status (-1: a signal or not running) */
static inline int
daemon_stop(void)
{
	if (!daemon_alive())
		return -1;
	kill(daemon_pid, SIGTERM);
	int st;
	if (waitpid(daemon_pid, &st, 0) != daemon_pid)
		return -1;
	daemon_pid = -1;
	return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* ---- a client of the line protocol ---- */

struct conn {
	int fd;
	char *buf;   /* bytes read and not yet taken as lines */
	size_t len, cap;
};

static char last_error[512]; /* the last request's failure, for FAIL lines */

/* connects to the daemon's socket, waiting up to ms for it: 0, or -1 */
static inline int
conn_open(struct conn *c, int ms)
{
	memset(c, 0, sizeof *c);
	struct sockaddr_un a = { .sun_family = AF_UNIX };
	snprintf(a.sun_path, sizeof a.sun_path, "%s", SOCK);
	uint64_t end = now_us() + (uint64_t)ms * 1000u;
	do {
		c->fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
		if (c->fd >= 0 && connect(c->fd, (struct sockaddr *)&a, sizeof a) == 0)
			return 0;
		close(c->fd);
		c->fd = -1;
		sleep_ms(50);
	} while (now_us() < end && daemon_alive());
	return -1;
}

static inline void
conn_close(struct conn *c)
{
	if (c->fd >= 0)
		close(c->fd);
	free(c->buf);
	memset(c, 0, sizeof *c);
	c->fd = -1;
}

/* the next line (malloc'ed, without its newline), waiting up to ms; NULL: none or EOF */
static inline char *
conn_line(struct conn *c, int ms)
{
	uint64_t end = now_us() + (uint64_t)ms * 1000u;
	for (;;) {
		char *nl = c->len ? memchr(c->buf, '\n', c->len) : NULL;
		if (nl) {
			size_t n = (size_t)(nl - c->buf);
			char *line = strndup(c->buf, n);
			memmove(c->buf, nl + 1, c->len - n - 1);
			c->len -= n + 1;
			return line;
		}
		/* ms 0 still looks once: what the socket holds counts, not only what is buffered */
		uint64_t now = now_us();
		int wait = now >= end ? 0 : (int)((end - now) / 1000u) + 1;
		struct pollfd p = { .fd = c->fd, .events = POLLIN };
		if (poll(&p, 1, wait) <= 0)
			return NULL;
		if (c->cap - c->len < 65536) {
			c->cap = c->cap ? c->cap * 2 : 1 << 17;
			c->buf = realloc(c->buf, c->cap);
		}
		ssize_t r = read(c->fd, c->buf + c->len, c->cap - c->len);
		if (r <= 0)
			return NULL;
		c->len += (size_t)r;
	}
}

/*
 * One request and its reply (events before it are skipped): the reply's
 * result (the caller's to json_decref), or NULL with last_error set.
 */
static inline json_t *
request(struct conn *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static inline json_t *
request(struct conn *c, const char *fmt, ...)
{
	char line[1024];
	va_list ap;
	va_start(ap, fmt);
	int n = vsnprintf(line, sizeof line - 1, fmt, ap);
	va_end(ap);
	line[n++] = '\n';
	if (write(c->fd, line, (size_t)n) != n) {
		snprintf(last_error, sizeof last_error, "write: %s", strerror(errno));
		return NULL;
	}
	for (;;) {
		char *text = conn_line(c, 20000);
		if (!text) {
			snprintf(last_error, sizeof last_error, "no reply to '%.*s'", n - 1, line);
			return NULL;
		}
		json_t *reply = json_loads(text, 0, NULL);
		free(text);
		if (!reply || json_object_get(reply, "event")) {
			json_decref(reply);
			continue;
		}
		json_t *result = json_incref(json_object_get(reply, "result"));
		if (!json_is_true(json_object_get(reply, "ok")) || !result) {
			char *why = json_dumps(json_object_get(reply, "error"), JSON_COMPACT);
			snprintf(last_error, sizeof last_error, "'%.*s': %s", n - 1, line,
				 why ? why : "?");
			free(why);
			json_decref(result);
			result = NULL;
		}
		json_decref(reply);
		return result;
	}
}

/* a request whose reply does not matter beyond success: 0, or -1 (said) */
static inline int
command(struct conn *c, const char *line)
{
	json_t *r = request(c, "%s", line);
	if (!r) {
		printf("command failed: %s\n", last_error);
		return -1;
	}
	json_decref(r);
	return 0;
}

/* ---- what the daemon says ---- */

/* an integer field of `status` (undo, redo ...), or -1 */
static inline long
status_field(struct conn *c, const char *key)
{
	json_t *r = request(c, "status");
	long v = r && json_is_integer(json_object_get(r, key)) ?
			 (long)json_integer_value(json_object_get(r, key)) : -1;
	json_decref(r);
	return v;
}

#endif
