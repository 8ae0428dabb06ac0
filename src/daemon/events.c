/* events.c - the events clients subscribe to, written without allocating (see events.h) */
#include "daemon/events.h"

#include <libevdev/libevdev.h>
#include <linux/input-event-codes.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "daemon/assess_json.h"
#include "daemon/assess_live.h"
#include "daemon/loads_json.h"
#include "daemon/loads_live.h"

int
events_init(struct events *E, struct server *srv, const struct daemon *d)
{
	E->srv = srv;
	E->d = d;
	return jbuf_init(&E->buf, EVENTS_BUF);
}

void
events_free(struct events *E)
{
	jbuf_free(&E->buf);
}

int
events_wanted(const struct events *E, unsigned kind)
{
	for (int i = 0; i < SERVER_MAX_CLIENTS; i++)
		if (E->srv->c[i].fd >= 0 && (E->srv->c[i].subs & kind) && !E->srv->c[i].closing)
			return 1;
	return 0;
}

void
events_send(struct events *E, unsigned kind)
{
	if (E->buf.overflow) {
		fprintf(stderr, "postured: an event did not fit its buffer; not sent\n");
		return;
	}
	jbuf_raw(&E->buf, "\n");
	for (int i = 0; i < SERVER_MAX_CLIENTS; i++) {
		struct client *c = &E->srv->c[i];
		if (c->fd < 0 || !(c->subs & kind) || c->closing)
			continue;
		if (server_queue(E->srv, i, E->buf.buf, E->buf.len) < 0) {
			fprintf(stderr, "postured: client %d does not read its events: dropped\n", i);
			server_drop(E->srv, i);
		}
	}
}

struct jbuf *
events_begin(struct events *E, const char *kind, const char *figure)
{
	struct jbuf *j = &E->buf;
	jbuf_reset(j);
	jbuf_raw(j, "{\"event\":");
	jbuf_str(j, kind);
	jbuf_key(j, "frame", 0);
	jbuf_int(j, (long long)E->d->stats.frame);
	if (figure) {
		jbuf_key(j, "figure", 0);
		jbuf_str(j, figure);
	}
	return j;
}

static void
posture_event(struct events *E, int fig)
{
	if (!events_wanted(E, SUB_POSTURE))
		return;
	const struct env_figure *f = &E->d->env.fig[fig];
	struct jbuf *j = events_begin(E, "posture", f->name);
	jbuf_key(j, "q", 0);
	jbuf_vec(j, f->state->q, f->model->ndof);
	jbuf_key(j, "com", 0);
	jbuf_vec(j, f->state->com, 3);
	jbuf_raw(j, "}");
	events_send(E, SUB_POSTURE);
}

void
events_posture_changes(struct events *E)
{
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		const struct env_figure *f = &E->d->env.fig[i];
		if (!f->gen)
			continue;
		uint64_t h = state_hash(f->model, f->state);
		if (E->told_gen[i] == f->gen && E->told_hash[i] == h)
			continue;
		E->told_gen[i] = f->gen;
		E->told_hash[i] = h;
		posture_event(E, i);
	}
}

void
events_message(struct events *E)
{
	if (!events_wanted(E, SUB_MESSAGE))
		return;
	struct jbuf *j = events_begin(E, "message", NULL);
	jbuf_key(j, "text", 0);
	jbuf_str(j, E->d->message);
	jbuf_raw(j, "}");
	events_send(E, SUB_MESSAGE);
}

