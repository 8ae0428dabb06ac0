/* session.c - sessions and postures as versioned text */
#include "daemon/session.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "pose/attach.h"
#include "pose/behave.h"
#include "pose/eyeview.h"
#include "figure/figure.h"
#include "figure/human.h"
#include "figure/kin.h"
#include "daemon/family.h"
#include "daemon/manikin.h"
#include "daemon/words.h"
#include "assess/assess.h"

static const char *const pos_names[] = { "none", "point", "line", "plane" };
static const char *const ori_names[] = { "none", "frame", "direction", "aim" };

static void
write_xform(FILE *f, const struct xform *x)
{
	for (int i = 0; i < 3; i++)
		fprintf(f, "%s%.17g", i ? "," : "", x->p[i]);
	for (int i = 0; i < 9; i++)
		fprintf(f, ",%.17g", x->r[i]);
}

/* "text" with '"' and '\\' escaped, as words_split reads them */
static void
write_quoted(FILE *f, const char *s)
{
	fputc('"', f);
	for (; *s; s++) {
		if (*s == '"' || *s == '\\')
			fputc('\\', f);
		fputc(*s, f);
	}
	fputc('"', f);
}

static void
write_vec(FILE *f, const double *v, int n)
{
	for (int i = 0; i < n; i++)
		fprintf(f, "%s%.17g", i ? "," : "", v[i]);
}

static void
write_figure_posture(const struct env_figure *fg, FILE *f)
{
	const struct model *m = fg->model;
	const struct state *s = fg->state;
	char site[2 * MODEL_NAME_MAX];
	/* sites moved on their segments first: the root's frame and the q depend on them */
	for (int k = 0; k < m->nsite; k++)
		if (m->site_moved[k]) {
			fprintf(f, "site %s %s ", fg->name, model_site_fullname(m, k, site, sizeof site));
			write_vec(f, &m->site_pos[3 * k], 3);
			fprintf(f, ",");
			write_vec(f, &m->site_quat[4 * k], 4);
			fprintf(f, "\n");
		}
	fprintf(f, "root %s %s ", fg->name, model_site_fullname(m, s->root_site, site, sizeof site));
	write_xform(f, &s->root_xf);
	/* one comma-separated word: a figure may have more dofs than a line has words */
	fprintf(f, "\nq %s ", fg->name);
	if (m->ndof)
		write_vec(f, s->q, m->ndof);
	else
		fprintf(f, "-");
	fprintf(f, "\n");
}

/* the fields of a constraint's definition, after its head */
static void
write_def(FILE *f, const struct model *m, const struct ik_constraint_def *d)
{
	char site[2 * MODEL_NAME_MAX];
	fprintf(f, " enabled=%d effector=%s", d->enabled,
		model_site_fullname(m, d->effector_site, site, sizeof site));
	fprintf(f, " effoff=");
	write_xform(f, &d->effector_offset);
	fprintf(f, " goalsite=%s",
		d->goal_site >= 0 ? model_site_fullname(m, d->goal_site, site, sizeof site) : "-");
	fprintf(f, " goal=");
	write_xform(f, &d->goal_xf);
	fprintf(f, " pos=%s ori=%s axis=", pos_names[d->pos], ori_names[d->ori]);
	write_vec(f, d->goal_axis, 3);
	fprintf(f, " effaxis=");
	write_vec(f, d->effector_axis, 3);
	fprintf(f, " posweight=%.17g weight=%.17g start=%s group=%d com=%d\n", d->pos_weight,
		d->weight, d->start_joint >= 0 ? m->jnt_name[d->start_joint] : "-", d->group,
		d->com_effector);
}

/* a behaving figure: its packed parameters and state, then its constraints */
static void
write_behave(const struct env_figure *fg, FILE *f)
{
	double v[256];
	int n = behave_pack(fg->behave, v, 256);
	fprintf(f, "behave %s ", fg->name);
	write_vec(f, v, n);
	/* a hand held on a site: the site by name, as every site kept (its index may move) */
	char site[2 * MODEL_NAME_MAX];
	for (int k = 0; k < 2; k++) {
		const struct behave_params *p = &fg->behave->p;
		if (p->hand[k] == HAND_ON_SITE && p->hand_site[k] >= 0 &&
		    p->hand_site[k] < fg->model->nsite)
			fprintf(f, " hand_%c=%s", "lr"[k],
				model_site_fullname(fg->model, p->hand_site[k], site, sizeof site));
	}
	fprintf(f, "\n");
	for (int k = 0; k < BEHAVE_NCON; k++) {
		fprintf(f, "bdef %s %d", fg->name, k);
		write_def(f, fg->model, behave_def(fg->behave, fg->ik, k));
	}
}

/* the assessments' settings, every key (a default that changes later leaves a session as it was) */
static void
write_assess(const struct assess_config *cfg, FILE *f)
{
	fprintf(f, "assess");
	for (size_t k = 0; k < assess_config_nkeys; k++) {
		const struct assess_config_key *key = &assess_config_keys[k];
		double v;
		memcpy(&v, (const char *)cfg + key->offset, sizeof v);
		fprintf(f, " %s=%.17g", key->key, v);
	}
	fprintf(f, "\n");
}

/* "load NAME slot= gen= figure= site= mass=KG | force=FX,FY,FZ torque=TX,TY,TZ" (session 5) */
static void
write_load(const struct env *e, int slot, FILE *f)
{
	const struct env_load *l = &e->load[slot];
	if (!l->gen)
		return;
	const struct env_figure *fg = &e->fig[l->fig];
	char site[2 * MODEL_NAME_MAX];
	fprintf(f, "load %s slot=%d gen=%u figure=%s site=%s", l->name, slot, l->gen, fg->name,
		model_site_fullname(fg->model, l->site, site, sizeof site));
	if (l->mass > 0) { /* a weight is its mass: its force follows from it */
		fprintf(f, " mass=%.17g\n", l->mass);
		return;
	}
	fprintf(f, " force=");
	write_vec(f, l->force, 3);
	fprintf(f, " torque=");
	write_vec(f, l->torque, 3);
	fprintf(f, "\n");
}

