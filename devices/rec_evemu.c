/* rec_evemu.c - evemu recordings read and written (see rec_evemu.h) */
#include "devices/rec_evemu.h"

#include <inttypes.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "devices/textfile.h"

/* the newest format this reader knows and the writer writes */
#define FORMAT_MAJOR 1
#define FORMAT_MINOR 3

/* a file larger than this is refused before reading */

struct code_name {
	uint8_t type;
	uint16_t code;
	const char *name;
};

/*
 * The names of <linux/input-event-codes.h> (linux-libc-dev 6.1), as
 * evemu's comments show them: for a value with several names the one
 * defined last, without the *_CNT limits and the aliases REP_MAX and
 * SW_MAX. Generated from the header; sorted by type, then code.
 */
static const char *const type_names[EV_MAX + 1] = {
	[0x00] = "EV_SYN",
	[0x01] = "EV_KEY",
	[0x02] = "EV_REL",
	[0x03] = "EV_ABS",
	[0x04] = "EV_MSC",
	[0x05] = "EV_SW",
	[0x11] = "EV_LED",
	[0x12] = "EV_SND",
	[0x14] = "EV_REP",
	[0x15] = "EV_FF",
	[0x16] = "EV_PWR",
	[0x17] = "EV_FF_STATUS",
	[0x1f] = "EV_MAX",
};

static const char *const prop_names[INPUT_PROP_MAX + 1] = {
	[0x00] = "INPUT_PROP_POINTER",
	[0x01] = "INPUT_PROP_DIRECT",
	[0x02] = "INPUT_PROP_BUTTONPAD",
	[0x03] = "INPUT_PROP_SEMI_MT",
	[0x04] = "INPUT_PROP_TOPBUTTONPAD",
	[0x05] = "INPUT_PROP_POINTING_STICK",
	[0x06] = "INPUT_PROP_ACCELEROMETER",
	[0x1f] = "INPUT_PROP_MAX",
};

