# The README's two commands are `make reproduce` and `make test`; both bootstrap .venv from
# pyproject.toml with every version pinned by requirements-lock.txt (refreshed by `make lock`).
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed
LOCK := requirements-lock.txt
PIP_QUIET := --quiet --disable-pip-version-check
# pytest-xdist workers of `make test` and `make test-slow` (each test module on one worker, so a
# module's shared fixtures are computed once); 2 = this project's machines' cores
TEST_WORKERS ?= 2
PYTEST_PARALLEL := -n $(TEST_WORKERS) --dist loadscope

.PHONY: setup lock regenerate calibrate calibrate-table6 fidelity fidelity-update scatter gains designs bound lint test test-slow bench reproduce docs clean

$(STAMP): pyproject.toml $(LOCK)
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install $(PIP_QUIET) -c $(LOCK) -e '.[derive,dev,docs]'
	touch $(STAMP)

setup: $(STAMP)

## lock: resolve pyproject.toml afresh in a scratch venv and pin every package (transitive too)
lock:
	rm -rf .lock-venv
	$(PYTHON) -m venv .lock-venv
	.lock-venv/bin/python -m pip install $(PIP_QUIET) '.[derive,dev,docs]'
	{ echo "# Pinned set of every runtime, derive and test dependency, transitive ones included."; \
	  echo "# Written by \`make lock\` (resolved from pyproject.toml with $$(.lock-venv/bin/python -V),"; \
	  echo "# $$(uname -sm)); \`make setup\` installs with it as constraints. Do not edit by hand."; \
	  .lock-venv/bin/python -m pip freeze --exclude-editable --exclude loader-model; } > $(LOCK).tmp
	mv $(LOCK).tmp $(LOCK)
	rm -rf .lock-venv build

## regenerate: derive every described machine (derive/machines/*.toml) with SymPy and rewrite
## generated/ (deterministic); `make regenerate MACHINE=name` derives one; the descriptions are
## shipped with the runtime as loader_model/data/machines/<name>.machine.toml
regenerate: setup
	$(PY) -m derive --output generated $(if $(MACHINE),--machine $(MACHINE))
	for f in derive/machines/*.toml; do \
	  cp "$$f" "loader_model/data/machines/$$(basename "$$f" .toml).machine.toml"; done

## calibrate: fit the default loader to the paper's Table 1, rewrite its TOML, then regenerate
calibrate: setup
	$(VENV)/bin/loader-model calibrate --output loader_model/data/default_loader.toml
	$(MAKE) regenerate

## lint: ruff check and format check over the whole tree, and the runtime's layer contract
lint: setup
	$(PY) -m ruff check .
	$(PY) -m ruff format --check .
	$(VENV)/bin/lint-imports --no-cache

## test: lint, generated-code staleness, fast tests
test: setup lint
	$(PY) -m pytest -m "not slow" -q $(PYTEST_PARALLEL)

## test-slow: the tests marked slow (full regeneration, independent derivation, wheel install)
test-slow: setup
	$(PY) -m pytest -m slow -q $(PYTEST_PARALLEL)

## calibrate-table6: fit the estimated parameters to the means and trial scatter of Table 6's 9 km/h
## cells (18 km/h held out) and the other way round; ships the two calibrated loader files and their
## summaries (15-30 minutes each); make fidelity-update then checks both speeds with 80 trials
CALIBRATE_TABLE6 = $(VENV)/bin/loader-model calibrate-table6 --evaluations 64 --design-points 32 --trials 6 --scatter-weight 1 --check-trials 0 --seed 0 --jobs 2
calibrate-table6: setup
	$(CALIBRATE_TABLE6) --fit-speed 9 --output loader_model/data/loader_calibrated_table6_9kmh.toml --summary loader_model/data/calibration_table6_9kmh.json
	$(CALIBRATE_TABLE6) --fit-speed 18 --output loader_model/data/loader_calibrated_table6_18kmh.toml --summary loader_model/data/calibration_table6_18kmh.json

## fidelity: the fidelity budget of Table 6 and the uncertainty study over the estimated
## parameters; ships loader_model/data/fidelity_budget.json (minutes; the report renders it)
fidelity: setup
	$(VENV)/bin/loader-model fidelity --trials 80 --machines 16 --machine-trials 6 --output loader_model/data/fidelity_budget.json

## fidelity-update: after make calibrate-table6, recompute only the budget's calibrated steps and the
## plausible machines' mean-and-scatter study in the shipped budget (23 minutes for the machines, 6-8
## for each calibrated step, measured on the shared 2-core Xeon at load 6-10)
fidelity-update: setup
	$(VENV)/bin/loader-model fidelity --trials 80 --machines 16 --machine-trials 6 --update --output loader_model/data/fidelity_budget.json

## scatter: the model's Table 6 trial scatter and means from 150 trials per group beside the
## scatter the paper's p-values imply; ships loader_model/data/table6_scatter.csv (minutes; the
## report renders it, a slow test checks it)
scatter: setup
	$(PY) -m loader_model.experiments.scatter_study --trials 150 --seed 0 --jobs 2 --output loader_model/data/table6_scatter.csv

## gains: refine the skyhook gains on the nonlinear paper course (both loads, 9 km/h) and ship them
gains: setup
	$(VENV)/bin/loader-model design --method refine --evaluations 150 --output loader_model/data/controller_refined.toml

## designs: each shipped machine's skyhook gains designed on the nonlinear machine and their design
## check, shipped for the report (about 20 minutes; a slow test checks that they still pass)
designs: setup
	$(VENV)/bin/loader-model design --method machine --start loader_model/data/controller_refined.toml --no-progress --output loader_model/data/controller_machine.toml
	$(VENV)/bin/loader-model check-design loader_model/data/controller_machine.toml --no-progress --output loader_model/data/design_check_skid_steer.md
	$(VENV)/bin/loader-model design --machine compact_wheel_loader --method machine --no-progress --output loader_model/data/controller_machine_compact_wheel_loader.toml
	$(VENV)/bin/loader-model check-design loader_model/data/controller_machine_compact_wheel_loader.toml --machine compact_wheel_loader --no-progress --output loader_model/data/design_check_compact_wheel_loader.md
	$(VENV)/bin/loader-model design --machine tractor_front_loader --method machine --start loader_model/data/controller_gated.toml --no-progress --output loader_model/data/controller_machine_tractor_front_loader.toml
	$(VENV)/bin/loader-model check-design loader_model/data/controller_machine_tractor_front_loader.toml --machine tractor_front_loader --study loader_model/data/robustness_tractor.toml --no-progress --output loader_model/data/design_check_tractor_front_loader.md

## bound: the bound for the four Table 6 conditions, shipped for the report (a slow test checks it)
bound: setup
	$(PY) -m loader_model.bound.table6 --output loader_model/data/bound_table6.toml

## bench: wall times of regeneration, import and model evaluation (medians, with ratios)
bench: setup
	$(PY) -m tests.bench

## reproduce: the main job on the default loader
reproduce: setup
	$(VENV)/bin/loader-model reproduce

## docs: the user guide and API reference as HTML in docs/_build/html (offline, warnings are errors)
docs: setup
	$(VENV)/bin/sphinx-build -b html -W --keep-going -q docs docs/_build/html

clean:
	rm -rf docs/_build $(VENV) .lock-venv build dist *.egg-info .pytest_cache .ruff_cache
