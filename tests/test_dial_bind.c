/*
 * test_dial_bind.c - the dial panel's bindings: the sample file against the
 * example panel's map, every target and unit read from a file, bad files
 * refused with their line and the table left as it was, the writer read
 * back to the same table and text, the relative dials (the first value
 * moves nothing, then gain times the change, invert, the dead zone, stale
 * and unplugged dials starting afresh, NaN ignored), buttons on press and
 * release, bind and unbind at run time, names resolved late; and 100 000
 * random events, huge and non-finite values among them, never giving a
 * delta that is not finite nor allocating.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <linux/input-event-codes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "devices/can_map.h"
#include "interact/dial_feed.h"

#include "alloc_count.h"
#include "test_random.h"
#include "test_util.h"

#define DEG (M_PI / 180)

/* about 80 kB each: not on the stack */
static struct dial_bind table, table_b, saved;
static struct can_map panel;

/* the test's panel: dial codes by name */
static const char *const names[] = { "Panel.Dial1", "Panel.Dial2", "Panel.Dial3", "Panel.Dial4" };
static const struct dial_bind_names name_list = { names, 4 };
static const struct dial_bind_lookup lookup = { dial_bind_find_in_names, &name_list };

static void
parse_with(const char *text, const struct dial_bind_lookup *by, struct dial_bind *dest)
{
	char err[256];
	if (dial_bind_parse(text, strlen(text), "t.bindings", by, dest, err, sizeof err))
		fail_msg("%s\n%s", err, text);
}

/* parses text that must be good, names through the test's panel */
static void
parse_ok(const char *text, struct dial_bind *dest)
{
	parse_with(text, &lookup, dest);
}

static struct input_event_rec
valuator(int code, double x)
{
	return (struct input_event_rec){ .kind = INPUT_VALUATOR, .code = (uint16_t)code, .x = x };
}

static struct input_event_rec
button(int code, int value)
{
	return (struct input_event_rec){ .kind = INPUT_BUTTON, .code = (uint16_t)code,
					 .value = value };
}

/* feeds one valuator value; the number of actions, the first in *a */
static int
turn(int code, double x, struct dial_action *a)
{
	struct input_event_rec e = valuator(code, x);
	return dial_bind_feed(&table, &e, a, 1);
}

/* feeds a value that must give exactly one move, and returns its delta */
#define moved(code, x) moved_at((code), (x), __LINE__)
static double
moved_at(int code, double x, int line)
{
	struct dial_action a;
	int n = turn(code, x, &a);
	if (n != 1 || a.kind != DIAL_ACTION_MOVE)
		fail_msg("line %d: dial %d to %g gave %d actions, not one move", line, code, x, n);
	return a.delta;
}

/* feeds a value that must give nothing */
#define still(code, x) still_at((code), (x), __LINE__)
static void
still_at(int code, double x, int line)
{
	struct dial_action a;
	int n = turn(code, x, &a);
	if (n)
		fail_msg("line %d: dial %d to %g moved %g", line, code, x, a.delta);
}

/* the command a button event gives, or NULL */
static const char *
pressed(int code, int value)
{
	struct input_event_rec e = button(code, value);
	struct dial_action a[2];
	int n = dial_bind_feed(&table, &e, a, 2);
	assert_true(n <= 1);
	if (!n)
		return NULL;
	assert_int_equal(a[0].kind, DIAL_ACTION_COMMAND);
	return a[0].command;
}

/* runs a command line split at spaces; returns its result, err in msg */
static int
command(const char *line, char *msg, size_t len)
{
	char buf[256];
	const char *w[16];
	int n = 0;
	snprintf(buf, sizeof buf, "%s", line);
	for (char *save, *t = strtok_r(buf, " ", &save); t; t = strtok_r(NULL, " ", &save))
		w[n++] = t;
	return dial_bind_command(&table, w, n, &lookup, msg, len);
}

static void
command_ok(const char *line)
{
	char err[256];
	if (command(line, err, sizeof err))
		fail_msg("%s: %s", line, err);
}

static void
command_refused(const char *line, const char *msg)
{
	char err[256];
	memcpy(&saved, &table, sizeof saved);
	assert_int_equal(command(line, err, sizeof err), -1);
	if (!strstr(err, msg))
		fail_msg("%s: '%s', not '%s'", line, err, msg);
	assert_memory_equal(&table, &saved, sizeof table);
}

/* ---- reading files ---- */

