"""Report sections about the model: the equivalent model against the paper's Table 3, and the
calibration (measured, CFD or the paper's Table 4)."""

from __future__ import annotations

import math
import typing
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from sloshkit.calibration import calibrate, zeta_from_log_decrement
from sloshkit.errors import InputError
from sloshkit.io.scenario import Scenario
from sloshkit.io.tables import base_name, read_table, select_column, unit_from_name
from sloshkit.io.units import parse_quantity
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import SloshModel, equivalent_model
from sloshkit.plotting import plot_free_response
from sloshkit.report.cfd_reference import shipped_cfd_free_decay
from sloshkit.report.paper import PAPER_TABLE3, PAPER_TABLE4
from sloshkit.report.writer import ReportWriter, recorded_warnings, render


def _model_section(writer: ReportWriter, scenario: Scenario, model: SloshModel) -> None:
    """The model every later section uses (``model``: the scenario's, or calibrated), with
    where its damping comes from; the paper's Table 3 beside the scenario's theory."""
    rows = [
        {
            "mode": mode.n,
            "omega [rad/s]": mode.omega_rad_s,
            "f [Hz]": mode.frequency_hz,
            "slosh mass [g]": 1e3 * mode.slosh_mass_kg,
            "length [mm]": 1e3 * mode.length_m,
            "pivot from bottom [mm]": 1e3 * mode.pivot_height_m,
            "bob from bottom [mm]": 1e3 * mode.bob_height_m,
            "k [N/m]": mode.stiffness_n_m,
            "zeta": mode.damping_ratio,
            "c [N s/m]": mode.damping_coefficient_n_s_m,
        }
        for mode in model.modes
    ]
    first = model.modes[0]
    writer.facts["model"] = {
        "omega_rad_s": first.omega_rad_s,
        "frequency_hz": first.frequency_hz,
        "slosh_mass_g": 1e3 * first.slosh_mass_kg,
        "length_mm": 1e3 * first.length_m,
        "damping_ratio": first.damping_ratio,
        "damping_source": _damping_source(model, scenario),
        "liquid": model.liquid.name,
    }
    model_table = writer.table("model", rows, "Equivalent pendulum model", {"mode": "d"})
    warnings = writer.warning_note("Equivalent model", _model_warnings(model), "about the model")
    table3 = (
        writer.table(
            "table3_comparison",
            _table3_rows(scenario.model),
            "The paper's Table 3 beside sloshkit",
        )
        if scenario.paper_comparison
        else None
    )
    body = render(
        "sections/model.html.j2",
        model=model,
        damping_source=writer.facts["model"]["damping_source"],
        calibrated=model is not scenario.model,
        table3_zeta=scenario.model.modes[0].damping_ratio,
        asterisk=_asterisk_note(model),
        model_table=model_table,
        warnings=warnings,
        table3=table3,
    )
    writer.section("Equivalent model", body)


def _damping_source(model: SloshModel, scenario: Scenario) -> str:
    """Where the damping ratio of ``model`` comes from, in words (calibration, the scenario or
    a correlation)."""
    calibrated = model.provenance.get("damping_ratio_1")
    if calibrated:
        return calibrated
    given = model.provenance.get("damping_ratio", "")
    if given == "user":
        if scenario.paper_comparison:
            return "the paper's Table 3, as the scenario gives it"
        return "the scenario's [model] damping_ratio"
    return given or "the model"


def _model_warnings(model: SloshModel) -> list[str]:
    """The validity warnings of the model's own inputs (Bond number, shallow fill, damping
    correlation), raised again here because the scenario built the model before the report."""
    from sloshkit.model.theory import DAMPING_LAWS

    law = model.damping_law if model.damping_law in DAMPING_LAWS else "seed"
    user_zeta = law != model.damping_law or model.provenance.get("damping_ratio", "") == "user"
    with recorded_warnings() as found:
        equivalent_model(
            model.container,
            model.liquid,
            model.fill_height_m,
            n_modes=len(model.modes),
            damping_law=typing.cast(typing.Any, law),
            damping_ratio=model.modes[0].damping_ratio if user_zeta else None,
            # None: the default, so an automatic correction says so again (the Bond number does
            # not depend on the fill height); False: a correction the scenario turned off.
            surface_tension=None if model.surface_tension_correction else False,
            gravity_m_s2=model.gravity_m_s2,
        )
    return found


