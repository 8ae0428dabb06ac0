/* replay_dev.c - a recorded device's bytes fed again through a decoder of its kind */
#include "devices/replay_dev.h"

#include <linux/input.h>
#include <stdio.h>
#include <string.h>

int
replay_dev_format_of(const char *name)
{
	if (!strcmp(name, "evemu"))
		return REPLAY_DEV_EVEMU;
	if (!strcmp(name, "hid-recorder"))
		return REPLAY_DEV_HID;
	if (!strcmp(name, "candump"))
		return REPLAY_DEV_CANDUMP;
	return -1;
}

int
replay_dev_open(struct replay_dev *r, enum replay_dev_format format, const char *path,
		const char *map_path, uint16_t device, char *err, size_t errlen)
{
	memset(r, 0, sizeof *r);
	r->format = format;
	snprintf(r->path, sizeof r->path, "%s", path);
	char who[64], why[300];
	snprintf(who, sizeof who, "replayed device %u", device);
	switch (format) {
	case REPLAY_DEV_EVEMU:
		if (rec_evemu_read(path, &r->evemu, err, errlen) < 0)
			return -1;
		evdev_input_init(&r->ev, device, who);
		rec_evemu_apply_abs(&r->evemu, &r->ev);
		return 0;
	case REPLAY_DEV_HID:
		if (rec_hid_read(path, &r->hid, err, errlen) < 0)
			return -1;
		if (r->hid.ndevices != 1 ||
		    hid_desc_parse(r->hid.devices[0].desc, r->hid.devices[0].desc_len, &r->desc, why,
				   sizeof why) < 0) {
			snprintf(err, errlen, "%s: %s", path,
				 r->hid.ndevices != 1 ? "not one device" : why);
			rec_hid_free(&r->hid);
			return -1;
		}
		hid_input_init(&r->hin, &r->desc, device, who);
		return 0;
	case REPLAY_DEV_CANDUMP:
		if (can_map_read(map_path, &r->map, err, errlen) < 0)
			return -1;
		if (rec_candump_read(path, &r->can, err, errlen) < 0)
			return -1;
		can_input_init(&r->cin, &r->map, device, who);
		return 0;
	}
	snprintf(err, errlen, "%s: no such format", path);
	return -1;
}

static size_t
records(const struct replay_dev *r)
{
	switch (r->format) {
	case REPLAY_DEV_EVEMU:
		return r->evemu.nev;
	case REPLAY_DEV_HID:
		return r->hid.nevents;
	case REPLAY_DEV_CANDUMP:
		return r->can.n;
	}
	return 0;
}

/* the next count reports or frames through the decoder, at t_us */
static void
feed(struct replay_dev *r, size_t count, uint64_t t_us, struct input_queue *q)
{
	for (size_t k = 0; k < count; k++, r->next++) {
		if (r->format == REPLAY_DEV_HID) {
			const struct rec_hid_event *e = &r->hid.events[r->next];
			hid_input_feed(&r->hin, e->bytes, e->len, t_us, q);
		} else {
			uint8_t frame[16];
			rec_candump_to_can_frame(&r->can.frames[r->next], frame);
			can_input_feed(&r->cin, frame, sizeof frame, t_us, q);
		}
	}
}

/* evemu: a read's records in one buffer, fed at once as the live read was */
static void
feed_evemu(struct replay_dev *r, size_t count, struct input_queue *q)
{
	struct input_event buf[64];
	while (count) {
		size_t m = count < 64 ? count : 64;
		for (size_t k = 0; k < m; k++) {
			const struct rec_evemu_event *e = &r->evemu.ev[r->next + k];
			buf[k] = (struct input_event){ .time = { .tv_sec = (time_t)e->sec,
								 .tv_usec = (suseconds_t)e->usec },
						       .type = e->type, .code = e->code,
						       .value = e->value };
		}
		evdev_input_feed(&r->ev, (const uint8_t *)buf, m * sizeof *buf, q);
		r->next += m;
		count -= m;
	}
}

int
replay_dev_call(struct replay_dev *r, enum input_tap_kind kind, int arg, size_t count,
		const uint8_t *bytes, size_t n, uint64_t t_us, struct input_queue *q, char *err,
		size_t errlen)
{
	switch (kind) {
	case INPUT_TAP_BYTES:
		if (count > records(r) - r->next) {
			snprintf(err, errlen, "%s: %zu records, the frame log reads %zu from record %zu",
				 r->path, records(r), count, r->next + 1);
			return -1;
		}
		if (r->format == REPLAY_DEV_EVEMU)
			feed_evemu(r, count, q);
		else
			feed(r, count, t_us, q);
		return 0;
	case INPUT_TAP_RESYNC:
		if (r->format != REPLAY_DEV_EVEMU || n != KEY_MAX / 8 + 1) {
			snprintf(err, errlen, "%s: a resync is an evdev device's, of %d bytes", r->path,
				 KEY_MAX / 8 + 1);
			return -1;
		}
		evdev_input_resync(&r->ev, bytes, t_us, q);
		return 0;
	case INPUT_TAP_RELEASE:
		if (r->format == REPLAY_DEV_EVEMU)
			evdev_input_release_all(&r->ev, t_us, q);
		else if (r->format == REPLAY_DEV_HID)
			hid_input_release_all(&r->hin, t_us, q);
		else
			can_input_release_all(&r->cin, t_us, q, arg);
		return 0;
	case INPUT_TAP_TICK:
		if (r->format == REPLAY_DEV_CANDUMP)
			can_input_tick(&r->cin, t_us, q);
		return 0;
	}
	snprintf(err, errlen, "%s: no such decoder call", r->path);
	return -1;
}

void
replay_dev_free(struct replay_dev *r)
{
	rec_evemu_free(&r->evemu);
	rec_hid_free(&r->hid);
	rec_candump_free(&r->can);
}
