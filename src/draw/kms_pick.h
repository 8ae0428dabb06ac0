/*
 * kms_pick.h - what the DRM/KMS sink decides, apart from the device: which
 * connector, mode and CRTC show the kiosk, which of its two buffers a frame
 * goes into while a flip may be in flight, and each frame's time from its
 * render to its flip request. Plain structs, filled from
 * libdrm's by sink_kms.c and by the tests directly.
 */
#ifndef POSTURE_DRAW_KMS_PICK_H
#define POSTURE_DRAW_KMS_PICK_H

#include <stddef.h>
#include <stdint.h>

#define KMS_MAX 32         /* connectors, encoders, CRTCs considered */
#define KMS_MAX_MODES 64   /* modes of a connector considered */
#define KMS_NAME_MAX 32

struct kms_mode {
	uint16_t w, h;
	uint32_t refresh;  /* Hz (vrefresh) */
	int preferred;     /* DRM_MODE_TYPE_PREFERRED */
};

struct kms_connector {
	uint32_t id;
	char name[KMS_NAME_MAX]; /* "HDMI-A-1", "Virtual-1": type and index as the kernel names them */
	int connected;
	uint32_t encoder;        /* the encoder driving it now, 0: none */
	uint32_t encoders[KMS_MAX];
	int nencoders;
	struct kms_mode modes[KMS_MAX_MODES];
	int nmodes;
};

struct kms_encoder {
	uint32_t id;
	uint32_t crtc;           /* the CRTC it drives now, 0: none */
	uint32_t possible_crtcs; /* bit i: the resources' i-th CRTC */
};

struct kms_resources {
	uint32_t crtcs[KMS_MAX];
	int ncrtcs;
	struct kms_encoder encoders[KMS_MAX];
	int nencoders;
	struct kms_connector connectors[KMS_MAX];
	int nconnectors;
};

/* what the user asked for: a connector by name, a mode WxH[@HZ]; empty or 0: any */
struct kms_want {
	char connector[KMS_NAME_MAX];
	int w, h, hz;
};

struct kms_choice {
	int connector;  /* indexes into the resources */
	int mode;
	uint32_t crtc;  /* the CRTC's id */
};

/*
 * "WxH" or "WxH@HZ" (and "" for none) into w, h, hz; 0, or -1 when malformed.
 */
int kms_parse_mode(const char *s, struct kms_want *dest);

/*
 * The connector (the wanted one, else the first connected one with modes),
 * its mode (the wanted size and rate, else the preferred one, else the
 * first: the kernel lists the best first), and a CRTC for it (the one its
 * encoder drives now, else the first its encoders can drive). Returns 0, or
 * -1 with why in plain words (no connector connected, no such mode...).
 */
int kms_choose(const struct kms_resources *r, const struct kms_want *want, struct kms_choice *dest,
	       char *why, size_t whylen);

/*
 * The two scanout buffers' bookkeeping: one shown (front), one drawn into
 * (back); at most one flip in flight, and while it is, the next frame waits
 * (the newest replaces an older waiting one: counted as dropped).
 */
struct kms_flips {
	int front;          /* the buffer shown */
	int in_flight;      /* a flip to the back buffer was asked for */
	uint64_t flips;     /* flips completed */
	uint64_t dropped;   /* frames replaced before they were shown */
};

/* the buffer a frame may be drawn into now, or -1 while a flip is in flight */
int kms_flips_back(const struct kms_flips *f);
/* a flip to the back buffer was asked for */
void kms_flips_asked(struct kms_flips *f);
/* ... and it happened: the back buffer is shown */
void kms_flips_done(struct kms_flips *f);

/*
 * A frame's way from the finished render to its flip request, in its
 * parts (us, CLOCK_MONOTONIC): the newest KMS_TIMES frames kept in a ring,
 * so the frame path never allocates; figures over them on demand.
 */
#define KMS_TIMES 256

struct kms_frame_time {
	uint32_t total; /* render handed over -> the flip request returned */
	uint32_t queue; /* handed over -> the sink's write began (the writer's thread took it) */
	uint32_t wait;  /* the previous flip's event waited for */
	uint32_t copy;  /* the frame converted into the back buffer */
	uint32_t ioctl; /* the flip request itself (drmModePageFlip) */
};

struct kms_times {
	struct kms_frame_time ring[KMS_TIMES];
	uint64_t n; /* frames timed: flip requests made */
};

/* each part's median, p99 and max over the kept frames, and the frames timed in all */
struct kms_times_summary {
	uint64_t n;
	int kept; /* frames the figures are over: the newest, KMS_TIMES at most */
	struct kms_frame_time median, p99, max;
};

/*
 * One frame timed from its stamps: handed (0: unknown, then the write's
 * beginning), began (the write), waited (the last flip's event in),
 * copied, asked (the flip request returned). A stamp earlier than the one
 * before it counts as that one.
 */
void kms_times_add(struct kms_times *t, uint64_t handed, uint64_t began, uint64_t waited,
		   uint64_t copied, uint64_t asked);
/* the figures so far; all 0 before the first frame */
void kms_times_sum(const struct kms_times *t, struct kms_times_summary *dest);

#endif
