"""`export assessment FIG PATH [view=VIEW]`: a posture's RULA, REBA and OWAS as a one-page HTML
report.

- The file parses as well-formed HTML (Python's html.parser; every element closed in order) with
  the picture inlined as a PNG that decodes at the size the report says, the three methods'
  derivations, their scores equal to what `assess rula|reba|owas` replies (each part's score,
  each table look-up's indices and value), every threshold `set assess` knows with its source,
  the figure's measures, the date, the sources and what is not modelled.
- Text is escaped: the adjustments' reasons ("... > 10 deg") reach the page as text.
- A refused path (outside the state directory, through a symbolic link, not .html), a figure
  that is not a human, an unknown view: an error, and nothing written or changed.
"""
import base64
import datetime
import html.parser
import os
import re
import shutil
import struct
import zlib

import pytest

from daemon import ROOT, daemon, daemon_factory  # noqa: F401 (fixtures)

VOID = {"meta", "img", "br", "hr", "link", "input", "col", "area", "base", "wbr", "source"}


class Page(html.parser.HTMLParser):
    """The elements as a tree of (tag, attrs, children, text); raises on a tag closed out of
    order or left open."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.root = {"tag": None, "attrs": {}, "kids": [], "text": ""}
        self.stack = [self.root]
        self.doctype = None

    def handle_decl(self, decl):
        self.doctype = decl

    def handle_starttag(self, tag, attrs):
        node = {"tag": tag, "attrs": dict(attrs), "kids": [], "text": ""}
        self.stack[-1]["kids"].append(node)
        if tag not in VOID:
            self.stack.append(node)

    def handle_startendtag(self, tag, attrs):
        self.stack[-1]["kids"].append({"tag": tag, "attrs": dict(attrs), "kids": [], "text": ""})

    def handle_endtag(self, tag):
        assert tag not in VOID, f"</{tag}>"
        assert self.stack[-1]["tag"] == tag, f"</{tag}> closes <{self.stack[-1]['tag']}>"
        self.stack.pop()

    def handle_data(self, data):
        for node in self.stack:
            node["text"] += data


def parse(text):
    p = Page()
    p.feed(text)
    p.close()
    assert len(p.stack) == 1, f"left open: {[n['tag'] for n in p.stack[1:]]}"
    assert p.doctype and p.doctype.lower() == "doctype html"
    return p.root


def walk(node):
    yield node
    for k in node["kids"]:
        yield from walk(k)


def find(node, tag=None, **attrs):
    """the elements below node with that tag and those attributes (class matches one word)"""
    out = []
    for n in walk(node):
        if tag and n["tag"] != tag:
            continue
        ok = True
        for k, v in attrs.items():
            k = k.rstrip("_").replace("_", "-")
            have = n["attrs"].get(k)
            ok &= have is not None and (v in have.split() if k == "class" else have == v)
        if ok:
            out.append(n)
    return out


def one(node, tag=None, **attrs):
    got = find(node, tag, **attrs)
    assert len(got) == 1, (tag, attrs, len(got))
    return got[0]


def cells(row):
    return [n["text"] for n in row["kids"] if n["tag"] in ("td", "th")]


def figure_table(page):
    """the figure's table: heading and value cells in pairs"""
    out = {}
    for row in find(one(page, "table", id="figure"), "tr"):
        c = cells(row)
        out.update(zip(c[0::2], c[1::2]))
    return out


def png_size(data):
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    n, kind = struct.unpack(">I4s", data[8:16])
    assert kind == b"IHDR"
    w, h = struct.unpack(">II", data[16:24])
    # the whole stream decompresses: it is a PNG, not only its header
    pos, idat = 8, b""
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        assert zlib.crc32(kind + body) == struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])[0]
        if kind == b"IDAT":
            idat += body
        pos += 12 + n
    assert len(zlib.decompress(idat)) == h * (1 + 4 * w)
    return w, h


def pose(c):
    c.request("load human as jack stature=1.80 mass=80")
    # the right arm raised and out to the side, the trunk bent and turned, the head down
    c.request("set joint jack shoulder_r 110deg 50deg 0")
    c.request("set joint jack elbow_r 30deg")


