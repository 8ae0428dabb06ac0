/* tape_loop.c - the loop's side of the tape: each outside input recorded, or answered from the log */
#include "daemon/tape_loop.h"

#include <errno.h>
#include <inttypes.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "daemon/posture_hash.h"
#include "daemon/statefile.h"
#include "daemon/tape_read.h"

/*
 * A figure's parts as hashes, so a divergence can name them: each joint's
 * values, then the root (its site and frame), then the rest of what the
 * figure's hash covers (moved sites, behaviours). Returns the count.
 */
static int
part_hashes(const struct env_figure *f, uint64_t whole, uint32_t *dest, int max)
{
	const struct model *m = f->model;
	const struct state *s = f->state;
	int n = 0;
	for (int j = 0; j < m->njnt && n < max - 2; j++)
		dest[n++] = (uint32_t)posture_fnv(POSTURE_FNV_BASIS, &s->q[m->jnt_dof0[j]],
					  sizeof *s->q * (size_t)m->jnt_ndof[j]);
	uint64_t r = posture_fnv(POSTURE_FNV_BASIS, &s->root_site, sizeof s->root_site);
	dest[n++] = (uint32_t)posture_fnv(r, &s->root_xf, sizeof s->root_xf);
	dest[n++] = (uint32_t)whole;
	return n;
}

/* ---- astray: the replay asked for what the log does not hold next ---- */

static void
astray(struct tape *t, const char *fmt, ...)
{
	if (t->broken[0])
		return;
	char why[400];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(why, sizeof why, fmt, ap);
	va_end(ap);
	const struct tape_entry *e = tape_peek(t);
	if (e)
		snprintf(t->broken, sizeof t->broken, "%s/frames:%d: %s", t->dir, e->lineno, why);
	else
		snprintf(t->broken, sizeof t->broken, "%s/frames: at its end: %s", t->dir, why);
}

/* the next record, which must be of kind; NULL (the replay astray) otherwise */
static const struct tape_entry *
expect(struct tape *t, enum tape_kind kind, const char *wanted)
{
	const struct tape_entry *e = tape_peek(t);
	if (t->broken[0])
		return NULL;
	if (!e || e->kind != kind) {
		astray(t, "the replay wants %s, the recording has %s here", wanted,
		       e ? tape_kind_name((enum tape_kind)e->kind) : "nothing more");
		return NULL;
	}
	t->pos++;
	return e;
}

/* ---- the loop's inputs ---- */

uint64_t
tape_clock(struct tape *t)
{
	if (t->mode == TAPE_VIRTUAL)
		return t->virtual_us;
	if (t->mode == TAPE_REPLAY) {
		const struct tape_entry *e = expect(t, TAPE_CLOCK, "a clock read");
		return e ? e->t : 0;
	}
	uint64_t now = tape_real_now();
	if (t->mode == TAPE_RECORD)
		tape_out_printf(t, TAPE_OUT_FRAMES, "clock %" PRIu64 "\n", now);
	return now;
}

void
tape_client_line(struct tape *t, int client, const char *line, size_t len)
{
	if (t->mode != TAPE_RECORD)
		return;
	t->lines++;
	tape_out_printf(t, TAPE_OUT_LINES, "%" PRIu64 " %d ", tape_real_now(), client);
	tape_out_escaped(t, TAPE_OUT_LINES, line, len);
	tape_out_printf(t, TAPE_OUT_FRAMES, "line %" PRIu64 "\n", t->lines);
}

char *
tape_read_state(struct tape *t, const char *path, size_t *len)
{
	char name[64];
	if (t->mode == TAPE_REPLAY) {
		const struct tape_entry *e = expect(t, TAPE_FILE, "a state file read");
		if (!e) {
			errno = EIO;
			return NULL;
		}
		if (e->fig) { /* the read failed then: it fails alike */
			errno = e->fig;
			return NULL;
		}
		snprintf(name, sizeof name, "read.%" PRIu64, e->t);
		char full[TAPE_PATH_MAX + 64];
		snprintf(full, sizeof full, "%s/%s", t->dir, name);
		char *text = statefile_read(full, len);
		if (!text)
			astray(t, "%s: %s", full, strerror(errno));
		return text;
	}
	char *text = path ? statefile_read(path, len) : NULL; /* no path: it did not resolve */
	if (t->mode != TAPE_RECORD)
		return text;
	int why = errno;
	if (!text) {
		tape_out_printf(t, TAPE_OUT_FRAMES, "nofile %d\n", why > 0 ? why : EIO);
	} else {
		snprintf(name, sizeof name, "read.%" PRIu64, ++t->reads);
		if (tape_write_file(t, name, text, *len) < 0) {
			int bad = errno ? errno : EIO;
			pthread_mutex_lock(&t->mu);
			if (!t->write_error) {
				t->write_error = bad;
				fprintf(stderr, "postured: recording %s: %s: %s\n", t->dir, name,
					strerror(bad));
			}
			pthread_mutex_unlock(&t->mu);
		}
		tape_out_printf(t, TAPE_OUT_FRAMES, "file %" PRIu64 "\n", t->reads);
	}
	errno = why;
	return text;
}

uint64_t
tape_frame_begin(struct tape *t)
{
	if (t->mode == TAPE_VIRTUAL) {
		t->frames++;
		return t->virtual_us;
	}
	if (t->mode == TAPE_REPLAY) {
		const struct tape_entry *e = expect(t, TAPE_FRAME, "a frame");
		t->frames++;
		return e ? e->t : 0;
	}
	uint64_t now = tape_real_now();
	if (t->mode == TAPE_RECORD)
		tape_out_printf(t, TAPE_OUT_FRAMES, "frame %" PRIu64 " t=%" PRIu64 "\n", ++t->frames,
				now);
	return now;
}

