# posture - one plain GNU Makefile (see README.md).
#
#   make run     the main job: the daemon with the built-in human, rendering frames
#   make test    unit tests (release and ASan+UBSan builds) and system tests
#   make bench   benchmarks; each prints "BENCH <name> key=value ..." lines
#   make deps    installs what is missing (Debian packages, Python venv)
#   make deb     the Debian package (debian/) into build/deb/; make install: DESTDIR, PREFIX

SHELL   := /bin/bash
CC      ?= cc
CFLAGS  ?= -O2 -g
WARN    := -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes
# libxkbcommon through pkg-config; before `make deps` has installed it, its plain name
XKB_CFLAGS := $(shell pkg-config --cflags xkbcommon 2>/dev/null)
XKB_LIBS := $(shell pkg-config --libs xkbcommon 2>/dev/null || echo -lxkbcommon)
BASE    := -std=c11 -pthread -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -Isrc -I. -I/usr/include/freetype2 -I/usr/include/libevdev-1.0 -I/usr/include/libusb-1.0 -I/usr/include/libdrm $(XKB_CFLAGS) -MMD -MP
# FCL (the fit layer's distances and contacts) is C++: its one translation unit is built by
# $(CXX) and every program links the C++ runtime
FCL_CFLAGS := $(filter-out -std=%,$(shell pkg-config --cflags fcl 2>/dev/null || echo -I/usr/include/eigen3))
FCL_LIBS := $(shell pkg-config --libs fcl 2>/dev/null || echo -lfcl -lccd -loctomap -loctomath)
CXX     ?= g++
CXXBASE := -std=c++17 -pthread -Isrc -I. $(FCL_CFLAGS) -MMD -MP
CXXWARN := -Wall -Wextra -Werror -Wshadow
LIBS    := -ljansson -lOSMesa -lfreetype -lpng -levdev -ludev -lhidapi-hidraw -lusb-1.0 -ldrm $(XKB_LIBS) $(FCL_LIBS) -lstdc++ -lm
TESTLIBS := -lcmocka -lnlopt
# NLopt is the independent minimiser the IK tests and benchmarks compare against;
# only tests and benchmarks link it
BENCHLIBS := -lnlopt
# float-cast-overflow: GCC leaves it out of -fsanitize=undefined (clang has it in)
SAN     := -fsanitize=address,undefined,float-cast-overflow -fno-omit-frame-pointer -fno-sanitize-recover=all

# where everything is built; another folder lets two builds of one tree run side by side
BUILD   ?= build
VENV    := .venv
PY      := $(VENV)/bin/python
# Debian packages the build, tests and benchmarks need (see docs/dependencies.md)
DEB_PKGS := build-essential libcglm-dev libcmocka-dev libjansson-dev libnlopt-dev libeigen3-dev libpng-dev libosmesa6-dev libfreetype-dev fonts-dejavu-core python3-venv python3-pip \
	libevdev-dev clang evemu-tools libevemu-dev umockdev libudev-dev libhidapi-dev libusb-1.0-0-dev can-utils \
	libxkbcommon-dev xkb-data libx11-data libdrm-dev libfcl-dev
# without their recommends: QEMU boots the kernel test tier's guest (tests/guest);
# debhelper, fakeroot and lintian build and check the Debian package (make deb);
# check_urdf (liburdfdom-tools) parses the URDF export; nodejs and npm run the Khronos glTF
# validator (the glTF export's tests); debootstrap and
# e2fsprogs make the clean Debian root the package is installed into and booted from in the
# guest (tests/guest/test_guest_package.py)
DEB_PKGS_LEAN := qemu-system-x86 debhelper fakeroot lintian liburdfdom-tools nodejs npm \
	debootstrap e2fsprogs
# the Khronos glTF validator, from npm into $(BUILD)/npm (make deps)
GLTF_VALIDATOR := gltf-validator@2.0.0-dev.3.10

