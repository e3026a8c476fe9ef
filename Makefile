# The two commands of the README. Both create .venv when it is missing, install the package
# with every extra and the system packages they need (tools/system-deps: apt on Debian/Ubuntu,
# else one line saying what to install), so they work on a fresh clone.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
# zenoh-ros2-sdk, an independent implementation of rmw_zenoh's wire format that the tests talk
# to (tests/ros2wire): a venv of its own, as its pinned dependencies differ from ours
SDK_VENV := .venv-ros2sdk
SDK_STAMP := $(SDK_VENV)/.installed

.PHONY: demo test test-fast docs bench lint typecheck clean wheel-smoke mutate

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

# uv (PyPI, by Astral) resolves and installs the same packages as pip, several times faster
# (on 2 cores: 104 s against 828 s for every extra, one run each while the machine was busy).
# It keeps the lock files of its builds in TMPDIR for good: this venv's own, not /tmp.
UV := TMPDIR=$(CURDIR)/$(VENV)/tmp $(BIN)/uv
$(STAMP): $(BIN)/python pyproject.toml
	$(BIN)/python -m pip install --quiet --upgrade pip uv
	mkdir -p $(VENV)/tmp
	$(UV) pip install --quiet --python $(BIN)/python -e '.[all,test,docs]'
	$(BIN)/python tools/install_clientlibs_pth.py
	touch $(STAMP)

$(SDK_STAMP): $(STAMP)
	$(PYTHON) -m venv $(SDK_VENV)
	$(UV) pip install --quiet --python $(SDK_VENV)/bin/python 'zenoh-ros2-sdk==0.1.8'
	touch $(SDK_STAMP)

# System packages first: a fresh Ubuntu cannot create .venv before python3-venv is installed.
demo:
	PYTHON=$(PYTHON) tools/system-deps demo
	$(MAKE) --no-print-directory $(STAMP)
	ROS_PACKAGE_PATH=$(CURDIR)/examples $(BIN)/robomodel launch simplebot_control simplebot_demo.launch

test:
	PYTHON=$(PYTHON) tools/system-deps test
	$(MAKE) --no-print-directory $(STAMP) $(SDK_STAMP)
	$(BIN)/ruff check --no-cache src tests bench
	$(BIN)/ruff format --no-cache --check src tests bench
	$(BIN)/mypy
	$(BIN)/python -m pytest -q -n 4 tests

# The built wheel (not the checkout) under every Python 3.10-3.13 the machine has, each in a
# fresh venv, one command of each verb family run outside the checkout (tools/wheel_smoke.py).
# `make test` runs it too, beside the rest of the suite (tests/test_wheel_smoke.py).
wheel-smoke:
	PYTHON=$(PYTHON) tools/system-deps test
	$(MAKE) --no-print-directory $(STAMP)
	$(BIN)/python tools/wheel_smoke.py

# The in-process tier: the tests that start no process, browser, ROS 1 graph, Zenoh session or
# simulator (their markers are set by tests/conftest.py, see tests/tiers.py), and are not slow
# (the long property-based and corpus tests). Under a minute on 2 cores: four workers, as some
# of its tests wait on sockets and threads rather than compute.
FAST_TIER := not (browser or ros1 or bus or process or sim or slow)

test-fast: $(STAMP)
	$(BIN)/python -m pytest -q -n 4 -m "$(FAST_TIER)" tests

# Mutation testing of the core modules with mutmut, one module group at a time, each against
# its fast in-process tests (tools/mutate.py; scores in CONTRIBUTING.md). Not part of `test`:
# it runs for about an hour on two cores. `tools/mutate.py GROUP` runs one group.
mutate: $(STAMP)
	$(BIN)/python tools/mutate.py

# The documentation site, strict (a broken link or a missing page fails). Its screenshots are the
# browser tests', committed in docs/assets/: tools/docs_screenshots takes and copies missing ones.
docs:
	PYTHON=$(PYTHON) tools/system-deps test
	$(MAKE) --no-print-directory $(STAMP)
	$(BIN)/python tools/docs_screenshots.py
	NO_MKDOCS_2_WARNING=1 $(BIN)/mkdocs build --strict --site-dir build/site

bench:
	PYTHON=$(PYTHON) tools/system-deps bench
	$(MAKE) --no-print-directory $(STAMP)
	$(BIN)/python bench/bench_startup.py
	$(BIN)/python bench/bench_parse.py
	$(BIN)/python bench/bench_xacro.py
	$(BIN)/python bench/bench_xacro.py --scaling --runs 15
	$(BIN)/python bench/bench_kinematics.py
	$(BIN)/python bench/bench_runtime.py --seconds 8 --rounds 3 --reference
	$(BIN)/python bench/bench_runtime.py --seconds 8 --rounds 3 --reference --bus ros1
	$(BIN)/python bench/bench_latency.py --seconds 2 --rounds 5 --stages
	$(BIN)/python bench/bench_handover.py
	$(BIN)/python bench/bench_codec.py
	$(BIN)/python bench/bench_control.py
	$(BIN)/python bench/bench_viewer.py
	$(BIN)/python bench/bench_viewer.py --scaling --socket
	$(BIN)/python bench/bench_sim.py
	$(BIN)/python bench/bench_camera.py --seconds 1 --rounds 3
	$(BIN)/python bench/bench_launch.py
	$(BIN)/python bench/bench_bag.py
	$(BIN)/python bench/bench_definitions.py
	$(BIN)/python bench/bench_bridges.py --seconds 5
	$(BIN)/python bench/bench_bridges.py --seconds 5 --clients node --bridge in-publisher
	$(BIN)/python bench/bench_ws_floor.py --seconds 5
	$(BIN)/python bench/bench_image_publish.py --seconds 5 --rounds 3

clean:
	rm -rf $(VENV) $(SDK_VENV) build .pytest_cache .mypy_cache .ruff_cache
