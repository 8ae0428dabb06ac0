/* test_session.c - request words, numbers with units, session and posture text, the family shown */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "test_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pose/attach.h"
#include "pose/behave.h"
#include "figure/kin.h"
#include "daemon/family.h"
#include "daemon/session.h"
#include "daemon/words.h"

static void
test_words_split_quotes_tags_and_limits(void **unused)
{
	(void)unused;
	static struct words w;
	const char *msg;
	const char *line = "#t9  set joint \"a b\" 30deg  \"x\\\"y\"";
	assert_int_equal(words_split(line, strlen(line), &w, &msg), WORDS_OK);
	assert_string_equal(w.tag, "t9");
	assert_int_equal(w.n, 5);
	assert_string_equal(w.w[2], "a b");
	assert_string_equal(w.w[4], "x\"y");
	assert_int_equal(words_split("  % a comment", 13, &w, &msg), WORDS_EMPTY);
	assert_int_equal(words_split("   ", 3, &w, &msg), WORDS_EMPTY);
	assert_int_equal(words_split("set \"open", 9, &w, &msg), WORDS_PARSE);
	assert_int_equal(words_split("# x", 3, &w, &msg), WORDS_PARSE);
	char many[400] = "";
	for (int i = 0; i < 65; i++)
		strcat(many, "w ");
	assert_int_equal(words_split(many, strlen(many), &w, &msg), WORDS_TOO_MANY);
}

static void
test_numbers_take_units_and_refuse_non_finite(void **unused)
{
	(void)unused;
	double v;
	assert_int_equal(words_number("30deg", UNIT_ANGLE, &v), 0);
	assert_near(v, M_PI / 6, 1e-15);
	assert_int_equal(words_number("12cm", UNIT_LENGTH, &v), 0);
	assert_near(v, 0.12, 1e-15);
	assert_int_equal(words_number("-2.5e-1", UNIT_NONE, &v), 0);
	assert_near(v, -0.25, 0);
	const char *bad[] = { "nan", "inf", "-inf", "1e999", "0x10", "30deg", "", "1.2.3", "5kg", "deg" };
	for (size_t i = 0; i < sizeof bad / sizeof *bad; i++)
		assert_int_equal(words_number(bad[i], i == 5 ? UNIT_LENGTH : UNIT_NONE, &v), -1);
	double l[3];
	assert_int_equal(words_list("1,2cm,3mm", UNIT_LENGTH, 3, l), 0);
	assert_near(l[1], 0.02, 1e-15);
	assert_int_equal(words_list("1,2", UNIT_LENGTH, 3, l), -1);
	assert_int_equal(words_list("1,2,3,4", UNIT_LENGTH, 3, l), -1);
	assert_int_equal(words_list("1,,3", UNIT_LENGTH, 3, l), -1);
}

/* an environment with a posed, re-rooted human and constraints */
static void
populate(struct env *e)
{
	char err[200];
	struct human_def hd = human_default_def(HUMAN_FEMALE);
	struct model *m = human_build(&hd, err, sizeof err);
	int f = env_add_figure(e, m, "eve", 1, &hd, NULL);
	assert_true(f >= 0);
	struct env_figure *fg = &e->fig[f];
	srand(4);
	for (int d = 0; d < m->ndof; d++)
		fg->state->q[d] = m->dof_lo[d] + (m->dof_hi[d] - m->dof_lo[d]) * rand() / RAND_MAX;
	kin_update(m, fg->state);
	kin_set_root(m, fg->state, model_find_site(m, "foot_l.balance"));
	/* two sites moved on their segments, the root's one of them, turned */
	struct xform loc = m->site_loc[model_find_site(m, "hand_r.palm")];
	loc.p[1] += 0.0123456789;
	env_place_site(e, f, model_find_site(m, "hand_r.palm"), &loc);
	xform_elementary(0, 2, 1, 0.3, &loc);
	loc.p[0] = 0.01;
	env_place_site(e, f, fg->state->root_site, &loc);
	struct ik_constraint_def c = ik_constraint_default_def();
	c.effector_site = model_find_site(m, "hand_r.palm");
	c.goal_xf.p[0] = 0.123456789012345678;
	c.ori = IK_FRAME;
	c.pos_weight = 0.3;
	c.start_joint = model_find_joint(m, "clavicle_r");
	c.group = 1;
	assert_true(env_add_constraint(e, f, "reach", &c) >= 0);
	c.enabled = 0;
	c.goal_site = model_find_site(m, "shank_l.knee");
	assert_true(env_add_constraint(e, f, NULL, &c) >= 0);
}

