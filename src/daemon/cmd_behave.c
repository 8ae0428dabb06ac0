/* cmd_behave.c - behaviours through the protocol: switching, parameters, primitives */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pose/attach.h"
#include "daemon/cmd_ctx.h"
#include "figure/kin.h"

/* the figure's slot when its behaviours are on, else -1 with the error set */
static int
behaving(struct cmd_ctx *c, const char *ref)
{
	int fig = cmd_figure(c, ref);
	if (fig >= 0 && !c->d->env.fig[fig].behave) {
		cmd_fail(c, "bad-argument", "behaviours are off for %s (behave %s on)",
			 c->d->env.fig[fig].name, c->d->env.fig[fig].name);
		return -1;
	}
	return fig;
}

int
cmd_behave(struct cmd_ctx *c)
{
	int fig = cmd_figure(c, c->argv[0]);
	if (fig < 0)
		return -1;
	struct env_figure *f = &c->d->env.fig[fig];
	int on = !strcmp(c->argv[1], "on");
	if (!on && strcmp(c->argv[1], "off"))
		return cmd_fail(c, "bad-argument", "behave FIG on|off");
	if (!on) {
		attach_release_all(&c->d->env, fig);
		free(f->behave);
		f->behave = NULL;
		f->ik_stale = 1;
		return 0;
	}
	if (f->behave)
		return 0;
	env_sync_solver(&c->d->env, fig);
	struct behave *b = calloc(1, sizeof *b);
	if (!b)
		return cmd_fail(c, "internal", "out of memory");
	if (behave_attach(b, f->model, f->state, f->ik, NULL) < 0) {
		free(b);
		f->ik_stale = 1;
		return cmd_fail(c, "bad-argument", "%s is not a standard human figure", f->name);
	}
	f->behave = b;
	return 0;
}

static int
on_off(struct cmd_ctx *c, const char *key, int *dest)
{
	const char *v = cmd_key(c, key);
	if (!v)
		return 0;
	if (strcmp(v, "on") && strcmp(v, "off"))
		return cmd_fail(c, "bad-argument", "%s=on|off", key);
	*dest = !strcmp(v, "on");
	return 0;
}

static int
aim_point(struct cmd_ctx *c, const char *key, int *on, double p[3])
{
	const char *v = cmd_key(c, key);
	if (!v)
		return 0;
	if (!strcmp(v, "release")) {
		*on = 0;
		return 0;
	}
	if (words_list(v, UNIT_LENGTH, 3, p) < 0)
		return cmd_fail(c, "bad-number", "%s=X,Y,Z or %s=release", key, key);
	*on = 1;
	return 0;
}

static int
hand_mode(struct cmd_ctx *c, const struct model *m, const char *key, struct behave_params *p,
	  int side)
{
	const char *v = cmd_key(c, key);
	if (!v)
		return 0;
	static const struct {
		const char *name;
		enum hand_behavior mode;
	} modes[] = { { "free", HAND_FREE }, { "hold", HAND_HOLD_GLOBAL }, { "hips", HAND_ON_HIPS },
		      { "knees", HAND_ON_KNEES } };
	for (size_t i = 0; i < sizeof modes / sizeof *modes; i++)
		if (!strcmp(v, modes[i].name)) {
			p->hand[side] = modes[i].mode;
			return 0;
		}
	int site = model_find_site(m, v);
	if (site < 0)
		return cmd_fail(c, "bad-argument", "%s=free|hold|hips|knees|SEG.SITE", key);
	p->hand[side] = HAND_ON_SITE;
	p->hand_site[side] = site;
	return 0;
}

static int
choice(struct cmd_ctx *c, const char *key, const char *a, const char *b, int va, int vb, int *dest)
{
	const char *v = cmd_key(c, key);
	if (!v)
		return 0;
	if (!strcmp(v, a))
		*dest = va;
	else if (!strcmp(v, b))
		*dest = vb;
	else
		return cmd_fail(c, "bad-argument", "%s=%s|%s", key, a, b);
	return 0;
}

