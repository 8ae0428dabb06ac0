/*
 * hidraw_dev.h - the hidraw backend: a /dev/hidrawN node opened through
 * hidapi (Debian libhidapi-hidraw 0.13.1), its reports into the HID
 * decoder (devices/hid_input.h), closed with what it held released.
 *
 * Finding devices. hidraw:VID:PID[:IFACE] enumerates with hid_enumerate
 * and keeps the entries whose usage is a mouse (page 0x01, usage 0x02) or
 * a keyboard (0x01/0x06); 0.13.1 lists one entry per collection, nested
 * Physical ones included (a mouse is 01/02 and 01/01), and one node can
 * hold a mouse and a keyboard, so the entries are de-duplicated by path:
 * one device per hidraw node. hidraw:/dev/hidrawN opens that node whatever
 * it is. The kernel's hid-input stays bound: its evdev node still gets the
 * events, hidraw sees a copy (there is no grab).
 *
 * The descriptor. 0.13.1 has no hid_get_report_descriptor: we read sysfs
 * /sys/class/hidraw/hidrawN/device/report_descriptor (no privilege needed)
 * and fall back to HIDIOCGRDESCSIZE + HIDIOCGRDESC on a descriptor of our
 * own. A descriptor our parser refuses leaves the device closed, with the
 * parser's message as the reason. The name, the physical path and the bus
 * come from the HID device's uevent (HID_NAME, HID_PHYS, HID_ID), what
 * hid-recorder writes as N:, P: and I:.
 *
 * Hi-res wheels. For each Resolution Multiplier the descriptor lists
 * (hid_desc.multipliers[]) the feature report is read (GET_FEATURE, to
 * keep its other fields; zeros when the device will not say), the
 * multiplier set to its logical maximum, as the kernel's
 * hid_setup_resolution_multiplier does, and written back
 * (hid_send_feature_report). The wheels it governs then count in
 * 1/multiplier detents, which the decoder turns into 1/120. A write the
 * device refuses is logged, and those wheels are decoded in whole detents
 * again (the device stays in its low-resolution mode).
 *
 * The poll loop. hidapi's hid_device hides its fd, so the loop cannot
 * poll it. Each device gets one reader thread that blocks in
 * hid_read_timeout and forwards each report as one datagram over a
 * socketpair(AF_UNIX, SOCK_SEQPACKET); the other end is the device's fd
 * in the loop. Why this shape:
 *   - the loop never blocks on a device and never wakes on a timer: it
 *     polls an fd like every other backend's, readable when a report is;
 *   - SEQPACKET keeps report boundaries (one recv, one report) and tells
 *     the end of the stream apart (recv returns 0 when the thread closed
 *     its end; every datagram has a header, so none is empty);
 *   - the thread only reads and sends; decoding, the queue, the time base
 *     and every decision stay on the loop's thread, so nothing but the
 *     socket is shared, plus two atomics for stopping and for why it ended;
 *   - the same socketpair is the test seam: hidraw_dev_adopt takes any
 *     SEQPACKET fd in the thread's place, and a test writes recorded
 *     reports into it (socketpair(SOCK_SEQPACKET) stands in for every
 *     backend's fd).
 * The alternatives were worse: polling hid_read_timeout(dev, 0) from the
 * loop on a timer adds latency and wakes an idle daemon; finding the fd
 * inside hid_device relies on hidapi's private layout; opening the node a
 * second time ourselves would bypass hidapi altogether.
 *
 * A datagram is HIDRAW_DEV_HEAD bytes of header, the CLOCK_MONOTONIC time
 * in microseconds at which the thread's read returned (host byte order;
 * hidraw has no timestamps of its own, and hid-recorder stamps reports the
 * same way), then the report as hidraw gives it (the id byte first when
 * the descriptor has ids).
 *
 * The thread's life. It is started after the multipliers are written (so
 * it is hid_device's only user from then on) with every signal blocked
 * (no EINTR inside hidapi). It ends on its own when hid_read_timeout
 * fails (the device gone: hidraw answers POLLHUP or EIO after an unplug),
 * storing why and closing its end: the loop reads the end of the stream,
 * releases what the device held and queues INPUT_REMOVED. It ends when
 * asked: hidraw_dev_close sets the stop flag and closes the loop's end
 * (a thread blocked in send, the loop having fallen behind, wakes with
 * EPIPE), then joins it (hid_read_timeout returns every
 * HIDRAW_DEV_POLL_MS to look at the flag), and only then hid_close()s
 * the device and frees what the thread used. Close order: stop flag, the
 * loop's end, join, hid_close, free; the thread closes its own end.
 *
 * A device flooding reports: hidraw_dev_read takes at most
 * HIDRAW_DEV_READ_MAX reports a call and counts the calls that stopped
 * there; the rest waits in the socket (the loop comes back at once, the
 * fd still readable). When the socket is full the thread waits in send
 * and the kernel's hidraw buffer (64 reports a reader) drops the excess.
 */