const struct ik_work *
tape_ik_replay(struct tape *t, int fig)
{
	if (t->mode != TAPE_REPLAY)
		return NULL;
	const struct tape_entry *e = expect(t, TAPE_IK, "a solve's work");
	if (e && e->fig != fig) {
		t->pos--;
		astray(t, "the replay solves figure %d, the recording figure %d", fig, e->fig);
		return NULL;
	}
	return e ? &e->work : NULL;
}

void
tape_ik_done(struct tape *t, int fig, const struct ik_work *w)
{
	if (t->mode != TAPE_RECORD)
		return;
	char line[IK_WORK_LINE_MAX];
	if (ik_work_write(w, line, sizeof line) > 0)
		tape_out_printf(t, TAPE_OUT_FRAMES, "ik %d %s\n", fig, line);
}

/* n as hex digits (16 or 8) into p; returns the end */
static char *
hex(char *p, uint64_t v, int digits)
{
	static const char d[] = "0123456789abcdef";
	for (int k = digits - 1; k >= 0; k--)
		p[k] = d[v & 15], v >>= 4;
	return p + digits;
}

/*
 * After a frame: each figure whose hash changed, with its parts' hashes,
 * then the posture; formatted here and appended at once (the loop's cost
 * of recording is mostly this).
 */
static void
record_frame_end(struct tape *t, const struct env *e)
{
	uint64_t env = POSTURE_FNV_BASIS;
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		const struct env_figure *f = &e->fig[i];
		uint64_t h = f->gen ? posture_figure_hash(f) : 0;
		if (f->gen) { /* posture_env_hash's sum, from the hashes at hand */
			env = posture_fnv(env, &i, sizeof i);
			env = posture_fnv(env, &h, sizeof h);
		}
		if (h == t->fig_hash[i])
			continue;
		t->fig_hash[i] = h;
		char line[64 + TAPE_JOINTS_MAX * 9], *p = line;
		p += snprintf(p, 32, "fig %d ", i);
		p = hex(p, h, 16);
		*p++ = '\n';
		if (f->gen) {
			uint32_t part[TAPE_JOINTS_MAX];
			int n = part_hashes(f, h, part, TAPE_JOINTS_MAX);
			p += snprintf(p, 32, "joints %d", i);
			for (int k = 0; k < n; k++) {
				*p++ = ' ';
				p = hex(p, part[k], 8);
			}
			*p++ = '\n';
		}
		tape_out_bytes(t, TAPE_OUT_FRAMES, line, (size_t)(p - line));
	}
	tape_out_printf(t, TAPE_OUT_FRAMES, "posture %" PRIu64 " %016" PRIx64 "\n", t->frames, env);
}

/* what of figure i differs from the recording's, in words */
static void
name_parts(const struct tape *t, const struct env_figure *f, int i, char *dest, size_t cap)
{
	uint32_t part[TAPE_JOINTS_MAX];
	size_t used = 0;
	dest[0] = 0;
	if (!f->gen) {
		snprintf(dest, cap, "the figure is gone");
		return;
	}
	int n = part_hashes(f, posture_figure_hash(f), part, TAPE_JOINTS_MAX), live = t->live_njoints[i];
	if (n != live) {
		snprintf(dest, cap, "%d parts, the recording %d", n, live);
		return;
	}
	const struct model *m = f->model;
	for (int k = 0; k < n && used + 40 < cap; k++) {
		if (part[k] == t->live_joints[i][k])
			continue;
		const char *name = k < n - 2 ? m->jnt_name[k] : k == n - 2 ? "(root)" : "(behaviours)";
		used += (size_t)snprintf(dest + used, cap - used, "%s%s", used ? " " : "", name);
	}
	if (!used)
		snprintf(dest, cap, "(nothing named)");
}

/* the recorded records after a frame: the figures' hashes and the posture */
static void
replay_frame_end(struct tape *t, const struct env *e)
{
	const struct tape_entry *x;
	while ((x = tape_peek(t)) && (x->kind == TAPE_FIG || x->kind == TAPE_JOINTS)) {
		if (x->fig >= 0 && x->fig < ENV_MAX_FIGURES) {
			if (x->kind == TAPE_FIG) {
				t->live_fig[x->fig] = x->hash;
			} else {
				int n = x->njoints < TAPE_JOINTS_MAX ? x->njoints : TAPE_JOINTS_MAX;
				memcpy(t->live_joints[x->fig], x->joints, sizeof(uint32_t) * (size_t)n);
				t->live_njoints[x->fig] = n;
			}
		}
		t->pos++;
	}
	if (!(x = expect(t, TAPE_POSTURE, "a frame's end")))
		return;
	t->last_posture = posture_env_hash(e);
	if (t->last_posture == x->hash)
		return;
	if (t->divergences++)
		return;
	t->first.frame = t->frames;
	t->first.fig = -1;
	snprintf(t->first.what, sizeof t->first.what, "posture %016" PRIx64 ", the recording's %016" PRIx64,
		 t->last_posture, x->hash);
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		const struct env_figure *f = &e->fig[i];
		uint64_t h = f->gen ? posture_figure_hash(f) : 0;
		if (h == t->live_fig[i])
			continue;
		char parts[400];
		name_parts(t, f, i, parts, sizeof parts);
		t->first.fig = i;
		snprintf(t->first.what, sizeof t->first.what, "figure %d (%s) differs: %s", i,
			 f->gen ? f->name : "-", parts);
		break;
	}
}

void
tape_frame_end(struct tape *t, const struct env *e)
{
	if (t->mode == TAPE_RECORD)
		record_frame_end(t, e);
	else if (t->mode == TAPE_REPLAY)
		replay_frame_end(t, e);
}
