/*
 * sink_kms.c - frames onto a screen through DRM/KMS (libdrm), see sink.h.
 *
 * The device part is thin: open the card, read its connectors, encoders and
 * CRTCs into plain structs for kms_choose (kms_pick.h), make two dumb
 * buffers (XRGB8888, rows `pitch` bytes apart), set the mode on the first
 * and flip between them, one flip in flight (kms_flips). The writes run on
 * the frame writer's thread, never the loop's: a frame waits there for the
 * last flip's event (which QEMU's drivers send at once, a real screen at its
 * next vertical blank), so the daemon's frame clock stays its own. On close
 * the CRTC as it was is put back.
 */
#include "draw/sink.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include <drm_fourcc.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include "draw/kms_pick.h"
#include "draw/pixfmt.h"
#include "draw/scanout.h"

#define SINK_KMS_FLIP_WAIT_MS 100 /* a flip's event this late: the frame is dropped */

struct kms_buffer {
	uint32_t handle, fb, pitch;
	uint64_t size;
	uint8_t *map;
};

struct sink_kms {
	struct sink base;
	int fd;
	char card[64];
	uint32_t connector, crtc;
	drmModeModeInfo mode;
	int w, h;
	struct kms_buffer buf[2];
	struct kms_flips flips;
	drmModeCrtc *saved;   /* the CRTC as it was, put back on close */
	struct pixfmt pf;     /* XRGB8888 */
	uint8_t black[4];     /* an opaque black pixel in it */
	char conn_name[KMS_NAME_MAX];
	struct kms_want want; /* what was asked for: chosen again when the connectors change */
	/* render to flip request, per frame; the writer's thread adds, another may read */
	struct kms_times times;
	pthread_mutex_t times_lock;
};

static const char *const connector_type[] = {
	"Unknown", "VGA", "DVI-I", "DVI-D", "DVI-A", "Composite", "SVIDEO", "LVDS", "Component",
	"DIN", "DP", "HDMI-A", "HDMI-B", "TV", "eDP", "Virtual", "DSI", "DPI", "Writeback", "SPI", "USB",
};

/* the card's connectors, encoders and CRTCs as plain structs, with libdrm's modes kept aside */
static int
read_resources(int fd, struct kms_resources *r, drmModeModeInfo (*modes)[KMS_MAX_MODES])
{
	drmModeRes *res = drmModeGetResources(fd);
	if (!res)
		return -1;
	memset(r, 0, sizeof *r);
	for (int i = 0; i < res->count_crtcs && r->ncrtcs < KMS_MAX; i++)
		r->crtcs[r->ncrtcs++] = res->crtcs[i];
	for (int i = 0; i < res->count_encoders && r->nencoders < KMS_MAX; i++) {
		drmModeEncoder *e = drmModeGetEncoder(fd, res->encoders[i]);
		if (!e)
			continue;
		r->encoders[r->nencoders++] = (struct kms_encoder){ e->encoder_id, e->crtc_id,
								    e->possible_crtcs };
		drmModeFreeEncoder(e);
	}
	for (int i = 0; i < res->count_connectors && r->nconnectors < KMS_MAX; i++) {
		drmModeConnector *c = drmModeGetConnector(fd, res->connectors[i]);
		if (!c)
			continue;
		struct kms_connector *k = &r->connectors[r->nconnectors];
		k->id = c->connector_id;
		k->connected = c->connection == DRM_MODE_CONNECTED;
		k->encoder = c->encoder_id;
		const char *type = c->connector_type < sizeof connector_type / sizeof *connector_type
					   ? connector_type[c->connector_type] : "Unknown";
		snprintf(k->name, sizeof k->name, "%s-%u", type, c->connector_type_id);
		for (int e = 0; e < c->count_encoders && k->nencoders < KMS_MAX; e++)
			k->encoders[k->nencoders++] = c->encoders[e];
		for (int m = 0; m < c->count_modes && k->nmodes < KMS_MAX_MODES; m++) {
			modes[r->nconnectors][k->nmodes] = c->modes[m];
			k->modes[k->nmodes++] = (struct kms_mode){
				c->modes[m].hdisplay, c->modes[m].vdisplay, c->modes[m].vrefresh,
				!!(c->modes[m].type & DRM_MODE_TYPE_PREFERRED) };
		}
		r->nconnectors++;
		drmModeFreeConnector(c);
	}
	drmModeFreeResources(res);
	return 0;
}