static void
test_session_round_trip_is_exact(void **unused)
{
	(void)unused;
	static struct env a, b;
	env_init(&a);
	env_init(&b);
	populate(&a);
	size_t la, lb;
	char *ta = session_to_string(&a, &la), err[300];
	assert_non_null(ta);
	assert_int_equal(session_read(ta, la, ".", NULL, &b, err, sizeof err), 0);
	char *tb = session_to_string(&b, &lb);
	assert_int_equal(la, lb);
	assert_memory_equal(ta, tb, la);
	/* the posture itself, to the bit, and the ids */
	assert_true(state_hash(a.fig[0].model, a.fig[0].state) ==
		    state_hash(b.fig[0].model, b.fig[0].state));
	for (int k = 0; k < a.fig[0].model->nsite; k++)
		assert_memory_equal(&a.fig[0].state->site_xf[k], &b.fig[0].state->site_xf[k],
				    sizeof(struct xform));
	assert_int_equal(env_find_constraint(&b, "reach"), env_find_constraint(&a, "reach"));
	char ida[32], idb[32];
	env_constraint_id(&a, 0, ida);
	env_constraint_id(&b, 0, idb);
	assert_string_equal(ida, idb);
	free(ta);
	free(tb);
	env_clear(&a);
	env_clear(&b);
}

/* a view's field of view round-trips to the bit; a view line written before it had one gets 40 deg */
static void
test_view_field_of_view(void **unused)
{
	(void)unused;
	static struct env a, b;
	env_init(&a);
	env_init(&b);
	struct env_view v = { .used = 1, .width = 320, .height = 240, .icons = 1,
			      .eye = { 0, 1.2, 3 }, .target = { 0, 1, 0 }, .fovy_deg = 0.1 + 27.2 };
	snprintf(v.name, sizeof v.name, "front");
	a.view[0] = v;
	size_t la;
	char *ta = session_to_string(&a, &la), err[300];
	assert_non_null(ta);
	assert_int_equal(session_read(ta, la, ".", NULL, &b, err, sizeof err), 0);
	assert_true(b.view[0].fovy_deg == v.fovy_deg);
	env_clear(&b);
	free(ta);

	const char *old = "session 1\nview front width=320 height=240 icons=1 eye=0,1.2,3 "
			  "target=0,1,0\nend\n";
	assert_int_equal(session_read(old, strlen(old), ".", NULL, &b, err, sizeof err), 0);
	assert_true(b.view[0].fovy_deg == 40);
	env_clear(&b);
	const char *bad[] = {
		"session 1\nview front width=320 height=240 icons=1 eye=0,1.2,3 target=0,1,0 fovy=0\nend\n",
		"session 1\nview front width=320 height=240 icons=1 eye=0,1.2,3 target=0,1,0 fovy=x\nend\n",
		"session 1\nview front width=320 height=240 icons=1 eye=0,1.2,3 target=0,1,0 zoom=2\nend\n",
	};
	for (int i = 0; i < 3; i++) {
		assert_int_equal(session_read(bad[i], strlen(bad[i]), ".", NULL, &b, err, sizeof err),
				 -1);
		env_clear(&b);
	}
}

