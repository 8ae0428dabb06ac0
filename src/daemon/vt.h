/*
 * vt.h - the virtual terminal the kiosk's screen is on, kept off the
 * screen: switched to graphics mode (the console draws nothing over the
 * picture), its keyboard off (keys typed at the kiosk do not reach a
 * login prompt behind it), and VT switches handled by the daemon
 * (VT_PROCESS: the kernel asks with a signal before it switches away, and
 * says with another when it is back). Everything is put back as it was on
 * the way out; after a crash, `postured --vt-restore TTY` (the unit's
 * ExecStopPost) gives a usable console back.
 */
#ifndef POSTURE_DAEMON_VT_H
#define POSTURE_DAEMON_VT_H

#include <signal.h>
#include <stddef.h>

#define VT_SIG_RELEASE SIGUSR1 /* the kernel wants to switch away */
#define VT_SIG_ACQUIRE SIGUSR2 /* ... and has switched back */

struct vt {
	int fd;          /* -1: no VT held */
	char path[64];
	int kd_mode;     /* KDGETMODE before */
	int kb_mode;     /* KDGKBMODE before */
	int active;      /* ours is the VT shown: draw */
};

/*
 * Takes the VT at path (a /dev/ttyN; "" or NULL: the one standard input is,
 * if it is one): graphics mode, keyboard off, VT switches by signal
 * (VT_SIG_RELEASE, VT_SIG_ACQUIRE, which the caller blocks and reads).
 * Returns 0, or -1 with why in err (not a VT, no permission), nothing
 * changed.
 */
int vt_take(struct vt *v, const char *path, char *err, size_t errlen);

/* the kernel asked to switch away: agreed (the caller has stopped drawing first) */
void vt_release(struct vt *v);
/* ... and has switched back: acknowledged (the caller draws again) */
void vt_acquire(struct vt *v);

/* text mode, the keyboard and automatic switching as they were; the VT let go */
void vt_give_back(struct vt *v);

/*
 * A console made usable again without its saved state (after a crash):
 * text mode, the keyboard in Unicode mode, automatic VT switching. 0, or
 * -1 with why in err.
 */
int vt_restore_console(const char *path, char *err, size_t errlen);

#endif
