/* vt.c - the kiosk's VT in graphics mode, its keyboard off, its switches ours (vt.h) */
#include "daemon/vt.h"

#include <errno.h>
#include <fcntl.h>
#include <linux/kd.h>
#include <linux/vt.h>
#include <stdio.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

int
vt_take(struct vt *v, const char *path, char *err, size_t errlen)
{
	memset(v, 0, sizeof *v);
	v->fd = -1;
	int fd = path && path[0] ? open(path, O_RDWR | O_NOCTTY | O_CLOEXEC) : dup(STDIN_FILENO);
	snprintf(v->path, sizeof v->path, "%s", path && path[0] ? path : "standard input");
	if (fd < 0) {
		snprintf(err, errlen, "%s: %s", v->path, strerror(errno));
		return -1;
	}
	struct vt_mode mode;
	if (ioctl(fd, KDGETMODE, &v->kd_mode) < 0 || ioctl(fd, KDGKBMODE, &v->kb_mode) < 0 ||
	    ioctl(fd, VT_GETMODE, &mode) < 0) {
		snprintf(err, errlen, "%s: not a virtual terminal (%s)", v->path, strerror(errno));
		close(fd);
		return -1;
	}
	struct vt_mode process = { .mode = VT_PROCESS, .relsig = VT_SIG_RELEASE,
				   .acqsig = VT_SIG_ACQUIRE };
	if (ioctl(fd, KDSETMODE, KD_GRAPHICS) < 0 || ioctl(fd, KDSKBMODE, K_OFF) < 0 ||
	    ioctl(fd, VT_SETMODE, &process) < 0) {
		snprintf(err, errlen, "%s: %s", v->path, strerror(errno));
		ioctl(fd, KDSETMODE, v->kd_mode);
		ioctl(fd, KDSKBMODE, v->kb_mode);
		close(fd);
		return -1;
	}
	v->fd = fd;
	v->active = 1;
	return 0;
}

void
vt_release(struct vt *v)
{
	if (v->fd < 0)
		return;
	v->active = 0;
	ioctl(v->fd, VT_RELDISP, 1);
}

void
vt_acquire(struct vt *v)
{
	if (v->fd < 0)
		return;
	ioctl(v->fd, VT_RELDISP, VT_ACKACQ);
	v->active = 1;
}

void
vt_give_back(struct vt *v)
{
	if (v->fd < 0)
		return;
	struct vt_mode automatic = { .mode = VT_AUTO };
	ioctl(v->fd, VT_SETMODE, &automatic);
	ioctl(v->fd, KDSKBMODE, v->kb_mode);
	ioctl(v->fd, KDSETMODE, v->kd_mode);
	close(v->fd);
	v->fd = -1;
}

int
vt_restore_console(const char *path, char *err, size_t errlen)
{
	int fd = open(path, O_RDWR | O_NOCTTY | O_CLOEXEC);
	if (fd < 0) {
		snprintf(err, errlen, "%s: %s", path, strerror(errno));
		return -1;
	}
	struct vt_mode automatic = { .mode = VT_AUTO };
	int rc = ioctl(fd, KDSETMODE, KD_TEXT) < 0 || ioctl(fd, KDSKBMODE, K_UNICODE) < 0 ||
			 ioctl(fd, VT_SETMODE, &automatic) < 0
		 ? -1 : 0;
	if (rc < 0)
		snprintf(err, errlen, "%s: %s", path, strerror(errno));
	close(fd);
	return rc;
}
