/* can_input.c - CAN frames through a panel map into events (see can_input.h) */
#include "devices/can_input.h"

#include <math.h>
#include <string.h>

void
can_input_init(struct can_input *c, const struct can_map *m, uint16_t device, const char *who)
{
	memset(c, 0, sizeof *c);
	c->map = m;
	c->device = device;
	devlog_init(&c->log, who);
}

/* the index of a frame's id in m->ids, or -1 */
static int
id_find(const struct can_map *m, uint32_t can_id)
{
	uint32_t key = (can_id & CAN_EFF_FLAG) ? (can_id & (CAN_EFF_MASK | CAN_EFF_FLAG))
					       : (can_id & CAN_SFF_MASK);
	int lo = 0, hi = m->n_ids - 1;
	while (lo <= hi) {
		int mid = (lo + hi) / 2;
		if (m->ids[mid] == key)
			return mid;
		if (m->ids[mid] < key)
			lo = mid + 1;
		else
			hi = mid - 1;
	}
	return -1;
}

/* one line's physical value from the frame read as little- and big-endian numbers */
static double
line_value(const struct can_map_line *l, uint64_t le, uint64_t be)
{
	uint64_t raw = ((l->order == CAN_MAP_INTEL ? le : be) >> l->shift) & l->mask;
	double v;
	if (l->is_signed && (raw >> (l->length - 1) & 1))
		v = (double)(int64_t)(raw | ~l->mask);
	else if (l->is_signed)
		v = (double)(int64_t)raw;
	else
		v = (double)raw;
	v = v * l->factor + l->offset;
	if (l->has_clamp)
		v = v < l->clamp_min ? l->clamp_min : v > l->clamp_max ? l->clamp_max : v;
	return v;
}

/* whether the mux line's value selects line l (cantools: the integer part of the value) */
static int
mux_selects(const struct can_map_line *l, double sel)
{
	if (!(sel > -9.2e18 && sel < 9.2e18))
		return 0;
	int64_t v = (int64_t)trunc(sel);
	for (int k = 0; k < l->n_mux; k++)
		if (l->mux_values[k] == v)
			return 1;
	return 0;
}

/*
 * The lines of id j from len bytes of data: ok[i] and val[i] for each of
 * them (indexed by line). Returns how many decoded; *missing_dest counts
 * the lines in their branch that the frame did not hold whole.
 */
static int
decode_id(const struct can_map *m, int j, const uint8_t *data, int len, uint8_t *ok, double *val,
	  int *missing_dest)
{
	uint8_t b[8] = { 0 };
	memcpy(b, data, (size_t)(len > 8 ? 8 : len));
	uint64_t le = 0, be = 0;
	for (int k = 0; k < 8; k++) {
		le |= (uint64_t)b[k] << (8 * k);
		be = be << 8 | b[k];
	}
	int count = 0, missing = 0;
	for (int k = m->id_first[j]; k < m->id_first[j] + m->id_count[j]; k++) {
		int i = m->by_id[k];
		const struct can_map_line *l = &m->line[i];
		ok[i] = 0;
		if (l->mux_line >= 0 && !(ok[l->mux_line] && mux_selects(l, val[l->mux_line])))
			continue;
		if (l->nbytes > len) {
			missing++;
			continue;
		}
		val[i] = line_value(l, le, be);
		ok[i] = 1;
		count++;
	}
	*missing_dest = missing;
	return count;
}

int
can_input_decode(const struct can_map *m, uint32_t can_id, const uint8_t *data, int len,
		 int *line_dest, double *value_dest, int max)
{
	if (can_id & (CAN_ERR_FLAG | CAN_RTR_FLAG))
		return 0;
	int j = id_find(m, can_id);
	if (j < 0)
		return 0;
	uint8_t ok[CAN_MAP_MAX_LINES];
	double val[CAN_MAP_MAX_LINES];
	int missing;
	if (len < 0)
		len = 0;
	int count = decode_id(m, j, data, len, ok, val, &missing);
	int out = 0;
	for (int i = 0; i < m->n && out < max; i++) {
		if (m->line[i].can_id != m->ids[j] || !ok[i])
			continue;
		line_dest[out] = i;
		value_dest[out] = val[i];
		out++;
	}
	return count;
}

static void
push(struct can_input *c, struct input_queue *q, uint64_t t_us, enum input_kind kind, uint8_t flags,
     uint16_t code, int32_t value, double x)
{
	struct input_event_rec e;
	memset(&e, 0, sizeof e);
	e.t_us = t_us;
	e.device = c->device;
	e.kind = (uint8_t)kind;
	e.flags = flags;
	e.code = code;
	e.value = value;
	e.x = x;
	if (input_queue_push(q, &e) < 0)
		c->lost++;
}

static int
can_input_feed_work(struct can_input *c, const uint8_t *frame, size_t n, uint64_t t_us,
	       struct input_queue *q)
{
	const struct can_map *m = c->map;
	if (n != CAN_INPUT_FRAME_SIZE) {
		c->bad_size++;
		devlog(&c->log, t_us, DEVLOG_DEVICE, "read of %zu bytes, not a 16-byte can_frame",
		       n);
		return -1;
	}
	uint32_t can_id;
	memcpy(&can_id, frame, sizeof can_id);
	int len = frame[4];