static void
test_sample_file_binds_the_example_panel(void **unused)
{
	(void)unused;
	char err[256];
	if (can_map_read("tests/input/can/panel.map", &panel, err, sizeof err))
		fail_msg("%s", err);
	const struct dial_bind_lookup by_map = { dial_bind_find_in_map, &panel };
	dial_bind_init(&table);
	if (dial_bind_read("tools/panel.bindings", &by_map, &table, err, sizeof err))
		fail_msg("%s", err);
	assert_int_equal(table.ndial, 9);
	assert_int_equal(table.nbutton, 3);
	/* Dials.Dial2 is the map's second line; it turns DOF 0 a degree per degree */
	assert_string_equal(table.dial[0].name, "Dials.Dial2");
	assert_int_equal(table.dial[0].index, 1);
	assert_int_equal(table.dial[0].target.kind, DIAL_TARGET_DOF);
	assert_int_equal(table.dial[0].target.dof, 0);
	assert_near(table.dial[0].gain, DEG, 1e-15);
	/* every dial resolved to an axis line of the map */
	for (int i = 0; i < table.ndial; i++) {
		assert_true(table.dial[i].index >= 0);
		assert_int_equal(panel.line[table.dial[i].index].kind, CAN_MAP_AXIS);
	}
	/* the buttons are those the map gives its button lines */
	int codes = 0;
	for (int i = 0; i < panel.n; i++)
		if (panel.line[i].kind == CAN_MAP_BUTTON)
			assert_int_equal(table.button[codes++].code, panel.line[i].code);
	assert_int_equal(codes, 3);
	/* a button line of the map is no dial */
	assert_int_equal(dial_bind_find_in_map(&panel, "Dials.Foot"), -1);
	assert_int_equal(dial_bind_find_in_map(&panel, "Dials.Dial3"), 4);
	assert_int_equal(dial_bind_find_in_map(&panel, "Nothing"), -1);
}

static void
test_every_target_and_unit(void **unused)
{
	(void)unused;
	dial_bind_init(&table);
	parse_ok("# a panel\n"
		 "\n"
		 "   bindings 1   # the version\n"
		 "dial Panel.Dial1 dof 0 gain=0.5deg\n"
		 "dial Panel.Dial2 camera sweep_h gain=1deg invert\n"
		 "dial Panel.Dial3 behavior elevation gain=1mm dead=0.2\r\n"
		 "dial Panel.Dial4 joint jack elbow_r 5 gain=2cm\n"
		 "button BTN_0 \"undo\"\n"
		 "button BTN_1 \"settle frames=30\" on=release\n"
		 "button 0x2ff \"say \\\"a # b\\\" \\\\\" on=press\n"
		 "button 300 undo\t# a bare command\n"
		 "button BTN_A redo\n",
		 &table);
	assert_int_equal(table.ndial, 4);
	const struct dial_bind_dial *d = table.dial;
	assert_string_equal(d[0].name, "Panel.Dial1");
	assert_int_equal(d[0].index, 0);
	assert_int_equal(d[0].target.kind, DIAL_TARGET_DOF);
	assert_near(d[0].gain, 0.5 * M_PI / 180, 1e-17);
	assert_int_equal(d[0].gain_unit, DIAL_UNIT_DEG);
	assert_int_equal(d[0].invert, 0);
	assert_true(d[0].dead == 0);
	assert_int_equal(d[1].target.kind, DIAL_TARGET_CAMERA);
	assert_int_equal(d[1].target.axis, DIAL_CAMERA_SWEEP_H);
	assert_int_equal(d[1].invert, 1);
	assert_int_equal(d[2].target.kind, DIAL_TARGET_BEHAVIOR);
	assert_int_equal(d[2].target.axis, DIAL_BEHAVIOR_ELEVATION);
	assert_near(d[2].gain, 0.001, 1e-18);
	assert_true(d[2].dead == 0.2);
	assert_int_equal(d[3].target.kind, DIAL_TARGET_JOINT);
	assert_string_equal(d[3].target.figure, "jack");
	assert_string_equal(d[3].target.joint, "elbow_r");
	assert_int_equal(d[3].target.dof, 5);
	assert_near(d[3].gain, 0.02, 1e-18);
	assert_int_equal(table.nbutton, 5);
	assert_int_equal(table.button[0].code, BTN_0);
	assert_string_equal(table.button[0].command, "undo");
	assert_int_equal(table.button[0].edge, DIAL_EDGE_PRESS);
	assert_int_equal(table.button[1].code, BTN_1);
	assert_string_equal(table.button[1].command, "settle frames=30");
	assert_int_equal(table.button[1].edge, DIAL_EDGE_RELEASE);
	assert_int_equal(table.button[2].code, 0x2ff);
	assert_string_equal(table.button[2].command, "say \"a # b\" \\");
	assert_int_equal(table.button[3].code, 300);
	assert_string_equal(table.button[3].command, "undo");
	/* an alias of the map's table: the gamepad's A is BTN_SOUTH */
	assert_int_equal(table.button[4].code, BTN_A);
	assert_int_equal(table.button[4].code, BTN_SOUTH);

	/* the rest of the targets; gains bare, in rad, m, cm, mm; the default gain */
	parse_with("bindings 1\n"
		 "dial Panel.Dial1 camera sweep_v gain=-0.25rad\n"
		 "dial Panel.Dial2 camera zoom gain=3cm\n"
		 "dial Panel.Dial3 behavior torso_forward gain=0.1\n"
		 "dial Panel.Dial4 behavior torso_lateral\n"
		 "dial a behavior torso_axial gain=+1e1deg\n"
		 "dial b manip x gain=1m\n"
		 "dial c manip y gain=1.5e-3\n"
		 "dial d manip z gain=.5mm\n"
		 "dial e manip rx gain=90deg\n"
		 "dial f manip ry gain=1rad\n"
		 "dial g manip rz gain=0\n"
		 "dial h dof 3 gain=1mm\n",
		 NULL, &table);
	d = table.dial;
	assert_int_equal(table.ndial, 12);
	assert_int_equal(d[0].target.axis, DIAL_CAMERA_SWEEP_V);
	assert_true(d[0].gain == -0.25);
	assert_int_equal(d[1].target.axis, DIAL_CAMERA_ZOOM);
	assert_near(d[1].gain, 0.03, 1e-18);
	assert_int_equal(d[2].target.axis, DIAL_BEHAVIOR_TORSO_FORWARD);
	assert_true(d[2].gain == 0.1);
	assert_int_equal(d[3].target.axis, DIAL_BEHAVIOR_TORSO_LATERAL);
	assert_true(d[3].gain == 1 && d[3].gain_unit == DIAL_UNIT_NONE);
	assert_int_equal(d[4].target.axis, DIAL_BEHAVIOR_TORSO_AXIAL);
	assert_near(d[4].gain, 10 * M_PI / 180, 1e-15);
	/* without a lookup names are kept unresolved */
	assert_int_equal(d[0].index, -1);
	for (int i = 5; i < 11; i++) {
		assert_int_equal(d[i].target.kind, DIAL_TARGET_MANIP);
		assert_int_equal(d[i].target.axis, i - 5);
	}
	assert_true(d[5].gain == 1);
	assert_true(d[6].gain == 1.5e-3);
	assert_near(d[7].gain, 0.0005, 1e-18);
	assert_near(d[8].gain, M_PI / 2, 1e-15);
	assert_true(d[9].gain == 1);
	assert_true(d[10].gain == 0);
	assert_int_equal(d[11].gain_unit, DIAL_UNIT_MM);
	assert_int_equal(dial_target_quantity(&d[11].target), DIAL_QUANTITY_EITHER);
	assert_int_equal(dial_target_quantity(&d[1].target), DIAL_QUANTITY_LENGTH);
	assert_int_equal(dial_target_quantity(&d[10].target), DIAL_QUANTITY_ANGLE);
	char s[64];
	assert_string_equal(dial_target_to_str(&d[4].target, s, sizeof s), "behavior torso_axial");
	/* a version-only file is an empty table */
	parse_ok("bindings 1\n", &table);
	assert_int_equal(table.ndial + table.nbutton, 0);
}

