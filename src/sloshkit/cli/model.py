"""``sloshkit model``: the equivalent model of a container and liquid."""

from __future__ import annotations

from rich.table import Table
from rich.text import Text

from sloshkit.cli.app import app, stdout
from sloshkit.cli.options import Json, print_json, with_model_options
from sloshkit.model.modal import SloshModel


def model_table(model: SloshModel) -> Table:
    """A rich table of the equivalent model, with units."""
    table = Table(
        title=(
            f"Equivalent sloshing model: R = {1e3 * model.radius_m:.2f} mm, "
            f"h = {1e3 * model.fill_height_m:.2f} mm, {model.liquid.name} "
            f"(m_F = {1e3 * model.liquid_mass_kg:.2f} g, m_0 = {1e3 * model.rigid_mass_kg:.2f} g)"
        )
    )
    columns = [
        ("mode", "n"),
        ("ω [rad/s]", "{:.2f}"),
        ("f [Hz]", "{:.3f}"),
        ("m_n [g]", "{:.3f}"),
        ("L_n [mm]", "{:.3f}"),
        ("pivot [mm]", "{:.2f}"),
        ("bob [mm]", "{:.2f}"),
        ("bob − CG [mm]", "{:.2f}"),
        ("k_n [N/m]", "{:.3f}"),
        ("ζ [-]", "{:.4f}"),
        ("c_n [N·s/m]", "{:.2e}"),
    ]
    for header, _ in columns:
        table.add_column(Text(header), justify="right")
    for mode in model.modes:
        table.add_row(
            str(mode.n),
            f"{mode.omega_rad_s:.2f}",
            f"{mode.frequency_hz:.3f}",
            f"{1e3 * mode.slosh_mass_kg:.3f}",
            f"{1e3 * mode.length_m:.3f}",
            f"{1e3 * mode.pivot_height_m:.2f}",
            f"{1e3 * mode.bob_height_m:.2f}",
            f"{1e3 * (mode.bob_height_m - model.cg_height_m):.2f}",
            f"{mode.stiffness_n_m:.3f}",
            f"{mode.damping_ratio:.4f}",
            f"{mode.damping_coefficient_n_s_m:.2e}",
        )
    table.caption = "Heights from the container bottom; damping: " + model.provenance.get(
        "damping_ratio", model.damping_law
    )
    return table


@app.command()
@with_model_options
def model(slosh_model: SloshModel, json_output: Json = False) -> None:
    """Equivalent pendulum model of a filled upright cylinder.

    Defaults are the seed paper's vial (R 20.5 mm, h 39 mm, water at 25 °C).

    Examples:

      sloshkit model --radius 20.5mm --fill-height 39mm --liquid water-25C

      sloshkit model --radius 8mm --fill-volume 2mL --liquid glycerol-50wt-20C --json
    """
    if json_output:
        print_json(slosh_model.to_dict())
    else:
        stdout.print(model_table(slosh_model))
