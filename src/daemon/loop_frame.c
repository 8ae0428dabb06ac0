/*
 * loop_frame.c - one frame: the input taken, the modes and dials moved on
 * by the clock, every figure with work solved within the frame's budget
 * (§4.7.2), the pictures published. What the state takes from outside (the
 * clock, the solves' cuts) goes through the tape, so a replay makes the
 * same frames.
 */
#include "daemon/loop_state.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "daemon/cmd.h"
#include "daemon/kiosk_route.h"
#include "daemon/tape_dev.h"
#include "pose/attach.h"
#include "pose/behave.h"
#include "pose/eyeview.h"
#include "pose/load_balance.h"

uint64_t
loop_real_now(void)
{
	return tape_real_now();
}

/* the loop thread's own CPU time: a round's stall apart from the CPUs being busy elsewhere */
uint64_t
loop_thread_cpu_us(void)
{
	struct timespec t;
	clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
	return (uint64_t)t.tv_sec * 1000000u + (uint64_t)t.tv_nsec / 1000u;
}

static uint64_t
real_now(void *ctx)
{
	(void)ctx;
	return tape_real_now();
}

/* settle's clock: every read advances it, so the time limit cuts alike on every run */
static uint64_t
virtual_now(void *ctx)
{
	struct loop *L = ctx;
	return L->virtual_us += 20;
}

int
loop_take_input(struct loop *L)
{
	struct input_event_rec e;
	int n = 0;
	while (input_queue_pop(&L->input, &e)) {
		n++;
		long px = 0, py = 0;
		struct motion_scale *m = e.device < INPUT_DEVS_MAX ? &L->pointer[e.device]
								   : &L->pointer[INPUT_DEVS_MAX];
		if (e.kind == INPUT_ADDED && e.device < INPUT_DEVS_MAX) /* a replay's devices are the tape's */
			motion_scale_init(m, L->tape.mode == TAPE_REPLAY ? tape_dev_dpi(&L->tape, e.device)
									 : L->devs.place[e.device].info.dpi,
					  L->pointer_gain);
		else if (e.kind == INPUT_MOTION)
			motion_scale_apply(m, e.x, e.y, &px, &py);
		if (escape_chord_feed(&L->escape, &e) && L->devs.grab) {
			input_devs_set_grab(&L->devs, 0);
			fprintf(stderr, "postured: Ctrl+Alt+Backspace: the kiosk grab given up "
					"('set input grab=yes' takes it again)\n");
		}
		if (!L->scene.input_us && e.kind != INPUT_FRAME) /* the oldest the pictures owe */
			L->scene.input_us = e.t_us;
		events_input(&L->events, &e, px, py);
		dials_input(&L->dials, &e);
		kiosk_route_input(&L->modes, &e, px, py);
	}
	events_kiosk(&L->events);
	return n;
}

void
loop_command(struct loop *L, int client, const char *line, size_t len, struct cmd_outcome *out)
{
	/* a command sees every input that came before it (a mode moved by them, say) */
	loop_take_input(L);
	/* what the solver did since the last reply is made durable first */
	if (journal_postures(&L->j, &L->d) < 0)
		fprintf(stderr, "postured: journal: %s\n", strerror(errno));
	cmd_run(&L->d, client, line, len, out);
	modes_sync(&L->modes);
	/* a change is replayed from its command; frames a command ran (settle)
	 * are recorded as the postures they reached */
	int rc = out->mutated ? journal_command(&L->j, &L->d, line, len)
			      : journal_postures(&L->j, &L->d);
	if (rc < 0)
		fprintf(stderr, "postured: journal: %s\n", strerror(errno));
	if (out->mutated)
		L->scene.dirty = 1;
	events_kiosk(&L->events);
	if (out->reply) { /* the message line under the pictures */
		snprintf(L->d.message, sizeof L->d.message, "> %.*s  %s", (int)(len > 100 ? 100 : len),
			 line, out->ok ? "ok" : "refused");
		events_message(&L->events);
	}
	events_posture_changes(&L->events);
	events_assessment(&L->events, &L->d);
	events_loads(&L->events, &L->d);
}

int
loop_queries(struct loop *L, const char *path)
{
	FILE *f = fopen(path, "r");
	if (!f) {
		fprintf(stderr, "postured: %s: %s\n", path, strerror(errno));
		return -1;
	}
	char line[4096];
	while (fgets(line, sizeof line, f)) {
		size_t len = strcspn(line, "\r\n");
		line[len] = 0;
		if (!len || line[0] == '#')
			continue;
		struct cmd_outcome out;
		loop_command(L, DAEMON_CLIENT_JOURNAL, line, len, &out);
		printf("reply: %s\n", out.json ? out.json : "null");
		free(out.json);
	}
	fclose(f);
	return 0;
}

static int
has_work(const struct env *e, int fig)
{
	if (e->fig[fig].behave)
		return 1;
	for (int i = 0; i < ENV_MAX_CONSTRAINTS; i++)
		if (e->con[i].gen && e->con[i].fig == fig && e->con[i].def.enabled)
			return 1;
	return 0;
}

