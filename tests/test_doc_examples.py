"""The shell examples of README.md, docs/commands.md and docs/how-do-i.md run as written.

Each document's ``sh`` blocks run in order, in one fresh working folder that holds only a copy
of ``examples/`` (the files the examples name), with the installed ``sloshkit`` entry point:
every command must exit 0, and one with ``--json`` must print one JSON object. Lines that set
up the machine (``make``, ``python3 -m venv``, ``source``, ``apt-get``) and the OpenFOAM runs
(``sloshkit cfd``, ``--cfd``: minutes of CFD, covered by tests/cfd) are not run here, and
neither is a command that an earlier document of `DOCUMENTS` runs as written (docs/commands.md
repeats most of the README's): it is tested there, and a later command that needs its files
fails here, naming them.
"""

from __future__ import annotations

import json
import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCUMENTS = ["README.md", "docs/commands.md", "docs/how-do-i.md"]
NOT_RUN = ("make ", "python3 -m venv", "source ", "apt-get ", "sloshkit cfd ")


def shell_commands(document: Path) -> list[str]:
    """The commands of the document's ``sh`` blocks, continuation lines joined."""
    commands = []
    for block in re.findall(r"```sh\n(.*?)```", document.read_text(encoding="utf-8"), re.S):
        for command in block.replace("\\\n", " ").splitlines():
            if command.strip() and not command.lstrip().startswith("#"):
                commands.append(command.strip())
    return commands


def runnable(command: str) -> bool:
    return not command.startswith(NOT_RUN) and "--cfd" not in command.split("#")[0]


def entry_point() -> str:
    beside = Path(sys.executable).with_name("sloshkit")
    return str(beside) if beside.exists() else shutil.which("sloshkit") or "sloshkit"


def test_every_document_has_examples_and_names_only_shipped_files():
    for name in DOCUMENTS:
        commands = [c for c in shell_commands(ROOT / name) if runnable(c)]
        assert len(commands) >= 5, name
        for command in commands:
            for word in shlex.split(command, comments=True):
                path = word.split(":", 1)[1] if word.startswith("file:") else word
                if path.startswith("examples/"):
                    assert (ROOT / path).is_file(), f"{name}: {path} is not shipped"


@pytest.mark.slow
@pytest.mark.parametrize("name", DOCUMENTS)
def test_shell_examples_run_as_written(name, tmp_path):
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    env = {**os.environ, "COLUMNS": "120"}
    env.pop("SLOSHKIT_MAX_MEMORY", None)
    earlier = {c for d in DOCUMENTS[: DOCUMENTS.index(name)] for c in shell_commands(ROOT / d)}
    for command in shell_commands(ROOT / name):
        if not runnable(command) or command in earlier:
            continue
        words = shlex.split(command, comments=True)
        if words[0] == "sloshkit":
            words[0] = entry_point()
        result = subprocess.run(
            words, cwd=tmp_path, capture_output=True, text=True, timeout=900, env=env
        )
        assert result.returncode == 0, f"{command}\n{result.stderr[-3000:]}"
        assert "Traceback" not in result.stderr, command
        if "--json" in words:
            payload = json.loads(result.stdout)
            assert isinstance(payload.get("warnings"), list), command
