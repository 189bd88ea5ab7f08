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
        " 'pydantic', 'sloshkit.cli.plan', 'sloshkit.cli.cfd') if m in sys.modules]\n"
        "print('HEAVY', heavy)\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=120
    )
    assert "HEAVY []" in result.stdout, result.stdout[-500:]
    assert "omega" in result.stdout


def test_the_readme_1d_plan_imports_neither_scipy_nor_numba():
    """The paper's 1-D plan (the startup benchmark's row, issue 24: under 1 s wall) runs on
    numpy and HiGHS alone: motions, screens, the EI shaper and the programs need no scipy, and
    the screens no compiled kernel."""
    code = (
        "import sys; sys.argv = ['sloshkit', 'plan', '--distance', '0.5m', '--max-angle',"
        " '5deg', '--max-residual', '0.25deg', '--vmax', '1.5m/s', '--amax', '20m/s^2',"
        " '--jmax', '500m/s^3', '--json']\n"
        "from sloshkit.cli import main\n"
        "try:\n    main()\nexcept SystemExit:\n    pass\n"
        "heavy = [m for m in ('scipy', 'numba', 'casadi', 'matplotlib', 'pandas')"
        " if m in sys.modules]\n"
        "print('HEAVY', heavy)\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=300
    )
    assert "HEAVY []" in result.stdout, result.stdout[-500:]
    assert '"method": "optimal-smooth"' in result.stdout


def test_plot_registry_names_every_figure_and_a_sweep_imports_only_its_own():
    import importlib

    from sloshkit.plotting import load_all
    from sloshkit.results import PLOTS, registered_plotters

    load_all()
    plotters = registered_plotters()
    for name, target in PLOTS.items():
        module, _, klass = name.rpartition(".")
        result_type = getattr(importlib.import_module(module), klass)
        figure_module, _, function = target.partition(":")
        assert plotters[result_type] is getattr(importlib.import_module(figure_module), function)
    registered = {
        f"{k.__module__}.{k.__qualname__}" for k in plotters if k.__module__.startswith("sloshkit")
    }
    assert registered <= set(PLOTS), "add the new figure to sloshkit.results.PLOTS"
    code = (
        "import sys, sloshkit as sk\n"
        "m = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid('water-25C'), 0.039)\n"
        "sk.run_sweep(m, ['septic'], 0.1, [1.0, 2.0]).plot()\n"
        "print([n for n in ('sloshkit.plotting.calibration', 'scipy.signal', 'sloshkit.plan')"
        " if n in sys.modules])\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


@pytest.mark.parametrize("count", [1, 3, 10, 12])
def test_tabulated_bessel_zeros_equal_scipy(count):
    from scipy.special import jnp_zeros

    from sloshkit.model.theory import bessel_roots

    np.testing.assert_allclose(bessel_roots(count), jnp_zeros(1, count), rtol=1e-15)
