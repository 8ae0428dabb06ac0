/*
 * test_prompt.c - a command's missing arguments asked for one by one: the
 * questions for the command table's own usage strings, answers building
 * the line, arguments already typed not asked for, key=value and
 * [optional] parts never asked for, the first of several forms, and every
 * usage of proto/commands.def read without a fault.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "interact/prompt.h"

static struct prompt p;

static void
test_manipulate_joint_asks_a_figure_then_a_joint(void **unused)
{
	(void)unused;
	assert_int_equal(prompt_begin(&p, "manipulate joint FIG JOINT [view=VIEW]", "manipulate joint"), 1);
	assert_int_equal(prompt_asking(&p)->kind, PROMPT_FIGURE);
	assert_string_equal(prompt_asking(&p)->question, "select a figure");
	assert_int_equal(prompt_answer(&p, ""), -1); /* nothing: asked again */
	assert_int_equal(prompt_answer(&p, "jack"), 0);
	assert_int_equal(prompt_asking(&p)->kind, PROMPT_JOINT);
	assert_int_equal(prompt_answer(&p, "elbow_r"), 1);
	assert_null(prompt_asking(&p));
	assert_string_equal(prompt_line(&p), "manipulate joint jack elbow_r");
}

static void
test_what_is_typed_is_not_asked_again(void **unused)
{
	(void)unused;
	/* the figure typed, and a key=value word that is no argument */
	assert_int_equal(prompt_begin(&p, "move hand FIG left|right X,Y,Z [rot=AXIS,ANGLE] [from=palm|wrist]",
				      "move hand jack from=wrist "), 1);
	assert_int_equal(prompt_asking(&p)->kind, PROMPT_CHOICE);
	assert_string_equal(prompt_asking(&p)->question, "left or right?");
	assert_int_equal(prompt_answer(&p, "left"), 0);
	assert_int_equal(prompt_asking(&p)->kind, PROMPT_VALUE);
	assert_string_equal(prompt_asking(&p)->question, "x,y,z?");
	assert_int_equal(prompt_answer(&p, "0.3,1.2,0.4"), 1);
	assert_string_equal(prompt_line(&p), "move hand jack from=wrist left 0.3,1.2,0.4");
	/* everything typed: nothing to ask */
	assert_int_equal(prompt_begin(&p, "get joint FIG JOINT", "get joint jack knee_l"), 0);
	/* nothing but options: nothing to ask */
	assert_int_equal(prompt_begin(&p, "load human [as NAME] [stature=M] [mass=KG] [sex=male|female]",
				      "load human"), 0);
}

static void
test_values_sites_views_and_choices(void **unused)
{
	(void)unused;
	assert_int_equal(prompt_begin(&p, "set joint FIG JOINT VALUE...", "set joint"), 1);
	assert_int_equal(p.narg, 3);
	assert_string_equal(p.arg[2].question, "value?");
	assert_int_equal(prompt_begin(&p, "drag FIG SEG.SITE [start=JOINT] [view=VIEW]", "drag"), 1);
	assert_int_equal(p.arg[1].kind, PROMPT_SITE);
	assert_string_equal(p.arg[1].question, "select a site");
	assert_int_equal(prompt_begin(&p, "pick VIEW X Y", "pick"), 1);
	assert_int_equal(p.arg[0].kind, PROMPT_VIEW);
	assert_int_equal(prompt_begin(&p, "behave FIG on|off", "behave jack"), 1);
	assert_string_equal(prompt_asking(&p)->question, "on or off?");
	assert_int_equal(prompt_begin(&p, "snap site|site_position|face_plane", "snap"), 1);
	assert_string_equal(prompt_asking(&p)->question, "site, site_position or face_plane?");
	/* several forms: the first is asked for */
	assert_int_equal(prompt_begin(&p, "unbind dial DIAL | unbind button BUTTON [on=press|release]",
				      "unbind dial"), 1);
	assert_int_equal(p.narg, 1);
	assert_string_equal(p.arg[0].question, "dial?");
	/* an answer with a space is quoted */
	assert_int_equal(prompt_begin(&p, "save session PATH", "save session"), 1);
	assert_int_equal(prompt_answer(&p, "my poses.session"), 1);
	assert_string_equal(prompt_line(&p), "save session \"my poses.session\"");
	/* a quoted word typed counts as one argument */
	assert_int_equal(prompt_begin(&p, "bind button BUTTON COMMAND [on=press|release]",
				      "bind button BTN_0 \"settle frames=3\""), 0);
	prompt_cancel(&p);
	assert_null(prompt_asking(&p));
}

/* every usage of the command table, asked for from its bare verb and object */
static void
test_every_usage_of_the_table_reads(void **unused)
{
	(void)unused;
	static const struct {
		const char *verb, *object, *usage;
	} table[] = {
#define CMD(verb, obj, mn, mx, fl, fn, usage, reply, summary) { verb, obj, usage },
#include "proto/commands.def"
#undef CMD
	};
	int asked = 0;
	for (size_t i = 0; i < sizeof table / sizeof *table; i++) {
		char line[128];
		snprintf(line, sizeof line, "%s %s", table[i].verb, table[i].object);
		int r = prompt_begin(&p, table[i].usage, line);
		assert_true(r == 0 || r == 1);
		for (int k = 0; r == 1 && k < p.narg; k++) {
			assert_true(p.arg[k].question[0] != '\0');
			/* OBJ[.SEGMENT] is a word of its own: an object, with a segment if wanted */
			assert_true(!strchr(p.arg[k].word, '[') || p.arg[k].kind == PROMPT_FIGURE);
			assert_null(strchr(p.arg[k].word, '='));
		}
		asked += r;
		/* answering every question gives the line its words, one per answer */
		for (int k = 0; r == 1 && prompt_asking(&p); k++)
			prompt_answer(&p, "w");
	}
	assert_true(asked > 40);
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_manipulate_joint_asks_a_figure_then_a_joint),
		cmocka_unit_test(test_what_is_typed_is_not_asked_again),
		cmocka_unit_test(test_values_sites_views_and_choices),
		cmocka_unit_test(test_every_usage_of_the_table_reads),
	};
	return cmocka_run_group_tests(tests, NULL, NULL);
}
