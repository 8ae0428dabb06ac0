/*
 * test_replay_dev.c - a recorded device played back (devices/replay_dev.h):
 * the same bytes through a decoder made from the recording's file give the
 * same events as the decoder the live backend makes, fed the same bytes.
 * The files are the input tests' own: an evemu mouse recording, a
 * hid-tools recording of a USB mouse, a candump log of the panel with its
 * map. And the candump lines a recording writes (rec_candump_format, from
 * the frames a CAN_RAW socket gives) read back as the same frames.
 */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "devices/replay_dev.h"

static struct replay_dev rd;
static struct input_queue q_replay, q_live;

static void
same_events(void)
{
	assert_true(q_live.len > 0);
	assert_int_equal(q_replay.len, q_live.len);
	struct input_event_rec a, b;
	while (input_queue_pop(&q_live, &a)) {
		assert_true(input_queue_pop(&q_replay, &b));
		/* field by field: the record has padding */
		assert_int_equal(a.t_us, b.t_us);
		assert_int_equal(a.device, b.device);
		assert_int_equal(a.kind, b.kind);
		assert_int_equal(a.flags, b.flags);
		assert_int_equal(a.code, b.code);
		assert_int_equal(a.value, b.value);
		assert_memory_equal(&a.x, &b.x, sizeof a.x);
		assert_memory_equal(&a.y, &b.y, sizeof a.y);
	}
}

static void
test_evemu_replays_as_the_evdev_decoder_decodes(void **state)
{
	(void)state;
	char err[512];
	struct rec_evemu r;
	assert_int_equal(rec_evemu_read("tests/input/evdev/mouse.evemu", &r, err, sizeof err), 0);
	input_queue_init(&q_replay);
	input_queue_init(&q_live);
	assert_int_equal(replay_dev_open(&rd, REPLAY_DEV_EVEMU, "tests/input/evdev/mouse.evemu", NULL,
					 3, err, sizeof err), 0);
	/* the file's records in reads of 5, as a live device's reads come */
	for (size_t k = 0; k < r.nev; k += 5)
		assert_int_equal(replay_dev_call(&rd, INPUT_TAP_BYTES, 0, r.nev - k < 5 ? r.nev - k : 5,
						 NULL, 0, 0, &q_replay, err, sizeof err), 0);
	struct evdev_input live;
	evdev_input_init(&live, 3, "live");
	rec_evemu_apply_abs(&r, &live);
	size_t n = rec_evemu_to_records(&r, NULL, 0);
	uint8_t *bytes = malloc(n);
	rec_evemu_to_records(&r, bytes, n);
	/* the live decoder sees the times as written, not rebased: give it the file's */
	for (size_t k = 0; k < r.nev; k++) {
		struct input_event ie;
		memcpy(&ie, bytes + k * sizeof ie, sizeof ie);
		ie.input_event_sec = (long)r.ev[k].sec;
		ie.input_event_usec = (long)r.ev[k].usec;
		evdev_input_feed(&live, (const uint8_t *)&ie, sizeof ie, &q_live);
	}
	same_events();
	/* past the file's end: said, nothing fed */
	assert_int_equal(replay_dev_call(&rd, INPUT_TAP_BYTES, 0, 1, NULL, 0, 0, &q_replay, err,
					 sizeof err), -1);
	assert_non_null(strstr(err, "mouse.evemu"));
	/* a release after the last press: the held buttons go up in both */
	assert_int_equal(replay_dev_call(&rd, INPUT_TAP_RELEASE, 0, 0, NULL, 0, 99, &q_replay, err,
					 sizeof err), 0);
	evdev_input_release_all(&live, 99, &q_live);
	assert_int_equal(q_replay.len, q_live.len);
	free(bytes);
	rec_evemu_free(&r);
	replay_dev_free(&rd);
}

static void
test_a_hid_recording_replays_as_the_hid_decoder_decodes(void **state)
{
	(void)state;
	char err[512];
	struct rec_hid r;
	struct hid_desc d;
	assert_int_equal(rec_hid_read("tests/input/hid/hidtools_mouse.hid", &r, err, sizeof err), 0);
	assert_int_equal(hid_desc_parse(r.devices[0].desc, r.devices[0].desc_len, &d, err, sizeof err),
			 0);
	input_queue_init(&q_replay);
	input_queue_init(&q_live);
	assert_int_equal(replay_dev_open(&rd, REPLAY_DEV_HID, "tests/input/hid/hidtools_mouse.hid",
					 NULL, 1, err, sizeof err), 0);
	struct hid_input live;
	hid_input_init(&live, &d, 1, "live");
	for (size_t k = 0; k < r.nevents; k++) {
		uint64_t t = 1000 * (uint64_t)k;
		assert_int_equal(replay_dev_call(&rd, INPUT_TAP_BYTES, 0, 1, NULL, 0, t, &q_replay, err,
						 sizeof err), 0);
		hid_input_feed(&live, r.events[k].bytes, r.events[k].len, t, &q_live);
	}
	same_events();
	rec_hid_free(&r);
	replay_dev_free(&rd);
}

