/* can_dev.c - the SocketCAN backend: CAN_RAW socket, filters, reads into the decoder (can_dev.h) */
#include <errno.h>
#include <fcntl.h>
#include <linux/can/raw.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/time.h>
#include <sys/timerfd.h>
#include <unistd.h>

#include "devices/can_dev.h"
#include "devices/input_devs.h"

/* CANFD_MTU: a datagram up to this size is read whole, so a wrong size can be named */
#define CAN_DEV_DATAGRAM_MAX 72

/* the fields every open shares, whether by interface or by a test's fd */
static void
can_dev_init(struct can_dev *d, const struct can_map *map, uint16_t device, const char *who)
{
	memset(d, 0, sizeof *d);
	d->fd = -1;
	d->map = map;
	d->recvmsg_fn = recvmsg;
	can_input_init(&d->in, map, device, who);
	devlog_init(&d->link_log, who);
}

/* a socket call failed: the reason into err, fd closed, -1 */
static int
can_dev_fail(struct can_dev *d, int fd, char *err, size_t errlen, const char *fmt, ...)
	__attribute__((format(printf, 5, 6)));

static int
can_dev_fail(struct can_dev *d, int fd, char *err, size_t errlen, const char *fmt, ...)
{
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(err, errlen, fmt, ap);
	va_end(ap);
	if (fd >= 0)
		close(fd);
	d->fd = -1;
	return -1;
}

int
can_dev_open(struct can_dev *d, const char *iface, const struct can_map *map, uint16_t device,
	     char *err, size_t errlen)
{
	char who[sizeof d->in.log.who];
	snprintf(who, sizeof who, "panel (%.*s)", IF_NAMESIZE - 1, iface);
	can_dev_init(d, map, device, who);
	if (strlen(iface) >= IF_NAMESIZE) {
		snprintf(err, errlen, "'%.40s': an interface name has at most %d characters", iface,
			 IF_NAMESIZE - 1);
		return -1;
	}
	snprintf(d->iface, sizeof d->iface, "%s", iface);

	int fd = socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
	if (fd < 0) {
		int e = errno;
		if (e == EAFNOSUPPORT || e == EPROTONOSUPPORT)
			return can_dev_fail(d, fd, err, errlen,
					    "no CAN in this kernel (socket(PF_CAN): %s)", strerror(e));
		return can_dev_fail(d, fd, err, errlen, "socket(PF_CAN): %s", strerror(e));
	}
	struct ifreq ifr;
	memset(&ifr, 0, sizeof ifr);
	snprintf(ifr.ifr_name, sizeof ifr.ifr_name, "%s", iface);
	if (ioctl(fd, SIOCGIFINDEX, &ifr) < 0) {
		int e = errno;
		if (e == ENODEV)
			return can_dev_fail(d, fd, err, errlen, "no such CAN interface");
		return can_dev_fail(d, fd, err, errlen, "SIOCGIFINDEX %s: %s", iface, strerror(e));
	}
	int ifindex = ifr.ifr_ifindex;

	/* the map's ids only (none: nothing), before bind so no other frame slips in */
	if (map) {
		struct can_filter flt[CAN_MAP_MAX_LINES];
		int n = can_map_filters(map, flt, CAN_MAP_MAX_LINES);
		if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, n ? flt : NULL,
			       (socklen_t)((size_t)n * sizeof flt[0])) < 0)
			return can_dev_fail(d, fd, err, errlen, "CAN_RAW_FILTER: %s",
					    strerror(errno));
	}
	can_err_mask_t em = CAN_DEV_ERR_MASK;
	if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &em, sizeof em) < 0)
		return can_dev_fail(d, fd, err, errlen, "CAN_RAW_ERR_FILTER: %s", strerror(errno));
	int on = 1;
	if (setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on) < 0 ||
	    setsockopt(fd, SOL_SOCKET, SO_TIMESTAMP, &on, sizeof on) < 0)
		return can_dev_fail(d, fd, err, errlen, "SO_RXQ_OVFL/SO_TIMESTAMP: %s",
				    strerror(errno));

	struct sockaddr_can addr;
	memset(&addr, 0, sizeof addr);
	addr.can_family = AF_CAN;
	addr.can_ifindex = ifindex;
	if (bind(fd, (struct sockaddr *)&addr, sizeof addr) < 0) {
		/* the kernel binds CAN sockets to CAN interfaces only */
		int e = errno;
		if (e == ENODEV)
			return can_dev_fail(d, fd, err, errlen, "%s is not a CAN interface", iface);
		return can_dev_fail(d, fd, err, errlen, "bind %s: %s", iface, strerror(e));
	}

	/*
	 * a bound socket on a down interface reads nothing until it is up: say so
	 * here, and take the ENETDOWN the kernel's bind left pending (SO_ERROR
	 * clears it), so that the first read does not say it a second time
	 */
	if (ioctl(fd, SIOCGIFFLAGS, &ifr) == 0 && !(ifr.ifr_flags & IFF_UP)) {
		int pending;
		socklen_t len = sizeof pending;
		getsockopt(fd, SOL_SOCKET, SO_ERROR, &pending, &len);
		d->down = 1;
		devlog(&d->link_log, 0, DEVLOG_DEVICE,
		       "interface %s is down: frames will be read when it is up", iface);
	}
	d->fd = fd;
	return 0;
}

