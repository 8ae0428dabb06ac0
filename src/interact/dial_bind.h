/*
 * dial_bind.h - the dial panel's bindings: which dial turns what (Jack's
 * dial box) and which panel button runs which command. Events in
 * (INPUT_VALUATOR, INPUT_BUTTON), actions out; the caller applies them.
 * Nothing here reads a clock, a file descriptor or GL, and nothing
 * allocates after parsing.
 *
 * The dials are relative, as Jack's were: the first value a dial gives
 * (and the first after it was stale, after the panel came or went, or
 * after dial_bind_reset) only sets its reference. Each later value V with
 * the reference P gives the change
 *
 *   delta = gain * (V - P), negated when the binding says invert,
 *
 * and P becomes V. When |V - P| <= dead the value gives nothing and P
 * stays, so jitter below the dead zone never moves anything while a slow
 * turn still adds up until it passes. A stale event gives nothing and
 * forgets P. NaN or infinite values, and changes whose delta would not be
 * finite, are counted and give nothing (the latter moves P to V); a delta
 * of zero (a zero gain) gives nothing either.
 *
 * The file, one statement per line; '#' outside double quotes starts a
 * comment; blank lines are skipped. Words are split as the protocol splits
 * them: spaces or tabs between words, double quotes keep spaces in a word
 * ("\"" and "\\" escape inside them). The first statement is the version:
 *
 *   bindings 1
 *   dial DIAL TARGET [gain=G] [invert] [dead=D]
 *   button BUTTON COMMAND [on=press|release]
 *
 *   DIAL     an axis of the panel's map by name (can_map.h): 1..63 letters,
 *            digits, '_', '.', '-'; a dial is bound at most once
 *   TARGET   dof N              DOF N (0..5) of the joint picked at the kiosk
 *            joint FIG JOINT N  DOF N of a named joint of a named figure (names
 *                               of 1..47 letters, digits, '_', '.', '-'; the
 *                               caller resolves them)
 *            camera sweep_h|sweep_v|zoom     Appendix C's sweep about the
 *                               vertical, about the camera's x axis, or the zoom
 *                               along its z axis, of the current view
 *            behavior elevation|torso_forward|torso_lateral|torso_axial
 *                               the centre of mass's held height; the spine's
 *                               total flexion, lateral and axial bends
 *            manip x|y|z|rx|ry|rz   a translation along, or a rotation about,
 *                               a world axis of the manipulation transform G
 *   gain=G   the target's units per unit of the dial's physical value, as the
 *            protocol writes numbers: a length (m, cm, mm) for zoom, elevation
 *            and manip x|y|z, an angle (deg, rad) for sweeps, torso bends and
 *            manip rx|ry|rz, either for a DOF (the caller checks it against
 *            the DOF's kind); a bare number is in metres or radians. Finite;
 *            default 1
 *   invert   reverses the dial's sense
 *   dead=D   the dead zone, in the dial's own units: finite, >= 0; default 0
 *   BUTTON   as the panel map's code= takes it: a BTN_* name or an evdev
 *            code 1..0x2ff (can_map_code_parse)
 *   COMMAND  the command line run on the press, or with on=release on the
 *            release: 1..1023 bytes, no control characters (quote it when it
 *            has spaces). A button may have one press and one release command
 *
 * Each option at most once. Any error refuses the whole file with
 * "name:line: message" and leaves the table as it was.
 *
 * At run time, dial_bind_command takes the protocol's words of
 *
 *   bind dial DIAL TARGET [gain=G] [invert] [dead=D]
 *   bind button BUTTON COMMAND [on=press|release]
 *   unbind dial DIAL
 *   unbind button BUTTON [on=press|release]   (without on=: both)
 *
 * where bind replaces the dial's (the button edge's) binding if it has one.
 * dial_bind_write prints the table in the file's syntax, and reading what
 * it wrote gives the same table.
 */
#ifndef POSTURE_INTERACT_DIAL_BIND_H
#define POSTURE_INTERACT_DIAL_BIND_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "devices/event.h"