static void
test_candump_lines_a_recording_writes_read_back_and_replay(void **state)
{
	(void)state;
	char err[512];
	struct rec_candump src, back;
	assert_int_equal(rec_candump_read("tests/input/can/panel.log", &src, err, sizeof err), 0);
	char path[] = "/tmp/posture-replay-dev-XXXXXX";
	int fd = mkstemp(path);
	assert_true(fd >= 0);
	FILE *f = fdopen(fd, "w");
	/* what the daemon's tap gets (a socket's frames, its own clock) written as it writes them */
	for (size_t k = 0; k < src.n; k++) {
		uint8_t frame[16];
		struct rec_candump_frame fr;
		char line[REC_CANDUMP_LINE_MAX];
		rec_candump_to_can_frame(&src.frames[k], frame);
		rec_candump_from_can_frame(frame, 5000000 + 1000 * k, "vcan0", &fr);
		size_t n = rec_candump_format(line, sizeof line, &fr, 0, 0);
		assert_true(n < sizeof line && line[n - 1] == '\n');
		fwrite(line, 1, n, f);
	}
	fclose(f);
	assert_int_equal(rec_candump_read(path, &back, err, sizeof err), 0);
	assert_int_equal(back.n, src.n);
	for (size_t k = 0; k < src.n; k++) {
		assert_int_equal(back.frames[k].can_id, src.frames[k].can_id);
		assert_int_equal(back.frames[k].len, src.frames[k].len);
		assert_memory_equal(back.frames[k].data, src.frames[k].data, src.frames[k].len);
		assert_int_equal(back.frames[k].t_abs_us, 5000000 + 1000 * k);
		assert_string_equal(back.frames[k].iface, "vcan0");
	}
	/* and replayed through the panel's decoder: the events of the live decoder */
	struct can_map map;
	assert_int_equal(can_map_read("tests/input/can/panel.map", &map, err, sizeof err), 0);
	input_queue_init(&q_replay);
	input_queue_init(&q_live);
	assert_int_equal(replay_dev_open(&rd, REPLAY_DEV_CANDUMP, path, "tests/input/can/panel.map",
					 2, err, sizeof err), 0);
	struct can_input live;
	can_input_init(&live, &map, 2, "live");
	for (size_t k = 0; k < src.n; k++) {
		uint8_t frame[16];
		uint64_t t = 7000000 + 500 * k;
		rec_candump_to_can_frame(&src.frames[k], frame);
		assert_int_equal(replay_dev_call(&rd, INPUT_TAP_BYTES, 0, 1, NULL, 0, t, &q_replay, err,
						 sizeof err), 0);
		can_input_feed(&live, frame, sizeof frame, t, &q_live);
		if (k % 16 == 15) { /* a stale timer now and then */
			replay_dev_call(&rd, INPUT_TAP_TICK, 0, 0, NULL, 0, t + 900000, &q_replay, err,
					sizeof err);
			can_input_tick(&live, t + 900000, &q_live);
		}
	}
	same_events();
	unlink(path);
	rec_candump_free(&src);
	rec_candump_free(&back);
	replay_dev_free(&rd);
}

static void
test_files_it_cannot_use_are_refused_with_their_place(void **state)
{
	(void)state;
	char err[512];
	assert_int_equal(replay_dev_format_of("evemu"), REPLAY_DEV_EVEMU);
	assert_int_equal(replay_dev_format_of("pcap"), -1);
	assert_int_equal(replay_dev_open(&rd, REPLAY_DEV_EVEMU, "/nonexistent/x.evemu", NULL, 0, err,
					 sizeof err), -1);
	assert_non_null(strstr(err, "/nonexistent/x.evemu"));
	/* a hid-recorder file whose events come before any device: refused at its line */
	char path[] = "/tmp/posture-replay-dev-XXXXXX";
	int fd = mkstemp(path);
	assert_true(fd >= 0);
	const char bad[] = "# nothing\nE: 000000.000000 4 01 00 00 00\n";
	assert_int_equal(write(fd, bad, sizeof bad - 1), (ssize_t)(sizeof bad - 1));
	close(fd);
	assert_int_equal(replay_dev_open(&rd, REPLAY_DEV_HID, path, NULL, 0, err, sizeof err), -1);
	assert_non_null(strstr(err, ":2:"));
	unlink(path);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_evemu_replays_as_the_evdev_decoder_decodes),
		cmocka_unit_test(test_a_hid_recording_replays_as_the_hid_decoder_decodes),
		cmocka_unit_test(test_candump_lines_a_recording_writes_read_back_and_replay),
		cmocka_unit_test(test_files_it_cannot_use_are_refused_with_their_place),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
