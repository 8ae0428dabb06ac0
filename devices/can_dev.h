/*
 * can_dev.h - the SocketCAN backend: a dial panel on a CAN interface
 * (`can:IFACE:MAPFILE`), read through a CAN_RAW socket into the panel
 * decoder (devices/can_input.h).
 *
 * The socket is bound to the named interface with one kernel receive
 * filter per id of the panel map (can_map_filters), so frames of other ids
 * never reach us; error frames come through CAN_RAW_ERR_FILTER (bus-off,
 * controller, protocol, transceiver, ACK and bus errors, restarts). Every
 * read is one whole 16-byte struct can_frame; anything else is refused and
 * counted with a log line blaming the device. SO_RXQ_OVFL says how many
 * frames the kernel dropped because we read too slowly (logged, counted).
 *
 * The interface going down and up (ENETDOWN): the socket is kept (the
 * kernel keeps it bound; reads resume when the interface is up again, no
 * rebind needed), the device stays in the set (no INPUT_REMOVED), but what
 * the panel holds may change unseen while it is down, so its buttons are
 * released and its valuators reported stale at once; the first frame after
 * up reports them afresh. Bus-off (an error frame) is treated the same way:
 * nothing arrives until the controller restarts. One log line each way.
 *
 * The interface disappearing (ENODEV) removes the device: its buttons are
 * released and INPUT_REMOVED queued. An interface that does not exist at
 * open is skipped with the reason "no such CAN interface"; a kernel with no
 * CAN (socket(PF_CAN) failing with EAFNOSUPPORT) is skipped with "no CAN in
 * this kernel". A rescan of the device set opens it when it has appeared.
 *
 * Valuators go stale by the map's stale= times even when the bus is silent:
 * the backend keeps one timer (a timerfd, its shared fd, every
 * CAN_DEV_TICK_MS while a CAN device is open) whose expiry has the set read
 * every CAN device, and each read ends with can_input_tick.
 *
 * Event times are the daemon's clock (now_us) at the read; the kernel's
 * receive time (SO_TIMESTAMP, the wall clock candump writes) is kept with
 * each frame of the last read for a recorder.
 */
#ifndef POSTURE_DEVICES_CAN_DEV_H
#define POSTURE_DEVICES_CAN_DEV_H

#include <linux/can/error.h>
#include <net/if.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/socket.h>
#include <sys/types.h>

#include "devices/can_input.h"
#include "devices/can_map.h"
#include "devices/input_backend.h"
#include "devices/queue.h"

/* frames one can_dev_read takes at most, so a flooding bus cannot hold the loop */
#define CAN_DEV_READ_MAX 64

/* how often the shared timer lets stale valuators be reported */
#define CAN_DEV_TICK_MS 50

/* the error classes asked for with CAN_RAW_ERR_FILTER (not lost arbitration: normal on a bus) */
#define CAN_DEV_ERR_MASK                                                                       \
	(CAN_ERR_TX_TIMEOUT | CAN_ERR_CRTL | CAN_ERR_PROT | CAN_ERR_TRX | CAN_ERR_ACK |        \
	 CAN_ERR_BUSOFF | CAN_ERR_BUSERROR | CAN_ERR_RESTARTED)

struct can_dev {
	int fd;                        /* -1 when closed */
	char iface[IF_NAMESIZE];
	const struct can_map *map;     /* NULL: every frame taken, none decoded (a recorder) */
	struct can_input in;           /* the decoder; its log names the device */
	struct devlog link_log;        /* down, up, bus-off, gone, drops: not drowned by bad frames */
	uint8_t down;                  /* the interface is down (or the bus off): nothing arrives */

	/* the test seam for faults: recvmsg, or a test's stand-in */
	ssize_t (*recvmsg_fn)(int fd, struct msghdr *msg, int flags);

	/* the last read's whole frames, and the kernel's receive times (wall clock, µs; 0: none) */
	uint8_t frame[CAN_DEV_READ_MAX][CAN_INPUT_FRAME_SIZE];
	uint64_t stamp_us[CAN_DEV_READ_MAX];
	int nlast;

	/* counters */
	uint64_t reads;          /* can_dev_read calls that read something */
	uint64_t capped;         /* ... that stopped at CAN_DEV_READ_MAX */
	uint64_t frames;         /* whole frames read (data, RTR and error) */
	uint64_t bad_size;       /* datagrams that were not 16 bytes, refused */
	uint64_t error_frames;
	uint64_t bus_off;        /* error frames saying bus-off */
	uint64_t downs;          /* times the interface was found down */
	uint64_t kernel_dropped; /* frames the kernel dropped for us (SO_RXQ_OVFL) */
	uint32_t rxq_ovfl;       /* the kernel's drop count last seen */
};

/*
 * Opens a CAN_RAW socket on interface iface (non-blocking, close-on-exec)
 * as the daemon's device index `device`: filters for the ids of map (which
 * must outlive d), or every frame when map is NULL; error frames; drop
 * counts; receive times. Returns 0, or -1 with the reason in err and d
 * closed: "no CAN in this kernel (...)", "no such CAN interface",
 * "IFACE is not a CAN interface", or the call that failed. An interface
 * that is down is not an error: it is logged and read once it is up.
 */
int
can_dev_open(struct can_dev *d, const char *iface, const struct can_map *map, uint16_t device,
	     char *err, size_t errlen);

/*
 * The test seam: takes fd (a SOCK_SEQPACKET socket standing in for the
 * CAN socket, whose datagrams a test writes) as can_dev_open takes the
 * interface called iface, with no filters. The fd is made non-blocking and
 * is d's from then on. Returns 0, or -1 with the reason in err.
 */
int
can_dev_adopt(struct can_dev *d, int fd, const struct can_map *map, uint16_t device,
	      const char *iface, char *err, size_t errlen);

/* the fd to poll for reading, or -1 when closed */
int
can_dev_fd(const struct can_dev *d);

/*
 * Reads what the socket has, at most CAN_DEV_READ_MAX frames, decodes the
 * data frames through the map into q at now_us, logs and counts error
 * frames and wrong sizes, handles the interface going down (see above),
 * then reports what went stale. Returns the whole frames read (0: none
 * waiting), or -1 when the interface is gone (ENODEV, or a stand-in's end
 * of stream): its buttons were released, INPUT_REMOVED queued and a line
 * logged; the caller closes it with can_dev_close.
 */
int
can_dev_read(struct can_dev *d, uint64_t now_us, struct input_queue *q);

/*
 * Releases the buttons the panel held (as events into q at now_us; q may be
 * NULL) and closes the socket. Safe on a closed or zeroed (fd -1) device.
 */
void
can_dev_close(struct can_dev *d, uint64_t now_us, struct input_queue *q);

/*
 * An error frame (16 bytes) in words: its classes, and the controller's
 * and protocol's details where the frame gives them, into dest.
 * Returns 1 when it says bus-off, else 0.
 */
int
can_dev_error_describe(const uint8_t frame[CAN_INPUT_FRAME_SIZE], char *dest, size_t n);

/* the backend for the device set: can:IFACE:MAPFILE (devices/input_backend.h) */
extern const struct input_backend input_backend_can;

#endif
