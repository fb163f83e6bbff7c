# riser — see README.md. `make demo` and `make test` install what they need.
SHELL := /bin/bash
CARGO ?= cargo
VENV := .venv
PY := $(VENV)/bin/python
# the studies and tools of python/riser_tools (riser_tools.studies; `$(TOOLS)` alone lists them)
TOOLS := $(VENV)/bin/riser-tools
BIN := target/release/riser
DEMO_DIR := out/demo

.PHONY: all build demo test check rust-test fmt lint test-build venv clean doc paper fmu vessel-fmu fmu-test fmu-test-release check-fmu stability study noise moordyn moordyn-seabed lowe-langley accuracy fuzz valgrind

all: build

build:
	$(CARGO) build --release

$(VENV)/.installed: requirements.txt python/riser_tools/pyproject.toml
	python3 -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -r requirements.txt
	$(PY) -m pip install --quiet -e python/riser_tools
	touch $@

venv: $(VENV)/.installed

# The main job on the built-in default scene: the static equilibrium of
# `catenary` (CSV and PNG), then the paper's catenary case through the FMU
# with fmpy (100 s of heave 2.5 m / 20 s, current 0.8 m/s), then the same line
# hanging from the six-degree-of-freedom vessel FMU (osp/vessel/Vessel6.py),
# coupled both ways in libcosim (60 s at 0.05 s steps), all in out/demo/.
demo: build venv fmu
	mkdir -p $(DEMO_DIR)
	$(BIN) statics catenary --out $(DEMO_DIR)
	$(TOOLS) plot-statics $(DEMO_DIR)/shape.csv $(DEMO_DIR)/shape.png --title "catenary (built-in scene): static state" --surface-z 10
	$(TOOLS) demo --fmu fmu/riser.fmu --bin $(BIN) --out $(DEMO_DIR)
	@echo "demo output in $(DEMO_DIR)/: shape.csv, shape.png, fmu_timeseries.csv, shapes.png, tension_energy.png, vessel_coupling.csv, vessel_coupling.png, moored_vessel.csv, moored_vessel.png"

# The seed paper's runs: docs/paper_runs.md, docs/paper_runs_damped.md
# and docs/figures/paper_*.png (a few minutes).
paper: build venv
	$(TOOLS) paper
	$(TOOLS) paper --damping 0.002

# Speed against accuracy (issue 5): docs/study.md and docs/figures/work_precision.png
# (tens of minutes; run it on a quiet machine, it measures wall time).
study: build venv
	$(TOOLS) study

# Tension noise of the conserving scheme, with and without the dissipative
# option (issue 5): the noise section of docs/performance.md (a few minutes).
noise: build venv
	$(TOOLS) noise

# MoorDyn side by side on the catenary scene (issue 5): docs/moordyn.md and
# docs/figures/moordyn_compare.png (~15 minutes; the pinned moordyn is in requirements.txt).
moordyn: build venv
	$(TOOLS) moordyn --bin $(BIN) --out out/moordyn --docs docs

# MoorDyn side by side on the steel catenary with seabed contact (issue 17):
# docs/moordyn_seabed.md and docs/figures/moordyn_seabed.png (~2 minutes).
moordyn-seabed: build venv fmu
	$(TOOLS) moordyn-seabed --bin $(BIN) --out out/moordyn_seabed --docs docs

# The Lowe & Langley (2006) jumper in surge, sway and heave against the
# paper's digitised tensions (docs/lowe_langley.md, a few seconds).
lowe-langley: build venv
	$(TOOLS) lowe-langley

# The accuracy study (issues 28, 51): the grid of the scheme's orders and the
# measured choice on its cases and on new scenes, docs/accuracy.md, docs/accuracy_runs.csv and docs/accuracy_measured.csv
# (about an hour on 2 cores; a rerun reuses out/accuracy/grid.csv and out/accuracy/measured/).
accuracy: build venv
	$(TOOLS) accuracy --bin $(BIN)

# The stability matrix (issue 5): docs/stability.md (several minutes).
stability: build venv
	$(TOOLS) stability

# The FMU through its C ABI (issue 28): benches/fmu_driver.c, compiled with
# cc, loads target/release/libriser.so as a master does (fmi2SetReal of the
# heave, fmi2DoStep) at communication steps of 0.05, 0.1 and 0.2 s on the
# catenary; real-time factor against the error of the top tension's window
# against a converged run (120 elements, 0.005 s), beside the CLI on the same
# numerics; and the cost of a step and of a Newton iteration at 5-60 elements
# (benches/fmu.rs; docs/performance.md, "Through the FMU's C ABI"). About 10
# minutes; it measures wall time: run it on a quiet machine. Not part of `make test`.
.PHONY: bench-fmu
bench-fmu:
	$(CARGO) build --release --lib --bin riser
	$(CARGO) bench --bench fmu