static int
make_buffer(int fd, int w, int h, struct kms_buffer *b)
{
	struct drm_mode_create_dumb create = { .width = (uint32_t)w, .height = (uint32_t)h, .bpp = 32 };
	if (drmIoctl(fd, DRM_IOCTL_MODE_CREATE_DUMB, &create) < 0)
		return -1;
	b->handle = create.handle;
	b->pitch = create.pitch;
	b->size = create.size;
	uint32_t handles[4] = { b->handle }, pitches[4] = { b->pitch }, offsets[4] = { 0 };
	if (drmModeAddFB2(fd, (uint32_t)w, (uint32_t)h, DRM_FORMAT_XRGB8888, handles, pitches, offsets,
			  &b->fb, 0) < 0)
		return -1;
	struct drm_mode_map_dumb map = { .handle = b->handle };
	if (drmIoctl(fd, DRM_IOCTL_MODE_MAP_DUMB, &map) < 0)
		return -1;
	void *p = mmap(NULL, b->size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, (off_t)map.offset);
	if (p == MAP_FAILED)
		return -1;
	b->map = p;
	memset(b->map, 0, b->size); /* black */
	return 0;
}

static void
free_buffer(int fd, struct kms_buffer *b)
{
	if (b->map)
		munmap(b->map, b->size);
	if (b->fb)
		drmModeRmFB(fd, b->fb);
	if (b->handle) {
		struct drm_mode_destroy_dumb d = { .handle = b->handle };
		drmIoctl(fd, DRM_IOCTL_MODE_DESTROY_DUMB, &d);
	}
	memset(b, 0, sizeof *b);
}

static void
flip_done(int fd, unsigned seq, unsigned sec, unsigned usec, void *data)
{
	(void)fd, (void)seq, (void)sec, (void)usec;
	kms_flips_done(&((struct sink_kms *)data)->flips);
}

/* the flip in flight waited for, at most ms; 0 when none is in flight any more */
static int
wait_flip(struct sink_kms *k, int ms)
{
	drmEventContext ev = { .version = 2, .page_flip_handler = flip_done };
	while (k->flips.in_flight) {
		struct pollfd p = { .fd = k->fd, .events = POLLIN };
		int got = poll(&p, 1, ms);
		if (got < 0 && errno == EINTR)
			continue;
		if (got <= 0)
			return -1;
		if (drmHandleEvent(k->fd, &ev) != 0)
			return -1;
	}
	return 0;
}

static int
sink_kms_write(struct sink *s, const struct frame *f, char *err, size_t errlen)
{
	struct sink_kms *k = (struct sink_kms *)s;
	uint64_t began = frame_now_us();
	if (k->flips.in_flight && wait_flip(k, SINK_KMS_FLIP_WAIT_MS) < 0) {
		k->flips.dropped++; /* the screen has not taken the last one yet: this one is skipped */
		return 0;
	}
	uint64_t waited = frame_now_us();
	int back = kms_flips_back(&k->flips);
	scanout_draw(&k->pf, k->black, f, k->buf[back].map, k->buf[back].pitch, k->w, k->h);
	uint64_t copied = frame_now_us();
	if (drmModePageFlip(k->fd, k->crtc, k->buf[back].fb, DRM_MODE_PAGE_FLIP_EVENT, k) < 0) {
		snprintf(err, errlen, "%s: page flip: %s", k->card, strerror(errno));
		return -1;
	}
	uint64_t asked = frame_now_us();
	kms_flips_asked(&k->flips);
	pthread_mutex_lock(&k->times_lock);
	kms_times_add(&k->times, f->done_us, began, waited, copied, asked);
	pthread_mutex_unlock(&k->times_lock);
	return 0;
}

