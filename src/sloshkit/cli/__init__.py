"""The ``sloshkit`` command line (typer + rich): thin commands over the library.

`sloshkit.cli.app` holds the typer application and `main`; each command group is a module that
registers its commands on import (imported here in the order of ``sloshkit --help``);
`sloshkit.cli.options` and `sloshkit.cli.moves` hold the option groups shared by commands.
"""
# isort: skip_file

from sloshkit.cli import model as model
from sloshkit.cli import simulate as simulate
from sloshkit.cli import sweep as sweep
from sloshkit.cli import calibrate as calibrate
from sloshkit.cli import plan as plan
from sloshkit.cli import export as export
from sloshkit.cli import report as report
from sloshkit.cli import cfd as cfd
from sloshkit.cli import cfd_sweep as cfd_sweep
from sloshkit.cli.app import app, main

__all__ = ["app", "main"]