/* text must be refused at line, with msg in the message, and the table kept */
static void
refused(const char *text, int line, const char *msg)
{
	char err[256], want[32];
	dial_bind_init(&table);
	parse_ok("bindings 1\ndial Panel.Dial1 dof 1 gain=2deg\nbutton BTN_0 undo\n", &table);
	memcpy(&saved, &table, sizeof saved);
	if (!dial_bind_parse(text, strlen(text), "bad.bindings", &lookup, &table, err, sizeof err))
		fail_msg("accepted:\n%s", text);
	snprintf(want, sizeof want, "bad.bindings:%d: ", line);
	if (strncmp(err, want, strlen(want)) || !strstr(err, msg))
		fail_msg("'%s', not '%s...%s', for\n%s", err, want, msg, text);
	assert_memory_equal(&table, &saved, sizeof table);
}

static void
test_bad_files_refused_with_their_line(void **unused)
{
	(void)unused;
	refused("", 1, "not a bindings file");
	refused("# only a comment\n\n", 2, "not a bindings file");
	refused("dial Panel.Dial1 dof 0\n", 1, "not a bindings file");
	refused("bindings\n", 1, "not a bindings file");
	refused("bindings 2\n", 1, "version 2 is newer");
	refused("bindings 0\n", 1, "whole number");
	refused("bindings 1.0\n", 1, "whole number");
	refused("bindings 1\nbindings 1\n", 2, "once, on the first line");
	refused("bindings 1\n\nknob Panel.Dial1 dof 0\n", 3, "unknown statement 'knob'");
	refused("bindings 1\ndial\n", 2, "a dial's name");
	refused("bindings 1\ndial Panel/Dial1 dof 0\n", 2, "a dial's name");
	refused("bindings 1\ndial Panel.Dial9 dof 0\n", 2, "the panel has no dial 'Panel.Dial9'");
	refused("bindings 1\ndial Panel.Dial1\n", 2, "needs a target");
	refused("bindings 1\ndial Panel.Dial1 dof\n", 2, "0..5");
	refused("bindings 1\ndial Panel.Dial1 dof 6\n", 2, "0..5");
	refused("bindings 1\ndial Panel.Dial1 dof -1\n", 2, "0..5");
	refused("bindings 1\ndial Panel.Dial1 joint jack elbow\n", 2,
		"a figure, a joint and a DOF");
	refused("bindings 1\ndial Panel.Dial1 joint ja\"c k\" elbow 0\n", 2, "figure's or joint's");
	refused("bindings 1\ndial Panel.Dial1 camera pan\n", 2, "sweep_h, sweep_v or zoom");
	refused("bindings 1\ndial Panel.Dial1 behavior height\n", 2, "elevation, torso_forward");
	refused("bindings 1\ndial Panel.Dial1 manip w\n", 2, "x, y, z, rx, ry or rz");
	refused("bindings 1\ndial Panel.Dial1 spine 0\n", 2, "unknown target 'spine'");
	refused("bindings 1\ndial Panel.Dial1 dof 0 fast\n", 2, "unknown option 'fast'");
	refused("bindings 1\ndial Panel.Dial1 dof 0 gain=1 gain=2\n", 2, "'gain' given twice");
	refused("bindings 1\ndial Panel.Dial1 dof 0 invert invert\n", 2, "'invert' given twice");
	refused("bindings 1\ndial Panel.Dial1 dof 0 gain=nan\n", 2, "gain= needs");
	refused("bindings 1\ndial Panel.Dial1 dof 0 gain=inf\n", 2, "gain= needs");
	refused("bindings 1\ndial Panel.Dial1 dof 0 gain=1e999\n", 2, "gain= needs");
	refused("bindings 1\ndial Panel.Dial1 dof 0 gain=0x10\n", 2, "gain= needs");
	refused("bindings 1\ndial Panel.Dial1 dof 0 gain=2kg\n", 2, "gain= needs");
	refused("bindings 1\ndial Panel.Dial1 dof 0 gain=\n", 2, "gain= needs");
	refused("bindings 1\ndial Panel.Dial1 camera zoom gain=1deg\n", 2, "a length (m, cm, mm)");
	refused("bindings 1\ndial Panel.Dial1 manip rx gain=1cm\n", 2, "an angle (deg, rad)");
	refused("bindings 1\ndial Panel.Dial1 behavior elevation gain=1rad\n", 2, "a length");
	refused("bindings 1\ndial Panel.Dial1 dof 0 dead=-1\n", 2, "dead= needs");
	refused("bindings 1\ndial Panel.Dial1 dof 0 dead=1mm\n", 2, "dead= needs");
	refused("bindings 1\ndial Panel.Dial1 dof 0\ndial Panel.Dial2 dof 1\n"
		"dial Panel.Dial1 dof 2\n",
		4, "'Panel.Dial1' is already bound on line 2");
	refused("bindings 1\nbutton BTN_0\n", 2, "button BUTTON COMMAND");
	refused("bindings 1\nbutton BTN_NOPE undo\n", 2, "a BTN_* name");
	refused("bindings 1\nbutton 0 undo\n", 2, "a BTN_* name");
	refused("bindings 1\nbutton 0x300 undo\n", 2, "a BTN_* name");
	refused("bindings 1\nbutton 12ab undo\n", 2, "a BTN_* name");
	refused("bindings 1\nbutton BTN_0 \"\"\n", 2, "1..1023 bytes");
	refused("bindings 1\nbutton BTN_0 settle frames=30\n", 2, "quote a command");
	refused("bindings 1\nbutton BTN_0 a b c\n", 2, "too many words");
	refused("bindings 1\nbutton BTN_0 undo on=hold\n", 2, "quote a command");
	refused("bindings 1\nbutton BTN_0 \"undo\nredo\"\n", 2, "unbalanced quote");
	refused("bindings 1\nbutton BTN_0 \"a\\n\"\n", 2, "may be escaped");
	refused("bindings 1\nbutton BTN_0 \"a\x01\"\n", 2, "control characters");
	refused("bindings 1\nbutton BTN_0 undo\nbutton BTN_1 undo\nbutton 256 redo\n", 4,
		"press is already bound on line 2");
	refused("bindings 1\nbutton BTN_0 redo on=release\nbutton BTN_0 undo on=release\n", 3,
		"release is already bound on line 2");
	refused("bindings 1\na b c d e f g h i j k l m n o p q\n", 2, "too many words");
	/* a NUL byte, and a line longer than the limit */
	char text[DIAL_BIND_LINE_MAX + 64];
	char err[256];
	memcpy(text, "bindings 1\ndial a\0b dof 0\n", 26);
	dial_bind_init(&table);
	assert_int_equal(dial_bind_parse(text, 26, "nul", NULL, &table, err, sizeof err), -1);
	assert_string_equal(err, "nul:2: a NUL byte in the line");
	int k = snprintf(text, sizeof text, "bindings 1\n# ");
	memset(text + k, 'x', DIAL_BIND_LINE_MAX);
	text[k + DIAL_BIND_LINE_MAX] = 0;
	refused(text, 2, "line too long");
	/* too many dials */
	static char many[DIAL_BIND_MAX_DIALS * 32 + 64];
	k = snprintf(many, sizeof many, "bindings 1\n");
	for (int i = 0; i <= DIAL_BIND_MAX_DIALS; i++)
		k += snprintf(many + k, sizeof many - (size_t)k, "dial d%d dof 0\n", i);
	assert_int_equal(dial_bind_parse(many, strlen(many), "many", NULL, &table, err, sizeof err),
			 -1);
	assert_string_equal(err, "many:66: too many dials (at most 64)");
	/* a file that cannot be read */
	const char *missing = "/nonexistent/p.bindings";
	assert_int_equal(dial_bind_read(missing, &lookup, &table, err, sizeof err), -1);
	assert_non_null(strstr(err, "/nonexistent/p.bindings"));
}

