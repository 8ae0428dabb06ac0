/*
 * cmd_manip.c - the interactive modes over the socket: `manipulate figure`
 * starts the mode the kiosk starts, the input lines (and the devices) drive
 * it through the loop, ESC ends it, `get manip` says where G is.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "daemon/cmd_ctx.h"
#include "daemon/daemon.h"
#include "figure/kin.h"
#include "interact/interact.h"
#include "interact/mouse_line.h"
#include "interact/pick.h"
#include "interact/snap.h"
#include "pose/behave.h"
#include "pose/spine.h"

/*
 * G was set by a command (a snap, a typed value): what the mode moves
 * follows, as one step of its own (one undo) unless a drag is under way.
 */
static void
moved_as_step(struct cmd_ctx *c)
{
	struct daemon *d = c->d;
	int own = d->mode_step && !d->step.open;
	if (own)
		d->mode_step(d, 'B');
	if (d->mode_moved)
		d->mode_moved(d);
	if (own)
		d->mode_step(d, 'E');
}

/* the view a mode works through: view=NAME, else the first there is; -1 with the error set */
static int
manip_view(struct cmd_ctx *c)
{
	const struct env *e = &c->d->env;
	const char *name = cmd_key(c, "view");
	if (name) {
		int v = env_find_view(e, name);
		if (v < 0)
			return cmd_fail(c, "not-found", "no view '%.60s'", name);
		return v;
	}
	for (int v = 0; v < ENV_MAX_VIEWS; v++)
		if (e->view[v].used)
			return v;
	return cmd_fail(c, "not-found", "no view to manipulate in: add view first");
}

/* a mode starting with G's origin off the screen turns the view to it first (§3.7) */
static void
manip_into_view(struct cmd_ctx *c)
{
	const struct interact *ia = c->d->interact;
	if (c->d->bring_into_view)
		c->d->bring_into_view(c->d, ia->view, ia->m.g.p);
}

/*
 * What every command starting a mode checks: the daemon takes input, the
 * words from first_key on are view= (or also `other`=), FIG names a
 * figure (into *fig) and the view exists (into *v). 0, or -1 with the error.
 */
static int
mode_args(struct cmd_ctx *c, int first_key, const char *other, int *fig, int *v)
{
	if (!c->d->interact)
		return cmd_fail(c, "bad-argument", "this daemon takes no input");
	for (int i = first_key; i < c->argc; i++)
		if (!words_is_key(c->argv[i], "view") && !(other && words_is_key(c->argv[i], other)))
			return cmd_fail(c, "bad-argument", "unexpected '%.60s'", c->argv[i]);
	if ((*fig = cmd_figure(c, c->argv[0])) < 0)
		return -1;
	*v = manip_view(c);
	return *v < 0 ? -1 : 0;
}

/* the camera of view v, for a mode starting there; the view itself */
static const struct env_view *
mode_camera(struct cmd_ctx *c, int v, struct camera *cam)
{
	const struct env_view *vw = &c->d->env.view[v];
	view_camera_of_view(vw, cam);
	return vw;
}

/* a mode started on figure fig: G brought into view, the reply's mode and view */
static void
mode_started(struct cmd_ctx *c, int fig, const char *mode, const struct env_view *vw)
{
	c->d->interact->tag = c->d->env.fig[fig].gen;
	manip_into_view(c);
	json_object_set_new(c->result, "mode", json_string(mode));
	json_object_set_new(c->result, "view", json_string(vw->name));
}

int
cmd_manipulate_figure(struct cmd_ctx *c)
{
	int fig, v;
	if (mode_args(c, 1, NULL, &fig, &v) < 0)
		return -1;
	if (c->client == DAEMON_CLIENT_JOURNAL) /* replaying the journal: no mode nobody drives */
		return 0;
	struct camera cam;
	const struct env_view *vw = mode_camera(c, v, &cam);
	/* G on the figure's root site, the frame its location is given in */
	const struct xform *root = &c->d->env.fig[fig].state->root_xf;
	interact_start(c->d->interact, INTERACT_FIGURE, fig, v, root, root, &cam, vw->width,
		       vw->height);
	mode_started(c, fig, "figure", vw);
	return 0;
}

