/* guest_drm.h - what the guest programs ask of the card and the VT about the screen
 * (static, as guest_check.h): the framebuffer a CRTC shows, its colours, tty1's mode */
#ifndef POSTURE_GUEST_DRM_H
#define POSTURE_GUEST_DRM_H

#include <fcntl.h>
#include <stdint.h>
#include <string.h>
#include <unistd.h>

#include <linux/kd.h>
#include <sys/ioctl.h>
#include <sys/mman.h>

#include <xf86drm.h>
#include <xf86drmMode.h>

/* the framebuffer on the first CRTC that shows one, and that CRTC's id; 0: none */
static inline uint32_t
crtc_fb(int fd, uint32_t *crtc)
{
	uint32_t fb = 0;
	drmModeRes *res = drmModeGetResources(fd);
	for (int i = 0; res && i < res->count_crtcs && !fb; i++) {
		drmModeCrtc *c = drmModeGetCrtc(fd, res->crtcs[i]);
		if (c && c->buffer_id) {
			fb = c->buffer_id;
			*crtc = c->crtc_id;
		}
		drmModeFreeCrtc(c);
	}
	drmModeFreeResources(res);
	return fb;
}

/* the pixels the screen shows (root may map another's buffer): distinct colours among a sample */
static inline int
screen_colours(int fd, uint32_t fb_id, long *lit)
{
	drmModeFBPtr fb = drmModeGetFB(fd, fb_id);
	struct drm_mode_map_dumb map = { .handle = fb ? fb->handle : 0 };
	if (!fb || drmIoctl(fd, DRM_IOCTL_MODE_MAP_DUMB, &map) < 0) {
		drmModeFreeFB(fb);
		return -1;
	}
	size_t size = (size_t)fb->pitch * fb->height;
	uint8_t *p = mmap(NULL, size, PROT_READ, MAP_SHARED, fd, (off_t)map.offset);
	int distinct = 0;
	uint32_t seen[64];
	*lit = 0;
	for (uint32_t y = 0; p != MAP_FAILED && y < fb->height; y += 7)
		for (uint32_t x = 0; x < fb->width; x += 7) {
			uint32_t v;
			memcpy(&v, p + (size_t)y * fb->pitch + (size_t)x * 4, 4);
			v &= 0xffffff;
			*lit += v != 0;
			int k = 0;
			while (k < distinct && seen[k] != v)
				k++;
			if (k == distinct && distinct < 64)
				seen[distinct++] = v;
		}
	if (p != MAP_FAILED)
		munmap(p, size);
	drmModeFreeFB(fb);
	return distinct;
}

/* a VT's KDGETMODE: KD_TEXT or KD_GRAPHICS; -1 when it cannot be asked */
static inline int
kd_mode(const char *tty)
{
	int fd = open(tty, O_RDWR | O_NOCTTY | O_CLOEXEC), mode = -1;
	if (fd >= 0) {
		ioctl(fd, KDGETMODE, &mode);
		close(fd);
	}
	return mode;
}

#endif
