"""The README and docs/ as a newcomer reads them: true to the product today.

- The README's picture, docs/kiosk.png, is what `make run` shows: tools/readme-picture
  draws it (the daemon started as the Makefile's `run` target starts it, the menu opened
  by a right click on the background); a test draws it again and compares.
- Every protocol command the pages show exists (the daemon's `help`), their ```posture
  blocks run on a `make run` daemon, and the programs, make targets, files and links they
  name exist; the dependencies page names every dependency; the layout page every module;
  no page names an issue number.
"""
import importlib.machinery
import importlib.util
import os
import re
import shlex
import subprocess

import numpy as np
import pytest

from conftest import BUILD, ROOT
from daemon import daemon, daemon_factory  # noqa: F401 (fixtures)
from posture import Client
from posture.replay import read_png

PICTURE = ROOT / "docs" / "kiosk.png"
# the status line's frame count, frame rate and times differ from run to run: the last
# band (VIEW_LINE_PX rows) is compared only over the view's name at its left
STATUS_ROWS, NAME_COLUMNS = 20, 48
# On this machine two drawings are the same to the bit outside those numbers. A channel
# off by more than 24 counts in more than 200 pixels is another picture: the right elbow
# turned 5 degrees changes 857 such pixels, the message line's "right" written "left"
# 773, the pointer 10 pixels to the right 34 000; the margin is for the few edge pixels
# another CPU's llvmpipe may draw otherwise.
COUNTS, PIXELS = 24, 200


def pixels(path):
    w, h, ch, data = read_png(path)
    return np.frombuffer(data, np.uint8).reshape(h, w, ch)[:, :, :3].astype(int)


def differing_pixels(a, b):
    """pixels with a channel off by more than COUNTS, the status line's numbers left out"""
    off = np.abs(a - b).max(axis=2) > COUNTS
    off[-STATUS_ROWS:, NAME_COLUMNS:] = False
    return int(off.sum())


def test_the_readme_picture_is_what_make_run_shows_now():
    out = BUILD / "test-output" / "readme" / "kiosk.png"
    env = dict(os.environ, POSTURE_BUILD=str(BUILD))
    p = subprocess.run([str(ROOT / "tools" / "readme-picture"), "--out", str(out)], env=env,
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stdout + p.stderr
    new, committed = pixels(out), pixels(PICTURE)
    how = (f"run tools/readme-picture to draw docs/kiosk.png again, look at it, and commit "
           f"it (this run's picture: {out})")
    assert new.shape == committed.shape, f"docs/kiosk.png is {committed.shape}, the daemon " \
        f"draws {new.shape}: {how}"
    n = differing_pixels(new, committed)
    assert n <= PIXELS, f"docs/kiosk.png is not what the daemon draws now ({n} pixels " \
        f"differ): {how}"


# ---- every command, program and file the README and docs/ show exists ----------------------
#
# Code blocks marked ```posture hold protocol lines (as typed in posturectl or at the kiosk);
# ```sh blocks hold shell commands. Both are checked, in README.md and every docs/ page.

PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))
FENCE = re.compile(r"^```(\w*)\n(.*?)^```", re.S | re.M)
# a word naming a file of the tree
TREE = ("src/", "devices/", "tools/", "tests/", "proto/", "docs/", "debian/", ".ci/")


def rel(page):
    return page.relative_to(ROOT)


def blocks(page, kind):
    """the code blocks of a page marked with kind ('posture', 'sh', '' for unmarked)"""
    return [body for k, body in FENCE.findall(page.read_text()) if k == kind]