int
session_write(const struct env *e, FILE *f)
{
	return session_write_with(e, NULL, f);
}

int
session_write_with(const struct env *e, const struct assess_config *cfg, FILE *f)
{
	fprintf(f, "session %d\nnext_gen %u\n", SESSION_VERSION, e->next_gen);
	for (int i = 0; i < ENV_MAX_FIGURES; i++) {
		const struct env_figure *fg = &e->fig[i];
		if (!fg->gen)
			continue;
		if (fg->is_human) {
			fprintf(f, "figure %s slot=%d gen=%u human stature=%.17g mass=%.17g sex=%s",
				fg->name, i, fg->gen, fg->human.stature, fg->human.mass,
				fg->human.sex == HUMAN_FEMALE ? "female" : "male");
			manikin_write_words(fg, f);
			fprintf(f, "\n");
		} else {
			fprintf(f, "figure %s slot=%d gen=%u file ", fg->name, i, fg->gen);
			write_quoted(f, fg->path);
			fprintf(f, "\n");
		}
		write_figure_posture(fg, f);
	}
	for (int i = 0; i < ENV_MAX_CONSTRAINTS; i++) {
		const struct env_constraint *c = &e->con[i];
		if (!c->gen || c->transient)
			continue;
		const struct env_figure *fg = &e->fig[c->fig];
		const struct model *m = fg->model;
		fprintf(f, "constraint %s slot=%d gen=%u figure=%s", c->name, i, c->gen, fg->name);
		write_def(f, m, &c->def);
	}
	for (int i = 0; i < ENV_MAX_LOADS; i++)
		write_load(e, i, f);
	for (int i = 0; i < ENV_MAX_FIGURES; i++)
		if (e->fig[i].gen && e->fig[i].behave)
			write_behave(&e->fig[i], f);
	for (int i = 0; i < ENV_MAX_ATTACH; i++) {
		const struct env_attach *a = &e->att[i];
		if (!a->used)
			continue;
		fprintf(f, "attach %s limb=%s side=%s kind=%s object=%s segment=%s rel=",
			e->fig[a->fig].name, a->limb == ATTACH_HAND ? "hand" : "foot",
			a->side ? "right" : "left", a->kind == ATTACH_GRAB ? "grab" : "local",
			e->fig[a->obj].name, e->fig[a->obj].model->seg_name[a->seg]);
		write_xform(f, &a->rel);
		fprintf(f, "\n");
	}
	for (int i = 0; i < ENV_MAX_VIEWS; i++) {
		const struct env_view *v = &e->view[i];
		if (!v->used)
			continue;
		fprintf(f, "view %s width=%d height=%d icons=%d eye=", v->name, v->width, v->height,
			v->icons);
		write_vec(f, v->eye, 3);
		fprintf(f, " target=");
		write_vec(f, v->target, 3);
		fprintf(f, " fovy=%.17g", v->fovy_deg);
		if (v->tint != ENV_TINT_OFF) /* written only when on: untinted views read as before */
			fprintf(f, " tint=%s", env_tint_str(v->tint));
		if (v->loads_hidden) /* likewise: only when the loads' arrows are off */
			fprintf(f, " loads=off");
		if (v->eyes[0]) /* likewise: only a view through a figure's eyes */
			fprintf(f, " eyes=%s which=%s hfov=%.17g", v->eyes,
				eyeview_which_str(v->eyes_which), v->hfov_deg);
		if (v->eyes[0] && !eyeview_cones_default(v)) { /* and its cones when not the default */
			fprintf(f, " cones=%s", v->ncones ? "" : "off");
			for (int k = 0; k < v->ncones; k++)
				fprintf(f, "%s%.17g", k ? "," : "", v->cones_deg[k]);
		}
		if (v->sight[0]) /* likewise: only a view drawing sight cones */
			fprintf(f, " sight=%s sight_length=%.17g", v->sight, v->sight_len);
		fprintf(f, "\n");
	}
	if (e->nlayout) {
		fprintf(f, "layout");
		for (int i = 0; i < e->nlayout; i++)
			fprintf(f, " %s", e->view[e->layout[i]].name);
		fprintf(f, "\n");
	}
	int sel = family_selected(e);
	if (sel >= 0) /* a family shown, with members left */
		fprintf(f, "show family %s %s select=%s spacing=%.17g\n", e->show.family,
			e->show.arrange == ENV_SHOW_ROW ? "row" : "overlay", e->fig[sel].name,
			e->show.spacing);
	if (cfg)
		write_assess(cfg, f);
	fprintf(f, "end\n");
	return ferror(f) ? -1 : 0;
}

char *
session_to_string(const struct env *e, size_t *len)
{
	return session_to_string_with(e, NULL, len);
}

char *
session_to_string_with(const struct env *e, const struct assess_config *cfg, size_t *len)
{
	char *buf = NULL;
	size_t n = 0;
	FILE *f = open_memstream(&buf, &n);
	if (!f)
		return NULL;
	int rc = session_write_with(e, cfg, f);
	if (fclose(f) != 0 || rc < 0) {
		free(buf);
		return NULL;
	}
	*len = n;
	return buf;
}

/* ---- reading ----------------------------------------------------------- */

struct reader {
	const char *text, *end;
	int line;
	char *err;
	size_t errlen;
	struct words w;
	struct assess_config assess; /* a session's: the defaults, then its assess line */
};

static int
fail(struct reader *r, const char *fmt, ...)
{
	char msg[200];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	snprintf(r->err, r->errlen, "line %d: %s", r->line, msg);
	return -1;
}

/* the next non-empty line as words; 1, 0 at the end, -1 on error */
static int
next_line(struct reader *r)
{
	while (r->text < r->end) {
		const char *nl = memchr(r->text, '\n', (size_t)(r->end - r->text));
		size_t len = nl ? (size_t)(nl - r->text) : (size_t)(r->end - r->text);
		const char *line = r->text;
		r->text = nl ? nl + 1 : r->end;
		r->line++;
		if (len > WORDS_LINE_MAX)
			return fail(r, "line too long");
		const char *msg;
		enum words_status st = words_split(line, len, &r->w, &msg);
		if (st == WORDS_EMPTY)
			continue;
		if (st != WORDS_OK)
			return fail(r, "%s", msg);
		return 1;
	}
	return 0;
}

