"""One source for each convention (docs/conventions.md): the grid rule, the gravity constant,
and private names that stay inside their module. Each check reads the source with `ast`, so a
copy written differently (spacing, names, line breaks) is still found, and a docstring or an
example that quotes the expression is not."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "src" / "sloshkit"


def modules() -> dict[str, ast.Module]:
    """Every module of src/sloshkit, by its path relative to the package."""
    return {
        path.relative_to(PACKAGE).as_posix(): ast.parse(path.read_text(encoding="utf-8"))
        for path in sorted(PACKAGE.rglob("*.py"))
    }


def grid_rule_copies(tree: ast.Module) -> list[int]:
    """Lines of ``ceil(a / b - eps)`` with a small float ``eps``: the grid rule written out."""
    lines = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        name = node.func.attr if isinstance(node.func, ast.Attribute) else ""
        name = name or (node.func.id if isinstance(node.func, ast.Name) else "")
        if name != "ceil":
            continue
        for inner in ast.walk(node):
            if (
                isinstance(inner, ast.BinOp)
                and isinstance(inner.op, ast.Sub)
                and isinstance(inner.right, ast.Constant)
                and isinstance(inner.right.value, float)
                and 0.0 < inner.right.value < 1e-6
            ):
                lines.append(node.lineno)
    return lines


def test_only_motion_sampling_writes_the_grid_rule():
    # The profile mesher counts pieces of at most one spacing with the same rounding; model/
    # sits below motion/ and cannot call it, and these are lengths, not the time grid.
    mesh_counts = {"model/axisymmetric.py", "model/profile.py"}
    allowed = {"motion/sampling.py"} | mesh_counts
    copies = [
        f"{name}:{line}"
        for name, tree in modules().items()
        if name not in allowed
        for line in grid_rule_copies(tree)
    ]
    assert copies == [], f"call sloshkit.motion.sampling.steps_to_reach instead: {copies}"


def scripts() -> dict[str, ast.Module]:
    """Every script of benchmarks/, validation/ and studies/, by its path from the root."""
    found = {
        path.relative_to(ROOT).as_posix(): ast.parse(path.read_text(encoding="utf-8"))
        for folder in ("benchmarks", "validation", "studies")
        for path in sorted((ROOT / folder).rglob("*.py"))
    }
    assert found, "the script folders are empty: the checks would pass on nothing"
    return found


def test_no_benchmark_validation_or_study_script_writes_the_grid_rule():
    copies = [
        f"{name}:{line}" for name, tree in scripts().items() for line in grid_rule_copies(tree)
    ]
    assert copies == [], f"call sloshkit.motion.sampling.steps_to_reach instead: {copies}"


def test_the_grid_rule_finder_finds_a_copy_and_not_a_quote():
    copy = ast.parse("import math\nn = math.ceil(duration / period - 1e-9)\n")
    quote = ast.parse('"""ceil(T / Ts - 1e-9)"""\nn = math.ceil(x / y)\n')
    assert grid_rule_copies(copy) == [2] and grid_rule_copies(quote) == []


#: Standard gravity and its usual rounding [m/s^2]: a module that writes either number writes
#: its own gravity constant.
GRAVITY_VALUES = {9.81, 9.80665, 9.8}


def gravity_literals(tree: ast.Module) -> list[int]:
    """Lines where a number equal to a value of `GRAVITY_VALUES` is written (not in strings)."""
    return sorted(
        node.lineno
        for node in ast.walk(tree)
        if isinstance(node, ast.Constant)
        and isinstance(node.value, float)
        and node.value in GRAVITY_VALUES
    )


def test_only_model_theory_writes_the_gravity_constant():
    allowed = {"model/theory.py"}  # GRAVITY_M_S2, the one constant
    literals = [
        f"{name}:{line}"
        for name, tree in modules().items()
        if name not in allowed
        for line in gravity_literals(tree)
    ]
    assert literals == [], f"import sloshkit.model.theory.GRAVITY_M_S2 instead: {literals}"


def test_no_benchmark_validation_or_study_script_writes_a_gravity_constant():
    literals = [
        f"{name}:{line}" for name, tree in scripts().items() for line in gravity_literals(tree)
    ]
    assert literals == [], f"import sloshkit.model.theory.GRAVITY_M_S2 instead: {literals}"


def test_no_module_quotes_standard_gravity():
    # 9.80665 is not the project's g (GRAVITY_M_S2 = 9.81): a docstring, comment or example
    # that writes it describes a second constant.
    quoted = [
        f"{path.relative_to(PACKAGE).as_posix()}:{number}"
        for path in sorted(PACKAGE.rglob("*.py"))
        if path.relative_to(PACKAGE).as_posix() != "model/theory.py"
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
        if "9.80665" in line
    ]
    assert quoted == [], f"the project's g is sloshkit.model.theory.GRAVITY_M_S2: {quoted}"


def test_the_gravity_finder_finds_a_literal_and_not_a_quote():
    literal = ast.parse("import numpy as np\nG = np.array([0.0, 0.0, -9.80665])\ng = 9.81\n")
    quote = ast.parse('"""g = 9.81 m/s^2"""\nx = 9.8101\n')
    assert gravity_literals(literal) == [2, 3] and gravity_literals(quote) == []


def private_imports(tree: ast.Module) -> list[tuple[str, str]]:
    """(module, name) of every ``from sloshkit... import _name`` (dunder names excepted)."""
    return [
        (node.module, alias.name)
        for node in ast.walk(tree)
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("sloshkit")
        for alias in node.names
        if alias.name.startswith("_") and not alias.name.startswith("__")
    ]


def test_no_module_imports_a_private_name_of_another():
    found = {
        (name, module, private)
        for name, tree in modules().items()
        for module, private in private_imports(tree)
    }
    assert sorted(found) == [], "make the name public or keep it inside"


def test_no_test_imports_a_private_name_of_the_package():
    """The tests use the package's public names (white-box tests too: what they need of a
    module is part of its documented interface)."""
    tests = Path(__file__).resolve().parent
    found = {
        (str(path.relative_to(tests)), module, private)
        for path in sorted(tests.rglob("*.py"))
        for module, private in private_imports(ast.parse(path.read_text(encoding="utf-8")))
    }
    assert sorted(found) == [], "use (or make) a public name"


def pose_column_copies(tree: ast.Module, names: tuple[str, ...]) -> list[int]:
    """Lines of a tuple or list of string constants equal to ``names``."""
    return [
        node.lineno
        for node in ast.walk(tree)
        if isinstance(node, ast.Tuple | ast.List)
        and all(isinstance(e, ast.Constant) and isinstance(e.value, str) for e in node.elts)
        and tuple(e.value for e in node.elts) == names  # type: ignore[attr-defined]
    ]


def test_the_pose_file_columns_are_written_once():
    from sloshkit.motion.poses import POSE_COLUMNS, PoseTrajectory

    poses = PoseTrajectory([0.0, 1.0], [[0, 0, 0], [1, 2, 3]], [[0, 0, 0, 1.0], [0, 0, 0, 1.0]])
    assert tuple(poses.columns()) == POSE_COLUMNS == ("t", "x", "y", "z", "qx", "qy", "qz", "qw")
    assert poses.columns()["z"].tolist() == [0.0, 3.0]
    copies = [
        f"{name}:{line}"
        for name, tree in modules().items()
        if name != "motion/poses.py"
        for line in pose_column_copies(tree, POSE_COLUMNS)
    ]
    assert copies == [], f"import sloshkit.motion.poses.POSE_COLUMNS instead: {copies}"
    copy = ast.parse('COLUMNS = ("t", "x", "y", "z", "qx", "qy", "qz", "qw")\n')
    assert pose_column_copies(copy, POSE_COLUMNS) == [1]
