/* settings.c - postured's flags and config file (see settings.h) */
#include "daemon/settings.h"

#include <errno.h>
#include <sys/types.h>
#include <stdlib.h>
#include <string.h>

#include <libevdev/libevdev.h>

/* a text setting into its field; one that does not fit is refused, not cut */
static int
copy_text(char *dest, size_t size, const char *key, const char *val)
{
	size_t n = strlen(val);
	if (n >= size) {
		fprintf(stderr, "postured: %s is longer than %zu bytes\n", key, size - 1);
		return -1;
	}
	memcpy(dest, val, n + 1);
	return 0;
}

int
settings_set(struct settings *s, const char *key, const char *val)
{
	char *end;
	if (!strcmp(key, "socket"))
		return copy_text(s->socket, sizeof s->socket, key, val);
	else if (!strcmp(key, "state-dir"))
		return copy_text(s->state_dir, sizeof s->state_dir, key, val);
	else if (!strcmp(key, "frames"))
		return copy_text(s->frames, sizeof s->frames, key, val);
	else if (!strcmp(key, "fb") || !strcmp(key, "display"))
		return copy_text(s->fb, sizeof s->fb, key, val);
	else if (!strcmp(key, "library"))
		return copy_text(s->library, sizeof s->library, key, val);
	else if (!strcmp(key, "input")) {
		if (s->ninputs == INPUT_DEVS_MAX || strlen(val) >= INPUT_DEVS_SPEC_MAX) {
			fprintf(stderr, "postured: at most %d inputs of %d bytes\n", INPUT_DEVS_MAX,
				INPUT_DEVS_SPEC_MAX - 1);
			return -1;
		}
		snprintf(s->input[s->ninputs], sizeof s->input[0], "%s", val);
		s->inputs[s->ninputs] = s->input[s->ninputs];
		s->ninputs++;
	} else if (!strcmp(key, "grab")) {
		if (strcmp(val, "yes") && strcmp(val, "no")) {
			fprintf(stderr, "postured: grab must be yes or no\n");
			return -1;
		}
		s->grab = !strcmp(val, "yes");
	} else if (!strcmp(key, "pointer-gain")) {
		s->pointer_gain = strtod(val, &end);
		if (*end || !(s->pointer_gain > 0 && s->pointer_gain <= 100)) {
			fprintf(stderr, "postured: pointer-gain must be a number above 0, at most 100\n");
			return -1;
		}
	} else if (!strcmp(key, "hotplug")) {
		if (strcmp(val, "udev") && strcmp(val, "kernel") && strcmp(val, "none")) {
			fprintf(stderr, "postured: hotplug must be udev, kernel or none\n");
			return -1;
		}
		return copy_text(s->hotplug, sizeof s->hotplug, key, val);
	} else if (!strcmp(key, "keymap")) {
		if (strlen(val) >= sizeof s->keymap || !val[0]) {
			fprintf(stderr, "postured: keymap is a layout name such as us or de:nodeadkeys\n");
			return -1;
		}
		return copy_text(s->keymap, sizeof s->keymap, key, val);
	} else if (!strcmp(key, "view-key")) {
		char name[64];
		snprintf(name, sizeof name, "%s%s", strncmp(val, "KEY_", 4) ? "KEY_" : "", val);
		int code = libevdev_event_code_from_name(EV_KEY, name);
		if (code < 0) {
			fprintf(stderr, "postured: view-key '%s' is no key name (F2, KEY_F3, ...)\n", val);
			return -1;
		}
		s->view_key = (unsigned)code;
	} else if (!strcmp(key, "screen")) {
		int w, h, used = 0;
		if (sscanf(val, "%dx%d%n", &w, &h, &used) != 2 || val[used] || w < 64 || h < 64 ||
		    w > 16384 || h > 16384) {
			fprintf(stderr, "postured: screen is WxH in pixels, such as 1920x1080\n");
			return -1;
		}
		s->screen_w = w;
		s->screen_h = h;
	} else if (!strcmp(key, "vt")) {
		s->vt_given = strcmp(val, "none") != 0;
		return copy_text(s->vt, sizeof s->vt, key, strcmp(val, "stdin") ? val : "");
	} else if (!strcmp(key, "drive")) {
		return copy_text(s->drive, sizeof s->drive, key, val);
	} else if (!strcmp(key, "attract")) {
		return copy_text(s->attract, sizeof s->attract, key, val);
	} else if (!strcmp(key, "attract-after")) {
		s->attract_after = strtod(val, &end);
		if (*end || !(s->attract_after >= 1 && s->attract_after <= 86400)) {
			fprintf(stderr, "postured: attract-after is seconds from 1 to 86400\n");
			return -1;
		}
	} else if (!strcmp(key, "record")) {
		return copy_text(s->record, sizeof s->record, key, val);
	} else if (!strcmp(key, "replay")) {
		return copy_text(s->replay, sizeof s->replay, key, val);
	} else if (!strcmp(key, "until")) {
		s->until = strtoull(val, &end, 10);
		if (*end || !val[0] || val[0] == '-' || !s->until) {
			fprintf(stderr, "postured: until is a frame number from 1\n");
			return -1;
		}
	} else if (!strcmp(key, "hash-frames")) {
		if (strcmp(val, "yes") && strcmp(val, "no")) {
			fprintf(stderr, "postured: hash-frames is yes or no\n");
			return -1;
		}
		s->hash_frames = !strcmp(val, "yes");
	} else if (!strcmp(key, "after")) {
		return copy_text(s->after, sizeof s->after, key, val);
	} else if (!strcmp(key, "speed")) {
		s->speed = strcmp(val, "max") ? strtod(val, &end) : 0;
		if (strcmp(val, "max") && (*end || !(s->speed >= 0.01 && s->speed <= 1000))) {
			fprintf(stderr, "postured: speed is max, or a factor of real time from 0.01 to 1000\n");
			return -1;
		}
	} else if (!strcmp(key, "bindings")) {
		return copy_text(s->bindings, sizeof s->bindings, key, val);
	} else if (!strcmp(key, "panel"))
		return copy_text(s->panel, sizeof s->panel, key, val);
	else if (!strcmp(key, "init"))
		return copy_text(s->init, sizeof s->init, key, val);
	else if (!strcmp(key, "token"))
		return copy_text(s->token, sizeof s->token, key, val);
	else if (!strcmp(key, "fps")) {
		s->fps = strtod(val, &end);
		if (*end || !(s->fps >= 1 && s->fps <= 1000)) {
			fprintf(stderr, "postured: fps must be a number from 1 to 1000\n");
			return -1;
		}
	} else if (!strcmp(key, "solve-budget")) {
		long us = strtol(val, &end, 10);
		if (*end || us < 10 || us > 1000000) {
			fprintf(stderr, "postured: solve-budget is microseconds from 10 to 1000000\n");
			return -1;
		}
		s->solve_budget = (unsigned)us;
	} else if (!strcmp(key, "tcp")) {
		long p = strtol(val, &end, 10);
		if (*end || p < 1 || p > 65535) {
			fprintf(stderr, "postured: tcp must be a port from 1 to 65535\n");
			return -1;
		}
		s->tcp = (int)p;
	} else {
		fprintf(stderr, "postured: unknown setting '%s'\n", key);
		return -1;
	}
	return 0;
}