static const char *const behavior_keys[] = {
	"foot", "foot_l", "foot_r", "heel", "heel_l", "heel_r", "elevation", "torso", "head", "eyes",
	"hands", "hand_l", "hand_r", "follow_feet", "pelvis_follows", "auto_root", "com_root",
	"step", "twist_step", "foot_orient", "hand_orient", "stability", "seated"
};

int
cmd_set_behavior(struct cmd_ctx *c)
{
	int fig = behaving(c, c->argv[0]);
	if (fig < 0)
		return -1;
	struct env_figure *f = &c->d->env.fig[fig];
	struct behave *b = f->behave;
	for (int i = 1; i < c->argc; i++) {
		int known = 0;
		for (size_t k = 0; k < sizeof behavior_keys / sizeof *behavior_keys; k++)
			known |= words_is_key(c->argv[i], behavior_keys[k]);
		if (!known)
			return cmd_fail(c, "bad-argument", "unexpected '%.60s'", c->argv[i]);
	}
	struct behave_params p = b->p;
	int foot = -1, heel = -1, elev = p.hold_elevation, torso = -1;
	if (choice(c, "foot", "pivot", "hold", FOOT_PIVOT, FOOT_HOLD_GLOBAL, &foot) < 0 ||
	    choice(c, "heel", "floor", "rise", HEEL_KEEP_ON_FLOOR, HEEL_ALLOW_RISE, &heel) < 0 ||
	    choice(c, "elevation", "hold", "free", 1, 0, &elev) < 0)
		return -1;
	if (foot >= 0)
		p.foot[0] = p.foot[1] = (enum foot_behavior)foot;
	if (heel >= 0)
		p.heel[0] = p.heel[1] = (enum heel_behavior)heel;
	for (int k = 0; k < 2; k++) {
		int fk = p.foot[k], hk = p.heel[k];
		if (choice(c, k ? "foot_r" : "foot_l", "pivot", "hold", FOOT_PIVOT, FOOT_HOLD_GLOBAL, &fk) < 0 ||
		    choice(c, k ? "heel_r" : "heel_l", "floor", "rise", HEEL_KEEP_ON_FLOOR, HEEL_ALLOW_RISE, &hk) < 0)
			return -1;
		p.foot[k] = (enum foot_behavior)fk;
		p.heel[k] = (enum heel_behavior)hk;
	}
	p.hold_elevation = elev;
	if (choice(c, "foot_orient", "global", "line", 0, 1, &p.foot_follows_line) < 0 ||
	    choice(c, "hand_orient", "global", "laban", 0, 1, &p.hands_laban) < 0)
		return -1;
	const char *th = cmd_key(c, "stability");
	if (th && (words_number(th, UNIT_LENGTH, &p.stability_threshold) < 0 ||
		   !(fabs(p.stability_threshold) <= 1)))
		return cmd_fail(c, "bad-number", "stability=LENGTH: the margin (-1 m..1 m) that raises the alert");
	const char *t = cmd_key(c, "torso");
	if (t) {
		torso = !strcmp(t, "vertical") ? TORSO_KEEP_VERTICAL : !strcmp(t, "global") ? TORSO_HOLD_GLOBAL
			: !strcmp(t, "free") ? TORSO_FREE : -1;
		if (torso < 0)
			return cmd_fail(c, "bad-argument", "torso=vertical|global|free");
		p.torso = (enum torso_behavior)torso;
	}
	if (aim_point(c, "head", &p.fixate_head, p.head_point) < 0 ||
	    aim_point(c, "eyes", &p.fixate_eyes, p.eyes_point) < 0 ||
	    hand_mode(c, f->model, "hands", &p, 0) < 0 || hand_mode(c, f->model, "hands", &p, 1) < 0 ||
	    hand_mode(c, f->model, "hand_l", &p, 0) < 0 || hand_mode(c, f->model, "hand_r", &p, 1) < 0 ||
	    on_off(c, "follow_feet", &p.balance_follows_feet) < 0 ||
	    on_off(c, "pelvis_follows", &p.pelvis_follows_feet) < 0 ||
	    on_off(c, "auto_root", &p.auto_root) < 0 || on_off(c, "com_root", &p.root_through_com) < 0 ||
	    on_off(c, "step", &p.step_when_losing_balance) < 0 ||
	    on_off(c, "twist_step", &p.step_when_twisted) < 0 || on_off(c, "seated", &p.seated) < 0)
		return -1;
	env_sync_solver(&c->d->env, fig);
	behave_set_params(b, f->model, f->state, f->ik, &p);
	return 0;
}

