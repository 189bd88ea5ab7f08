"""The written conventions (docs/conventions.md) that can be checked mechanically."""

from __future__ import annotations

import ast
import importlib
import inspect
import subprocess
import sys
import typing
from pathlib import Path

import pytest
from numpydoc.docscrape import NumpyDocString

import sloshkit

ROOT = Path(__file__).resolve().parents[1]
TIME_STEP_ALIASES = {"dt", "ts", "step_s", "time_step", "time_step_s"}


def _public_callables() -> list[tuple[str, object]]:
    found = []
    for name in sloshkit.__all__:
        obj = getattr(sloshkit, name)
        if isinstance(obj, type) and issubclass(obj, BaseException):
            continue  # exceptions and warnings document their message, not parameters
        if callable(obj):
            found.append((name, inspect.unwrap(obj)))
    return found


def _documented(doc: NumpyDocString) -> set[str]:
    names = set()
    for section in ("Parameters", "Other Parameters", "Attributes"):
        for parameter in doc[section]:
            names.update(part.strip().lstrip("*") for part in parameter.name.split(","))
    return names


@pytest.mark.parametrize(("name", "obj"), _public_callables())
def test_every_public_parameter_is_documented(name, obj):
    doc = NumpyDocString(inspect.getdoc(obj) or "")
    parameters = [p for p in inspect.signature(obj).parameters if p not in ("self", "cls")]
    missing = [p for p in parameters if p not in _documented(doc)]
    assert not missing, f"sloshkit.{name}: undocumented parameters {missing}"
    assert doc["Examples"], f"sloshkit.{name}: no Examples section"
    assert not TIME_STEP_ALIASES & set(parameters), f"sloshkit.{name}: say sample_period_s"


#: Modules whose every public function and class follows the docstring convention too.
DOCUMENTED_MODULES = (
    "sloshkit.sim.equations",
    "sloshkit.sim.metrics",
    "sloshkit.sim.discretisation",
    "sloshkit.sim.simulate",
    "sloshkit.sim.response",
    "sloshkit.motion.sampling",
    "sloshkit.motion.scaling",
    "sloshkit.results",
    "sloshkit.files",
    "sloshkit.io.requests",
    "sloshkit.model.document",
)


def _module_callables() -> list[tuple[str, object]]:
    found = []
    for module_name in DOCUMENTED_MODULES:
        module = importlib.import_module(module_name)
        for name, obj in vars(module).items():
            if name.startswith("_") or getattr(obj, "__module__", None) != module_name:
                continue
            if inspect.isfunction(obj) or (inspect.isclass(obj) and obj.__doc__):
                if inspect.isclass(obj) and issubclass(obj, typing.Protocol):  # type: ignore[arg-type]
                    continue
                found.append((f"{module_name}.{name}", obj))
    return found


@pytest.mark.parametrize(("name", "obj"), _module_callables())
def test_touched_modules_are_documented(name, obj):
    doc = NumpyDocString(inspect.getdoc(obj) or "")
    parameters = [p for p in inspect.signature(obj).parameters if p not in ("self", "cls")]
    missing = [p for p in parameters if p not in _documented(doc)]
    assert not missing, f"{name}: undocumented parameters {missing}"
    assert doc["Examples"], f"{name}: no Examples section"


def test_the_checker_fails_on_an_undocumented_parameter():
    def undocumented(model, motion, *, sample_period_s=1e-3):
        """Something.

        Parameters
        ----------
        model : SloshModel
            The model.

        Examples
        --------
        >>> 1
        1
        """

    doc = NumpyDocString(inspect.getdoc(undocumented) or "")
    parameters = set(inspect.signature(undocumented).parameters)
    assert parameters - _documented(doc) == {"motion", "sample_period_s"}


def test_import_sloshkit_is_cheap():
    code = (
        "import sys, sloshkit; "
        "print(sorted(m for m in ('numpy', 'scipy', 'matplotlib') if m in sys.modules))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout
    assert out.strip() == "[]"


def test_nothing_refers_outside_the_repository():
    needles = ("../" + "shared", "/work/" + "shared", "/work/" + "main", "/work/" + "wt")
    offenders = []
    for folder in ("src", "tests", "docs", "benchmarks", "examples"):
        for path in (ROOT / folder).rglob("*"):
            if path.is_file() and path.suffix in {".py", ".md", ".toml", ".rst", ".txt", ".j2"}:
                text = path.read_text(encoding="utf-8", errors="replace")
                offenders += [f"{path.relative_to(ROOT)}: {n}" for n in needles if n in text]
    assert offenders == [], offenders


def test_no_public_signature_names_a_time_step_otherwise_than_sample_period_s():
    offenders = []
    for path in (ROOT / "src" / "sloshkit").rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.FunctionDef) and not node.name.startswith("_"):
                arguments = node.args.args + node.args.kwonlyargs
                offenders += [
                    f"{path.relative_to(ROOT)}:{node.lineno} {node.name}({a.arg})"
                    for a in arguments
                    if a.arg in TIME_STEP_ALIASES
                ]
    assert offenders == [], offenders
