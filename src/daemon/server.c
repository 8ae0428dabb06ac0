/* server.c - sockets, client buffers and their limits */
#define _GNU_SOURCE /* accept4 */
#include "daemon/server.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

static int
fail(char *err, size_t errlen, const char *what, const char *path)
{
	snprintf(err, errlen, "%s %s: %s", what, path, strerror(errno));
	return -1;
}

/* a socket file nobody answers on is a leftover of a crash: remove it */
static int
remove_stale(const char *path)
{
	struct sockaddr_un a = { .sun_family = AF_UNIX };
	snprintf(a.sun_path, sizeof a.sun_path, "%s", path);
	int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
	if (fd < 0)
		return -1;
	int live = connect(fd, (struct sockaddr *)&a, sizeof a) == 0;
	close(fd);
	if (live) {
		errno = EADDRINUSE;
		return -1;
	}
	struct stat st;
	if (!lstat(path, &st) && S_ISSOCK(st.st_mode))
		unlink(path);
	return 0;
}

void
server_init(struct server *s)
{
	memset(s, 0, sizeof *s);
	s->unix_fd = s->tcp_fd = -1;
	for (int i = 0; i < SERVER_MAX_CLIENTS; i++)
		s->c[i].fd = -1;
}

int
server_open(struct server *s, const char *path, int tcp_port, const char *token, char *err,
	    size_t errlen)
{
	server_init(s);
	struct sockaddr_un a = { .sun_family = AF_UNIX };
	if (strlen(path) >= sizeof a.sun_path) {
		snprintf(err, errlen, "socket path longer than %zu bytes", sizeof a.sun_path - 1);
		return -1;
	}
	snprintf(a.sun_path, sizeof a.sun_path, "%s", path);
	snprintf(s->unix_path, sizeof s->unix_path, "%s", path);
	if (remove_stale(path) < 0)
		return fail(err, errlen, "another daemon listens on", path);
	s->unix_fd = socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
	/* created 0660 from the start: no window where others could connect */
	mode_t old = umask(0117);
	int rc = s->unix_fd < 0 ? -1 : bind(s->unix_fd, (struct sockaddr *)&a, sizeof a);
	umask(old);
	if (rc < 0 || listen(s->unix_fd, 64) < 0)
		return fail(err, errlen, "cannot listen on", path);
	if (tcp_port > 0) {
		if (!token || !token[0]) {
			snprintf(err, errlen, "--tcp needs --token");
			return -1;
		}
		snprintf(s->token, sizeof s->token, "%s", token);
		struct sockaddr_in in = { .sin_family = AF_INET, .sin_port = htons((uint16_t)tcp_port) };
		in.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
		int one = 1;
		s->tcp_fd = socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
		if (s->tcp_fd < 0 || setsockopt(s->tcp_fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) < 0 ||
		    bind(s->tcp_fd, (struct sockaddr *)&in, sizeof in) < 0 || listen(s->tcp_fd, 64) < 0)
			return fail(err, errlen, "cannot listen on", "127.0.0.1");
	}
	return 0;
}

void
server_drop(struct server *s, int i)
{
	struct client *c = &s->c[i];
	if (c->fd < 0)
		return;
	close(c->fd);
	free(c->in);
	free(c->out);
	memset(c, 0, sizeof *c);
	c->fd = -1;
	s->nclients--;
}

void
server_close(struct server *s)
{
	for (int i = 0; i < SERVER_MAX_CLIENTS; i++)
		server_drop(s, i);
	if (s->unix_fd >= 0) {
		close(s->unix_fd);
		unlink(s->unix_path);
	}
	if (s->tcp_fd >= 0)
		close(s->tcp_fd);
	s->unix_fd = s->tcp_fd = -1;
}

