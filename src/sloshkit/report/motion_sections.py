"""Report sections about motions: the laws compared (seed Figs. 7-9), slosh maps, the fastest
safe move."""

from __future__ import annotations

import math
import typing
from collections.abc import Callable

from sloshkit.files import write_columns_csv
from sloshkit.io.scenario import Scenario
from sloshkit.model.modal import SloshModel, model_family
from sloshkit.motion.laws import comparison_s_curve_limits, make_law
from sloshkit.plan.line.planner import plan
from sloshkit.plan.line.problem import MachineLimits, PlanProblem, SloshLimits
from sloshkit.plotting import plot_law_comparison, plot_slosh_comparison, plot_sweep_map
from sloshkit.report.writer import ReportWriter, recorded_warnings, render
from sloshkit.sim.simulate import LARGE_ANGLE_DEG, simulate
from sloshkit.sweep import linspace_inclusive, run_sweep

#: What the report calls the laws the paper names differently.
LAW_NOTES = {"septic": "septic (the paper's jerk-continuous law)"}


def law_label(name: str) -> str:
    """A law's name with the paper's name for it, e.g. ``septic (the paper's jerk-continuous
    law)``.

    Parameters
    ----------
    name : str
        The law's name in sloshkit.

    Returns
    -------
    str

    Examples
    --------
    >>> law_label("septic"), law_label("quintic")
    ("septic (the paper's jerk-continuous law)", 'quintic')
    """
    return LAW_NOTES.get(name, name)


def _best_paper_law(payload: dict[str, typing.Any]) -> tuple[str, float] | None:
    """The fastest feasible candidate among the paper's laws: (name, duration [s])."""
    from sloshkit.plan.line.problem import PAPER_LAWS

    feasible = [
        (c["method"], float(c["duration_s"]))
        for c in payload["candidates"]
        if c["feasible"] and c["method"] in PAPER_LAWS and c["duration_s"]
    ]
    return min(feasible, key=lambda item: item[1]) if feasible else None


def _collapsed_shortest(rows: list[dict[str, object]]) -> list[dict[str, object]]:
    """Consecutive fill heights with the same shortest safe duration and law as one row."""
    collapsed: list[dict[str, object]] = []
    for row in rows:
        height = 1e3 * float(typing.cast(float, row["fill_height_m"]))
        law = law_label(str(row["law"])) if row["law"] else "none"
        last = collapsed[-1] if collapsed else None
        if last and last["shortest safe duration [s]"] == row["duration_s"] and last["law"] == law:
            last["to fill height [mm]"] = height
            last["fill heights"] = typing.cast(int, last["fill heights"]) + 1
            continue
        collapsed.append(
            {
                "from fill height [mm]": height,
                "to fill height [mm]": height,
                "fill heights": 1,
                "shortest safe duration [s]": row["duration_s"],
                "law": law,
            }
        )
    return collapsed