def protocol_lines(page):
    """(line, where) of every protocol command a page shows: its ```posture lines, and
    the commands given to posturectl in its ```sh lines"""
    out = []
    for body in blocks(page, "posture"):
        for line in body.splitlines():
            if line.strip() and not line.strip().startswith("%"):
                out.append((line.strip(), f"{rel(page)}: {line.strip()}"))
    for body in blocks(page, "sh"):
        for cmd in shell_commands(body):
            if cmd and cmd[0].endswith("posturectl"):
                words, i = [], 1
                while i < len(cmd):
                    if cmd[i] in ("--socket", "--tcp", "--token", "--timeout", "-f", "--file"):
                        i += 2
                        words = None if cmd[i - 2] in ("-f", "--file") else words
                        continue
                    if cmd[i].startswith("-"):
                        words = None if cmd[i] == "--watch" else words
                        i += 1
                        continue
                    if words is not None:
                        words.append(cmd[i])
                    i += 1
                if words:
                    out.append((" ".join(words), f"{rel(page)}: {' '.join(cmd)}"))
    return out


def shell_commands(body):
    """the simple commands of a ```sh block, as word lists: continuations joined, comments
    dropped, split at && || | ;, leading VAR=value words and sudo dropped"""
    text = re.sub(r"\\\n", " ", body)
    out = []
    for line in text.splitlines():
        try:
            words = shlex.split(line, comments=True)
        except ValueError:  # an unbalanced quote inside a quoted program (python3 -c ...)
            words = line.split()
        cmd = []
        for w in words + [";"]:
            if w in ("&&", "||", "|", ";"):
                while cmd and (re.match(r"^[A-Z_]+=", cmd[0]) or cmd[0] == "sudo"):
                    cmd.pop(0)
                if cmd:
                    out.append(cmd)
                cmd = []
            else:
                cmd.append(w)
    return out


def usages(client):
    """(literal words, usage) of every command of the daemon's `help`"""
    out = []
    for entry in client.request("help")["commands"]:
        verb = entry["usage"].split()[0]  # "layout VIEW... | layout off": two forms
        for alt in re.split(r" \| (?=" + re.escape(verb) + " )", entry["usage"]):
            lead = []
            for w in alt.split():
                if not re.fullmatch(r"[a-z_]+", w):
                    break
                lead.append(w)
            assert lead, f"a usage that starts with no word: {entry['usage']}"
            out.append((lead, entry["usage"]))
    return out


def ansur2_measures():
    """the measured dimensions of ANSUR II (its CSV header's lowercase columns), which
    `load human` takes as MEASURE=MM"""
    path = ROOT / "data" / "ansur2" / "ANSUR_II_MALE_Public.csv"
    header = path.read_text(encoding="latin-1").splitlines()[0].split(",")
    return {c for c in header if c == c.lower()}


def unknown(line, known):
    """why a protocol line is not a command the daemon knows, or None"""
    words = line.split()
    match = max((u for u in known if words[:len(u[0])] == u[0]), key=lambda u: len(u[0]),
                default=None)
    if match is None:
        return "no such command"
    lead, usage = match
    for w in words[len(lead):]:
        key = w.split("=", 1)[0]
        if "=" not in w or re.search(r"(?<![\w])" + re.escape(key) + r"(?=[=|])", usage):
            continue
        if "MEASURE=" in usage and key in ansur2_measures():
            continue
        return f"'{key}=' is not in its usage, {usage}"
    return None


def test_every_protocol_command_the_readme_and_docs_show_exists(daemon):
    lines = [x for page in PAGES for x in protocol_lines(page)]
    assert len(lines) > 40, "the pages show hardly any commands: is the parsing broken?"
    with daemon.client() as c:
        known = usages(c)
    bad = [f"{where}: {why}" for line, where in lines if (why := unknown(line, known))]
    assert not bad, "commands the daemon's `help` does not know:\n" + "\n".join(bad)