	/* what is counted, not decoded */
	if (can_id & CAN_ERR_FLAG) {
		c->error_frames++;
		devlog(&c->log, t_us, DEVLOG_DEVICE, "error frame, class 0x%x",
		       can_id & CAN_ERR_MASK);
		return -1;
	}
	if (can_id & CAN_RTR_FLAG) {
		c->rtr_frames++;
		return -1;
	}
	if (len > 8) {
		c->bad_len++;
		devlog(&c->log, t_us, DEVLOG_DEVICE, "frame with len %d, more than 8", len);
		return -1;
	}
	int j = id_find(m, can_id);
	if (j < 0) {
		c->unknown_ids++;
		return -1;
	}

	/* the fields */
	uint8_t ok[CAN_MAP_MAX_LINES];
	double val[CAN_MAP_MAX_LINES];
	int missing;
	int count = decode_id(m, j, frame + 8, len, ok, val, &missing);
	if (len < m->id_len[j]) {
		c->short_frames++;
		c->missing_fields += (uint64_t)missing;
		devlog(&c->log, t_us, DEVLOG_DEVICE,
		       "frame %X of %d bytes, its message has %d: %d fields missing",
		       can_id & CAN_EFF_MASK, len, m->id_len[j], missing);
	}
	if (count == 0)
		return -1;
	c->frames++;

	/* events for what changed */
	int events = 0;
	for (int k = m->id_first[j]; k < m->id_first[j] + m->id_count[j]; k++) {
		int i = m->by_id[k];
		if (!ok[i])
			continue;
		const struct can_map_line *l = &m->line[i];
		switch ((enum can_map_kind)l->kind) {
		case CAN_MAP_BUTTON: {
			uint8_t down = val[i] != 0;
			if (down != c->pressed[i]) {
				push(c, q, t_us, INPUT_BUTTON, 0, l->code, down, 0);
				c->pressed[i] = down;
				events++;
			}
			break;
		}
		case CAN_MAP_AXIS:
		case CAN_MAP_MUX:
			if (!c->seen[i] || c->stale[i] || val[i] != c->value[i]) {
				push(c, q, t_us, INPUT_VALUATOR, 0, (uint16_t)i, 0, val[i]);
				events++;
			}
			break;
		}
		c->value[i] = val[i];
		c->last_us[i] = t_us;
		c->seen[i] = 1;
		c->stale[i] = 0;
	}
	if (events)
		push(c, q, t_us, INPUT_FRAME, 0, 0, 0, 0);
	return 0;
}

/* what the tap of q records (queue.h), then the work */
int
can_input_feed(struct can_input *c, const uint8_t *frame, size_t n, uint64_t t_us, struct input_queue *q)
{
	input_queue_decoder_enter(q, c->device, INPUT_TAP_BYTES, 0, frame, n, t_us);
	int rc = can_input_feed_work(c, frame, n, t_us, q);
	input_queue_decoder_leave(q);
	return rc;
}

static void
can_input_tick_work(struct can_input *c, uint64_t now_us, struct input_queue *q)
{
	const struct can_map *m = c->map;
	int events = 0;
	for (int i = 0; i < m->n; i++) {
		const struct can_map_line *l = &m->line[i];
		if (!c->seen[i] || c->stale[i] || l->stale_ms == 0)
			continue;
		if (now_us <= c->last_us[i] + (uint64_t)l->stale_ms * 1000)
			continue;
		c->stale[i] = 1;
		switch ((enum can_map_kind)l->kind) {
		case CAN_MAP_BUTTON:
			if (c->pressed[i]) {
				push(c, q, now_us, INPUT_BUTTON, 0, l->code, 0, 0);
				c->pressed[i] = 0;
				events++;
			}
			break;
		case CAN_MAP_AXIS:
		case CAN_MAP_MUX:
			push(c, q, now_us, INPUT_VALUATOR, INPUT_F_STALE, (uint16_t)i, 0,
			     c->value[i]);
			events++;
			break;
		}
	}
	if (events)
		push(c, q, now_us, INPUT_FRAME, 0, 0, 0, 0);
}

/* what the tap of q records (queue.h), then the work */
void
can_input_tick(struct can_input *c, uint64_t now_us, struct input_queue *q)
{
	input_queue_decoder_enter(q, c->device, INPUT_TAP_TICK, 0, NULL, 0, now_us);
	can_input_tick_work(c, now_us, q);
	input_queue_decoder_leave(q);
}

static int
can_input_release_all_work(struct can_input *c, uint64_t now_us, struct input_queue *q,
		      int stale_valuators)
{
	const struct can_map *m = c->map;
	int released = 0, events = 0;
	for (int i = 0; m && i < m->n; i++) {
		const struct can_map_line *l = &m->line[i];
		switch ((enum can_map_kind)l->kind) {
		case CAN_MAP_BUTTON:
			if (c->pressed[i]) {
				push(c, q, now_us, INPUT_BUTTON, 0, l->code, 0, 0);
				c->pressed[i] = 0;
				released++;
				events++;
			}
			break;
		case CAN_MAP_AXIS:
		case CAN_MAP_MUX:
			if (stale_valuators && c->seen[i] && !c->stale[i]) {
				push(c, q, now_us, INPUT_VALUATOR, INPUT_F_STALE, (uint16_t)i, 0,
				     c->value[i]);
				c->stale[i] = 1;
				events++;
			}
			break;
		}
	}
	if (events)
		push(c, q, now_us, INPUT_FRAME, 0, 0, 0, 0);
	return released;
}

/* what the tap of q records (queue.h), then the work */
int
can_input_release_all(struct can_input *c, uint64_t now_us, struct input_queue *q, int stale_valuators)
{
	input_queue_decoder_enter(q, c->device, INPUT_TAP_RELEASE, stale_valuators, NULL, 0, now_us);
	int rc = can_input_release_all_work(c, now_us, q, stale_valuators);
	input_queue_decoder_leave(q);
	return rc;
}