/* a behaving human whose hand grabbed another figure: the attachment round-trips */
static void
test_attachments_round_trip_and_bad_ones_are_refused(void **unused)
{
	(void)unused;
	static struct env a, b;
	env_init(&a);
	env_init(&b);
	char err[300];
	struct human_def hd = human_default_def(HUMAN_MALE);
	int jack = env_add_figure(&a, human_build(&hd, err, sizeof err), "jack", 1, &hd, NULL);
	int crate = env_add_figure(&a, human_build(&hd, err, sizeof err), "crate", 1, &hd, NULL);
	assert_true(jack >= 0 && crate >= 0);
	a.fig[jack].behave = calloc(1, sizeof *a.fig[jack].behave);
	assert_int_equal(behave_attach(a.fig[jack].behave, a.fig[jack].model, a.fig[jack].state,
				       a.fig[jack].ik, NULL), 0);
	assert_int_equal(attach_grab(&a, jack, 1, crate, err, sizeof err), 0);
	assert_int_equal(attach_grab(&a, jack, 1, crate, err, sizeof err), -1); /* held already */
	assert_int_equal(attach_grab(&a, crate, 0, jack, err, sizeof err), -1); /* crate does not behave */
	size_t la, lb;
	char *ta = session_to_string(&a, &la), *tb;
	assert_non_null(strstr(ta, "\nattach jack limb=hand side=right kind=grab object=crate segment="));
	assert_int_equal(session_read(ta, la, ".", NULL, &b, err, sizeof err), 0);
	tb = session_to_string(&b, &lb);
	assert_int_equal(la, lb);
	assert_memory_equal(ta, tb, la);
	free(tb);
	env_clear(&b);
	/* each field broken in turn: the whole session is refused */
	const char *breaks[][2] = { { "limb=hand", "limb=wing" }, { "side=right", "side=up" },
				    { "kind=grab", "kind=hug" }, { "object=crate", "object=nobody" },
				    { "attach jack", "attach crate" }, { "rel=", "rel=1," } };
	for (size_t i = 0; i < sizeof breaks / sizeof *breaks; i++) {
		char *t = malloc(la + 16), *at = strstr(ta, breaks[i][0]);
		assert_non_null(at);
		size_t head = (size_t)(at - ta), ol = strlen(breaks[i][0]);
		memcpy(t, ta, head);
		strcpy(t + head, breaks[i][1]);
		strcat(t, ta + head + ol);
		env_init(&b);
		assert_int_equal(session_read(t, strlen(t), ".", NULL, &b, err, sizeof err), -1);
		assert_int_equal(env_count(&b), 0);
		free(t);
	}
	free(ta);
	/* unloading the object lets go */
	env_remove_figure(&a, crate);
	assert_int_equal(attach_find(&a, jack, ATTACH_HAND, 1), -1);
	env_clear(&a);
}

/* two members of family f and one other human, f_1 selected among them overlaid */
static void
family_env(struct env *e)
{
	char err[300];
	const char *names[] = { "f_0", "f_1", "jack" };
	for (int i = 0; i < 3; i++) {
		struct human_def hd = human_default_def(HUMAN_FEMALE);
		int slot = env_add_figure(e, human_build(&hd, err, sizeof err), names[i], 1, &hd, NULL);
		assert_int_equal(slot, i);
		struct env_manikin *mk = &e->fig[slot].manikin;
		if (i == 2)
			continue;
		*mk = (struct env_manikin){ .percentile = NAN, .mahalanobis = i ? 2.5 : 0,
					    .member = i, .coverage = 0.9 };
		snprintf(mk->population, sizeof mk->population, "ansur2");
		snprintf(mk->family, sizeof mk->family, "f");
		mk->given[population_column("stature")] = 1;
	}
	e->show = (struct env_show){ .arrange = ENV_SHOW_OVERLAY };
	snprintf(e->show.family, sizeof e->show.family, "f");
	snprintf(e->show.selected, sizeof e->show.selected, "f_1");
}

