/* input_devs.c - the open input devices and the specs that named them (see input_devs.h) */
#include "devices/input_devs.h"

#include <stdio.h>
#include <string.h>

void
input_devs_init(struct input_devs *s, const struct input_backend *const *backends, int n, int grab,
		struct input_queue *q)
{
	memset(s, 0, sizeof *s);
	s->backends = backends;
	s->nbackends = n < INPUT_DEVS_BACKENDS_MAX ? n : INPUT_DEVS_BACKENDS_MAX;
	s->grab = grab;
	s->q = q;
	s->input_dir = "/dev/input";
}

void
input_devs_skip(struct input_devs *s, const char *what, const char *why)
{
	for (int k = 0; k < s->nskip; k++) /* one line a thing: the latest reason */
		if (!strncmp(s->skip[k].what, what, sizeof s->skip[k].what - 1)) {
			snprintf(s->skip[k].why, sizeof s->skip[k].why, "%.*s",
				 (int)sizeof s->skip[k].why - 1, why);
			return;
		}
	if (s->nskip == INPUT_DEVS_SKIP_MAX)
		return;
	struct input_devs_skip *k = &s->skip[s->nskip++];
	snprintf(k->what, sizeof k->what, "%.*s", (int)sizeof k->what - 1, what);
	snprintf(k->why, sizeof k->why, "%.*s", (int)sizeof k->why - 1, why);
}

int
input_devs_free_place(struct input_devs *s, const char *what)
{
	for (int i = 0; i < INPUT_DEVS_MAX; i++)
		if (!s->place[i].be)
			return i;
	input_devs_skip(s, what, "too many devices open");
	return -1;
}

int
input_devs_find(const struct input_devs *s, const struct input_backend *be, const char *path)
{
	for (int i = 0; i < INPUT_DEVS_MAX; i++)
		if (s->place[i].be == be && !strcmp(s->place[i].info.path, path))
			return i;
	return -1;
}

void
input_devs_put(struct input_devs *s, int i, const struct input_backend *be, void *dev,
	       const struct input_dev_info *info)
{
	struct input_devs_place *p = &s->place[i];
	p->be = be;
	p->dev = dev;
	p->info = *info;
	p->announced = 0;
	for (int k = 0; k < s->nskip; k++) /* skipped before, open now */
		if (!strcmp(s->skip[k].what, info->path)) {
			s->skip[k] = s->skip[--s->nskip];
			break;
		}
	if (s->q) {
		struct input_event_rec e = { .t_us = s->now_us, .device = (uint16_t)i,
					     .kind = INPUT_ADDED, .code = (uint16_t)info->cls };
		input_queue_push(s->q, &e);
	}
}

/* the backend a spec names and its argument (NULL for auto); NULL for none */
static const struct input_backend *
input_devs_backend(const struct input_devs *s, const char *spec, const char **arg)
{
	*arg = NULL;
	if (!strcmp(spec, "auto")) /* the first backend is the one auto means */
		return s->nbackends ? s->backends[0] : NULL;
	for (int b = 0; b < s->nbackends; b++) {
		size_t n = strlen(s->backends[b]->name);
		if (!strncmp(spec, s->backends[b]->name, n) && spec[n] == ':' && spec[n + 1]) {
			*arg = spec + n + 1;
			return s->backends[b];
		}
	}
	return NULL;
}

static int
input_devs_open_one(struct input_devs *s, const char *spec, char *err, size_t errlen)
{
	if (!strcmp(spec, "none"))
		return 0;
	const char *arg;
	const struct input_backend *be = input_devs_backend(s, spec, &arg);
	if (!be) {
		char forms[200] = "";
		for (int b = 0; b < s->nbackends; b++)
			snprintf(forms + strlen(forms), sizeof forms - strlen(forms), ", %s",
				 s->backends[b]->usage);
		snprintf(err, errlen, "input '%.100s': expected auto, none%s", spec, forms);
		return -1;
	}
	return be->open_spec(s, arg, err, errlen);
}

int
input_devs_open(struct input_devs *s, const char *spec, uint64_t now_us, char *err, size_t errlen)
{
	if (s->nspec == INPUT_DEVS_SPECS_MAX) {
		snprintf(err, errlen, "input '%.100s': more than %d specs", spec, INPUT_DEVS_SPECS_MAX);
		return -1;
	}
	if (strlen(spec) >= INPUT_DEVS_SPEC_MAX) {
		snprintf(err, errlen, "input '%.60s...': longer than %d bytes", spec,
			 INPUT_DEVS_SPEC_MAX - 1);
		return -1;
	}
	s->now_us = now_us;
	int n = input_devs_open_one(s, spec, err, errlen);
	if (n >= 0)
		snprintf(s->spec[s->nspec++], INPUT_DEVS_SPEC_MAX, "%s", spec);
	return n;
}