/* ---- writing ---- */

static void
dial_equal(const struct dial_bind_dial *a, const struct dial_bind_dial *b)
{
	assert_string_equal(a->name, b->name);
	assert_int_equal(a->index, b->index);
	assert_int_equal(a->target.kind, b->target.kind);
	assert_int_equal(a->target.axis, b->target.axis);
	assert_int_equal(a->target.dof, b->target.dof);
	assert_string_equal(a->target.figure, b->target.figure);
	assert_string_equal(a->target.joint, b->target.joint);
	/* exactly: the same bits */
	assert_memory_equal(&a->gain, &b->gain, sizeof a->gain);
	assert_memory_equal(&a->gain_written, &b->gain_written, sizeof a->gain);
	assert_int_equal(a->gain_unit, b->gain_unit);
	assert_int_equal(a->invert, b->invert);
	assert_memory_equal(&a->dead, &b->dead, sizeof a->dead);
}

static void
table_equal(const struct dial_bind *a, const struct dial_bind *b)
{
	assert_int_equal(a->ndial, b->ndial);
	for (int i = 0; i < a->ndial; i++)
		dial_equal(&a->dial[i], &b->dial[i]);
	assert_int_equal(a->nbutton, b->nbutton);
	for (int i = 0; i < a->nbutton; i++) {
		assert_int_equal(a->button[i].code, b->button[i].code);
		assert_int_equal(a->button[i].edge, b->button[i].edge);
		assert_string_equal(a->button[i].command, b->button[i].command);
	}
}