static void
sink_kms_close(struct sink *s)
{
	struct sink_kms *k = (struct sink_kms *)s;
	wait_flip(k, SINK_KMS_FLIP_WAIT_MS);
	if (k->saved) { /* the screen as it was (the console's) */
		drmModeSetCrtc(k->fd, k->saved->crtc_id, k->saved->buffer_id, k->saved->x, k->saved->y,
			       &k->connector, 1, k->saved->mode_valid ? &k->saved->mode : NULL);
		drmModeFreeCrtc(k->saved);
	}
	for (int i = 0; i < 2; i++)
		free_buffer(k->fd, &k->buf[i]);
	if (k->fd >= 0)
		close(k->fd);
	pthread_mutex_destroy(&k->times_lock);
	free(k);
}

static const struct sink_ops sink_kms_ops = { "kms", sink_kms_write, sink_kms_close };

/*
 * The connector, mode and CRTC chosen from what the card has now; when
 * they are not what shows already, the buffers made for the mode's size
 * (again when it changed) and the mode set on the first. 0 when nothing
 * changed, 1 when the mode was set, -1 with err.
 */
static int
configure(struct sink_kms *k, char *err, size_t errlen)
{
	static struct kms_resources r; /* large: not on the writer's or loop's stack */
	static drmModeModeInfo modes[KMS_MAX][KMS_MAX_MODES];
	struct kms_choice ch;
	char why[200];
	const char *card = k->card;
	if (read_resources(k->fd, &r, modes) < 0) {
		snprintf(err, errlen, "%s: no KMS resources: %s", card, strerror(errno));
		return -1;
	}
	if (kms_choose(&r, &k->want, &ch, why, sizeof why) < 0) {
		snprintf(err, errlen, "%s: %s", card, why);
		return -1;
	}
	int same = k->connector == r.connectors[ch.connector].id && k->crtc == ch.crtc &&
		   !memcmp(&k->mode, &modes[ch.connector][ch.mode], sizeof k->mode);
	if (same && k->buf[0].map)
		return 0; /* what shows now is still what to show */
	k->connector = r.connectors[ch.connector].id;
	k->crtc = ch.crtc;
	k->mode = modes[ch.connector][ch.mode];
	if (k->w != k->mode.hdisplay || k->h != k->mode.vdisplay) /* buffers of the new size */
		for (int i = 0; i < 2; i++)
			free_buffer(k->fd, &k->buf[i]);
	k->w = k->mode.hdisplay;
	k->h = k->mode.vdisplay;
	snprintf(k->conn_name, sizeof k->conn_name, "%s", r.connectors[ch.connector].name);
	if (!k->saved)
		k->saved = drmModeGetCrtc(k->fd, k->crtc);
	for (int i = 0; i < 2; i++)
		if (!k->buf[i].map && make_buffer(k->fd, k->w, k->h, &k->buf[i]) < 0) {
			snprintf(err, errlen, "%s: dumb buffer %dx%d: %s", card, k->w, k->h,
				 strerror(errno));
			return -1;
		}
	if (drmModeSetCrtc(k->fd, k->crtc, k->buf[0].fb, 0, 0, &k->connector, 1, &k->mode) < 0) {
		snprintf(err, errlen, "%s: setting %dx%d on %s: %s", card, k->w, k->h, k->conn_name,
			 strerror(errno));
		return -1;
	}
	k->flips.front = 0;
	k->flips.in_flight = 0;
	return 1;
}