static const struct code_name code_names[] = {
	{ 0x00, 0x000, "SYN_REPORT" },
	{ 0x00, 0x001, "SYN_CONFIG" },
	{ 0x00, 0x002, "SYN_MT_REPORT" },
	{ 0x00, 0x003, "SYN_DROPPED" },
	{ 0x00, 0x00f, "SYN_MAX" },
	{ 0x01, 0x000, "KEY_RESERVED" },
	{ 0x01, 0x001, "KEY_ESC" },
	{ 0x01, 0x002, "KEY_1" },
	{ 0x01, 0x003, "KEY_2" },
	{ 0x01, 0x004, "KEY_3" },
	{ 0x01, 0x005, "KEY_4" },
	{ 0x01, 0x006, "KEY_5" },
	{ 0x01, 0x007, "KEY_6" },
	{ 0x01, 0x008, "KEY_7" },
	{ 0x01, 0x009, "KEY_8" },
	{ 0x01, 0x00a, "KEY_9" },
	{ 0x01, 0x00b, "KEY_0" },
	{ 0x01, 0x00c, "KEY_MINUS" },
	{ 0x01, 0x00d, "KEY_EQUAL" },
	{ 0x01, 0x00e, "KEY_BACKSPACE" },
	{ 0x01, 0x00f, "KEY_TAB" },
	{ 0x01, 0x010, "KEY_Q" },
	{ 0x01, 0x011, "KEY_W" },
	{ 0x01, 0x012, "KEY_E" },
	{ 0x01, 0x013, "KEY_R" },
	{ 0x01, 0x014, "KEY_T" },
	{ 0x01, 0x015, "KEY_Y" },
	{ 0x01, 0x016, "KEY_U" },
	{ 0x01, 0x017, "KEY_I" },
	{ 0x01, 0x018, "KEY_O" },
	{ 0x01, 0x019, "KEY_P" },
	{ 0x01, 0x01a, "KEY_LEFTBRACE" },
	{ 0x01, 0x01b, "KEY_RIGHTBRACE" },
	{ 0x01, 0x01c, "KEY_ENTER" },
	{ 0x01, 0x01d, "KEY_LEFTCTRL" },
	{ 0x01, 0x01e, "KEY_A" },
	{ 0x01, 0x01f, "KEY_S" },
	{ 0x01, 0x020, "KEY_D" },
	{ 0x01, 0x021, "KEY_F" },
	{ 0x01, 0x022, "KEY_G" },
	{ 0x01, 0x023, "KEY_H" },
	{ 0x01, 0x024, "KEY_J" },
	{ 0x01, 0x025, "KEY_K" },
	{ 0x01, 0x026, "KEY_L" },
	{ 0x01, 0x027, "KEY_SEMICOLON" },
	{ 0x01, 0x028, "KEY_APOSTROPHE" },
	{ 0x01, 0x029, "KEY_GRAVE" },
	{ 0x01, 0x02a, "KEY_LEFTSHIFT" },
	{ 0x01, 0x02b, "KEY_BACKSLASH" },
	{ 0x01, 0x02c, "KEY_Z" },
	{ 0x01, 0x02d, "KEY_X" },
	{ 0x01, 0x02e, "KEY_C" },
	{ 0x01, 0x02f, "KEY_V" },
	{ 0x01, 0x030, "KEY_B" },
	{ 0x01, 0x031, "KEY_N" },
	{ 0x01, 0x032, "KEY_M" },
	{ 0x01, 0x033, "KEY_COMMA" },
	{ 0x01, 0x034, "KEY_DOT" },
	{ 0x01, 0x035, "KEY_SLASH" },
	{ 0x01, 0x036, "KEY_RIGHTSHIFT" },
	{ 0x01, 0x037, "KEY_KPASTERISK" },
	{ 0x01, 0x038, "KEY_LEFTALT" },
	{ 0x01, 0x039, "KEY_SPACE" },
	{ 0x01, 0x03a, "KEY_CAPSLOCK" },
	{ 0x01, 0x03b, "KEY_F1" },
	{ 0x01, 0x03c, "KEY_F2" },
	{ 0x01, 0x03d, "KEY_F3" },
	{ 0x01, 0x03e, "KEY_F4" },
	{ 0x01, 0x03f, "KEY_F5" },
	{ 0x01, 0x040, "KEY_F6" },
	{ 0x01, 0x041, "KEY_F7" },
	{ 0x01, 0x042, "KEY_F8" },
	{ 0x01, 0x043, "KEY_F9" },
	{ 0x01, 0x044, "KEY_F10" },
	{ 0x01, 0x045, "KEY_NUMLOCK" },
	{ 0x01, 0x046, "KEY_SCROLLLOCK" },
	{ 0x01, 0x047, "KEY_KP7" },
	{ 0x01, 0x048, "KEY_KP8" },
	{ 0x01, 0x049, "KEY_KP9" },
	{ 0x01, 0x04a, "KEY_KPMINUS" },
	{ 0x01, 0x04b, "KEY_KP4" },
	{ 0x01, 0x04c, "KEY_KP5" },
	{ 0x01, 0x04d, "KEY_KP6" },
	{ 0x01, 0x04e, "KEY_KPPLUS" },
	{ 0x01, 0x04f, "KEY_KP1" },
	{ 0x01, 0x050, "KEY_KP2" },
	{ 0x01, 0x051, "KEY_KP3" },
	{ 0x01, 0x052, "KEY_KP0" },
	{ 0x01, 0x053, "KEY_KPDOT" },
	{ 0x01, 0x055, "KEY_ZENKAKUHANKAKU" },
	{ 0x01, 0x056, "KEY_102ND" },
	{ 0x01, 0x057, "KEY_F11" },
	{ 0x01, 0x058, "KEY_F12" },
	{ 0x01, 0x059, "KEY_RO" },
	{ 0x01, 0x05a, "KEY_KATAKANA" },
	{ 0x01, 0x05b, "KEY_HIRAGANA" },
	{ 0x01, 0x05c, "KEY_HENKAN" },
	{ 0x01, 0x05d, "KEY_KATAKANAHIRAGANA" },
	{ 0x01, 0x05e, "KEY_MUHENKAN" },
	{ 0x01, 0x05f, "KEY_KPJPCOMMA" },
	{ 0x01, 0x060, "KEY_KPENTER" },
	{ 0x01, 0x061, "KEY_RIGHTCTRL" },
	{ 0x01, 0x062, "KEY_KPSLASH" },
	{ 0x01, 0x063, "KEY_SYSRQ" },
	{ 0x01, 0x064, "KEY_RIGHTALT" },
	{ 0x01, 0x065, "KEY_LINEFEED" },
	{ 0x01, 0x066, "KEY_HOME" },
	{ 0x01, 0x067, "KEY_UP" },
	{ 0x01, 0x068, "KEY_PAGEUP" },
	{ 0x01, 0x069, "KEY_LEFT" },
	{ 0x01, 0x06a, "KEY_RIGHT" },
	{ 0x01, 0x06b, "KEY_END" },
	{ 0x01, 0x06c, "KEY_DOWN" },
	{ 0x01, 0x06d, "KEY_PAGEDOWN" },
	{ 0x01, 0x06e, "KEY_INSERT" },
	{ 0x01, 0x06f, "KEY_DELETE" },
	{ 0x01, 0x070, "KEY_MACRO" },
	{ 0x01, 0x071, "KEY_MUTE" },
	{ 0x01, 0x072, "KEY_VOLUMEDOWN" },
	{ 0x01, 0x073, "KEY_VOLUMEUP" },
	{ 0x01, 0x074, "KEY_POWER" },
	{ 0x01, 0x075, "KEY_KPEQUAL" },
	{ 0x01, 0x076, "KEY_KPPLUSMINUS" },
	{ 0x01, 0x077, "KEY_PAUSE" },
	{ 0x01, 0x078, "KEY_SCALE" },
	{ 0x01, 0x079, "KEY_KPCOMMA" },
	{ 0x01, 0x07a, "KEY_HANGEUL" },
	{ 0x01, 0x07b, "KEY_HANJA" },
	{ 0x01, 0x07c, "KEY_YEN" },
	{ 0x01, 0x07d, "KEY_LEFTMETA" },
	{ 0x01, 0x07e, "KEY_RIGHTMETA" },
	{ 0x01, 0x07f, "KEY_COMPOSE" },
	{ 0x01, 0x080, "KEY_STOP" },
	{ 0x01, 0x081, "KEY_AGAIN" },
	{ 0x01, 0x082, "KEY_PROPS" },
	{ 0x01, 0x083, "KEY_UNDO" },
	{ 0x01, 0x084, "KEY_FRONT" },
	{ 0x01, 0x085, "KEY_COPY" },
	{ 0x01, 0x086, "KEY_OPEN" },
	{ 0x01, 0x087, "KEY_PASTE" },
	{ 0x01, 0x088, "KEY_FIND" },
	{ 0x01, 0x089, "KEY_CUT" },
	{ 0x01, 0x08a, "KEY_HELP" },
	{ 0x01, 0x08b, "KEY_MENU" },
	{ 0x01, 0x08c, "KEY_CALC" },
	{ 0x01, 0x08d, "KEY_SETUP" },
	{ 0x01, 0x08e, "KEY_SLEEP" },
	{ 0x01, 0x08f, "KEY_WAKEUP" },
	{ 0x01, 0x090, "KEY_FILE" },
	{ 0x01, 0x091, "KEY_SENDFILE" },
	{ 0x01, 0x092, "KEY_DELETEFILE" },
	{ 0x01, 0x093, "KEY_XFER" },
	{ 0x01, 0x094, "KEY_PROG1" },
	{ 0x01, 0x095, "KEY_PROG2" },
	{ 0x01, 0x096, "KEY_WWW" },
	{ 0x01, 0x097, "KEY_MSDOS" },
	{ 0x01, 0x098, "KEY_COFFEE" },
	{ 0x01, 0x099, "KEY_ROTATE_DISPLAY" },
	{ 0x01, 0x09a, "KEY_CYCLEWINDOWS" },
	{ 0x01, 0x09b, "KEY_MAIL" },
	{ 0x01, 0x09c, "KEY_BOOKMARKS" },
	{ 0x01, 0x09d, "KEY_COMPUTER" },
	{ 0x01, 0x09e, "KEY_BACK" },
	{ 0x01, 0x09f, "KEY_FORWARD" },
	{ 0x01, 0x0a0, "KEY_CLOSECD" },
	{ 0x01, 0x0a1, "KEY_EJECTCD" },
	{ 0x01, 0x0a2, "KEY_EJECTCLOSECD" },
	{ 0x01, 0x0a3, "KEY_NEXTSONG" },
	{ 0x01, 0x0a4, "KEY_PLAYPAUSE" },
	{ 0x01, 0x0a5, "KEY_PREVIOUSSONG" },
	{ 0x01, 0x0a6, "KEY_STOPCD" },
	{ 0x01, 0x0a7, "KEY_RECORD" },
	{ 0x01, 0x0a8, "KEY_REWIND" },
	{ 0x01, 0x0a9, "KEY_PHONE" },
	{ 0x01, 0x0aa, "KEY_ISO" },
	{ 0x01, 0x0ab, "KEY_CONFIG" },
	{ 0x01, 0x0ac, "KEY_HOMEPAGE" },
	{ 0x01, 0x0ad, "KEY_REFRESH" },
	{ 0x01, 0x0ae, "KEY_EXIT" },
	{ 0x01, 0x0af, "KEY_MOVE" },
	{ 0x01, 0x0b0, "KEY_EDIT" },
	{ 0x01, 0x0b1, "KEY_SCROLLUP" },
	{ 0x01, 0x0b2, "KEY_SCROLLDOWN" },
	{ 0x01, 0x0b3, "KEY_KPLEFTPAREN" },
	{ 0x01, 0x0b4, "KEY_KPRIGHTPAREN" },
	{ 0x01, 0x0b5, "KEY_NEW" },
	{ 0x01, 0x0b6, "KEY_REDO" },
	{ 0x01, 0x0b7, "KEY_F13" },
	{ 0x01, 0x0b8, "KEY_F14" },
	{ 0x01, 0x0b9, "KEY_F15" },
	{ 0x01, 0x0ba, "KEY_F16" },
	{ 0x01, 0x0bb, "KEY_F17" },
	{ 0x01, 0x0bc, "KEY_F18" },
	{ 0x01, 0x0bd, "KEY_F19" },
	{ 0x01, 0x0be, "KEY_F20" },
	{ 0x01, 0x0bf, "KEY_F21" },
	{ 0x01, 0x0c0, "KEY_F22" },
	{ 0x01, 0x0c1, "KEY_F23" },
	{ 0x01, 0x0c2, "KEY_F24" },
	{ 0x01, 0x0c8, "KEY_PLAYCD" },
	{ 0x01, 0x0c9, "KEY_PAUSECD" },
	{ 0x01, 0x0ca, "KEY_PROG3" },
	{ 0x01, 0x0cb, "KEY_PROG4" },
	{ 0x01, 0x0cc, "KEY_ALL_APPLICATIONS" },
	{ 0x01, 0x0cd, "KEY_SUSPEND" },
	{ 0x01, 0x0ce, "KEY_CLOSE" },
	{ 0x01, 0x0cf, "KEY_PLAY" },
	{ 0x01, 0x0d0, "KEY_FASTFORWARD" },
	{ 0x01, 0x0d1, "KEY_BASSBOOST" },
	{ 0x01, 0x0d2, "KEY_PRINT" },
	{ 0x01, 0x0d3, "KEY_HP" },
	{ 0x01, 0x0d4, "KEY_CAMERA" },
	{ 0x01, 0x0d5, "KEY_SOUND" },
	{ 0x01, 0x0d6, "KEY_QUESTION" },
	{ 0x01, 0x0d7, "KEY_EMAIL" },
	{ 0x01, 0x0d8, "KEY_CHAT" },
	{ 0x01, 0x0d9, "KEY_SEARCH" },
	{ 0x01, 0x0da, "KEY_CONNECT" },
	{ 0x01, 0x0db, "KEY_FINANCE" },
	{ 0x01, 0x0dc, "KEY_SPORT" },
	{ 0x01, 0x0dd, "KEY_SHOP" },
	{ 0x01, 0x0de, "KEY_ALTERASE" },
	{ 0x01, 0x0df, "KEY_CANCEL" },
	{ 0x01, 0x0e0, "KEY_BRIGHTNESSDOWN" },
	{ 0x01, 0x0e1, "KEY_BRIGHTNESSUP" },
	{ 0x01, 0x0e2, "KEY_MEDIA" },
	{ 0x01, 0x0e3, "KEY_SWITCHVIDEOMODE" },
	{ 0x01, 0x0e4, "KEY_KBDILLUMTOGGLE" },
	{ 0x01, 0x0e5, "KEY_KBDILLUMDOWN" },
	{ 0x01, 0x0e6, "KEY_KBDILLUMUP" },
	{ 0x01, 0x0e7, "KEY_SEND" },
	{ 0x01, 0x0e8, "KEY_REPLY" },
	{ 0x01, 0x0e9, "KEY_FORWARDMAIL" },
	{ 0x01, 0x0ea, "KEY_SAVE" },
	{ 0x01, 0x0eb, "KEY_DOCUMENTS" },
	{ 0x01, 0x0ec, "KEY_BATTERY" },
	{ 0x01, 0x0ed, "KEY_BLUETOOTH" },
	{ 0x01, 0x0ee, "KEY_WLAN" },
	{ 0x01, 0x0ef, "KEY_UWB" },
	{ 0x01, 0x0f0, "KEY_UNKNOWN" },
	{ 0x01, 0x0f1, "KEY_VIDEO_NEXT" },
	{ 0x01, 0x0f2, "KEY_VIDEO_PREV" },
	{ 0x01, 0x0f3, "KEY_BRIGHTNESS_CYCLE" },
	{ 0x01, 0x0f4, "KEY_BRIGHTNESS_AUTO" },
	{ 0x01, 0x0f5, "KEY_DISPLAY_OFF" },
	{ 0x01, 0x0f6, "KEY_WWAN" },
	{ 0x01, 0x0f7, "KEY_RFKILL" },
	{ 0x01, 0x0f8, "KEY_MICMUTE" },
	{ 0x01, 0x100, "BTN_0" },
	{ 0x01, 0x101, "BTN_1" },
	{ 0x01, 0x102, "BTN_2" },
	{ 0x01, 0x103, "BTN_3" },
	{ 0x01, 0x104, "BTN_4" },
	{ 0x01, 0x105, "BTN_5" },
	{ 0x01, 0x106, "BTN_6" },
	{ 0x01, 0x107, "BTN_7" },
	{ 0x01, 0x108, "BTN_8" },
	{ 0x01, 0x109, "BTN_9" },
	{ 0x01, 0x110, "BTN_LEFT" },
	{ 0x01, 0x111, "BTN_RIGHT" },
	{ 0x01, 0x112, "BTN_MIDDLE" },
	{ 0x01, 0x113, "BTN_SIDE" },
	{ 0x01, 0x114, "BTN_EXTRA" },
	{ 0x01, 0x115, "BTN_FORWARD" },
	{ 0x01, 0x116, "BTN_BACK" },
	{ 0x01, 0x117, "BTN_TASK" },
	{ 0x01, 0x120, "BTN_TRIGGER" },
	{ 0x01, 0x121, "BTN_THUMB" },
	{ 0x01, 0x122, "BTN_THUMB2" },
	{ 0x01, 0x123, "BTN_TOP" },
	{ 0x01, 0x124, "BTN_TOP2" },
	{ 0x01, 0x125, "BTN_PINKIE" },
	{ 0x01, 0x126, "BTN_BASE" },
	{ 0x01, 0x127, "BTN_BASE2" },
	{ 0x01, 0x128, "BTN_BASE3" },
	{ 0x01, 0x129, "BTN_BASE4" },
	{ 0x01, 0x12a, "BTN_BASE5" },
	{ 0x01, 0x12b, "BTN_BASE6" },
	{ 0x01, 0x12f, "BTN_DEAD" },
	{ 0x01, 0x130, "BTN_SOUTH" },
	{ 0x01, 0x131, "BTN_EAST" },
	{ 0x01, 0x132, "BTN_C" },
	{ 0x01, 0x133, "BTN_NORTH" },
	{ 0x01, 0x134, "BTN_WEST" },
	{ 0x01, 0x135, "BTN_Z" },
	{ 0x01, 0x136, "BTN_TL" },
	{ 0x01, 0x137, "BTN_TR" },
	{ 0x01, 0x138, "BTN_TL2" },
	{ 0x01, 0x139, "BTN_TR2" },
	{ 0x01, 0x13a, "BTN_SELECT" },
	{ 0x01, 0x13b, "BTN_START" },
	{ 0x01, 0x13c, "BTN_MODE" },
	{ 0x01, 0x13d, "BTN_THUMBL" },
	{ 0x01, 0x13e, "BTN_THUMBR" },
	{ 0x01, 0x140, "BTN_TOOL_PEN" },
	{ 0x01, 0x141, "BTN_TOOL_RUBBER" },
	{ 0x01, 0x142, "BTN_TOOL_BRUSH" },
	{ 0x01, 0x143, "BTN_TOOL_PENCIL" },
	{ 0x01, 0x144, "BTN_TOOL_AIRBRUSH" },
	{ 0x01, 0x145, "BTN_TOOL_FINGER" },
	{ 0x01, 0x146, "BTN_TOOL_MOUSE" },
	{ 0x01, 0x147, "BTN_TOOL_LENS" },
	{ 0x01, 0x148, "BTN_TOOL_QUINTTAP" },
	{ 0x01, 0x149, "BTN_STYLUS3" },
	{ 0x01, 0x14a, "BTN_TOUCH" },
	{ 0x01, 0x14b, "BTN_STYLUS" },
	{ 0x01, 0x14c, "BTN_STYLUS2" },
	{ 0x01, 0x14d, "BTN_TOOL_DOUBLETAP" },
	{ 0x01, 0x14e, "BTN_TOOL_TRIPLETAP" },
	{ 0x01, 0x14f, "BTN_TOOL_QUADTAP" },
	{ 0x01, 0x150, "BTN_GEAR_DOWN" },
	{ 0x01, 0x151, "BTN_GEAR_UP" },
	{ 0x01, 0x160, "KEY_OK" },
	{ 0x01, 0x161, "KEY_SELECT" },
	{ 0x01, 0x162, "KEY_GOTO" },
	{ 0x01, 0x163, "KEY_CLEAR" },
	{ 0x01, 0x164, "KEY_POWER2" },
	{ 0x01, 0x165, "KEY_OPTION" },
	{ 0x01, 0x166, "KEY_INFO" },
	{ 0x01, 0x167, "KEY_TIME" },
	{ 0x01, 0x168, "KEY_VENDOR" },
	{ 0x01, 0x169, "KEY_ARCHIVE" },
	{ 0x01, 0x16a, "KEY_PROGRAM" },
	{ 0x01, 0x16b, "KEY_CHANNEL" },
	{ 0x01, 0x16c, "KEY_FAVORITES" },
	{ 0x01, 0x16d, "KEY_EPG" },
	{ 0x01, 0x16e, "KEY_PVR" },
	{ 0x01, 0x16f, "KEY_MHP" },
	{ 0x01, 0x170, "KEY_LANGUAGE" },
	{ 0x01, 0x171, "KEY_TITLE" },
	{ 0x01, 0x172, "KEY_SUBTITLE" },
	{ 0x01, 0x173, "KEY_ANGLE" },
	{ 0x01, 0x174, "KEY_FULL_SCREEN" },
	{ 0x01, 0x175, "KEY_MODE" },
	{ 0x01, 0x176, "KEY_KEYBOARD" },
	{ 0x01, 0x177, "KEY_ASPECT_RATIO" },
	{ 0x01, 0x178, "KEY_PC" },
	{ 0x01, 0x179, "KEY_TV" },
	{ 0x01, 0x17a, "KEY_TV2" },
	{ 0x01, 0x17b, "KEY_VCR" },
	{ 0x01, 0x17c, "KEY_VCR2" },
	{ 0x01, 0x17d, "KEY_SAT" },
	{ 0x01, 0x17e, "KEY_SAT2" },
	{ 0x01, 0x17f, "KEY_CD" },
	{ 0x01, 0x180, "KEY_TAPE" },
	{ 0x01, 0x181, "KEY_RADIO" },
	{ 0x01, 0x182, "KEY_TUNER" },
	{ 0x01, 0x183, "KEY_PLAYER" },
	{ 0x01, 0x184, "KEY_TEXT" },
	{ 0x01, 0x185, "KEY_DVD" },
	{ 0x01, 0x186, "KEY_AUX" },
	{ 0x01, 0x187, "KEY_MP3" },
	{ 0x01, 0x188, "KEY_AUDIO" },
	{ 0x01, 0x189, "KEY_VIDEO" },
	{ 0x01, 0x18a, "KEY_DIRECTORY" },
	{ 0x01, 0x18b, "KEY_LIST" },
	{ 0x01, 0x18c, "KEY_MEMO" },
	{ 0x01, 0x18d, "KEY_CALENDAR" },
	{ 0x01, 0x18e, "KEY_RED" },
	{ 0x01, 0x18f, "KEY_GREEN" },
	{ 0x01, 0x190, "KEY_YELLOW" },
	{ 0x01, 0x191, "KEY_BLUE" },
	{ 0x01, 0x192, "KEY_CHANNELUP" },
	{ 0x01, 0x193, "KEY_CHANNELDOWN" },
	{ 0x01, 0x194, "KEY_FIRST" },
	{ 0x01, 0x195, "KEY_LAST" },
	{ 0x01, 0x196, "KEY_AB" },
	{ 0x01, 0x197, "KEY_NEXT" },
	{ 0x01, 0x198, "KEY_RESTART" },
	{ 0x01, 0x199, "KEY_SLOW" },
	{ 0x01, 0x19a, "KEY_SHUFFLE" },
	{ 0x01, 0x19b, "KEY_BREAK" },
	{ 0x01, 0x19c, "KEY_PREVIOUS" },
	{ 0x01, 0x19d, "KEY_DIGITS" },
	{ 0x01, 0x19e, "KEY_TEEN" },
	{ 0x01, 0x19f, "KEY_TWEN" },
	{ 0x01, 0x1a0, "KEY_VIDEOPHONE" },
	{ 0x01, 0x1a1, "KEY_GAMES" },
	{ 0x01, 0x1a2, "KEY_ZOOMIN" },
	{ 0x01, 0x1a3, "KEY_ZOOMOUT" },
	{ 0x01, 0x1a4, "KEY_ZOOMRESET" },
	{ 0x01, 0x1a5, "KEY_WORDPROCESSOR" },
	{ 0x01, 0x1a6, "KEY_EDITOR" },
	{ 0x01, 0x1a7, "KEY_SPREADSHEET" },
	{ 0x01, 0x1a8, "KEY_GRAPHICSEDITOR" },
	{ 0x01, 0x1a9, "KEY_PRESENTATION" },
	{ 0x01, 0x1aa, "KEY_DATABASE" },
	{ 0x01, 0x1ab, "KEY_NEWS" },
	{ 0x01, 0x1ac, "KEY_VOICEMAIL" },
	{ 0x01, 0x1ad, "KEY_ADDRESSBOOK" },
	{ 0x01, 0x1ae, "KEY_MESSENGER" },
	{ 0x01, 0x1af, "KEY_DISPLAYTOGGLE" },
	{ 0x01, 0x1b0, "KEY_SPELLCHECK" },
	{ 0x01, 0x1b1, "KEY_LOGOFF" },
	{ 0x01, 0x1b2, "KEY_DOLLAR" },
	{ 0x01, 0x1b3, "KEY_EURO" },
	{ 0x01, 0x1b4, "KEY_FRAMEBACK" },
	{ 0x01, 0x1b5, "KEY_FRAMEFORWARD" },
	{ 0x01, 0x1b6, "KEY_CONTEXT_MENU" },
	{ 0x01, 0x1b7, "KEY_MEDIA_REPEAT" },
	{ 0x01, 0x1b8, "KEY_10CHANNELSUP" },
	{ 0x01, 0x1b9, "KEY_10CHANNELSDOWN" },
	{ 0x01, 0x1ba, "KEY_IMAGES" },
	{ 0x01, 0x1bc, "KEY_NOTIFICATION_CENTER" },
	{ 0x01, 0x1bd, "KEY_PICKUP_PHONE" },
	{ 0x01, 0x1be, "KEY_HANGUP_PHONE" },
	{ 0x01, 0x1bf, "KEY_LINK_PHONE" },
	{ 0x01, 0x1c0, "KEY_DEL_EOL" },
	{ 0x01, 0x1c1, "KEY_DEL_EOS" },
	{ 0x01, 0x1c2, "KEY_INS_LINE" },
	{ 0x01, 0x1c3, "KEY_DEL_LINE" },
	{ 0x01, 0x1d0, "KEY_FN" },
	{ 0x01, 0x1d1, "KEY_FN_ESC" },
	{ 0x01, 0x1d2, "KEY_FN_F1" },
	{ 0x01, 0x1d3, "KEY_FN_F2" },
	{ 0x01, 0x1d4, "KEY_FN_F3" },
	{ 0x01, 0x1d5, "KEY_FN_F4" },
	{ 0x01, 0x1d6, "KEY_FN_F5" },
	{ 0x01, 0x1d7, "KEY_FN_F6" },
	{ 0x01, 0x1d8, "KEY_FN_F7" },
	{ 0x01, 0x1d9, "KEY_FN_F8" },
	{ 0x01, 0x1da, "KEY_FN_F9" },
	{ 0x01, 0x1db, "KEY_FN_F10" },
	{ 0x01, 0x1dc, "KEY_FN_F11" },
	{ 0x01, 0x1dd, "KEY_FN_F12" },
	{ 0x01, 0x1de, "KEY_FN_1" },
	{ 0x01, 0x1df, "KEY_FN_2" },
	{ 0x01, 0x1e0, "KEY_FN_D" },
	{ 0x01, 0x1e1, "KEY_FN_E" },
	{ 0x01, 0x1e2, "KEY_FN_F" },
	{ 0x01, 0x1e3, "KEY_FN_S" },
	{ 0x01, 0x1e4, "KEY_FN_B" },
	{ 0x01, 0x1e5, "KEY_FN_RIGHT_SHIFT" },
	{ 0x01, 0x1f1, "KEY_BRL_DOT1" },
	{ 0x01, 0x1f2, "KEY_BRL_DOT2" },
	{ 0x01, 0x1f3, "KEY_BRL_DOT3" },
	{ 0x01, 0x1f4, "KEY_BRL_DOT4" },
	{ 0x01, 0x1f5, "KEY_BRL_DOT5" },
	{ 0x01, 0x1f6, "KEY_BRL_DOT6" },
	{ 0x01, 0x1f7, "KEY_BRL_DOT7" },
	{ 0x01, 0x1f8, "KEY_BRL_DOT8" },
	{ 0x01, 0x1f9, "KEY_BRL_DOT9" },
	{ 0x01, 0x1fa, "KEY_BRL_DOT10" },
	{ 0x01, 0x200, "KEY_NUMERIC_0" },
	{ 0x01, 0x201, "KEY_NUMERIC_1" },
	{ 0x01, 0x202, "KEY_NUMERIC_2" },
	{ 0x01, 0x203, "KEY_NUMERIC_3" },
	{ 0x01, 0x204, "KEY_NUMERIC_4" },
	{ 0x01, 0x205, "KEY_NUMERIC_5" },
	{ 0x01, 0x206, "KEY_NUMERIC_6" },
	{ 0x01, 0x207, "KEY_NUMERIC_7" },
	{ 0x01, 0x208, "KEY_NUMERIC_8" },
	{ 0x01, 0x209, "KEY_NUMERIC_9" },
	{ 0x01, 0x20a, "KEY_NUMERIC_STAR" },
	{ 0x01, 0x20b, "KEY_NUMERIC_POUND" },
	{ 0x01, 0x20c, "KEY_NUMERIC_A" },
	{ 0x01, 0x20d, "KEY_NUMERIC_B" },
	{ 0x01, 0x20e, "KEY_NUMERIC_C" },
	{ 0x01, 0x20f, "KEY_NUMERIC_D" },
	{ 0x01, 0x210, "KEY_CAMERA_FOCUS" },
	{ 0x01, 0x211, "KEY_WPS_BUTTON" },
	{ 0x01, 0x212, "KEY_TOUCHPAD_TOGGLE" },
	{ 0x01, 0x213, "KEY_TOUCHPAD_ON" },
	{ 0x01, 0x214, "KEY_TOUCHPAD_OFF" },
	{ 0x01, 0x215, "KEY_CAMERA_ZOOMIN" },
	{ 0x01, 0x216, "KEY_CAMERA_ZOOMOUT" },
	{ 0x01, 0x217, "KEY_CAMERA_UP" },
	{ 0x01, 0x218, "KEY_CAMERA_DOWN" },
	{ 0x01, 0x219, "KEY_CAMERA_LEFT" },
	{ 0x01, 0x21a, "KEY_CAMERA_RIGHT" },
	{ 0x01, 0x21b, "KEY_ATTENDANT_ON" },
	{ 0x01, 0x21c, "KEY_ATTENDANT_OFF" },
	{ 0x01, 0x21d, "KEY_ATTENDANT_TOGGLE" },
	{ 0x01, 0x21e, "KEY_LIGHTS_TOGGLE" },
	{ 0x01, 0x220, "BTN_DPAD_UP" },
	{ 0x01, 0x221, "BTN_DPAD_DOWN" },
	{ 0x01, 0x222, "BTN_DPAD_LEFT" },
	{ 0x01, 0x223, "BTN_DPAD_RIGHT" },
	{ 0x01, 0x230, "KEY_ALS_TOGGLE" },
	{ 0x01, 0x231, "KEY_ROTATE_LOCK_TOGGLE" },
	{ 0x01, 0x232, "KEY_REFRESH_RATE_TOGGLE" },
	{ 0x01, 0x240, "KEY_BUTTONCONFIG" },
	{ 0x01, 0x241, "KEY_TASKMANAGER" },
	{ 0x01, 0x242, "KEY_JOURNAL" },
	{ 0x01, 0x243, "KEY_CONTROLPANEL" },
	{ 0x01, 0x244, "KEY_APPSELECT" },
	{ 0x01, 0x245, "KEY_SCREENSAVER" },
	{ 0x01, 0x246, "KEY_VOICECOMMAND" },
	{ 0x01, 0x247, "KEY_ASSISTANT" },
	{ 0x01, 0x248, "KEY_KBD_LAYOUT_NEXT" },
	{ 0x01, 0x249, "KEY_EMOJI_PICKER" },
	{ 0x01, 0x24a, "KEY_DICTATE" },
	{ 0x01, 0x250, "KEY_BRIGHTNESS_MIN" },
	{ 0x01, 0x251, "KEY_BRIGHTNESS_MAX" },
	{ 0x01, 0x260, "KEY_KBDINPUTASSIST_PREV" },
	{ 0x01, 0x261, "KEY_KBDINPUTASSIST_NEXT" },
	{ 0x01, 0x262, "KEY_KBDINPUTASSIST_PREVGROUP" },
	{ 0x01, 0x263, "KEY_KBDINPUTASSIST_NEXTGROUP" },
	{ 0x01, 0x264, "KEY_KBDINPUTASSIST_ACCEPT" },
	{ 0x01, 0x265, "KEY_KBDINPUTASSIST_CANCEL" },
	{ 0x01, 0x266, "KEY_RIGHT_UP" },
	{ 0x01, 0x267, "KEY_RIGHT_DOWN" },
	{ 0x01, 0x268, "KEY_LEFT_UP" },
	{ 0x01, 0x269, "KEY_LEFT_DOWN" },
	{ 0x01, 0x26a, "KEY_ROOT_MENU" },
	{ 0x01, 0x26b, "KEY_MEDIA_TOP_MENU" },
	{ 0x01, 0x26c, "KEY_NUMERIC_11" },
	{ 0x01, 0x26d, "KEY_NUMERIC_12" },
	{ 0x01, 0x26e, "KEY_AUDIO_DESC" },
	{ 0x01, 0x26f, "KEY_3D_MODE" },
	{ 0x01, 0x270, "KEY_NEXT_FAVORITE" },
	{ 0x01, 0x271, "KEY_STOP_RECORD" },
	{ 0x01, 0x272, "KEY_PAUSE_RECORD" },
	{ 0x01, 0x273, "KEY_VOD" },
	{ 0x01, 0x274, "KEY_UNMUTE" },
	{ 0x01, 0x275, "KEY_FASTREVERSE" },
	{ 0x01, 0x276, "KEY_SLOWREVERSE" },
	{ 0x01, 0x277, "KEY_DATA" },
	{ 0x01, 0x278, "KEY_ONSCREEN_KEYBOARD" },
	{ 0x01, 0x279, "KEY_PRIVACY_SCREEN_TOGGLE" },
	{ 0x01, 0x27a, "KEY_SELECTIVE_SCREENSHOT" },
	{ 0x01, 0x27b, "KEY_NEXT_ELEMENT" },
	{ 0x01, 0x27c, "KEY_PREVIOUS_ELEMENT" },
	{ 0x01, 0x27d, "KEY_AUTOPILOT_ENGAGE_TOGGLE" },
	{ 0x01, 0x27e, "KEY_MARK_WAYPOINT" },
	{ 0x01, 0x27f, "KEY_SOS" },
	{ 0x01, 0x280, "KEY_NAV_CHART" },
	{ 0x01, 0x281, "KEY_FISHING_CHART" },
	{ 0x01, 0x282, "KEY_SINGLE_RANGE_RADAR" },
	{ 0x01, 0x283, "KEY_DUAL_RANGE_RADAR" },
	{ 0x01, 0x284, "KEY_RADAR_OVERLAY" },
	{ 0x01, 0x285, "KEY_TRADITIONAL_SONAR" },
	{ 0x01, 0x286, "KEY_CLEARVU_SONAR" },
	{ 0x01, 0x287, "KEY_SIDEVU_SONAR" },
	{ 0x01, 0x288, "KEY_NAV_INFO" },
	{ 0x01, 0x289, "KEY_BRIGHTNESS_MENU" },
	{ 0x01, 0x290, "KEY_MACRO1" },
	{ 0x01, 0x291, "KEY_MACRO2" },
	{ 0x01, 0x292, "KEY_MACRO3" },
	{ 0x01, 0x293, "KEY_MACRO4" },
	{ 0x01, 0x294, "KEY_MACRO5" },
	{ 0x01, 0x295, "KEY_MACRO6" },
	{ 0x01, 0x296, "KEY_MACRO7" },
	{ 0x01, 0x297, "KEY_MACRO8" },
	{ 0x01, 0x298, "KEY_MACRO9" },
	{ 0x01, 0x299, "KEY_MACRO10" },
	{ 0x01, 0x29a, "KEY_MACRO11" },
	{ 0x01, 0x29b, "KEY_MACRO12" },
	{ 0x01, 0x29c, "KEY_MACRO13" },
	{ 0x01, 0x29d, "KEY_MACRO14" },
	{ 0x01, 0x29e, "KEY_MACRO15" },
	{ 0x01, 0x29f, "KEY_MACRO16" },
	{ 0x01, 0x2a0, "KEY_MACRO17" },
	{ 0x01, 0x2a1, "KEY_MACRO18" },
	{ 0x01, 0x2a2, "KEY_MACRO19" },
	{ 0x01, 0x2a3, "KEY_MACRO20" },
	{ 0x01, 0x2a4, "KEY_MACRO21" },
	{ 0x01, 0x2a5, "KEY_MACRO22" },
	{ 0x01, 0x2a6, "KEY_MACRO23" },
	{ 0x01, 0x2a7, "KEY_MACRO24" },
	{ 0x01, 0x2a8, "KEY_MACRO25" },
	{ 0x01, 0x2a9, "KEY_MACRO26" },
	{ 0x01, 0x2aa, "KEY_MACRO27" },
	{ 0x01, 0x2ab, "KEY_MACRO28" },
	{ 0x01, 0x2ac, "KEY_MACRO29" },
	{ 0x01, 0x2ad, "KEY_MACRO30" },
	{ 0x01, 0x2b0, "KEY_MACRO_RECORD_START" },
	{ 0x01, 0x2b1, "KEY_MACRO_RECORD_STOP" },
	{ 0x01, 0x2b2, "KEY_MACRO_PRESET_CYCLE" },
	{ 0x01, 0x2b3, "KEY_MACRO_PRESET1" },
	{ 0x01, 0x2b4, "KEY_MACRO_PRESET2" },
	{ 0x01, 0x2b5, "KEY_MACRO_PRESET3" },
	{ 0x01, 0x2b8, "KEY_KBD_LCD_MENU1" },
	{ 0x01, 0x2b9, "KEY_KBD_LCD_MENU2" },
	{ 0x01, 0x2ba, "KEY_KBD_LCD_MENU3" },
	{ 0x01, 0x2bb, "KEY_KBD_LCD_MENU4" },
	{ 0x01, 0x2bc, "KEY_KBD_LCD_MENU5" },
	{ 0x01, 0x2c0, "BTN_TRIGGER_HAPPY1" },
	{ 0x01, 0x2c1, "BTN_TRIGGER_HAPPY2" },
	{ 0x01, 0x2c2, "BTN_TRIGGER_HAPPY3" },
	{ 0x01, 0x2c3, "BTN_TRIGGER_HAPPY4" },
	{ 0x01, 0x2c4, "BTN_TRIGGER_HAPPY5" },
	{ 0x01, 0x2c5, "BTN_TRIGGER_HAPPY6" },
	{ 0x01, 0x2c6, "BTN_TRIGGER_HAPPY7" },
	{ 0x01, 0x2c7, "BTN_TRIGGER_HAPPY8" },
	{ 0x01, 0x2c8, "BTN_TRIGGER_HAPPY9" },
	{ 0x01, 0x2c9, "BTN_TRIGGER_HAPPY10" },
	{ 0x01, 0x2ca, "BTN_TRIGGER_HAPPY11" },
	{ 0x01, 0x2cb, "BTN_TRIGGER_HAPPY12" },
	{ 0x01, 0x2cc, "BTN_TRIGGER_HAPPY13" },
	{ 0x01, 0x2cd, "BTN_TRIGGER_HAPPY14" },
	{ 0x01, 0x2ce, "BTN_TRIGGER_HAPPY15" },
	{ 0x01, 0x2cf, "BTN_TRIGGER_HAPPY16" },
	{ 0x01, 0x2d0, "BTN_TRIGGER_HAPPY17" },
	{ 0x01, 0x2d1, "BTN_TRIGGER_HAPPY18" },
	{ 0x01, 0x2d2, "BTN_TRIGGER_HAPPY19" },
	{ 0x01, 0x2d3, "BTN_TRIGGER_HAPPY20" },
	{ 0x01, 0x2d4, "BTN_TRIGGER_HAPPY21" },
	{ 0x01, 0x2d5, "BTN_TRIGGER_HAPPY22" },
	{ 0x01, 0x2d6, "BTN_TRIGGER_HAPPY23" },
	{ 0x01, 0x2d7, "BTN_TRIGGER_HAPPY24" },
	{ 0x01, 0x2d8, "BTN_TRIGGER_HAPPY25" },
	{ 0x01, 0x2d9, "BTN_TRIGGER_HAPPY26" },
	{ 0x01, 0x2da, "BTN_TRIGGER_HAPPY27" },
	{ 0x01, 0x2db, "BTN_TRIGGER_HAPPY28" },
	{ 0x01, 0x2dc, "BTN_TRIGGER_HAPPY29" },
	{ 0x01, 0x2dd, "BTN_TRIGGER_HAPPY30" },
	{ 0x01, 0x2de, "BTN_TRIGGER_HAPPY31" },
	{ 0x01, 0x2df, "BTN_TRIGGER_HAPPY32" },
	{ 0x01, 0x2e0, "BTN_TRIGGER_HAPPY33" },
	{ 0x01, 0x2e1, "BTN_TRIGGER_HAPPY34" },
	{ 0x01, 0x2e2, "BTN_TRIGGER_HAPPY35" },
	{ 0x01, 0x2e3, "BTN_TRIGGER_HAPPY36" },
	{ 0x01, 0x2e4, "BTN_TRIGGER_HAPPY37" },
	{ 0x01, 0x2e5, "BTN_TRIGGER_HAPPY38" },
	{ 0x01, 0x2e6, "BTN_TRIGGER_HAPPY39" },
	{ 0x01, 0x2e7, "BTN_TRIGGER_HAPPY40" },
	{ 0x01, 0x2ff, "KEY_MAX" },
	{ 0x02, 0x000, "REL_X" },
	{ 0x02, 0x001, "REL_Y" },
	{ 0x02, 0x002, "REL_Z" },
	{ 0x02, 0x003, "REL_RX" },
	{ 0x02, 0x004, "REL_RY" },
	{ 0x02, 0x005, "REL_RZ" },
	{ 0x02, 0x006, "REL_HWHEEL" },
	{ 0x02, 0x007, "REL_DIAL" },
	{ 0x02, 0x008, "REL_WHEEL" },
	{ 0x02, 0x009, "REL_MISC" },
	{ 0x02, 0x00a, "REL_RESERVED" },
	{ 0x02, 0x00b, "REL_WHEEL_HI_RES" },
	{ 0x02, 0x00c, "REL_HWHEEL_HI_RES" },
	{ 0x02, 0x00f, "REL_MAX" },
	{ 0x03, 0x000, "ABS_X" },
	{ 0x03, 0x001, "ABS_Y" },
	{ 0x03, 0x002, "ABS_Z" },
	{ 0x03, 0x003, "ABS_RX" },
	{ 0x03, 0x004, "ABS_RY" },
	{ 0x03, 0x005, "ABS_RZ" },
	{ 0x03, 0x006, "ABS_THROTTLE" },
	{ 0x03, 0x007, "ABS_RUDDER" },
	{ 0x03, 0x008, "ABS_WHEEL" },
	{ 0x03, 0x009, "ABS_GAS" },
	{ 0x03, 0x00a, "ABS_BRAKE" },
	{ 0x03, 0x010, "ABS_HAT0X" },
	{ 0x03, 0x011, "ABS_HAT0Y" },
	{ 0x03, 0x012, "ABS_HAT1X" },
	{ 0x03, 0x013, "ABS_HAT1Y" },
	{ 0x03, 0x014, "ABS_HAT2X" },
	{ 0x03, 0x015, "ABS_HAT2Y" },
	{ 0x03, 0x016, "ABS_HAT3X" },
	{ 0x03, 0x017, "ABS_HAT3Y" },
	{ 0x03, 0x018, "ABS_PRESSURE" },
	{ 0x03, 0x019, "ABS_DISTANCE" },
	{ 0x03, 0x01a, "ABS_TILT_X" },
	{ 0x03, 0x01b, "ABS_TILT_Y" },
	{ 0x03, 0x01c, "ABS_TOOL_WIDTH" },
	{ 0x03, 0x020, "ABS_VOLUME" },
	{ 0x03, 0x021, "ABS_PROFILE" },
	{ 0x03, 0x028, "ABS_MISC" },
	{ 0x03, 0x02e, "ABS_RESERVED" },
	{ 0x03, 0x02f, "ABS_MT_SLOT" },
	{ 0x03, 0x030, "ABS_MT_TOUCH_MAJOR" },
	{ 0x03, 0x031, "ABS_MT_TOUCH_MINOR" },
	{ 0x03, 0x032, "ABS_MT_WIDTH_MAJOR" },
	{ 0x03, 0x033, "ABS_MT_WIDTH_MINOR" },
	{ 0x03, 0x034, "ABS_MT_ORIENTATION" },
	{ 0x03, 0x035, "ABS_MT_POSITION_X" },
	{ 0x03, 0x036, "ABS_MT_POSITION_Y" },
	{ 0x03, 0x037, "ABS_MT_TOOL_TYPE" },
	{ 0x03, 0x038, "ABS_MT_BLOB_ID" },
	{ 0x03, 0x039, "ABS_MT_TRACKING_ID" },
	{ 0x03, 0x03a, "ABS_MT_PRESSURE" },
	{ 0x03, 0x03b, "ABS_MT_DISTANCE" },
	{ 0x03, 0x03c, "ABS_MT_TOOL_X" },
	{ 0x03, 0x03d, "ABS_MT_TOOL_Y" },
	{ 0x03, 0x03f, "ABS_MAX" },
	{ 0x04, 0x000, "MSC_SERIAL" },
	{ 0x04, 0x001, "MSC_PULSELED" },
	{ 0x04, 0x002, "MSC_GESTURE" },
	{ 0x04, 0x003, "MSC_RAW" },
	{ 0x04, 0x004, "MSC_SCAN" },
	{ 0x04, 0x005, "MSC_TIMESTAMP" },
	{ 0x04, 0x007, "MSC_MAX" },
	{ 0x05, 0x000, "SW_LID" },
	{ 0x05, 0x001, "SW_TABLET_MODE" },
	{ 0x05, 0x002, "SW_HEADPHONE_INSERT" },
	{ 0x05, 0x003, "SW_RFKILL_ALL" },
	{ 0x05, 0x004, "SW_MICROPHONE_INSERT" },
	{ 0x05, 0x005, "SW_DOCK" },
	{ 0x05, 0x006, "SW_LINEOUT_INSERT" },
	{ 0x05, 0x007, "SW_JACK_PHYSICAL_INSERT" },
	{ 0x05, 0x008, "SW_VIDEOOUT_INSERT" },
	{ 0x05, 0x009, "SW_CAMERA_LENS_COVER" },
	{ 0x05, 0x00a, "SW_KEYPAD_SLIDE" },
	{ 0x05, 0x00b, "SW_FRONT_PROXIMITY" },
	{ 0x05, 0x00c, "SW_ROTATE_LOCK" },
	{ 0x05, 0x00d, "SW_LINEIN_INSERT" },
	{ 0x05, 0x00e, "SW_MUTE_DEVICE" },
	{ 0x05, 0x00f, "SW_PEN_INSERTED" },
	{ 0x05, 0x010, "SW_MACHINE_COVER" },
	{ 0x11, 0x000, "LED_NUML" },
	{ 0x11, 0x001, "LED_CAPSL" },
	{ 0x11, 0x002, "LED_SCROLLL" },
	{ 0x11, 0x003, "LED_COMPOSE" },
	{ 0x11, 0x004, "LED_KANA" },
	{ 0x11, 0x005, "LED_SLEEP" },
	{ 0x11, 0x006, "LED_SUSPEND" },
	{ 0x11, 0x007, "LED_MUTE" },
	{ 0x11, 0x008, "LED_MISC" },
	{ 0x11, 0x009, "LED_MAIL" },
	{ 0x11, 0x00a, "LED_CHARGING" },
	{ 0x11, 0x00f, "LED_MAX" },
	{ 0x12, 0x000, "SND_CLICK" },
	{ 0x12, 0x001, "SND_BELL" },
	{ 0x12, 0x002, "SND_TONE" },
	{ 0x12, 0x007, "SND_MAX" },
	{ 0x14, 0x000, "REP_DELAY" },
	{ 0x14, 0x001, "REP_PERIOD" },
	{ 0x15, 0x000, "FF_STATUS_STOPPED" },
	{ 0x15, 0x001, "FF_STATUS_MAX" },
	{ 0x15, 0x050, "FF_RUMBLE" },
	{ 0x15, 0x051, "FF_PERIODIC" },
	{ 0x15, 0x052, "FF_CONSTANT" },
	{ 0x15, 0x053, "FF_SPRING" },
	{ 0x15, 0x054, "FF_FRICTION" },
	{ 0x15, 0x055, "FF_DAMPER" },
	{ 0x15, 0x056, "FF_INERTIA" },
	{ 0x15, 0x057, "FF_RAMP" },
	{ 0x15, 0x058, "FF_SQUARE" },
	{ 0x15, 0x059, "FF_TRIANGLE" },
	{ 0x15, 0x05a, "FF_SINE" },
	{ 0x15, 0x05b, "FF_SAW_UP" },
	{ 0x15, 0x05c, "FF_SAW_DOWN" },
	{ 0x15, 0x05d, "FF_CUSTOM" },
	{ 0x15, 0x060, "FF_GAIN" },
	{ 0x15, 0x061, "FF_AUTOCENTER" },
	{ 0x15, 0x07f, "FF_MAX" },
};