/* value of "key=..." among words from index `from`; NULL when absent */
static const char *
arg(const struct words *w, int from, const char *key)
{
	for (int i = from; i < w->n; i++)
		if (words_is_key(w->w[i], key))
			return w->w[i] + strlen(key) + 1;
	return NULL;
}

static int
read_xform(const char *s, struct xform *dest)
{
	double v[12];
	if (!s || words_list(s, UNIT_NONE, 12, v) < 0)
		return -1;
	memcpy(dest->p, v, sizeof dest->p);
	memcpy(dest->r, v + 3, sizeof dest->r);
	return 0;
}

static int
read_uint(const char *s, unsigned long max, unsigned long *dest)
{
	char *end;
	if (!s || !*s || *s == '-')
		return -1;
	*dest = strtoul(s, &end, 10);
	return *end || *dest > max ? -1 : 0;
}

static int
lookup(const char *const *names, int n, const char *s)
{
	for (int i = 0; s && i < n; i++)
		if (!strcmp(names[i], s))
			return i;
	return -1;
}

static int
find_fig(struct env *e, const char *name)
{
	for (int i = 0; i < ENV_MAX_FIGURES; i++)
		if (e->fig[i].gen && !strcmp(e->fig[i].name, name))
			return i;
	return -1;
}

/*
 * A figure file's path as load figure takes it: relative to the state
 * directory with no ".." in it, or "lib:NAME" with NAME a file of the
 * library. A session reaches no other file (one outside could be a FIFO or
 * a terminal, and the daemon would wait on it for ever).
 */
static int
path_inside(const char *path)
{
	if (!strncmp(path, "lib:", 4))
		return path[4] && path[4] != '.' && !strchr(path + 4, '/');
	if (!path[0] || path[0] == '/')
		return 0;
	for (const char *p = path; p; p = strchr(p, '/') ? strchr(p, '/') + 1 : NULL)
		if (!strncmp(p, "..", 2) && (p[2] == '/' || !p[2]))
			return 0;
	return 1;
}

static int
read_figure(struct reader *r, struct env *e, const char *base_dir, const char *library_dir)
{
	struct words *w = &r->w;
	unsigned long slot, gen;
	if (w->n < 5 || !words_is_name(w->w[1]) || read_uint(arg(w, 2, "slot"), ENV_MAX_FIGURES - 1, &slot) < 0 ||
	    read_uint(arg(w, 2, "gen"), 0xffffffffu, &gen) < 0 || gen == 0)
		return fail(r, "expected: figure NAME slot=N gen=G human|file ...");
	if (e->fig[slot].gen || find_fig(e, w->w[1]) >= 0)
		return fail(r, "figure %s or its slot appears twice", w->w[1]);
	char err[300];
	struct model *m = NULL;
	struct human_def hd = human_default_def(HUMAN_MALE);
	struct env_manikin mk = { .percentile = NAN, .coverage = NAN };
	int human = !strcmp(w->w[4], "human");
	const char *path = NULL;
	if (human) {
		const char *sex = arg(w, 5, "sex");
		if (!sex || (strcmp(sex, "male") && strcmp(sex, "female")))
			return fail(r, "a human needs sex=male|female");
		hd.sex = !strcmp(sex, "male") ? HUMAN_MALE : HUMAN_FEMALE;
		if (words_number(arg(w, 5, "stature") ? arg(w, 5, "stature") : "x", UNIT_LENGTH, &hd.stature) < 0 ||
		    words_number(arg(w, 5, "mass") ? arg(w, 5, "mass") : "x", UNIT_NONE, &hd.mass) < 0)
			return fail(r, "a human needs stature= and mass=");
		if (manikin_read_words(w, 5, &hd, &mk, err, sizeof err) < 0)
			return fail(r, "figure %s: %s", w->w[1], err);
		m = human_build(&hd, err, sizeof err);
	} else if (!strcmp(w->w[4], "file") && w->n == 6) {
		path = w->w[5];
		if (strlen(path) >= ENV_PATH_MAX)
			return fail(r, "figure %s: a path longer than %d bytes", w->w[1], ENV_PATH_MAX - 1);
		if (!path_inside(path))
			return fail(r, "figure %s: its file must be inside the state directory (a relative "
				       "path without '..'), or lib:NAME of the library", w->w[1]);
		char full[2 * ENV_PATH_MAX + 4200];
		if (!strncmp(path, "lib:", 4))
			snprintf(full, sizeof full, "%s/%s", library_dir ? library_dir : ".", path + 4);
		else
			snprintf(full, sizeof full, "%s/%s", base_dir ? base_dir : ".", path);
		m = figure_read_file(full, err, sizeof err);
	} else {
		return fail(r, "a figure is 'human ...' or 'file PATH'");
	}
	if (!m)
		return fail(r, "figure %s: %s", w->w[1], err);
	/* put it in its slot with its generation, as it was */
	uint32_t keep = e->next_gen;
	int got = env_add_figure(e, m, w->w[1], human, &hd, path);
	if (got < 0)
		return fail(r, "figure %s could not be added", w->w[1]);
	if (got != (int)slot) { /* move it into the recorded slot */
		e->fig[slot] = e->fig[got];
		memset(&e->fig[got], 0, sizeof e->fig[got]);
	}
	e->fig[slot].gen = (uint32_t)gen;
	if (human)
		e->fig[slot].manikin = mk;
	e->next_gen = keep;
	return 0;
}

static int
read_root(struct reader *r, struct env *e)
{
	struct words *w = &r->w;
	int fig = w->n == 4 ? find_fig(e, w->w[1]) : -1;
	if (fig < 0)
		return fail(r, "expected: root FIGURE SEG.SITE XFORM for a figure defined above");
	struct env_figure *f = &e->fig[fig];
	int site = model_find_site(f->model, w->w[2]);
	struct xform x;
	if (site < 0 || read_xform(w->w[3], &x) < 0)
		return fail(r, "bad root site or frame");
	state_root_at(f->model, f->state, site, &x);
	kin_update(f->model, f->state);
	return 0;
}