#define DIAL_BIND_VERSION 1
#define DIAL_BIND_MAX_DIALS 64
#define DIAL_BIND_MAX_BUTTONS 64
#define DIAL_BIND_MAX_AXES 256   /* valuator codes with a reference: CAN_MAP_MAX_LINES */
#define DIAL_BIND_DIAL_MAX 64    /* bytes of a dial's name, with its NUL */
#define DIAL_BIND_NAME_MAX 48    /* bytes of a figure's or joint's name, with its NUL */
#define DIAL_BIND_COMMAND_MAX 1024 /* bytes of a command, with its NUL */
#define DIAL_BIND_LINE_MAX 4096  /* bytes of a file's line */
#define DIAL_BIND_DOF_MAX 6      /* DOFs of a joint: MODEL_JOINT_DOF_MAX */

enum dial_target_kind {
	DIAL_TARGET_DOF,      /* DOF `dof` of the picked joint */
	DIAL_TARGET_JOINT,    /* DOF `dof` of joint `joint` of figure `figure` */
	DIAL_TARGET_CAMERA,   /* axis: enum dial_camera_axis */
	DIAL_TARGET_BEHAVIOR, /* axis: enum dial_behavior_param */
	DIAL_TARGET_MANIP,    /* axis: enum dial_manip_axis */
};

enum dial_camera_axis { DIAL_CAMERA_SWEEP_H, DIAL_CAMERA_SWEEP_V, DIAL_CAMERA_ZOOM };

enum dial_behavior_param {
	DIAL_BEHAVIOR_ELEVATION,
	DIAL_BEHAVIOR_TORSO_FORWARD,
	DIAL_BEHAVIOR_TORSO_LATERAL,
	DIAL_BEHAVIOR_TORSO_AXIAL,
};

enum dial_manip_axis {
	DIAL_MANIP_X,
	DIAL_MANIP_Y,
	DIAL_MANIP_Z,
	DIAL_MANIP_RX,
	DIAL_MANIP_RY,
	DIAL_MANIP_RZ,
};

/* the unit a gain was written in: it is written back the same way */
enum dial_unit {
	DIAL_UNIT_NONE,
	DIAL_UNIT_M,
	DIAL_UNIT_CM,
	DIAL_UNIT_MM,
	DIAL_UNIT_DEG,
	DIAL_UNIT_RAD,
};

/* the kind of quantity a target moves, which says the units its gain takes */
enum dial_quantity { DIAL_QUANTITY_LENGTH, DIAL_QUANTITY_ANGLE, DIAL_QUANTITY_EITHER };

struct dial_target {
	uint8_t kind; /* enum dial_target_kind */
	uint8_t axis; /* camera, behaviour or manip: which one */
	uint8_t dof;  /* dof, joint: the DOF's index in its joint, 0..DIAL_BIND_DOF_MAX-1 */
	char figure[DIAL_BIND_NAME_MAX]; /* joint only */
	char joint[DIAL_BIND_NAME_MAX];  /* joint only */
};

/*
 * A dial's binding. The gain is kept in base units (gain) and as written
 * (gain_written, gain_unit) so that the writer gives back the text read.
 */
struct dial_bind_dial {
	char name[DIAL_BIND_DIAL_MAX];
	int index;            /* the valuator's code, or -1 while the name is unresolved */
	struct dial_target target;
	double gain;          /* target units (m or rad) per unit of the dial */
	double gain_written;
	uint8_t gain_unit;    /* enum dial_unit */
	uint8_t invert;
	double dead;          /* >= 0, in the dial's units */
};

enum dial_edge { DIAL_EDGE_PRESS, DIAL_EDGE_RELEASE };

struct dial_bind_button {
	uint16_t code;   /* evdev code */
	uint8_t edge;    /* enum dial_edge */
	char command[DIAL_BIND_COMMAND_MAX];
};

