"""The first HiGHS solver of a process is created without printing HiGHS's banner on stdout
(HiGHS 1.16 prints it from inside the constructor, before any option can silence it)."""

from __future__ import annotations

import subprocess
import sys


def test_new_highs_prints_nothing_on_stdout():
    code = "from sloshkit.highs import new_highs\nnew_highs(); new_highs()\nprint('done')\n"
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True
    )
    assert result.stdout == "done\n"
    assert "HiGHS" not in result.stderr
