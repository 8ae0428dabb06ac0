"""The real daemon at the kiosk on a real kernel (tests/guest/guest_kiosk.c): postured runs in
the QEMU guest and is driven through the devices this machine lacks, and checked through its
socket.

The dial panel: real CAN frames on vcan0, read through `--input can:vcan0:MAP`. The frames
and the joint values they must give are worked out here from the map (tests/input/can/
panel.map: the field's bits, factor and offset) and the bindings (tools/panel.bindings: the
dial's gain, the button's command), as tests/system/test_dials.py works them out for
`input valuator` lines. The guest's map is panel.map with stale=0 on every line: the guest
sends a frame only when a dial moves, where the panel sends one every few milliseconds.

The keyboard: a uinput keyboard types at the edit line and is destroyed mid-edit with Shift
held; a second one, hot-plugged (`--hotplug kernel`: the guest has no udevd), types on.

postured drags OSMesa and LLVM along (about 200 MB of libraries, placed twice in the
initramfs): the guest gets 2048 MiB.
"""
import math
import re
import shlex

from tier import BUILD, ROOT, assert_checks, require_built, require_tier, run_program

PANEL_MAP = ROOT / "tests" / "input" / "can" / "panel.map"
BINDINGS = ROOT / "tools" / "panel.bindings"
POSTURED = BUILD / "bin" / "postured"
MEMORY = 2048
DIAL, BUTTON = "Dials.Dial2", "Dials.Foot"
BTN_TRIGGER_HAPPY1 = 0x2C0  # a map's first button line's code (devices/can_map.h)
# the dial's physical values (the map's units): a reference, then two turns
REF, TURN1, TURN2 = 10.0, 15.0, 55.0
# xkb-data and the compose tables: the kiosk's keyboard layout (src/interact/kbd_text.c)
KEYBOARD_DATA = ["/usr/share/X11/xkb:/usr/share/X11/xkb",
                 "/usr/share/X11/locale:/usr/share/X11/locale"]
# with POSTURE_BUILD=build/san the daemon's exit status counts leaks: OSMesa's are not ours
SANITIZER = ["%s:/guest/lsan.supp" % (ROOT / "tests" / "lsan.supp")]
SANITIZER_ENV = ["ASAN_OPTIONS=detect_leaks=1", "UBSAN_OPTIONS=print_stacktrace=1",
                 "LSAN_OPTIONS=suppressions=/guest/lsan.supp"]
ANGLE = {"deg": math.pi / 180, "rad": 1.0, "": 1.0}


def map_lines():
    """panel.map's lines: [(kind, id, field, name, {option: value})]"""
    out = []
    for line in PANEL_MAP.read_text().splitlines():
        words = line.split("#")[0].split()
        if words:
            opts = dict(w.split("=", 1) for w in words[4:])
            out.append((words[0], words[1], words[2], words[3], opts))
    return out


def write_guest_map(path):
    """panel.map with stale=0 on every line"""
    text = []
    for kind, cid, field, name, opts in map_lines():
        opts = dict(opts, stale="0")
        text.append(" ".join([kind, cid, field, name] + ["%s=%s" % kv for kv in opts.items()]))
    path.write_text("\n".join(text) + "\n")


def intel_field(field):
    """S|L@1+ or S|L@1-: (start bit, length, signed); the panel's dial and button are Intel"""
    m = re.fullmatch(r"(\d+)\|(\d+)@1([+-])", field)
    assert m, "not an Intel field: " + field
    return int(m.group(1)), int(m.group(2)), m.group(3) == "-"


def put(data, field, raw):
    """data (an int holding the frame's 8 bytes, little-endian) with raw in field"""
    start, length, signed = intel_field(field)
    lo, hi = (-(1 << (length - 1)), (1 << (length - 1)) - 1) if signed else (0, (1 << length) - 1)
    assert lo <= raw <= hi, (field, raw)
    mask = ((1 << length) - 1) << start
    return (data & ~mask) | ((raw & ((1 << length) - 1)) << start)


def binding(kind, name):
    """the words of tools/panel.bindings' line binding dial or button name"""
    for line in BINDINGS.read_text().splitlines():
        words = shlex.split(line.split("#")[0]) if not line.lstrip().startswith("#") else []
        if words[:2] == [kind, name]:
            return words
    raise AssertionError("%s %s is not bound in %s" % (kind, name, BINDINGS))


def gain_radians(words):
    """a dial binding's gain= in radians (bare: radians)"""
    for w in words:
        if w.startswith("gain="):
            m = re.fullmatch(r"([-+0-9.e]+)(deg|rad|)", w[5:])
            return float(m.group(1)) * ANGLE[m.group(2)]
    return 1.0