def load_readme_picture():
    loader = importlib.machinery.SourceFileLoader("readme_picture",
                                                  str(ROOT / "tools" / "readme-picture"))
    spec = importlib.util.spec_from_loader("readme_picture", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


@pytest.mark.parametrize("page", [p for p in PAGES if blocks(p, "posture")],
                         ids=lambda p: str(rel(p)))
def test_the_posture_blocks_of_a_page_run_on_make_runs_daemon(page):
    """each page's ```posture lines, in order, on a fresh daemon started as `make run`
    starts it: every reply ok; the README's replay of its tour replays without divergence"""
    make_run = load_readme_picture().make_run_daemon
    lines = [line for body in blocks(page, "posture") for line in body.splitlines()]
    with make_run(BUILD / "bin" / "postured") as (sock, state):
        with Client(socket_path=str(sock), timeout=120) as c:
            for line in lines:
                if line.strip() and not line.strip().startswith("%"):
                    reply = c.request_reply(line)
                    assert reply["ok"], f"{rel(page)}: {line}: {reply}"
        for cmd in (cmd for body in blocks(page, "sh") for cmd in shell_commands(body)):
            if cmd[0] == "build/rel/bin/postured" and "--replay" in cmd:
                rec = cmd[cmd.index("--replay") + 1].replace("build/run/state", str(state))
                p = subprocess.run([str(BUILD / "bin" / "postured"), "--replay", rec],
                                   capture_output=True, text=True, timeout=120)
                last = p.stdout.strip().splitlines()[-1:] or [""]
                assert p.returncode == 0 and last[0].endswith(" divergences=0"), \
                    f"{rel(page)}: {' '.join(cmd)}: {p.stdout}{p.stderr}"


# ---- programs, make targets and files --------------------------------------------------

def make_targets():
    return set(re.findall(r"^([\w.-]+):", (ROOT / "Makefile").read_text(), re.M))


def buildable(path):
    """a build/ path the Makefile makes: a program, a test, a benchmark or a fuzz harness"""
    f = re.fullmatch(r"build/fuzz/bin/(fuzz_\w+)", path)
    if f:
        return (ROOT / "tests" / "fuzz" / f"{f[1]}.c").exists()
    m = re.fullmatch(r"build/(rel|san)/(bin|tests|bench)/([\w-]+)", path)
    if not m:
        return False
    kind, name = m[2], m[3]
    if kind == "bin":
        return name == "postured" or (ROOT / "tools" / f"{name}.c").exists()
    if kind == "tests":
        return (ROOT / "tests" / f"{name}.c").exists()
    return any((ROOT / "tools" / "bench" / f"{name}{e}").exists() for e in (".c", ".cpp"))


def tree_path_exists(word):
    """a word naming files of the tree: a path, a glob, model.[ch], or one with a
    placeholder in capitals (fuzz_NAME.c)"""
    word = word.rstrip(".,;:)")
    if (ROOT / word).exists():
        return True
    pattern = re.sub(r"\[ch\]$", "[ch]", word)
    pattern = re.sub(r"[A-Z]{2,}", "*", pattern)
    return bool(list(ROOT.glob(pattern)))


def program_problem(cmd, targets):
    prog = cmd[0]
    if prog == "make":
        for t in cmd[1:]:
            if t.startswith("-") or "=" in t:
                continue
            if t not in targets and not buildable(t):
                return f"make {t}: no such target"
        return None
    if prog.startswith("build/"):
        return None if buildable(prog) else f"{prog}: nothing builds it"
    if prog.startswith("tools/") or prog.startswith(".ci/"):
        p = ROOT / prog
        return None if p.is_file() and os.access(p, os.X_OK) else f"{prog}: no such program"
    if re.fullmatch(r"posture[\w-]*", prog):
        ok = prog == "postured" or (ROOT / "tools" / prog).exists() or \
            (ROOT / "tools" / f"{prog}.c").exists()
        return None if ok else f"{prog}: no such program"
    return None  # other people's programs: apt-get, python3, blender ...


def test_every_program_make_target_and_file_the_pages_name_exists():
    targets = make_targets()
    bad = []
    for page in PAGES:
        text = page.read_text()
        for body in blocks(page, "sh"):
            for cmd in shell_commands(body):
                why = program_problem(cmd, targets)
                if why:
                    bad.append(f"{rel(page)}: {' '.join(cmd)}: {why}")
        # every word naming a file of the tree, in code spans and blocks
        code = " ".join(re.findall(r"`([^`\n]+)`", text) + [b for _, b in FENCE.findall(text)])
        for word in re.findall(r"(?<![\w/.$=-])(?:" + "|".join(map(re.escape, TREE))
                               + r")[\w./*\[\]-]*", code):
            if not tree_path_exists(word):
                bad.append(f"{rel(page)}: {word}: no such file")
        # and every link to another page or file
        for link in re.findall(r"\]\(([^)#:]+)(?:#[^)]*)?\)", text):
            if not (page.parent / link).exists():
                bad.append(f"{rel(page)}: link {link}: no such file")
    assert not bad, "\n".join(bad)


def test_the_readme_shows_the_two_commands_and_stays_a_front_page():
    text = (ROOT / "README.md").read_text()
    assert len(text.splitlines()) <= 400
    shell = [cmd for body in blocks(ROOT / "README.md", "sh") for cmd in shell_commands(body)]
    assert ["make", "run"] in shell and ["make", "test"] in shell
    assert "](docs/kiosk.png)" in text


def test_no_page_names_an_issue_number():
    texts = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")),
             *sorted((ROOT / "tools").glob("*.[18]")), *sorted(ROOT.glob("*/README.md")),
             *sorted(ROOT.glob("*/*/README.md"))]
    bad = [f"{rel(p)}:{i}: {line.strip()}" for p in texts
           for i, line in enumerate(p.read_text().splitlines(), 1)
           if re.search(r"\bissues?\s*#?\d", line, re.I)]
    assert not bad, "the product's text is no log of the work:\n" + "\n".join(bad)