static const char *
foot_name(enum foot_behavior m)
{
	return m == FOOT_PIVOT ? "pivot" : "hold";
}

int
cmd_get_behavior(struct cmd_ctx *c)
{
	int fig = behaving(c, c->argv[0]);
	if (fig < 0)
		return -1;
	const struct behave *b = c->d->env.fig[fig].behave;
	static const char *const hands[] = { "free", "hold", "hips", "knees", "site" };
	static const char *const torso[] = { "vertical", "global", "free" };
	static const char *const roots[] = { "left foot", "right foot", "lower torso" };
	json_t *p = json_object(), *bal = json_object();
	json_object_set_new(p, "foot_l", json_string(foot_name(b->p.foot[0])));
	json_object_set_new(p, "foot_r", json_string(foot_name(b->p.foot[1])));
	json_object_set_new(p, "heel_l", json_string(b->p.heel[0] == HEEL_KEEP_ON_FLOOR ? "floor" : "rise"));
	json_object_set_new(p, "heel_r", json_string(b->p.heel[1] == HEEL_KEEP_ON_FLOOR ? "floor" : "rise"));
	json_object_set_new(p, "elevation", json_string(b->p.hold_elevation ? "hold" : "free"));
	json_object_set_new(p, "torso", json_string(torso[b->p.torso]));
	json_object_set_new(p, "head", b->p.fixate_head ? cmd_vec(b->p.head_point, 3) : json_string("release"));
	json_object_set_new(p, "eyes", b->p.fixate_eyes ? cmd_vec(b->p.eyes_point, 3) : json_string("release"));
	json_object_set_new(p, "hand_l", json_string(hands[b->p.hand[0]]));
	json_object_set_new(p, "hand_r", json_string(hands[b->p.hand[1]]));
	json_object_set_new(p, "follow_feet", json_boolean(b->p.balance_follows_feet));
	json_object_set_new(p, "pelvis_follows", json_boolean(b->p.pelvis_follows_feet));
	json_object_set_new(p, "auto_root", json_boolean(b->p.auto_root));
	json_object_set_new(p, "com_root", json_boolean(b->p.root_through_com));
	json_object_set_new(p, "step", json_boolean(b->p.step_when_losing_balance));
	json_object_set_new(p, "twist_step", json_boolean(b->p.step_when_twisted));
	json_object_set_new(p, "foot_orient", json_string(b->p.foot_follows_line ? "line" : "global"));
	json_object_set_new(p, "hand_orient", json_string(b->p.hands_laban ? "laban" : "global"));
	json_object_set_new(p, "seated", json_boolean(b->p.seated));
	json_object_set_new(p, "stability", json_real(b->p.stability_threshold));
	json_object_set_new(bal, "x", json_real(b->bal.x));
	json_object_set_new(bal, "z", json_real(b->bal.z));
	json_object_set_new(bal, "margin", json_real(b->bal.margin));
	json_object_set_new(bal, "point", cmd_vec(b->bal.point, 2));
	json_object_set_new(bal, "held", cmd_vec(b->bal_point, 2));
	json_object_set_new(bal, "low", json_boolean(b->stability_low));
	json_object_set_new(c->result, "parameters", p);
	json_object_set_new(c->result, "root", json_string(roots[b->root]));
	json_object_set_new(c->result, "balance", bal);
	json_object_set_new(c->result, "steps", json_integer(b->steps_taken));
	json_object_set_new(c->result, "stepping", json_boolean(b->step.active));
	json_object_set_new(c->result, "attachments", cmd_attachments(&c->d->env, fig));
	return 0;
}