void
events_kiosk(struct events *E)
{
	const struct daemon *d = E->d;
	const struct interact *ia = d->interact;
	int on = ia && ia->mode != INTERACT_NONE;
	const char *fig = on && ia->fig >= 0 ? d->env.fig[ia->fig].name : "";
	const char *view = on && ia->view >= 0 ? d->env.view[ia->view].name : "";
	const struct prompt_arg *asking = d->prompt ? prompt_asking(d->prompt) : NULL;
	const struct env_figure *hf = d->hover_fig >= 0 && d->hover_fig < ENV_MAX_FIGURES &&
						      d->env.fig[d->hover_fig].gen
					      ? &d->env.fig[d->hover_fig]
					      : NULL;
	const char *hseg = hf && d->hover_seg >= 0 ? hf->model->seg_name[d->hover_seg] : "";
	char now[sizeof E->told_kiosk];
	snprintf(now, sizeof now, "%s|%s|%s|%d|%.80s|%.30s|%s|%s", on ? interact_name(ia) : "none",
		 fig, view, d->step.open, asking ? prompt_line(d->prompt) : "",
		 asking ? asking->question : "", hf ? hf->name : "", hseg);
	if (!strcmp(now, E->told_kiosk))
		return;
	memcpy(E->told_kiosk, now, sizeof now);
	if (!events_wanted(E, SUB_KIOSK))
		return;
	struct jbuf *j = events_begin(E, "kiosk", NULL);
	jbuf_key(j, "mode", 0);
	jbuf_str(j, on ? interact_name(ia) : "none");
	jbuf_key(j, "target", 0);
	if (on && fig[0])
		jbuf_str(j, fig);
	else
		jbuf_raw(j, "null");
	jbuf_key(j, "view", 0);
	if (on && view[0])
		jbuf_str(j, view);
	else
		jbuf_raw(j, "null");
	jbuf_key(j, "step", 0);
	jbuf_bool(j, d->step.open);
	jbuf_key(j, "prompt", 0);
	if (asking) {
		jbuf_raw(j, "{");
		jbuf_key(j, "line", 1);
		jbuf_str(j, prompt_line(d->prompt));
		jbuf_key(j, "question", 0);
		jbuf_str(j, asking->question);
		jbuf_raw(j, "}");
	} else {
		jbuf_raw(j, "null");
	}
	jbuf_key(j, "picked", 0);
	if (hf) {
		jbuf_raw(j, "{");
		jbuf_key(j, "figure", 1);
		jbuf_str(j, hf->name);
		jbuf_key(j, "segment", 0);
		jbuf_str(j, hseg);
		jbuf_raw(j, "}");
	} else {
		jbuf_raw(j, "null");
	}
	jbuf_raw(j, "}");
	events_send(E, SUB_KIOSK);
}

void
events_telemetry(struct events *E, int fig, const struct ik_result *r, uint64_t budget,
		 double us)
{
	if (!events_wanted(E, SUB_TELEMETRY))
		return;
	const struct env *e = &E->d->env;
	const struct env_figure *f = &e->fig[fig];
	const struct model *m = f->model;
	struct jbuf *j = events_begin(E, "telemetry", f->name);
	jbuf_key(j, "budget_us", 0);
	jbuf_int(j, (long long)budget);
	jbuf_key(j, "used_us", 0);
	jbuf_num(j, us);
	jbuf_key(j, "iterations", 0);
	jbuf_int(j, r->iterations);
	jbuf_key(j, "status", 0);
	jbuf_str(j, ik_status_to_str(r->status));
	jbuf_key(j, "time_limit_cut", 0);
	jbuf_bool(j, r->status == IK_TIME_LIMIT);
	jbuf_key(j, "step_factor_cut", 0);
	jbuf_bool(j, r->stepped);
	jbuf_key(j, "balance_rounds", 0);
	jbuf_int(j, r->balance_rounds);
	jbuf_key(j, "energy", 0);
	jbuf_num(j, r->f_end);
	jbuf_key(j, "constraints", 0);
	jbuf_raw(j, "[");
	int first = 1;
	for (int i = 0; i < ENV_MAX_CONSTRAINTS; i++) {
		const struct env_constraint *c = &e->con[i];
		if (!c->gen || c->fig != fig)
			continue;
		double pe, oe;
		ik_constraint_error(f->ik, m, f->state, env_solver_index(e, i), &pe, &oe);
		jbuf_raw(j, first ? "{" : ",{");
		first = 0;
		jbuf_key(j, "name", 1);
		jbuf_str(j, c->name);
		jbuf_key(j, "enabled", 0);
		jbuf_bool(j, c->def.enabled);
		jbuf_key(j, "pos_error", 0);
		jbuf_num(j, pe);
		jbuf_key(j, "ori_error", 0);
		jbuf_num(j, oe);
		jbuf_raw(j, "}");
	}
	jbuf_raw(j, "]");
	jbuf_key(j, "active_limits", 0);
	jbuf_raw(j, "[");
	int nlim = ik_active_limits(f->ik, m, f->state, E->limit_dofs, EVENTS_LIMITS_REPORTED);
	for (int k = 0; k < nlim; k++) {
		int d = E->limit_dofs[k];
		jbuf_raw(j, k ? ",{" : "{");
		jbuf_key(j, "joint", 1);
		jbuf_str(j, m->jnt_name[m->dof_jnt[d]]);
		jbuf_key(j, "dof", 0);
		jbuf_int(j, d - m->jnt_dof0[m->dof_jnt[d]]);
		jbuf_key(j, "at", 0);
		jbuf_str(j, f->state->q[d] <= m->dof_lo[d] ? "lower" : "upper");
		jbuf_raw(j, "}");
	}
	jbuf_raw(j, "]}");
	events_send(E, SUB_TELEMETRY);
}