/* t written; the caller frees the text */
static char *
written(const struct dial_bind *t)
{
	char *text = NULL;
	size_t n = 0;
	FILE *f = open_memstream(&text, &n);
	assert_int_equal(dial_bind_write(f, t), 0);
	fclose(f);
	return text;
}

static void
test_written_and_read_back_is_the_same(void **unused)
{
	(void)unused;
	dial_bind_init(&table);
	parse_with("bindings 1\n"
		 "dial Panel.Dial1 dof 0 gain=0.5deg   # comment\n"
		 "dial  Panel.Dial2  camera sweep_h  invert gain=1deg\n"
		 "dial Panel.Dial3 behavior elevation gain=1mm dead=0.2\n"
		 "dial Panel.Dial4 joint jack elbow_r 2 gain=0.30000000000000004cm dead=1e-300\n"
		 "dial x manip rz gain=-7.5e-05rad\n"
		 "dial y camera zoom\n"
		 "button BTN_0 \"undo\"\n"
		 "button BTN_1 \"settle frames=30\" on=release\n"
		 "button 0x2ff \"say \\\"hi\\\" \\\\ # not a comment\" on=press\n"
		 "button 2 undo on=release\n",
		 NULL, &table);
	char *text = written(&table);
	assert_string_equal(text,
			    "bindings 1\n"
			    "dial Panel.Dial1 dof 0 gain=0.5deg\n"
			    "dial Panel.Dial2 camera sweep_h gain=1deg invert\n"
			    "dial Panel.Dial3 behavior elevation gain=1mm dead=0.2\n"
			    "dial Panel.Dial4 joint jack elbow_r 2 gain=0.30000000000000004cm "
			    "dead=1e-300\n"
			    "dial x manip rz gain=-7.5e-05rad\n"
			    "dial y camera zoom gain=1\n"
			    "button BTN_0 \"undo\"\n"
			    "button BTN_1 \"settle frames=30\" on=release\n"
			    "button 767 \"say \\\"hi\\\" \\\\ # not a comment\"\n"
			    "button 2 \"undo\" on=release\n");
	/* read back: the same table, and written again the same text */
	parse_with(text, NULL, &table_b);
	table_equal(&table, &table_b);
	char *again = written(&table_b);
	assert_string_equal(again, text);
	free(again);
	free(text);
	/* the sample file too */
	char err[256];
	const struct dial_bind_lookup by_map = { dial_bind_find_in_map, &panel };
	if (can_map_read("tests/input/can/panel.map", &panel, err, sizeof err) ||
	    dial_bind_read("tools/panel.bindings", &by_map, &table, err, sizeof err))
		fail_msg("%s", err);
	text = written(&table);
	if (dial_bind_parse(text, strlen(text), "w", &by_map, &table_b, err, sizeof err))
		fail_msg("%s", err);
	table_equal(&table, &table_b);
	free(text);
}

/* ---- the dials ---- */

static void
test_relative_dials(void **unused)
{
	(void)unused;
	dial_bind_init(&table);
	parse_ok("bindings 1\n"
		 "dial Panel.Dial1 dof 0 gain=0.5deg\n"
		 "dial Panel.Dial2 camera sweep_h gain=2deg invert\n"
		 "dial Panel.Dial3 behavior elevation gain=1mm dead=0.2\n",
		 &table);
	/* the first value only sets the reference, wherever the dial stands */
	still(0, 100);
	/* then half a degree per unit of change: 4 units are 2 degrees, -1 is -0.5 */
	struct dial_action a;
	assert_int_equal(turn(0, 104, &a), 1);
	assert_int_equal(a.kind, DIAL_ACTION_MOVE);
	assert_int_equal(a.binding, 0);
	assert_ptr_equal(a.target, &table.dial[0].target);
	assert_near(a.delta, 2 * DEG, 1e-15);
	assert_near(moved(0, 103), -0.5 * DEG, 1e-15);
	/* no change, no action */
	still(0, 103);
	/* invert: 2 degrees per unit, the other way */
	still(1, -5);
	assert_near(moved(1, -4.5), -1 * DEG, 1e-15);
	assert_near(moved(1, -6), 3 * DEG, 1e-15);
	/* the dead zone: changes up to 0.2 move nothing and keep the reference,
	   so a slow turn adds up until it passes */
	still(2, 10);
	still(2, 10.1);
	still(2, 9.85);
	still(2, 10.2);
	assert_near(moved(2, 10.25), 0.25 * 0.001, 1e-15);
	still(2, 10.35);
	assert_near(moved(2, 9.75), -0.5 * 0.001, 1e-15);
	assert_int_equal(table.dead, 4);
	/* a dial nothing is bound to gives nothing */
	still(3, 1);
	still(3, 2);
	/* codes beyond the panel's axes are ignored */
	still(4000, 1);
	still(4000, 2);
}