/*
 * manipulate site FIG SEG.SITE [view=VIEW]: G starts on the site and the
 * site moves on its segment as G moves; the segment stays where it is. A
 * site its segment hangs from (other than the root) would carry the
 * segment along instead, away from G: refused, with the way out.
 */
int
cmd_manipulate_site(struct cmd_ctx *c)
{
	int fig, v;
	if (mode_args(c, 2, NULL, &fig, &v) < 0)
		return -1;
	const struct env_figure *f = &c->d->env.fig[fig];
	int site = model_find_site(f->model, c->argv[1]);
	if (site < 0)
		return cmd_fail(c, "not-found", "no site '%.60s' on %s", c->argv[1], f->name);
	int seg = f->model->site_seg[site];
	if (site != f->state->root_site && f->state->seg_root_site[seg] == site)
		return cmd_fail(c, "bad-argument",
				"%s hangs from %s: moving it would move the segment, not the site "
				"(root the figure there first: set root %s %s)",
				f->model->seg_name[seg], c->argv[1], f->name, c->argv[1]);
	if (c->client == DAEMON_CLIENT_JOURNAL)
		return 0;
	struct camera cam;
	const struct env_view *vw = mode_camera(c, v, &cam);
	const struct xform *at = &f->state->site_xf[site];
	interact_start(c->d->interact, INTERACT_SITE, fig, v, at, at, &cam, vw->width, vw->height);
	c->d->interact->site = site;
	mode_started(c, fig, "site", vw);
	return 0;
}

/* manipulate joint FIG JOINT [view=VIEW] (§3.8): the buttons turn its DOFs until ESC */
int
cmd_manipulate_joint(struct cmd_ctx *c)
{
	int fig, v;
	if (mode_args(c, 2, NULL, &fig, &v) < 0)
		return -1;
	const struct env_figure *f = &c->d->env.fig[fig];
	int joint = model_find_joint(f->model, c->argv[1]);
	if (joint < 0)
		return cmd_fail(c, "not-found", "no joint '%.60s' on %s", c->argv[1], f->name);
	if (f->model->jnt_ndof[joint] < 1)
		return cmd_fail(c, "bad-argument", "joint %s has no DOF to move", c->argv[1]);
	if (c->client == DAEMON_CLIENT_JOURNAL)
		return 0;
	struct camera cam;
	const struct env_view *vw = mode_camera(c, v, &cam);
	interact_start_joint(c->d->interact, fig, v, f->model, f->state, joint, &cam, vw->width,
			     vw->height);
	/* the joint the dial box turns from now on, in the mode and after it */
	c->d->picked.fig = fig;
	c->d->picked.gen = f->gen;
	c->d->picked.joint = joint;
	mode_started(c, fig, "joint", vw);
	json_object_set_new(c->result, "dofs", json_integer(f->model->jnt_ndof[joint]));
	return 0;
}

/*
 * manipulate hand|foot FIG left|right, manipulate com FIG (Table 5.2): the
 * behaviour primitive's goal follows G each time it moves, as the move
 * commands set it; the behaviours respond frame by frame.
 */
