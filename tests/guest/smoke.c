/* smoke.c — prove, inside the test guest, the kernel interfaces that the
 * input backends rely on: uinput + evdev (grab, monotonic clock), vcan +
 * CAN_RAW (loopback, filters, interface down/up) and uhid + hidraw.
 *
 * When dummy_hcd, libcomposite and usb_f_hid are loaded it also makes a
 * USB HID mouse through a configfs gadget and reads its report on the host
 * side.  One line per check: "ok <what>", "FAIL <what>: <why>", or
 * "skip <what>: <why>" for a part whose modules were not asked for.  Exit status is
 * the number of failures (capped at 100).  Needs root and the modules
 * uinput, evdev, vcan, can_raw, uhid, hid_generic (and for the gadget:
 * dummy_hcd, libcomposite, usb_f_hid, usbhid).  Stand-alone: no project
 * code.  Build: cc -std=c11 -Wall -Wextra -Werror -o smoke smoke.c
 */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <net/if.h>
#include <poll.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <linux/can.h>
#include <linux/can/raw.h>
#include <linux/hidraw.h>
#include <linux/input.h>
#include <linux/uhid.h>
#include <linux/uinput.h>

static int failures;

static void ok(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("ok ", stdout);
    vprintf(fmt, ap);
    putchar('\n');
    va_end(ap);
    fflush(stdout);
}

static int fail(const char *what, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    printf("FAIL %s: ", what);
    vprintf(fmt, ap);
    putchar('\n');
    va_end(ap);
    fflush(stdout);
    failures++;
    return -1;
}

static void sleep_ms(long ms)
{
    struct timespec ts = { ms / 1000, (ms % 1000) * 1000000L };
    nanosleep(&ts, NULL);
}

static double mono_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec / 1e9;
}

/* Read exactly n bytes with a timeout; returns bytes read or -1. */
static ssize_t read_timeout(int fd, void *buf, size_t n, int ms)
{
    struct pollfd p = { .fd = fd, .events = POLLIN };
    int r = poll(&p, 1, ms);
    if (r <= 0) {
        if (r == 0)
            errno = ETIMEDOUT;
        return -1;
    }
    return read(fd, buf, n);
}

/* Find the "eventN" child of a sysfs folder (one level deep). */
static int find_event_child(const char *dir, char *out, size_t outlen)
{
    DIR *d = opendir(dir);
    if (!d)
        return -1;
    struct dirent *e;
    int found = -1;
    while ((e = readdir(d)) != NULL) {
        if (strncmp(e->d_name, "event", 5) == 0) {
            snprintf(out, outlen, "/dev/input/%s", e->d_name);
            found = 0;
            break;
        }
    }
    closedir(d);
    return found;
}

/* ------------------------------------------------------------- uinput */

static int emit(int fd, int type, int code, int value)
{
    struct input_event ev;
    memset(&ev, 0, sizeof ev);
    ev.type = (unsigned short)type;
    ev.code = (unsigned short)code;
    ev.value = value;
    return write(fd, &ev, sizeof ev) == (ssize_t)sizeof ev ? 0 : -1;
}