int
can_dev_adopt(struct can_dev *d, int fd, const struct can_map *map, uint16_t device,
	      const char *iface, char *err, size_t errlen)
{
	char who[sizeof d->in.log.who];
	snprintf(who, sizeof who, "panel (%.*s)", IF_NAMESIZE - 1, iface);
	can_dev_init(d, map, device, who);
	int flags = fcntl(fd, F_GETFL);
	if (flags < 0 || fcntl(fd, F_SETFL, flags | O_NONBLOCK) < 0) {
		snprintf(err, errlen, "fd %d: %s", fd, strerror(errno));
		return -1;
	}
	snprintf(d->iface, sizeof d->iface, "%.*s", IF_NAMESIZE - 1, iface);
	d->fd = fd;
	return 0;
}

int
can_dev_fd(const struct can_dev *d)
{
	return d->fd;
}

/* appends text to dest (n bytes), kept NUL-terminated */
static void
append(char *dest, size_t n, const char *text)
{
	size_t len = strlen(dest);
	if (len + 1 < n)
		snprintf(dest + len, n - len, "%s%s", len ? ", " : "", text);
}

int
can_dev_error_describe(const uint8_t frame[CAN_INPUT_FRAME_SIZE], char *dest, size_t n)
{
	static const struct {
		uint32_t bit;
		const char *what;
	} classes[] = {
		{ CAN_ERR_TX_TIMEOUT, "transmit timeout" },
		{ CAN_ERR_LOSTARB, "lost arbitration" },
		{ CAN_ERR_CRTL, "controller problem" },
		{ CAN_ERR_PROT, "protocol violation" },
		{ CAN_ERR_TRX, "transceiver problem" },
		{ CAN_ERR_ACK, "no ACK" },
		{ CAN_ERR_BUSOFF, "bus-off" },
		{ CAN_ERR_BUSERROR, "bus error" },
		{ CAN_ERR_RESTARTED, "controller restarted" },
		{ CAN_ERR_CNT, "error counters" },
	};
	static const struct {
		uint8_t bit;
		const char *what;
	} crtl[] = {
		{ CAN_ERR_CRTL_RX_OVERFLOW, "receive buffer overflow" },
		{ CAN_ERR_CRTL_TX_OVERFLOW, "transmit buffer overflow" },
		{ CAN_ERR_CRTL_RX_WARNING, "receive error warning" },
		{ CAN_ERR_CRTL_TX_WARNING, "transmit error warning" },
		{ CAN_ERR_CRTL_RX_PASSIVE, "receive error passive" },
		{ CAN_ERR_CRTL_TX_PASSIVE, "transmit error passive" },
		{ CAN_ERR_CRTL_ACTIVE, "back to error active" },
	};
	uint32_t can_id;
	memcpy(&can_id, frame, sizeof can_id);
	const uint8_t *data = frame + 8;
	if (n)
		dest[0] = 0;
	for (size_t k = 0; k < sizeof classes / sizeof classes[0]; k++)
		if (can_id & classes[k].bit)
			append(dest, n, classes[k].what);
	if (can_id & CAN_ERR_CRTL)
		for (size_t k = 0; k < sizeof crtl / sizeof crtl[0]; k++)
			if (data[1] & crtl[k].bit)
				append(dest, n, crtl[k].what);
	if (can_id & CAN_ERR_PROT) {
		char detail[48];
		snprintf(detail, sizeof detail, "protocol type 0x%02x at 0x%02x", data[2], data[3]);
		append(dest, n, detail);
	}
	if (n && !dest[0])
		snprintf(dest, n, "no class given (id 0x%08x)", can_id);
	return (can_id & CAN_ERR_BUSOFF) != 0;
}