/* site FIGURE SEG.SITE X,Y,Z,QX,QY,QZ,QW: a site moved on its segment */
static int
read_site(struct reader *r, struct env *e)
{
	struct words *w = &r->w;
	int fig = w->n == 4 ? find_fig(e, w->w[1]) : -1;
	if (fig < 0)
		return fail(r, "expected: site FIGURE SEG.SITE X,Y,Z,QX,QY,QZ,QW for a figure defined above");
	struct env_figure *f = &e->fig[fig];
	int site = model_find_site(f->model, w->w[2]);
	double v[7];
	if (site < 0 || words_list(w->w[3], UNIT_NONE, 7, v) < 0)
		return fail(r, "no site %s on %s, or not 7 numbers", w->w[2], f->name);
	double n2 = v[3] * v[3] + v[4] * v[4] + v[5] * v[5] + v[6] * v[6];
	if (!(fabs(n2 - 1) < 1e-9) || !(fabs(v[0]) < 1e6 && fabs(v[1]) < 1e6 && fabs(v[2]) < 1e6))
		return fail(r, "site %s: the quaternion is not of unit length, or the position is wild",
			    w->w[2]);
	model_set_site(f->model, site, v, v + 3);
	f->ik_stale = 1;
	kin_update(f->model, f->state);
	return 0;
}

static int
read_q(struct reader *r, struct env *e)
{
	struct words *w = &r->w;
	int fig = w->n == 3 ? find_fig(e, w->w[1]) : -1;
	if (fig < 0)
		return fail(r, "expected: q FIGURE V0,V1,... for a figure defined above");
	struct env_figure *f = &e->fig[fig];
	const struct model *m = f->model;
	double *q = malloc(sizeof *q * (size_t)(m->ndof + 1));
	if (!q)
		return fail(r, "out of memory");
	int ok = m->ndof == 0 ? !strcmp(w->w[2], "-") : words_list(w->w[2], UNIT_NONE, m->ndof, q) == 0;
	for (int d = 0; ok && d < m->ndof; d++)
		ok = q[d] >= m->dof_lo[d] && q[d] <= m->dof_hi[d];
	if (ok)
		memcpy(f->state->q, q, sizeof *q * (size_t)m->ndof);
	free(q);
	if (!ok)
		return fail(r, "figure %s needs %d values within their limits", f->name, m->ndof);
	kin_update(m, f->state);
	return 0;
}

/* a constraint definition from key=value words (from index from on) */
static int
read_def(struct reader *r, int from, const struct model *m, struct ik_constraint_def *dest)
{
	struct words *w = &r->w;
	struct ik_constraint_def d = ik_constraint_default_def();
	unsigned long group;
	const char *eff = arg(w, from, "effector"), *gs = arg(w, from, "goalsite"),
		   *st = arg(w, from, "start");
	d.effector_site = eff ? model_find_site(m, eff) : -1;
	d.goal_site = gs && strcmp(gs, "-") ? model_find_site(m, gs) : -1;
	d.start_joint = st && strcmp(st, "-") ? model_find_joint(m, st) : -1;
	int pos = lookup(pos_names, 4, arg(w, from, "pos")), ori = lookup(ori_names, 4, arg(w, from, "ori"));
	const char *en = arg(w, from, "enabled"), *com = arg(w, from, "com");
	if (d.effector_site < 0 || (gs && strcmp(gs, "-") && d.goal_site < 0) ||
	    (st && strcmp(st, "-") && d.start_joint < 0) || pos < 0 || ori < 0 || !en || !com ||
	    read_uint(arg(w, from, "group"), 3, &group) < 0 ||
	    read_xform(arg(w, from, "effoff"), &d.effector_offset) < 0 ||
	    read_xform(arg(w, from, "goal"), &d.goal_xf) < 0 ||
	    words_list(arg(w, from, "axis"), UNIT_NONE, 3, d.goal_axis) < 0 ||
	    words_list(arg(w, from, "effaxis"), UNIT_NONE, 3, d.effector_axis) < 0 ||
	    words_number(arg(w, from, "posweight") ? arg(w, from, "posweight") : "", UNIT_NONE, &d.pos_weight) < 0 ||
	    words_number(arg(w, from, "weight") ? arg(w, from, "weight") : "", UNIT_NONE, &d.weight) < 0)
		return -1;
	d.pos = (enum ik_pos)pos;
	d.ori = (enum ik_ori)ori;
	d.enabled = !strcmp(en, "1");
	d.com_effector = !strcmp(com, "1");
	d.group = (int)group;
	*dest = d;
	return 0;
}

/*
 * The sites the hands are held on: by name (hand_l=, hand_r=), or, in what
 * was written before names were, the packed site index; a human's from
 * before it carried its landmark sites (figure/human.h). 0, or -1.
 */
static int
behave_hand_sites(struct behave *b, const struct env_figure *f, const char *const name[2])
{
	for (int k = 0; k < 2; k++) {
		int *site = &b->p.hand_site[k], on = b->p.hand[k] == HAND_ON_SITE;
		if (name[k]) {
			*site = model_find_site(f->model, name[k]);
			if (!on || *site < 0)
				return -1;
		} else if (on && *site >= 0 && f->is_human) {
			*site = human_site_before_landmarks(f->model, *site);
			if (*site < 0)
				return -1;
		}
	}
	return 0;
}