static void check_uinput(void)
{
    const char *W = "uinput";
    int ufd = open("/dev/uinput", O_WRONLY | O_NONBLOCK | O_CLOEXEC);
    if (ufd < 0) {
        fail(W, "open /dev/uinput: %s", strerror(errno));
        return;
    }
    if (ioctl(ufd, UI_SET_EVBIT, EV_KEY) < 0 ||
        ioctl(ufd, UI_SET_KEYBIT, BTN_LEFT) < 0 ||
        ioctl(ufd, UI_SET_EVBIT, EV_REL) < 0 ||
        ioctl(ufd, UI_SET_RELBIT, REL_X) < 0 ||
        ioctl(ufd, UI_SET_RELBIT, REL_Y) < 0) {
        fail(W, "UI_SET_*BIT: %s", strerror(errno));
        close(ufd);
        return;
    }
    struct uinput_setup us;
    memset(&us, 0, sizeof us);
    us.id.bustype = BUS_USB;
    us.id.vendor = 0x1234;
    us.id.product = 0x5678;
    snprintf(us.name, sizeof us.name, "posture smoke mouse");
    if (ioctl(ufd, UI_DEV_SETUP, &us) < 0 || ioctl(ufd, UI_DEV_CREATE) < 0) {
        fail(W, "UI_DEV_SETUP/CREATE: %s", strerror(errno));
        close(ufd);
        return;
    }
    char sysname[64] = "", dir[160], node[320];
    if (ioctl(ufd, UI_GET_SYSNAME(sizeof sysname), sysname) < 0) {
        fail(W, "UI_GET_SYSNAME: %s", strerror(errno));
        goto out;
    }
    snprintf(dir, sizeof dir, "/sys/devices/virtual/input/%s", sysname);
    int tries;
    for (tries = 0; tries < 100; tries++) {
        if (find_event_child(dir, node, sizeof node) == 0 &&
            access(node, R_OK) == 0)
            break;
        sleep_ms(20);
    }
    if (tries == 100) {
        fail(W, "no event node under %s (is evdev loaded?)", dir);
        goto out;
    }
    ok("uinput device %s -> %s", sysname, node);

    int efd = open(node, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    int other = open(node, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (efd < 0 || other < 0) {
        fail("evdev open", "%s: %s", node, strerror(errno));
        goto out2;
    }
    char name[128] = "";
    if (ioctl(efd, EVIOCGNAME(sizeof name), name) < 0 ||
        strcmp(name, us.name) != 0)
        fail("evdev EVIOCGNAME", "got '%s'", name);
    else
        ok("evdev EVIOCGNAME '%s'", name);
    int clk = CLOCK_MONOTONIC;
    if (ioctl(efd, EVIOCSCLOCKID, &clk) < 0)
        fail("evdev EVIOCSCLOCKID", "%s", strerror(errno));
    else
        ok("evdev EVIOCSCLOCKID CLOCK_MONOTONIC");
    if (ioctl(efd, EVIOCGRAB, 1) < 0)
        fail("evdev EVIOCGRAB", "%s", strerror(errno));
    else if (ioctl(other, EVIOCGRAB, 1) == 0 || errno != EBUSY)
        fail("evdev EVIOCGRAB", "a second grab did not fail with EBUSY");
    else
        ok("evdev EVIOCGRAB (a second grab gets EBUSY)");

    double before = mono_now();
    if (emit(ufd, EV_REL, REL_X, 10) || emit(ufd, EV_REL, REL_Y, -4) ||
        emit(ufd, EV_SYN, SYN_REPORT, 0) ||
        emit(ufd, EV_KEY, BTN_LEFT, 1) || emit(ufd, EV_SYN, SYN_REPORT, 0)) {
        fail("uinput write", "%s", strerror(errno));
        goto out2;
    }
    const struct { int type, code, value; } want[] = {
        { EV_REL, REL_X, 10 }, { EV_REL, REL_Y, -4 }, { EV_SYN, SYN_REPORT, 0 },
        { EV_KEY, BTN_LEFT, 1 }, { EV_SYN, SYN_REPORT, 0 },
    };
    size_t n = sizeof want / sizeof want[0], got = 0;
    int bad = 0;
    double t_first = 0, after;
    while (got < n) {
        struct input_event ev;
        ssize_t r = read_timeout(efd, &ev, sizeof ev, 2000);
        if (r != (ssize_t)sizeof ev) {
            fail("evdev read", "after %zu events: %s (r=%zd)", got,
                 r < 0 ? strerror(errno) : "short read", r);
            bad = 1;
            break;
        }
        if (ev.type != want[got].type || ev.code != want[got].code ||
            ev.value != want[got].value) {
            fail("evdev read", "event %zu is %u/%u/%d, want %d/%d/%d", got,
                 ev.type, ev.code, ev.value, want[got].type, want[got].code,
                 want[got].value);
            bad = 1;
            break;
        }
        if (got == 0)
            t_first = (double)ev.input_event_sec +
                      (double)ev.input_event_usec / 1e6;
        got++;
    }
    after = mono_now();
    if (!bad) {
        ok("evdev read back %zu events of %zu bytes (REL_X 10, REL_Y -4, "
           "BTN_LEFT 1)", n, sizeof(struct input_event));
        /* A monotonic stamp falls between the two readings (1 ms slack for
         * the microsecond rounding); a realtime one would be far outside. */
        if (t_first + 0.001 < before || t_first > after + 0.001)
            fail("evdev monotonic time", "stamp %.6f outside [%.6f, %.6f]",
                 t_first, before, after);
        else
            ok("evdev timestamps are CLOCK_MONOTONIC (%.6f)", t_first);
    }
    struct input_event junk;
    if (read(other, &junk, sizeof junk) >= 0)
        fail("evdev grab", "a second reader got events despite the grab");
    else if (errno != EAGAIN)
        fail("evdev grab", "second reader: %s", strerror(errno));
    else
        ok("evdev grab hides events from other readers");

    /* Unplug: the reader sees ENODEV once the device is destroyed. */
    if (ioctl(ufd, UI_DEV_DESTROY) < 0) {
        fail("uinput destroy", "%s", strerror(errno));
    } else {
        struct pollfd p = { .fd = efd, .events = POLLIN };
        poll(&p, 1, 2000);
        ssize_t r = read(efd, &junk, sizeof junk);
        while (r == (ssize_t)sizeof junk)
            r = read(efd, &junk, sizeof junk);
        if (r < 0 && errno == ENODEV)
            ok("evdev read after UI_DEV_DESTROY fails with ENODEV "
               "(poll revents 0x%x)", (unsigned)p.revents);
        else
            fail("evdev unplug", "read gave %zd (%s), want ENODEV", r,
                 r < 0 ? strerror(errno) : "data");
    }
out2:
    if (efd >= 0)
        close(efd);
    if (other >= 0)
        close(other);
out:
    close(ufd);
}

/* ---------------------------------------------------------------- CAN */

static int sh(const char *cmd)
{
    int st = system(cmd);
    if (st == -1)
        return -1;
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128;
}

static int can_open(int ifindex)
{
    int s = socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
    if (s < 0)
        return -1;
    struct sockaddr_can a;
    memset(&a, 0, sizeof a);
    a.can_family = AF_CAN;
    a.can_ifindex = ifindex;
    if (bind(s, (struct sockaddr *)&a, sizeof a) < 0) {
        int e = errno;
        close(s);
        errno = e;
        return -1;
    }
    return s;
}

static int can_send(int s, canid_t id, const char *data, unsigned len)
{
    struct can_frame f;
    memset(&f, 0, sizeof f);
    f.can_id = id;
    f.len = (unsigned char)len;
    memcpy(f.data, data, len);
    return write(s, &f, sizeof f) == (ssize_t)sizeof f ? 0 : -1;
}

static void check_can(void)
{
    const char *W = "vcan";
    if (sh("ip link add dev vcan0 type vcan") != 0)
        fail(W, "'ip link add dev vcan0 type vcan' failed");
    else if (sh("ip link set vcan0 up") != 0)
        fail(W, "'ip link set vcan0 up' failed");
    unsigned ifindex = if_nametoindex("vcan0");
    if (ifindex == 0) {
        fail(W, "no vcan0: %s", strerror(errno));
        return;
    }
    ok("vcan0 created and up with busybox ip (ifindex %u)", ifindex);

    int tx = can_open((int)ifindex), rx = can_open((int)ifindex);
    if (tx < 0 || rx < 0) {
        fail("can_raw socket", "%s", strerror(errno));
        goto out;
    }
    ok("CAN_RAW sockets bound to vcan0");
    struct can_filter flt[2] = {
        { 0x181, CAN_SFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG },
        { 0x18FF0A42 | CAN_EFF_FLAG, CAN_EFF_MASK | CAN_EFF_FLAG | CAN_RTR_FLAG },
    };
    if (setsockopt(rx, SOL_CAN_RAW, CAN_RAW_FILTER, flt, sizeof flt) < 0) {
        fail("CAN_RAW_FILTER", "%s", strerror(errno));
        goto out;
    }
    can_err_mask_t em = CAN_ERR_MASK;
    if (setsockopt(rx, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &em, sizeof em) < 0)
        fail("CAN_RAW_ERR_FILTER", "%s", strerror(errno));
    else
        ok("CAN_RAW_FILTER (2 ids) and CAN_RAW_ERR_FILTER set");

    if (can_send(tx, 0x123, "\x01\x02", 2) ||
        can_send(tx, 0x181, "\xE8\x03\xF4\x01\x00\xF8\x00\x00", 8) ||
        can_send(tx, 0x18FF0A42 | CAN_EFF_FLAG, "\x7f", 1)) {
        fail("can send", "%s", strerror(errno));
        goto out;
    }
    struct can_frame f;
    ssize_t r = read_timeout(rx, &f, sizeof f, 2000);
    if (r != (ssize_t)sizeof f)
        fail("can loopback", "read %zd: %s", r,
             r < 0 ? strerror(errno) : "short");
    else if (f.can_id != 0x181 || f.len != 8 || f.data[0] != 0xE8 ||
             f.data[5] != 0xF8)
        fail("can filter", "first frame id 0x%x len %u, want 0x181 "
             "(0x123 should have been filtered)", f.can_id, f.len);
    else
        ok("CAN loopback: 0x181 [8] read back as one %zu-byte frame, 0x123 "
           "filtered out", sizeof f);
    r = read_timeout(rx, &f, sizeof f, 2000);
    if (r != (ssize_t)sizeof f || f.can_id != (0x18FF0A42 | CAN_EFF_FLAG))
        fail("can extended id", "read %zd id 0x%x", r, r > 0 ? f.can_id : 0);
    else
        ok("CAN extended id 0x18FF0A42 passes its filter");
    if (read_timeout(rx, &f, sizeof f, 100) >= 0)
        fail("can filter", "an extra frame 0x%x came through", f.can_id);

    /* The interface goes down and up under a bound socket. */
    if (sh("ip link set vcan0 down") != 0) {
        fail("vcan down", "'ip link set vcan0 down' failed");
        goto out;
    }
    r = read_timeout(rx, &f, sizeof f, 1000);
    int rerr = errno;
    int serr = can_send(tx, 0x181, "\x00", 1) < 0 ? errno : 0;
    if (r < 0 && rerr == ENETDOWN && serr == ENETDOWN)
        ok("vcan0 down: a bound reader gets ENETDOWN once, sending "
           "gets ENETDOWN");
    else
        fail("vcan down", "reader got %zd (%s), sender got %s", r,
             r < 0 ? strerror(rerr) : "data", serr ? strerror(serr) : "ok");
    if (sh("ip link set vcan0 up") != 0) {
        fail("vcan up", "'ip link set vcan0 up' failed");
        goto out;
    }
    if (can_send(tx, 0x181, "\x11", 1) < 0)
        fail("vcan up again", "send: %s", strerror(errno));
    else if ((r = read_timeout(rx, &f, sizeof f, 2000)) != (ssize_t)sizeof f ||
             f.can_id != 0x181 || f.data[0] != 0x11)
        fail("vcan up again", "the old socket read %zd: %s", r,
             r < 0 ? strerror(errno) : "wrong frame");
    else
        ok("vcan0 up again: the same bound socket receives again");
out:
    if (tx >= 0)
        close(tx);
    if (rx >= 0)
        close(rx);
}

/* --------------------------------------------------------------- uhid */

/* A boot-protocol mouse with a wheel: 3 buttons, 5 bits padding, then
 * X, Y, wheel as signed bytes (4-byte reports, no report id).  This is
 * the layout QEMU's emulated USB mouse reports. */
static const unsigned char mouse_rdesc[] = {
    0x05, 0x01, 0x09, 0x02, 0xA1, 0x01, 0x09, 0x01, 0xA1, 0x00,
    0x05, 0x09, 0x19, 0x01, 0x29, 0x03, 0x15, 0x00, 0x25, 0x01,
    0x95, 0x03, 0x75, 0x01, 0x81, 0x02, 0x95, 0x01, 0x75, 0x05,
    0x81, 0x01, 0x05, 0x01, 0x09, 0x30, 0x09, 0x31, 0x09, 0x38,
    0x15, 0x81, 0x25, 0x7F, 0x75, 0x08, 0x95, 0x03, 0x81, 0x06,
    0xC0, 0xC0,
};

static const char UHID_NAME[] = "posture smoke uhid mouse";

/* Find /dev/hidrawN and /dev/input/eventM of the HID device named name. */
static int find_hid_nodes(const char *name, char *hidraw, size_t hl,
                          char *event, size_t el)
{
    size_t namelen = strlen(name);
    DIR *d = opendir("/sys/class/hidraw");
    if (!d)
        return -1;
    struct dirent *e;
    int found = -1;
    while ((e = readdir(d)) != NULL && found < 0) {
        if (e->d_name[0] == '.')
            continue;
        char path[600], line[256];
        snprintf(path, sizeof path, "/sys/class/hidraw/%s/device/uevent",
                 e->d_name);
        FILE *f = fopen(path, "r");
        if (!f)
            continue;
        while (fgets(line, sizeof line, f)) {
            if (strncmp(line, "HID_NAME=", 9) == 0 &&
                strncmp(line + 9, name, namelen) == 0) {
                snprintf(hidraw, hl, "/dev/%s", e->d_name);
                found = 0;
            }
        }
        fclose(f);
        if (found == 0) {
            /* hid-input's evdev node: device/input/inputK/eventM */
            snprintf(path, sizeof path, "/sys/class/hidraw/%s/device/input",
                     e->d_name);
            DIR *in = opendir(path);
            event[0] = '\0';
            if (in) {
                struct dirent *i;
                while ((i = readdir(in)) != NULL) {
                    if (strncmp(i->d_name, "input", 5) != 0)
                        continue;
                    char sub[1200];
                    snprintf(sub, sizeof sub, "%s/%s", path, i->d_name);
                    if (find_event_child(sub, event, el) == 0)
                        break;
                }
                closedir(in);
            }
        }
    }
    closedir(d);
    return found;
}

static void check_uhid(void)
{
    const char *W = "uhid";
    int u = open("/dev/uhid", O_RDWR | O_CLOEXEC);
    if (u < 0) {
        if (errno == ENOENT)
            printf("skip uhid: /dev/uhid missing (module not loaded)\n");
        else
            fail(W, "open /dev/uhid: %s", strerror(errno));
        return;
    }
    struct uhid_event ev;
    memset(&ev, 0, sizeof ev);
    ev.type = UHID_CREATE2;
    snprintf((char *)ev.u.create2.name, sizeof ev.u.create2.name, "%s",
             UHID_NAME);
    memcpy(ev.u.create2.rd_data, mouse_rdesc, sizeof mouse_rdesc);
    ev.u.create2.rd_size = sizeof mouse_rdesc;
    ev.u.create2.bus = BUS_USB;
    ev.u.create2.vendor = 0x0627;
    ev.u.create2.product = 0x0001;
    if (write(u, &ev, sizeof ev) != (ssize_t)sizeof ev) {
        fail(W, "UHID_CREATE2: %s", strerror(errno));
        close(u);
        return;
    }
    char hidraw[320] = "", event[320] = "";
    int tries;
    for (tries = 0; tries < 150; tries++) {
        if (find_hid_nodes(UHID_NAME, hidraw, sizeof hidraw, event,
                           sizeof event) == 0 &&
            access(hidraw, R_OK) == 0 && event[0] && access(event, R_OK) == 0)
            break;
        sleep_ms(20);
    }
    if (!hidraw[0] || access(hidraw, R_OK) != 0) {
        fail(W, "no hidraw node for the uhid device (is hid_generic "
             "loaded?)");
        close(u);
        return;
    }
    ok("uhid device -> %s, hid-input -> %s", hidraw,
       event[0] ? event : "(none)");

    int h = open(hidraw, O_RDWR | O_NONBLOCK | O_CLOEXEC);
    int e = event[0] ? open(event, O_RDONLY | O_NONBLOCK | O_CLOEXEC) : -1;
    if (h < 0) {
        fail("hidraw open", "%s: %s", hidraw, strerror(errno));
        goto out;
    }
    int dsize = 0;
    struct hidraw_report_descriptor rd;
    memset(&rd, 0, sizeof rd);
    if (ioctl(h, HIDIOCGRDESCSIZE, &dsize) < 0 ||
        dsize != (int)sizeof mouse_rdesc)
        fail("hidraw HIDIOCGRDESCSIZE", "%d (%s)", dsize, strerror(errno));
    else {
        rd.size = (unsigned)dsize;
        if (ioctl(h, HIDIOCGRDESC, &rd) < 0 ||
            memcmp(rd.value, mouse_rdesc, sizeof mouse_rdesc) != 0)
            fail("hidraw HIDIOCGRDESC", "descriptor differs or %s",
                 strerror(errno));
        else
            ok("hidraw HIDIOCGRDESC returns the %d-byte descriptor", dsize);
    }
    struct hidraw_devinfo di;
    if (ioctl(h, HIDIOCGRAWINFO, &di) < 0 || di.bustype != BUS_USB ||
        (unsigned short)di.vendor != 0x0627)
        fail("hidraw HIDIOCGRAWINFO", "%s", strerror(errno));
    else
        ok("hidraw HIDIOCGRAWINFO bus 0x%x %04x:%04x", di.bustype,
           (unsigned short)di.vendor, (unsigned short)di.product);

    /* Button 1, X +5, Y -5, wheel +1. */
    const unsigned char report[4] = { 0x01, 0x05, 0xFB, 0x01 };
    memset(&ev, 0, sizeof ev);
    ev.type = UHID_INPUT2;
    ev.u.input2.size = sizeof report;
    memcpy(ev.u.input2.data, report, sizeof report);
    if (write(u, &ev, sizeof ev) != (ssize_t)sizeof ev) {
        fail("uhid UHID_INPUT2", "%s", strerror(errno));
        goto out;
    }
    unsigned char buf[64];
    ssize_t r = read_timeout(h, buf, sizeof buf, 2000);
    if (r != (ssize_t)sizeof report || memcmp(buf, report, sizeof report))
        fail("hidraw read", "got %zd bytes (%s)", r,
             r < 0 ? strerror(errno) : "wrong content");
    else
        ok("hidraw read back the report 01 05 fb 01");

    if (e >= 0) {
        int rel_x = 0, rel_y = 0, wheel = 0, btn = 0, syn = 0;
        struct input_event ie;
        while (!syn && read_timeout(e, &ie, sizeof ie, 2000) ==
                           (ssize_t)sizeof ie) {
            if (ie.type == EV_REL && ie.code == REL_X)
                rel_x = ie.value;
            else if (ie.type == EV_REL && ie.code == REL_Y)
                rel_y = ie.value;
            else if (ie.type == EV_REL && ie.code == REL_WHEEL)
                wheel = ie.value;
            else if (ie.type == EV_KEY && ie.code == BTN_LEFT)
                btn = ie.value;
            else if (ie.type == EV_SYN && ie.code == SYN_REPORT)
                syn = 1;
        }
        if (!syn || rel_x != 5 || rel_y != -5 || wheel != 1 || btn != 1)
            fail("hid-input evdev", "got x %d y %d wheel %d left %d syn %d",
                 rel_x, rel_y, wheel, btn, syn);
        else
            ok("hid-input evdev agrees: REL_X 5 REL_Y -5 REL_WHEEL 1 "
               "BTN_LEFT 1");
    } else {
        fail("hid-input evdev", "no event node for the uhid device");
    }

    memset(&ev, 0, sizeof ev);
    ev.type = UHID_DESTROY;
    if (write(u, &ev, sizeof ev) != (ssize_t)sizeof ev)
        fail("uhid UHID_DESTROY", "%s", strerror(errno));
    else {
        struct pollfd p = { .fd = h, .events = POLLIN };
        poll(&p, 1, 2000);
        r = read(h, buf, sizeof buf);
        if (r < 0 && (errno == EIO || errno == ENODEV))
            ok("hidraw read after UHID_DESTROY fails with %s",
               errno == EIO ? "EIO" : "ENODEV");
        else
            fail("hidraw unplug", "read gave %zd (%s)", r,
                 r < 0 ? strerror(errno) : "data");
    }
out:
    if (h >= 0)
        close(h);
    if (e >= 0)
        close(e);
    close(u);
}

/* ---------------------------------------------------------- USB gadget */

#define GADGET "/sys/kernel/config/usb_gadget/posture_smoke"

static int put(const char *path, const void *data, size_t len)
{
    int fd = open(path, O_WRONLY | O_CLOEXEC);
    if (fd < 0)
        return -1;
    ssize_t w = write(fd, data, len);
    int e = errno;
    close(fd);
    errno = e;
    return w == (ssize_t)len ? 0 : -1;
}

static int puts_to(const char *path, const char *text)
{
    return put(path, text, strlen(text));
}

/* The name of the first UDC (dummy_hcd's is "dummy_udc.0"), or -1. */
static int first_udc(char *out, size_t len)
{
    DIR *d = opendir("/sys/class/udc");
    if (!d)
        return -1;
    struct dirent *e;
    int r = -1;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] != '.') {
            snprintf(out, len, "%s", e->d_name);
            r = 0;
            break;
        }
    }
    closedir(d);
    return r;
}