def _asterisk_note(model: SloshModel) -> dict[str, Any] | None:
    """What the ``*`` of a preset liquid whose properties the scenario overrides means: the
    preset's name (None when it is unknown) and the changes (None without a ``*``)."""
    if not model.liquid.name.endswith("*"):
        return None
    try:
        base = get_liquid(model.liquid.name.rstrip("*"))
    except InputError:
        return {"preset": None, "changes": []}
    changed = [
        f"{label} {new:g} {unit} instead of the preset's {old:g}"
        for label, unit, old, new in (
            ("ρ =", "kg/m³", base.density_kg_m3, model.liquid.density_kg_m3),
            ("μ =", "Pa·s", base.viscosity_pa_s, model.liquid.viscosity_pa_s),
            ("σ =", "N/m", base.surface_tension_n_m, model.liquid.surface_tension_n_m),
        )
        if not math.isclose(old, new)
    ]
    return {"preset": base.name, "changes": changed}


def _table3_rows(model: SloshModel) -> list[dict[str, Any]]:
    mode = model.modes[0]
    cg = model.cg_height_m
    paper = PAPER_TABLE3
    return [
        {
            "quantity": "natural pulsation ω₁ [rad/s]",
            "paper": paper["omega"],
            "sloshkit": mode.omega_rad_s,
            "explanation": "eq. 1; agrees",
        },
        {
            "quantity": "pendulum length L₁ [m]",
            "paper": paper["length"],
            "sloshkit": mode.length_m,
            "explanation": "eq. 9; agrees",
        },
        {
            "quantity": "slosh mass m₁ [kg]",
            "paper": paper["slosh_mass"],
            "sloshkit": mode.slosh_mass_kg,
            "explanation": "eq. 8 with ρ = 1000 gives 0.01228; no stated input gives 0.0132",
        },
        {
            "quantity": "stiffness k₁ [N/m]",
            "paper": paper["stiffness"],
            "sloshkit": mode.stiffness_n_m,
            "explanation": "m₁ω₁²; the paper's own 0.0132·29.7² is 11.6, not 11.3",
        },
        {
            "quantity": "damping coefficient σ [N s/m]",
            "paper": paper["damping_coefficient"],
            "sloshkit": mode.damping_coefficient_n_s_m,
            "explanation": f"2ζm₁ω₁ with the paper's ζ = {mode.damping_ratio:.3g} and our m₁",
        },
        {
            "quantity": "'hinge location' [m]",
            "paper": paper["hinge"],
            "sloshkit": mode.bob_height_m - cg,
            "explanation": f"this is the bob below the liquid CG; the pivot is {mode.pivot_height_m - cg:+.4f} m",
        },
        {
            "quantity": "'damping rate for first mode'",
            "paper": paper["damping_rate"],
            "sloshkit": mode.bessel_root,
            "explanation": "the first root ξ₁ of J₁′, mislabelled in the paper",
        },
    ]


@dataclass(frozen=True)
class _Calibration:
    """What the calibration found: its result (None without data), where the record came from
    (``cfd``, ``data``, ``shipped`` or ""), its warnings, the values its text quotes and the
    model every later section uses."""

    model: SloshModel
    result: Any | None = None
    source: str = ""
    found: list[str] = field(default_factory=list)
    values: dict[str, Any] = field(default_factory=dict)


