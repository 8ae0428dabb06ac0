/*
 * test_kms_pick.c - the KMS sink's choices (draw/kms_pick.h) on plain
 * structs: the connector, mode and CRTC a kiosk's card gives, what a
 * setting asks for, the two buffers' flips, and each frame's way to its flip.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "draw/kms_pick.h"

/* a card as QEMU's bochs and a laptop's show them: eDP (connected) and HDMI (not), two CRTCs */
static void
card(struct kms_resources *r)
{
	memset(r, 0, sizeof *r);
	r->ncrtcs = 2;
	r->crtcs[0] = 40;
	r->crtcs[1] = 41;
	r->nencoders = 2;
	r->encoders[0] = (struct kms_encoder){ 50, 0, 0x3 };
	r->encoders[1] = (struct kms_encoder){ 51, 0, 0x2 };
	r->nconnectors = 2;
	struct kms_connector *hdmi = &r->connectors[0], *edp = &r->connectors[1];
	*hdmi = (struct kms_connector){ .id = 60, .name = "HDMI-A-1", .connected = 0,
					.encoders = { 50 }, .nencoders = 1 };
	*edp = (struct kms_connector){ .id = 61, .name = "eDP-1", .connected = 1,
				       .encoders = { 51 }, .nencoders = 1, .nmodes = 3 };
	edp->modes[0] = (struct kms_mode){ 1920, 1080, 60, 0 };
	edp->modes[1] = (struct kms_mode){ 1280, 800, 75, 1 };
	edp->modes[2] = (struct kms_mode){ 1280, 800, 60, 0 };
}

static void
test_the_connected_connector_its_preferred_mode_and_a_crtc_it_can_drive(void **state)
{
	(void)state;
	struct kms_resources r;
	struct kms_want want = { .w = 0 };
	struct kms_choice c;
	char why[200];
	card(&r);
	assert_int_equal(kms_choose(&r, &want, &c, why, sizeof why), 0);
	assert_int_equal(c.connector, 1);
	assert_int_equal(c.mode, 1);           /* the preferred one, not the first */
	assert_int_equal(c.crtc, 41);          /* encoder 51 can drive CRTC index 1 only */
	/* what the encoder drives now wins */
	r.connectors[1].encoder = 51;
	r.encoders[1].crtc = 41;
	assert_int_equal(kms_choose(&r, &want, &c, why, sizeof why), 0);
	assert_int_equal(c.crtc, 41);
	/* no preferred mode: the first (the kernel's best) */
	r.connectors[1].modes[1].preferred = 0;
	assert_int_equal(kms_choose(&r, &want, &c, why, sizeof why), 0);
	assert_int_equal(c.mode, 0);
}

static void
test_what_a_setting_asks_for(void **state)
{
	(void)state;
	struct kms_resources r;
	struct kms_want want = { .w = 0 };
	struct kms_choice c;
	char why[200];
	card(&r);
	assert_int_equal(kms_parse_mode("1280x800@60", &want), 0);
	assert_int_equal(kms_choose(&r, &want, &c, why, sizeof why), 0);
	assert_int_equal(c.mode, 2);
	assert_int_equal(kms_parse_mode("1920x1080", &want), 0);
	assert_int_equal(kms_choose(&r, &want, &c, why, sizeof why), 0);
	assert_int_equal(c.mode, 0);
	assert_int_equal(kms_parse_mode("800x600", &want), 0);
	assert_int_equal(kms_choose(&r, &want, &c, why, sizeof why), -1);
	assert_string_equal(why, "connector eDP-1 has no mode 800x600");
	assert_int_equal(kms_parse_mode("", &want), 0);
	strcpy(want.connector, "HDMI-A-1");
	assert_int_equal(kms_choose(&r, &want, &c, why, sizeof why), -1);
	assert_string_equal(why, "connector HDMI-A-1 is not connected");
	strcpy(want.connector, "DP-9");
	assert_int_equal(kms_choose(&r, &want, &c, why, sizeof why), -1);
	assert_string_equal(why, "no connector DP-9");
	const char *bad[] = { "1280", "1280x", "x800", "0x800", "1280x800@", "1280x800@0",
			      "1280x800x", "1280x800@60hz", "99999x1" };
	for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
		assert_int_equal(kms_parse_mode(bad[i], &want), -1);
}