static int
manipulate_primitive(struct cmd_ctx *c, enum interact_primitive kind)
{
	int sided = kind == INTERACT_HAND || kind == INTERACT_FOOT, fig, v, side = 0;
	if (mode_args(c, sided ? 2 : 1, NULL, &fig, &v) < 0)
		return -1;
	struct env *e = &c->d->env;
	struct env_figure *f = &e->fig[fig];
	if (!f->behave)
		return cmd_fail(c, "bad-argument", "behaviours are off for %s (behave %s on)",
				f->name, f->name);
	if (sided && (side = cmd_side(c, c->argv[1])) < 0)
		return -1;
	if (c->client == DAEMON_CLIENT_JOURNAL)
		return 0;
	env_sync_solver(e, fig);
	const struct behave *b = f->behave;
	struct xform g;
	if (kind == INTERACT_HAND) {
		g = f->state->site_xf[b->s_palm[side]];
	} else if (kind == INTERACT_FOOT) {
		g = f->state->site_xf[behave_foot_site(b, side)];
	} else if (kind == INTERACT_PELVIS) { /* the pelvis's frame: CONTROL and a button turn it */
		g = f->state->site_xf[b->s_pelvis];
	} else if (kind == INTERACT_TORSO) { /* on the chest, in the pelvis's axes: the bend's */
		g = f->state->site_xf[b->s_pelvis];
		memcpy(g.p, f->state->site_xf[b->s_chest].p, sizeof g.p);
	} else if (kind == INTERACT_COM) { /* the centre of mass balanced, in the world's axes */
		kin_com(f->model, f->state);
		xform_identity(&g);
		behave_com(b, f->state, g.p);
	} else { /* the point fixated, or 1 m along the head's (an eye's) +z, the aim axis */
		int eyes = kind == INTERACT_EYES;
		const struct xform *site = &f->state->site_xf[eyes ? b->s_eye[0] : b->s_head];
		xform_identity(&g);
		if (eyes ? b->p.fixate_eyes : b->p.fixate_head)
			memcpy(g.p, eyes ? b->p.eyes_point : b->p.head_point, sizeof g.p);
		else
			for (int k = 0; k < 3; k++)
				g.p[k] = site->p[k] + site->r[3 * k + 2];
	}
	struct camera cam;
	const struct env_view *vw = mode_camera(c, v, &cam);
	interact_start(c->d->interact, INTERACT_PRIMITIVE, fig, v, &g, &g, &cam, vw->width,
		       vw->height);
	c->d->interact->primitive = kind;
	c->d->interact->side = side;
	memcpy(c->d->interact->applied_r, g.r, sizeof g.r);
	spine_totals(f->model, f->state, c->d->interact->torso0);
	mode_started(c, fig, interact_primitive_to_str(kind), vw);
	return 0;
}

int
cmd_manipulate_hand(struct cmd_ctx *c)
{
	return manipulate_primitive(c, INTERACT_HAND);
}

int
cmd_manipulate_foot(struct cmd_ctx *c)
{
	return manipulate_primitive(c, INTERACT_FOOT);
}

int
cmd_manipulate_com(struct cmd_ctx *c)
{
	return manipulate_primitive(c, INTERACT_COM);
}

int
cmd_manipulate_pelvis(struct cmd_ctx *c)
{
	return manipulate_primitive(c, INTERACT_PELVIS);
}

int
cmd_manipulate_head(struct cmd_ctx *c)
{
	return manipulate_primitive(c, INTERACT_HEAD);
}

int
cmd_manipulate_eyes(struct cmd_ctx *c)
{
	return manipulate_primitive(c, INTERACT_EYES);
}

int
cmd_manipulate_torso(struct cmd_ctx *c)
{
	return manipulate_primitive(c, INTERACT_TORSO);
}

/*
 * drag FIG SEG.SITE [start=JOINT] [view=VIEW] (§4.6.1): the site is held to
 * G by a constraint named "drag" (position and orientation, the chain from
 * the site up to JOINT, or to the root), which the solver satisfies each
 * frame within its time limit; G starts on the site. ESC ends the drag and
 * deletes the constraint; the posture stays. The constraint is the mode's
 * (transient): sessions and undo leave it out, each step of the drag is
 * journaled as the postures it reached.
 */
