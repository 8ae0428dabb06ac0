/* loop_config.h - the settings the loop runs with (postured's flags and config file) */
#ifndef POSTURE_LOOP_CONFIG_H
#define POSTURE_LOOP_CONFIG_H

#include <stdint.h>

struct loop_config {
	const char *socket_path;
	const char *state_dir;
	const char *frames_dir; /* NULL: no frames written */
	double fps;
	unsigned solve_budget_us;  /* the solver's time a frame; 0: the frame less its drawing (§4.7.2) */
	int tcp_port;
	const char *token;
	const char *init_file; /* commands for a first start, NULL: none */
	const char *library_dir; /* shipped figure files, NULL: none */
	const char *fb_device;   /* a framebuffer for the first view, NULL: none */
	const char *panel_map;   /* the dial panel's map (devices/can_map.h), NULL: none */
	const char *const *inputs; /* --input specs (devices/input_devs.h); none: auto */
	int ninputs;
	int grab;                  /* the kiosk grab on the devices that have one */
	double pointer_gain;       /* pixels per 1/1000 inch of mouse motion */
	const char *hotplug;       /* "udev" (NULL: the same), "kernel" or "none" (devices/hotplug.h) */
	const char *keymap;        /* the kiosk keyboard's layout, LAYOUT[:VARIANT]; NULL: us */
	unsigned view_key;         /* the change-view key at the edit line; 0: KEY_F2 */
	const char *bindings;      /* the dial panel's bindings file (interact/dial_bind.h), NULL: none */
	int screen_w, screen_h;    /* the kiosk's screen; 0: the framebuffer's, else 1280x720 */
	const char *record_dir;    /* record from the start into this folder (daemon/tape.h); NULL: no */
	const char *vt;            /* the kiosk's VT (/dev/ttyN; "" standard input); NULL: none */
	const char *attract_dir;   /* the attract mode's recording; NULL: none */
	double attract_after;      /* ... played after this many seconds without input */
	const char *replay_dir;    /* loop_replay's recording */
	const char *drive_file;    /* loop_drive's script */
	double speed;              /* loop_replay's pace: 1 real time, 0 as fast as it goes */
	uint64_t until;            /* loop_replay stops after this frame; 0: at the end */
	int hash_frames;           /* loop_replay draws every view each frame and hashes the pixels */
	const char *after;         /* loop_replay's commands once it stopped (their replies printed) */
};

#endif