static void
test_nothing_connected_or_no_crtc_is_said(void **state)
{
	(void)state;
	struct kms_resources r;
	struct kms_want want = { .w = 0 };
	struct kms_choice c;
	char why[200];
	card(&r);
	r.connectors[1].connected = 0;
	assert_int_equal(kms_choose(&r, &want, &c, why, sizeof why), -1);
	assert_string_equal(why, "no connector is connected");
	card(&r);
	r.encoders[1].possible_crtcs = 0;
	assert_int_equal(kms_choose(&r, &want, &c, why, sizeof why), -1);
	assert_string_equal(why, "no CRTC can drive connector eDP-1");
}

static void
test_two_buffers_one_flip_in_flight(void **state)
{
	(void)state;
	struct kms_flips f = { 0 };
	assert_int_equal(kms_flips_back(&f), 1); /* buffer 0 is shown after the mode set */
	kms_flips_asked(&f);
	assert_int_equal(kms_flips_back(&f), -1); /* nothing to draw into until the event */
	kms_flips_done(&f);
	assert_int_equal(f.front, 1);
	assert_int_equal(kms_flips_back(&f), 0);
	kms_flips_done(&f); /* a stray event changes nothing */
	assert_int_equal(f.front, 1);
	assert_int_equal(f.flips, 1);
}

static void
test_render_to_flip_in_its_parts(void **state)
{
	(void)state;
	static struct kms_times t; /* large for a test's stack */
	struct kms_times_summary sum;
	kms_times_sum(&t, &sum);
	assert_int_equal(sum.kept, 0);
	assert_int_equal(sum.median.total, 0);
	/* handed at 1000, taken at 1300, the last flip in at 1400, copied by 3400, asked by 3450 */
	kms_times_add(&t, 1000, 1300, 1400, 3400, 3450);
	kms_times_sum(&t, &sum);
	assert_int_equal(sum.n, 1);
	assert_int_equal(sum.median.total, 2450);
	assert_int_equal(sum.median.queue, 300);
	assert_int_equal(sum.median.wait, 100);
	assert_int_equal(sum.median.copy, 2000);
	assert_int_equal(sum.median.ioctl, 50);
	/* not stamped (a caller writing directly), or stamped later than the write began */
	memset(&t, 0, sizeof t);
	kms_times_add(&t, 0, 5000, 5000, 5100, 5110);
	kms_times_add(&t, 9000, 5000, 5000, 5100, 5110);
	kms_times_sum(&t, &sum);
	assert_int_equal(sum.max.total, 110);
	assert_int_equal(sum.max.queue, 0);
	/* a stamp before the one before it counts as that one: the parts add up */
	memset(&t, 0, sizeof t);
	kms_times_add(&t, 100, 200, 150, 400, 390);
	kms_times_sum(&t, &sum);
	assert_int_equal(sum.median.total, 300);
	assert_int_equal(sum.median.queue, 100);
	assert_int_equal(sum.median.wait, 0);
	assert_int_equal(sum.median.copy, 200);
	assert_int_equal(sum.median.ioctl, 0);
}

static void
test_the_newest_frames_kept_median_and_p99(void **state)
{
	(void)state;
	static struct kms_times t;
	struct kms_times_summary sum;
	/* 1000 frames: totals 1..1000 us; the ring keeps the newest 256 (745..1000) */
	for (uint64_t i = 1; i <= 1000; i++)
		kms_times_add(&t, 10000 * i, 10000 * i, 10000 * i, 10000 * i + i, 10000 * i + i);
	kms_times_sum(&t, &sum);
	assert_int_equal(sum.n, 1000);
	assert_int_equal(sum.kept, KMS_TIMES);
	assert_int_equal(sum.median.total, 745 + KMS_TIMES / 2);
	assert_int_equal(sum.p99.total, 745 + (KMS_TIMES * 99) / 100);
	assert_int_equal(sum.max.total, 1000);
	assert_int_equal(sum.max.copy, 1000);
	assert_int_equal(sum.max.ioctl, 0);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_the_connected_connector_its_preferred_mode_and_a_crtc_it_can_drive),
		cmocka_unit_test(test_what_a_setting_asks_for),
		cmocka_unit_test(test_nothing_connected_or_no_crtc_is_said),
		cmocka_unit_test(test_two_buffers_one_flip_in_flight),
		cmocka_unit_test(test_render_to_flip_in_its_parts),
		cmocka_unit_test(test_the_newest_frames_kept_median_and_p99),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
