"""Figures (matplotlib, imported only here and only when a figure is asked for)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from sloshkit.calibration import CalibrationResult
    from sloshkit.motion.laws import Motion
    from sloshkit.plan.planner import PlanResult
    from sloshkit.sim.response import SloshResponse
    from sloshkit.sweep import SweepResult


def _pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(figure: Any, path: str | Path | None) -> Any:
    """Save ``figure`` atomically (format from the suffix) when ``path`` is given."""
    if path is not None:
        from sloshkit.files import atomic_open

        target = Path(path)
        with atomic_open(target, "wb") as stream:
            figure.savefig(
                stream, format=target.suffix.lstrip(".") or "png", dpi=130, bbox_inches="tight"
            )
        _pyplot().close(figure)
    return figure


def plot_response(response: SloshResponse, path: str | Path | None = None) -> Any:
    """Container velocity and acceleration, pendulum angles and wall elevation over time."""
    plt = _pyplot()
    figure, axes = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    t = response.time_s
    axes[0].plot(t, response.velocity_m_s, label="velocity [m/s]")
    axes[0].plot(t, response.acceleration_m_s2, label="acceleration [m/s²]", alpha=0.7)
    axes[0].set_title(f"{response.motion_name} move, {response.kind} model")
    for index, mode in enumerate(response.model.modes):
        axes[1].plot(t, np.degrees(response.angle_rad[index]), label=f"mode {mode.n}")
    axes[1].set_ylabel("slosh angle [deg]")
    axes[2].plot(t, 1e3 * response.wall_elevation_m, color="tab:blue")
    axes[2].set_ylabel("wall elevation [mm]")
    axes[2].set_xlabel("time [s]")
    for axis in axes:
        axis.axvline(response.move_duration_s, color="grey", linestyle=":", linewidth=1)
        axis.grid(alpha=0.3)
    axes[0].legend(loc="upper right")
    axes[1].legend(loc="upper right")
    figure.tight_layout()
    return save_figure(figure, path)


def plot_law_comparison(motions: Sequence[Motion], path: str | Path | None = None) -> Any:
    """Velocity, acceleration and jerk of each law (the seed paper's Fig. 7)."""
    plt = _pyplot()
    figure, axes = plt.subplots(3, 1, figsize=(8, 8), sharex=True)
    for motion in motions:
        t = np.linspace(0.0, motion.duration_s, 2001)
        axes[0].plot(t, motion.velocity(t), label=motion.name)
        axes[1].plot(t, motion.acceleration(t), label=motion.name)
        axes[2].plot(t, motion.jerk(t), label=motion.name)
    for axis, label in zip(
        axes, ("velocity [m/s]", "acceleration [m/s²]", "jerk [m/s³]"), strict=True
    ):
        axis.set_ylabel(label)
        axis.grid(alpha=0.3)
    axes[2].set_xlabel("time [s]")
    axes[0].legend()
    axes[0].set_title("Motion laws (jerk impulses at acceleration jumps not drawn)")
    figure.tight_layout()
    return save_figure(figure, path)


def plot_slosh_comparison(
    responses: Sequence[SloshResponse], path: str | Path | None = None
) -> Any:
    """First-mode slosh angle and angular rate of each law (the seed paper's Figs. 8-9)."""
    plt = _pyplot()
    figure, axes = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True)
    for response in responses:
        axes[0].plot(response.time_s, np.degrees(response.angle_rad[0]), label=response.motion_name)
        axes[1].plot(
            response.time_s, np.degrees(response.rate_rad_s[0]), label=response.motion_name
        )
    axes[0].set_ylabel("slosh angle θ₁ [deg]")
    axes[1].set_ylabel("angular rate θ₁' [deg/s]")
    axes[1].set_xlabel("time [s]")
    for axis in axes:
        axis.grid(alpha=0.3)
    axes[0].legend()
    mode = responses[0].model.modes[0] if responses else None
    if mode is not None:
        axes[0].set_title(
            f"First mode: f₁ = {mode.frequency_hz:.2f} Hz, ζ = {mode.damping_ratio:.3g}"
        )
    figure.tight_layout()
    return save_figure(figure, path)