#ifndef POSTURE_DEVICES_HIDRAW_DEV_H
#define POSTURE_DEVICES_HIDRAW_DEV_H

#include <stddef.h>
#include <stdint.h>

#include "devices/event.h"
#include "devices/hid_desc.h"
#include "devices/hid_input.h"
#include "devices/input_backend.h"
#include "devices/queue.h"
#include "devices/rec_hid.h"

#define HIDRAW_DEV_READ_MAX 64        /* reports one hidraw_dev_read takes at most */
#define HIDRAW_DEV_REPORT_MAX 4096    /* bytes of one report (hid-recorder reads 4096) */
#define HIDRAW_DEV_HEAD 8             /* a datagram's header: the uint64_t time in us */
#define HIDRAW_DEV_POLL_MS 50         /* the thread's read timeout: how soon it sees a stop */
#define HIDRAW_DEV_FOUND_MAX 16       /* nodes one enumeration gives at most */
#define HIDRAW_DEV_WHY_MAX 160

/* what a device is: the HID device's uevent, the enumeration, the descriptor */
struct hidraw_dev_info {
	char name[REC_HID_MAX_NAME];  /* HID_NAME */
	char phys[REC_HID_MAX_NAME];  /* HID_PHYS */
	uint16_t bus, vendor, product; /* HID_ID: the kernel's BUS_* and the ids */
	int iface;                     /* the USB interface, -1 when unknown or not USB */
	/*
	 * by the descriptor's top-level Application collections: Mouse
	 * (Generic Desktop 0x02) or Keyboard (0x06); a node with both is
	 * called a mouse and has both flags
	 */
	enum input_class cls;
	uint8_t mouse, keyboard;
};

/* a node hid_enumerate gave for a spec (de-duplicated) */
struct hidraw_dev_found {
	char path[INPUT_DEV_PATH_MAX];
	uint16_t vendor, product;
	int iface;
	uint8_t mouse, keyboard;       /* the usages its entries had */
};

/*
 * Feature reports, for the multipliers: set 0 reads report buf[0] into
 * buf (at most n bytes; returns the bytes, the id byte included), set 1
 * writes the n bytes of buf (returns the bytes written); -1 on failure.
 * hidapi's hid_get/send_feature_report behind a real device; tests put
 * their own.
 */
typedef int (*hidraw_dev_feature_fn)(void *ctx, int set, uint8_t *buf, size_t n);

/* called with each report read, before it is decoded (a recorder's hook) */
typedef void (*hidraw_dev_tap_fn)(void *ctx, uint64_t t_us, const uint8_t *report, size_t n);

struct hidraw_reader;

struct hidraw_dev {
	int fd;                          /* the loop's end of the socketpair, or -1 */
	char path[INPUT_DEV_PATH_MAX];
	struct hidraw_dev_info info;
	uint16_t desc_len;
	uint8_t desc_bytes[HID_DESC_MAX_BYTES]; /* as the device gave it, for a recorder */
	struct hid_desc desc;
	struct hid_input in;             /* the decoder (points at desc) */
	struct hidraw_reader *reader;    /* the thread and the hid_device; NULL when adopted */
	hidraw_dev_tap_fn tap;
	void *tap_ctx;
	uint8_t buf[HIDRAW_DEV_HEAD + HIDRAW_DEV_REPORT_MAX + 1];

	/* counters */
	uint64_t reads;      /* hidraw_dev_read calls that read something */
	uint64_t capped;     /* ... that stopped at HIDRAW_DEV_READ_MAX */
	uint64_t reports;    /* reports handed to the decoder */
	uint64_t bad;        /* datagrams dropped: shorter than the header, or longer than a report */
	unsigned multipliers_set, multipliers_refused;
};

