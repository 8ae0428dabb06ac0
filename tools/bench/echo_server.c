/*
 * echo_server.c - the peer of the socket benchmark: a trivial single-threaded
 * poll() server on a Unix socket that writes back every byte it reads.
 *
 * It costs what any server over the same socket must pay (poll, read, write),
 * so postured's round trip beside it shows what parsing, dispatch, the JSON
 * reply and the journal add. Usage: echo_server SOCKET (SIGTERM or SIGINT ends it).
 */
#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#define MAX_CLIENTS 128

static volatile sig_atomic_t stop;

static void
on_signal(int sig)
{
	(void)sig;
	stop = 1;
}

/* writes all of buf; 0, or -1 when the client is gone */
static int
write_all(int fd, const char *buf, size_t len)
{
	while (len) {
		ssize_t n = write(fd, buf, len);
		if (n < 0 && errno == EINTR)
			continue;
		if (n <= 0)
			return -1;
		buf += n;
		len -= (size_t)n;
	}
	return 0;
}

int
main(int argc, char **argv)
{
	if (argc != 2) {
		fprintf(stderr, "usage: echo_server SOCKET\n");
		return 2;
	}
	struct sigaction sa = { .sa_handler = on_signal };
	sigaction(SIGTERM, &sa, NULL);
	sigaction(SIGINT, &sa, NULL);
	signal(SIGPIPE, SIG_IGN);

	/* listen */
	struct sockaddr_un addr = { .sun_family = AF_UNIX };
	if (strlen(argv[1]) >= sizeof addr.sun_path) {
		fprintf(stderr, "echo_server: socket path too long\n");
		return 1;
	}
	strcpy(addr.sun_path, argv[1]);
	unlink(argv[1]);
	int lfd = socket(AF_UNIX, SOCK_STREAM, 0);
	if (lfd < 0 || bind(lfd, (struct sockaddr *)&addr, sizeof addr) < 0 || listen(lfd, 128) < 0) {
		perror("echo_server");
		return 1;
	}

	/* serve: slot 0 listens, the others are clients (fd -1 when free) */
	struct pollfd fds[MAX_CLIENTS + 1];
	fds[0] = (struct pollfd){ .fd = lfd, .events = POLLIN };
	for (int i = 1; i <= MAX_CLIENTS; i++)
		fds[i] = (struct pollfd){ .fd = -1, .events = POLLIN };
	char buf[1 << 16];
	while (!stop) {
		if (poll(fds, MAX_CLIENTS + 1, 500) < 0) {
			if (errno == EINTR)
				continue;
			perror("echo_server: poll");
			break;
		}
		if (fds[0].revents & POLLIN) {
			int cfd = accept(lfd, NULL, NULL);
			int placed = 0;
			for (int i = 1; cfd >= 0 && i <= MAX_CLIENTS && !placed; i++)
				if (fds[i].fd < 0) {
					fds[i].fd = cfd;
					placed = 1;
				}
			if (cfd >= 0 && !placed)
				close(cfd);
		}
		for (int i = 1; i <= MAX_CLIENTS; i++) {
			if (fds[i].fd < 0 || !fds[i].revents)
				continue;
			ssize_t n = read(fds[i].fd, buf, sizeof buf);
			if (n < 0 && errno == EINTR)
				continue;
			if (n <= 0 || write_all(fds[i].fd, buf, (size_t)n) < 0) {
				close(fds[i].fd);
				fds[i].fd = -1;
			}
		}
	}
	close(lfd);
	unlink(argv[1]);
	return 0;
}
