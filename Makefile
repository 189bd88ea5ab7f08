# The README's two commands: `make demo` and `make test`. Both set themselves up.
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(VENV)/bin
DEMO_OUT ?= demo-output
## The tested dependency set: every package pinned to the version the suite passed with
## (see docs/dependencies.md; `make lock` refreshes it). Empty: the newest releases.
CONSTRAINTS ?= constraints.txt
PIP := $(BIN)/python -m pip install -q $(if $(CONSTRAINTS),-c $(CONSTRAINTS))
## Test processes (pytest-xdist): one per core; TEST_WORKERS=0 runs the suite in this process.
TEST_WORKERS ?= auto
LINT_PATHS := src tests $(wildcard benchmarks examples studies validation)

.PHONY: demo test test-latest lock lint typecheck unit docs system-deps clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(PIP) --upgrade pip

$(VENV)/.installed-base: pyproject.toml $(CONSTRAINTS) | $(BIN)/python
	$(PIP) -e .
	touch $@

$(VENV)/.installed-test: pyproject.toml $(CONSTRAINTS) | $(BIN)/python
	$(PIP) -e '.[test]'
	touch $@ $(VENV)/.installed-base

## demo: the seed paper rebuilt end to end on the analytic model (no CFD), as a report.
demo: $(VENV)/.installed-base
	$(BIN)/sloshkit model --radius 20.5mm --fill-height 39mm --liquid water-25C
	$(BIN)/sloshkit reproduce --out $(DEMO_OUT)

## system-deps: Debian packages the tests need (headless Chromium for the report test,
## OpenFOAM for the CFD tests); installed with apt-get only when missing.
system-deps:
	@missing=""; \
	command -v chromium >/dev/null 2>&1 || missing="$$missing chromium"; \
	command -v chromedriver >/dev/null 2>&1 || missing="$$missing chromium-driver"; \
	command -v interFoam >/dev/null 2>&1 || missing="$$missing openfoam"; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ]; then sudo=""; else sudo=sudo; fi; \
	  echo "installing Debian packages:$$missing"; \
	  $$sudo apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $$sudo apt-get install -y -qq $$missing >/dev/null; \
	fi

lint: $(VENV)/.installed-test
	$(BIN)/ruff check $(LINT_PATHS)
	$(BIN)/ruff format --check $(LINT_PATHS)
	$(BIN)/lint-imports

typecheck: $(VENV)/.installed-test
	$(BIN)/mypy

unit: $(VENV)/.installed-test system-deps
	$(BIN)/python -m pytest -n $(TEST_WORKERS)

## docs: the API reference (Sphinx, warnings are errors), into docs/api/_build.
docs: $(VENV)/.installed-test
	$(BIN)/python -m sphinx -W -q -b html docs/api docs/api/_build

## test: lint, types, the whole test suite (with the doctests of src/sloshkit) and the API docs.
test: lint typecheck unit docs

## test-latest: the same suite against the newest release of every dependency, in a fresh
## .venv-latest (what a machine installing without the lock would get).
test-latest:
	rm -rf .venv-latest
	$(MAKE) test VENV=.venv-latest CONSTRAINTS=

## lock: resolve the newest releases in a fresh .venv-lock and write them to constraints.txt;
## then run `make test` (it reinstalls from the new lock) before committing it.
lock:
	rm -rf .venv-lock
	$(PYTHON) -m venv .venv-lock
	.venv-lock/bin/python -m pip install -q --upgrade pip
	.venv-lock/bin/python -m pip install -q -e '.[test]'
	{ echo "# The tested dependency set of sloshkit (pip constraints), written by 'make lock'"; \
	  echo "# on $$(date -u +%Y-%m-%d) with $$(.venv-lock/bin/python --version)."; \
	  echo "# make demo and make test install from it; see docs/dependencies.md."; \
	  .venv-lock/bin/python -m pip freeze --all --exclude-editable | grep -v '^setuptools=='; \
	} > constraints.txt.tmp && mv constraints.txt.tmp constraints.txt
	rm -rf .venv-lock

clean:
	rm -rf $(VENV) .venv-latest .venv-lock $(DEMO_OUT) .pytest_cache .mypy_cache .ruff_cache .hypothesis docs/api/_build