/* the common head of the primitives: the figure, synced, and its behaviour */
static struct behave *
primitive(struct cmd_ctx *c, struct env_figure **f)
{
	int fig = behaving(c, c->argv[0]);
	if (fig < 0)
		return NULL;
	env_sync_solver(&c->d->env, fig);
	*f = &c->d->env.fig[fig];
	return (*f)->behave;
}

/* a hand or foot moved by hand stops following the object it held a place on */
static void
drop_local_hold(struct cmd_ctx *c, const struct env_figure *f, enum attach_limb limb, int side)
{
	struct env *e = &c->d->env;
	int fig = (int)(f - e->fig), i = attach_find(e, fig, limb, side);
	if (i >= 0 && e->att[i].kind == ATTACH_LOCAL)
		attach_release(e, fig, limb, side);
}

int
cmd_move_foot(struct cmd_ctx *c)
{
	struct env_figure *f;
	struct behave *b = primitive(c, &f);
	int side;
	double p[3], yaw = 0;
	if (!b || (side = cmd_side(c, c->argv[1])) < 0)
		return -1;
	if (words_list(c->argv[2], UNIT_LENGTH, 3, p) < 0)
		return cmd_fail(c, "bad-number", "X,Y,Z: three lengths");
	const char *y = cmd_key(c, "yaw");
	if ((c->argc == 4 && !y) || (y && words_number(y, UNIT_ANGLE, &yaw) < 0))
		return cmd_fail(c, "bad-argument", "yaw=ANGLE");
	struct xform g = f->state->site_xf[behave_foot_site(b, side)];
	memcpy(g.p, p, sizeof p);
	if (y) { /* turned about the vertical */
		double r[9];
		mathx_rot_y(yaw, r);
		mathx_mat3_mul(r, g.r, g.r);
	}
	drop_local_hold(c, f, ATTACH_FOOT, side);
	behave_move_foot(b, f->model, f->state, f->ik, side, &g);
	return 0;
}

int
cmd_move_com(struct cmd_ctx *c)
{
	struct env_figure *f;
	struct behave *b = primitive(c, &f);
	double v[3] = { 0, 0, 0 };
	if (!b)
		return -1;
	for (int i = 1; i < c->argc; i++)
		if (words_number(c->argv[i], UNIT_LENGTH, &v[i - 1]) < 0)
			return cmd_fail(c, "bad-number", "DX DZ [DY]: lengths");
	behave_move_com(b, f->model, f->state, f->ik, v[0], v[1], v[2]);
	return 0;
}