# riser-sweep on Dask (issue 15): 48 cases as a plain loop and on a local
# cluster of 1 and 2 workers; the "Sweeps on Dask" figures of docs/performance.md
# (5 to 8 minutes; run it on a quiet machine, it measures wall time).
.PHONY: bench-sweep
bench-sweep: venv fmu
	$(TOOLS) bench-sweep

# The Rust tests in the `fasttest` profile (Cargo.toml): optimised as the
# physics needs, without the release profile's fat LTO, which made the test
# binaries' link the longest part of `make test`.
TEST_PROFILE := fasttest

# The lints ride on the tests' build: riser's own crates (the library, the
# command line, the build script, the unit and integration tests, the
# benchmarks, the examples: every target `cargo clippy --all-targets` lints)
# are compiled by clippy's driver, as `cargo clippy` itself runs it (cargo's
# RUSTC_WORKSPACE_WRAPPER; clippy's arguments in CLIPPY_ARGS, separated by
# __CLIPPY_HACKERY__), so the dependencies are compiled once, for the tests,
# instead of also being checked in the dev profile for clippy (a minute and a
# half of a fresh clone's `make test`). Every cargo command of the fasttest
# profile below runs with the same two variables, and so do the Python tests
# (two build examples with cargo): without them cargo builds riser again (its
# artifacts are told apart by the wrapper; they do not replace each other).
ifndef CLIPPY_DRIVER
CLIPPY_DRIVER := $(shell rustup which clippy-driver 2>/dev/null || command -v clippy-driver)
endif
LINTED := RUSTC_WORKSPACE_WRAPPER=$(CLIPPY_DRIVER) CLIPPY_ARGS=-D__CLIPPY_HACKERY__warnings
TEST_CARGO := $(LINTED) $(CARGO)

fmt:
	$(CARGO) fmt --check

# formatting, then the lints of every target with the tests' build
lint: fmt test-build

# `cargo build --all-targets` builds what `cargo test` runs (the examples as
# programs, as `cargo test` and the Python tests build them) and the benchmarks.
test-build:
	@test -n "$(CLIPPY_DRIVER)" || { echo "clippy-driver not found: rustup component add clippy"; exit 1; }
	$(TEST_CARGO) build --profile $(TEST_PROFILE) --all-targets

rust-test:
	$(TEST_CARGO) test --profile $(TEST_PROFILE)

# The API pages (target/doc/riser/index.html) by rustdoc on the tests' build, with its rlibs as the
# dependencies (python/riser_tools/src/riser_tools/rustdoc.py, the standard library only): `cargo
# doc` would check every dependency again for their metadata (cargo cannot document against a
# build's), 122 s of CPU on a fresh clone against 5 s. It asks cargo for the build's artifacts with
# `make test-build`'s target selection and variables (fresh after it; from a clean target it is that
# build). `-D warnings`: a broken intra-doc link fails it, as RUSTDOCFLAGS="-D warnings" did.
doc:
	$(LINTED) CARGO=$(CARGO) python3 python/riser_tools/src/riser_tools/rustdoc.py --profile $(TEST_PROFILE) -- -D warnings

# fmu/riser.fmu: modelDescription.xml (from modelDescription/variables.csv via
# build.rs), binaries/linux64/riser.so, resources/ (scenes), documentation/.
fmu: build venv
	$(TOOLS) package-fmu

# The six-degree-of-freedom vessel FMU (pythonfmu) beside
# osp/vessel6/OspSystemStructure.xml, which couples it to riser both ways.
vessel-fmu: venv
	$(PY) -m pythonfmu build -f osp/vessel/Vessel6.py -d osp/vessel6

# The FMU as fmpy and libcosim drive it (tests/python), packaged from the
# fasttest build (out/check/riser.fmu: the same sources and FMU, without the
# release profile's fat LTO, whose link took 2.5 of `make test`'s 11 minutes
# on a clean clone; the Python tests take as long on either build). The FMU
# as shipped (release) runs in `make demo`, and all of them in
# `make fmu-test-release`.
# Two pytest workers (pytest-xdist), each taking whole test files (--dist loadfile: a
# file's module fixtures are built once); each file's time against its budget is
# printed at the end.
PYTEST_WORKERS ?= 2
fmu-test: venv check-fmu
	$(LINTED) RISER_FMU=$(CHECK_DIR)/riser.fmu RISER_BIN=target/$(TEST_PROFILE)/riser $(PY) -m pytest -q -m "not long" \
		-n $(PYTEST_WORKERS) --dist loadfile tests/python