/* the balance of a behaving figure as it stands after its frame */
static void
balance_fields(struct jbuf *j, const struct behave *b)
{
	jbuf_key(j, "margin", 0);
	jbuf_num(j, b->bal.margin);
	jbuf_key(j, "threshold", 0);
	jbuf_num(j, b->p.stability_threshold);
	jbuf_key(j, "com", 0);
	jbuf_vec(j, b->bal.point, 2);
}

void
events_stability(struct events *E, int fig)
{
	const struct env_figure *f = &E->d->env.fig[fig];
	const struct behave *b = f->behave;
	if (b->stability_changed && events_wanted(E, SUB_ALERT)) {
		struct jbuf *j = events_begin(E, "alert", f->name);
		jbuf_key(j, "stability", 0);
		jbuf_str(j, b->stability_low ? "low" : "ok");
		balance_fields(j, b);
		jbuf_raw(j, "}");
		events_send(E, SUB_ALERT);
	}
	if (!events_wanted(E, SUB_STABILITY))
		return;
	struct jbuf *j = events_begin(E, "stability", f->name);
	balance_fields(j, b);
	jbuf_key(j, "low", 0);
	jbuf_bool(j, b->stability_low);
	jbuf_key(j, "balance_point", 0);
	jbuf_vec(j, b->bal_point, 2);
	jbuf_key(j, "x", 0);
	jbuf_num(j, b->bal.x);
	jbuf_key(j, "z", 0);
	jbuf_num(j, b->bal.z);
	jbuf_key(j, "weight_left", 0);
	jbuf_num(j, b->bal.weight_l);
	jbuf_key(j, "stepping", 0);
	jbuf_bool(j, b->step.active);
	jbuf_key(j, "polygon", 0);
	jbuf_raw(j, "[");
	for (int k = 0; k < b->bal.npoly; k++) {
		if (k)
			jbuf_raw(j, ",");
		jbuf_vec(j, b->bal.poly[k], 2);
	}
	jbuf_raw(j, "]}");
	events_send(E, SUB_STABILITY);
}

/* a key or button code, and its name in the kernel's headers when it has one */
static void
code_name(struct jbuf *j, uint16_t code)
{
	jbuf_key(j, "code", 0);
	jbuf_int(j, code);
	const char *name = libevdev_event_code_get_name(EV_KEY, code);
	if (name) {
		jbuf_key(j, "name", 0);
		jbuf_str(j, name);
	}
}

