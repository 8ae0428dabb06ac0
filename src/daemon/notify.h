/* notify.h - systemd's readiness and watchdog protocol, without libsystemd */
#ifndef POSTURE_NOTIFY_H
#define POSTURE_NOTIFY_H

#include <stdint.h>

/* sends a state string ("READY=1", "WATCHDOG=1", ...) to $NOTIFY_SOCKET; 0 when unset */
int notify_send(const char *state);

/* the watchdog interval in microseconds ($WATCHDOG_USEC for this pid), 0 when off */
uint64_t notify_watchdog_usec(void);

#endif
