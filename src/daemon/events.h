/*
 * events.h - the events clients subscribe to (docs/protocol.md, Events):
 * postures that changed, the message line, the solver's telemetry of a
 * figure's frame, stability and its alerts, and the pictures' frames. Each
 * is one JSON line written into a buffer made once, so a frame's events
 * allocate nothing, and queued to every client subscribed to its kind.
 */
#ifndef POSTURE_EVENTS_H
#define POSTURE_EVENTS_H

#include <stdint.h>

#include "assess/assess.h"
#include "assess/statics.h"
#include "daemon/daemon.h"
#include "daemon/jbuf.h"
#include "daemon/server.h"
#include "devices/event.h"
#include "pose/ik.h"

#define EVENTS_BUF (1u << 20)       /* the largest event: a frame's PNG in base64 */
#define EVENTS_LIMITS_REPORTED 256 /* dofs listed as resting on a limit */

/* what an assessment event told of a figure: compared to know when its scores change */
struct events_assess_told {
	uint32_t gen; /* 0: nothing told */
	struct {
		int score, action_level, side, worst, nparts;
		int part[ASSESS_MAX_PARTS];
		char code[8];
	} m[ASSESS_NMETHODS];
};

/*
 * What a loads event told of a figure, compared with the analysis now to
 * know when to tell again (the thresholds are events.c's, LOADS_TELL_*).
 */
struct events_loads_told {
	uint32_t gen; /* 0: nothing told */
	int low_back, zone;
	double compression; /* N */
	int weakest_joint, weakest_axis; /* -1: none */
	double capable;     /* percent; NAN: none */
	int nsupport, tips;
	int support_site[STATICS_MAX_SUPPORT];
	double support_force[STATICS_MAX_SUPPORT][3];
	uint64_t loads_id; /* which loads act (their origins), not their numbers */
};

struct events {
	struct server *srv;     /* the clients and their subscriptions */
	const struct daemon *d; /* what the events tell of */
	struct jbuf buf;        /* the event being written */
	uint64_t told_hash[ENV_MAX_FIGURES]; /* postures as the last posture events told them */
	uint32_t told_gen[ENV_MAX_FIGURES];
	int limit_dofs[EVENTS_LIMITS_REPORTED];
	char told_kiosk[256]; /* the kiosk's state as the last kiosk event told it */
	struct events_assess_told told_assess[ENV_MAX_FIGURES];
	struct events_loads_told told_loads[ENV_MAX_FIGURES];
};

/* 0, or -1 when out of memory (events_free cleans up either way) */
int events_init(struct events *E, struct server *srv, const struct daemon *d);
void events_free(struct events *E);

/* 1 when some client that is not closing subscribes to kind (enum sub_kind) */
int events_wanted(const struct events *E, unsigned kind);
/* starts an event in E->buf: {"event":kind,"frame":N[,"figure":figure] */
struct jbuf *events_begin(struct events *E, const char *kind, const char *figure);
/*
 * Ends the line in E->buf and queues it to every subscriber of kind; a
 * client whose queue is full is dropped, an event that overflowed the
 * buffer is not sent.
 */
void events_send(struct events *E, unsigned kind);

/* a posture event for every figure that changed since the last one, whoever moved it */
void events_posture_changes(struct events *E);
/*
 * An assessment event for every human whose scores changed since the last
 * one told them (any method's grand score, action level, side, worst part
 * or a part's score; OWAS's code), computed only while someone subscribes.
 */
void events_assessment(struct events *E, struct daemon *d);
/* every human's assessment told again at the next events_assessment (a client subscribed) */
void events_assessment_retell(struct events *E);
/*
 * A loads event for every figure whose analysis changed since the last one
 * told it by more than the thresholds (events.c): its low back's
 * compression by LOADS_TELL_COMPRESSION_N or a NIOSH zone crossed, the
 * weakest joint or axis, its percent capable by LOADS_TELL_CAPABLE_PCT, a
 * support added or gone or its force by LOADS_TELL_SUPPORT_N, tipping, a
 * load added or gone. Computed only while someone subscribes.
 */
void events_loads(struct events *E, struct daemon *d);
/* every figure's loads told again at the next events_loads (a client subscribed) */
void events_loads_retell(struct events *E);
/* the message line under the pictures */
void events_message(struct events *E);
/*
 * The kiosk's state, when it changed since the last kiosk event: the mode
 * (none, figure, drag, joint, site, hand, ...), its figure and view, and
 * whether a step (a drag) is under way.
 */
void events_kiosk(struct events *E);
/* why a goal is (not) reached: the solver's view of one figure's frame */
void events_telemetry(struct events *E, int fig, const struct ik_result *r, uint64_t budget,
		      double us);
/*
 * Stability as data: every frame the support polygon, the balance point
 * the behaviours hold, the centre of mass on the floor, its parameters and
 * the margin; and an alert when the margin crosses the figure's threshold.
 */
void events_stability(struct events *E, int fig);
/* one input event as the loop takes it from the queue (subscribe input) */
/*
 * An input event to the clients that subscribed; px, py: a device's motion
 * in screen pixels (devices/motion_scale.h), beside its raw counts.
 */
void events_input(struct events *E, const struct input_event_rec *e, long px, long py);

#endif