void
events_input(struct events *E, const struct input_event_rec *e, long px, long py)
{
	if (!events_wanted(E, SUB_INPUT))
		return;
	struct jbuf *j = events_begin(E, "input", NULL);
	jbuf_key(j, "kind", 0);
	jbuf_str(j, input_kind_to_str((enum input_kind)e->kind));
	jbuf_key(j, "device", 0);
	if (e->device == INPUT_DEVICE_SOCKET)
		jbuf_str(j, "socket");
	else
		jbuf_int(j, e->device);
	jbuf_key(j, "t_us", 0);
	jbuf_int(j, (long long)e->t_us);
	switch ((enum input_kind)e->kind) {
	case INPUT_MOTION:
		jbuf_key(j, "dx", 0);
		jbuf_num(j, e->x);
		jbuf_key(j, "dy", 0);
		jbuf_num(j, e->y);
		jbuf_key(j, "px", 0);
		jbuf_int(j, px);
		jbuf_key(j, "py", 0);
		jbuf_int(j, py);
		break;
	case INPUT_POINTER:
		if (e->flags & INPUT_F_VIEW) {
			jbuf_key(j, "view", 0);
			const struct env *env = &E->d->env;
			jbuf_str(j, e->code < ENV_MAX_VIEWS ? env->view[e->code].name : "");
		}
		jbuf_key(j, "x", 0);
		jbuf_num(j, e->x);
		jbuf_key(j, "y", 0);
		jbuf_num(j, e->y);
		break;
	case INPUT_BUTTON:
	case INPUT_KEY:
		code_name(j, e->code);
		jbuf_key(j, "value", 0);
		jbuf_int(j, e->value);
		break;
	case INPUT_WHEEL:
		jbuf_key(j, "axis", 0);
		jbuf_str(j, e->code == INPUT_WHEEL_H ? "horizontal" : "vertical");
		jbuf_key(j, "detents", 0);
		jbuf_int(j, e->value);
		jbuf_key(j, "hires", 0);
		jbuf_num(j, e->x);
		break;
	case INPUT_VALUATOR:
		jbuf_key(j, "valuator", 0);
		jbuf_int(j, e->code);
		if (E->d->panel && e->code < E->d->panel->n) {
			jbuf_key(j, "name", 0);
			jbuf_str(j, E->d->panel->line[e->code].name);
		}
		jbuf_key(j, "value", 0);
		jbuf_num(j, e->x);
		jbuf_key(j, "stale", 0);
		jbuf_bool(j, e->flags & INPUT_F_STALE);
		break;
	case INPUT_ADDED:
	case INPUT_REMOVED:
	case INPUT_FRAME:
		break;
	}
	jbuf_raw(j, "}");
	events_send(E, SUB_INPUT);
}

/* ---- assessments ----------------------------------------------------------- */

void
events_assessment_retell(struct events *E)
{
	memset(E->told_assess, 0, sizeof E->told_assess);
}

/* what an event says of a figure's assessment, for comparing with what was told */
static void
assess_told_of(const struct assess_live_fig *a, uint32_t gen, struct events_assess_told *t)
{
	memset(t, 0, sizeof *t);
	t->gen = gen;
	for (int k = 0; k < ASSESS_NMETHODS; k++) {
		const struct assess_result *r = &a->res[k];
		t->m[k].score = r->score;
		t->m[k].action_level = r->action_level;
		t->m[k].side = r->side;
		t->m[k].worst = r->worst;
		t->m[k].nparts = r->nparts < ASSESS_MAX_PARTS ? r->nparts : ASSESS_MAX_PARTS;
		for (int i = 0; i < t->m[k].nparts; i++)
			t->m[k].part[i] = r->part[i].score;
		memcpy(t->m[k].code, r->code, sizeof t->m[k].code);
	}
}

void
events_assessment(struct events *E, struct daemon *d)
{
	if (!events_wanted(E, SUB_ASSESSMENT))
		return;
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		const struct env_figure *f = &d->env.fig[i];
		if (!f->gen || !f->is_human)
			continue;
		const struct assess_live_fig *a = assess_live_of(d, i);
		if (!a)
			continue;
		struct events_assess_told now;
		assess_told_of(a, f->gen, &now);
		if (!memcmp(&now, &E->told_assess[i], sizeof now))
			continue;
		memcpy(&E->told_assess[i], &now, sizeof now);
		struct jbuf *j = events_begin(E, "assessment", f->name);
		for (int k = 0; k < ASSESS_NMETHODS; k++) {
			jbuf_key(j, assess_json_method((enum assess_method)k), 0);
			assess_json_summary(j, &a->res[k]);
		}
		jbuf_key(j, "load_kg", 0);
		jbuf_num(j, a->load_kg);
		jbuf_raw(j, "}");
		events_send(E, SUB_ASSESSMENT);
	}
}

/* ---- loads ------------------------------------------------------------------------ */

