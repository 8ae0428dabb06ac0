#!/usr/bin/env python3
"""survey.py - which of opendbc's DBC files cantools reads as they are, why not, and
whether tools/dbc2panel's repairs make each readable.

    .venv/bin/python tests/input/can/opendbc/survey.py [--tsv]

The files: every dbc/*.dbc, and every *_generated.dbc that opendbc's own generator
(dbc/generator/generator.py, run here into a temporary folder) makes from this revision.
For each: whether cantools (strict=False, as dbc2panel loads) reads the file as cantools
reads files (load_file); the repairs dbc2panel makes, by kind (dbc2panel's DEFECTS); of
those, the kinds cantools refuses: each kind without whose repair (all others made)
cantools still refuses the file, or, where no one kind is needed so, the kinds whose
repair alone makes it readable (a|b: either); and whether cantools reads the repaired
text and dbc2panel writes a map. tests/tools/test_dbc2panel_opendbc.py checks survey.txt
is what this prints.
"""

import collections
import glob
import importlib.machinery
import importlib.util
import io
import os
import subprocess
import sys
import tempfile

import cantools

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(HERE))))
DBC_DIR = os.path.join(HERE, "dbc")
DBC2PANEL = os.path.join(ROOT, "tools", "dbc2panel")
REVISION = "7343a66d46213d5f73528afc6c6db713ebd88a9d"


def load_dbc2panel():
    loader = importlib.machinery.SourceFileLoader("dbc2panel", DBC2PANEL)
    spec = importlib.util.spec_from_loader("dbc2panel", loader)
    mod = importlib.util.module_from_spec(spec)
    loader.exec_module(mod)
    return mod


def generate(dest):
    """opendbc's generated DBC files, made by its generator from this copy, into dest.
    Its scripts import themselves as opendbc.dbc.generator.*: a package folder that
    holds this dbc/ gives them that name."""
    pkg = os.path.join(dest, "pkg", "opendbc")
    os.makedirs(pkg)
    os.symlink(DBC_DIR, os.path.join(pkg, "dbc"))
    out = os.path.join(dest, "generated")
    os.makedirs(out)
    code = ("import sys; sys.path.insert(0, sys.argv[1])\n"
            "from opendbc.dbc.generator.generator import create_all\n"
            "create_all(sys.argv[2])\n")
    subprocess.run([sys.executable, "-B", "-c", code, os.path.join(dest, "pkg"), out],
                   check=True)
    return sorted(glob.glob(os.path.join(out, "*_generated.dbc")))


def dbc_files(dest):
    """(name, path) of every DBC the survey covers, the generated ones made into dest"""
    return ([(os.path.basename(p), p) for p in sorted(glob.glob(os.path.join(DBC_DIR, "*.dbc")))] +
            [(os.path.basename(p), p) for p in generate(dest)])


def cantools_reads(text, keep=None):
    """None when cantools reads the text (the database into keep, a list, if given), else
    the first line of its complaint"""
    try:
        db = cantools.database.load_string(text, "dbc", strict=False)
    except Exception as e:  # cantools raises several kinds
        return str(e).splitlines()[0]
    if keep is not None:
        keep.append(db)
    return None


def repaired(mod, text, skip=(), only=None):
    """the text with the repairs of every kind but skip (or only those of only)"""
    kinds = set(mod.DEFECTS) - set(skip) if only is None else {only}
    return mod.repair(text, lambda *a: None, {}, mod.Repairs(set(mod.DEFECTS) - kinds))


def survey_file(mod, path):
    """what the survey says of one file: a dict (with the databases cantools read from
    the file as it is and as repaired, None where it refused, and dbc2panel's map)"""
    try:
        db_as_is = cantools.database.load_file(path, database_format="dbc", strict=False)
        as_is = None
    except Exception as e:  # cantools raises several kinds
        db_as_is, as_is = None, str(e).splitlines()[0]
    text = mod.read_dbc(path)
    r = mod.Repairs()
    keep = []
    after = cantools_reads(mod.repair(text, lambda *a: None, {}, r), keep)
    made = collections.Counter(kind for _, kind, _ in r.made)
    # the kinds cantools refuses: those whose repair the file cannot do without; where
    # no one kind is needed, those that alone make it readable (a|b: either)
    refused_for = []
    if as_is:
        refused_for = [k for k in made if cantools_reads(repaired(mod, text, skip={k}))]
        if not refused_for:
            refused_for = ["|".join(k for k in made
                                    if not cantools_reads(repaired(mod, text, only=k)))]
    try:
        the_map = mod.make_map(path, None, lambda *a: None)
    except mod.Refused:
        the_map = None
    return {"as_is": as_is, "made": made, "refused_for": refused_for, "after": after,
            "mapped": the_map is not None, "map": the_map, "db_as_is": db_as_is,
            "db_repaired": keep[0] if keep else None}


def report(results, out):
    """the survey's text: one line a file, then the counts"""
    defects = load_dbc2panel().DEFECTS
    order = list(defects)
    print(f"# opendbc {REVISION[:12]}'s DBC files and cantools {cantools.__version__}: "
          "read as is, the repairs dbc2panel makes,", file=out)
    print("# those cantools refuses (each left out in turn, cantools refuses the file), "
          "and read after repair", file=out)
    print("# file\tas-is\trefused-for\trepairs\tafter", file=out)
    for name, res in results:
        made = ",".join(f"{k}={res['made'][k]}" for k in order if k in res["made"]) or "-"
        after = "read" if res["after"] is None and res["mapped"] else "REFUSED"
        why = ",".join(sorted(res["refused_for"], key=lambda k: order.index(k.split("|")[0])))
        print(f"{name}\t{'refused' if res['as_is'] else 'read'}\t{why or '-'}\t{made}\t{after}",
              file=out)
    refused = [(n, r) for n, r in results if r["as_is"]]
    generated = sum(1 for n, _ in results if n.endswith("_generated.dbc"))
    print(f"\nfiles: {len(results)} ({len(results) - generated} in dbc/, {generated} generated)",
          file=out)
    print(f"refused by cantools as they are: {len(refused)}", file=out)
    for kind in order:
        n = sum(1 for _, r in refused if kind in r["refused_for"])
        if n:
            print(f"  for {kind} ({defects[kind]}): {n}", file=out)
    for either in sorted({k for _, r in refused for k in r["refused_for"] if "|" in k}):
        n = sum(1 for _, r in refused if either in r["refused_for"])
        print(f"  for {either} (either repair alone makes it readable): {n}", file=out)
    def converts(rs):
        return sum(1 for _, r in rs if r["after"] is None and r["mapped"])
    print(f"read after repair, with a map written: {converts(refused)} of the {len(refused)} "
          f"refused; {converts(results)} of all {len(results)}", file=out)
    for kind in order:
        n = sum(1 for _, r in results if kind in r["made"])
        if n:
            print(f"repaired, {kind}: in {n} files, "
                  f"{sum(r['made'][kind] for _, r in results)} times", file=out)


def survey():
    """[(name, result)] for every file"""
    mod = load_dbc2panel()
    with tempfile.TemporaryDirectory() as tmp:
        return [(name, survey_file(mod, path)) for name, path in dbc_files(tmp)]


def main():
    out = io.StringIO()
    report(survey(), out)
    sys.stdout.write(out.getvalue())


if __name__ == "__main__":
    main()