/* the panel can no longer be heard: buttons released, valuators stale (once), one line */
static void
can_dev_went_silent(struct can_dev *d, uint64_t now_us, struct input_queue *q, const char *why)
{
	d->down = 1;
	int released = d->map ? can_input_release_all(&d->in, now_us, q, 1) : 0;
	devlog(&d->link_log, now_us, DEVLOG_DEVICE,
	       "%s: %d button(s) released, dials stale until frames come again", why, released);
}

/* an error frame: counted, said in words; bus-off silences the panel */
static void
can_dev_error_frame(struct can_dev *d, const uint8_t *frame, uint64_t now_us,
		    struct input_queue *q)
{
	char what[200];
	d->error_frames++;
	if (can_dev_error_describe(frame, what, sizeof what)) {
		d->bus_off++;
		char why[240];
		snprintf(why, sizeof why, "the bus is off (error frame: %s)", what);
		can_dev_went_silent(d, now_us, q, why);
		return;
	}
	devlog(&d->in.log, now_us, DEVLOG_DEVICE, "error frame: %s", what);
}

/* the interface is gone: release what the panel held, say so, queue INPUT_REMOVED */
static void
can_dev_gone(struct can_dev *d, uint64_t now_us, struct input_queue *q, int err)
{
	int released = d->map ? can_input_release_all(&d->in, now_us, q, 0) : 0;
	if (err)
		devlog_last(&d->link_log, now_us, err == ENODEV ? DEVLOG_DEVICE : DEVLOG_KERNEL,
			    "interface %s gone (%s); %d button(s) released", d->iface, strerror(err),
			    released);
	else
		devlog_last(&d->link_log, now_us, DEVLOG_KERNEL,
			    "gone (end of the stream); %d button(s) released", released);
	input_queue_removed(q, now_us, d->in.device, INPUT_CLASS_PANEL);
}

/* the kernel's receive time and drop count from the control messages */
static void
can_dev_cmsgs(struct can_dev *d, struct msghdr *msg, uint64_t now_us, uint64_t *stamp_dest)
{
	*stamp_dest = 0;
	for (struct cmsghdr *c = CMSG_FIRSTHDR(msg); c; c = CMSG_NXTHDR(msg, c)) {
		if (c->cmsg_level != SOL_SOCKET)
			continue;
		if (c->cmsg_type == SO_TIMESTAMP && c->cmsg_len >= CMSG_LEN(sizeof(struct timeval))) {
			struct timeval tv;
			memcpy(&tv, CMSG_DATA(c), sizeof tv);
			*stamp_dest = (uint64_t)tv.tv_sec * 1000000u + (uint64_t)tv.tv_usec;
		} else if (c->cmsg_type == SO_RXQ_OVFL && c->cmsg_len >= CMSG_LEN(sizeof(uint32_t))) {
			uint32_t dropped;
			memcpy(&dropped, CMSG_DATA(c), sizeof dropped);
			if (dropped != d->rxq_ovfl) {
				uint32_t more = dropped - d->rxq_ovfl;
				d->kernel_dropped += more;
				d->rxq_ovfl = dropped;
				devlog(&d->link_log, now_us, DEVLOG_US,
				       "the kernel dropped %u frame(s): we read too slowly", more);
			}
		}
	}
}