def _calibrate(scenario: Scenario, cfd_result: Any | None) -> _Calibration:
    """Calibrate from the scenario's data file, from CFD, or (paper) demonstrate on the shipped
    CFD free decay. A CFD or data calibration replaces the model's omega_1 and damping for the
    whole report (its model table and summary included); the demonstration keeps the model."""
    model = scenario.model
    if cfd_result is not None:
        found = list(getattr(cfd_result, "warnings", ()))
        return _Calibration(cfd_result.calibrated_model(model), cfd_result, "cfd", found)
    if scenario.calibrate:
        options = scenario.calibrate
        header, table = read_table(options["data"])
        scale = parse_quantity(f"1 {options['time_unit']}", "time", "time_unit")
        with recorded_warnings() as found:
            result = calibrate(
                select_column(header, table, options["time_column"], "time_column") * scale,
                select_column(header, table, options["signal_column"], "signal_column"),
                method=options["method"],
                start_s=options["start"],
                end_s=options["end"],
                source=str(options["data"]),
            )
        values: dict[str, Any] = {"data_file": str(options["data"])}
        return _Calibration(result.calibrated_model(model), result, "data", found, values)
    if scenario.paper_comparison:
        delta = PAPER_TABLE4["log_decrement"]
        time_s, elevation_m, record = shipped_cfd_free_decay()
        with recorded_warnings() as found:
            result = calibrate(time_s, elevation_m, source="sloshkit CFD free decay (shipped)")
        quoted = {"paper_delta": delta, "paper_zeta": zeta_from_log_decrement(delta)}
        return _Calibration(model, result, "shipped", found, {**quoted, "record": record})
    return _Calibration(model)


def _calibration_section(writer: ReportWriter, scenario: Scenario, found_: _Calibration) -> None:
    """The calibration section: the estimators against theory and the paper's Table 4, the
    fit's intervals and the figures."""
    model = scenario.model
    result, source, found, values = found_.result, found_.source, found_.found, found_.values
    shipped = source == "shipped"
    if result is None:
        writer.section(
            "Calibration",
            render(
                "sections/no_calibration.html.j2",
                damping_source=model.provenance.get("damping_ratio", "its correlation"),
            ),
        )
        return
    payload = result.to_dict()
    rows = []
    for name, estimate in payload["estimates"].items():
        rows.append(
            {
                "estimator": name + (" (reported)" if name == result.method else ""),
                "omega_n [rad/s]": estimate["omega_n_rad_s"],
                "f_n [Hz]": estimate["frequency_hz"],
                "zeta": estimate["damping_ratio"],
                "log decrement": estimate["log_decrement"],
            }
        )
    first = model.modes[0]
    rows.append(
        {
            "estimator": "equivalent model (theory)",
            "omega_n [rad/s]": first.omega_rad_s,
            "f_n [Hz]": first.frequency_hz,
            # A calibration replaces the damping everywhere: the scenario's is not shown again.
            "zeta": first.damping_ratio if found_.model is model else None,
            "log decrement": None,
        }
    )
    if shipped:
        rows = [
            {**row, "estimator": "sloshkit CFD: " + str(row["estimator"])}
            if row["estimator"] != "equivalent model (theory)"
            else row
            for row in rows
        ]
    if scenario.paper_comparison:
        rows.append(
            {
                "estimator": "paper Table 4, CFD",
                "omega_n [rad/s]": PAPER_TABLE4["cfd_omega"],
                "f_n [Hz]": PAPER_TABLE4["cfd_f"],
                "zeta": PAPER_TABLE4["cfd_zeta"],
                "log decrement": PAPER_TABLE4["log_decrement"],
            }
        )
        rows.append(
            {
                "estimator": "paper Table 4, multibody",
                "omega_n [rad/s]": PAPER_TABLE4["mb_omega"],
                "f_n [Hz]": PAPER_TABLE4["mb_f"],
                "zeta": PAPER_TABLE4["mb_zeta"],
                "log decrement": None,
            }
        )
    estimates_table = writer.table(
        "table4_calibration", rows, "Frequency and damping (the paper's Table 4)"
    )
    table4 = _table4_comment(first.omega_rad_s) if scenario.paper_comparison else None
    warnings = writer.warning_note("Calibration", found, "about the estimates above")
    intervals = None
    if payload["omega_n_interval_rad_s"]:
        intervals = {
            "omega": payload["omega_n_interval_rad_s"],
            "zeta": payload["damping_ratio_interval"],
            "window": payload["window_s"],
            "peaks": payload["n_peaks"],
        }
    label = (
        "wall elevation (detrended) [m]"
        if source != "data"
        else _signal_label(str(scenario.calibrate["signal_column"]))
    )
    figures = [
        writer.figure(
            "fig5b_calibration",
            result.plot(None, signal_label=label),
            "Free decay, detected peaks and fitted envelope (the paper's Fig. 5b)",
        )
    ]
    if source == "cfd" or shipped:
        figures.append(
            writer.figure(
                "fig9_cfd_vs_model",
                _free_response_figure(result, model),
                "CFD free decay against the equivalent pendulum (linear-theory frequency, the "
                "CFD's damping, started from the CFD's amplitude and phase): the paper's Fig. 9",
            )
        )
    body = render(
        "sections/calibration.html.j2",
        source=source,
        estimates_table=estimates_table,
        table4=table4,
        warnings=warnings,
        intervals=intervals,
        figures=figures,
        calibrated_zeta=found_.model.modes[0].damping_ratio,
        **values,
    )
    writer.section("Calibration", body)


