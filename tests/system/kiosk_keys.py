"""Typing at the kiosk over the socket: text as the key presses a US keyboard makes for it
(the evdev names of linux/input-event-codes.h; the US layout's symbols file gives which
key and level make each character), sent as `input key` lines."""

LETTERS = {c: f"KEY_{c.upper()}" for c in "abcdefghijklmnopqrstuvwxyz"}
DIGITS = {c: f"KEY_{c}" for c in "0123456789"}
# unshifted and shifted punctuation of the US layout (xkb symbols/us, "basic")
PLAIN = {" ": "KEY_SPACE", "-": "KEY_MINUS", "=": "KEY_EQUAL", ".": "KEY_DOT",
         ",": "KEY_COMMA", "/": "KEY_SLASH", ";": "KEY_SEMICOLON", "'": "KEY_APOSTROPHE",
         "[": "KEY_LEFTBRACE", "]": "KEY_RIGHTBRACE", "\\": "KEY_BACKSLASH", "`": "KEY_GRAVE"}
SHIFTED = {"_": "KEY_MINUS", "+": "KEY_EQUAL", ":": "KEY_SEMICOLON", '"': "KEY_APOSTROPHE",
           "<": "KEY_COMMA", ">": "KEY_DOT", "?": "KEY_SLASH", "!": "KEY_1", "@": "KEY_2",
           "#": "KEY_3", "$": "KEY_4", "%": "KEY_5", "^": "KEY_6", "&": "KEY_7", "*": "KEY_8",
           "(": "KEY_9", ")": "KEY_0"}


def key_lines(text):
    """the `input key` lines that type text on a US keyboard"""
    lines = []
    for ch in text:
        shift = ch in SHIFTED or ch.isupper()
        name = SHIFTED.get(ch) or LETTERS.get(ch.lower()) or DIGITS.get(ch) or PLAIN.get(ch)
        if name is None:
            raise ValueError(f"no US key types {ch!r}")
        if shift:
            lines.append("input key KEY_LEFTSHIFT down")
        lines += [f"input key {name} down", f"input key {name} up"]
        if shift:
            lines.append("input key KEY_LEFTSHIFT up")
    return lines


def press(c, *names):
    """presses the keys in order and releases them in reverse (a chord: Ctrl+Z)"""
    for n in names:
        c.request(f"input key {n} down")
    for n in reversed(names):
        c.request(f"input key {n} up")


def type_text(c, text, enter=False):
    for line in key_lines(text):
        c.request(line)
    if enter:
        press(c, "KEY_ENTER")
