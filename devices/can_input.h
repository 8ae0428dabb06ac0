/*
 * can_input.h - CAN frames through a panel map (can_map.h) into events.
 *
 * A frame is the kernel's struct can_frame, 16 bytes as read() gives it
 * (can_id in host order with its EFF/RTR/ERR flags, len, pad, res,
 * len8_dlc, data[8]). Each line of the map whose id matches decodes on its
 * own, as cantools decodes a DBC signal: the raw field (signed by two's
 * complement of its width) times factor plus offset, then the line's clamp.
 * A line with mux= decodes only when its mux line decoded with one of its
 * values. A frame shorter than its message yields the fields it holds
 * whole; the others are counted missing (cantools' allow_truncated).
 *
 * Events: an axis or mux line gives INPUT_VALUATOR (code = the line's index,
 * x = the value) when its value changes, the first time, and after it was
 * stale; a button line gives INPUT_BUTTON (value 1/0) when it changes.
 * One INPUT_FRAME follows each frame (and each tick) that gave events.
 * Nothing allocates after can_input_init.
 */
#ifndef POSTURE_DEVICES_CAN_INPUT_H
#define POSTURE_DEVICES_CAN_INPUT_H

#include <stddef.h>
#include <stdint.h>

#include "devices/can_map.h"
#include "devices/devlog.h"
#include "devices/queue.h"

#define CAN_INPUT_FRAME_SIZE 16 /* sizeof(struct can_frame), CAN_MTU */

struct can_input {
	const struct can_map *map;
	uint16_t device;
	struct devlog log;
	/* per map line */
	double value[CAN_MAP_MAX_LINES];
	uint64_t last_us[CAN_MAP_MAX_LINES]; /* the frame that last decoded it */
	uint8_t seen[CAN_MAP_MAX_LINES];
	uint8_t stale[CAN_MAP_MAX_LINES];
	uint8_t pressed[CAN_MAP_MAX_LINES];
	/* counters */
	uint64_t frames;         /* frames decoded, wholly or in part */
	uint64_t bad_size;       /* reads that were not 16 bytes */
	uint64_t bad_len;        /* frames with len > 8 */
	uint64_t error_frames;
	uint64_t rtr_frames;
	uint64_t unknown_ids;
	uint64_t short_frames;   /* frames shorter than their message */
	uint64_t missing_fields; /* lines a short frame did not hold whole */
	uint64_t lost;           /* events the queue lost */
};

/*
 * Prepares c to decode frames through m (which must outlive c) as device
 * `device`; who names the source in log lines ("panel (can0)").
 */
void can_input_init(struct can_input *c, const struct can_map *m, uint16_t device, const char *who);

/*
 * Decodes one frame (n bytes, which must be 16) received at t_us into q.
 * Returns 0 when the frame was decoded, wholly or in part, and -1 when it
 * was dropped: a wrong size, len > 8, an error or RTR frame, an id not in
 * the map, or no field held (each counted; bad bytes logged, blaming the
 * device).
 */
int can_input_feed(struct can_input *c, const uint8_t *frame, size_t n, uint64_t t_us,
		   struct input_queue *q);

/*
 * Reports once, at now_us, each valuator whose last frame is older than its
 * stale timeout (INPUT_VALUATOR with INPUT_F_STALE, x its last value) and
 * releases each button held that long.
 */
void can_input_tick(struct can_input *c, uint64_t now_us, struct input_queue *q);

/*
 * The panel can no longer be heard (its interface went down, its bus went
 * off, it is closing): every button it held is released (INPUT_BUTTON 0),
 * and with stale_valuators every valuator seen and not yet stale is
 * reported stale (INPUT_F_STALE, x its last value), so that the next frame
 * reports each afresh. One INPUT_FRAME follows when anything was queued.
 * Returns the buttons released.
 */
int can_input_release_all(struct can_input *c, uint64_t now_us, struct input_queue *q,
			  int stale_valuators);

/*
 * Every line of m that decodes from a frame of can_id (CAN_EFF_FLAG for an
 * extended id) with len data bytes: up to max of their indexes into
 * line_dest and values into value_dest, in map order. Returns how many
 * lines decoded (0 for an error or RTR id or an unknown one).
 */
int can_input_decode(const struct can_map *m, uint32_t can_id, const uint8_t *data, int len,
		     int *line_dest, double *value_dest, int max);

#endif