def _signal_label(column: str) -> str:
    """Axis label of a recorded signal: its name and the unit its header gives."""
    unit = unit_from_name(column)
    name = base_name(column) if unit else column
    return f"{name} (detrended) [{unit or 'unit of the record'}]"


def _table4_comment(theory_omega_rad_s: float) -> dict[str, float]:
    """The numbers behind the note on the paper's Table 4, which disagrees with itself."""
    table = PAPER_TABLE4
    return {
        **table,
        "mb_f_from_omega": table["mb_omega"] / (2 * math.pi),
        "mb_omega_from_f": 2 * math.pi * table["mb_f"],
        "cfd_f_from_omega": table["cfd_omega"] / (2 * math.pi),
        "below_theory_percent": 100 * (1 - table["cfd_omega"] / theory_omega_rad_s),
        "theory_omega": theory_omega_rad_s,
        "zeta_from_delta": zeta_from_log_decrement(table["log_decrement"]),
    }


def _free_response_figure(result: Any, model: SloshModel) -> Any:
    """The CFD signal and the pendulum's free response with matched amplitude and phase."""
    t = result.signal.time_s - result.signal.time_s[0]
    y = result.signal.values
    mode = model.modes[0]
    zeta = result.damping_ratio if result.damping_ratio is not None else mode.damping_ratio
    damped = mode.omega_rad_s * math.sqrt(1 - zeta**2)
    envelope = np.exp(-zeta * mode.omega_rad_s * t)
    design = np.column_stack((envelope * np.cos(damped * t), envelope * np.sin(damped * t)))
    coefficients, *_ = np.linalg.lstsq(design, y, rcond=None)
    return plot_free_response(
        result.signal.time_s,
        y,
        design @ coefficients,
        f"pendulum: f = {mode.frequency_hz:.3f} Hz (theory), ζ = {zeta:.4f}",
    )


def write_model_sections(
    writer: ReportWriter,
    scenario: Scenario,
    cfd_calibration: Any | None = None,
    progress: Callable[[str], None] | None = None,
) -> SloshModel:
    """Write the scenario's model and calibration sections; return the model every later
    section uses (a CFD or data calibration replaces omega_1 and the damping for the whole
    report, its model table and summary included).

    Parameters
    ----------
    writer : ReportWriter
        The report being written.
    scenario : Scenario
        The scenario (its ``analyses`` choose the sections).
    cfd_calibration : object, optional
        A CFD result that calibrates the model (``reproduce --cfd``).
    progress : callable, optional
        Called with the name of each section as it starts.

    Returns
    -------
    SloshModel
        The scenario's model, or the calibrated one.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from sloshkit.io.scenario import parse_scenario
    >>> scenario = parse_scenario({"name": "vial", "analyses": ["model"],
    ...                            "container": {"radius": "20.5mm"}, "fill": {"height": "39mm"},
    ...                            "move": {"distance": "0.2m", "duration": "1s"}})
    >>> writer = ReportWriter(pathlib.Path(tempfile.mkdtemp()))
    >>> write_model_sections(writer, scenario, progress=print) is scenario.model
    equivalent model
    True
    """
    say = progress or (lambda _: None)
    model = scenario.model
    calibration = None
    if "calibrate" in scenario.analyses or "cfd" in scenario.analyses:
        say("calibration")
        calibration = _calibrate(scenario, cfd_calibration)
        model = calibration.model
    if "model" in scenario.analyses:
        say("equivalent model")
        _model_section(writer, scenario, model)
    if calibration is not None:
        _calibration_section(writer, scenario, calibration)
    return model
