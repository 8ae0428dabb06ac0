/* guest_drm.h - what the guest programs ask of the card about its screen (static, as guest_check.h) */
#ifndef POSTURE_GUEST_DRM_H
#define POSTURE_GUEST_DRM_H

#include <stdint.h>

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

#endif
