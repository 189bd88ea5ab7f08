"""Every public function and class of `sloshkit.cfd` and of the ``cfd`` CLI modules has a
numpydoc docstring with Parameters (every parameter), Returns and Examples."""

from __future__ import annotations

import enum
import importlib
import inspect
import pkgutil

import pytest
from numpydoc.docscrape import NumpyDocString

import sloshkit.cfd

CLI_MODULES = ("sloshkit.cli.cfd", "sloshkit.cli.cfd_options", "sloshkit.cli.cfd_sweep")


def _modules() -> list[str]:
    names = [f"sloshkit.cfd.{info.name}" for info in pkgutil.iter_modules(sloshkit.cfd.__path__)]
    return ["sloshkit.cfd", *sorted(names), *CLI_MODULES]


def _public() -> list[tuple[str, object]]:
    found = []
    for module_name in _modules():
        module = importlib.import_module(module_name)
        for name, obj in vars(module).items():
            if name.startswith("_") or getattr(obj, "__module__", None) != module_name:
                continue
            if inspect.isfunction(obj) or inspect.isclass(obj):
                found.append((f"{module_name}.{name}", inspect.unwrap(obj)))
    return found


def _documented(doc: NumpyDocString) -> set[str]:
    names = set()
    for section in ("Parameters", "Other Parameters", "Attributes"):
        for parameter in doc[section]:
            names.update(part.strip().lstrip("*") for part in parameter.name.split(","))
    return names


def missing_sections(obj: object) -> list[str]:
    """What the docstring of ``obj`` lacks: undocumented parameters, Returns, Examples."""
    doc = NumpyDocString(inspect.getdoc(obj) or "")
    problems = []
    try:
        parameters = [p for p in inspect.signature(obj).parameters if p not in ("self", "cls")]
    except (TypeError, ValueError):
        parameters = []
    # Exceptions document their message, enumerations their members: only Examples needed.
    plain = isinstance(obj, type) and issubclass(obj, BaseException | enum.Enum)
    undocumented = [p for p in parameters if p not in _documented(doc)]
    if undocumented and not plain:
        problems.append(f"parameters {undocumented}")
    if not (doc["Returns"] or doc["Yields"] or plain):
        problems.append("Returns")
    if not doc["Examples"]:
        problems.append("Examples")
    return problems


@pytest.mark.parametrize(("name", "obj"), _public(), ids=lambda v: v if isinstance(v, str) else "")
def test_public_cfd_api_is_documented(name, obj):
    assert not missing_sections(obj), f"{name}: missing {missing_sections(obj)}"


def test_the_checker_fails_without_examples():
    def undocumented(case):
        """Something.

        Parameters
        ----------
        case : Path
            A case.

        Returns
        -------
        int
        """

    assert missing_sections(undocumented) == ["Examples"]