/* the family shown at the kiosk round-trips with its ghosts; a bad statement is refused whole */
static void
test_a_shown_family_round_trips_and_bad_ones_are_refused(void **unused)
{
	(void)unused;
	static struct env a, b;
	env_init(&a);
	env_init(&b);
	family_env(&a);
	assert_int_equal(family_is_ghost(&a, 0, -1), 1);
	assert_int_equal(family_is_ghost(&a, 0, 0), 0); /* the one a mode is on is drawn as it is */
	assert_int_equal(family_is_ghost(&a, 1, -1), 0);
	assert_int_equal(family_is_ghost(&a, 2, -1), 0);
	size_t la, lb;
	char *ta = session_to_string(&a, &la), *tb, err[300];
	assert_non_null(strstr(ta, "\nshow family f overlay select=f_1 spacing=0\nend\n"));
	assert_int_equal(session_read(ta, la, ".", NULL, &b, err, sizeof err), 0);
	assert_int_equal(b.show.arrange, ENV_SHOW_OVERLAY);
	assert_int_equal(family_selected(&b), 1);
	assert_int_equal(family_is_ghost(&b, 0, -1), 1);
	tb = session_to_string(&b, &lb);
	assert_int_equal(la, lb);
	assert_memory_equal(ta, tb, la);
	free(tb);
	env_clear(&b);
	const char *breaks[][2] = { { "select=f_1", "select=jack" }, { "select=f_1", "select=nobody" },
				    { "overlay select", "sideways select" }, { "spacing=0", "spacing=-1" },
				    { "show family f", "show family g" }, { "show family", "show families" },
				    { " spacing=0", "" } };
	for (size_t i = 0; i < sizeof breaks / sizeof *breaks; i++) {
		char *t = malloc(la + 16), *at = strstr(ta, breaks[i][0]);
		assert_non_null(at);
		size_t head = (size_t)(at - ta), ol = strlen(breaks[i][0]);
		memcpy(t, ta, head);
		strcpy(t + head, breaks[i][1]);
		strcat(t, ta + head + ol);
		env_init(&b);
		assert_int_equal(session_read(t, strlen(t), ".", NULL, &b, err, sizeof err), -1);
		assert_int_equal(env_count(&b), 0);
		assert_int_equal(b.show.arrange, ENV_SHOW_OFF);
		free(t);
	}
	free(ta);
	/* the selected one unloaded: the first member left is; none left: nothing is shown */
	env_remove_figure(&a, 1);
	assert_int_equal(family_selected(&a), 0);
	assert_int_equal(family_is_ghost(&a, 0, -1), 0);
	env_remove_figure(&a, 0);
	assert_int_equal(family_selected(&a), -1);
	ta = session_to_string(&a, &la);
	assert_null(strstr(ta, "\nshow "));
	free(ta);
	env_clear(&a);
}

static void
test_bad_sessions_load_nothing(void **unused)
{
	(void)unused;
	static struct env e, good;
	env_init(&good);
	populate(&good);
	size_t len;
	char *text = session_to_string(&good, &len), err[300];
	const char *cuts[] = { "session 2\n", "sesion 1\nend\n", "session 1\nfigure x slot=0 gen=1 robot\nend\n",
			       "session 1\nq nobody 1,2\nend\n",
			       "session 1\nsite nobody a.b 0,0,0,0,0,0,1\nend\n" };
	for (size_t i = 0; i < sizeof cuts / sizeof *cuts; i++) {
		env_init(&e);
		assert_int_equal(session_read(cuts[i], strlen(cuts[i]), ".", NULL, &e, err, sizeof err), -1);
		assert_int_equal(env_count(&e), 0);
		assert_non_null(strstr(err, "line "));
	}
	/* truncated anywhere before "end": refused whole */
	for (size_t cut = 10; cut + 5 < len; cut += len / 7) {
		env_init(&e);
		assert_int_equal(session_read(text, cut, ".", NULL, &e, err, sizeof err), -1);
		assert_int_equal(env_count(&e), 0);
	}
	/* a value outside its limit */
	char *q = strstr(text, "\nq eve ");
	assert_non_null(q);
	char *broken = strdup(text);
	memcpy(broken + (q - text) + 7, "99", 2);
	env_init(&e);
	assert_int_equal(session_read(broken, len, ".", NULL, &e, err, sizeof err), -1);
	free(broken);
	/* a moved site whose quaternion is not of unit length */
	char *site = strstr(text, "\nsite eve hand_r.palm ");
	assert_non_null(site);
	broken = strdup(text);
	char *w = strchr(broken + (site - text) + 22, ',');
	w = strchr(w + 1, ',');
	w = strchr(w + 1, ','); /* the quaternion's x */
	w[1] = '7';
	env_init(&e);
	assert_int_equal(session_read(broken, len, ".", NULL, &e, err, sizeof err), -1);
	assert_non_null(strstr(err, "unit length"));
	free(broken);
	free(text);
	env_clear(&good);
}