static void check_usb_gadget(void)
{
    const char *W = "usb gadget";
    char udc[320];
    if (access("/sys/kernel/config/usb_gadget", F_OK) != 0 ||
        first_udc(udc, sizeof udc) != 0) {
        printf("skip usb gadget: no configfs usb_gadget or no UDC "
               "(modules dummy_hcd, libcomposite, usb_f_hid not loaded)\n");
        return;
    }
    static const char *dirs[] = {
        GADGET, GADGET "/strings/0x409", GADGET "/configs/c.1",
        GADGET "/functions/hid.usb0",
    };
    for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
        if (mkdir(dirs[i], 0755) < 0 && errno != EEXIST) {
            fail(W, "mkdir %s: %s", dirs[i], strerror(errno));
            return;
        }
    }
    if (puts_to(GADGET "/idVendor", "0x1d6b") ||
        puts_to(GADGET "/idProduct", "0x0104") ||
        puts_to(GADGET "/strings/0x409/manufacturer", "posture") ||
        puts_to(GADGET "/strings/0x409/product", "smoke gadget mouse") ||
        puts_to(GADGET "/functions/hid.usb0/protocol", "2") ||
        puts_to(GADGET "/functions/hid.usb0/subclass", "1") ||
        puts_to(GADGET "/functions/hid.usb0/report_length", "4") ||
        put(GADGET "/functions/hid.usb0/report_desc", mouse_rdesc,
            sizeof mouse_rdesc)) {
        fail(W, "configfs attribute: %s", strerror(errno));
        return;
    }
    if (symlink(GADGET "/functions/hid.usb0", GADGET "/configs/c.1/hid.usb0")
            < 0 && errno != EEXIST) {
        fail(W, "link function: %s", strerror(errno));
        return;
    }
    if (puts_to(GADGET "/UDC", udc)) {
        fail(W, "bind to %s: %s", udc, strerror(errno));
        return;
    }
    ok("usb gadget HID boot mouse bound to %s", udc);

    /* The host side enumerates it through usbcore, usbhid, hid-generic. */
    char hidraw[320] = "", event[320] = "";
    int tries;
    for (tries = 0; tries < 250; tries++) {
        if (find_hid_nodes("posture smoke gadget mouse", hidraw,
                           sizeof hidraw, event, sizeof event) == 0 &&
            access(hidraw, R_OK) == 0 && access("/dev/hidg0", W_OK) == 0)
            break;
        sleep_ms(20);
    }
    if (tries == 250) {
        fail(W, "the host side did not enumerate it (hidraw '%s')", hidraw);
        goto unbind;
    }
    int usbdevs = 0;
    DIR *d = opendir("/dev/bus/usb/001");
    if (d) {
        struct dirent *e;
        while ((e = readdir(d)) != NULL)
            usbdevs += e->d_name[0] != '.';
        closedir(d);
    }
    ok("usb host side: %s, %s, %d nodes in /dev/bus/usb/001", hidraw,
       event[0] ? event : "(no evdev)", usbdevs);

    int h = open(hidraw, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    int g = open("/dev/hidg0", O_WRONLY | O_CLOEXEC);
    if (h < 0 || g < 0) {
        fail(W, "open %s / /dev/hidg0: %s", hidraw, strerror(errno));
    } else {
        const unsigned char report[4] = { 0x02, 0xFE, 0x03, 0x00 };
        unsigned char buf[64];
        ssize_t r = -1;
        /* The host polls the interrupt endpoint once the hidraw node is
         * open; the first report may need a retry while that starts. */
        for (int i = 0; i < 5 && r != (ssize_t)sizeof report; i++) {
            if (write(g, report, sizeof report) != (ssize_t)sizeof report) {
                fail(W, "write /dev/hidg0: %s", strerror(errno));
                break;
            }
            r = read_timeout(h, buf, sizeof buf, 1000);
        }
        if (r != (ssize_t)sizeof report || memcmp(buf, report, sizeof report))
            fail("usb hidraw read", "got %zd bytes (%s)", r,
                 r < 0 ? strerror(errno) : "wrong content");
        else
            ok("usb gadget report 02 fe 03 00 read back through hidraw");
    }
    if (h >= 0)
        close(h);
    if (g >= 0)
        close(g);
unbind:
    if (puts_to(GADGET "/UDC", "\n"))
        fail(W, "unbind: %s", strerror(errno));
    else
        ok("usb gadget unbound");
}

int main(void)
{
    if (geteuid() != 0)
        printf("note: not root; expect permission failures\n");
    check_uinput();
    check_can();
    check_uhid();
    check_usb_gadget();
    printf("smoke: %d failure%s\n", failures, failures == 1 ? "" : "s");
    return failures > 100 ? 100 : failures;
}
