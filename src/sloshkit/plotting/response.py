"""Figures of simulations: one response, laws and responses side by side (seed Figs. 7-9)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from sloshkit.motion.profile import Motion
from sloshkit.plotting.base import panels, save_figure
from sloshkit.results import register_plot
from sloshkit.sim.response import SloshResponse


@register_plot(SloshResponse)
def plot_response(
    response: SloshResponse, path: str | Path | None = None, *, ax: Any = None
) -> Any:
    """Container velocity and acceleration, pendulum angles and wall elevation over time.

    Parameters
    ----------
    response : SloshResponse
        The simulation.
    path : str or Path, optional
        Where to save the figure.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into.

    Returns
    -------
    matplotlib.figure.Figure
        The figure (saved to ``path`` when given).

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"), 0.039)
    >>> figure = plot_response(sk.simulate(model, sk.quintic(0.1, 1.0)))
    >>> [axis.get_ylabel() for axis in figure.axes][1:]
    ['slosh angle [deg]', 'wall elevation [mm]']
    """
    figure, axes = panels(ax, 3, figsize=(8, 8), sharex=True)
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
    if ax is None:
        figure.tight_layout()
    return save_figure(figure, path)


def plot_law_comparison(
    motions: Sequence[Motion], path: str | Path | None = None, *, ax: Any = None
) -> Any:
    """Velocity, acceleration and jerk of each law (the seed paper's Fig. 7).

    Parameters
    ----------
    motions : sequence of Motion
        The laws.
    path : str or Path, optional
        Where to save the figure.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into.

    Returns
    -------
    matplotlib.figure.Figure
        The figure (saved to ``path`` when given).

    Examples
    --------
    >>> import sloshkit as sk
    >>> figure = plot_law_comparison([sk.quintic(0.1, 1.0), sk.septic(0.1, 1.0)])
    >>> len(figure.axes), len(figure.axes[0].get_lines())
    (3, 2)
    """
    figure, axes = panels(ax, 3, figsize=(8, 8), sharex=True)
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
    if ax is None:
        figure.tight_layout()
    return save_figure(figure, path)


def plot_slosh_comparison(
    responses: Sequence[SloshResponse], path: str | Path | None = None, *, ax: Any = None
) -> Any:
    """First-mode slosh angle and angular rate of each law (the seed paper's Figs. 8-9).

    Parameters
    ----------
    responses : sequence of SloshResponse
        The simulations.
    path : str or Path, optional
        Where to save the figure.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into.

    Returns
    -------
    matplotlib.figure.Figure
        The figure (saved to ``path`` when given).

    Examples
    --------
    >>> import sloshkit as sk
    >>> model = sk.equivalent_model(sk.UprightCylinder(0.0205), sk.get_liquid("water-25C"), 0.039)
    >>> responses = [sk.simulate(model, law(0.1, 1.0)) for law in (sk.quintic, sk.septic)]
    >>> len(plot_slosh_comparison(responses).axes)
    2
    """
    figure, axes = panels(ax, 2, figsize=(8, 6.5), sharex=True)
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
    if ax is None:
        figure.tight_layout()
    return save_figure(figure, path)