int
settings_read(struct settings *s, FILE *f, const char *path)
{
	/* each line whole, whatever its length: a piece of a long one is no line of its own */
	char *line = NULL;
	size_t cap = 0;
	ssize_t len;
	int n = 0, rc = 0;
	while (rc == 0 && (len = getline(&line, &cap, f)) >= 0) {
		n++;
		if (memchr(line, 0, (size_t)len)) {
			fprintf(stderr, "postured: %s:%d: a NUL byte in the line\n", path, n);
			rc = -1;
			break;
		}
		char *p = line, *eq;
		while (*p == ' ' || *p == '\t')
			p++;
		if (*p == '#' || *p == '\n' || !*p)
			continue;
		p[strcspn(p, "\r\n")] = 0;
		if (!(eq = strchr(p, '='))) {
			fprintf(stderr, "postured: %s:%d: expected key = value\n", path, n);
			rc = -1;
			break;
		}
		char *k = p, *v = eq + 1, *ke = eq;
		while (ke > k && (ke[-1] == ' ' || ke[-1] == '\t'))
			ke--;
		*ke = 0;
		while (*v == ' ' || *v == '\t')
			v++;
		if (settings_set(s, k, v) < 0) {
			fprintf(stderr, "postured: in %s:%d\n", path, n);
			rc = -1;
		}
	}
	free(line);
	return rc;
}

int
settings_read_file(struct settings *s, const char *path)
{
	FILE *f = fopen(path, "r");
	if (!f) {
		fprintf(stderr, "postured: %s: %s\n", path, strerror(errno));
		return -1;
	}
	int rc = settings_read(s, f, path);
	fclose(f);
	return rc;
}