int
can_dev_read(struct can_dev *d, uint64_t now_us, struct input_queue *q)
{
	if (d->fd < 0)
		return -1;
	d->nlast = 0;
	int got = 0;
	/* bounded in datagrams too: refused ones and errors count against the cap */
	for (int tries = 0; tries < 2 * CAN_DEV_READ_MAX && d->nlast < CAN_DEV_READ_MAX; tries++) {
		uint8_t buf[CAN_DEV_DATAGRAM_MAX];
		union {
			char buf[CMSG_SPACE(sizeof(struct timeval)) + CMSG_SPACE(sizeof(uint32_t))];
			struct cmsghdr align;
		} control;
		struct iovec iov = { .iov_base = buf, .iov_len = sizeof buf };
		struct msghdr msg = { .msg_iov = &iov, .msg_iovlen = 1,
				      .msg_control = control.buf,
				      .msg_controllen = sizeof control.buf };
		ssize_t n = d->recvmsg_fn(d->fd, &msg, MSG_DONTWAIT);
		if (n < 0) {
			if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)
				break;
			if (errno == ENETDOWN) {
				/* the socket stays bound: reads resume when the interface is up */
				d->downs++;
				char why[64];
				snprintf(why, sizeof why, "interface %s went down", d->iface);
				can_dev_went_silent(d, now_us, q, why);
				continue;
			}
			can_dev_gone(d, now_us, q, errno);
			return -1;
		}
		if (n == 0) {
			/* a CAN socket never reads 0 bytes: only a stand-in's closed peer does */
			can_dev_gone(d, now_us, q, 0);
			return -1;
		}
		got = 1;
		if (n != CAN_INPUT_FRAME_SIZE || (msg.msg_flags & MSG_TRUNC)) {
			d->bad_size++;
			devlog(&d->in.log, now_us, DEVLOG_DEVICE,
			       "read of %zd bytes%s, not a 16-byte can_frame: refused", n,
			       (msg.msg_flags & MSG_TRUNC) ? " or more" : "");
			continue;
		}
		uint64_t stamp;
		can_dev_cmsgs(d, &msg, now_us, &stamp);
		memcpy(d->frame[d->nlast], buf, CAN_INPUT_FRAME_SIZE);
		d->stamp_us[d->nlast++] = stamp;
		d->frames++;

		uint32_t can_id;
		memcpy(&can_id, buf, sizeof can_id);
		if (can_id & CAN_ERR_FLAG) {
			can_dev_error_frame(d, buf, now_us, q);
			continue;
		}
		/* a data frame: whatever silenced the panel is over */
		if (d->down) {
			d->down = 0;
			devlog(&d->link_log, now_us, DEVLOG_DEVICE, "frames again on %s", d->iface);
		}
		if (d->map)
			can_input_feed(&d->in, buf, CAN_INPUT_FRAME_SIZE, now_us, q);
	}
	if (got)
		d->reads++;
	if (d->nlast == CAN_DEV_READ_MAX)
		d->capped++;
	if (d->map)
		can_input_tick(&d->in, now_us, q);
	return d->nlast;
}

void
can_dev_close(struct can_dev *d, uint64_t now_us, struct input_queue *q)
{
	if (q && d->map)
		can_input_release_all(&d->in, now_us, q, 0);
	if (d->fd >= 0)
		close(d->fd);
	d->fd = -1;
}

/* ---- the backend for the device set (devices/input_backend.h) ---- */

/* a panel: the device and the map it decodes by, in one allocation made at open */
struct can_panel {
	struct can_dev dev;
	struct can_map map;
};

/* the shared timer that lets stale dials be reported on a silent bus */
static int can_timer_fd = -1;
static int can_panels_open;

static void
can_timer_hold(void)
{
	if (can_panels_open++ || can_timer_fd >= 0)
		return;
	can_timer_fd = timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC);
	if (can_timer_fd < 0)
		return; /* staleness is then reported when frames come */
	struct itimerspec its = {
		.it_interval = { .tv_sec = 0, .tv_nsec = CAN_DEV_TICK_MS * 1000000L },
		.it_value = { .tv_sec = 0, .tv_nsec = CAN_DEV_TICK_MS * 1000000L },
	};
	if (timerfd_settime(can_timer_fd, 0, &its, NULL) < 0) {
		close(can_timer_fd);
		can_timer_fd = -1;
	}
}

static void
can_timer_release(void)
{
	if (can_panels_open > 0 && --can_panels_open == 0 && can_timer_fd >= 0) {
		close(can_timer_fd);
		can_timer_fd = -1;
	}
}