def plot_sweep_map(result: SweepResult, quantity: str, path: str | Path | None = None) -> Any:
    """Heat map of ``quantity`` (``peak_angle_deg`` or ``residual_angle_deg``) over fill height
    and duration (or peak acceleration), one panel per law; the safe region is outlined."""
    from matplotlib.colors import LogNorm

    plt = _pyplot()
    values = getattr(result, quantity)
    count = len(result.laws)
    columns = min(count, 3)
    rows = math.ceil(count / columns)
    figure, axes = plt.subplots(
        rows,
        columns,
        figsize=(4.6 * columns, 3.8 * rows),
        squeeze=False,
        sharey=True,
        layout="constrained",
    )
    positive = values[values > 0]
    low = float(positive.min()) if positive.size else 1e-6
    high = float(values.max()) if values.size else 1.0
    norm = LogNorm(vmin=max(low, high * 1e-4), vmax=max(high, low * 10))
    safe = result.safe()
    heights_mm = 1e3 * result.fill_heights_m
    image = None
    for index, law in enumerate(result.laws):
        axis = axes[index // columns][index % columns]
        x = (
            result.durations_s[index]
            if result.axis == "duration"
            else result.peak_acceleration_m_s2[index]
        )
        if x.size > 1 and heights_mm.size > 1:
            image = axis.pcolormesh(
                x, heights_mm, values[index], norm=norm, shading="nearest", cmap="viridis"
            )
            if not safe[index].any():
                axis.fill_between(
                    [x.min(), x.max()],
                    heights_mm.min(),
                    heights_mm.max(),
                    facecolor="none",
                    hatch="//",
                    edgecolor="black",
                    linewidth=0,
                )
            elif not safe[index].all():
                axis.contour(
                    x,
                    heights_mm,
                    safe[index].astype(float),
                    levels=[0.5],
                    colors="white",
                    linewidths=1.5,
                )
                axis.contourf(
                    x,
                    heights_mm,
                    safe[index].astype(float),
                    levels=[-0.5, 0.5],
                    colors="none",
                    hatches=["//"],
                )
        else:
            axis.plot(x, values[index].T, marker=".")
        axis.set_title(law)
        axis.set_xlabel("duration [s]" if result.axis == "duration" else "peak acceleration [m/s²]")
        if index % columns == 0:
            axis.set_ylabel("fill height [mm]")
    for index in range(count, rows * columns):
        axes[index // columns][index % columns].set_visible(False)
    label = "peak slosh angle θ₁ [deg]" if quantity == "peak_angle_deg" else "residual θ₁ [deg]"
    if image is not None:
        figure.colorbar(image, ax=axes.ravel().tolist(), label=label, shrink=0.9)
    limits = []
    if result.max_angle_deg is not None:
        limits.append(f"peak ≤ {result.max_angle_deg:g}°")
    if result.max_residual_deg is not None:
        limits.append(f"residual ≤ {result.max_residual_deg:g}°")
    figure.suptitle(
        f"{label}, {1e3 * result.distance_m:.0f} mm move"
        + (f"; hatched: violates {', '.join(limits)}" if limits else "")
    )
    return save_figure(figure, path)


def plot_calibration(result: CalibrationResult, path: str | Path | None = None) -> Any:
    """Signal in the window, detected peaks and the fitted decay envelope (seed Fig. 5b)."""
    plt = _pyplot()
    figure, axis = plt.subplots(figsize=(8, 4.2), layout="constrained")
    signal = result.signal
    axis.plot(signal.time_s, signal.values, color="tab:blue", linewidth=1, label="signal (window)")
    axis.plot(
        result.peak_times_s,
        result.peak_values,
        "o",
        color="tab:red",
        markersize=4,
        label=f"peaks ({result.peak_times_s.size})",
    )
    fit = result.estimates.get("fit")
    if fit is not None and fit.amplitude is not None and fit.omega_n_rad_s and fit.damping_ratio:
        t0 = signal.time_s[0]
        envelope = fit.amplitude * np.exp(
            -fit.damping_ratio * fit.omega_n_rad_s * (signal.time_s - t0)
        )
        # The plotted signal is detrended; the envelope is centred on zero like it.
        offset = 0.0
        axis.plot(
            signal.time_s,
            offset + envelope,
            "--",
            color="black",
            linewidth=1,
            label=f"fit envelope, ζ = {fit.damping_ratio:.4f}",
        )
        axis.plot(signal.time_s, offset - envelope, "--", color="black", linewidth=1)
    chosen = result.chosen
    frequency = (chosen.omega_n_rad_s or math.nan) / (2 * math.pi)
    zeta = "n/a" if chosen.damping_ratio is None else f"{chosen.damping_ratio:.4f}"
    axis.set_title(f"{result.method}: f_n = {frequency:.4g} Hz, ζ = {zeta}")
    axis.set_xlabel("time [s]")
    axis.set_ylabel("signal (detrended)")
    axis.grid(alpha=0.3)
    axis.legend(loc="upper right")
    return save_figure(figure, path)


def plot_plan(result: PlanResult, path: str | Path | None = None) -> Any:
    """Velocity, acceleration and re-simulated first-mode slosh angle of each verified
    candidate (exported samples), with the limits."""
    from sloshkit.motion.sampling import export_samples
    from sloshkit.sim.discretisation import linear_mode_response

    plt = _pyplot()
    figure, axes = plt.subplots(3, 1, figsize=(8.5, 8.5), sharex=True, layout="constrained")
    problem = result.problem
    mode = problem.model.modes[0]
    chosen = result.chosen
    for candidate in result.candidates:
        if candidate.motion is None or not candidate.feasible:
            continue
        samples = export_samples(candidate.motion, problem.sample_period_s)
        t = samples["t_s"]
        theta, _ = linear_mode_response(
            samples["velocity_m_s"],
            problem.sample_period_s,
            mode.omega_rad_s,
            mode.damping_ratio,
            mode.length_m,
        )
        is_chosen = candidate is chosen
        style = {"linewidth": 2.2 if is_chosen else 1.0, "alpha": 1.0 if is_chosen else 0.7}
        label = f"{candidate.method} ({candidate.duration_s:.3f} s)" + (" ◀" if is_chosen else "")
        axes[0].plot(t, samples["velocity_m_s"], label=label, **style)
        axes[1].plot(t, samples["acceleration_m_s2"], **style)
        axes[2].plot(t, np.degrees(theta), **style)
    limit = math.degrees(problem.slosh.max_angle_rad)
    for sign in (1, -1):
        axes[2].axhline(sign * limit, color="red", linestyle="--", linewidth=1)
    axes[0].set_ylabel("velocity [m/s]")
    axes[1].set_ylabel("acceleration [m/s²]")
    axes[2].set_ylabel("slosh angle θ₁ [deg]")
    axes[2].set_xlabel("time [s]")
    for axis in axes:
        axis.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    axes[0].set_title(
        f"Fastest moves of {1e3 * problem.distance_m:.0f} mm with |θ₁| ≤ {limit:g}°, residual ≤ "
        f"{math.degrees(problem.slosh.max_residual_rad):g}° (verified at "
        f"{1e3 * problem.sample_period_s:g} ms)"
    )
    return save_figure(figure, path)


def plot_cfd_validation(result: dict[str, Any], path: str | Path | None = None) -> Any:
    """CFD wall elevation against the pendulum model for the same motion (seed Fig. 9)."""
    plt = _pyplot()
    figure, axis = plt.subplots(figsize=(8, 4.2), layout="constrained")
    t = result["time_s"]
    axis.plot(
        t, 1e3 * np.asarray(result["cfd_elevation_m"]), label="CFD (interFoam)", linewidth=1.4
    )
    axis.plot(
        t,
        1e3 * np.asarray(result["model_elevation_m"]),
        "--",
        label="pendulum model",
        linewidth=1.2,
    )
    if result.get("excitation_end_s"):
        axis.axvline(result["excitation_end_s"], color="grey", linestyle=":", linewidth=1)
    axis.set_xlabel("time [s]")
    axis.set_ylabel("wall elevation at 0.98 R [mm]")
    axis.set_title(f"CFD vs equivalent model (correlation {result['correlation']:.3f})")
    axis.grid(alpha=0.3)
    axis.legend()
    return save_figure(figure, path)