static void
test_stale_nan_and_unplugged_dials_start_afresh(void **unused)
{
	(void)unused;
	dial_bind_init(&table);
	parse_ok("bindings 1\ndial Panel.Dial1 manip x gain=1cm\n", &table);
	still(0, 1);
	assert_near(moved(0, 3), 0.02, 1e-15);
	/* stale: nothing, and the next value is a new reference */
	struct input_event_rec e = valuator(0, 3);
	e.flags = INPUT_F_STALE;
	struct dial_action a;
	assert_int_equal(dial_bind_feed(&table, &e, &a, 1), 0);
	still(0, 50);
	assert_near(moved(0, 51), 0.01, 1e-15);
	/* NaN and infinities are ignored and counted; the reference stays */
	still(0, NAN);
	still(0, INFINITY);
	still(0, -INFINITY);
	assert_int_equal(table.nonfinite, 3);
	assert_near(moved(0, 52), 0.01, 1e-15);
	/* a change too large for a finite delta moves only the reference */
	assert_near(moved(0, -1.5e308), 0.01 * -1.5e308, 1e292);
	command_ok("bind dial Panel.Dial1 manip x gain=10");
	still(0, 1.5e308); /* 10 * 3e308 is no double */
	assert_int_equal(table.overflow, 1);
	assert_near(moved(0, 1.4e308), 10 * -0.1e308, 1e293);
	command_ok("bind dial Panel.Dial1 manip x gain=1cm");
	assert_int_equal(dial_bind_feed(&table, &e, &a, 1), 0); /* stale again */
	/* the panel unplugged, or plugged in: every dial starts afresh */
	still(0, 1);
	assert_near(moved(0, 2), 0.01, 1e-15);
	e = (struct input_event_rec){ .kind = INPUT_REMOVED, .code = INPUT_CLASS_PANEL };
	assert_int_equal(dial_bind_feed(&table, &e, &a, 1), 0);
	still(0, 7);
	assert_near(moved(0, 8), 0.01, 1e-15);
	e.kind = INPUT_ADDED;
	assert_int_equal(dial_bind_feed(&table, &e, &a, 1), 0);
	still(0, 20);
	/* a mouse coming or going does not */
	e = (struct input_event_rec){ .kind = INPUT_REMOVED, .code = INPUT_CLASS_MOUSE };
	assert_int_equal(dial_bind_feed(&table, &e, &a, 1), 0);
	assert_near(moved(0, 21), 0.01, 1e-15);
	/* and dial_bind_reset, for the caller's own reasons */
	dial_bind_reset(&table);
	still(0, 30);
	assert_near(moved(0, 29), -0.01, 1e-15);
	/* no room for the action: counted lost, the reference still moves */
	e = valuator(0, 31);
	assert_int_equal(dial_bind_feed(&table, &e, &a, 0), 0);
	assert_int_equal(table.lost, 1);
	assert_near(moved(0, 32), 0.01, 1e-15);
	/* other kinds of event give nothing */
	int kinds[] = { INPUT_MOTION, INPUT_POINTER, INPUT_WHEEL, INPUT_KEY, INPUT_FRAME, 200 };
	for (int i = 0; i < 6; i++) {
		e = (struct input_event_rec){ .kind = (uint8_t)kinds[i], .code = 0, .x = 5 };
		assert_int_equal(dial_bind_feed(&table, &e, &a, 1), 0);
	}
}

static void
test_several_dials_one_target(void **unused)
{
	(void)unused;
	dial_bind_init(&table);
	parse_ok("bindings 1\n"
		 "dial Panel.Dial1 manip ry gain=1deg\n"
		 "dial Panel.Dial2 manip ry gain=0.1deg\n",
		 &table);
	still(0, 0);
	still(1, 0);
	struct dial_action a;
	assert_int_equal(turn(0, 10, &a), 1);
	assert_int_equal(a.target->kind, DIAL_TARGET_MANIP);
	assert_int_equal(a.target->axis, DIAL_MANIP_RY);
	assert_near(a.delta, 10 * DEG, 1e-15);
	assert_int_equal(turn(1, 10, &a), 1);
	assert_int_equal(a.binding, 1);
	assert_int_equal(a.target->axis, DIAL_MANIP_RY);
	assert_near(a.delta, 1 * DEG, 1e-15);
}

/* ---- buttons ---- */

