"""evemu files against libevemu (evemu 2.7) and libevdev as independent readers and writers.

Small C programs are compiled at test time: one links libevemu (its reader,
evemu_read + evemu_read_event, and its writer, evemu_write +
evemu_write_event), one links our reader and writer (devices/rec_evemu.c),
one links libevdev for the names of types and codes. Checked:
- the committed references tests/input/evdev/NAME.ref are what libevemu's
  reader makes of NAME.evemu today;
- a file our writer wrote reads in libevemu's reader as the original did;
- our writer writes what libevemu's writer writes for the same file, line
  for line, apart from the comments naming the machine (# Kernel, # DMI);
- every type, code and property name we write is libevdev's, apart from
  codes newer than the libevdev installed (which has no name for them).
"""
import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "input" / "evdev"
FILES = ["mouse", "keyboard", "tablet", "tablet-v1.0"]
CC = shutil.which("cc")

pytestmark = pytest.mark.skipif(
    not CC or not Path("/usr/include/evemu.h").exists(), reason="needs cc and libevemu-dev")

# libevemu: rewrite a file with its writer, or dump what its reader makes of one
EVEMU_TOOL = r"""
#include <evemu.h>
#include <stdio.h>
#include <string.h>
int main(int argc, char **argv) {
	FILE *f = fopen(argv[2], "r");
	struct evemu_device *dev = evemu_new(NULL);
	if (!f || !dev || evemu_read(dev, f) <= 0) return 1;
	struct input_event ev;
	if (!strcmp(argv[1], "write")) {
		evemu_write(dev, stdout);
		while (evemu_read_event(f, &ev) > 0) evemu_write_event(stdout, &ev);
		return 0;
	}
	printf("N %s\n", evemu_get_name(dev));
	printf("I %u %u %u %u\n", evemu_get_id_bustype(dev), evemu_get_id_vendor(dev),
	       evemu_get_id_product(dev), evemu_get_id_version(dev));
	for (int p = 0; p <= INPUT_PROP_MAX; p++)
		if (evemu_has_prop(dev, p)) printf("P %d\n", p);
	for (int t = 1; t <= EV_MAX; t++)
		for (int c = 0; c <= KEY_MAX; c++)
			if (evemu_has_event(dev, t, c)) printf("B %d %d\n", t, c);
	for (int c = 0; c <= ABS_MAX; c++)
		if (evemu_has_event(dev, EV_ABS, c))
			printf("A %d %d %d %d %d %d\n", c, evemu_get_abs_minimum(dev, c),
			       evemu_get_abs_maximum(dev, c), evemu_get_abs_fuzz(dev, c),
			       evemu_get_abs_flat(dev, c), evemu_get_abs_resolution(dev, c));
	while (evemu_read_event(f, &ev) > 0)
		printf("E %lu %lu %u %u %d\n", (unsigned long)ev.time.tv_sec,
		       (unsigned long)ev.time.tv_usec, ev.type, ev.code, ev.value);
	return 0;
}
"""

# ours: rewrite a file with our writer, or print our names of everything
OUR_TOOL = r"""
#include <stdio.h>
#include <string.h>
#include "devices/rec_evemu.h"
int main(int argc, char **argv) {
	if (!strcmp(argv[1], "names")) {
		for (unsigned t = 0; t <= EV_MAX; t++) {
			const char *n = rec_evemu_type_name(t);
			if (n) printf("T %u %s\n", t, n);
			for (unsigned c = 0; c <= KEY_MAX; c++)
				if ((n = rec_evemu_code_name(t, c))) printf("C %u %u %s\n", t, c, n);
		}
		return 0;
	}
	struct rec_evemu r;
	char err[512];
	if (rec_evemu_read(argv[2], &r, err, sizeof err)) { fprintf(stderr, "%s\n", err); return 1; }
	rec_evemu_write(stdout, &r);
	rec_evemu_free(&r);
	return 0;
}
"""

LIBEVDEV_NAMES = r"""
#include <libevdev/libevdev.h>
#include <stdio.h>
int main(void) {
	for (int t = 0; t <= EV_MAX; t++) {
		const char *n = libevdev_event_type_get_name(t);
		if (n) printf("T %d %s\n", t, n);
		int max = libevdev_event_type_get_max(t);
		for (int c = 0; c <= max; c++)
			if ((n = libevdev_event_code_get_name(t, c))) printf("C %d %d %s\n", t, c, n);
	}
	return 0;
}
"""


def build(tmp, name, source, *args):
    src = tmp / f"{name}.c"
    src.write_text(source)
    exe = tmp / name
    subprocess.run([CC, "-std=c11", "-D_POSIX_C_SOURCE=200809L", "-D_DEFAULT_SOURCE",
                    f"-I{ROOT}", str(src), *args, "-o", str(exe)], check=True)
    return exe


@pytest.fixture(scope="module")
def tools(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("evemu")
    # the device layer as the build made it: the archive gives the tool what it uses
    ours = [str(ROOT / os.environ.get("POSTURE_BUILD", "build/rel") / "libposture.a")]
    return {
        "evemu": build(tmp, "evemu_tool", EVEMU_TOOL, "-levemu"),
        "ours": build(tmp, "our_tool", OUR_TOOL, *ours, "-I/usr/include/libevdev-1.0",
                      "-levdev", "-ludev", "-lhidapi-hidraw", "-lusb-1.0", "-lm"),
        "libevdev": build(tmp, "libevdev_names", LIBEVDEV_NAMES, "-I/usr/include/libevdev-1.0",
                          "-levdev"),
        "tmp": tmp,
    }


def run(*cmd):
    return subprocess.run([str(c) for c in cmd], check=True, capture_output=True,
                          text=True).stdout


@pytest.mark.parametrize("name", FILES)
def test_references_are_libevemus_reading(tools, name):
    assert run(tools["evemu"], "dump", DATA / f"{name}.evemu") == \
        (DATA / f"{name}.ref").read_text()


@pytest.mark.parametrize("name", FILES)
def test_libevemu_reads_what_we_write(tools, name):
    ours = tools["tmp"] / f"{name}.ours.evemu"
    ours.write_text(run(tools["ours"], "write", DATA / f"{name}.evemu"))
    assert run(tools["evemu"], "dump", ours) == run(tools["evemu"], "dump", DATA / f"{name}.evemu")


def machine_lines_out(text):
    return [l for l in text.splitlines() if not l.startswith(("# Kernel:", "# DMI:"))]


@pytest.mark.parametrize("name", FILES)
def test_we_write_what_libevemu_writes(tools, name):
    theirs = run(tools["evemu"], "write", DATA / f"{name}.evemu")
    ours = run(tools["ours"], "write", DATA / f"{name}.evemu")
    assert machine_lines_out(ours) == machine_lines_out(theirs)


def test_names_are_libevdevs(tools):
    ours = set(run(tools["ours"], "names").splitlines())
    theirs = set(run(tools["libevdev"]).splitlines())
    # names the installed libevdev (1.13) predates; the kernel header has them
    newer = {"C 1 447 KEY_LINK_PHONE", "C 1 562 KEY_REFRESH_RATE_TOGGLE", "C 3 33 ABS_PROFILE"}
    assert theirs - ours == set()
    assert ours - theirs <= newer