def _compare_section(writer: ReportWriter, scenario: Scenario, model: SloshModel) -> None:

    motions = []
    for name in scenario.laws:
        vmax, amax, jmax = scenario.move_limits
        if name == "s-curve" and scenario.peak_velocity_m_s is not None:
            vmax, amax, jmax = comparison_s_curve_limits(
                scenario.distance_m, scenario.peak_velocity_m_s, vmax, amax, jmax
            )
        motions.append(
            make_law(
                name,
                scenario.distance_m,
                duration_s=scenario.duration_s,
                peak_velocity_m_s=scenario.peak_velocity_m_s,
                max_velocity_m_s=vmax,
                max_acceleration_m_s2=amax,
                max_jerk_m_s3=jmax,
            )
        )
    responses = []
    notes: list[str] = []
    for motion in motions:
        with recorded_warnings() as found:
            responses.append(simulate(model, motion))
        notes.extend(f"{law_label(motion.name)}: {message}" for message in found)
    rows = []
    for motion, response in zip(motions, responses, strict=True):
        metrics = response.metrics()
        rows.append(
            {
                "law": law_label(motion.name),
                "duration [s]": metrics["duration_s"],
                "peak acc. [m/s²]": metrics["peak_acceleration_m_s2"],
                "peak jerk [m/s³]": metrics["peak_jerk_m_s3"],
                "peak θ₁ [deg]": metrics["peak_angle_deg"],
                "residual θ₁ [deg]": metrics["residual_angle_deg"],
                "peak wall η [mm]": 1e3 * metrics["peak_wall_elevation_m"],
                "settling [s]": metrics["settling_time_s"],
            }
        )
    table = writer.table(
        "compare",
        rows,
        "Motion laws compared (peak values during the move; residual amplitude left at its end)",
    )
    warnings = writer.warning_note("Motion laws", notes, "about the table above")
    residual = {
        motion.name: response.metrics()["residual_angle_deg"]
        for motion, response in zip(motions, responses, strict=True)
    }
    ratio = None
    if "trapezoidal" in residual and "septic" in residual and residual["septic"] > 0:
        ratio = residual["trapezoidal"] / residual["septic"]
        writer.facts["residual_ratio_trapezoid_septic"] = ratio
    figures = [
        writer.figure(
            "fig7_laws",
            plot_law_comparison(motions, None),
            "Velocity, acceleration and jerk of each law (the paper's Fig. 7; septic = the "
            "paper's jerk-continuous law)",
        ),
        writer.figure(
            "fig8_slosh",
            plot_slosh_comparison(responses, None),
            "First-mode slosh angle and rate under each law (the paper's Figs. 8–9; septic = "
            "the paper's jerk-continuous law)",
        ),
    ]
    body = render(
        "sections/compare.html.j2",
        distance_m=scenario.distance_m,
        table=table,
        warnings=warnings,
        ratio=ratio,
        figures=figures,
    )
    writer.section("Motion laws", body)


def _sweep_section(writer: ReportWriter, scenario: Scenario, model: SloshModel) -> None:

    options = scenario.sweep
    heights = linspace_inclusive(*options["fill_height"])
    durations = linspace_inclusive(*options["duration"])
    # Every model option of the scenario reaches the maps: the report's one damping ratio, the
    # capillary correction as the scenario's model has it (the Bond number does not depend on
    # the fill height) and gravity.
    family = model_family(
        model.container,
        model.liquid,
        n_modes=len(model.modes),
        damping_ratio=model.modes[0].damping_ratio,
        surface_tension=model.surface_tension_correction,
        gravity_m_s2=model.gravity_m_s2,
    )

    def model_at(fill_height_m: float) -> SloshModel:
        # The scenario's (possibly calibrated) model at its own fill height, theory elsewhere.
        return model if math.isclose(fill_height_m, model.fill_height_m) else family(fill_height_m)

    with recorded_warnings() as found:
        result = run_sweep(
            model_at,
            list(options["laws"]),
            scenario.distance_m,
            durations,
            fill_heights_m=heights,
            max_angle_rad=scenario.plan_limits["max_angle"],
            max_residual_rad=scenario.plan_limits["max_residual"],
        )
    rows = _collapsed_shortest(result.shortest_safe())
    beyond = float((result.peak_angle_deg > LARGE_ANGLE_DEG).mean())
    if beyond > 0:
        found.append(
            f"{100 * beyond:.0f} % of the cases reach a peak slosh angle above {LARGE_ANGLE_DEG:g}° "
            f"(up to {float(result.peak_angle_deg.max()):.0f}°), where the linear model is not "
            "trustworthy: read those colours as 'far too much', not as values"
        )
    peak_map = writer.figure(
        "sweep_peak_map",
        plot_sweep_map(result, "peak_angle_deg", None),
        f"Peak slosh angle over fill height and duration (hatched: peak above "
        f"{result.max_angle_deg:g}°)",
    )
    warnings = writer.warning_note("Slosh maps", found, "about the maps")
    residual_map = writer.figure(
        "sweep_residual_map",
        plot_sweep_map(result, "residual_angle_deg", None),
        f"Residual slosh angle over fill height and duration (hatched: residual above "
        f"{result.max_residual_deg:g}°)",
    )
    table = writer.table(
        "sweep_shortest_safe",
        rows,
        "Shortest safe duration per fill height (fill heights with the same answer in one row)",
    )
    body = render(
        "sections/sweep.html.j2",
        result=result,
        peak_map=peak_map,
        warnings=warnings,
        residual_map=residual_map,
        table=table,
    )
    writer.section("Slosh maps", body)