def check_method(page, name, reply):
    sec = one(page, "section", id=name)
    assert int(sec["attrs"]["data-score"]) == reply["score"]
    assert int(sec["attrs"]["data-action-level"]) == reply["action_level"]
    rows = find(one(sec, "table", class_="parts"), "tr")
    parts = {r["attrs"]["data-part"]: cells(r) for r in rows if "data-part" in r["attrs"]}
    assert list(parts) == list(reply["parts"]), (name, list(parts))
    for part, got in parts.items():
        want = reply["parts"][part]
        assert got[0] == part
        assert got[4] == f"{want['score']} / {want['max']}", (name, part, got)
        assert got[2].startswith(f"{want['base']}: {want['band']}"), (name, part, got)
        for adj in want["adjust"]:
            assert adj["reason"] in got[3], (name, part, adj, got)
        if want["angle_name"] and want["angle"] is not None:
            angle = 0.0 if abs(want["angle"]) < 0.05 else want["angle"]  # no "-0.0"
            assert got[1] == f"{want['angle_name']} {angle:.1f}", (name, part, got)
    looks = [n for n in find(one(sec, "table", class_="lookups"), "td")]
    assert len(looks) == len(reply["lookups"])
    for cell, want in zip(looks, reply["lookups"]):
        assert cell["attrs"]["data-table"] == want["table"]
        assert int(cell["attrs"]["data-value"]) == want["value"]
        idx = ", ".join(f"{k} {v}" for k, v in want["idx"].items())
        assert cell["text"] == f"{want['table']} ({idx}) = {want['value']}", cell["text"]
    h2 = one(sec, "h2")["text"]
    assert f"score {reply['score']}" in h2
    assert reply["action"] in sec["text"]
    return sec


def test_the_report_holds_the_picture_the_derivations_the_inputs_and_the_sources(daemon):
    with daemon.client() as c:
        pose(c)
        replies = {m: c.request(f"assess {m} jack") for m in ("rula", "reba", "owas")}
        (daemon.state_dir / "reports").mkdir()
        got = c.request("export assessment jack reports/jack.html")
    assert got["path"] == "reports/jack.html"
    path = daemon.state_dir / "reports" / "jack.html"
    text = path.read_text(encoding="utf-8")
    page = parse(text)
    assert got["width"] == 480 and got["height"] == 600
    assert {m: got[m] for m in replies} == {m: r["score"] for m, r in replies.items()}
    # the picture: a PNG of the size its element says
    img = one(page, "img", id="picture")
    src = img["attrs"]["src"]
    assert src.startswith("data:image/png;base64,")
    assert png_size(base64.b64decode(src.split(",", 1)[1], validate=True)) == (480, 600)
    assert (int(img["attrs"]["width"]), int(img["attrs"]["height"])) == (480, 600)
    # the three methods, each as `assess` says it
    for m, r in replies.items():
        check_method(page, m, r)
    summary = {r["attrs"]["data-method"]: cells(r) for r in find(one(page, "table", id="summary"), "tr")
               if "data-method" in r["attrs"]}
    assert list(summary) == ["rula", "reba", "owas"]
    for m, r in replies.items():
        assert int(summary[m][1]) == r["score"] and summary[m][2].endswith(str(r["action_level"]))
        assert summary[m][4] == (r["worst"] or "")
    assert replies["owas"]["code"] in one(page, "section", id="owas")["text"]
    # the figure and its size
    fig = figure_table(page)
    assert fig["name"] == "jack" and fig["stature"] == "1.800 m" and fig["mass"] == "80.0 kg"
    # every threshold with a value and a source
    th = {p["attrs"]["data-key"]: p for p in find(one(page, id="thresholds"), "p")}
    assert {"upright", "shoulder_raised", "arm_abducted", "owas_back", "kneel_height"} <= set(th)
    assert all(len(one(p, "span", class_="source")["text"]) > 10 for p in th.values())
    assert one(th["shoulder_raised"], "span", class_="value")["text"] == "10 deg"
    inputs = {p["attrs"]["data-key"]: one(p, "span", class_="value")["text"]
              for p in find(one(page, id="inputs"), "p")}
    assert inputs["load"] == "0.00 kg" and inputs["side"] == "worse" and inputs["coupling"] == "good"
    # the date the daemon's calendar gave, today's (or yesterday's just past midnight)
    made = one(page, "p", id="made")["text"]
    date = re.search(r"(\d{4}-\d{2}-\d{2}) \d{2}:\d{2} UTC", made).group(1)
    today = datetime.datetime.now(datetime.timezone.utc).date()
    assert date in (str(today), str(today - datetime.timedelta(days=1)))
    # sources and what is not modelled
    sources = one(page, "section", id="sources")["text"]
    for cite in ("McAtamney", "Corlett", "Hignett", "Karhu", "Applied Ergonomics 24(2):91-99",
                 "31(2):201-205", "8(4):199-201"):
        assert cite in sources, cite
    assert len(find(one(page, "section", id="not-modelled"), "li")) >= 4
    assert "@page{size:A4" in text.replace(" ", "")
    assert not list(daemon.state_dir.glob("reports/*.part"))