# the layers, bottom up; each folder includes only from those before it (make layer-check)
LAYERS    := figure pose assess draw export interact fit daemon
MAIN_SRC  := src/daemon/main.c
LIB_SRC   := $(filter-out $(MAIN_SRC),$(foreach l,$(LAYERS),$(wildcard src/$(l)/*.c)) $(wildcard devices/*.c))
# C++ translation units (the FCL wrapper alone)
LIB_CXX   := $(foreach l,$(LAYERS),$(wildcard src/$(l)/*.cc))
TOOL_SRC  := $(wildcard tools/*.c)
TEST_SRC  := $(wildcard tests/test_*.c)
BENCH_SRC := $(wildcard tools/bench/*.c)
# programs the kernel test tier runs inside its QEMU guest (tests/guest)
GUEST_SRC := $(wildcard tests/guest/guest_*.c)

# two builds of everything: rel (optimised) and san (ASan + UBSan)
define variant
$(1)_CFLAGS := $(BASE) $(WARN) $(2)
$(1)_LDFLAGS := $(3) $(LDFLAGS)
$(1)_OBJ := $$(patsubst %.c,$(BUILD)/$(1)/%.o,$$(LIB_SRC)) $$(patsubst %.cc,$(BUILD)/$(1)/%.o,$$(LIB_CXX))
$(1)_LIB := $(BUILD)/$(1)/libposture.a
$(1)_TOOLS := $$(patsubst tools/%.c,$(BUILD)/$(1)/bin/%,$$(TOOL_SRC)) $(BUILD)/$(1)/bin/postured
$(1)_TESTS := $$(patsubst tests/%.c,$(BUILD)/$(1)/tests/%,$$(TEST_SRC))
$(1)_BENCH := $$(patsubst tools/bench/%.c,$(BUILD)/$(1)/bench/%,$$(BENCH_SRC))
$(1)_GUEST := $$(patsubst tests/guest/%.c,$(BUILD)/$(1)/guest/%,$$(GUEST_SRC))

$(BUILD)/$(1)/%.o: %.c | $(BUILD)/.deps-apt
	@mkdir -p $$(dir $$@)
	$$(CC) $$($(1)_CFLAGS) -c $$< -o $$@

$(BUILD)/$(1)/%.o: %.cc | $(BUILD)/.deps-apt
	@mkdir -p $$(dir $$@)
	$$(CXX) $$(CXXBASE) $$(CXXWARN) $(4) -c $$< -o $$@

$$($(1)_LIB): $$($(1)_OBJ)
	@mkdir -p $$(dir $$@)
	rm -f $$@ && ar rcs $$@ $$^

$(BUILD)/$(1)/bin/%: $(BUILD)/$(1)/tools/%.o $$($(1)_LIB)
	@mkdir -p $$(dir $$@)
	$$(CC) $$($(1)_CFLAGS) $$< $$($(1)_LIB) $$($(1)_LDFLAGS) $(LIBS) -o $$@

$(BUILD)/$(1)/bin/postured: $(BUILD)/$(1)/src/daemon/main.o $$($(1)_LIB)
	@mkdir -p $$(dir $$@)
	$$(CC) $$($(1)_CFLAGS) $$< $$($(1)_LIB) $$($(1)_LDFLAGS) $(LIBS) -o $$@

$(BUILD)/$(1)/tests/%: $(BUILD)/$(1)/tests/%.o $$($(1)_LIB)
	@mkdir -p $$(dir $$@)
	$$(CC) $$($(1)_CFLAGS) $$< $$($(1)_LIB) $$($(1)_LDFLAGS) $(TESTLIBS) $(LIBS) -o $$@

$(BUILD)/$(1)/bench/%: $(BUILD)/$(1)/tools/bench/%.o $$($(1)_LIB)
	@mkdir -p $$(dir $$@)
	$$(CC) $$($(1)_CFLAGS) $$< $$($(1)_LIB) $$($(1)_LDFLAGS) $(BENCHLIBS) $(LIBS) -o $$@

$(BUILD)/$(1)/guest/%: $(BUILD)/$(1)/tests/guest/%.o $$($(1)_LIB)
	@mkdir -p $$(dir $$@)
	$$(CC) $$($(1)_CFLAGS) $$< $$($(1)_LIB) $$($(1)_LDFLAGS) $(LIBS) -o $$@

-include $$(patsubst %.cc,$(BUILD)/$(1)/%.d,$$(LIB_CXX))
-include $$(patsubst %.c,$(BUILD)/$(1)/%.d,$$(LIB_SRC) $(MAIN_SRC) $$(TOOL_SRC) $$(TEST_SRC) $$(BENCH_SRC) $$(GUEST_SRC))
endef

$(eval $(call variant,rel,$(CFLAGS) -march=x86-64-v2,,-O2 -g -march=x86-64-v2))
$(eval $(call variant,san,-O1 -g $(SAN),$(SAN),-O1 -g $(SAN)))

.PHONY: all run test layer-check unit-test system-test fuzz fuzz-smoke bench deps check clean install deb
.SECONDARY:

all: $(rel_LIB) $(rel_TOOLS) $(rel_TESTS) $(rel_BENCH) $(rel_GUEST)

# ---- dependencies --------------------------------------------------------
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

deps: $(BUILD)/.deps-apt $(VENV)/.installed $(BUILD)/npm/.installed-$(GLTF_VALIDATOR)

# NO_APT=1 (the package build, debian/rules): the Build-Depends are there; no apt-get.
# npm counts as there when its program is: another nodejs (NodeSource's) bundles it and
# conflicts with Debian's package
$(BUILD)/.deps-apt: Makefile
	@mkdir -p $(BUILD)
	@[ "$(NO_APT)" = 1 ] || missing=$$(for p in $(DEB_PKGS) $(DEB_PKGS_LEAN); do \
		{ [ $$p = npm ] && command -v npm >/dev/null; } || \
		dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'install ok installed' || echo $$p; \
	done); \
	if [ -n "$$missing" ]; then \
		echo "deps: installing Debian packages:" $$missing; \
		$(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get update -qq && \
		lean=$$(for p in $$missing; do case " $(DEB_PKGS_LEAN) " in *" $$p "*) echo $$p;; esac; done); \
		rest=$$(for p in $$missing; do case " $(DEB_PKGS_LEAN) " in *" $$p "*) ;; *) echo $$p;; esac; done); \
		{ [ -z "$$rest" ] || $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$rest; } && \
		{ [ -z "$$lean" ] || $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
			--no-install-recommends $$lean; }; \
	fi
	@touch $@

$(VENV)/.installed: tests/requirements.txt | $(BUILD)/.deps-apt
	@[ -x $(PY) ] || python3 -m venv $(VENV)
	$(PY) -m pip install -q --disable-pip-version-check -r tests/requirements.txt
	@touch $@

# without npm the validator's tests skip, saying why
$(BUILD)/npm/.installed-$(GLTF_VALIDATOR): | $(BUILD)/.deps-apt
	@if command -v npm >/dev/null; then \
		npm install --prefix $(BUILD)/npm --no-audit --no-fund $(GLTF_VALIDATOR) && touch $@; \
	else echo "deps: no npm: $(GLTF_VALIDATOR) not installed (the glTF validator tests skip)"; fi

# ---- the main job --------------------------------------------------------
run: deps $(BUILD)/rel/bin/postured $(BUILD)/rel/bin/posture-figure
	@mkdir -p $(BUILD)/run
	$(BUILD)/rel/bin/postured --socket $(BUILD)/run/postured.sock --state-dir $(BUILD)/run/state \
		--frames $(BUILD)/run/frames --init tools/kiosk.init --library src/figure/library

# ---- install and the Debian package -------------------------------------
# make install [DESTDIR=...] [PREFIX=/usr/local]: the programs, the man page, the Python
# client, the shipped figures and the kiosk's first start under PREFIX; the system's
# files (unit, udev rules, sysusers, modules-load, the configuration) where systemd,
# udev and the package tools look for them, whatever PREFIX is
PREFIX     ?= /usr/local
BINDIR     ?= $(PREFIX)/bin
DATADIR    ?= $(PREFIX)/share/posture
MANDIR     ?= $(PREFIX)/share/man
PYDIR      ?= $(if $(filter /usr,$(PREFIX)),/usr/lib/python3/dist-packages,$(PREFIX)/lib/python3/dist-packages)
SYSCONFDIR ?= /etc
UNITDIR    ?= /lib/systemd/system
UDEVDIR    ?= /lib/udev/rules.d
SYSUSERSDIR ?= /usr/lib/sysusers.d
MODLOADDIR ?= /usr/lib/modules-load.d
# the scripts' interpreter: the system's Python, whose path holds PYDIR
INSTALL_PYTHON ?= /usr/bin/python3
INSTALL_PROGS := postured posture-figure posture-input posture-assess
INSTALL_SCRIPTS := posturectl posture-replay
INSTALL_PY := __init__.py client.py replay.py

install: $(addprefix $(BUILD)/rel/bin/,$(INSTALL_PROGS))
	install -d $(DESTDIR)$(BINDIR) $(DESTDIR)$(DATADIR)/library $(DESTDIR)$(MANDIR)/man8 $(DESTDIR)$(MANDIR)/man1 \
		$(DESTDIR)$(PYDIR)/posture $(DESTDIR)$(SYSCONFDIR)/posture $(DESTDIR)$(UNITDIR) \
		$(DESTDIR)$(UDEVDIR) $(DESTDIR)$(SYSUSERSDIR) $(DESTDIR)$(MODLOADDIR)
	install -m 0755 $(addprefix $(BUILD)/rel/bin/,$(INSTALL_PROGS)) $(DESTDIR)$(BINDIR)/
	for f in $(INSTALL_SCRIPTS); do sed -e '1s|^#!/usr/bin/env python3|#!$(INSTALL_PYTHON)|' \
		tools/$$f > $(DESTDIR)$(BINDIR)/$$f && chmod 0755 $(DESTDIR)$(BINDIR)/$$f; done
	install -m 0644 $(addprefix tools/posture/,$(INSTALL_PY)) $(DESTDIR)$(PYDIR)/posture/
	install -m 0644 src/figure/library/*.fig $(DESTDIR)$(DATADIR)/library/
	install -m 0644 tools/kiosk.init $(DESTDIR)$(DATADIR)/kiosk.init
	install -m 0644 tools/postured.8 $(DESTDIR)$(MANDIR)/man8/postured.8
	install -m 0644 $(addprefix tools/,$(addsuffix .1,$(INSTALL_PROGS:postured=) $(INSTALL_SCRIPTS))) \
		$(DESTDIR)$(MANDIR)/man1/
	sed -e 's|/usr/bin/postured|$(BINDIR)/postured|' tools/postured.service \
		> $(DESTDIR)$(UNITDIR)/postured.service
	sed -e 's|/usr/share/posture|$(DATADIR)|' tools/postured.conf \
		> $(DESTDIR)$(SYSCONFDIR)/posture/postured.conf
	install -m 0644 tools/60-posture.rules $(DESTDIR)$(UDEVDIR)/60-posture.rules
	install -m 0644 tools/posture.sysusers $(DESTDIR)$(SYSUSERSDIR)/posture.conf
	install -m 0644 tools/posture-modules.conf $(DESTDIR)$(MODLOADDIR)/posture.conf

# make deb: the Debian package (debian/), built as CI builds it, into build/deb/;
# dpkg-buildpackage writes beside the tree, so its results are moved here
DEB_JOBS ?= 2
deb: | $(BUILD)/.deps-apt
	dpkg-buildpackage -us -uc -b -j$(DEB_JOBS)
	@mkdir -p $(BUILD)/deb
	v=$$(dpkg-parsechangelog -S Version); a=$$(dpkg-architecture -q DEB_HOST_ARCH); \
	for f in ../posture_$${v}_$$a.deb ../posture-dbgsym_$${v}_$$a.deb ../posture_$${v}_$$a.buildinfo \
		../posture_$${v}_$$a.changes; do [ ! -e $$f ] || mv $$f $(BUILD)/deb/; done
	@ls -l $(BUILD)/deb

# ---- tests ---------------------------------------------------------------
test: deps layer-check unit-test system-test fuzz-smoke

# every include points down the layers, and no two modules need each other
layer-check:
	python3 tools/layer-check

unit-test: $(rel_TESTS) $(san_TESTS) $(rel_TOOLS)
	@set -e; for t in $(rel_TESTS) $(san_TESTS); do \
		echo "== $$t"; ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
			LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp $$t; \
	done

system-test: $(rel_TOOLS) $(rel_GUEST) | deps
	POSTURE_BUILD=$(BUILD)/rel PYTHONPATH=tools $(PY) -m pytest -p posture.pytest_replay -q -rs tests/system tests/tools tests/guest tests/replays

check: layer-check unit-test

# ---- fuzzing (libFuzzer from Debian's clang) ---------------------------------
# every parser of outside bytes has a harness tests/fuzz/fuzz_NAME.c with seeds in
# tests/fuzz/corpus/NAME; `make test` runs each briefly on its seeds, `make fuzz` long
FUZZ_SRC  := $(wildcard tests/fuzz/fuzz_*.c)
FUZZ_CC   := clang
FUZZ_SAN  := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
FUZZ_OBJ  := $(patsubst %.c,$(BUILD)/fuzz/%.o,$(LIB_SRC)) $(patsubst %.cc,$(BUILD)/fuzz/%.o,$(LIB_CXX))
# the C++ file's objects: without UBSan's vptr check, whose runtime is C++'s and the
# harnesses are linked by the C driver
FUZZ_CXX  := clang++
FUZZ_LIB  := $(BUILD)/fuzz/libposture.a
FUZZ_BIN  := $(patsubst tests/fuzz/%.c,$(BUILD)/fuzz/bin/%,$(FUZZ_SRC))
FUZZ_RUNS ?= 10000000
FUZZ_SMOKE_RUNS ?= 20000

# the figure's kinematics and the human's builder read no outside bytes but run for every
# figure a session, journal or posture names: checked by the sanitizers, not traced for
# coverage (the tracing of their loops was 40% of the session harness's time)
FUZZ_NOCOV := src/figure/kin.c src/figure/state.c src/figure/human.c src/figure/human_data.c

$(BUILD)/fuzz/%.o: %.c | $(BUILD)/.deps-apt
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(BASE) $(WARN) -g -O1 $(if $(filter $<,$(FUZZ_NOCOV)),,-fsanitize=fuzzer-no-link) \
		$(FUZZ_SAN) -c $< -o $@

$(BUILD)/fuzz/%.o: %.cc | $(BUILD)/.deps-apt
	@mkdir -p $(dir $@)
	$(FUZZ_CXX) $(CXXBASE) $(CXXWARN) -g -O1 $(FUZZ_SAN) -fno-sanitize=vptr -c $< -o $@

$(FUZZ_LIB): $(FUZZ_OBJ)
	rm -f $@ && ar rcs $@ $^

# a harness's own link flags: its comment's line " * fuzz-link: FLAGS"
$(BUILD)/fuzz/bin/%: tests/fuzz/%.c $(FUZZ_LIB)
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(BASE) $(WARN) -g -O1 -fsanitize=fuzzer $(FUZZ_SAN) $< $(FUZZ_LIB) \
		$$(sed -n 's/^ \* fuzz-link: //p' $<) $(LIBS) -o $@

# a header changed: the objects and harnesses that include it are built again
-include $(patsubst %.c,$(BUILD)/fuzz/%.d,$(LIB_SRC)) $(patsubst tests/fuzz/%.c,$(BUILD)/fuzz/bin/%.d,$(FUZZ_SRC))

# runs every harness $(1) times over its seeds and a working corpus, with the libFuzzer
# options of its comment's line " * fuzz-options: ..." (a smaller -max_len where an
# input's cost grows with its length); a crash prints the end of its log and stops
define fuzz_run
	@set -e; for f in $(FUZZ_BIN); do n=$${f##*/fuzz_}; w=$(BUILD)/fuzz/work/$$n; \
		mkdir -p $$w; opts=$$(sed -n 's/^ \* fuzz-options: //p' tests/fuzz/fuzz_$$n.c); \
		if ! $$f -runs=$(1) -max_len=65536 $$opts -print_final_stats=1 $$w tests/fuzz/corpus/$$n \
			> $$w.log 2>&1; then tail -40 $$w.log; echo "fuzz: $$n failed (log $$w.log)"; \
			exit 1; fi; \
		echo "fuzz: $$n $$(grep -ao 'number_of_executed_units: *[0-9]*' $$w.log | grep -o '[0-9]*$$') executions, no crash"; \
	done
endef

fuzz: $(FUZZ_BIN)
	$(call fuzz_run,$(FUZZ_RUNS))

fuzz-smoke: $(FUZZ_BIN)
	$(call fuzz_run,$(FUZZ_SMOKE_RUNS))

# ---- benchmarks ----------------------------------------------------------
# peers in C++ against the libraries the pip wheels ship (Pinocchio, Boost)
PEER_CXXFLAGS := -O2 -std=c++17 -DPINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION \
	-DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 \
	-DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -I/usr/include/eigen3

PEER_BENCH := $(patsubst tools/bench/%.cpp,$(BUILD)/rel/bench/%,$(wildcard tools/bench/*.cpp))

$(PEER_BENCH): $(BUILD)/rel/bench/%: tools/bench/%.cpp | deps
	@mkdir -p $(dir $@)
	P=$$(echo $(CURDIR)/$(VENV)/lib/python3*/site-packages/cmeel.prefix); \
	$(CXX) $(PEER_CXXFLAGS) -I$$P/include -I$$P/include/pinocchio/deprecated $< \
		-L$$P/lib -lpinocchio_default -lboost_serialization -Wl,-rpath,$$P/lib -o $@

# C benchmarks that need no peer run on their own; the others are run by the
# Python orchestrators (tools/bench/*.py), which measure ours and the peers (and
# kernel_latency.py and kms_flip_bench.py run guest programs in the kernel tier's QEMU guest)
BENCH_STANDALONE := $(BUILD)/rel/bench/ik_body $(BUILD)/rel/bench/behave_bench $(BUILD)/rel/bench/interact_bench \
	$(BUILD)/rel/bench/pick_bench $(BUILD)/rel/bench/hemi_bench $(BUILD)/rel/bench/display_bench \
	$(BUILD)/rel/bench/family_bench $(BUILD)/rel/bench/anthro_bench $(BUILD)/rel/bench/assess_bench \
	$(BUILD)/rel/bench/assess_live_bench $(BUILD)/rel/bench/tint_bench $(BUILD)/rel/bench/lowback_bench \
	$(BUILD)/rel/bench/loads_bench $(BUILD)/rel/bench/loads_live_bench $(BUILD)/rel/bench/reach_bench \
	$(BUILD)/rel/bench/visibility_bench \
	$(BUILD)/rel/bench/fit_bench \
	$(BUILD)/rel/bench/envelope_bench

bench: deps $(rel_BENCH) $(rel_TOOLS) $(rel_GUEST) $(PEER_BENCH)
	@set -e; for b in $(BENCH_STANDALONE); do echo "== $$b"; $$b; done
	@set -e; for b in $(wildcard tools/bench/*.py); do \
		echo "== $$b"; POSTURE_BUILD=$(BUILD)/rel $(PY) $$b; done

clean:
	rm -rf $(BUILD)