/*
 * How much a figure's analysis must change to be told again: a drag moves
 * the numbers every frame, the event tells what a person would notice.
 * 50 N of disc compression is 1.5 % of NIOSH's action limit (3400 N) and
 * about the weight of a forearm and hand; 1 percentage point of the
 * population capable is the resolution the status line shows; 10 N on a
 * foot is 1 kg moved from one foot to the other.
 */
#define LOADS_TELL_COMPRESSION_N 50.0
#define LOADS_TELL_CAPABLE_PCT 1.0
#define LOADS_TELL_SUPPORT_N 10.0

void
events_loads_retell(struct events *E)
{
	memset(E->told_loads, 0, sizeof E->told_loads);
}

static uint64_t
loads_identity(const struct loads_live_fig *a)
{
	uint64_t h = 14695981039346656037ull;
	for (int k = 0; k < a->nloads; k++) {
		const int v[3] = { a->origin[k].load, a->origin[k].carried, a->origin[k].side };
		for (size_t b = 0; b < sizeof v; b++)
			h = (h ^ ((const unsigned char *)v)[b]) * 1099511628211ull;
	}
	return h ^ (uint64_t)a->nloads;
}

/* what an event would tell of a now */
static void
loads_told_of(const struct loads_live_fig *a, uint32_t gen, struct events_loads_told *t)
{
	memset(t, 0, sizeof *t);
	t->gen = gen;
	t->low_back = a->low_back;
	t->zone = a->low_back ? (int)a->lb.zone : -1;
	t->compression = a->low_back ? a->lb.compression : 0;
	int weak = a->strength && !isnan(a->sr.capable);
	t->weakest_joint = weak ? a->sr.weakest_joint : -1;
	t->weakest_axis = weak ? a->sr.weakest_axis : -1;
	t->capable = weak ? a->sr.capable : NAN;
	t->nsupport = a->st.nsupport;
	t->tips = a->st.tips;
	for (int k = 0; k < a->st.nsupport && k < STATICS_MAX_SUPPORT; k++) {
		t->support_site[k] = a->st.support[k].site;
		memcpy(t->support_force[k], a->st.support[k].force, sizeof t->support_force[k]);
	}
	t->loads_id = loads_identity(a);
}

/* 1 when now differs from what was told by more than the thresholds */
static int
loads_changed(const struct events_loads_told *was, const struct events_loads_told *now)
{
	if (was->gen != now->gen || was->low_back != now->low_back || was->zone != now->zone ||
	    was->weakest_joint != now->weakest_joint || was->weakest_axis != now->weakest_axis ||
	    was->nsupport != now->nsupport || was->tips != now->tips || was->loads_id != now->loads_id)
		return 1;
	if (fabs(now->compression - was->compression) >= LOADS_TELL_COMPRESSION_N)
		return 1;
	if (now->weakest_joint >= 0 && fabs(now->capable - was->capable) >= LOADS_TELL_CAPABLE_PCT)
		return 1;
	for (int k = 0; k < now->nsupport && k < STATICS_MAX_SUPPORT; k++) {
		double d2 = 0;
		for (int i = 0; i < 3; i++) {
			double dv = now->support_force[k][i] - was->support_force[k][i];
			d2 += dv * dv;
		}
		if (now->support_site[k] != was->support_site[k] ||
		    d2 >= LOADS_TELL_SUPPORT_N * LOADS_TELL_SUPPORT_N)
			return 1;
	}
	return 0;
}

void
events_loads(struct events *E, struct daemon *d)
{
	if (!events_wanted(E, SUB_LOADS))
		return;
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		const struct env_figure *f = &d->env.fig[i];
		if (!f->gen)
			continue;
		const struct loads_live_fig *a = loads_live_of(d, i);
		if (!a)
			continue;
		struct events_loads_told now;
		loads_told_of(a, f->gen, &now);
		if (!loads_changed(&E->told_loads[i], &now))
			continue;
		E->told_loads[i] = now;
		struct jbuf *j = events_begin(E, "loads", f->name);
		loads_json_summary_keys(j, &d->env, i, a);
		jbuf_raw(j, "}");
		events_send(E, SUB_LOADS);
	}
}