/* "behave FIG V0,V1,... [hand_l=SITE] [hand_r=SITE]" and "bdef FIG K fields": a figure's behaviours */
static int
read_behave(struct reader *r, struct env *e)
{
	struct words *w = &r->w;
	int fig = w->n >= 3 ? find_fig(e, w->w[1]) : -1;
	if (fig < 0)
		return fail(r, "expected: %s FIGURE ... for a figure defined above", w->w[0]);
	struct env_figure *f = &e->fig[fig];
	if (!strcmp(w->w[0], "bdef")) {
		unsigned long k;
		if (!f->behave || read_uint(w->w[2], BEHAVE_NCON - 1, &k) < 0 ||
		    read_def(r, 3, f->model, &f->behave->def[k]) < 0)
			return fail(r, "bad behaviour constraint for %s", f->name);
		f->behave->detached = 1;
		f->ik_stale = 1;
		return 0;
	}
	double v[256];
	int n = 1;
	for (const char *c = w->w[2]; *c; c++)
		n += *c == ',';
	const char *hand_at[2] = { arg(w, 3, "hand_l"), arg(w, 3, "hand_r") };
	int extra = (hand_at[0] != NULL) + (hand_at[1] != NULL);
	/* unpacked into a copy (it keeps the constraints' definitions): nothing changes on an error */
	static struct behave zero;
	struct behave *b = malloc(sizeof *b);
	if (b)
		*b = f->behave ? *f->behave : zero;
	if (!b || n > 256 || w->n != 3 + extra || words_list(w->w[2], UNIT_NONE, n, v) < 0 ||
	    behave_unpack(b, f->model, v, n) < 0 || behave_hand_sites(b, f, hand_at) < 0) {
		free(b);
		return fail(r, "bad behaviour state for %s", f->name);
	}
	if (f->behave) {
		*f->behave = *b;
		free(b);
	} else {
		f->behave = b;
	}
	f->ik_stale = 1;
	/* what the behaviours measure, measured again on the posture read above (f->behave:
	 * b may have been copied into it and freed) */
	behave_measure(f->behave, f->model, f->state);
	return 0;
}

static int
read_constraint(struct reader *r, struct env *e)
{
	struct words *w = &r->w;
	unsigned long slot, gen, group;
	const char *figname = arg(w, 2, "figure");
	int fig = figname ? find_fig(e, figname) : -1;
	if (w->n < 3 || !words_is_name(w->w[1]) || fig < 0 ||
	    read_uint(arg(w, 2, "slot"), ENV_MAX_CONSTRAINTS - 1, &slot) < 0 ||
	    read_uint(arg(w, 2, "gen"), 0xffffffffu, &gen) < 0 || gen == 0 ||
	    read_uint(arg(w, 2, "group"), 3, &group) < 0)
		return fail(r, "expected: constraint NAME slot=N gen=G figure=FIG ... group=G");
	const struct model *m = e->fig[fig].model;
	struct ik_constraint_def d;
	if (read_def(r, 2, m, &d) < 0)
		return fail(r, "constraint %s: a field is missing or bad", w->w[1]);
	d.group = (int)group;
	if (e->con[slot].gen)
		return fail(r, "constraint slot %lu appears twice", slot);
	/* the solver checks the definition itself */
	if (ik_add(e->fig[fig].ik, m, &d) < 0)
		return fail(r, "constraint %s is not a valid definition", w->w[1]);
	struct env_constraint *c = &e->con[slot];
	c->gen = (uint32_t)gen;
	snprintf(c->name, sizeof c->name, "%s", w->w[1]);
	c->fig = fig;
	c->def = d;
	e->fig[fig].ik_stale = 1;
	return 0;
}

/*
 * "load NAME slot=N gen=G figure=FIG site=SEG.SITE mass=KG" or "... force=
 * FX,FY,FZ torque=TX,TY,TZ": a load on a figure defined above (session 5)
 */
static int
read_load(struct reader *r, struct env *e)
{
	struct words *w = &r->w;
	unsigned long slot, gen;
	const char *figname = arg(w, 2, "figure"), *site = arg(w, 2, "site"), *mass = arg(w, 2, "mass"),
		   *force = arg(w, 2, "force"), *torque = arg(w, 2, "torque");
	struct env_load l = { .fig = figname ? find_fig(e, figname) : -1 };
	l.site = l.fig >= 0 && site ? model_find_site(e->fig[l.fig].model, site) : -1;
	int weight = mass && !force && !torque && w->n == 7;
	int pushed = !mass && force && torque && w->n == 8;
	if (w->n < 7 || !words_is_name(w->w[1]) || l.fig < 0 ||
	    read_uint(arg(w, 2, "slot"), ENV_MAX_LOADS - 1, &slot) < 0 ||
	    read_uint(arg(w, 2, "gen"), 0xffffffffu, &gen) < 0 || gen == 0 || !(weight || pushed))
		return fail(r, "expected: load NAME slot=N gen=G figure=FIG site=SEG.SITE mass=KG | "
			       "force=FX,FY,FZ torque=TX,TY,TZ, for a figure defined above");
	if (l.site < 0)
		return fail(r, "load %s: %s has no site %s", w->w[1], figname, site ? site : "(none)");
	if (weight && (words_number(mass, UNIT_NONE, &l.mass) < 0 || !(l.mass > 0)))
		return fail(r, "load %s: mass= a number of kg above 0", w->w[1]);
	if (weight)
		l.force[1] = -l.mass * LOAD_GRAVITY;
	if (pushed && (words_list(force, UNIT_NONE, 3, l.force) < 0 ||
		       words_list(torque, UNIT_NONE, 3, l.torque) < 0))
		return fail(r, "load %s: force= and torque= three numbers each", w->w[1]);
	if (e->load[slot].gen || env_find_load(e, w->w[1]) >= 0)
		return fail(r, "load %s or its slot appears twice", w->w[1]);
	uint32_t keep = e->next_gen;
	int got = env_add_load(e, w->w[1], &l);
	if (got < 0)
		return fail(r, "load %s: out of range (at most %g N, %g N m, %g kg)", w->w[1],
			    ENV_LOAD_FORCE_MAX, ENV_LOAD_TORQUE_MAX, ENV_LOAD_MASS_MAX);
	if (got != (int)slot) { /* into the recorded slot */
		e->load[slot] = e->load[got];
		memset(&e->load[got], 0, sizeof e->load[got]);
	}
	e->load[slot].gen = (uint32_t)gen;
	e->next_gen = keep;
	return 0;
}