void
server_accept(struct server *s, int listen_fd)
{
	for (;;) {
		int fd = accept4(listen_fd, NULL, NULL, SOCK_NONBLOCK | SOCK_CLOEXEC);
		if (fd < 0)
			return; /* EAGAIN, or a client that vanished while queued */
		int slot = -1;
		for (int i = 0; i < SERVER_MAX_CLIENTS && slot < 0; i++)
			if (s->c[i].fd < 0)
				slot = i;
		char *in = slot >= 0 ? malloc(SERVER_IN_MAX) : NULL;
		if (!in) {
			static const char full[] =
				"{\"ok\":false,\"error\":{\"code\":\"limit\",\"message\":\"too many clients\"}}\n";
			ssize_t ignored = write(fd, full, sizeof full - 1);
			(void)ignored;
			close(fd);
			continue;
		}
		struct client *c = &s->c[slot];
		memset(c, 0, sizeof *c);
		c->fd = fd;
		c->in = in;
		c->tcp = listen_fd == s->tcp_fd;
		c->authed = !c->tcp;
		s->nclients++;
	}
}

int
server_pollfds(const struct server *s, struct pollfd *fds, int *owner)
{
	int n = 0;
	if (s->unix_fd >= 0) {
		fds[n] = (struct pollfd){ .fd = s->unix_fd, .events = POLLIN };
		owner[n++] = -1;
	}
	if (s->tcp_fd >= 0) {
		fds[n] = (struct pollfd){ .fd = s->tcp_fd, .events = POLLIN };
		owner[n++] = -2;
	}
	for (int i = 0; i < SERVER_MAX_CLIENTS; i++) {
		const struct client *c = &s->c[i];
		if (c->fd < 0)
			continue;
		short ev = c->closing ? 0 : POLLIN;
		if (c->out_len > c->out_off)
			ev |= POLLOUT;
		fds[n] = (struct pollfd){ .fd = c->fd, .events = ev };
		owner[n++] = i;
	}
	return n;
}

long
server_read(struct server *s, int i)
{
	struct client *c = &s->c[i];
	size_t room = SERVER_IN_MAX - c->in_len;
	if (!room)
		return (long)c->in_len; /* full: the caller finds the over-long line */
	ssize_t n = read(c->fd, c->in + c->in_len, room);
	if (n < 0)
		return errno == EAGAIN || errno == EINTR ? (long)c->in_len : -1;
	if (n == 0)
		return 0;
	c->in_len += (size_t)n;
	return (long)c->in_len;
}

const char *
server_line(struct client *c, size_t *len, size_t *consumed)
{
	char *nl = memchr(c->in, '\n', c->in_len);
	if (!nl)
		return NULL;
	*len = (size_t)(nl - c->in);
	*consumed = *len + 1;
	return c->in;
}

void
server_consume(struct client *c, size_t n)
{
	memmove(c->in, c->in + n, c->in_len - n);
	c->in_len -= n;
}

int
server_queue(struct server *s, int i, const char *data, size_t len)
{
	struct client *c = &s->c[i];
	if (c->out_off && c->out_off == c->out_len) /* all sent: start over */
		c->out_off = c->out_len = 0;
	if (c->out_len - c->out_off + len > SERVER_OUT_MAX) {
		s->dropped++;
		return -1;
	}
	if (c->out_len + len > c->out_cap) {
		/* compact first, grow only when that is not enough */
		if (c->out_off) /* (a first reply: no buffer yet, nothing to move) */
			memmove(c->out, c->out + c->out_off, c->out_len - c->out_off);
		c->out_len -= c->out_off;
		c->out_off = 0;
		if (c->out_len + len > c->out_cap) {
			size_t cap = c->out_cap ? c->out_cap : 65536;
			while (cap < c->out_len + len)
				cap *= 2;
			char *p = realloc(c->out, cap);
			if (!p)
				return -1;
			c->out = p;
			c->out_cap = cap;
		}
	}
	memcpy(c->out + c->out_len, data, len);
	c->out_len += len;
	return 0;
}

void
server_flush(struct server *s, int i)
{
	struct client *c = &s->c[i];
	while (c->fd >= 0 && c->out_off < c->out_len) {
		ssize_t n = send(c->fd, c->out + c->out_off, c->out_len - c->out_off, MSG_NOSIGNAL);
		if (n < 0 && errno == EINTR)
			continue;
		if (n < 0 && errno == EAGAIN)
			return;
		if (n <= 0) {
			server_drop(s, i);
			return;
		}
		c->out_off += (size_t)n;
	}
	if (c->fd >= 0 && c->closing && c->out_off == c->out_len)
		server_drop(s, i);
}