int
input_devs_rescan(struct input_devs *s, uint64_t now_us)
{
	char err[256];
	int opened = 0;
	s->now_us = now_us;
	s->nskip = 0;
	for (int k = 0; k < s->nspec; k++) {
		int n = input_devs_open_one(s, s->spec[k], err, sizeof err);
		opened += n > 0 ? n : 0;
	}
	return opened;
}

int
input_devs_pollfds(const struct input_devs *s, struct pollfd *fds, int *tags, int max)
{
	int n = 0;
	for (int i = 0; i < INPUT_DEVS_MAX && n < max; i++) {
		const struct input_devs_place *p = &s->place[i];
		int fd = p->be ? p->be->fd(p->dev) : -1;
		if (fd >= 0) {
			fds[n] = (struct pollfd){ .fd = fd, .events = POLLIN };
			tags[n++] = i;
		}
	}
	for (int b = 0; b < s->nbackends; b++) {
		const struct input_backend *be = s->backends[b];
		if (!be->shared_fds)
			continue;
		int room = max - n < INPUT_DEVS_SHARED_FDS ? max - n : INPUT_DEVS_SHARED_FDS;
		int got = room > 0 ? be->shared_fds(fds + n, room) : 0;
		for (int k = 0; k < got; k++)
			tags[n + k] = INPUT_DEVS_MAX + b;
		n += got > 0 ? got : 0;
	}
	return n;
}

/* reads place i; a device gone is closed and its place freed */
static int
input_devs_read_place(struct input_devs *s, int i, uint64_t now_us, struct input_queue *q)
{
	struct input_devs_place *p = &s->place[i];
	if (!p->be)
		return -1;
	if (p->be->read(p->dev, now_us, q) >= 0)
		return 0;
	/* gone: read released what it held and queued the removal */
	p->be->close(p->dev, now_us, NULL);
	memset(p, 0, sizeof *p);
	return -1;
}

int
input_devs_ready(struct input_devs *s, int tag, uint64_t now_us, struct input_queue *q)
{
	if (tag >= 0 && tag < INPUT_DEVS_MAX)
		return input_devs_read_place(s, tag, now_us, q);
	int b = tag - INPUT_DEVS_MAX;
	if (b < 0 || b >= s->nbackends || !s->backends[b]->shared_work)
		return 0;
	const struct input_backend *be = s->backends[b];
	be->shared_work(now_us, q);
	int rc = 0;
	for (int i = 0; i < INPUT_DEVS_MAX; i++)
		if (s->place[i].be == be && input_devs_read_place(s, i, now_us, q) < 0)
			rc = -1;
	/* a hot-plug noted in the work: the specs opened again, outside it */
	if (be->arrived && be->arrived())
		input_devs_rescan(s, now_us);
	return rc;
}

int
input_devs_set_grab(struct input_devs *s, int on)
{
	int rc = 0;
	s->grab = on != 0;
	for (int i = 0; i < INPUT_DEVS_MAX; i++) {
		struct input_devs_place *p = &s->place[i];
		if (!p->be || !p->be->set_grab)
			continue;
		if (p->be->set_grab(p->dev, on) < 0)
			rc = -1;
		else
			p->info.grabbed = on != 0;
	}
	return rc;
}

void
input_devs_close_all(struct input_devs *s, uint64_t now_us, struct input_queue *q)
{
	for (int i = 0; i < INPUT_DEVS_MAX; i++)
		if (s->place[i].be) {
			s->place[i].be->close(s->place[i].dev, now_us, q);
			memset(&s->place[i], 0, sizeof s->place[i]);
		}
}

int
input_devs_count(const struct input_devs *s)
{
	int n = 0;
	for (int i = 0; i < INPUT_DEVS_MAX; i++)
		n += s->place[i].be != NULL;
	return n;
}

int
input_devs_next_new(struct input_devs *s)
{
	for (int i = 0; i < INPUT_DEVS_MAX; i++)
		if (s->place[i].be && !s->place[i].announced) {
			s->place[i].announced = 1;
			return i;
		}
	return -1;
}