int
cmd_drag(struct cmd_ctx *c)
{
	int fig, v;
	if (mode_args(c, 2, "start", &fig, &v) < 0)
		return -1;
	struct env *e = &c->d->env;
	struct env_figure *f = &e->fig[fig];
	/* an older journal's drag: its postures are journaled, not its mode */
	if (c->client == DAEMON_CLIENT_JOURNAL)
		return 0;
	struct ik_constraint_def def = ik_constraint_default_def();
	if ((def.effector_site = model_find_site(f->model, c->argv[1])) < 0)
		return cmd_fail(c, "not-found", "no site '%.60s' on %s", c->argv[1], f->name);
	const char *start = cmd_key(c, "start");
	if (start && (def.start_joint = model_find_joint(f->model, start)) < 0)
		return cmd_fail(c, "not-found", "start=%.60s: no such joint", start);
	def.pos = IK_POINT;
	def.ori = IK_FRAME;
	def.goal_site = -1;
	def.goal_xf = f->state->site_xf[def.effector_site];
	/* one drag at a time: a drag constraint left from before is replaced */
	int old = env_find_constraint(e, CMD_DRAG_CONSTRAINT);
	if (old >= 0)
		env_remove_constraint(e, old);
	int slot = env_add_constraint(e, fig, CMD_DRAG_CONSTRAINT, &def);
	if (slot < 0)
		return cmd_fail(c, "limit", "%d constraints at most", ENV_MAX_CONSTRAINTS);
	e->con[slot].transient = 1; /* the mode's: what it moves is journaled, not the constraint */
	struct camera cam;
	const struct env_view *vw = mode_camera(c, v, &cam);
	interact_start(c->d->interact, INTERACT_DRAG, fig, v, &def.goal_xf, &def.goal_xf, &cam,
		       vw->width, vw->height);
	c->d->interact->con = slot;
	c->d->interact->con_tag = e->con[slot].gen;
	mode_started(c, fig, "drag", vw);
	char id[32];
	env_constraint_id(e, slot, id);
	json_object_set_new(c->result, "constraint", json_string(id));
	return 0;
}

/*
 * snap KIND (B.4): in a mode, G onto the feature under the mode's pointer
 * (the site, vertex, edge or face picked there); what the mode moves
 * follows. Not in the joint mode, whose G is the joint's pivot.
 */
int
cmd_snap(struct cmd_ctx *c)
{
	struct interact *ia = c->d->interact;
	if (!ia || ia->mode == INTERACT_NONE || ia->mode == INTERACT_JOINT)
		return cmd_fail(c, "bad-argument", "snap works in a figure, drag or primitive mode");
	int kind = snap_kind_named(c->argv[0]);
	if (kind < 0)
		return cmd_fail(c, "bad-argument", "site, site_position, site_orientation, "
				"node_position, edge_position, edge_line, edge_orientation, "
				"face_position, face_center, face_plane or face_orientation");
	struct env *e = &c->d->env;
	const struct env_view *vw = &e->view[ia->view];
	struct camera cam;
	struct ray r;
	view_camera_of_view(vw, &cam);
	if (mouse_line(&cam, vw->width, vw->height, ia->px, ia->py, &r) < 0)
		return cmd_fail(c, "internal", "no mouse line under the pointer");
	/* the feature under the pointer, on any figure but the one being moved */
	struct pick_hit h;
	int hit_fig, hit = daemon_pick(c->d, &r, cam.znear, ia->fig, &h, &hit_fig);
	if (hit < 0)
		return cmd_fail(c, "internal", "out of memory");
	if (!hit)
		return cmd_fail(c, "not-found", "nothing under the pointer to snap to");
	struct snap_feature f;
	memset(&f, 0, sizeof f);
	const struct env_figure *hf = &e->fig[hit_fig];
	if ((f.has_site = h.site >= 0))
		f.site = hf->state->site_xf[h.site];
	memcpy(f.face, h.tri, sizeof f.face);
	memcpy(f.vertex, h.tri[h.vertex_corner], sizeof f.vertex);
	memcpy(f.edge[0], h.tri[h.edge_corner[0]], sizeof f.edge[0]);
	memcpy(f.edge[1], h.tri[h.edge_corner[1]], sizeof f.edge[1]);
	struct xform g;
	if (snap_apply((enum snap_kind)kind, &f, &ia->m.g, &g) < 0)
		return cmd_fail(c, "bad-argument", "no %s to snap to there", c->argv[0]);
	manip_set(&ia->m, &g);
	moved_as_step(c);
	char id[32];
	env_figure_id(e, hit_fig, id);
	json_object_set_new(c->result, "snapped", json_string(c->argv[0]));
	json_object_set_new(c->result, "figure", json_string(id));
	json_object_set_new(c->result, "segment", json_string(hf->model->seg_name[h.segment]));
	json_object_set_new(c->result, "position", cmd_vec(g.p, 3));
	return 0;
}