def _plan_section(writer: ReportWriter, scenario: Scenario, model: SloshModel) -> None:

    limits = scenario.plan_limits
    problem = PlanProblem(
        scenario.distance_m,
        MachineLimits(limits["vmax"], limits["amax"], limits["jmax"]),
        SloshLimits(
            limits["max_angle"],
            limits["max_residual"],
            limits.get("max_wall_elevation"),
            limits.get("robust", 0.0),
        ),
        model,
        limits["sample_period"],
    )
    with recorded_warnings() as found:
        result = plan(problem, limits.get("method", "auto"))
    payload = result.to_dict()
    rows = [
        {
            "method": law_label(c["method"]),
            "duration [s]": c["duration_s"],
            "peak θ₁ [deg]": c["peak_angle_deg"],
            "residual θ₁ [deg]": c["residual_angle_deg"],
            "peak v [m/s]": c["peak_velocity_m_s"],
            "peak a [m/s²]": c["peak_acceleration_m_s2"],
            "peak j [m/s³]": c["peak_jerk_m_s3"],
            "verified": "yes" if c["feasible"] else "no",
            "compute [s]": c["compute_time_s"],
        }
        for c in payload["candidates"]
    ]
    chosen = None
    speed_up = None
    if result.feasible and result.chosen is not None:
        chosen = result.chosen
        speed_up = payload["speed_up_over_best_paper_law"]
        writer.facts["plan"] = {
            "method": result.chosen.method,
            "duration_s": result.chosen.duration_s,
            "speed_up": speed_up,
            "best_paper_law": _best_paper_law(payload),
        }
        write_columns_csv(
            writer.staging / "tables" / "fastest_move_trajectory.csv", result.samples()
        )
        writer.table_names.append("fastest_move_trajectory")
    table = writer.table("plan", rows, "Planner candidates")
    warnings = writer.warning_note("Fastest safe move", found, "about the planner's candidates")
    figure = (
        writer.figure(
            "plan",
            result.plot(None),
            "The fastest verified moves against the paper's laws (septic = the paper's "
            "jerk-continuous law)",
        )
        if result.feasible
        else ""
    )
    body = render(
        "sections/plan.html.j2",
        limits={
            **limits,
            "max_angle_deg": math.degrees(limits["max_angle"]),
            "max_residual_deg": math.degrees(limits["max_residual"]),
        },
        chosen=chosen,
        speed_up=speed_up,
        table=table,
        warnings=warnings,
        figure=figure,
    )
    writer.section("Fastest safe move", body)


def write_motion_sections(
    writer: ReportWriter,
    scenario: Scenario,
    model: SloshModel,
    progress: Callable[[str], None] | None = None,
) -> None:
    """Write the scenario's motion sections on ``model``: the laws compared, the slosh maps
    and the fastest safe move, each where the scenario's ``analyses`` name it.

    Parameters
    ----------
    writer : ReportWriter
        The report being written.
    scenario : Scenario
        The scenario.
    model : SloshModel
        The model every section uses (`sloshkit.report.model_sections.write_model_sections`).
    progress : callable, optional
        Called with the name of each section as it starts.

    Returns
    -------
    None

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from sloshkit.io.scenario import parse_scenario
    >>> scenario = parse_scenario({"name": "vial", "analyses": ["model"],
    ...                            "container": {"radius": "20.5mm"}, "fill": {"height": "39mm"},
    ...                            "move": {"distance": "0.2m", "duration": "1s"}})
    >>> writer = ReportWriter(pathlib.Path(tempfile.mkdtemp()))
    >>> write_motion_sections(writer, scenario, scenario.model, progress=print)
    >>> writer.facts
    {}
    """
    say = progress or (lambda _: None)
    if "compare" in scenario.analyses:
        say("motion laws")
        _compare_section(writer, scenario, model)
    if "sweep" in scenario.analyses:
        say("slosh maps")
        _sweep_section(writer, scenario, model)
    if "plan" in scenario.analyses:
        say("planning the fastest safe move")
        _plan_section(writer, scenario, model)