static int
can_backend_fd(const void *dev)
{
	return can_dev_fd(dev);
}

static int
can_backend_read(void *dev, uint64_t now_us, struct input_queue *q)
{
	return can_dev_read(dev, now_us, q) < 0 ? -1 : 0;
}

static void
can_backend_close(void *dev, uint64_t now_us, struct input_queue *q)
{
	can_dev_close(dev, now_us, q);
	free(dev);
	can_timer_release();
}

static int
can_backend_shared_fds(struct pollfd *fds, int max)
{
	if (can_timer_fd < 0 || max < 1)
		return 0;
	fds[0] = (struct pollfd){ .fd = can_timer_fd, .events = POLLIN };
	return 1;
}

static void
can_backend_shared_work(uint64_t now_us, struct input_queue *q)
{
	(void)now_us;
	(void)q;
	uint64_t expirations;
	if (can_timer_fd >= 0 && read(can_timer_fd, &expirations, sizeof expirations) < 0) {
		/* EAGAIN: not expired yet; the set reads the panels all the same */
	}
}

static int
can_backend_open_spec(struct input_devs *s, const char *arg, char *err, size_t errlen)
{
	/* IFACE:MAPFILE */
	const char *colon = arg ? strchr(arg, ':') : NULL;
	if (!colon || colon == arg || !colon[1]) {
		snprintf(err, errlen, "input 'can:%.100s': expected can:IFACE:MAPFILE",
			 arg ? arg : "");
		return -1;
	}
	char iface[IF_NAMESIZE];
	size_t len = (size_t)(colon - arg);
	if (len >= sizeof iface) {
		snprintf(err, errlen, "input 'can:%.100s': an interface name has at most %d "
			 "characters", arg, IF_NAMESIZE - 1);
		return -1;
	}
	memcpy(iface, arg, len);
	iface[len] = 0;
	if (input_devs_find(s, &input_backend_can, iface) >= 0)
		return 0;

	/* the map first: a bad one is the configuration's fault, whatever the kernel has */
	struct can_panel *p = malloc(sizeof *p);
	if (!p) {
		snprintf(err, errlen, "input 'can:%.100s': out of memory", arg);
		return -1;
	}
	char why[256];
	if (can_map_read(colon + 1, &p->map, why, sizeof why) < 0) {
		snprintf(err, errlen, "input 'can:%.40s': %s", arg, why);
		free(p);
		return -1;
	}
	int i = input_devs_free_place(s, iface);
	if (i < 0) {
		free(p);
		return 0;
	}
	if (can_dev_open(&p->dev, iface, &p->map, (uint16_t)i, why, sizeof why) < 0) {
		input_devs_skip(s, iface, why);
		free(p);
		return 0;
	}
	struct input_dev_info info = { .iface = -1, .cls = INPUT_CLASS_PANEL };
	snprintf(info.path, sizeof info.path, "%s", iface);
	const char *base = strrchr(colon + 1, '/');
	snprintf(info.name, sizeof info.name, "CAN panel (%.100s)", base ? base + 1 : colon + 1);
	can_timer_hold();
	input_devs_put(s, i, &input_backend_can, p, &info);
	return 1;
}

static void
can_backend_stats(const void *dev, struct input_dev_stats *dest)
{
	const struct can_dev *d = dev;
	*dest = (struct input_dev_stats){
		.reads = d->reads,
		.capped = d->capped,
		.errors = d->bad_size + d->error_frames + d->kernel_dropped,
	};
}

/* a candump log has no head: the panel's map, which its frames are decoded by */
static int
can_backend_describe(const void *dev, FILE *out)
{
	const struct can_dev *d = dev;
	return d->map ? can_map_write(out, d->map) : -1;
}

const struct input_backend input_backend_can = {
	.name = "can",
	.usage = "can:IFACE:MAPFILE",
	.open_spec = can_backend_open_spec,
	.fd = can_backend_fd,
	.read = can_backend_read,
	.close = can_backend_close,
	.stats = can_backend_stats,
	.shared_fds = can_backend_shared_fds,
	.shared_work = can_backend_shared_work,
	.rec_format = "candump",
	.describe = can_backend_describe,
};
