"""Synthetic machine records for the calibration tests: sloshkit's own simulator, a large forced
move before the free decay, noise, quantisation, jittered time steps, offset and drift."""

from __future__ import annotations

import dataclasses

import numpy as np

from sloshkit.model.geometry import UprightCylinder
from sloshkit.model.liquids import get_liquid
from sloshkit.model.modal import SloshModel, equivalent_model
from sloshkit.motion import quintic
from sloshkit.motion.laws import Motion
from sloshkit.sim.simulate import simulate

#: Rigid mass of the container and fixture below the force sensor [kg].
CONTAINER_MASS_KG = 1.0


def water_cylinder(damping_ratio: float = 0.012) -> SloshModel:
    """A water cylinder on a robot: R 40 mm, fill 60 mm (first mode about 4.4 Hz)."""
    water = dataclasses.replace(get_liquid("water-25C"), density_kg_m3=1000.0)
    return equivalent_model(UprightCylinder(0.04), water, 0.06, damping_ratio=damping_ratio)


@dataclasses.dataclass(frozen=True)
class Record:
    """A synthetic record and what produced it."""

    time_s: np.ndarray
    values: np.ndarray
    motion: Motion
    motion_start_s: float
    model: SloshModel


def machine_record(
    kind: str = "force",
    *,
    model: SloshModel | None = None,
    motion: Motion | None = None,
    rest_s: float = 1.0,
    decay_s: float = 8.0,
    noise: float = 0.02,
    quantum: float = 0.01,
    jitter: float = 0.3,
    offset: float = 0.5,
    drift: float = 0.02,
    sample_period_s: float = 0.002,
    seed: int = 0,
) -> Record:
    """A record of ``kind`` force [N], height [m] or angle [rad] around a move.

    ``noise``, ``quantum``, ``offset`` and ``drift`` (per second) are fractions of the free
    decay's first amplitude (of the slosh part when the record has no decay); ``jitter`` is a
    fraction of the sample period.
    """
    model = water_cylinder() if model is None else model
    motion = quintic(0.15, 0.8) if motion is None else motion
    response = simulate(model, motion, sample_period_s=1e-3, settle_time_s=decay_s)
    if kind == "force":
        total = CONTAINER_MASS_KG + model.liquid_mass_kg
        clean = -total * response.acceleration_m_s2 + response.slosh_force_n
        slosh_masses = sum(mode.slosh_mass_kg for mode in model.modes)
        slosh = response.slosh_force_n - slosh_masses * response.acceleration_m_s2
    elif kind == "height":
        clean = slosh = response.wall_elevation_m
    elif kind == "angle":
        clean = slosh = response.angle_rad[0]
    else:
        raise ValueError(kind)
    after = response.time_s > motion.duration_s
    # Noise and offsets scale with the free decay's amplitude (the slosh part without one).
    amplitude = float(np.max(np.abs(slosh[after] if after.any() else slosh)))
    rng = np.random.default_rng(seed)
    t_clean = np.concatenate(([-rest_s], response.time_s)) + rest_s
    y_clean = np.concatenate(([0.0], clean))
    t = np.arange(0.0, t_clean[-1], sample_period_s)
    t = t + rng.uniform(-0.5, 0.5, t.size) * jitter * sample_period_s
    t = np.sort(np.clip(t, 0.0, t_clean[-1]))
    t = np.unique(t)
    y = np.interp(t, t_clean, y_clean)
    y = y + amplitude * (offset + drift * t + rng.normal(0.0, noise, t.size))
    if quantum > 0:
        step = quantum * amplitude
        y = step * np.round(y / step)
    return Record(t, y, motion, rest_s, model)