def test_text_is_escaped(daemon):
    with daemon.client() as c:
        pose(c)
        c.request("export assessment jack r.html")
        reasons = [a["reason"] for p in c.request("assess rula jack")["parts"].values()
                   for a in p["adjust"]]
    text = (daemon.state_dir / "r.html").read_text()
    assert any(">" in r for r in reasons), reasons  # "abducted: 50.0 > 35 deg"
    for r in reasons:
        assert r.replace("&", "&amp;").replace(">", "&gt;").replace("<", "&lt;") in text, r
    # a source quoting the method: its quotes escaped
    assert "&#39;working across the midline&#39;" in text


def test_a_manikin_shows_its_measures_and_a_view_gives_its_camera_and_size(daemon):
    with daemon.client() as c:
        c.request("load human as ann sex=female sittingheight=880 weightkg=60")
        c.request("add view side width=320 height=400 eye=3,1.2,0 target=0,1,0")
        c.request("set view side tint=reba")
        got = c.request("export assessment ann ann.html view=side")
    assert (got["width"], got["height"]) == (320, 400)
    page = parse((daemon.state_dir / "ann.html").read_text())
    img = one(page, "img", id="picture")
    assert png_size(base64.b64decode(img["attrs"]["src"].split(",", 1)[1])) == (320, 400)
    fig = figure_table(page)
    assert fig["population"] == "ansur2" and fig["sex"] == "female"
    measures = one(page, "p", id="measures")["text"]
    assert "sittingheight 880.0 (given)" in measures and "weightkg 60.0 (given)" in measures


def listing(root):
    out = {}
    for dirpath, dirs, files in os.walk(root):
        for n in dirs + files:
            p = os.path.join(dirpath, n)
            st = os.lstat(p)
            out[os.path.relpath(p, root)] = (st.st_mode, st.st_size, st.st_mtime_ns,
                                             os.readlink(p) if os.path.islink(p) else None)
    return out


def test_refused_requests_write_nothing(daemon, tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    victim = outside / "victim.html"
    victim.write_text("keep me")
    (daemon.state_dir / "link.html").symlink_to(victim)
    (daemon.state_dir / "out").symlink_to(outside, target_is_directory=True)
    with daemon.client() as c:
        c.request("load human as jack")
        shutil.copy(ROOT / "src/figure/library/chair.fig", daemon.state_dir / "chair.fig")
        c.request("load figure chair.fig as chair")
        before = listing(daemon.state_dir)
        for line, code in (("export assessment jack ../x.html", "denied"),
                           (f"export assessment jack {tmp_path}/x.html", "denied"),
                           ("export assessment jack link.html", "denied"),
                           ("export assessment jack out/victim.html", "denied"),
                           ("export assessment jack jack.pdf", "bad-argument"),
                           ("export assessment jack .html", "bad-argument"),
                           ("export assessment jack j.html colour=red", "bad-argument"),
                           ("export assessment jack j.html view=nowhere", "not-found"),
                           ("export assessment nobody j.html", "not-found"),
                           ("export assessment chair j.html", "bad-argument"),
                           ("export assessment jack nodir/j.html", "not-found")):
            reply = c.request_reply(line)
            assert not reply["ok"] and reply["error"]["code"] == code, (line, reply)
            assert listing(daemon.state_dir) == before, line
    assert victim.read_text() == "keep me"
    assert sorted(p.name for p in outside.iterdir()) == ["victim.html"]