def test_every_dependency_is_on_the_dependencies_page():
    make = (ROOT / "Makefile").read_text().replace("\\\n", " ")
    debian = []
    for var in ("DEB_PKGS", "DEB_PKGS_LEAN"):
        debian += re.search(rf"^{var} := (.*)$", make, re.M)[1].split()
    python = [re.split(r"[<>=~ #]", line.strip(), maxsplit=1)[0]
              for line in (ROOT / "tests" / "requirements.txt").read_text().splitlines()
              if line.strip() and not line.startswith("#")]
    page = (ROOT / "docs" / "dependencies.md").read_text()
    missing = [p for p in debian + python + ["gltf-validator"]
               if not re.search(r"(?<![\w-])" + re.escape(p) + r"(?![\w-])", page)]
    assert len(debian) > 20 and len(python) > 10
    assert not missing, f"docs/dependencies.md does not say why we need: {missing}"


def test_the_layout_page_names_every_module_and_only_files_that_exist():
    text = (ROOT / "docs" / "layout.md").read_text()
    named, bad, folder = set(), [], None
    for body in blocks(ROOT / "docs" / "layout.md", "")[1:]:  # the layers' insides
        for line in body.splitlines():
            m = re.match(r"^(src/\w+/|devices/)\s", line)
            folder = m[1] if m else folder
            for w in (x.strip("(),;:") for x in line.split()[1 if m else 0:]):
                if not re.fullmatch(r"[\w*]+(\.\[ch\]|\.c|\.cc|\.h|\.md)", w):
                    continue
                stem = w.split(".")[0]
                found = list((ROOT / folder).glob(w.replace("[ch]", "[ch]")))
                if not found or (w.endswith("[ch]") and len(found) != 2):
                    bad.append(f"{folder}{w}")
                named.update(folder + p.stem for p in found) if "*" in stem else \
                    named.add(folder + stem)
    modules = {f"{d}/{p.stem}" for d in ("src/figure", "src/pose", "src/assess", "src/draw",
                                          "src/export", "src/interact", "src/fit", "src/daemon",
                                          "devices")
               for p in (ROOT / d).glob("*.[ch]")} | \
        {f"src/fit/{p.stem}" for p in (ROOT / "src/fit").glob("*.cc")}
    assert "src/figure/" in text and not bad, f"docs/layout.md names files that are not: {bad}"
    assert not modules - named, \
        f"docs/layout.md does not name these modules: {sorted(modules - named)}"