/*
 * Parses a spec's argument: "VID:PID" or "VID:PID:IFACE" (hex ids, a
 * decimal interface) into *vid, *pid, *iface (-1 when not given), or a
 * path ("/dev/hidraw3") into *path. Returns 0, or -1 with err.
 */
int
hidraw_dev_parse_spec(const char *arg, uint16_t *vid, uint16_t *pid, int *iface,
		      const char **path, char *err, size_t errlen);

/*
 * The hidraw nodes hid_enumerate lists for vid:pid (0 matches any) that
 * hold a mouse or keyboard collection, on interface iface (-1: any), one
 * per path, in hidapi's order, at most max into dest. Returns the count;
 * when it is 0, err says why (hidapi's message when it found nothing, as
 * 0.13.1 does not tell "no device" from "cannot enumerate").
 */
int
hidraw_dev_enumerate(uint16_t vid, uint16_t pid, int iface, struct hidraw_dev_found *dest,
		     int max, char *err, size_t errlen);

/*
 * Opens the hidraw node at path as the daemon's device index `device`
 * (iface: what the enumeration said, -1 otherwise): reads and parses its
 * descriptor, opens it with hid_open_path, writes the Resolution
 * Multipliers and starts the reader. Returns 0, or -1 with the reason in
 * err (the descriptor cannot be read or is refused, hidapi cannot open
 * the node, no socket or thread) and d closed.
 */
int
hidraw_dev_open(struct hidraw_dev *d, const char *path, int iface, uint16_t device, char *err,
		size_t errlen);

/*
 * The test seam: takes fd, one end of a socketpair(AF_UNIX,
 * SOCK_SEQPACKET) whose other end a test writes datagrams into (header
 * and report, as the reader thread sends them), in place of the reader,
 * with the descriptor desc[0..n) (parsed as hidraw_dev_open parses it;
 * no multipliers written: see hidraw_dev_set_multipliers). The fd is made
 * non-blocking and is d's from then on (closed by hidraw_dev_close).
 * Returns 0, or -1 with the reason in err (the descriptor is refused, or
 * fd is not an open descriptor) and d closed, the fd left open.
 */
int
hidraw_dev_adopt(struct hidraw_dev *d, int fd, const uint8_t *desc, size_t n, uint16_t device,
		 const char *who, char *err, size_t errlen);

/*
 * Writes every Resolution Multiplier of d's descriptor through feature
 * (see hidraw_dev_feature_fn), as hidraw_dev_open does with hidapi's. A
 * multiplier whose write fails is logged and its wheels are decoded in
 * whole detents. Returns the multipliers written.
 */
int
hidraw_dev_set_multipliers(struct hidraw_dev *d, hidraw_dev_feature_fn feature, void *ctx);

/* the fd to poll for reading, or -1 when closed */
int
hidraw_dev_fd(const struct hidraw_dev *d);

/*
 * Reads what has arrived, at most HIDRAW_DEV_READ_MAX reports, each into
 * the decoder (its events into q, stamped with the report's time) after
 * the tap. Returns the reports read (0: nothing waiting), or -1 when the
 * device is gone (the reader saw the device fail, or the stream ended):
 * what it held was released as events at now_us, INPUT_REMOVED queued and
 * a line logged; the caller closes it with hidraw_dev_close.
 */
int
hidraw_dev_read(struct hidraw_dev *d, uint64_t now_us, struct input_queue *q);

/*
 * Releases the buttons and keys the device held (as events into q, at
 * now_us; q may be NULL), stops and joins the reader, closes the device
 * and the fd. Safe on a closed or never opened (zeroed, fd -1) device.
 */
void
hidraw_dev_close(struct hidraw_dev *d, uint64_t now_us, struct input_queue *q);

/* d's description as a hid-recorder device (R:, N:, P:, I:) */
void
hidraw_dev_describe(const struct hidraw_dev *d, struct rec_hid_device *dest);

/* the backend for the device set: hidraw:VID:PID[:IFACE], hidraw:PATH */
extern const struct input_backend input_backend_hidraw;

#endif
