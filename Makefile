# The README's two commands: `make demo` and `make test`. Both set themselves up.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
DEMO_OUT ?= demo-output

.PHONY: demo test lint typecheck unit docs system-deps clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip

$(VENV)/.installed-base: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install -q -e .
	touch $@

$(VENV)/.installed-test: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install -q -e '.[test]'
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
	$(BIN)/ruff check src tests $(wildcard benchmarks examples)
	$(BIN)/ruff format --check src tests $(wildcard benchmarks examples)
	$(BIN)/lint-imports

typecheck: $(VENV)/.installed-test
	$(BIN)/mypy

unit: $(VENV)/.installed-test system-deps
	$(BIN)/python -m pytest

## docs: the API reference (Sphinx, warnings are errors), into docs/api/_build.
docs: $(VENV)/.installed-test
	$(BIN)/python -m sphinx -W -q -b html docs/api docs/api/_build

## test: lint, types, the whole test suite (with the doctests of src/sloshkit) and the API docs.
test: lint typecheck unit docs

clean:
	rm -rf $(VENV) $(DEMO_OUT) .pytest_cache .mypy_cache .ruff_cache .hypothesis docs/api/_build