static void
test_buttons_run_commands(void **unused)
{
	(void)unused;
	dial_bind_init(&table);
	parse_ok("bindings 1\n"
		 "button BTN_0 \"undo\"\n"
		 "button BTN_1 \"settle frames=30\" on=release\n"
		 "button BTN_TRIGGER_HAPPY1 \"grab jack right box\" on=press\n"
		 "button BTN_TRIGGER_HAPPY1 \"drop jack right\" on=release\n",
		 &table);
	assert_string_equal(pressed(BTN_0, 1), "undo");
	assert_null(pressed(BTN_0, 0));
	assert_null(pressed(BTN_1, 1));
	assert_string_equal(pressed(BTN_1, 0), "settle frames=30");
	assert_string_equal(pressed(BTN_TRIGGER_HAPPY1, 1), "grab jack right box");
	assert_string_equal(pressed(BTN_TRIGGER_HAPPY1, 0), "drop jack right");
	/* a repeat is no press; an unbound button is nothing */
	assert_null(pressed(BTN_0, 2));
	assert_null(pressed(BTN_2, 1));
	/* a button's code as a valuator's is no button */
	struct dial_action a;
	still(BTN_0, 1);
	assert_int_equal(turn(BTN_0, 2, &a), 0);
}

/* ---- run time ---- */

static void
test_bind_and_unbind_at_run_time(void **unused)
{
	(void)unused;
	dial_bind_init(&table);
	parse_ok("bindings 1\n"
		 "dial Panel.Dial1 dof 0 gain=0.5deg\n"
		 "dial Panel.Dial2 camera sweep_h gain=1deg\n"
		 "button BTN_0 undo\n",
		 &table);
	still(0, 0);
	/* bind replaces the dial's binding in its place; the reference holds */
	command_ok("bind dial Panel.Dial1 dof 2 gain=1deg invert");
	assert_int_equal(table.ndial, 2);
	assert_int_equal(table.dial[0].target.dof, 2);
	assert_near(moved(0, 3), -3 * DEG, 1e-15);
	/* a new dial goes last */
	command_ok("bind dial Panel.Dial3 manip z gain=1mm dead=0.5");
	assert_int_equal(table.ndial, 3);
	assert_string_equal(table.dial[2].name, "Panel.Dial3");
	assert_int_equal(table.dial[2].index, 2);
	/* a dial followed while unbound moves from where it was */
	table.dial[2].dead = 0;
	still(3, 1);
	command_ok("bind dial Panel.Dial4 manip x gain=1m");
	assert_near(moved(3, 1.5), 0.5, 1e-15);
	/* buttons: replace the press's command, add a release's */
	command_ok("bind button BTN_0 redo");
	assert_int_equal(table.nbutton, 1);
	assert_string_equal(pressed(BTN_0, 1), "redo");
	command_ok("bind button BTN_0 undo on=release");
	assert_int_equal(table.nbutton, 2);
	assert_string_equal(pressed(BTN_0, 0), "undo");
	command_ok("bind button 0x101 settle");
	assert_int_equal(table.button[2].code, BTN_1);
	/* refusals leave the table */
	command_refused("bind dial Panel.Dial9 dof 0", "the panel has no dial 'Panel.Dial9'");
	command_refused("bind dial Panel.Dial1 dof 9", "0..5");
	command_refused("bind dial Panel.Dial1 camera zoom gain=1deg", "a length");
	command_refused("bind button BTN_0", "button BUTTON COMMAND");
	command_refused("bind knob x", "bind dial ...");
	command_refused("bind", "bind dial ...");
	command_refused("unbind dial Panel.Dial7", "'Panel.Dial7' is not bound");
	command_refused("unbind dial", "unbind dial DIAL");
	command_refused("unbind dial Panel.Dial1 now", "unbind dial DIAL");
	command_refused("unbind button BTN_5", "has no command");
	command_refused("unbind button BTN_1 on=release", "has no command on that edge");
	command_refused("unbind button BTN_0 on=hold", "unbind button BUTTON");
	command_refused("unbind knob", "unbind dial DIAL, or unbind button");
	/* unbind a dial: the others keep their order; the dial moves nothing more */
	command_ok("unbind dial Panel.Dial1");
	assert_int_equal(table.ndial, 3);
	assert_string_equal(table.dial[0].name, "Panel.Dial2");
	assert_string_equal(table.dial[1].name, "Panel.Dial3");
	still(0, 10);
	/* unbind one edge, then both */
	command_ok("unbind button BTN_0 on=press");
	assert_null(pressed(BTN_0, 1));
	assert_string_equal(pressed(BTN_0, 0), "undo");
	command_ok("bind button BTN_0 redo on=press");
	command_ok("unbind button BTN_0");
	assert_int_equal(table.nbutton, 1);
	assert_int_equal(table.button[0].code, BTN_1);
	/* the table full: a new dial is refused, a replacement is not */
	dial_bind_init(&table);
	for (int i = 0; i < DIAL_BIND_MAX_DIALS; i++) {
		snprintf(table.dial[i].name, sizeof table.dial[i].name, "d%d", i);
		table.dial[i].index = -1;
	}
	table.ndial = DIAL_BIND_MAX_DIALS;
	snprintf(table.dial[5].name, sizeof table.dial[5].name, "Panel.Dial2");
	command_refused("bind dial Panel.Dial1 dof 1", "too many dials");
	command_ok("bind dial Panel.Dial2 dof 1");
	assert_int_equal(table.dial[5].index, 1);
	assert_int_equal(table.ndial, DIAL_BIND_MAX_DIALS);
	/* an error buffer is optional */
	const char *w[] = { "unbind" };
	assert_int_equal(dial_bind_command(&table, w, 1, NULL, NULL, 0), -1);
}