/* "attach FIG limb= side= kind= object= segment= rel=": a hand or foot held to a figure */
static int
read_attach(struct reader *r, struct env *e)
{
	static const char *const limbs[] = { "hand", "foot" }, *const sides[] = { "left", "right" },
				  *const kinds[] = { "grab", "local" };
	struct words *w = &r->w;
	struct env_attach a = { .used = 1 };
	const char *obj = arg(w, 2, "object"), *seg = arg(w, 2, "segment");
	a.fig = w->n == 8 ? find_fig(e, w->w[1]) : -1;
	a.obj = obj ? find_fig(e, obj) : -1;
	a.limb = (enum attach_limb)lookup(limbs, 2, arg(w, 2, "limb"));
	a.side = lookup(sides, 2, arg(w, 2, "side"));
	a.kind = (enum attach_kind)lookup(kinds, 2, arg(w, 2, "kind"));
	a.seg = a.obj >= 0 && seg ? model_find_segment(e->fig[a.obj].model, seg) : -1;
	if (a.fig < 0 || a.obj < 0 || (int)a.limb < 0 || a.side < 0 || (int)a.kind < 0 || a.seg < 0 ||
	    read_xform(arg(w, 2, "rel"), &a.rel) < 0)
		return fail(r, "expected: attach FIG limb=hand|foot side=left|right kind=grab|local "
			       "object=FIG segment=SEG rel=12 numbers, for figures defined above");
	if (attach_add(e, &a) < 0)
		return fail(r, "attachment of %s to %s is not possible (behaviours off? twice?)",
			    w->w[1], obj);
	return 0;
}

/*
 * "view NAME width= height= icons= eye= target= [fovy=] [tint=] [loads=off]
 * [eyes=FIG which= hfov= [cones=]] [sight=FIG|all sight_length=M]": fovy (degrees),
 * tint (an assessment's colours, off when absent), loads (the loads' arrows, on when
 * absent), the eye view's three (a camera of its own when absent) and the sight
 * cones (none when absent) came later
 */
static int
read_view(struct reader *r, struct env *e)
{
	struct words *w = &r->w;
	unsigned long wd, ht, icons;
	struct env_view v = { .used = 1, .fovy_deg = ENV_VIEW_FOVY_DEG };
	const char *fovy = arg(w, 2, "fovy"), *tint = arg(w, 2, "tint"), *loads = arg(w, 2, "loads");
	if (tint && (v.tint = env_tint_find(tint)) < 0)
		return fail(r, "view %s: tint=rula|reba|owas|strength|off", w->w[1]);
	if (loads && strcmp(loads, "on") && strcmp(loads, "off"))
		return fail(r, "view %s: loads=on|off", w->w[1]);
	v.loads_hidden = loads && !strcmp(loads, "off");
	const char *eyes = arg(w, 2, "eyes"), *which = arg(w, 2, "which"), *hfov = arg(w, 2, "hfov");
	if (eyes && (!words_is_name(eyes) || !which || !hfov ||
		     (v.eyes_which = eyeview_which_find(which)) < 0 ||
		     words_number(hfov, UNIT_NONE, &v.hfov_deg) < 0 || v.hfov_deg < EYEVIEW_HFOV_MIN ||
		     v.hfov_deg > EYEVIEW_HFOV_MAX))
		return fail(r, "view %s: eyes=FIG which=left|right|both hfov=%g..%g", w->w[1],
			    EYEVIEW_HFOV_MIN, EYEVIEW_HFOV_MAX);
	const char *cones = arg(w, 2, "cones");
	if (eyes)
		snprintf(v.eyes, sizeof v.eyes, "%s", eyes);
	if (eyes)
		v.ncones = eyeview_default_cones(v.cones_deg);
	if (cones && (!eyes || (v.ncones = eyeview_parse_cones(cones, v.cones_deg)) < 0))
		return fail(r, "view %s: cones=off|DEG,... (1 to %d, an eye view's)", w->w[1],
			    ENV_VIEW_CONES);
	for (int k = v.ncones; k < ENV_VIEW_CONES; k++)
		v.cones_deg[k] = 0;
	const char *sight = arg(w, 2, "sight"), *sight_len = arg(w, 2, "sight_length");
	if (sight && (!sight_len || !words_is_name(sight) ||
		      words_number(sight_len, UNIT_NONE, &v.sight_len) < 0 ||
		      v.sight_len < EYEVIEW_SIGHT_LEN_MIN || v.sight_len > EYEVIEW_SIGHT_LEN_MAX))
		return fail(r, "view %s: sight=FIG|all sight_length=%g..%g", w->w[1],
			    EYEVIEW_SIGHT_LEN_MIN, EYEVIEW_SIGHT_LEN_MAX);
	if (sight)
		snprintf(v.sight, sizeof v.sight, "%s", sight);
	if (w->n != 7 + (fovy != NULL) + (tint != NULL) + (loads != NULL) + 3 * (eyes != NULL) +
			    (cones != NULL) + 2 * (sight != NULL) ||
	    !words_is_name(w->w[1]) ||
	    env_find_view(e, w->w[1]) >= 0 ||
	    read_uint(arg(w, 2, "width"), 16384, &wd) < 0 || wd < 16 ||
	    read_uint(arg(w, 2, "height"), 16384, &ht) < 0 || ht < 16 ||
	    read_uint(arg(w, 2, "icons"), 1, &icons) < 0 ||
	    words_list(arg(w, 2, "eye"), UNIT_NONE, 3, v.eye) < 0 ||
	    words_list(arg(w, 2, "target"), UNIT_NONE, 3, v.target) < 0 ||
	    (fovy && (words_number(fovy, UNIT_NONE, &v.fovy_deg) < 0 ||
		      v.fovy_deg < ENV_VIEW_FOVY_MIN || v.fovy_deg > ENV_VIEW_FOVY_MAX)))
		return fail(r, "expected: view NAME width=W height=H icons=0|1 eye=X,Y,Z target=X,Y,Z "
			       "[fovy=DEG] [tint=rula|reba|owas|strength|off] [loads=on|off] "
			       "[eyes=FIG which=left|right|both hfov=DEG [cones=off|DEG,...]] "
			       "[sight=FIG|all sight_length=M]");
	snprintf(v.name, sizeof v.name, "%s", w->w[1]);
	v.width = (int)wd;
	v.height = (int)ht;
	v.icons = (int)icons;
	for (int i = 0; i < ENV_MAX_VIEWS; i++)
		if (!e->view[i].used) {
			e->view[i] = v;
			return 0;
		}
	return fail(r, "more than %d views", ENV_MAX_VIEWS);
}