/* ---- names ---------------------------------------------------------------- */

const char *
rec_evemu_type_name(unsigned type)
{
	return type <= EV_MAX ? type_names[type] : NULL;
}

const char *
rec_evemu_code_name(unsigned type, unsigned code)
{
	size_t lo = 0, hi = sizeof code_names / sizeof code_names[0];
	while (lo < hi) {
		size_t mid = lo + (hi - lo) / 2;
		const struct code_name *c = &code_names[mid];
		if (c->type == type && c->code == code)
			return c->name;
		if (c->type < type || (c->type == type && c->code < code))
			lo = mid + 1;
		else
			hi = mid;
	}
	return NULL;
}

/* as printf shows a NULL string, which evemu's comments carry for codes without a name */
static const char *
shown(const char *name)
{
	return name ? name : "(null)";
}

/* the highest code of a type, as the writer sizes its bitmask lines; -1 for none */
static int
type_max(unsigned type)
{
	switch (type) {
	case EV_SYN:
		return SYN_MAX;
	case EV_KEY:
		return KEY_MAX;
	case EV_REL:
		return REL_MAX;
	case EV_ABS:
		return ABS_MAX;
	case EV_MSC:
		return MSC_MAX;
	case EV_SW:
		return SW_MAX;
	case EV_LED:
		return LED_MAX;
	case EV_SND:
		return SND_MAX;
	case EV_REP:
		return REP_MAX;
	case EV_FF:
		return FF_MAX;
	default:
		return -1;
	}
}