static void
test_names_resolved_later(void **unused)
{
	(void)unused;
	char err[256];
	const char *text = "bindings 1\n"
			   "dial Panel.Dial2 dof 0 gain=1rad\n"
			   "dial Other.Dial dof 1\n";
	dial_bind_init(&table);
	/* no lookup: the names wait; nothing turns */
	assert_int_equal(dial_bind_parse(text, strlen(text), "late", NULL, &table, err, sizeof err),
			 0);
	assert_int_equal(table.dial[0].index, -1);
	still(1, 0);
	still(1, 1);
	/* the panel's map arrives: one name found, one not */
	assert_int_equal(dial_bind_resolve(&table, &lookup), 1);
	assert_int_equal(table.dial[0].index, 1);
	assert_int_equal(table.dial[1].index, -1);
	/* resolving forgot the references */
	still(1, 5);
	assert_near(moved(1, 5.25), 0.25, 1e-15);
	/* a parse keeps the counters and forgets the references */
	table.nonfinite = 7;
	parse_ok("bindings 1\ndial Panel.Dial2 dof 0 gain=1rad\n", &table);
	assert_int_equal(table.nonfinite, 7);
	still(1, 6);
	assert_int_equal(dial_bind_resolve(&table, NULL), 1);
}

/* ---- random events ---- */

/* a value from every corner: ordinary, tiny, huge, NaN, infinite */
static double
random_value(void)
{
	switch ((int)(urand() * 8)) {
	case 0:
		return NAN;
	case 1:
		return urand() < 0.5 ? INFINITY : -INFINITY;
	case 2:
		return span(-1, 1) * 1.7e308;
	case 3:
		return span(-1, 1) * 1e-300;
	case 4:
		return (double)(int)span(-5, 5);
	default:
		return span(-1000, 1000);
	}
}

static void
test_random_events_never_give_non_finite_deltas(void **unused)
{
	(void)unused;
	rng_state = 0x6469616c;
	dial_bind_init(&table);
	parse_ok("bindings 1\n"
		 "dial Panel.Dial1 dof 0 gain=1e300\n"
		 "dial Panel.Dial2 camera zoom gain=-1e-3 invert dead=0.5\n"
		 "dial Panel.Dial3 manip rx gain=90deg dead=1e308\n"
		 "dial Panel.Dial4 behavior torso_axial gain=0\n"
		 "button BTN_0 undo\n"
		 "button BTN_0 redo on=release\n",
		 &table);
#if COUNT_ALLOCS
	long before = allocs;
#endif
	long moves = 0, commands = 0;
	for (long step = 0; step < 100000; step++) {
		struct input_event_rec e = { .kind = INPUT_VALUATOR };
		double r = urand();
		if (r < 0.8) {
			e.code = (uint16_t)(urand() * 6);
			e.x = random_value();
			if (urand() < 0.05)
				e.flags = INPUT_F_STALE;
		} else if (r < 0.95) {
			e.kind = INPUT_BUTTON;
			e.code = urand() < 0.5 ? BTN_0 : (uint16_t)(urand() * 0x300);
			e.value = (int32_t)(urand() * 3);
		} else {
			e.kind = (uint8_t)(urand() * 10);
			e.code = (uint16_t)(urand() * 4);
			e.x = random_value();
		}
		struct dial_action a[4];
		int max = (int)(urand() * 3);
		int n = dial_bind_feed(&table, &e, a, max);
		assert_true(n >= 0 && n <= max && n <= 1);
		for (int i = 0; i < n; i++) {
			if (a[i].kind == DIAL_ACTION_COMMAND) {
				assert_true(a[i].binding >= 0 && a[i].binding < table.nbutton);
				assert_ptr_equal(a[i].command, table.button[a[i].binding].command);
				commands++;
				continue;
			}
			assert_int_equal(a[i].kind, DIAL_ACTION_MOVE);
			if (!isfinite(a[i].delta))
				fail_msg("step %ld: delta %g from x=%g code %u", step,
					 a[i].delta, e.x, e.code);
			assert_true(a[i].delta != 0);
			assert_true(a[i].binding >= 0 && a[i].binding < table.ndial);
			assert_ptr_equal(a[i].target, &table.dial[a[i].binding].target);
			moves++;
		}
	}
#if COUNT_ALLOCS
	assert_int_equal(allocs, before);
#endif
	/* the walk met every case */
	assert_true(moves > 5000);
	assert_true(commands > 1000);
	assert_true(table.nonfinite > 1000);
	assert_true(table.overflow > 100);
	assert_true(table.dead > 100);
	assert_true(table.lost > 1000);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sample_file_binds_the_example_panel),
		cmocka_unit_test(test_every_target_and_unit),
		cmocka_unit_test(test_bad_files_refused_with_their_line),
		cmocka_unit_test(test_written_and_read_back_is_the_same),
		cmocka_unit_test(test_relative_dials),
		cmocka_unit_test(test_stale_nan_and_unplugged_dials_start_afresh),
		cmocka_unit_test(test_several_dials_one_target),
		cmocka_unit_test(test_buttons_run_commands),
		cmocka_unit_test(test_bind_and_unbind_at_run_time),
		cmocka_unit_test(test_names_resolved_later),
		cmocka_unit_test(test_random_events_never_give_non_finite_deltas),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