/* layout VIEW...: the views tiled on the kiosk's screen, named above */
static int
read_layout(struct reader *r, struct env *e)
{
	struct words *w = &r->w;
	if (w->n < 2 || w->n - 1 > ENV_MAX_VIEWS)
		return fail(r, "expected: layout VIEW... (1 to %d views defined above)", ENV_MAX_VIEWS);
	for (int i = 1; i < w->n; i++) {
		int v = env_find_view(e, w->w[i]);
		for (int k = 0; v >= 0 && k < i - 1; k++)
			if (e->layout[k] == v)
				v = -1;
		if (v < 0)
			return fail(r, "layout: no view %s defined above, or named twice", w->w[i]);
		e->layout[i - 1] = v;
	}
	e->nlayout = w->n - 1;
	return 0;
}

/*
 * show family PREFIX row|overlay select=FIG spacing=M: the family shown at
 * the kiosk, its members and the selected one defined above
 */
static int
read_show(struct reader *r, struct env *e)
{
	struct words *w = &r->w;
	struct env_show sh = { 0 };
	const char *sel = NULL, *sp = NULL;
	for (int i = 4; i < w->n; i++)
		if (words_is_key(w->w[i], "select"))
			sel = w->w[i] + 7;
		else if (words_is_key(w->w[i], "spacing"))
			sp = w->w[i] + 8;
	if (w->n != 6 || strcmp(w->w[1], "family") || !sel || !sp || !words_is_name(w->w[2]) ||
	    words_number(sp, UNIT_NONE, &sh.spacing) < 0 || sh.spacing < 0)
		return fail(r, "expected: show family PREFIX row|overlay select=FIG spacing=M");
	if (!strcmp(w->w[3], "row"))
		sh.arrange = ENV_SHOW_ROW;
	else if (!strcmp(w->w[3], "overlay"))
		sh.arrange = ENV_SHOW_OVERLAY;
	else
		return fail(r, "show family: row or overlay, not '%s'", w->w[3]);
	int fig = env_find_figure(e, sel);
	if (fig < 0 || !family_is_member(e, w->w[2], fig))
		return fail(r, "show family: %s is no member of family %s defined above", sel, w->w[2]);
	snprintf(sh.family, sizeof sh.family, "%s", w->w[2]);
	snprintf(sh.selected, sizeof sh.selected, "%s", sel);
	e->show = sh;
	return 0;
}

/* "assess KEY=VALUE ...": the assessments' settings (session 4); each key known and in range */
static int
read_assess(struct reader *r)
{
	for (int i = 1; i < r->w.n; i++) {
		size_t klen;
		const char *val = words_value(r->w.w[i], &klen);
		char key[64], why[160];
		double v;
		if (!val || klen >= sizeof key)
			return fail(r, "assess: KEY=VALUE, not '%.40s'", r->w.w[i]);
		memcpy(key, r->w.w[i], klen);
		key[klen] = '\0';
		if (words_number(val, UNIT_NONE, &v) < 0)
			return fail(r, "assess: %s is not a number", key);
		if (assess_config_set(&r->assess, key, v, why, sizeof why) < 0)
			return fail(r, "assess: %s", why);
	}
	return 0;
}

int
session_read(const char *text, size_t len, const char *base_dir, const char *library_dir,
	     struct env *dest, char *err, size_t errlen)
{
	return session_read_with(text, len, base_dir, library_dir, dest, NULL, err, errlen);
}

int
session_read_with(const char *text, size_t len, const char *base_dir, const char *library_dir,
		  struct env *dest, struct assess_config *cfg, char *err, size_t errlen)
{
	struct reader *r = malloc(sizeof *r);
	if (!r) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	*r = (struct reader){ .text = text, .end = text + len, .err = err, .errlen = errlen,
			      .assess = assess_config_default() };
	int rc = -1, got = next_line(r);
	unsigned long version, next_gen = 0;
	if (got <= 0 || r->w.n != 2 || strcmp(r->w.w[0], "session") ||
	    read_uint(r->w.w[1], 1000000, &version) < 0) {
		if (got >= 0)
			fail(r, "not a session file (expected 'session %d')", SESSION_VERSION);
		goto out;
	}
	if (version > SESSION_VERSION) {
		fail(r, "session version %lu is newer than this daemon's %d", version, SESSION_VERSION);
		goto out;
	}
	int ended = 0;
	while (!ended && (got = next_line(r)) > 0) {
		const char *kw = r->w.w[0];
		int ok;
		if (!strcmp(kw, "next_gen"))
			ok = r->w.n == 2 && read_uint(r->w.w[1], 0xffffffffu, &next_gen) == 0 ? 0 : fail(r, "bad next_gen");
		else if (!strcmp(kw, "figure"))
			ok = read_figure(r, dest, base_dir, library_dir);
		else if (!strcmp(kw, "site"))
			ok = read_site(r, dest);
		else if (!strcmp(kw, "root"))
			ok = read_root(r, dest);
		else if (!strcmp(kw, "q"))
			ok = read_q(r, dest);
		else if (!strcmp(kw, "constraint"))
			ok = read_constraint(r, dest);
		else if (!strcmp(kw, "view"))
			ok = read_view(r, dest);
		else if (!strcmp(kw, "layout"))
			ok = read_layout(r, dest);
		else if (!strcmp(kw, "show"))
			ok = read_show(r, dest);
		else if (!strcmp(kw, "behave") || !strcmp(kw, "bdef"))
			ok = read_behave(r, dest);
		else if (!strcmp(kw, "attach"))
			ok = read_attach(r, dest);
		else if (!strcmp(kw, "load"))
			ok = read_load(r, dest);
		else if (!strcmp(kw, "assess"))
			ok = read_assess(r);
		else if (!strcmp(kw, "end"))
			ok = 0, ended = 1;
		else
			ok = fail(r, "unknown statement '%s'", kw);
		if (ok < 0)
			goto out;
	}
	if (got < 0)
		goto out;
	if (!ended) {
		fail(r, "the session ends without 'end' (a truncated file?)");
		goto out;
	}
	if (next_gen)
		dest->next_gen = (uint32_t)next_gen;
	if (cfg)
		*cfg = r->assess;
	rc = 0;
out:
	if (rc < 0) {
		env_clear(dest);
		env_init(dest);
	}
	free(r);
	return rc;
}

