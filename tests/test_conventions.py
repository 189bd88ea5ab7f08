"""The written conventions (docs/conventions.md) that can be checked mechanically."""

from __future__ import annotations

import ast
import importlib
import inspect
import pkgutil
import subprocess
import sys
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


def _command_callbacks() -> set[object]:
    """The functions typer runs for a command: the CLI is documented by ``--help`` instead."""
    from sloshkit.cli import load_commands

    callbacks: set[object] = set()
    groups = [load_commands()]
    while groups:
        group = groups.pop()
        callbacks.update(c.callback for c in group.registered_commands)
        callbacks.update(
            g.typer_instance.registered_callback.callback
            for g in group.registered_groups
            if g.typer_instance.registered_callback
        )
        groups.extend(g.typer_instance for g in group.registered_groups)
    return callbacks


def _all_modules() -> list[str]:
    modules = sorted(m.name for m in pkgutil.walk_packages(sloshkit.__path__, "sloshkit."))
    return [*modules, "sloshkit"]


def _module_callables() -> list[tuple[str, object]]:
    """Every public module-level function and class of sloshkit, where it is defined."""
    exempt = _command_callbacks()
    found = []
    for module_name in _all_modules():
        module = importlib.import_module(module_name)
        for name, obj in vars(module).items():
            if name.startswith("_") or getattr(obj, "__module__", None) != module_name:
                continue
            if (inspect.isfunction(obj) or inspect.isclass(obj)) and obj not in exempt:
                found.append((f"{module_name}.{name}", obj))
    return found


def _returns_something(obj: object) -> bool:
    if inspect.isclass(obj):
        return False
    annotation = inspect.signature(obj).return_annotation  # type: ignore[arg-type]
    return annotation not in (None, "None", "NoReturn", "typing.NoReturn", inspect.Signature.empty)


def _docstring_problems(obj: object) -> list[str]:
    doc = NumpyDocString(inspect.getdoc(obj) or "")
    problems = []
    if not doc["Summary"]:
        problems.append("no summary line")
    try:
        parameters = [p for p in inspect.signature(obj).parameters if p not in ("self", "cls")]  # type: ignore[arg-type]
    except ValueError:  # no signature (a builtin-backed class)
        parameters = []
    if getattr(obj, "_is_protocol", False):
        parameters = []  # a protocol is never constructed: its members are its documentation
    missing = [p for p in parameters if p not in _documented(doc)]
    if missing:
        problems.append(f"undocumented parameters {missing}")
    if _returns_something(obj) and not (doc["Returns"] or doc["Yields"]):
        problems.append("no Returns section")
    examples = "\n".join(doc["Examples"])
    if ">>>" not in examples:
        problems.append("no Examples section with a doctest")
    if "+SKIP" in examples:
        problems.append("an Examples section that is skipped")
    return problems


@pytest.mark.parametrize(("name", "obj"), _module_callables())
def test_every_public_definition_is_documented(name, obj):
    problems = _docstring_problems(obj)
    assert not problems, f"{name}: {'; '.join(problems)}"


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
    for folder in ("src", "tests", "docs", "benchmarks", "examples", "studies", "validation"):
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