/*
 * The table, in the order bound (a run-time bind of a new dial or button
 * goes last; one that replaces keeps its place), and each valuator's
 * reference. The caller places it (about 80 kB) and fills it with
 * dial_bind_init or a parse.
 */
struct dial_bind {
	int ndial, nbutton;
	struct dial_bind_dial dial[DIAL_BIND_MAX_DIALS];
	struct dial_bind_button button[DIAL_BIND_MAX_BUTTONS];
	/* per valuator code: the reference value, and whether there is one */
	double ref[DIAL_BIND_MAX_AXES];
	uint8_t has_ref[DIAL_BIND_MAX_AXES];
	/* counters */
	uint64_t nonfinite;   /* values NaN or infinite, ignored */
	uint64_t overflow;    /* changes whose delta was not finite: only the reference moved */
	uint64_t dead;        /* values inside the dead zone */
	uint64_t lost;        /* actions beyond the caller's max */
};

/*
 * How dial names become valuator codes: find returns the code of the
 * dial called name, or -1 when the panel has none. A NULL lookup leaves
 * names unresolved (index -1) for a later dial_bind_resolve, as when the
 * panel's map is not known yet.
 */
struct dial_bind_lookup {
	int (*find)(const void *user, const char *name);
	const void *user;
};

/* names[i] is the dial with code i: for find_in_names */
struct dial_bind_names {
	const char *const *name;
	int n;
};

/* lookup through a struct dial_bind_names */
int dial_bind_find_in_names(const void *names, const char *name);

/* lookup through a const struct can_map: its axis and mux lines (the map's valuators) */
int dial_bind_find_in_map(const void *can_map, const char *name);

/* an empty table with no references */
void dial_bind_init(struct dial_bind *dest);

/*
 * Parses n bytes of bindings text; name is the file name used in messages.
 * Names are resolved through lookup (NULL: left unresolved). *dest must
 * hold a table (dial_bind_init's or a parse's). Returns 0 with *dest
 * replaced (references forgotten, counters kept), or -1 with
 * "name:line: message" in err and *dest unchanged.
 */
int dial_bind_parse(const char *text, size_t n, const char *name,
		    const struct dial_bind_lookup *lookup, struct dial_bind *dest, char *err,
		    size_t errlen);

/* reads and parses the file at path: as dial_bind_parse, and -1 when it cannot be read */
int dial_bind_read(const char *path, const struct dial_bind_lookup *lookup,
		   struct dial_bind *dest, char *err, size_t errlen);

/*
 * The run-time command: words w[0..n-1] as the protocol split them, w[0]
 * "bind" or "unbind" (see above). Returns 0 with t changed, or -1 with a
 * message in err and t unchanged; unbinding what is not bound is an error.
 * Allocates nothing.
 */
int dial_bind_command(struct dial_bind *t, const char *const *w, int n,
		      const struct dial_bind_lookup *lookup, char *err, size_t errlen);

/*
 * Resolves the dials' names again through lookup (the panel's map came or
 * changed): each gets its code or -1, and references are forgotten.
 * Returns the number of names left unresolved.
 */
int dial_bind_resolve(struct dial_bind *t, const struct dial_bind_lookup *lookup);

/*
 * Writes t in the file's syntax, version line first, numbers exact.
 * Returns 0, or -1 on a write error.
 */
int dial_bind_write(FILE *out, const struct dial_bind *t);

/* the binding of button code's edge (enum dial_edge), or -1 */
int dial_bind_button_find(const struct dial_bind *t, uint16_t code, uint8_t edge);

/* forgets every reference (the panel was unplugged): each dial's next value moves nothing */
void dial_bind_reset(struct dial_bind *t);

/* the quantity a target moves: the units its gain may carry */
enum dial_quantity dial_target_quantity(const struct dial_target *target);

/* a target in the file's words ("camera sweep_h", "joint jack elbow_r 0") into dest */
const char *dial_target_to_str(const struct dial_target *target, char *dest, size_t len);

#endif