/* one frame: solve every figure with work within the budget */
static int
frame(struct loop *L, const struct ik_clock *clock, uint64_t budget_us, int *changed)
{
	struct env *e = &L->d.env;
	uint64_t start = loop_real_now(), start_cpu = loop_thread_cpu_us();
	int busy = 0;
	*changed = 0;
	for (int i = 0; i < ENV_MAX_FIGURES; i++)
		busy += e->fig[i].gen && has_work(e, i);
	L->d.stats.ik_us = 0;
	L->d.stats.iterations = 0;
	L->d.stats.time_cut = L->d.stats.step_cut = 0;
	L->d.stats.budget_us = budget_us;
	for (int i = 0; i < ENV_MAX_FIGURES && busy; i++) {
		struct env_figure *f = &e->fig[i];
		if (!f->gen || !has_work(e, i))
			continue;
		env_sync_solver(e, i);
		uint64_t before = state_hash(f->model, f->state);
		struct ik_options opt = ik_default_options();
		opt.budget_us = budget_us / (uint64_t)busy; /* an equal share each */
		opt.replay = tape_ik_replay(&L->tape, i); /* replaying: cut where the recording was */
		if (L->tape.broken[0])
			break;
		if (f->behave) /* hands and feet holding on to objects go where the objects are */
			attach_before_solve(e, i);
		load_balance_update(e, i); /* balance holds the weights it feels now too */
		uint64_t t0 = loop_real_now();
		struct ik_result r = f->behave ? behave_frame(f->behave, f->model, f->state, f->ik, &opt,
							      clock)
					       : ik_solve(f->ik, f->model, f->state, &opt, clock);
		double us = (double)(loop_real_now() - t0);
		tape_ik_done(&L->tape, i, &r.work);
		L->d.stats.ik_us += us;
		L->d.stats.iterations += r.iterations;
		L->d.stats.time_cut |= r.status == IK_TIME_LIMIT;
		L->d.stats.step_cut |= r.stepped;
		*changed |= state_hash(f->model, f->state) != before;
		if (f->behave) /* objects its hands grabbed follow them */
			*changed |= attach_after_solve(e, i);
		events_telemetry(&L->events, i, &r, opt.budget_us, us);
		if (f->behave)
			events_stability(&L->events, i);
	}
	eyeview_follow_all(e); /* the eye views move with the heads and eyes just solved */
	L->d.stats.frame++;
	L->round_solve_us += loop_real_now() - start;
	L->round_solve_cpu_us += loop_thread_cpu_us() - start_cpu;
	return 0;
}

int
loop_settle_frame(struct daemon *d, int *changed)
{
	struct loop *L = d->loop;
	struct ik_clock clock = { virtual_now, L };
	loop_take_input(L);
	modes_frame(&L->modes, tape_clock(&L->tape)); /* a snap is eased over real time, settle or not */
	int rc = frame(L, &clock, L->period_us, changed);
	events_posture_changes(&L->events);
	events_assessment(&L->events, &L->d);
	events_loads(&L->events, &L->d);
	return rc;
}

int
loop_live_frame(struct loop *L)
{
	int virtual = L->tape.mode == TAPE_VIRTUAL; /* a driven run: its solves cut by a virtual clock */
	struct ik_clock clock = { virtual ? virtual_now : real_now, L };
	int changed;
	uint64_t begun = tape_frame_begin(&L->tape);
	uint64_t draw = virtual ? 0 : (uint64_t)L->d.stats.draw_us;
	uint64_t budget = L->period_us > draw + 500 ? L->period_us - draw - 500 : L->period_us / 4;
	if (L->cfg && L->cfg->solve_budget_us && !virtual) /* set by hand (--solve-budget) */
		budget = L->cfg->solve_budget_us;
	/* what this frame changes on screen, apart from what was waiting already */
	int waiting = L->scene.dirty;
	L->scene.dirty = 0;
	int moved = loop_take_input(L) > 0;
	modes_frame(&L->modes, begun);
	dials_frame(&L->dials, begun);
	events_kiosk(&L->events);
	frame(L, &clock, budget, &changed);
	tape_frame_end(&L->tape, &L->d.env);
	/* a replay's pictures are paced by the recording's clock, not by how fast it runs */
	uint64_t now = L->tape.mode == TAPE_REPLAY || virtual ? begun : loop_real_now();
	moved |= changed || L->scene.dirty;
	L->scene.dirty |= waiting || changed;
	events_posture_changes(&L->events);
	events_assessment(&L->events, &L->d);
	events_loads(&L->events, &L->d);
	uint64_t drawn = L->scene.drawn_us;
	if (scene_publish(&L->scene, &L->d, &L->events, now)) {
		/* rendering's share of the frame, smoothed: the solver gets the rest (§4.7.2) */
		double us = (double)(L->scene.drawn_us - drawn);
		L->d.stats.draw_us = L->d.stats.draw_us ? 0.8 * L->d.stats.draw_us + 0.2 * us : us;
	}
	L->fps_frames++;
	if (now - L->fps_t0 >= 1000000) {
		L->d.stats.fps = (double)L->fps_frames * 1e6 / (double)(now - L->fps_t0);
		L->fps_t0 = now;
		L->fps_frames = 0;
	}
	return !moved && !scene_waiting(&L->scene, &L->events) &&
	       !events_wanted(&L->events, SUB_TELEMETRY | SUB_STABILITY);
}