/*
 * set manip [increments=on|off] [step=LENGTH] [turn=ANGLE]: motion in
 * steps (1 cm and 5 degrees unless set), for this mode and the next ones.
 */
static int
set_increments(struct cmd_ctx *c, struct interact *ia)
{
	int on = ia->increments;
	double step = ia->def.step, turn = ia->def.step_angle;
	for (int i = 0; i < c->argc; i++) {
		const char *w = c->argv[i], *v = strchr(w, '=');
		if (words_is_key(w, "increments")) {
			if (strcmp(v + 1, "on") && strcmp(v + 1, "off"))
				return cmd_fail(c, "bad-argument", "increments=on|off");
			on = !strcmp(v + 1, "on");
		} else if (words_is_key(w, "step")) {
			if (words_number(v + 1, UNIT_LENGTH, &step) < 0 || !(step >= 1e-4 && step <= 10))
				return cmd_fail(c, "bad-number", "step=LENGTH from 0.1mm to 10m, such as 5mm");
		} else if (words_is_key(w, "turn")) {
			if (words_number(v + 1, UNIT_ANGLE, &turn) < 0 ||
			    !(turn >= 0.01 * M_PI / 180 && turn <= M_PI))
				return cmd_fail(c, "bad-number", "turn=ANGLE from 0.01deg to 180deg, such as 15deg");
		} else {
			return cmd_fail(c, "bad-argument", "increments=on|off step=LENGTH turn=ANGLE, "
					"or a value alone");
		}
	}
	interact_increments(ia, on, step, turn);
	json_object_set_new(c->result, "increments", json_boolean(on));
	json_object_set_new(c->result, "step", json_real(step));
	json_object_set_new(c->result, "turn", json_real(turn));
	return 0;
}

/* set manip VALUE: a typed displacement along (or turn about) the active axis, exactly */
int
cmd_set_manip(struct cmd_ctx *c)
{
	struct interact *ia = c->d->interact;
	if (!ia)
		return cmd_fail(c, "bad-argument", "this daemon takes no input");
	if (words_is_key(c->argv[0], "increments") || words_is_key(c->argv[0], "step") ||
	    words_is_key(c->argv[0], "turn"))
		return set_increments(c, ia);
	if (c->argc != 1)
		return cmd_fail(c, "bad-argument", "one value: a length or an angle");
	if (ia->mode == INTERACT_NONE)
		return cmd_fail(c, "bad-argument", "a value is typed in a mode");
	if (ia->mode == INTERACT_JOINT) { /* the selected DOF's displacement, in its own sense */
		int rot = interact_joint_rotation(ia);
		double typed;
		if (rot < 0)
			return cmd_fail(c, "bad-argument", "no DOF is selected: hold a button");
		if (words_number(c->argv[0], rot ? UNIT_ANGLE : UNIT_LENGTH, &typed) < 0)
			return cmd_fail(c, "bad-number", "%s", rot ? "an angle (-30deg)" : "a length (2cm)");
		interact_joint_type(ia, typed);
		moved_as_step(c);
		json_object_set_new(c->result, "value", json_real(ia->moved_value));
		return 0;
	}
	if (words_is_key(c->argv[0], "increments") || words_is_key(c->argv[0], "step") ||
	    words_is_key(c->argv[0], "turn"))
		return set_increments(c, ia);
	enum manip_state st = ia->m.state;
	if (st != MANIP_LINEAR && st != MANIP_ROTATE)
		return cmd_fail(c, "bad-argument", "no axis is active: hold a button (CONTROL: a turn)");
	double v;
	if (words_number(c->argv[0], st == MANIP_LINEAR ? UNIT_LENGTH : UNIT_ANGLE, &v) < 0)
		return cmd_fail(c, "bad-number", "%s", st == MANIP_LINEAR ? "a length (10cm)"
									  : "an angle (-30deg)");
	if (manip_type(&ia->m, v) < 0)
		return cmd_fail(c, "bad-argument", "not a value for this axis");
	moved_as_step(c);
	json_object_set_new(c->result, "position", cmd_vec(ia->m.g.p, 3));
	return 0;
}

