/*
 * server.h - listeners and clients: a Unix socket, and a loopback TCP port
 * only when asked for (with a token). Per-client input and output buffers
 * with hard caps; a protocol breach is answered, then the client closed;
 * a client that does not read is dropped rather than stalling the others.
 */
#ifndef POSTURE_SERVER_H
#define POSTURE_SERVER_H

#include <poll.h>
#include <stddef.h>
#include <stdint.h>

#define SERVER_MAX_CLIENTS 64
#define SERVER_IN_MAX (65536 + 2)   /* a request line, its CR and LF */
#define SERVER_OUT_MAX (8u << 20)   /* queued output before a client is dropped */

struct client {
	int fd; /* -1: a free slot */
	int tcp;
	int authed;      /* TCP: the token was given */
	int closing;     /* flush what is queued, then close */
	unsigned subs;   /* enum sub_kind bits */
	char *in;        /* SERVER_IN_MAX bytes */
	size_t in_len;
	char *out;
	size_t out_len, out_off, out_cap;
};

struct server {
	int unix_fd, tcp_fd;
	char unix_path[4096];
	char token[128];
	struct client c[SERVER_MAX_CLIENTS];
	int nclients;
	uint64_t dropped; /* clients dropped for not reading */
};

/* no sockets and no clients yet (server_open does this first; server_close is safe after it) */
void server_init(struct server *s);

/*
 * Opens the Unix socket at path (mode 0660; a stale socket file is
 * replaced, a live one refused) and, when tcp_port > 0, 127.0.0.1:port.
 * Returns 0, or -1 with a message.
 */
int server_open(struct server *s, const char *path, int tcp_port, const char *token, char *err,
		size_t errlen);
void server_close(struct server *s);

/* accepts pending connections on a listener; the overflow is told `limit` and closed */
void server_accept(struct server *s, int listen_fd);

/* fills pollfds: listeners, then clients; returns the count */
int server_pollfds(const struct server *s, struct pollfd *fds, int *owner);

/*
 * Reads what a client sent. Returns the number of bytes now buffered, 0
 * when the peer closed, -1 on an error (the caller closes the client).
 */
long server_read(struct server *s, int i);

/* the next complete line of client i (without LF), or NULL; *len set */
const char *server_line(struct client *c, size_t *len, size_t *consumed);
void server_consume(struct client *c, size_t n);

/* queues bytes (a reply or event line, newline included); -1 when over the cap */
int server_queue(struct server *s, int i, const char *data, size_t len);

/* writes queued output; closes clients that finished closing or broke */
void server_flush(struct server *s, int i);

void server_drop(struct server *s, int i);

#endif