static void
test_posture_file_applies_by_name_and_checks_first(void **unused)
{
	(void)unused;
	static struct env e;
	env_init(&e);
	populate(&e);
	char *buf = NULL, err[300];
	size_t len = 0;
	FILE *f = open_memstream(&buf, &len);
	session_write_posture(&e, 0, f);
	fclose(f);
	struct env_figure *fg = &e.fig[0];
	uint64_t h = state_hash(fg->model, fg->state);
	state_reset(fg->model, fg->state);
	kin_update(fg->model, fg->state);
	assert_int_equal(session_read_posture(&e, 0, buf, len, err, sizeof err), 0);
	assert_true(state_hash(fg->model, fg->state) == h);
	/* an unknown joint changes nothing */
	const char *bad = "posture 1\njoint knee_l 0.1\njoint nojoint 1\nend\n";
	state_reset(fg->model, fg->state);
	kin_update(fg->model, fg->state);
	uint64_t h0 = state_hash(fg->model, fg->state);
	assert_int_equal(session_read_posture(&e, 0, bad, strlen(bad), err, sizeof err), -1);
	assert_true(state_hash(fg->model, fg->state) == h0);
	free(buf);
	env_clear(&e);
}

static char *
slurp(const char *path, size_t *n)
{
	FILE *f = fopen(path, "rb");
	assert_non_null(f);
	fseek(f, 0, SEEK_END);
	long len = ftell(f);
	fseek(f, 0, SEEK_SET);
	char *buf = malloc((size_t)len + 1);
	assert_non_null(buf);
	assert_int_equal(fread(buf, 1, (size_t)len, f), (size_t)len);
	buf[len] = 0;
	fclose(f);
	*n = (size_t)len;
	return buf;
}

/* the figure's site by name, which must exist */
static int
site_of(const struct model *m, const char *name)
{
	int k = model_find_site(m, name);
	if (k < 0)
		fail_msg("no site %s", name);
	return k;
}

/* jack's hands held on the chest and the head, each as named */
static void
assert_hands_on_chest_and_head(const struct env *e)
{
	int f = env_find_figure(e, "jack");
	assert_true(f >= 0);
	const struct env_figure *fg = &e->fig[f];
	assert_non_null(fg->behave);
	assert_int_equal(fg->behave->p.hand[0], HAND_ON_SITE);
	assert_int_equal(fg->behave->p.hand[1], HAND_ON_SITE);
	assert_int_equal(fg->behave->p.hand_site[0], site_of(fg->model, "head.vertex"));
	assert_int_equal(fg->behave->p.hand_site[1], site_of(fg->model, "T5.chest"));
}

/*
 * A session saved before every human carried its landmark sites
 * (tests/sessions/landmarks/README.md) loads as it was: its hands held on
 * the chest and the head (the behaviour state held their sites' indices
 * then, T5.chest 33 and head.vertex 46 of 101), its moved site, root and
 * constraint as named. Written again, the hands' sites are named too.
 */
static void
test_session_from_before_the_landmarks_loads(void **unused)
{
	(void)unused;
	static struct env e, again;
	size_t len, len2;
	char *text = slurp("tests/sessions/landmarks/saved.session", &len), err[300];
	env_init(&e);
	assert_int_equal(session_read(text, len, ".", NULL, &e, err, sizeof err), 0);
	assert_hands_on_chest_and_head(&e);
	const struct env_figure *fg = &e.fig[env_find_figure(&e, "jack")];
	const struct model *m = fg->model;
	int palm = site_of(m, "hand_r.palm");
	assert_true(m->site_moved[palm]);
	assert_near(m->site_pos[3 * palm + 1], -0.06, 1e-15);
	assert_near(m->site_pos[3 * palm + 2], 0.01, 1e-15);
	assert_int_equal(fg->state->root_site, site_of(m, "toes_r.toe"));
	int c = env_find_constraint(&e, "look");
	assert_true(c >= 0);
	assert_int_equal(e.con[c].def.effector_site, site_of(m, "head.between_eyes"));
	assert_int_equal(e.con[c].def.goal_site, palm);

	char *out = session_to_string(&e, &len2);
	assert_non_null(out);
	assert_non_null(strstr(out, " hand_l=head.vertex hand_r=T5.chest\n"));
	env_init(&again);
	assert_int_equal(session_read(out, len2, ".", NULL, &again, err, sizeof err), 0);
	assert_hands_on_chest_and_head(&again);
	env_clear(&again);
	/* a hand's site that the figure does not have: nothing loads */
	char *bad = strstr(out, "hand_r=T5.chest");
	memcpy(bad + 8, "T5.chust", 8);
	env_init(&again);
	assert_int_equal(session_read(out, len2, ".", NULL, &again, err, sizeof err), -1);
	assert_int_equal(env_count(&again), 0);
	free(out);
	free(text);
	env_clear(&e);
}