def panel_plan():
    """the frame's id, its data at REF, TURN1, TURN2 and TURN2 with the foot button pressed
    (hex), and the elbow's values after the two turns"""
    lines = {name: (kind, cid, field, opts) for kind, cid, field, name, opts in map_lines()}
    kind, cid, field, opts = lines[DIAL]
    assert kind == "axis" and lines[BUTTON][1] == cid, "the dial and the button share a frame"
    factor, offset = float(opts.get("factor", 1)), float(opts.get("offset", 0))
    dlc = int(opts.get("dlc", 8))
    # raw counts that decode to the physical values exactly (0.01 steps)
    raws = [round((v - offset) / factor) for v in (REF, TURN1, TURN2)]
    phys = [r * factor + offset for r in raws]
    frames = [put(0, field, r) for r in raws]
    press = put(frames[2], lines[BUTTON][2], 1)
    # the button is the map's first: BTN_TRIGGER_HAPPY1, bound to undo
    buttons = [n for n, (k, *_) in lines.items() if k == "button"]
    assert buttons[0] == BUTTON and binding("button", "BTN_TRIGGER_HAPPY1")[2] == "undo"
    words = binding("dial", DIAL)
    assert words[2:4] == ["dof", "0"], words
    g = gain_radians(words)
    want1 = g * (phys[1] - phys[0])
    want2 = want1 + g * (phys[2] - phys[1])
    hexes = [f.to_bytes(dlc, "little").hex() for f in frames + [press]]
    return [cid] + hexes + ["%.17g" % want1, "%.17g" % want2]


def test_the_dial_panel_on_vcan0_drives_the_daemon(tmp_path):
    require_tier()
    require_built("guest_kiosk")
    write_guest_map(tmp_path / "panel.map")
    plan = panel_plan()
    status, lines = run_program(
        "guest_kiosk", ["vcan", "can_raw"],
        ["can", "/usr/local/bin/postured", "/guest/panel.map", "/guest/panel.bindings", *plan],
        files=["%s:/guest/panel.map" % (tmp_path / "panel.map"),
               "%s:/guest/panel.bindings" % BINDINGS, *KEYBOARD_DATA, *SANITIZER],
        exes=[POSTURED], timeout=240, memory=MEMORY, env=SANITIZER_ENV)
    assert_checks(status, lines, [
        "vcan0 made", "list devices shows the panel on vcan0 (can backend)",
        "the dial turns the picked joint by the binding's gain",
        "a turning dial is a step under way", "a second turn adds up",
        "a client's undo while the dials turn is refused busy",
        "a client's change to the turned figure waits too (busy)",
        "the dials still for 0.5 s end the step: one undo step", "undo returns the joint",
        "the panel button runs its command (undo)",
        "vcan0 down then up: the daemon runs on, the panel still listed",
        "after up the dial turns the joint again", "postured stops cleanly on SIGTERM"])
    # the daemon's own lines (its stderr shares the console): opened, down, up, once each
    out = "\n".join(lines)
    for said in ("postured: input 0: vcan0 (CAN panel (panel.map), can)",
                 "posture: panel (vcan0): device fault: interface vcan0 went down: ",
                 "posture: panel (vcan0): device fault: frames again on vcan0"):
        assert out.count(said) == 1, said


def test_a_keyboard_unplugged_mid_edit_loses_only_the_typed_line():
    require_tier()
    require_built("guest_kiosk")
    status, lines = run_program(
        "guest_kiosk", ["uinput"], ["keyboard", "/usr/local/bin/postured"],
        files=KEYBOARD_DATA + SANITIZER,
        exes=[POSTURED], timeout=240, memory=MEMORY, env=SANITIZER_ENV)
    assert_checks(status, lines, [
        "list devices shows the uinput keyboard (evdev backend)",
        "a command typed on the keyboard runs (load human)",
        "the edit line holds the typed text, Shift on its last letter",
        "the daemon saw the keyboard go (a removed event)",
        "the held Shift released as an event when it went",
        "the daemon runs on after the unplug", "the typed line is gone",
        "the environment is unchanged (figures, postures, constraints, undo)",
        "a new keyboard plugged in is opened (hot-plug, kernel uevents)",
        "it types lower case: no Shift stuck",
        "the history is kept (Up recalls the command typed before)",
        "it types a command that runs (load human as kid)",
        "postured stops cleanly on SIGTERM"])
    # stopped across the unplug, the daemon could not read the kernel's own release of
    # Shift: the one release came from the backend (devices/evdev_dev.c)
    out = "\n".join(lines)
    assert re.search(r"posture: posture kiosk keyboard 1 \(event\d+\): device fault: gone "
                     r"\(No such device\); 1 key\(s\) and button\(s\) released", out), out
