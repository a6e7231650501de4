# allocator_pkg: `make run` starts the node, `make test` runs the whole suite.
# Both set everything up on first use (a .venv from requirements.lock, allocator_msgs
# built with CMake into it, allocator_pkg installed editable); later calls take seconds.

SHELL := /bin/bash
.DEFAULT_GOAL := help

# DDS discovery stays on this machine unless the caller says otherwise (real vehicle network).
export ROS_AUTOMATIC_DISCOVERY_RANGE ?= LOCALHOST
export ROS_DOMAIN_ID ?= 42

PYTHON ?= $(shell python3.12 -c '' >/dev/null 2>&1 && echo python3.12 || echo python3)
VENV := .venv
VENV_ABS := $(abspath $(VENV))
PY := $(VENV)/bin/python
STAMPS := $(VENV)/.stamps
MSGS_BUILD := build/allocator_msgs
MSGS_SOURCES := $(wildcard allocator_msgs/CMakeLists.txt allocator_msgs/package.xml allocator_msgs/msg/*.msg allocator_msgs/srv/*.srv)

CONFIG ?= config/default.yaml
PYTEST_ARGS ?=
# The suite on every core (pytest-xdist), each test file on one worker (their shared runs are
# made once); every run of a node is in a namespace of its own, so workers never cross.
TEST_WORKERS ?= auto

.PHONY: help setup run test lint lock docs capability demo sim bench load soak clean prereqs

help:
	@echo "make run     set up (first time) and start allocator_node with CONFIG=$(CONFIG)"
	@echo "make test    set up (first time), lint, and run the whole pytest suite on every core (TEST_WORKERS=$(TEST_WORKERS))"
	@echo "make demo    closed loop: a DP vessel on station while an azimuth fails, live table, footprint and timeline PNGs"
	@echo "make sim     every scenario in config/scenarios/ under SIM_METHODS, side by side, into build/sim/ (SIM_ARGS=--in-process: no node)"
	@echo "make setup   only the set-up: .venv, allocator_msgs, allocator_pkg (idempotent)"
	@echo "make lint    ruff"
	@echo "make docs    regenerate docs/configuration.md (schema), the file key tables of docs/closed_loop.md and docs/dp_capability.md, docs/faults.md, docs/thrust_markers.png, docs/priorities.png"
	@echo "make capability  capability plots of every shipped vehicle (and of each method that differs) into docs/capability/"
	@echo "make dp-capability  DNV-ST-0111 Level 1 DP capability of every vessel in config/particulars/, Level 2 of dp_vessel, into docs/dp_capability/"
	@echo "make bench   solver and node benchmarks into bench/results/latest.json and docs/performance.md"
	@echo "make load    the node under a 10 kHz wrench flood and a busy core, LOAD_SECONDS=$(LOAD_SECONDS) per trigger"
	@echo "make soak    the node for SOAK_MINUTES=$(SOAK_MINUTES) at 500 Hz under random faults and changes"
	@echo "make explore generated vehicles by the thousand against independent references, EXPLORE_MINUTES=$(EXPLORE_MINUTES)"
	@echo "make lock    re-resolve requirements.in into requirements.lock"
	@echo "make clean   remove .venv and build/"

setup: $(STAMPS)/pkg

prereqs:
	@tools/check_prereqs.sh $(PYTHON)

$(STAMPS)/venv: requirements.lock | prereqs
	@echo "setup: creating $(VENV) with $(PYTHON) and installing requirements.lock"
	@test -x $(PY) || $(PYTHON) -m venv $(VENV)
	@$(PY) -m pip install --quiet --upgrade pip
	@$(PY) -m pip install --quiet -r requirements.lock
	@$(PY) tools/fix_wheel_cmake_paths.py
	@mkdir -p $(STAMPS) && touch $@

$(STAMPS)/msgs: $(STAMPS)/venv $(MSGS_SOURCES) | prereqs
	@echo "setup: building allocator_msgs into $(VENV) (log: $(MSGS_BUILD).log)"
	@mkdir -p $(MSGS_BUILD)
	@export PATH="$(VENV_ABS)/bin:$$PATH"; \
	{ cmake -S allocator_msgs -B $(MSGS_BUILD) \
	    -DCMAKE_INSTALL_PREFIX=$(VENV_ABS) -DCMAKE_PREFIX_PATH=$(VENV_ABS) \
	    -DPython3_EXECUTABLE=$(VENV_ABS)/bin/python -DBUILD_TESTING=OFF \
	  && cmake --build $(MSGS_BUILD) -j2 && cmake --install $(MSGS_BUILD); } \
	  > $(MSGS_BUILD).log 2>&1 \
	  || { tail -n 30 $(MSGS_BUILD).log; echo "setup: building allocator_msgs failed; full log in $(MSGS_BUILD).log" >&2; exit 1; }
	@touch $@

$(STAMPS)/pkg: $(STAMPS)/msgs setup.py setup.cfg package.xml
	@echo "setup: installing allocator_pkg (editable) into $(VENV)"
	@mkdir -p build
	@$(PY) -m pip install --no-deps --no-build-isolation -e . > build/allocator_pkg-install.log 2>&1 \
	  || { cat build/allocator_pkg-install.log; echo "setup: installing allocator_pkg failed" >&2; exit 1; }
	@touch $@

run: setup
	$(VENV)/bin/allocator_node --ros-args --params-file $(CONFIG)

DEMO_SCENARIO ?= config/scenarios/dp_azimuth_failure.yaml
demo: setup
	$(PY) -m allocator_pkg.cli.demo --scenario $(DEMO_SCENARIO) --out build/demo

SCENARIOS := $(wildcard config/scenarios/*.yaml)
SIM_METHODS ?= qp lp pseudoinverse nonlinear dynamic svd_filter explicit
SIM_ARGS ?=
sim: setup
	@broken=""; refused=""; failed=""; for scenario in $(SCENARIOS); do name=$$(basename $$scenario .yaml); \
	  $(VENV)/bin/allocator-sim compare $$scenario --methods $(SIM_METHODS) --out build/sim/$$name $(SIM_ARGS); \
	  case $$? in 0) ;; 1) broken="$$broken $$name";; 2) refused="$$refused $$name";; *) failed="$$failed $$name";; \
	  esac; done; \
	  if [ -n "$$broken" ]; then echo "sim: a method broke a bound (its verdict line says which) in:$$broken"; fi; \
	  if [ -n "$$refused" ]; then echo "sim: the scenario was refused before anything ran:$$refused"; fi; \
	  if [ -n "$$failed" ]; then echo "sim: a run failed (crashed, no verdict) in:$$failed"; fi; \
	  if [ -n "$$broken$$refused$$failed" ]; then exit 1; fi; echo "sim: every method held the bounds of every scenario"

lint: setup
	@$(VENV)/bin/ruff check .

test: lint
	$(PY) -m pytest -n $(TEST_WORKERS) --dist loadfile $(PYTEST_ARGS)

docs: setup
	$(PY) tools/update_docs.py
	$(PY) tools/render_markers.py
	$(PY) tools/plot_priorities.py
	$(PY) tools/plot_bus_trip.py
	$(PY) tools/plot_drilling_rig.py

VEHICLES := $(filter-out config/default.yaml,$(wildcard config/*.yaml))
capability: setup
	@for vehicle in $(VEHICLES); do $(VENV)/bin/allocator-capability $$vehicle --all-methods --out docs/capability || exit 1; done

.PHONY: dp-capability
dp-capability: setup
	@for particulars in config/particulars/*.yaml; do $(VENV)/bin/allocator-capability --dnv-level1 config/$$(basename $$particulars) $$particulars --out docs/dp_capability || exit 1; done
	@$(VENV)/bin/allocator-capability --dnv-level2 config/dp_vessel.yaml config/particulars/dp_vessel.yaml --out docs/dp_capability

BENCH_ARGS ?=
bench: setup
	$(PY) bench/run.py $(BENCH_ARGS)

LOAD_SECONDS ?= 60
load: setup
	$(PY) bench/load.py --seconds $(LOAD_SECONDS)

SOAK_MINUTES ?= 10
soak: setup
	$(PY) bench/soak.py --minutes $(SOAK_MINUTES)

EXPLORE_MINUTES ?= 5
EXPLORE_EXAMPLES ?= 1000
explore: setup
	$(PY) tools/explore.py --examples $(EXPLORE_EXAMPLES) --minutes $(EXPLORE_MINUTES)

lock: | prereqs
	@test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --dry-run --ignore-installed --quiet --report - -r requirements.in \
	  | $(PY) tools/write_lock.py > requirements.lock

clean:
	rm -rf $(VENV) build