/* card: its connector, mode and CRTC chosen, two buffers, the mode set; NULL with err */
static struct sink *
open_card(const char *card, const struct kms_want *want, char *err, size_t errlen)
{
	struct sink_kms *k = calloc(1, sizeof *k);
	char why[200];
	uint64_t dumb = 0;
	if (!k) {
		snprintf(err, errlen, "out of memory");
		return NULL;
	}
	k->base.ops = &sink_kms_ops;
	pthread_mutex_init(&k->times_lock, NULL);
	snprintf(k->card, sizeof k->card, "%s", card);
	k->pf = (struct pixfmt){ .bpp = 32, .red = { 16, 8, 0 }, .green = { 8, 8, 0 }, .blue = { 0, 8, 0 } };
	if ((k->fd = open(card, O_RDWR | O_CLOEXEC)) < 0) {
		snprintf(err, errlen, "%s: %s", card, strerror(errno));
		pthread_mutex_destroy(&k->times_lock);
		free(k);
		return NULL;
	}
	static const uint8_t opaque_black[4] = { 0, 0, 0, 255 };
	if (pixfmt_init(&k->pf, why, sizeof why) == 0)
		pixfmt_convert_row(&k->pf, opaque_black, 1, k->black);
	if (k->pf.bytes != 4 || drmGetCap(k->fd, DRM_CAP_DUMB_BUFFER, &dumb) < 0 ||
	    !dumb) {
		snprintf(err, errlen, "%s: no dumb buffers (not a KMS device?)", card);
		goto fail;
	}
	k->want = *want;
	if (configure(k, err, errlen) < 0)
		goto fail;
	return &k->base;
fail:
	if (k->saved)
		drmModeFreeCrtc(k->saved);
	k->saved = NULL;
	for (int i = 0; i < 2; i++)
		free_buffer(k->fd, &k->buf[i]);
	close(k->fd);
	pthread_mutex_destroy(&k->times_lock);
	free(k);
	return NULL;
}

struct sink *
sink_kms_open(const char *card, const char *connector, const char *mode, char *err, size_t errlen)
{
	struct kms_want want = { .w = 0 };
	snprintf(want.connector, sizeof want.connector, "%s", connector ? connector : "");
	if (kms_parse_mode(mode, &want) < 0) {
		snprintf(err, errlen, "mode '%s' is not WxH or WxH@HZ", mode);
		return NULL;
	}
	if (card)
		return open_card(card, &want, err, errlen);
	/* the first card that can show something */
	char path[32], first[300] = "";
	for (int i = 0; i < 8; i++) {
		snprintf(path, sizeof path, "/dev/dri/card%d", i);
		struct sink *s = open_card(path, &want, err, errlen);
		if (s)
			return s;
		if (!first[0])
			snprintf(first, sizeof first, "%s", err);
	}
	snprintf(err, errlen, "%s", first[0] ? first : "no /dev/dri/card*");
	return NULL;
}

void
sink_kms_info(const struct sink *s, int *w, int *h, char *desc, size_t desclen)
{
	const struct sink_kms *k = (const struct sink_kms *)s;
	*w = k->w;
	*h = k->h;
	snprintf(desc, desclen, "%s %s %dx%d@%u", k->card, k->conn_name, k->w, k->h, k->mode.vrefresh);
}

const uint8_t *
sink_kms_front(const struct sink *s, uint32_t *pitch, uint64_t *flips, uint64_t *dropped)
{
	const struct sink_kms *k = (const struct sink_kms *)s;
	*pitch = k->buf[k->flips.front].pitch;
	*flips = k->flips.flips;
	*dropped = k->flips.dropped;
	return k->buf[k->flips.front].map;
}

void
sink_kms_times(struct sink *s, struct kms_times_summary *dest)
{
	struct sink_kms *k = (struct sink_kms *)s;
	pthread_mutex_lock(&k->times_lock); /* the writer waits at most one summary's sorting */
	kms_times_sum(&k->times, dest);
	pthread_mutex_unlock(&k->times_lock);
}

int
sink_kms_settle(struct sink *s)
{
	return wait_flip((struct sink_kms *)s, SINK_KMS_FLIP_WAIT_MS);
}

int
sink_kms_master(struct sink *s, int on)
{
	struct sink_kms *k = (struct sink_kms *)s;
	if (on) {
		if (drmSetMaster(k->fd) < 0)
			return -1;
		/* the mode again: whoever held the screen meanwhile set their own */
		return drmModeSetCrtc(k->fd, k->crtc, k->buf[k->flips.front].fb, 0, 0, &k->connector, 1,
				      &k->mode);
	}
	wait_flip(k, SINK_KMS_FLIP_WAIT_MS);
	return drmDropMaster(k->fd);
}

int
sink_kms_reprobe(struct sink *s, char *err, size_t errlen)
{
	struct sink_kms *k = (struct sink_kms *)s;
	wait_flip(k, SINK_KMS_FLIP_WAIT_MS);
	return configure(k, err, errlen);
}
