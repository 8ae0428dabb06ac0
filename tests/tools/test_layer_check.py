"""tools/layer-check: the tree passes, and each kind of fault planted in a copy of it fails.

Every plant is a change a careless edit could make; the check must name the
file, the line and what reaches where.
"""
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CHECK = ROOT / "tools" / "layer-check"


def run(root):
    return subprocess.run([sys.executable, str(CHECK), "--root", str(root)],
                          capture_output=True, text=True)


@pytest.fixture
def tree(tmp_path):
    """a copy of the checked folders, to plant faults in"""
    for d in ("src", "devices", "proto"):
        shutil.copytree(ROOT / d, tmp_path / d)
    return tmp_path


def plant(path, text, after=None):
    """appends text to path, or inserts it after the first line containing `after`"""
    body = path.read_text() if path.exists() else ""
    if after is None:
        body += text
    else:
        i = body.index(after)
        j = body.index("\n", i) + 1
        body = body[:j] + text + body[j:]
    path.write_text(body)


def line_of(path, text):
    return path.read_text().split("\n").index(text) + 1


def test_the_tree_keeps_its_layers():
    r = run(ROOT)
    assert r.returncode == 0, r.stderr
    assert "every include points down, no cycle" in r.stdout


def test_the_copy_passes_before_anything_is_planted(tree):
    assert run(tree).returncode == 0


def test_upward_include_fails_naming_file_line_and_include(tree):
    f = tree / "src/figure/model.c"
    plant(f, '#include "daemon/loop.h"\n', after='#include "figure/model.h"')
    r = run(tree)
    assert r.returncode == 1
    n = line_of(f, '#include "daemon/loop.h"')
    assert ('src/figure/model.c:%d: #include "daemon/loop.h" reaches src/daemon/ from src/figure/ '
            "(a higher layer)" % n) in r.stderr


def test_each_layer_may_not_reach_the_one_above(tree):
    pairs = [("src/pose/ik.c", "draw/view.h"), ("src/draw/view.c", "interact/x.h"),
             ("src/interact/manip.c", "daemon/cmd.h")]
    (tree / "src/interact/x.h").write_text("/* x */\n")
    for f, inc in pairs:
        plant(tree / f, '#include "%s"\n' % inc)
    r = run(tree)
    assert r.returncode == 1
    for f, inc in pairs:
        assert '%s:' % f in r.stderr and '#include "%s"' % inc in r.stderr


def test_include_without_its_folder_fails(tree):
    plant(tree / "src/figure/kin.c", '#include "model.h"\n')
    r = run(tree)
    assert r.returncode == 1
    assert '#include "model.h" does not name its folder (write "figure/...")' in r.stderr


def test_devices_know_nothing_of_figures(tree):
    (tree / "devices/evdev.c").write_text('#include "figure/model.h"\n')
    r = run(tree)
    assert r.returncode == 1
    assert ('devices/evdev.c:1: #include "figure/model.h" reaches src/figure/ from devices/ '
            "(a folder beside it)") in r.stderr


def test_a_call_cycle_between_modules_fails_naming_the_ties(tree):
    p = tree / "src/pose"
    (p / "ping.h").write_text("int ping(int n);\n")
    (p / "pong.h").write_text("int pong(int n);\n")
    (p / "ping.c").write_text('#include "pose/ping.h"\n#include "pose/pong.h"\n\n'
                              "int\nping(int n)\n{\n\treturn n ? pong(n - 1) : 0;\n}\n")
    (p / "pong.c").write_text('#include "pose/pong.h"\n#include "pose/ping.h"\n\n'
                              "int\npong(int n)\n{\n\treturn n ? ping(n - 1) : 1;\n}\n")
    r = run(tree)
    assert r.returncode == 1
    assert "module cycle: src/pose/ping -> src/pose/pong -> src/pose/ping" in r.stderr
    assert "src/pose/pong.c uses ping (src/pose/ping.c)" in r.stderr


def test_the_old_state_kin_cycle_would_be_caught(tree):
    f = tree / "src/figure/state.c"
    plant(f, '#include "figure/kin.h"\n', after='#include "figure/state.h"')
    plant(f, "\nvoid state_refresh(const struct model *m, struct state *s);\n"
             "void\nstate_refresh(const struct model *m, struct state *s)\n{\n"
             "\tkin_update(m, s);\n}\n")
    r = run(tree)
    assert r.returncode == 1
    assert "module cycle: src/figure/kin -> src/figure/state -> src/figure/kin" in r.stderr
    assert "src/figure/state.c uses kin_update (src/figure/kin.c)" in r.stderr


def test_names_in_comments_and_strings_are_not_uses(tree):
    plant(tree / "src/figure/model.c",
          '/* ik_solve and kin_update are named here only */\nstatic const char *why = "ik_solve";\n')
    assert run(tree).returncode == 0


def test_gl_belongs_to_the_renderer(tree):
    f = tree / "src/draw/view.c"
    plant(f, "#include <GL/gl.h>\n")
    r = run(tree)
    assert r.returncode == 1
    assert "src/draw/view.c:%d: #include <GL/gl.h> belongs to the renderer alone" \
        % line_of(f, "#include <GL/gl.h>") in r.stderr


def test_missing_header_fails(tree):
    plant(tree / "src/pose/balance.c", '#include "pose/nothing.h"\n')
    r = run(tree)
    assert r.returncode == 1
    assert '#include "pose/nothing.h": no such file src/pose/nothing.h' in r.stderr