/* the active axis or plane: "x", "y", "z", "xy", "yz", "xz", or NULL */
static const char *
manip_axis_name(const struct manip_icon *ic)
{
	static const char *const axes[] = { "x", "y", "z" };
	static const char *const planes[] = { "yz", "xz", "xy" }; /* by the normal's index */
	int a = ic->sel.axis;
	if (a < 0 || a > 2)
		return NULL;
	switch (ic->state) {
	case MANIP_LINEAR:
	case MANIP_ROTATE:
		return axes[a];
	case MANIP_PLANAR:
		return planes[a];
	case MANIP_REFUSED:
		return ic->sel.mode == MANIP_MODE_PLANAR ? planes[a] : axes[a];
	default:
		return NULL;
	}
}

int
cmd_get_manip(struct cmd_ctx *c)
{
	const struct interact *ia = c->d->interact;
	int on = ia && ia->mode != INTERACT_NONE;
	json_object_set_new(c->result, "mode", json_string(on ? interact_name(ia) : "none"));
	if (!on) {
		json_object_set_new(c->result, "view", json_null());
		json_object_set_new(c->result, "position", json_null());
		json_object_set_new(c->result, "rotation", json_null());
		json_object_set_new(c->result, "axis", json_null());
		json_object_set_new(c->result, "state", json_string("idle"));
		json_object_set_new(c->result, "message", json_string(""));
		return 0;
	}
	struct manip_icon ic;
	manip_icon(&ia->m, &ic);
	json_object_set_new(c->result, "view", json_string(c->d->env.view[ia->view].name));
	if (ia->mode == INTERACT_JOINT) {
		/* G on the joint's pivot; the axis: the DOF the buttons selected */
		json_object_set_new(c->result, "position", cmd_vec(ia->m.g.p, 3));
		json_t *rot = json_array();
		for (int i = 0; i < 3; i++)
			json_array_append_new(rot, cmd_vec(&ia->m.g.r[3 * i], 3));
		json_object_set_new(c->result, "rotation", rot);
		char dof[16];
		snprintf(dof, sizeof dof, "dof%d", ia->jm.dof);
		json_object_set_new(c->result, "axis", ia->jm.dof >= 0 ? json_string(dof) : json_null());
		json_object_set_new(c->result, "state", json_string(ia->jm.dof >= 0 ? "joint" : "idle"));
		json_object_set_new(c->result, "message", json_string(""));
		return 0;
	}
	json_object_set_new(c->result, "position", cmd_vec(ia->m.g.p, 3));
	json_t *rot = json_array();
	for (int i = 0; i < 3; i++)
		json_array_append_new(rot, cmd_vec(&ia->m.g.r[3 * i], 3));
	json_object_set_new(c->result, "rotation", rot);
	const char *axis = manip_axis_name(&ic);
	json_object_set_new(c->result, "axis", axis ? json_string(axis) : json_null());
	json_object_set_new(c->result, "state", json_string(manip_state_to_str(ic.state)));
	json_object_set_new(c->result, "frame",
			    json_string(ic.sel.frame == MANIP_LOCAL ? "local" : "global"));
	json_object_set_new(c->result, "message", json_string(ia->message));
	return 0;
}
