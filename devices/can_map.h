/*
 * can_map.h - the CAN panel map: which bits of which frames are a panel's
 * dials and buttons, and how their raw numbers become physical values.
 * A text file, one line per axis, button or multiplexer, so that a DBC file
 * becomes a map by tools/dbc2panel and the map decodes exactly as cantools
 * decodes the DBC (see can_input.h).
 *
 * Syntax, one line per field; '#' starts a comment; blank lines are skipped:
 *
 *   KIND ID FIELD NAME [OPTION=VALUE ...]
 *
 *   KIND   axis     a dial: decodes to a valuator (INPUT_VALUATOR, code = the line's index)
 *          button   decodes to button presses and releases (pressed: value != 0)
 *          mux      a multiplexer: a value of its own (a valuator, like an axis) that
 *                   selects which of the lines naming it (mux=NAME:...) decode
 *   ID     the CAN id in hex as candump writes it: 3 digits for a standard id
 *          (000..7FF), 8 digits for an extended one (00000000..1FFFFFFF)
 *   FIELD  S|L@O+ or S|L@O-  DBC style: start bit S (0..63), length L (1..64), O = 1
 *                   Intel (little-endian, S is the least significant bit) or 0 Motorola
 *                   (big-endian, S is the most significant bit in the DBC's sawtooth
 *                   numbering: bit 7 of byte 0 is 7, bit 0 of byte 1 is 8); '+' unsigned,
 *                   '-' signed (two's complement of the field's width)
 *          A-B[le|be][+|-]  bytes A..B (0..7), little-endian (the default) or big-endian,
 *                   unsigned (the default) or signed
 *          N[+|-]   byte N
 *          N.b      bit b (0 = least significant) of byte N, unsigned
 *          Every field must lie within the 8 bytes of a CAN frame. Fields may overlap.
 *   NAME   letters, digits, '_', '.', '-'; at most 63 characters; unique in the map
 *
 *   OPTIONS, each at most once:
 *   factor=F       physical = raw * F + offset (default 1)
 *   offset=O       (default 0)
 *   clamp=MIN,MAX  axis only: the physical value is held within [MIN, MAX] (default: none;
 *                  a DBC's minimum and maximum are not a clamp)
 *   stale=MS       a valuator with no frame for MS milliseconds is reported stale once, and
 *                  a button held that long is released; 0: never (default 1000)
 *   mux=NAME:V[,V...]  the line decodes only when the mux line NAME (an earlier line of
 *                  the same id) decodes and the integer part of its physical value is one
 *                  of the V (at most 8)
 *   code=BTN_x|N   button only: the evdev code (a BTN_* name or a number); default
 *                  BTN_TRIGGER_HAPPY1 + the number of button lines before this one, the
 *                  kernel's 40 codes for such buttons: a 41st button line needs code=
 *   dlc=N          the message's length in bytes (1..8), when it is longer than its fields
 *
 * Example:
 *   mux    181       0|8@1+    Panel.Page
 *   axis   181       8|16@1-   Panel.Dial1   factor=0.1 clamp=-100,100 mux=Panel.Page:0
 *   axis   18FF0A42  3|13@0+   Tilt.Angle    factor=0.25 offset=-90 stale=500
 *   button 181       7.0       Panel.Foot    code=BTN_0
 */
#ifndef POSTURE_DEVICES_CAN_MAP_H
#define POSTURE_DEVICES_CAN_MAP_H

#include <linux/can.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#define CAN_MAP_MAX_LINES 256
#define CAN_MAP_NAME_MAX 64      /* with the terminating NUL */
#define CAN_MAP_MUX_VALUES 8
#define CAN_MAP_STALE_DEFAULT_MS 1000
#define CAN_MAP_MAX_LINE_CHARS 1024

enum can_map_kind { CAN_MAP_AXIS, CAN_MAP_BUTTON, CAN_MAP_MUX };

enum can_map_order { CAN_MAP_INTEL, CAN_MAP_MOTOROLA };

struct can_map_line {
	uint32_t can_id;     /* CAN_EFF_FLAG set for an extended id */
	uint8_t kind;        /* enum can_map_kind */
	uint8_t order;       /* enum can_map_order */
	uint8_t is_signed;
	uint8_t start;       /* DBC start bit */
	uint8_t length;      /* bits, 1..64 */
	uint8_t has_clamp;
	uint8_t dlc;         /* the dlc= option; 0 when not given */
	uint8_t n_mux;       /* values in mux_values; 0: not multiplexed */
	int16_t mux_line;    /* index of the selecting mux line, or -1 */
	uint16_t code;       /* button: the evdev code */
	uint32_t stale_ms;
	double factor, offset;
	double clamp_min, clamp_max;
	int64_t mux_values[CAN_MAP_MUX_VALUES];
	char name[CAN_MAP_NAME_MAX];
	/* derived from the above by the parser */
	uint8_t shift;       /* right shift of the frame read as one 64-bit number */
	uint8_t nbytes;      /* bytes of the frame the field needs */
	uint64_t mask;
};

/*
 * The lines in file order, and an index by id: ids[] sorted, each with its
 * lines' indexes (in file order, so a mux line comes before the lines it
 * selects) at by_id[id_first[i]] .. by_id[id_first[i] + id_count[i] - 1].
 */
struct can_map {
	int n;
	struct can_map_line line[CAN_MAP_MAX_LINES];
	int n_ids;
	uint32_t ids[CAN_MAP_MAX_LINES];
	uint16_t id_first[CAN_MAP_MAX_LINES];
	uint16_t id_count[CAN_MAP_MAX_LINES];
	uint8_t id_len[CAN_MAP_MAX_LINES]; /* the message length: max of fields and dlc= */
	uint16_t by_id[CAN_MAP_MAX_LINES];
};

/*
 * Parses n bytes of map text; name is the file name used in messages.
 * Returns 0 with *dest filled, or -1 with "name:line: message" in err and
 * *dest unchanged (all or nothing).
 */
int can_map_parse(const char *text, size_t n, const char *name, struct can_map *dest, char *err,
		  size_t errlen);

/* reads and parses the file at path: as can_map_parse, and -1 when it cannot be read */
int can_map_read(const char *path, struct can_map *dest, char *err, size_t errlen);

/*
 * Writes m in the syntax above (fields in DBC form, numbers exact), so that
 * parsing the text gives m again. Returns 0, or -1 on a write error.
 */
int can_map_write(FILE *out, const struct can_map *m);

/*
 * Fills dest with up to max exact-match receive filters, one per id of the
 * map (data and RTR frames of that id; error frames come through
 * CAN_RAW_ERR_FILTER). Returns the number of ids, which may exceed max.
 */
int can_map_filters(const struct can_map *m, struct can_filter *dest, int max);

/* the index of the line called name, or -1 */
int can_map_find(const struct can_map *m, const char *name);

/* the BTN_* name of an evdev button code, or NULL when it has none in the map's table */
const char *can_map_code_to_str(uint16_t code);

/*
 * A button as code= takes it: a BTN_* name of that table (aliases such as
 * BTN_A too) or a code 1..KEY_MAX (strtoul's base 0). Returns 0, or -1.
 */
int can_map_code_parse(const char *s, uint16_t *dest);

#endif