int
session_write_posture(const struct env *e, int fig, FILE *f)
{
	const struct env_figure *fg = &e->fig[fig];
	const struct model *m = fg->model;
	const struct state *s = fg->state;
	char site[2 * MODEL_NAME_MAX];
	fprintf(f, "posture %d\nfigure %s\nroot %s ", POSTURE_VERSION, m->name,
		model_site_fullname(m, s->root_site, site, sizeof site));
	write_xform(f, &s->root_xf);
	fprintf(f, "\n");
	if (fg->is_human)
		fprintf(f, "support %.17g\n", family_sole_height(m, s));
	for (int j = 0; j < m->njnt; j++) {
		if (!m->jnt_ndof[j])
			continue;
		fprintf(f, "joint %s", m->jnt_name[j]);
		for (int d = m->jnt_dof0[j]; d < m->jnt_dof0[j] + m->jnt_ndof[j]; d++)
			fprintf(f, " %.17g", s->q[d]);
		fprintf(f, "\n");
	}
	fprintf(f, "end\n");
	return ferror(f) ? -1 : 0;
}

int
session_read_posture(struct env *e, int fig, const char *text, size_t len, char *err, size_t errlen)
{
	struct env_figure *fg = &e->fig[fig];
	return session_posture_onto(fg->model, fg->is_human, fg->state, text, len, err, errlen);
}

int
session_posture_onto(const struct model *m, int is_human, struct state *s, const char *text,
		     size_t len, char *err, size_t errlen)
{
	struct reader *r = malloc(sizeof *r);
	double *q = malloc(sizeof *q * (size_t)(m->ndof + 1));
	int rc = -1, got, root = -1;
	struct xform root_xf;
	double support = NAN;
	if (!r || !q) {
		snprintf(err, errlen, "out of memory");
		goto out;
	}
	*r = (struct reader){ .text = text, .end = text + len, .err = err, .errlen = errlen };
	memcpy(q, s->q, sizeof *q * (size_t)m->ndof);
	unsigned long version;
	if (next_line(r) <= 0 || r->w.n != 2 || strcmp(r->w.w[0], "posture") ||
	    read_uint(r->w.w[1], 1000000, &version) < 0 || version > POSTURE_VERSION) {
		fail(r, "not a posture file of version <= %d", POSTURE_VERSION);
		goto out;
	}
	int ended = 0;
	while (!ended && (got = next_line(r)) > 0) {
		struct words *w = &r->w;
		if (!strcmp(w->w[0], "end")) {
			ended = 1;
		} else if (!strcmp(w->w[0], "figure") && w->n == 2) {
			continue; /* informative: postures move between figures of the same joints */
		} else if (!strcmp(w->w[0], "root") && w->n == 3) {
			root = model_find_site(m, w->w[1]);
			if (root < 0 || read_xform(w->w[2], &root_xf) < 0) {
				fail(r, "no site %s on this figure, or a bad frame", w->w[1]);
				goto out;
			}
		} else if (!strcmp(w->w[0], "support") && w->n == 2) {
			if (words_number(w->w[1], UNIT_NONE, &support) < 0) {
				fail(r, "support: a height");
				goto out;
			}
		} else if (!strcmp(w->w[0], "joint") && w->n >= 2) {
			int j = model_find_joint(m, w->w[1]);
			if (j < 0 || w->n - 2 != m->jnt_ndof[j]) {
				fail(r, "no joint %s of %d dofs on this figure", w->w[1], w->n - 2);
				goto out;
			}
			for (int k = 0; k < m->jnt_ndof[j]; k++) {
				int d = m->jnt_dof0[j] + k;
				double v;
				if (words_number(w->w[2 + k], UNIT_NONE, &v) < 0 || v < m->dof_lo[d] ||
				    v > m->dof_hi[d]) {
					fail(r, "joint %s: value %d is not a number within its limits",
					     w->w[1], k + 1);
					goto out;
				}
				q[d] = v;
			}
		} else {
			fail(r, "unknown statement '%s'", w->w[0]);
			goto out;
		}
	}
	if (!ended) {
		if (got >= 0)
			fail(r, "the posture ends without 'end'");
		goto out;
	}
	/* everything checked: apply */
	memcpy(s->q, q, sizeof *q * (size_t)m->ndof);
	if (root >= 0)
		state_root_at(m, s, root, &root_xf);
	kin_update(m, s);
	/* a human of another size: its feet as high as the file's were (it stands where that one stood) */
	double shift = is_human && !isnan(support) ? support - family_sole_height(m, s) : 0;
	if (fabs(shift) > 1e-9) {
		struct xform at = s->root_xf;
		at.p[1] += shift;
		state_root_at(m, s, s->root_site, &at);
		kin_update(m, s);
	}
	rc = 0;
out:
	free(r);
	free(q);
	return rc;
}

void
session_write_figure_posture(const struct env *e, int fig, FILE *f)
{
	write_figure_posture(&e->fig[fig], f);
	if (e->fig[fig].behave)
		write_behave(&e->fig[fig], f);
}

int
session_apply_line(struct env *e, const char *line, size_t len, char *err, size_t errlen)
{
	struct reader *r = malloc(sizeof *r);
	if (!r) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	*r = (struct reader){ .text = line, .end = line + len, .err = err, .errlen = errlen };
	int rc = next_line(r);
	if (rc > 0) {
		if (!strcmp(r->w.w[0], "site"))
			rc = read_site(r, e);
		else if (!strcmp(r->w.w[0], "root"))
			rc = read_root(r, e);
		else if (!strcmp(r->w.w[0], "q"))
			rc = read_q(r, e);
		else if (!strcmp(r->w.w[0], "behave") || !strcmp(r->w.w[0], "bdef"))
			rc = read_behave(r, e);
		else
			rc = fail(r, "not a posture statement");
	} else if (rc == 0) {
		rc = fail(r, "empty statement");
	}
	free(r);
	return rc < 0 ? -1 : 0;
}
