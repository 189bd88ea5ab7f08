"""Start-up: the root help and the command table, lazy imports, tabulated constants."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest


def test_root_help_table_matches_the_commands_own_help():
    import typer.main

    from sloshkit.cli import COMMANDS, app

    group = typer.main.get_command(app)
    assert list(COMMANDS) == list(group.commands)  # same commands, same order
    for name, (module, short) in COMMANDS.items():
        command = group.commands[name]
        first_paragraph = " ".join((command.help or "").split("\n\n")[0].split())
        assert first_paragraph == short, f"{name}: update sloshkit.cli.COMMANDS"
        assert sys.modules[module] is not None


def test_root_help_imports_no_command_module_nor_scipy():
    code = (
        "import sys; sys.argv = ['sloshkit', '--help']\n"
        "from sloshkit.cli import main\n"
        "try:\n    main()\nexcept SystemExit:\n    pass\n"
        "heavy = [m for m in ('scipy', 'casadi', 'matplotlib', 'numba', 'pandas', 'pint',"
        " 'sloshkit.cli.model', 'sloshkit.cli.plan') if m in sys.modules]\n"
        "print('HEAVY', heavy)\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=120
    )
    assert "HEAVY []" in result.stdout, result.stdout[-500:]
    assert "Commands" in result.stdout


def test_model_command_imports_neither_scipy_nor_the_other_commands():
    code = (
        "import sys; sys.argv = ['sloshkit', 'model', '--json']\n"
        "from sloshkit.cli import main\n"
        "try:\n    main()\nexcept SystemExit:\n    pass\n"
        "heavy = [m for m in ('scipy.special', 'scipy.signal', 'scipy.interpolate',"
        " 'scipy.integrate', 'scipy.optimize', 'casadi', 'matplotlib', 'numba', 'pandas',"
        " 'sloshkit.cli.plan', 'sloshkit.cli.cfd') if m in sys.modules]\n"
        "print('HEAVY', heavy)\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=120
    )
    assert "HEAVY []" in result.stdout, result.stdout[-500:]
    assert "omega" in result.stdout


@pytest.mark.parametrize("count", [1, 3, 10, 12])
def test_tabulated_bessel_zeros_equal_scipy(count):
    from scipy.special import jnp_zeros

    from sloshkit.model.theory import bessel_roots

    np.testing.assert_allclose(bessel_roots(count), jnp_zeros(1, count), rtol=1e-15)