# The long comparisons that `make test` leaves out (tests marked `long`: the FMU's growing
# high-frequency oscillation over 150 s at 160 elements, ...), against the same FMU.
.PHONY: check-long
check-long: venv check-fmu
	$(TEST_CARGO) test --profile $(TEST_PROFILE) -- --ignored
	$(LINTED) RISER_FMU=$(CHECK_DIR)/riser.fmu RISER_BIN=target/$(TEST_PROFILE)/riser $(PY) -m pytest -q -m long -n $(PYTEST_WORKERS) --dist loadfile tests/python

fmu-test-release: fmu
	$(PY) -m pytest -q -m "not long" tests/python

# Every test: formatting, lints, docs, the Rust tests (profile fasttest), and the FMU packaged from
# the same build through fmpy and libcosim. The venv's install (pip, mostly files) runs niced in the
# background from the start; after the linted build and rustdoc (seconds), the Rust tests and the
# Python tests run side by side (their output apart: the Rust tests' is printed after the Python
# tests', from $(CHECK_DIR)/rust-test.log), so that neither's tail (a last long test, a
# subprocess's start, a wait on a Dask worker) leaves a core idle: `make test` is CPU-bound on two
# cores, and its wall time about its CPU time over two. The Rust tests niced: the Python tests are
# the longer part (3:10 alone on the quiet machine against 1:44) and the more serial (a file to a
# worker, subprocesses waited on), the integration binary's many tests fill what they leave. A fresh clone's CPU (user + sys, measured
# 2026-12-08, docs/performance.md "The test loop"): the linted build 478 s, rustdoc 5 s (cargo doc
# checked the dependencies: 122 s), the Rust tests about 120 s, the Python tests about 271 s, about
# 910 s in all against the 960 s of 8 minutes of two cores (9 min 52 s quiet at dc5f965, the build
# 3:56, the Rust tests 1:44 with rustdoc ending 58 s after them, the Python tests 3:10, one after
# the other). `make test` fails if any part does. Not
# incremental: a fresh build writes the incremental cache for nothing (about 10 s of a fresh
# clone); cargo's fingerprint is the same, so `make check`'s incremental rebuilds after it start
# from its artifacts.
test: export CARGO_INCREMENTAL := 0
test: fmt
	@mkdir -p $(CHECK_DIR); \
	nice -n 10 $(MAKE) --no-print-directory venv & venv=$$!; \
	{ $(MAKE) --no-print-directory test-build && $(MAKE) --no-print-directory doc; } || { wait $$venv; exit 1; }; \
	nice -n 5 $(MAKE) --no-print-directory rust-test > $(CHECK_DIR)/rust-test.log 2>&1 & rust=$$!; \
	wait $$venv && $(MAKE) --no-print-directory fmu-test; py=$$?; \
	wait $$rust; rust=$$?; \
	echo "---- the Rust tests (cargo test, beside the Python tests; $(CHECK_DIR)/rust-test.log)"; \
	cat $(CHECK_DIR)/rust-test.log; \
	test $$py -eq 0 -a $$rust -eq 0

# Before each commit (a minute or two once built): formatting, lints, the Rust
# tests, and the FMU's Python tests but the long fuzz and Dask ones, against an
# FMU packaged from the fasttest build (out/check/riser.fmu), so that no fat-LTO
# link is waited for. `make test` remains the gate.
CHECK_DIR := out/check
check: lint rust-test venv check-fmu
	$(LINTED) RISER_FMU=$(CHECK_DIR)/riser.fmu RISER_BIN=target/$(TEST_PROFILE)/riser \
		$(PY) -m pytest -q -m "not long" -n $(PYTEST_WORKERS) --dist loadfile tests/python -k "not fuzz and not sweep and not scatter"

# The FMU of the fasttest build: the library and the CLI as `cargo test`
# builds them (its cdylib stays in deps/), not `cargo build`'s, which would
# rebuild faer and the crate without the dev-dependency's feature (a minute).
check-fmu: venv
	$(TEST_CARGO) test --profile $(TEST_PROFILE) --no-run
	$(TOOLS) package-fmu --bin target/$(TEST_PROFILE)/riser \
		--lib target/$(TEST_PROFILE)/deps/libriser.so --out $(CHECK_DIR)/riser.fmu

clean:
	$(CARGO) clean
	rm -rf out $(VENV) fmu/riser.fmu osp/vessel6/Vessel6.fmu

# The long fuzz run of the FMU's C ABI (robustness issue): 5000 seeded random
# FMI call sequences, each in a child process; the result in docs/fuzz.md
# (~6 minutes on a quiet machine). `make test` runs 400 of them (tests/python/test_fuzz.py).
fuzz: fmu
	$(TOOLS) fuzz

# riser.so under valgrind memcheck: an fmpy run and a sample of the fuzz
# sequences; errors and leaks attributed by their stacks (docs/fuzz.md,
# 'valgrind'; ~7 minutes).
valgrind: fmu
	$(TOOLS) valgrind