int
cmd_bend_torso(struct cmd_ctx *c)
{
	struct env_figure *f;
	struct behave *b = primitive(c, &f);
	double total[3];
	if (!b)
		return -1;
	for (int i = 0; i < 3; i++)
		if (words_number(c->argv[1 + i], UNIT_ANGLE, &total[i]) < 0)
			return cmd_fail(c, "bad-number", "FORWARD LATERAL AXIAL: angles");
	struct spine_flavor fl = spine_bend_from_waist();
	const char *name = cmd_key(c, "flavor");
	if (name && spine_flavor_named(name, &fl) < 0)
		return cmd_fail(c, "bad-argument", "flavor=waist|neck");
	/* or the flavour's joints one by one (§5.5.3): spine_0 (L5/S1) .. spine_17 (the neck) */
	static const char *const ends[] = { "bottom", "top", "initiator", "resistor" };
	int *field[] = { &fl.bottom, &fl.top, &fl.initiator, &fl.resistor };
	for (int i = 4; i < c->argc; i++) {
		int known = words_is_key(c->argv[i], "flavor");
		for (int k = 0; k < 4; k++)
			known |= words_is_key(c->argv[i], ends[k]);
		if (!known)
			return cmd_fail(c, "bad-argument", "unexpected '%.60s'", c->argv[i]);
	}
	for (int k = 0; k < 4; k++) {
		const char *v = cmd_key(c, ends[k]);
		int j, used = 0;
		if (!v)
			continue;
		if (sscanf(v, "spine_%d%n", &j, &used) != 1 || v[used] || j < 0 || j >= SPINE_NJNT)
			return cmd_fail(c, "bad-argument", "%s=spine_0..spine_%d", ends[k], SPINE_NJNT - 1);
		*field[k] = j;
	}
	double shortfall[3];
	if (spine_distribute(f->model, &fl, total, (double[SPINE_NDOF]){ 0 }, shortfall) < 0 ||
	    behave_bend_torso(b, f->model, f->state, f->ik, total, &fl) < 0)
		return cmd_fail(c, "bad-argument", "not a bend this figure's spine can take");
	json_object_set_new(c->result, "shortfall", cmd_vec(shortfall, 3));
	return 0;
}

int
cmd_rotate_pelvis(struct cmd_ctx *c)
{
	struct env_figure *f;
	struct behave *b = primitive(c, &f);
	double r[9];
	int given;
	if (!b || cmd_rotation(c, r, &given) < 0)
		return -1;
	if (!given)
		return cmd_fail(c, "arity", "rotate pelvis FIG rot=AXIS,ANGLE");
	behave_rotate_pelvis(b, f->model, f->state, f->ik, r);
	return 0;
}

int
cmd_move_hand(struct cmd_ctx *c)
{
	struct env_figure *f;
	struct behave *b = primitive(c, &f);
	int side;
	double p[3], r[9];
	int turned;
	if (!b || (side = cmd_side(c, c->argv[1])) < 0)
		return -1;
	if (words_list(c->argv[2], UNIT_LENGTH, 3, p) < 0)
		return cmd_fail(c, "bad-number", "X,Y,Z: three lengths");
	for (int i = 3; i < c->argc; i++)
		if (!words_is_key(c->argv[i], "rot") && !words_is_key(c->argv[i], "from"))
			return cmd_fail(c, "bad-argument", "unexpected '%.60s'", c->argv[i]);
	const char *from = cmd_key(c, "from");
	if (from && strcmp(from, "palm") && strcmp(from, "wrist"))
		return cmd_fail(c, "bad-argument", "from=palm|wrist");
	if (cmd_rotation(c, r, &turned) < 0)
		return -1;
	struct xform g = f->state->site_xf[b->s_palm[side]];
	memcpy(g.p, p, sizeof p);
	if (turned)
		memcpy(g.r, r, sizeof r);
	else if (b->p.hands_laban)
		behave_predict_hand(b, f->state, side, &g);
	drop_local_hold(c, f, ATTACH_HAND, side);
	behave_move_hand(b, f->model, f->state, f->ik, side, &g, from && !strcmp(from, "wrist"));
	return 0;
}

static int
move_aim(struct cmd_ctx *c, int eyes)
{
	struct env_figure *f;
	struct behave *b = primitive(c, &f);
	double p[3];
	if (!b)
		return -1;
	if (words_list(c->argv[1], UNIT_LENGTH, 3, p) < 0)
		return cmd_fail(c, "bad-number", "X,Y,Z: three lengths");
	if (eyes)
		behave_move_eyes(b, f->ik, p);
	else
		behave_move_head(b, f->ik, p);
	return 0;
}

int
cmd_move_head(struct cmd_ctx *c)
{
	return move_aim(c, 0);
}

int
cmd_move_eyes(struct cmd_ctx *c)
{
	return move_aim(c, 1);
}
