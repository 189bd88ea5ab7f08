"""docs/architecture.md names every module of src/sloshkit, and only modules that exist.

The doc's *Modules* section has one item per package (`- `model/`: ...`, the base modules
under `- `sloshkit/` ...`); the item names each module by its file stem in backticks, outside
any parentheses (the parentheses say what the module holds and may quote other names). A new
module adds `stem (what it holds)` to its package's item; a new package adds an item.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "src" / "sloshkit"
DOC = ROOT / "docs" / "architecture.md"

#: An item of the Modules list: "- `cfd/`: ..." or "- `sloshkit/` (...): ...", with its
#: indented continuation lines.
ITEM = re.compile(r"^- `([\w/]+/)`(.*(?:\n  .*)*)", re.MULTILINE)


def modules_section(text: str) -> str:
    """The text of the doc's *Modules* section (up to the next heading or "Around the package")."""
    start = text.index("\n## Modules\n")
    ends = (text.find("\n## ", start + 1), text.find("\nAround the package", start))
    end = min((i for i in ends if i > 0), default=len(text))
    return text[start:end]


def top_level(text: str) -> str:
    """`text` without anything inside parentheses (nested parentheses included)."""
    depth, kept = 0, []
    for char in text:
        if char == "(":
            depth += 1
        elif char == ")":
            depth = max(depth - 1, 0)
        elif depth == 0:
            kept.append(char)
    return "".join(kept)


def documented() -> dict[str, set[str]]:
    """Package path (relative to src/sloshkit, "" for the root) -> the module stems named."""
    items = {}
    for match in ITEM.finditer(modules_section(DOC.read_text(encoding="utf-8"))):
        package = match.group(1).rstrip("/")
        package = "" if package == "sloshkit" else package
        assert package not in items, f"architecture.md lists {package or 'sloshkit'}/ twice"
        items[package] = set(re.findall(r"`(\w+)`", top_level(match.group(2))))
    return items


def actual() -> dict[str, set[str]]:
    """Package path -> the stems of its modules (every .py but __init__), from the file tree."""
    packages = {}
    for init in PACKAGE.rglob("__init__.py"):
        folder = init.parent
        key = folder.relative_to(PACKAGE).as_posix()
        packages["" if key == "." else key] = {
            p.stem for p in folder.glob("*.py") if p.stem != "__init__"
        }
    return packages


def test_every_package_has_an_item_and_every_item_is_a_package():
    doc, tree = documented(), actual()
    assert sorted(set(tree) - set(doc)) == [], "packages missing from docs/architecture.md"
    assert sorted(set(doc) - set(tree)) == [], "docs/architecture.md lists packages that are gone"


def test_every_module_is_named_and_every_name_is_a_module():
    doc, tree = documented(), actual()
    missing = sorted(f"{p}/{m}" for p in tree for m in tree[p] - doc.get(p, set()))
    stale = sorted(f"{p}/{m}" for p in doc for m in doc[p] - tree.get(p, set()))
    assert missing == [], f"modules that docs/architecture.md does not name: {missing}"
    assert stale == [], f"docs/architecture.md names modules that do not exist: {stale}"


def test_a_name_inside_parentheses_does_not_count_one_on_a_continuation_line_does():
    text = "\n## Modules\n\n- `demo/`: `alpha` (holds `beta`), `gamma`\n  (more), `delta`\n\n## X\n"
    match = ITEM.search(modules_section(text))
    assert match is not None
    assert set(re.findall(r"`(\w+)`", top_level(match.group(2)))) == {"alpha", "gamma", "delta"}