/*
 * The assessments' settings (set assess) ride in a session: every key
 * written, read back bit for bit; a session from before them (before 4)
 * reads with the defaults (version 1 here); a key unknown, out of its range or not a number
 * loads nothing and leaves the settings as they were.
 */
static void
test_assess_settings_round_trip_and_old_sessions_take_the_defaults(void **unused)
{
	(void)unused;
	static struct env e, back;
	char err[300];
	size_t len, olen;
	struct assess_config cfg = assess_config_default(), got, def = assess_config_default();
	assert_int_equal(assess_config_set(&cfg, "shoulder_raised", 12.5, err, sizeof err), 0);
	assert_int_equal(assess_config_set(&cfg, "out_to_side", 0.1 + 0.2, err, sizeof err), 0);
	env_init(&e);
	char *text = session_to_string_with(&e, &cfg, &len);
	assert_non_null(text);
	assert_non_null(strstr(text, "session 5\n"));
	assert_non_null(strstr(text, " shoulder_raised=12.5 "));
	env_init(&back);
	assert_int_equal(session_read_with(text, len, ".", NULL, &back, &got, err, sizeof err), 0);
	assert_memory_equal(&got, &cfg, sizeof cfg);
	free(text);
	/* written without settings, or older: the defaults */
	text = session_to_string(&e, &len);
	assert_null(strstr(text, "assess"));
	got = cfg;
	assert_int_equal(session_read_with(text, len, ".", NULL, &back, &got, err, sizeof err), 0);
	assert_memory_equal(&got, &def, sizeof def);
	free(text);
	char *old = slurp("tests/sessions/landmarks/saved.session", &olen);
	assert_true(!strncmp(old, "session 1\n", 10)); /* older than the settings */
	got = cfg;
	assert_int_equal(session_read_with(old, olen, ".", NULL, &back, &got, err, sizeof err), 0);
	assert_memory_equal(&got, &def, sizeof def);
	env_clear(&back);
	free(old);
	const char *bad[] = { "session 4\nassess shoulder_raised=99\nend\n",
			      "session 4\nassess shoulder_rised=10\nend\n",
			      "session 4\nassess shoulder_raised=ten\nend\n",
			      "session 4\nassess shoulder_raised\nend\n" };
	for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
		got = cfg;
		env_init(&back);
		assert_int_equal(session_read_with(bad[i], strlen(bad[i]), ".", NULL, &back, &got, err,
						   sizeof err), -1);
		assert_non_null(strstr(err, "line 2: assess"));
		assert_memory_equal(&got, &cfg, sizeof cfg);
	}
}

int
main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_words_split_quotes_tags_and_limits),
		cmocka_unit_test(test_numbers_take_units_and_refuse_non_finite),
		cmocka_unit_test(test_session_round_trip_is_exact),
		cmocka_unit_test(test_view_field_of_view),
		cmocka_unit_test(test_attachments_round_trip_and_bad_ones_are_refused),
		cmocka_unit_test(test_a_shown_family_round_trips_and_bad_ones_are_refused),
		cmocka_unit_test(test_bad_sessions_load_nothing),
		cmocka_unit_test(test_posture_file_applies_by_name_and_checks_first),
		cmocka_unit_test(test_session_from_before_the_landmarks_loads),
		cmocka_unit_test(test_assess_settings_round_trip_and_old_sessions_take_the_defaults),
	};
	return cmocka_run_group_tests_name("session", tests, NULL, NULL);
}