static int
bit(const uint8_t *mask, unsigned i)
{
	return (mask[i / 8] >> (i % 8)) & 1;
}

/* ---- reading -------------------------------------------------------------- */

struct parser {
	const char *name;
	unsigned line;
	char *err;
	size_t errlen;
	int seen_version_line; /* a non-blank line has been read */
	int seen_n, seen_i, seen_desc, seen_e;
	unsigned pbytes;                /* P: bytes read */
	unsigned mbytes[EV_CNT];        /* B: bytes read, per type */
	uint64_t first_us, prev_us;
	size_t cap;                     /* of dest->ev */
};

static int
fail(struct parser *p, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static int
fail(struct parser *p, const char *fmt, ...)
{
	if (!p->errlen)
		return -1;
	int k = snprintf(p->err, p->errlen, "%s:%u: ", p->name, p->line);
	if (k >= 0 && (size_t)k < p->errlen) {
		va_list ap;
		va_start(ap, fmt);
		vsnprintf(p->err + k, p->errlen - (size_t)k, fmt, ap);
		va_end(ap);
	}
	return -1;
}

/* a line's cursor: s moves towards end */
struct cursor {
	const char *s, *end;
};

static void
skip_blank(struct cursor *c)
{
	while (c->s < c->end && (*c->s == ' ' || *c->s == '\t'))
		c->s++;
}

/* 1 when the cursor stands at the end of a token */
static int
at_break(const struct cursor *c)
{
	return c->s == c->end || *c->s == ' ' || *c->s == '\t' || *c->s == '#';
}

static int
hexval(char ch)
{
	if (ch >= '0' && ch <= '9')
		return ch - '0';
	if (ch >= 'a' && ch <= 'f')
		return ch - 'a' + 10;
	if (ch >= 'A' && ch <= 'F')
		return ch - 'A' + 10;
	return -1;
}

/* a hex number of 1..maxdigits digits after blanks: 0, or -1 */
static int
take_hex(struct cursor *c, int maxdigits, unsigned *dest)
{
	skip_blank(c);
	unsigned v = 0;
	int n = 0;
	while (c->s < c->end && hexval(*c->s) >= 0) {
		if (++n > maxdigits)
			return -1;
		v = v * 16 + (unsigned)hexval(*c->s++);
	}
	if (!n || !at_break(c))
		return -1;
	*dest = v;
	return 0;
}

/* a decimal int32 with an optional sign after blanks: 0, or -1 */
static int
take_int(struct cursor *c, int32_t *dest)
{
	skip_blank(c);
	int neg = 0;
	if (c->s < c->end && (*c->s == '-' || *c->s == '+'))
		neg = *c->s++ == '-';
	int64_t v = 0;
	int n = 0;
	while (c->s < c->end && *c->s >= '0' && *c->s <= '9') {
		v = v * 10 + (*c->s++ - '0');
		if (v > (int64_t)INT32_MAX + 1)
			return -1;
		n++;
	}
	if (!n || !at_break(c))
		return -1;
	v = neg ? -v : v;
	if (v > INT32_MAX)
		return -1;
	*dest = (int32_t)v;
	return 0;
}

/* nothing but blanks, then the end or a comment: 0, or -1 */
static int
take_end(struct cursor *c)
{
	skip_blank(c);
	return c->s == c->end || *c->s == '#' ? 0 : -1;
}

/* "# EVEMU <major>.<minor>" on the first line: 1 taken, 0 not such a line, -1 bad */
static int
parse_version(struct parser *p, struct cursor c, struct rec_evemu *r)
{
	static const char tag[] = "# EVEMU";
	size_t k = sizeof tag - 1;
	if ((size_t)(c.end - c.s) < k || memcmp(c.s, tag, k))
		return 0;
	c.s += k;
	skip_blank(&c);
	unsigned v[2] = { 0, 0 };
	for (int i = 0; i < 2; i++) {
		int n = 0;
		while (c.s < c.end && *c.s >= '0' && *c.s <= '9' && n < 5) {
			v[i] = v[i] * 10 + (unsigned)(*c.s++ - '0');
			n++;
		}
		if (!n || (i == 0 && (c.s == c.end || *c.s++ != '.')))
			return fail(p, "bad format line, expected \"# EVEMU <major>.<minor>\"");
	}
	if (take_end(&c))
		return fail(p, "bad format line, expected \"# EVEMU <major>.<minor>\"");
	if (v[0] != FORMAT_MAJOR)
		return fail(p, "format %u.%u is not one this reader knows (1.x)", v[0], v[1]);
	r->major = v[0];
	r->minor = v[1];
	return 1;
}

static int
parse_name(struct parser *p, struct cursor c, struct rec_evemu *r)
{
	if (p->seen_n)
		return fail(p, "a second N: line");
	if (p->seen_desc)
		return fail(p, "N: after the description's other lines");
	skip_blank(&c);
	const char *cr = memchr(c.s, '\r', (size_t)(c.end - c.s));
	size_t len = (size_t)((cr ? cr : c.end) - c.s);
	if (len >= sizeof r->name)
		return fail(p, "name longer than %zu bytes", sizeof r->name - 1);
	memcpy(r->name, c.s, len);
	r->name[len] = 0;
	p->seen_n = 1;
	return 0;
}

static int
parse_id(struct parser *p, struct cursor c, struct rec_evemu *r)
{
	if (!p->seen_n)
		return fail(p, "I: before the N: line");
	if (p->seen_i)
		return fail(p, "a second I: line");
	unsigned v[4];
	for (int i = 0; i < 4; i++)
		if (take_hex(&c, 4, &v[i]))
			return fail(p, "expected \"I: <bus> <vendor> <product> <version>\" in hex");
	if (take_end(&c))
		return fail(p, "unexpected text after the I: line's four numbers");
	r->bustype = (uint16_t)v[0];
	r->vendor = (uint16_t)v[1];
	r->product = (uint16_t)v[2];
	r->version = (uint16_t)v[3];
	p->seen_i = 1;
	return 0;
}

/*
 * 8 hex bytes onto a bitmask of cap bytes from byte *at: bytes past cap
 * must be zero (a longer bitmask than this kernel's, with nothing in it)
 */
static int
parse_bytes(struct parser *p, struct cursor *c, uint8_t *mask, size_t cap, unsigned *at,
	    const char *what)
{
	for (int i = 0; i < 8; i++) {
		unsigned b;
		if (take_hex(c, 2, &b))
			return fail(p, "expected 8 hex bytes in the %s line", what);
		if (*at + (unsigned)i < cap)
			mask[*at + (unsigned)i] = (uint8_t)b;
		else if (b)
			return fail(p, "bits past the %zu bytes of the %s bitmask", cap, what);
	}
	if (take_end(c))
		return fail(p, "unexpected text after the %s line's 8 bytes", what);
	if (*at < 4096)
		*at += 8;
	return 0;
}

static int
parse_prop(struct parser *p, struct cursor c, struct rec_evemu *r)
{
	return parse_bytes(p, &c, r->props, sizeof r->props, &p->pbytes, "P:");
}

static int
parse_mask(struct parser *p, struct cursor c, struct rec_evemu *r)
{
	unsigned type;
	if (take_hex(&c, 2, &type))
		return fail(p, "expected \"B: <type> <8 hex bytes>\"");
	if (type > EV_MAX)
		return fail(p, "no event type %#x (the largest is %#x)", type, EV_MAX);
	return parse_bytes(p, &c, r->bits[type], sizeof r->bits[type], &p->mbytes[type], "B:");
}

static int
parse_abs(struct parser *p, struct cursor c, struct rec_evemu *r)
{
	/* the resolution came with format 1.2 */
	int needed = r->major == 1 && r->minor < 2 ? 5 : 6;
	unsigned code;
	int32_t v[5] = { 0, 0, 0, 0, 0 };
	if (take_hex(&c, 4, &code))
		return fail(p, "expected \"A: <code> <min> <max> <fuzz> <flat>%s\"",
			    needed == 6 ? " <res>" : "");
	if (code > ABS_MAX)
		return fail(p, "no ABS code %#x (the largest is %#x)", code, ABS_MAX);
	for (int i = 0; i < needed - 1; i++)
		if (take_int(&c, &v[i]))
			return fail(p,
				    "expected %d numbers after the A: line's code (format %u.%u)",
				    needed - 1, r->major, r->minor);
	if (take_end(&c))
		return fail(p, "more than %d numbers after the A: line's code in format %u.%u",
			    needed - 1, r->major, r->minor);
	struct rec_evemu_abs *a = &r->abs[code];
	a->min = v[0];
	a->max = v[1];
	a->fuzz = v[2];
	a->flat = v[3];
	a->res = v[4];
	r->abs_given[code] = 1;
	return 0;
}

/* L: and S: lines: a code and its state */
static int
parse_state(struct parser *p, struct cursor c, int32_t *states, unsigned max, char tag)
{
	unsigned code;
	int32_t v;
	if (take_hex(&c, 4, &code) || take_int(&c, &v) || take_end(&c))
		return fail(p, "expected \"%c: <code> <state>\"", tag);
	if (code > max)
		return fail(p, "no %s code %#x (the largest is %#x)", tag == 'L' ? "LED" : "SW",
			    code, max);
	states[code] = v;
	return 0;
}

static int
parse_event(struct parser *p, struct cursor c, struct rec_evemu *r)
{
	struct rec_evemu_event ev;
	uint64_t sec = 0;
	int n = 0;
	skip_blank(&c);
	while (c.s < c.end && *c.s >= '0' && *c.s <= '9') {
		if (sec > (UINT64_MAX / 1000000u - 9) / 10)
			return fail(p, "the event's seconds are too large");
		sec = sec * 10 + (uint64_t)(*c.s++ - '0');
		n++;
	}
	if (!n || c.s == c.end || *c.s++ != '.')
		return fail(p, "expected \"E: <sec>.<usec> <type> <code> <value>\"");
	uint32_t usec = 0;
	for (n = 0; c.s < c.end && *c.s >= '0' && *c.s <= '9'; n++)
		usec = usec * 10 + (uint32_t)(*c.s++ - '0');
	if (n != 6 || !at_break(&c))
		return fail(p, "the event's fraction of a second must have 6 digits");
	unsigned type, code;
	if (take_hex(&c, 4, &type) || take_hex(&c, 4, &code) || take_int(&c, &ev.value))
		return fail(p, "expected \"E: <sec>.<usec> <type> <code> <value>\"");
	if (take_end(&c))
		return fail(p, "unexpected text after the event's value");
	if (type > EV_MAX)
		return fail(p, "no event type %#x (the largest is %#x)", type, EV_MAX);
	uint64_t t = sec * 1000000u + usec;
	if (!p->seen_e)
		p->first_us = t;
	if (t < p->first_us)
		return fail(p, "the event is earlier than the first event");
	ev.t_us = t - p->first_us;
	ev.sec = sec;
	ev.usec = usec;
	ev.type = (uint16_t)type;
	ev.code = (uint16_t)code;
	if (r->nev == p->cap) {
		size_t cap = p->cap ? p->cap * 2 : 256;
		struct rec_evemu_event *grown = realloc(r->ev, cap * sizeof *grown);
		if (!grown)
			return fail(p, "out of memory for %zu events", cap);
		r->ev = grown;
		p->cap = cap;
	}
	r->ev[r->nev++] = ev;
	p->seen_e = 1;
	return 0;
}

/* one line (without its '\n'): 0, or -1 with the error written */
static int
parse_line(struct parser *p, struct cursor c, struct rec_evemu *r)
{
	if (memchr(c.s, 0, (size_t)(c.end - c.s)))
		return fail(p, "a NUL byte in the line");
	if (c.end > c.s && c.end[-1] == '\r')
		c.end--;
	skip_blank(&c);
	if (c.s == c.end)
		return 0;
	int first = !p->seen_version_line;
	p->seen_version_line = 1;
	if (*c.s == '#') {
		if (!first)
			return 0;
		return parse_version(p, c, r) < 0 ? -1 : 0;
	}
	if (c.end - c.s < 2 || c.s[1] != ':')
		return 0;
	char tag = c.s[0];
	struct cursor rest = { c.s + 2, c.end };
	if (tag == 'E')
		return parse_event(p, rest, r);
	if (tag == 0 || !strchr("NIPBALS", tag))
		return 0;
	if (p->seen_e)
		return fail(p, "a %c: line after the events", tag);
	if (tag == 'N')
		return parse_name(p, rest, r);
	if (tag == 'I')
		return parse_id(p, rest, r);
	if (!p->seen_i)
		return fail(p, "a %c: line before the N: and I: lines", tag);
	p->seen_desc = 1;
	switch (tag) {
	case 'P':
		return parse_prop(p, rest, r);
	case 'B':
		return parse_mask(p, rest, r);
	case 'A':
		return parse_abs(p, rest, r);
	case 'L':
		return parse_state(p, rest, r->led, LED_MAX, 'L');
	default:
		return parse_state(p, rest, r->sw, SW_MAX, 'S');
	}
}

int
rec_evemu_parse(const char *text, size_t n, const char *name, struct rec_evemu *dest, char *err,
		size_t errlen)
{
	struct parser p = { .name = name, .err = err, .errlen = errlen };
	struct rec_evemu *r = calloc(1, sizeof *r);
	memset(dest, 0, sizeof *dest);
	if (errlen)
		err[0] = 0;
	if (!r)
		return fail(&p, "out of memory");
	/* without a "# EVEMU" line, the file is format 1.0 */
	r->major = 1;
	r->minor = 0;
	const char *s = text, *end = text + n;
	while (s < end) {
		const char *nl = memchr(s, '\n', (size_t)(end - s));
		const char *e = nl ? nl : end;
		p.line++;
		struct cursor c = { s, e };
		if (parse_line(&p, c, r)) {
			rec_evemu_free(r);
			free(r);
			return -1;
		}
		s = nl ? nl + 1 : end;
	}
	if (!p.seen_n && !r->nev) {
		rec_evemu_free(r);
		free(r);
		return fail(&p, "neither a device description nor events");
	}
	if (p.seen_n && !p.seen_i) {
		rec_evemu_free(r);
		free(r);
		return fail(&p, "an N: line without an I: line");
	}
	r->described = p.seen_n;
	/* every code with its EV_ABS bit has an absinfo, all zero without an A: line */
	for (unsigned c = 0; c <= ABS_MAX; c++)
		if (bit(r->bits[EV_ABS], c))
			r->abs_given[c] = 1;
	*dest = *r;
	free(r);
	return 0;
}

int
rec_evemu_read(const char *path, struct rec_evemu *dest, char *err, size_t errlen)
{
	memset(dest, 0, sizeof *dest);
	size_t n;
	char *text = textfile_read(path, &n, err, errlen);
	if (!text)
		return -1;
	int rc = rec_evemu_parse(text, n, path, dest, err, errlen);
	free(text);
	return rc;
}

void
rec_evemu_free(struct rec_evemu *r)
{
	free(r->ev);
	r->ev = NULL;
	r->nev = 0;
}

/* ---- writing -------------------------------------------------------------- */

static void
write_desc(FILE *out, const struct rec_evemu *r)
{
	fprintf(out, "# Input device name: \"%s\"\n", r->name);
	fprintf(out, "# Input device ID: bus %#04x vendor %#04x product %#04x version %#04x\n",
		r->bustype, r->vendor, r->product, r->version);
	if (bit(r->bits[EV_ABS], ABS_X) && bit(r->bits[EV_ABS], ABS_Y)) {
		const struct rec_evemu_abs *x = &r->abs[ABS_X], *y = &r->abs[ABS_Y];
		int64_t w = x->res ? ((int64_t)x->max - x->min) / x->res : 0;
		int64_t h = y->res ? ((int64_t)y->max - y->min) / y->res : 0;
		if (w && h)
			fprintf(out, "# Size in mm: %" PRId64 "x%" PRId64 "\n", w, h);
	}
	fprintf(out, "# Supported events:\n");
	for (unsigned t = 0; t <= EV_MAX; t++) {
		int any = 0;
		for (unsigned i = 0; i < REC_EVEMU_MASK_BYTES; i++)
			any |= r->bits[t][i];
		if (!any)
			continue;
		fprintf(out, "#   Event type %u (%s)\n", t, shown(rec_evemu_type_name(t)));
		for (unsigned c = 0; c < 8 * REC_EVEMU_MASK_BYTES; c++) {
			/* evemu lists every EV_SYN code once the type is there */
			if (t == EV_SYN ? c > SYN_MAX : !bit(r->bits[t], c))
				continue;
			fprintf(out, "#     Event code %u (%s)\n", c,
				shown(rec_evemu_code_name(t, c)));
			if (t == EV_ABS && c <= ABS_MAX) {
				const struct rec_evemu_abs *a = &r->abs[c];
				fprintf(out, "#       Value   %6d\n", 0);
				fprintf(out, "#       Min     %6d\n", a->min);
				fprintf(out, "#       Max     %6d\n", a->max);
				fprintf(out, "#       Fuzz    %6d\n", a->fuzz);
				fprintf(out, "#       Flat    %6d\n", a->flat);
				fprintf(out, "#       Resolution %3d\n", a->res);
			} else if (t == EV_LED && c <= LED_MAX) {
				fprintf(out, "#        State %d\n", r->led[c]);
			} else if (t == EV_SW && c <= SW_MAX) {
				fprintf(out, "#        State %d\n", r->sw[c]);
			}
		}
	}
	fprintf(out, "# Properties:\n");
	for (unsigned i = 0; i <= INPUT_PROP_MAX; i++)
		if (bit(r->props, i))
			fprintf(out, "#   Property  type %u (%s)\n", i, shown(prop_names[i]));
}

/* 8 bytes of a bitmask as one line's hex */
static void
write_bytes(FILE *out, const uint8_t *b)
{
	for (int i = 0; i < 8; i++)
		fprintf(out, " %02x", b[i]);
	fputc('\n', out);
}

static void
write_masks(FILE *out, const struct rec_evemu *r)
{
	fputs("P:", out);
	write_bytes(out, r->props);
	for (unsigned t = 0; t <= EV_MAX; t++) {
		/* evemu writes every type with a largest code in full, and EV_SYN as one line */
		size_t bytes = t == EV_SYN ? 8 : (size_t)(type_max(t) + 1 + 7) / 8;
		for (size_t i = REC_EVEMU_MASK_BYTES; i-- > bytes;)
			if (r->bits[t][i]) {
				bytes = i + 1;
				break;
			}
		for (size_t i = 0; i < bytes; i += 8) {
			fprintf(out, "B: %02x", t);
			write_bytes(out, &r->bits[t][i]);
		}
	}
}

int
rec_evemu_write_event(FILE *out, const struct rec_evemu_event *ev, uint64_t *last_ms)
{
	fprintf(out, "E: %" PRIu64 ".%06u %04x %04x %04d\t", ev->sec, (unsigned)ev->usec, ev->type,
		ev->code, (int)ev->value);
	const char *code = shown(rec_evemu_code_name(ev->type, ev->code));
	if (ev->type == EV_SYN && ev->code == SYN_MT_REPORT) {
		fprintf(out, "# ++++++++++++ %s (%d) ++++++++++\n", code, (int)ev->value);
	} else if (ev->type == EV_SYN) {
		uint64_t ms = ev->sec * 1000 + ev->usec / 1000;
		fprintf(out, "# ------------ %s (%d) ---------- %+" PRId64 "ms\n", code,
			(int)ev->value, (int64_t)(ms - *last_ms));
		*last_ms = ms;
	} else {
		fprintf(out, "# %s / %-20s %d\n", shown(rec_evemu_type_name(ev->type)), code,
			(int)ev->value);
	}
	return ferror(out) ? -1 : 0;
}

int
rec_evemu_write(FILE *out, const struct rec_evemu *r)
{
	fprintf(out, "# EVEMU %d.%d\n", FORMAT_MAJOR, FORMAT_MINOR);
	if (r->described) {
		write_desc(out, r);
		fprintf(out, "N: %s\n", r->name);
		fprintf(out, "I: %04x %04x %04x %04x\n", r->bustype, r->vendor, r->product,
			r->version);
		write_masks(out, r);
		for (unsigned c = 0; c <= ABS_MAX; c++) {
			const struct rec_evemu_abs *a = &r->abs[c];
			if (r->abs_given[c])
				fprintf(out, "A: %02x %d %d %d %d %d\n", c, a->min, a->max, a->fuzz,
					a->flat, a->res);
		}
		for (unsigned c = 0; c <= LED_MAX; c++)
			if (r->led[c])
				fprintf(out, "L: %02x %d\n", c, r->led[c]);
		for (unsigned c = 0; c <= SW_MAX; c++)
			if (r->sw[c])
				fprintf(out, "S: %02x %d\n", c, r->sw[c]);
	}
	uint64_t last_ms = 0;
	for (size_t i = 0; i < r->nev; i++)
		rec_evemu_write_event(out, &r->ev[i], &last_ms);
	return ferror(out) ? -1 : 0;
}

/* ---- replay ---------------------------------------------------------------- */

size_t
rec_evemu_to_records(const struct rec_evemu *r, uint8_t *dest, size_t max)
{
	const size_t size = sizeof(struct input_event);
	for (size_t i = 0; i < r->nev && (i + 1) * size <= max; i++) {
		const struct rec_evemu_event *ev = &r->ev[i];
		struct input_event rec;
		memset(&rec, 0, sizeof rec);
		rec.input_event_sec = (time_t)(ev->t_us / 1000000u);
		rec.input_event_usec = (suseconds_t)(ev->t_us % 1000000u);
		rec.type = ev->type;
		rec.code = ev->code;
		rec.value = ev->value;
		memcpy(dest + i * size, &rec, size);
	}
	return r->nev * size;
}

int
rec_evemu_apply_abs(const struct rec_evemu *r, struct evdev_input *dest)
{
	int n = 0;
	for (uint16_t c = ABS_X; c <= ABS_Y; c++)
		if (r->abs_given[c] &&
		    evdev_input_set_abs(dest, c, r->abs[c].min, r->abs[c].max) == 0)
			n++;
	return n;
}
