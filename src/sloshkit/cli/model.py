"""``sloshkit model``: the equivalent model of a container and liquid."""

from __future__ import annotations

from collections.abc import Callable

from rich.table import Table
from rich.text import Text

from sloshkit.cli.app import app, stdout
from sloshkit.cli.options import Json, print_json, with_model_options
from sloshkit.model.modal import SloshMode, SloshModel
from sloshkit.model.profile import ProfileContainer


def model_table(model: SloshModel) -> Table:
    """A rich table of the equivalent model: one row per quantity (with its unit), one column
    per mode, so it fits 80 columns for any number of modes up to about five.

    Parameters
    ----------
    model : SloshModel
        The model.

    Returns
    -------
    rich.table.Table

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"), 0.039)
    >>> table = model_table(model)
    >>> len(table.columns), str(table.columns[1].header)
    (4, 'mode 1')
    """
    container = model.container
    named = f"{container.name}, surface " if isinstance(container, ProfileContainer) else ""
    table = Table(
        title=(
            f"Equivalent sloshing model: {named}R = {1e3 * model.radius_m:.2f} mm, "
            f"h = {1e3 * model.fill_height_m:.2f} mm, {model.liquid.name}"
        )
    )
    rows: list[tuple[str, Callable[[SloshMode], str]]] = [
        ("natural pulsation ω [rad/s]", lambda m: f"{m.omega_rad_s:.2f}"),
        ("frequency f [Hz]", lambda m: f"{m.frequency_hz:.3f}"),
        ("slosh mass m_n [g]", lambda m: f"{1e3 * m.slosh_mass_kg:.3f}"),
        ("pendulum length L_n [mm]", lambda m: f"{1e3 * m.length_m:.3f}"),
        ("pivot height [mm]", lambda m: f"{1e3 * m.pivot_height_m:.2f}"),
        ("bob height [mm]", lambda m: f"{1e3 * m.bob_height_m:.2f}"),
        ("bob − liquid CG [mm]", lambda m: f"{1e3 * (m.bob_height_m - model.cg_height_m):.2f}"),
        ("spring k_n [N/m]", lambda m: f"{m.stiffness_n_m:.4g}"),
        ("damping ratio ζ [-]", lambda m: f"{m.damping_ratio:.4f}"),
        ("damper c_n [N·s/m]", lambda m: f"{m.damping_coefficient_n_s_m:.3g}"),
    ]
    table.add_column(Text("quantity"))
    for mode in model.modes:
        table.add_column(Text(f"mode {mode.n}"), justify="right")
    for header, cell in rows:
        table.add_row(Text(header), *(cell(mode) for mode in model.modes))
    note = model.liquid.name.endswith("*")
    table.caption = (
        f"liquid mass m_F = {1e3 * model.liquid_mass_kg:.2f} g, rigid mass "
        f"m_0 = {1e3 * model.rigid_mass_kg:.2f} g; heights from the container bottom; damping: "
        + model.provenance.get("damping_ratio", model.damping_law)
        + ("; * = preset liquid with overridden properties" if note else "")
    )
    return table


@app.command()
@with_model_options
def model(slosh_model: SloshModel, json_output: Json = False) -> None:
    """Equivalent pendulum model of a filled upright cylinder or real container.

    A real container (--container from the catalogue, --profile for any axisymmetric inner
    profile) has its modes computed by finite elements; the cylinder keeps its closed form.

    Defaults are the seed paper's vial (R 20.5 mm, h 39 mm, water at 25 °C).

    Examples:

      sloshkit model --radius 20.5mm --fill-height 39mm --liquid water-25C

      sloshkit model --radius 8mm --fill-volume 2mL --liquid glycerol-50wt-20C --json

      sloshkit model --container iso8362-2R --fill-volume 1mL --json
    """
    if json_output:
        print_json(slosh_model.to_dict())
    else:
        stdout.print(model_table(slosh_model))
