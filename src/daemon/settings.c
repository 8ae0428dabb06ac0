/* settings.c - postured's flags and config file (see settings.h) */
#include "daemon/settings.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include <libevdev/libevdev.h>

int
settings_set(struct settings *s, const char *key, const char *val)
{
	char *end;
	if (!strcmp(key, "socket"))
		snprintf(s->socket, sizeof s->socket, "%s", val);
	else if (!strcmp(key, "state-dir"))
		snprintf(s->state_dir, sizeof s->state_dir, "%s", val);
	else if (!strcmp(key, "frames"))
		snprintf(s->frames, sizeof s->frames, "%s", val);
	else if (!strcmp(key, "fb") || !strcmp(key, "display"))
		snprintf(s->fb, sizeof s->fb, "%s", val);
	else if (!strcmp(key, "library"))
		snprintf(s->library, sizeof s->library, "%s", val);
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
		snprintf(s->hotplug, sizeof s->hotplug, "%s", val);
	} else if (!strcmp(key, "keymap")) {
		if (strlen(val) >= sizeof s->keymap || !val[0]) {
			fprintf(stderr, "postured: keymap is a layout name such as us or de:nodeadkeys\n");
			return -1;
		}
		snprintf(s->keymap, sizeof s->keymap, "%s", val);
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
		snprintf(s->vt, sizeof s->vt, "%s", strcmp(val, "stdin") ? val : "");
		s->vt_given = strcmp(val, "none") != 0;
	} else if (!strcmp(key, "drive")) {
		snprintf(s->drive, sizeof s->drive, "%s", val);
	} else if (!strcmp(key, "attract")) {
		snprintf(s->attract, sizeof s->attract, "%s", val);
	} else if (!strcmp(key, "attract-after")) {
		s->attract_after = strtod(val, &end);
		if (*end || !(s->attract_after >= 1 && s->attract_after <= 86400)) {
			fprintf(stderr, "postured: attract-after is seconds from 1 to 86400\n");
			return -1;
		}
	} else if (!strcmp(key, "record")) {
		snprintf(s->record, sizeof s->record, "%s", val);
	} else if (!strcmp(key, "replay")) {
		snprintf(s->replay, sizeof s->replay, "%s", val);
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
		snprintf(s->after, sizeof s->after, "%s", val);
	} else if (!strcmp(key, "speed")) {
		s->speed = strcmp(val, "max") ? strtod(val, &end) : 0;
		if (strcmp(val, "max") && (*end || !(s->speed >= 0.01 && s->speed <= 1000))) {
			fprintf(stderr, "postured: speed is max, or a factor of real time from 0.01 to 1000\n");
			return -1;
		}
	} else if (!strcmp(key, "bindings")) {
		snprintf(s->bindings, sizeof s->bindings, "%s", val);
	} else if (!strcmp(key, "panel"))
		snprintf(s->panel, sizeof s->panel, "%s", val);
	else if (!strcmp(key, "init"))
		snprintf(s->init, sizeof s->init, "%s", val);
	else if (!strcmp(key, "token"))
		snprintf(s->token, sizeof s->token, "%s", val);
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
	char line[4200];
	int n = 0, rc = 0;
	while (rc == 0 && fgets(line, sizeof line, f)) {
		n++;
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

